"""The robot tuple (A, C, M) of the active/passive model (thesis 4.1.2) as frozen dataclasses.

Read from a robot file by :mod:`gaitc.models.active_passive.description`; angles in radians,
stiffness in g·mm²/s² per rad², lengths mm, masses g.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gaitc.diagnostics import Span
from gaitc.gaitgraph.robot import Robot


@dataclass(frozen=True)
class ActiveShape:
    """The steady active state of an actuator for one chamber pattern (κ 1/mm, φ, τ rad/mm)."""

    curvature: float
    angle: float
    torsion: float


@dataclass(frozen=True)
class PassiveRange:
    """A passive degree of freedom: bounds (rad; for torsion the total twist) and stiffness."""

    name: str
    lower: float
    upper: float
    stiffness: float  # g·mm²/s² per rad²


@dataclass(frozen=True)
class Component:
    """An actuator (``leg`` set) or a rigid non-actuating component."""

    name: str
    mass: float
    friction: tuple[float, ...]  # one per wireframe vertex (per section point for actuators)
    wireframe: tuple[tuple[float, float, float], ...] = ()  # rigid components
    cg: tuple[float, float, float] = (0.0, 0.0, 0.0)
    leg: str | None = None  # actuators: the robot-file leg whose valves drive it
    valves: tuple[int, ...] = ()
    length: float = 0.0
    section: tuple[tuple[float, float], ...] = ()
    stations: int = 0
    states: tuple[tuple[str, ActiveShape], ...] = ()
    torsion: PassiveRange | None = None
    natural_frequency: float = 4.0  # rad/s, second-order curvature response
    damping_ratio: float = 1.0
    span: Span | None = field(default=None, compare=False, repr=False)

    @property
    def is_actuator(self) -> bool:
        return self.leg is not None

    def shape(self, pattern: str) -> ActiveShape:
        return dict(self.states)[pattern]


@dataclass(frozen=True)
class Connection:
    """A mounting connection: ``to``'s frame is placed at p_f of ``from`` (section 4.1.2)."""

    source: str  # ID_f
    target: str  # ID_t
    point: tuple[float, float, float] | None  # p_f as a fixed point (f_f: identity)
    arc: float | None  # p_f as an arc length along an actuator (f_f: the backbone)
    target_point: tuple[float, float, float]  # p_t
    offset: tuple[float, float, float]  # d, in the from frame
    rotation: tuple[tuple[float, float, float], ...]  # R
    joint: PassiveRange | None
    axis: tuple[float, float, float] = (0.0, 1.0, 0.0)  # hinge axis in the connection frame


@dataclass(frozen=True)
class ActivePassiveRobot:
    robot: Robot
    components: tuple[Component, ...]  # root first, every parent before its children
    connections: tuple[Connection, ...]  # the connection into components[1:], in that order
    contact_tolerance: float  # ε of the static load problem, mm
    period: float = 6.0  # s, the control period (thesis 4.3.1)

    def component(self, name: str) -> Component:
        return next(c for c in self.components if c.name == name)
