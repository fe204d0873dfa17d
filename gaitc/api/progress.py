"""Progress, as the facade takes it: the ``progress`` argument of the solving, simulating,
drawing and driving calls is a :data:`Progress`, called with each :class:`Stage` of a long
solve (:mod:`gaitc.solver.progress`); a notebook can pass ``print``."""

from __future__ import annotations

from gaitc.solver.progress import Progress, Stage

__all__ = ["Progress", "Stage"]
