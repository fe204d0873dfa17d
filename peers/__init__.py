"""peers: everything that touches the peer GR(1) solvers gr1c and omega.

gaitc measures itself against SLUGS (:mod:`slugs_bridge`) and against these two: gr1c, a
C program that reads its own ``.spc`` format (Livingston, https://github.com/tulip-control/gr1c),
and omega, a Python package that solves GR(1) games over ``dd`` BDDs (Filippidis,
https://github.com/tulip-control/omega).  The game both read is checked and brought to
state-based liveness in :mod:`peers.game`; :mod:`peers.comparisons` writes an integer
comparison as comparisons of one variable with a constant (gr1c's only kind);
:mod:`peers.spc` writes gr1c's text, :mod:`peers.omega_game` builds and solves omega's
automaton, and :mod:`peers.runners` runs either and times it.  Imports :mod:`gaitc.ir`,
:mod:`gaitc.diagnostics`, and :mod:`slugs_bridge` for its file readers; never the embedded
solver nor the .gait front end.
"""
