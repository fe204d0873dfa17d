"""verifier: independent checks of the automata a solver returns.

:mod:`gaitc.verifier.strategy` proves that a controller realizes a GR(1) spec and
:mod:`gaitc.verifier.counterstrategy` that a counter-strategy defeats it. They share no code with
:mod:`gaitc.solver` (a test enforces it), so a solver bug cannot hide itself.
"""
