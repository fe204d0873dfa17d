"""The active/passive model of thesis 4.1.2 as a :class:`MotionModel` ("active-passive").

One valve transition is simulated as in thesis 4.2.2: the active curvatures follow their
second-order step responses (f_q); at every time step the passive states come from the
minimum-energy problem (:mod:`gaitc.models.active_passive.statics`); the planar motion of the
heading frame then follows from the particle system of component centres of mass, whose
linear and angular momentum change only by the viscous friction at the wireframe vertices
(F = −μ N v, loads N from the minimum-load static problem).  Both phases are taken in one
implicit Euler step, so stiff friction gives the quasi-static limit and zero friction gives
exact conservation of momentum ("Robot Angular Momentum").  Steps fall at equal shape
increments and are halved where the set of touching vertices changes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from gaitc.gaitgraph.robot import Robot
from gaitc.models.active_passive.description import load_active_passive
from gaitc.models.active_passive.kinematics import GRAVITY, Kinematics
from gaitc.models.active_passive.robot import ActivePassiveRobot, Component
from gaitc.models.active_passive.statics import Rest, RestSolver, normal_loads
from gaitc.models.motion import LoadedModel, Pose2D, ValveState

Array = NDArray[np.float64]

_SETTLED = 1e-3  # a response this close to its target counts as settled
_DENSE = 400  # samples used to place the time steps at equal shape increments


@dataclass(frozen=True)
class Step:
    """One simulated time step: the pose of the heading frame at its end and what acted."""

    time: float
    pose: Pose2D
    rest: Rest
    loads: Array  # normal load on every vertex, g·mm/s²
    velocity: Array  # (vx, vy, ω) of the heading frame, in that frame
    momentum: Array  # (px, py, L about the centre of mass), in the heading frame
    friction_power: float  # Σ F·v over the contacts (never positive)


def settle_time(comp: Component) -> float:
    """When the second-order response (ζ ≥ 1) is within 0.1 % of its target, seconds."""
    wn, zeta = comp.natural_frequency, comp.damping_ratio
    slow = wn * (zeta - math.sqrt(max(zeta * zeta - 1.0, 0.0)))
    times = np.linspace(0.0, 40.0 / slow, 4000)
    late = np.flatnonzero(1.0 - step_response(comp, times) > _SETTLED)
    return float(times[min(late[-1] + 1, times.size - 1)]) if late.size else 0.0


def step_response(comp: Component, t: Array) -> Array:
    """The unit step response of f_q from rest: critically damped or overdamped."""
    wn, zeta = comp.natural_frequency, comp.damping_ratio
    if zeta - 1.0 < 1e-9:
        return 1.0 - (1.0 + wn * t) * np.exp(-wn * t)
    root = wn * math.sqrt(zeta * zeta - 1.0)
    r1, r2 = -wn * zeta + root, -wn * zeta - root
    return 1.0 + (r2 * np.exp(r1 * t) - r1 * np.exp(r2 * t)) / (r1 - r2)


class ActivePassiveModel:
    """Predicts the chassis (root component) motion of valve transitions."""

    name = "active-passive"

    def __init__(
        self, robot: ActivePassiveRobot, steps: int = 8, refine: int = 2, cache: bool = True
    ) -> None:
        self.robot = robot
        self.steps = steps
        self.refine = refine
        self.kinematics = Kinematics(robot)
        self.solver = RestSolver(self.kinematics)
        self._actuators = [robot.component(n) for n in self.kinematics.actuators]
        self._steady: dict[ValveState, Rest] = {}
        self._transitions: dict[tuple[ValveState, ValveState, float], Pose2D] | None = (
            {} if cache else None
        )

    @classmethod
    def from_robot_file(
        cls, path: str | Path, steps: int = 8, refine: int = 2, cache: bool = True
    ) -> ActivePassiveModel:
        """The model of a robot file with an ``active_passive`` section."""
        return cls(load_active_passive(path), steps, refine, cache)

    @classmethod
    def from_robot(cls, robot: Robot, steps: int = 8, refine: int = 2) -> ActivePassiveModel:
        """The model of a robot parsed by :func:`gaitc.gaitgraph.robot.load_robot` (its file is read
        again for the ``active_passive`` section)."""
        return cls.from_robot_file(robot.file, steps, refine)

    @property
    def valve_count(self) -> int:
        return self.robot.robot.valve_count

    def active(self, valves: ValveState) -> Array:
        """Each actuator's steady (κ cos φ, κ sin φ, τ) for a valve state, (A, 3)."""
        if len(valves) != self.valve_count:
            raise ValueError(
                f"a valve state of {self.robot.robot.name} has "
                f"{self.valve_count} entries, not {len(valves)}"
            )
        rows = []
        for comp in self._actuators:
            shape = comp.shape("".join("1" if valves[i] else "0" for i in comp.valves))
            rows.append(
                [
                    shape.curvature * math.cos(shape.angle),
                    shape.curvature * math.sin(shape.angle),
                    shape.torsion,
                ]
            )
        return np.array(rows, dtype=float).reshape(len(self._actuators), 3)

    def steady(self, valves: ValveState) -> Rest:
        """The rest posture of a valve state: the lowest of several starts (see
        :meth:`RestSolver.lowest`)."""
        if valves not in self._steady:
            self._steady[valves] = self.solver.lowest(self.active(valves))
        return self._steady[valves]

    def transition(self, start: ValveState, end: ValveState, period_s: float) -> Pose2D:
        """Chassis displacement in the start pose's frame after ``period_s`` seconds."""
        key = (tuple(start), tuple(end), float(period_s))
        if self._transitions is not None and key in self._transitions:
            return self._transitions[key]
        steps = self.simulate(start, end, period_s)
        pose = steps[-1].pose if steps else Pose2D(0.0, 0.0, 0.0)
        if self._transitions is not None:
            self._transitions[key] = pose
        return pose

    def cycle(self, states: list[ValveState], period_s: float) -> Pose2D:
        """Net displacement of running a valve cycle once (each state held ``period_s``)."""
        pose = Pose2D(0.0, 0.0, 0.0)
        for a, b in zip(states, states[1:] + states[:1], strict=True):
            pose = pose.compose(self.transition(a, b, period_s))
        return pose

    # ------------------------------------------------------------ the time stepping

    def _loads(self, rest: Rest) -> Array:
        """Normal loads on the vertices of a rest posture."""
        m = self.kinematics.masses
        centre = m @ rest.posture.centres[0] / m.sum()
        return normal_loads(
            rest.posture.vertices[0], centre, self.solver.weight, self.robot.contact_tolerance
        )

    def _touching(self, rest: Rest) -> Array:
        heights = rest.posture.vertices[0, :, 2]
        touching: Array = heights <= heights.min() + self.robot.contact_tolerance
        return touching

    def _plan(self, first: Array, last: Array, period: float) -> tuple[Array, Array, Array]:
        """Progress marks at equal shape increments and the (progress, time) table."""
        moving = [
            c
            for i, c in enumerate(self._actuators)
            if not np.allclose(first[i], last[i], rtol=0.0, atol=1e-12)
        ]
        if not moving or period <= 0.0:
            return np.array([]), np.array([0.0]), np.array([0.0])
        horizon = min(period, max(settle_time(c) for c in moving))
        dense = np.linspace(0.0, horizon, _DENSE)
        progress = np.mean([step_response(c, dense) for c in moving], axis=0)
        return np.linspace(progress[0], progress[-1], self.steps + 1), progress, dense

    def simulate(self, start: ValveState, end: ValveState, period_s: float) -> list[Step]:
        """Every time step of a transition (none when no actuator changes its state).

        A step across which the set of touching vertices changes is halved, up to
        ``refine`` times, so that contact events fall near a step's end."""
        first, last = self.active(start), self.active(end)
        marks, progress, dense = self._plan(first, last, period_s)
        if marks.size == 0:
            return []
        track = _Track(self, self.steady(start))
        narrowest = (marks[1] - marks[0]) / 2**self.refine
        pending = list(marks[:0:-1])  # pop() gives the next mark
        reached, shaped = float(marks[0]), first
        solved: dict[float, Rest] = {}
        while pending:
            mark = pending.pop()
            t = float(np.interp(mark, progress, dense))
            done = np.array([step_response(c, np.array([t]))[0] for c in self._actuators])
            done[done >= 1.0 - _SETTLED] = 1.0  # a settled response has reached its target
            active = first + (last - first) * done[:, None]
            if np.array_equal(active, shaped):
                new = track.rest
            elif mark in solved:  # solved before its step was halved
                new = solved.pop(mark)
            else:
                new = self.solver.solve(active, track.guess())
            wide = mark - reached > narrowest * 1.5
            if wide and not np.array_equal(self._touching(track.rest), self._touching(new)):
                solved[mark] = new
                pending += [mark, (reached + mark) / 2]
                continue
            track.advance(new, t)
            reached, shaped = mark, active
        horizon = float(dense[-1])
        if period_s > horizon + 1e-9:
            # held: a posture left in another local minimum than the steady state snaps into
            # it (so that transitions compose), then it stays
            track.advance(self.steady(end), (horizon + period_s) / 2)
            track.advance(track.rest, period_s)
        return track.steps


