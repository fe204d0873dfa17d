"""Gait synthesis in the global frame, refined online (thesis chapter 5).

Pipeline: :mod:`transitions` (the gait graph's predicted motions, mutable) →
:mod:`cells` (the (dx, dy, dθ) lattice of 5.2.2) → :mod:`astar` / :mod:`lpa` (with
:mod:`lpa_arrays` and :mod:`incoming` for dense graphs) / :mod:`dstar` (hybrid graph
search) or :mod:`mcts` (5.2.4), behind :mod:`planners` (one :class:`Planner` interface)
→ :mod:`plans` (results); :mod:`registry` (every search method, chapters 2 and 5, with its
entry) over :mod:`goal_search` (the chapter 5 searches' first plan);
:mod:`predictions` (the chapter 2 kinematic graph or a chapter 4 model's gait graph);
:mod:`walker` (the simulated robot with model mismatch), :mod:`physics_walker` (the
spring-damper model; :mod:`perturbation`, its model mismatch) and :mod:`backends` (which
of them) under :mod:`online` (Algorithms 2 and 3; one cycle in :mod:`cycles`),
:mod:`stepwise` (per-transition re-planning) and :mod:`growth` (adding valve states
online); :mod:`primitives` (a ``.gait`` primitive clause's valves); :mod:`drawing`
(pictures).
"""

from __future__ import annotations

from gaitc.search.goals import Goal, parse_goal
from gaitc.search.online import Learned, learn_gait
from gaitc.search.planners import Planner, Settings
from gaitc.search.plans import GaitPlan
from gaitc.search.registry import SEARCHES, plan_gait
from gaitc.search.walker import Mismatch

__all__ = [
    "SEARCHES",
    "GaitPlan",
    "Goal",
    "Learned",
    "Mismatch",
    "Planner",
    "Settings",
    "learn_gait",
    "parse_goal",
    "plan_gait",
]
