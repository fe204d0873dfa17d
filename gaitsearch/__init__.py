"""Gait synthesis in the global frame, refined online (thesis chapter 5).

Pipeline: :mod:`transitions` (the gait graph's predicted motions, mutable) →
:mod:`cells` (the (dx, dy, dθ) lattice of 5.2.2) → :mod:`astar` / :mod:`lpa` (hybrid graph
search) or :mod:`mcts` (5.2.4) → :mod:`plans` (results); :mod:`walker` (the simulated robot
with model mismatch) and :mod:`online` (Algorithms 2 and 3); :mod:`drawing` (pictures);
:mod:`api` (the functions the CLI and notebooks call).
"""
