"""The generalized spring-damper model of thesis section 4.1.1, integrated in time.

Each limb pushes on the chassis with eq. 4.1, F = K_q (p_e − p̃_e) + b_q (ṗ_e − p̃̇_e): p̃_e
is the unloaded end effector that the curvature dynamics f_q and the chain map f_e give,
p_e the loaded one, held at the ground by the contact (a massless foot, so the ground
force on it equals F).  The chassis follows centroidal dynamics (thesis ref. [51]): one
mass for robot and limbs, translation in x, y, z and rotation about the vertical axis; the
chassis stays level (roll and pitch are not modelled).  Friction is :mod:`friction`.

Integration is semi-implicit Euler at the robot's time step, over a batch of independent
robots at once (every array has a leading batch axis B), so that the many transitions of
a gait graph cost little more than one.  A run stops early once every robot of the batch
is at rest (curvatures settled, chassis still, no foot sliding): nothing moves for the
rest of the control period, so the answer is the same and far cheaper.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from gaitc.models.motion import Pose2D, ValveState
from gaitc.models.spring_damper.description import SpringDamperRobot
from gaitc.models.spring_damper.friction import FrictionTable, coulomb
from gaitc.models.spring_damper.limbs import LimbArrays

Array = NDArray[np.float64]
Flags = NDArray[np.bool_]

REST_SPEED = 1e-4  # m/s, rad/s: below this (and curvatures settled) the robot is at rest
REST_TIP = 1e-4  # m: every unloaded tip this close to its steady state
TIP_SPEED = 2e-3  # m/s: and no faster (a tip 0.1 mm away moves about this fast)


@dataclass(frozen=True)
class State:
    """The model state of B robots: chassis, limb curvatures, feet (world frame, SI)."""

    position: Array  # (B, 3) chassis centre of mass
    velocity: Array  # (B, 3)
    theta: Array  # (B,) yaw
    omega: Array  # (B,) yaw rate
    kappa: Array  # (B, n, S) segment curvatures
    kappa_rate: Array  # (B, n, S)
    feet: Array  # (B, n, 3) loaded end effectors p_e
    contact: Flags  # (B, n) foot on the ground
    sliding: Flags  # (B, n) foot sliding

    def pose(self, i: int = 0) -> Pose2D:
        """Robot ``i``'s chassis pose in mm and radians."""
        return Pose2D(
            float(self.position[i, 0]) * 1000.0,
            float(self.position[i, 1]) * 1000.0,
            float(self.theta[i]),
        )

    def pick(self, rows: Sequence[int]) -> State:
        """The robots ``rows`` of the batch, as a new batch."""
        index = np.asarray(rows, dtype=np.int64)
        return State(*(getattr(self, f)[index] for f in self.__dataclass_fields__))

    @staticmethod
    def join(states: Sequence[State]) -> State:
        """One batch of all robots of ``states``."""
        return State(
            *(np.concatenate([getattr(s, f) for s in states]) for f in State.__dataclass_fields__)
        )


@dataclass(frozen=True)
class Forces:
    """What one evaluation of eq. 4.1 and the friction law gives, (B, n, ...) arrays."""

    ground: Array  # (B, n, 3) ground force on each foot (= limb force on the chassis)
    feet: Array  # (B, n, 3) feet after this step's slip
    contact: Flags
    sliding: Flags
    deflection: Array  # (B, n, 3) p_e − p̃_e in the limb frames
    stiffness: Array  # (B, n, 9) K in the limb frames, row by row