class _Track:
    """The motion of the heading frame through one transition (thesis 4.2.2, "Robot Angular
    Momentum"): momentum changes only by the friction wrench, taken implicitly."""

    def __init__(self, model: ActivePassiveModel, rest: Rest) -> None:
        self.model = model
        self.rest = rest
        self.loads = model._loads(rest)
        self.before = rest.x
        self.masses = model.kinematics.masses
        self.pose = Pose2D(0.0, 0.0, 0.0)
        self.momentum = np.zeros(3)
        self.time = 0.0
        self.centre = self.masses @ rest.posture.centres[0, :, :2] / self.masses.sum()
        self.steps: list[Step] = []

    def guess(self) -> Array:
        """A linear predictor of the next passive state."""
        return 2.0 * self.rest.x - self.before if self.steps else self.rest.x

    def advance(self, new: Rest, t: float) -> None:
        masses, dt = self.masses, t - self.time
        rho0, rho1 = self.rest.posture.centres[0, :, :2], new.posture.centres[0, :, :2]
        q0, q1 = self.rest.posture.vertices[0, :, :2], new.posture.vertices[0, :, :2]
        loads = self.loads if new is self.rest else self.model._loads(new)
        velocity, momentum, power = _implicit_step(

            masses=masses,
            rho=(rho0 + rho1) / 2,
            rho_dot=(rho1 - rho0) / dt,
            q=(q0 + q1) / 2,
            q_dot=(q1 - q0) / dt,
            drag=self.model.kinematics.friction * (self.loads + loads) / 2,
            momentum=self.momentum,
            dt=dt,
        )
        # the centre of mass moves with the momentum (exactly still without friction); the
        # heading frame follows from it, the turn and the new shape
        turn = velocity[2] * dt
        mid = self.pose.theta + turn / 2
        shift = momentum[:2] / masses.sum() * dt
        cx = self.centre[0] + math.cos(mid) * shift[0] - math.sin(mid) * shift[1]
        cy = self.centre[1] + math.sin(mid) * shift[0] + math.cos(mid) * shift[1]
        theta = self.pose.theta + turn
        local = masses @ rho1 / masses.sum()
        self.centre = np.array([cx, cy])
        self.pose = Pose2D(
            float(cx - math.cos(theta) * local[0] + math.sin(theta) * local[1]),
            float(cy - math.sin(theta) * local[0] - math.cos(theta) * local[1]),
            float(theta),
        )
        cr, sr = math.cos(turn), math.sin(turn)  # momentum into the turned heading frame
        self.momentum = np.array(
            [cr * momentum[0] + sr * momentum[1], -sr * momentum[0] + cr * momentum[1], momentum[2]]
        )
        self.steps.append(Step(t, self.pose, new, loads, velocity, self.momentum, power))
        self.before, self.rest, self.loads, self.time = self.rest.x, new, loads, t


