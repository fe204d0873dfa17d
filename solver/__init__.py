"""solver: the embedded GR(1) solver on CUDD BDDs (``dd.cudd``).

Stages: the symbolic spec and variable order (:mod:`solver.symbolic`, :mod:`solver.ordering`),
the fixpoints of Bloem et al., JCSS 2012 (:mod:`solver.game`), explicit strategy and
counter-strategy extraction (:mod:`solver.strategy`, :mod:`solver.counter`) and the facade
:mod:`solver.synthesis`. Imports only :mod:`gr1` and :mod:`diagnostics`.
"""
