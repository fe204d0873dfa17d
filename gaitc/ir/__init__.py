"""gr1: the logic layer, a GR(1) specification as data.

The formula IR (:mod:`gaitc.ir.formula`, an immutable DAG with spans, walked by the one iterative
traversal of :mod:`gaitc.ir.traversal`, so depth never matters), its evaluation on valuations, the
specification IR with its six named sections (:mod:`gaitc.ir.spec`), SLUGS-compatible bit-blasting
of integers (:mod:`gaitc.ir.bitblast`, with the bit names of :mod:`gaitc.ir.bits`) and explicit
automata with their JSON file format (:mod:`gaitc.ir.controller`). It imports only
:mod:`gaitc.diagnostics`; every other package builds on it.
"""
