"""Code generation: a compact controller as C tables for a host or the valve board.

Stages: :mod:`~gaitc.codegen.tables` (the flattened diagrams), :mod:`~gaitc.codegen.emitter`
(C source), :mod:`~gaitc.codegen.build` (compiling, sizing and refusing what does not fit).
"""