def loaded_model(path: str | Path) -> LoadedModel:
    """The active/passive model of a robot file as :mod:`gaitc.models.catalogue` lists models:
    register it with ``MODELS["active-passive"] = loaded_model``."""
    model = ActivePassiveModel.from_robot_file(path)
    robot = model.robot.robot
    flat = model.steady((False,) * robot.valve_count).posture.vertices[0, :, :2]
    length = float(np.ptp(flat, axis=0).max())
    return LoadedModel(model, robot.name, robot.leg_of_valve, model.robot.period, length)


def _cross(a: Array, b: Array) -> Array:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _implicit_step(
    masses: Array,
    rho: Array,
    rho_dot: Array,
    q: Array,
    *, q_dot: Array,
    drag: Array,
    momentum: Array,
    dt: float,
) -> tuple[Array, Array, float]:
    """Velocity (vx, vy, ω) of the heading frame over one step, the momentum after it and
    the friction power.  Momentum G ν + g₀ changes by dt times the friction wrench −C ν − c₀.
    """
    total = masses.sum()
    centre = masses @ rho / total
    rel = rho - centre
    inertia = float(masses @ np.sum(rel * rel, axis=1))
    g = np.array(
        [[total, 0.0, -total * centre[1]], [0.0, total, total * centre[0]], [0.0, 0.0, inertia]]
    )
    g0 = np.array([*(masses @ rho_dot), masses @ _cross(rel, rho_dot)])
    arm = q - centre
    w = drag.sum()
    jq = np.stack([-q[:, 1], q[:, 0]], axis=1)  # ω × q for ω = 1
    c = np.array(
        [
            [w, 0.0, drag @ jq[:, 0]],
            [0.0, w, drag @ jq[:, 1]],
            [drag @ -arm[:, 1], drag @ arm[:, 0], drag @ _cross(arm, jq)],
        ]
    )
    c0 = np.array([*(drag @ q_dot), drag @ _cross(arm, q_dot)])
    velocity = np.linalg.solve(g + dt * c, momentum - g0 - dt * c0)
    after = g @ velocity + g0
    speed = velocity[:2][None, :] + velocity[2] * jq + q_dot
    power = -float(drag @ np.sum(speed * speed, axis=1))
    return velocity, after, power


__all__ = [
    "GRAVITY",
    "ActivePassiveModel",
    "Step",
    "loaded_model",
    "settle_time",
    "step_response",
]
