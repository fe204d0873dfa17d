"""solver: the embedded GR(1) solver on CUDD BDDs (``dd.cudd``).

Stages: the symbolic spec and variable order (:mod:`gaitc.solver.symbolic`,
:mod:`gaitc.solver.ordering`), the fixpoints of Bloem et al., JCSS 2012 (:mod:`gaitc.solver.game`),
explicit strategy and counter-strategy extraction (:mod:`gaitc.solver.strategy`,
:mod:`gaitc.solver.counter`) and the facade
:mod:`gaitc.solver.synthesis`. Imports only :mod:`gaitc.ir` and :mod:`gaitc.diagnostics`.
"""
