"""A simulated robot whose real transitions differ from the gait graph's predictions.

The "true" motion of each transition is its predicted motion scaled, biased and turned by a
fixed, seeded error (the model mismatch of thesis 5.2.1 and 5.3); each execution adds
Gaussian noise, as the dead-reckoned EKF estimate of chapter 4 would.  A share of
transitions cannot be made at all (the robot stays put).  When a valve state has several
stable poses the robot falls into the one its true motions need the least slip for, which
may not be the pose the planner meant.  It is a :class:`gaitc.hw.backend.Backend`, so valve
states are checked the same way as on the board.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.hw.backend import Backend, HardwareError, SensorReading, where
from gaitc.search.transitions import Floats, Step, TransitionModel


@dataclass(frozen=True)
class Mismatch:
    """How the simulated robot differs from the model (fixed per transition, seeded)."""

    scale: float = 0.2  # relative error of length and rotation, and bias in units of 5 mm / 5°
    noise: float = 0.2  # standard deviation of each execution: mm and degrees
    infeasible: float = 0.0  # share of transitions the robot cannot make
    seed: int = 0
    # the physics backend: each limb's stiffness and friction scaled by seeded factors in
    # [1 - model, 1 + model] (:mod:`gaitc.search.perturbation`); the simulated robot uses scale
    model: float = 0.0


@dataclass(frozen=True)
class Outcome:
    """What one valve state did: the pose reached and the motion measured (None: no move)."""

    edge: int | None  # the transition the robot really made
    pose: int
    measured: Step | None


class SimulatedWalker(Backend):
    """The robot on the ground: tracks its pose, makes transitions with their true motion."""

    name = "simulated walker"

    def __init__(
        self,
        model: TransitionModel,
        start: int,
        valve_count: int,
        legs: tuple[str, ...],
        mismatch: Mismatch,
    ) -> None:
        super().__init__(valve_count)
        self.legs = legs
        self.model, self.start, self.mismatch = model, start, mismatch
        self.true_dx, self.true_dy, self.true_rot, self.feasible = self._truth(model, mismatch.seed)
        self.noise = np.random.default_rng(mismatch.seed + 1)
        self.pose = start
        self.last: Outcome | None = None
        self.applied: list[str] = []
        self.is_open = False

    def _truth(
        self, model: TransitionModel, seed: int
    ) -> tuple[Floats, Floats, Floats, NDArray[np.bool_]]:
        rng = np.random.default_rng(seed)
        n, f = len(model), self.mismatch.scale
        a = rng.uniform(-1, 1, size=(4, n))
        true_dx = model.dx * (1 + f * a[0]) + 5.0 * f * a[1]
        true_dy = model.dy * (1 + f * a[0]) + 5.0 * f * a[2]
        true_rot = model.rot * (1 + f * a[0]) + 5.0 * f * a[3]
        feasible = rng.uniform(0, 1, size=n) >= self.mismatch.infeasible
        return true_dx, true_dy, true_rot, feasible

    def grow(self, model: TransitionModel, rows: dict[int, int], batch: int) -> None:
        """The gait graph grew to ``model`` (its predictions); ``rows`` maps the old edges
        to their new rows.  Old transitions keep their true motion, new ones get theirs
        from a generator seeded by the seed and the batch number."""
        dx, dy, rot, feasible = self._truth(model, self.mismatch.seed + 1000 * batch)
        for old, new in rows.items():
            dx[new], dy[new], rot[new] = self.true_dx[old], self.true_dy[old], self.true_rot[old]
            feasible[new] = self.feasible[old]
        self.model = model
        self.true_dx, self.true_dy, self.true_rot, self.feasible = dx, dy, rot, feasible

    def true_step(self, edge: int) -> Step:
        return Step(
            float(self.true_dx[edge]), float(self.true_dy[edge]), float(self.true_rot[edge])
        )

    def open(self) -> None:
        self.is_open = True

    def close(self) -> None:
        self.is_open = False

    def wait(self, seconds: float) -> None:
        """Simulated time passes at once."""

    def reset(self) -> None:
        """Back to the rest pose (the operator sets the robot down vented)."""
        self.pose = self.start
        self.last = None

    def apply(self, valves: str) -> None:
        if not self.is_open:
            raise HardwareError("the simulated walker is not open", where(self.name))
        self.check_valves(valves)
        self.applied.append(valves)
        m = self.model
        rows = list(m.rows(self.pose))
        fits = [e for e in rows if m.labels[int(m.dst[e])] == valves and self.feasible[e]]
        if not fits:
            self.last = Outcome(None, self.pose, None)
            return
        e = min(fits, key=lambda r: (float(m.slip[r]), r))
        true = self.true_step(e)
        sigma = self.mismatch.noise
        jitter = self.noise.normal(0.0, sigma, size=3) if sigma > 0 else np.zeros(3)
        measured = Step(
            true.dx + float(jitter[0]), true.dy + float(jitter[1]), true.rotation + float(jitter[2])
        )
        self.pose = int(m.dst[e])
        self.last = Outcome(e, self.pose, measured)

    def read_sensors(self) -> SensorReading:
        """No leg wears out in this simulation: every leg reads healthy (level 2)."""
        return SensorReading(tuple((leg, 2) for leg in self.legs), None, None)