class SpringDamperModel:
    """A :class:`~gaitc.models.motion.MotionModel` for a :class:`SpringDamperRobot`."""

    name = "spring-damper"

    def __init__(self, robot: SpringDamperRobot, time_step: float | None = None) -> None:
        self.robot = robot
        self.dt = time_step or robot.time_step
        self.arrays = LimbArrays.of(robot)
        self.friction = FrictionTable.of(robot.limbs)
        self.mass = robot.mass
        self.steps = 0  # robot time steps integrated so far (batch size × steps)
        self._steady: dict[ValveState, State] = {}

    # ------------------------------------------------------------ the motion-model protocol

    def transition(self, start: ValveState, end: ValveState, period_s: float) -> Pose2D:
        """Body-frame chassis motion from ``start``'s steady state, ``end`` held ``period_s``."""
        return self.transitions([(start, end)], period_s)[0]

    def transitions(
        self, pairs: Sequence[tuple[ValveState, ValveState]], period_s: float
    ) -> list[Pose2D]:
        """:meth:`transition` for many pairs, simulated as one batch."""
        if not pairs:
            return []
        self.steady_states(sorted({start for start, _ in pairs}))
        before = State.join([self._steady[start] for start, _ in pairs])
        after = self.run(before, [end for _, end in pairs], period_s)
        return [before.pose(i).inverse().compose(after.pose(i)) for i in range(len(pairs))]

    # ------------------------------------------------------------ states

    def rest_state(self, valves: Sequence[ValveState]) -> State:
        """Curvatures settled at each valve state, chassis level with its lowest foot on the
        ground, no foot loaded yet (the robot is then dropped onto its feet, as in 4.3.2)."""
        a = self.arrays
        kappa = np.stack([a.targets(v) for v in valves])
        px, pz = a.chain(kappa)
        local = np.stack([px, np.zeros_like(px), pz], axis=-1)
        feet = np.stack([a.to_world(row, np.zeros(3), 0.0) for row in local])
        height = -feet[:, :, 2].min(axis=1)
        feet[:, :, 2] += height[:, None]
        b, n = len(valves), len(a.names)
        position = np.zeros((b, 3))
        position[:, 2] = height
        return State(

            position=position,
            velocity=np.zeros((b, 3)),
            theta=np.zeros(b),
            omega=np.zeros(b),
            kappa=kappa,
            kappa_rate=np.zeros_like(kappa),
            feet=feet,
            contact=np.zeros((b, n), dtype=bool),
            sliding=np.zeros((b, n), dtype=bool),
        )

    def steady_states(self, valves: Sequence[ValveState]) -> list[State]:
        """The robot at rest on the ground with each valve state held (cached)."""
        todo = [v for v in dict.fromkeys(valves) if v not in self._steady]
        if todo:
            settled = self.run(self.rest_state(todo), todo, 60.0)
            for i, v in enumerate(todo):
                self._steady[v] = settled.pick([i])
        return [self._steady[v] for v in valves]

    def steady_state(self, valves: ValveState) -> State:
        return self.steady_states([valves])[0]

    def check(self, valves: ValveState) -> None:
        if len(valves) != self.robot.valve_count:
            raise ValueError(
                f"a valve state of {self.robot.name} has "
                f"{self.robot.valve_count} entries, not {len(valves)}"
            )

    # ------------------------------------------------------------ integration

    def run(
        self, state: State, valves: Sequence[ValveState], duration: float, stop_at_rest: bool = True
    ) -> State:
        """Hold ``valves[i]`` on robot i for ``duration`` seconds from ``state``."""
        for v in valves:
            self.check(v)
        target = np.stack([self.arrays.targets(v) for v in valves])
        steps = max(1, round(duration / self.dt))
        for i in range(steps):
            state = self.step(state, target)
            if stop_at_rest and i % 20 == 19 and self.at_rest(state, target):
                break
        return state

    def at_rest(self, state: State, target: Array) -> bool:
        """Whether every robot of the batch is at rest at its curvature targets."""
        a = self.arrays
        tip = np.abs(state.kappa - target).max(initial=0.0) * a.max_length
        rate = np.abs(state.kappa_rate).max(initial=0.0) * a.max_length
        return bool(
            tip < REST_TIP
            and rate < TIP_SPEED
            and np.abs(state.velocity).max() < REST_SPEED
            and np.abs(state.omega).max() < REST_SPEED
            and not state.sliding.any()
        )

    def forces(self, state: State, kappa: Array, kappa_rate: Array) -> Forces:
        """Eq. 4.1 at every limb with the contact and friction laws of :mod:`friction`."""
        a = self.arrays
        h = 1e-4  # s: the unloaded end-effector rate is a forward difference over h
        both_x, both_z = a.chain(np.stack([kappa, kappa + h * kappa_rate]))
        px, pz = both_x[0], both_z[0]
        rate_x, rate_z = (both_x[1] - px) / h, (both_z[1] - pz) / h
        theta = state.theta[:, None]
        ct, st = np.cos(theta), np.sin(theta)
        phi = theta + a.yaw
        c, s = np.cos(phi), np.sin(phi)
        pos, vel = state.position, state.velocity
        lever_x = ct * a.offset[:, 0] - st * a.offset[:, 1] + c * px
        lever_y = st * a.offset[:, 0] + ct * a.offset[:, 1] + s * px
        ex, ey = pos[:, 0:1] + lever_x, pos[:, 1:2] + lever_y
        ez = pos[:, 2:3] + a.offset[:, 2] + pz
        w = state.omega[:, None]
        rx = vel[:, 0:1] - w * lever_y + c * rate_x
        ry = vel[:, 1:2] + w * lever_x + s * rate_x
        rz = vel[:, 2:3] + rate_z
        was = state.contact
        contact = was | (ez <= 0.0)
        fx = np.where(was, state.feet[..., 0], ex)
        fy = np.where(was, state.feet[..., 1], ey)
        dx, dy = np.where(contact, fx - ex, 0.0), np.where(contact, fy - ey, 0.0)
        dz = np.where(contact, -ez, 0.0)
        lx, ly = c * dx + s * dy, c * dy - s * dx  # deflection in the limb frames
        fraction = a.fraction(kappa)
        k = a.stiffness_local(fraction)
        kx = k[..., 0] * lx + k[..., 1] * ly + k[..., 2] * dz
        ky = k[..., 3] * lx + k[..., 4] * ly + k[..., 5] * dz
        kz = k[..., 6] * lx + k[..., 7] * ly + k[..., 8] * dz
        b = a.damping
        hold_x = c * kx - s * ky - b * rx  # ground force with the foot held still
        hold_y = s * kx + c * ky - b * ry
        normal = kz - b * rz
        contact = contact & (normal > 0.0)
        normal = np.where(contact, normal, 0.0)
        fr = coulomb(

            hold_x=hold_x,
            hold_y=hold_y,
            normal=normal,
            damping=b,
            cos=c,
            sin=s,
            activation=a.activation(fraction),
            table=self.friction,
            was_sliding=state.sliding & contact,
        )
        # a massless foot slides at most until its force is back on the friction cone
        slip_x, slip_y = fr.slip_x * self.dt, fr.slip_y * self.dt
        stiff = np.maximum(np.maximum(k[..., 0], k[..., 4]), 1e-12)
        excess = np.hypot(hold_x, hold_y) - np.hypot(fr.force_x, fr.force_y)
        length = np.hypot(slip_x, slip_y)
        cap = np.maximum(excess, 0.0) / stiff
        scale = np.where(length > cap, cap / np.where(length > 0, length, 1.0), 1.0)
        feet = np.stack(
            [
                np.where(contact, fx + slip_x * scale, ex),
                np.where(contact, fy + slip_y * scale, ey),
                np.where(contact, 0.0, ez),
            ],
            axis=-1,
        )
        ground = np.stack([fr.force_x, fr.force_y, normal], axis=-1)
        deflection = np.stack([lx, ly, dz], axis=-1)
        return Forces(ground, feet, contact, fr.sliding, deflection, k)

    def step(self, state: State, target: Array) -> State:
        """One semi-implicit Euler step towards the curvature targets (B, n, S)."""
        a = self.arrays
        dt = self.dt
        w, z = a.frequency, a.damping_ratio
        kappa_rate = state.kappa_rate + dt * (
            w * w * (target - state.kappa) - 2.0 * z * w * state.kappa_rate
        )
        kappa = state.kappa + dt * kappa_rate
        f = self.forces(state, kappa, kappa_rate)
        g = f.ground
        arm = f.feet - state.position[:, None, :]
        torque = np.sum(arm[..., 0] * g[..., 1] - arm[..., 1] * g[..., 0], axis=1)
        total = g.sum(axis=1)
        total[:, 2] -= self.mass * self.robot.gravity
        velocity = state.velocity + dt * total / self.mass
        omega = state.omega + dt * torque / a.inertia
        self.steps += len(state.theta)
        return State(

            position=state.position + dt * velocity,
            velocity=velocity,
            theta=state.theta + dt * omega,
            omega=omega,
            kappa=kappa,
            kappa_rate=kappa_rate,
            feet=f.feet,
            contact=f.contact,
            sliding=f.sliding,
        )

    def energy(self, state: State) -> Array:
        """Kinetic, gravitational and elastic energy (J) of every robot of the batch."""
        f = self.forces(state, state.kappa, state.kappa_rate)
        d = f.deflection
        k = f.stiffness.reshape(*d.shape[:2], 3, 3)
        elastic = 0.5 * np.einsum("bni,bnij,bnj->b", d, k, d)
        kinetic = (
            0.5 * self.mass * np.sum(state.velocity**2, axis=1)
            + 0.5 * self.arrays.inertia * state.omega**2
        )
        out: Array = kinetic + self.mass * self.robot.gravity * state.position[:, 2] + elastic
        return out
