"""Spring-damper limbs from a robot file's ``model: spring_damper:`` section (thesis 4.1.1).

A limb is the tuple (q_a, u_a, f_q, f_e, f_m, K_q, b_q) of section 4.1.1: its state is the
curvature of each segment of a planar actuator chain (one chamber per segment), its input
the segment's valve; f_q is a second-order step response per segment (section 4.2.1,
"Modeling Actuator Curvature"), f_e and f_m map the curvatures to the unloaded end
effector and the limb centre of mass, K_q is interpolated between the stiffness matrices
measured at the steady states, b_q is one damping coefficient.  A limb that names a
chassis contact instead of a leg is a passive skid: no segments, a fixed end effector.

File units are mm, g, degrees, N/mm and N·s/mm; everything here is SI (m, kg, rad, N/m,
N·s/m).  Other keys under ``model:`` (other models) are left to their own readers.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

from gaitc.diagnostics import Span
from gaitc.diagnostics.files import decode_text, read_input
from gaitc.diagnostics.yamltext import compose
from gaitc.gaitgraph.robot import Robot, parse_robot
from gaitc.models.fields import Fields, ModelFileError, span_of

Matrix3 = tuple[tuple[float, ...], ...]


@dataclass(frozen=True)
class Segment:
    """One single-chamber segment of an actuator chain: vented and pressurised curvature."""

    length: float  # m
    rest_curvature: float  # 1/m; positive curls the tip down and inwards
    curvature: float  # 1/m, the steady state with the chamber pressurised


@dataclass(frozen=True)
class Dynamics:
    """Second-order curvature response of a segment to a valve step (section 4.2.1)."""

    frequency: float  # natural frequency ω_n, rad/s
    damping_ratio: float  # ζ


@dataclass(frozen=True)
class Coefficients:
    """Coulomb friction with stiction: static and kinetic coefficient."""

    static: float
    kinetic: float


@dataclass(frozen=True)
class ToeFriction:
    """Friction of a foot (section 3.4): heel at rest; the toe's pad, band and sides."""

    heel: Coefficients  # the contact while the limb is vented
    outward: Coefficients  # toe sliding away from the mount (the high-friction pad)
    inward: Coefficients  # toe sliding back towards the mount (the low-friction band)
    lateral: Coefficients  # toe sliding sideways


@dataclass(frozen=True)
class Limb:
    """One spring-damper limb (or skid) mounted on the chassis."""

    name: str
    position: tuple[float, float, float]  # origin of the limb frame in the chassis frame, m
    yaw: float  # the limb frame's x axis (outward) in the chassis xy-plane, rad
    pitch: float  # the chain's first tangent below the limb x axis, rad
    mass: float  # kg
    segments: tuple[Segment, ...]
    dynamics: Dynamics
    stiffness: tuple[tuple[str, Matrix3], ...]  # valve pattern → K in the limb frame, N/m
    damping: float  # b, N·s/m
    friction: ToeFriction
    valves: tuple[int, ...]  # positions of the segments' valves in the robot's valve state
    span: Span | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class SpringDamperRobot:
    """The robot tuple (A, P, R) of section 4.1.1 with its simulation settings."""

    name: str
    file: str
    chassis_mass: float  # kg, the rigid chassis without its limbs
    limbs: tuple[Limb, ...]
    valve_count: int
    gravity: float = 9.81  # m/s²
    time_step: float = 0.001  # s
    period: float = 6.0  # s, the control period (thesis 4.3.1)

    @property
    def mass(self) -> float:
        """The single mass of the centroidal model: chassis and every limb."""
        return self.chassis_mass + sum(limb.mass for limb in self.limbs)


_SECTION = {"time_step", "period", "gravity", "defaults", "limbs"}
_LIMB = {
    "name",
    "position",
    "yaw",
    "pitch",
    "mass",
    "segments",
    "dynamics",
    "stiffness",
    "damping",
    "friction",
}
_SEGMENT = {"length", "rest_curvature", "curvature"}
_DYNAMICS = {"frequency", "damping_ratio"}
_FRICTION = {"heel", "outward", "inward", "lateral"}
_FRICTION_HINT = "friction maps heel, outward, inward and lateral to [static, kinetic]"


def load_spring_damper(path: str | Path) -> SpringDamperRobot:
    """Read a robot file and its ``model: spring_damper:`` section."""
    name = str(path)
    data = read_input(path, "robot file")
    return parse_spring_damper(decode_text(data, name, ModelFileError), name)


def section_node(text: str, path: str, model: str) -> yaml.Node:
    """The YAML node of ``model: <model>:`` in a robot file (an error when absent)."""
    root = compose(text, path, ModelFileError, "robot file")
    f = Fields(path)
    if not isinstance(root, yaml.MappingNode):
        raise ModelFileError("robot file is empty", Span(path, 1, 1))
    top = {str(k.value): v for k, v in root.value}
    if "model" not in top:
        raise f.fail(
            root,
            "robot file has no 'model' section",
            f"add 'model: {{{model}: ...}}' (docs/models.md lists its fields)",
        )
    section = f.mapping(top["model"], "model", _any_keys(top["model"]))
    if model not in section:
        raise f.fail(top["model"], f"the model section has no {model!r} entry")
    return section[model]


def _any_keys(node: yaml.Node) -> set[str]:
    return {str(k.value) for k, _ in node.value} if isinstance(node, yaml.MappingNode) else set()


def parse_spring_damper(text: str, path: str = "<robot>") -> SpringDamperRobot:
    """Validate the robot file text and read its spring-damper limbs."""
    robot = parse_robot(text, path)
    f = Fields(path)
    node = section_node(text, path, "spring_damper")
    sec = f.mapping(node, "model spring_damper", _SECTION)
    defaults = (
        f.mapping(sec["defaults"], "limb defaults", _LIMB - {"name"}) if "defaults" in sec else {}
    )
    if "limbs" not in sec:
        raise f.fail(node, "model spring_damper needs 'limbs', one per leg")
    limbs = tuple(_limb(f, item, defaults, robot) for item in f.sequence(sec["limbs"], "limbs"))
    named = [limb.name for limb in limbs]
    for i, item in enumerate(sec["limbs"].value):
        if named[i] in named[:i]:
            raise f.fail(item, f"limb {named[i]} is described twice")
    for leg in robot.legs:
        if leg.name not in named:
            raise f.fail(sec["limbs"], f"leg {leg.name} has no limb in model spring_damper")
    if any(leg.parent is not None for leg in robot.legs):
        raise f.fail(
            sec["limbs"],
            "the spring-damper model mounts every limb on the chassis; "
            "legs with a parent are not supported",
        )
    settings = {
        key: f.number(sec[key], key, positive=True)
        for key in ("time_step", "period", "gravity")
        if key in sec
    }
    return SpringDamperRobot(
        robot.name, path, robot.chassis_mass / 1000.0, limbs, robot.valve_count, **settings
    )


def _limb(f: Fields, item: yaml.Node, defaults: dict[str, yaml.Node], robot: Robot) -> Limb:
    m = {**defaults, **f.mapping(item, "a limb", _LIMB)}
    if "name" not in m:
        raise f.fail(item, "every limb needs a name (a leg or a chassis contact)")
    name = f.text(m["name"], "limb name")
    leg = next((leg for leg in robot.legs if leg.name == name), None)
    contact = dict(robot.contacts).get(name)
    if leg is None and contact is None:
        raise f.fail(
            m["name"], f"limb {name} is neither a leg nor a chassis contact of robot {robot.name}"
        )
    for key in ("stiffness", "damping", "friction"):
        if key not in m:
            raise f.fail(item, f"limb {name} needs {key!r}")
    segments = (
        tuple(_segment(f, s, name) for s in f.sequence(m["segments"], "segments"))
        if "segments" in m
        else ()
    )
    chambers = len(leg.chambers) if leg is not None else 0
    if len(segments) != chambers:
        raise f.fail(
            m.get("segments", item),
            f"limb {name} has {len(segments)} segments but {chambers} chambers",
            "each chamber drives one segment; a chassis contact has none",
        )
    if "position" in m:
        x, y, z = f.vector(m["position"], f"position of limb {name}", 3)
    else:
        x, y, z = leg.mount if leg is not None else (contact or (0.0, 0.0, 0.0))
    yaw = (
        math.radians(f.number(m["yaw"], "yaw"))
        if "yaw" in m
        else (leg.yaw if leg is not None else 0.0)
    )
    grams = (
        f.number(m["mass"], f"mass of limb {name}", 0.0)
        if "mass" in m
        else (leg.mass + leg.tip_mass if leg is not None else 0.0)
    )
    return Limb(
        name=name,
        position=(x / 1000.0, y / 1000.0, z / 1000.0),
        yaw=yaw,
        pitch=math.radians(f.number(m["pitch"], "pitch")) if "pitch" in m else 0.0,
        mass=grams / 1000.0,
        segments=segments,
        dynamics=_dynamics(f, m["dynamics"], name) if "dynamics" in m else Dynamics(20.0, 1.0),
        stiffness=_stiffness(f, m["stiffness"], name, len(segments)),
        damping=f.number(m["damping"], f"damping of limb {name}", positive=True) * 1000.0,
        friction=_friction(f, m["friction"], name),
        valves=tuple(range(leg.first_valve, leg.first_valve + chambers)) if leg else (),
        span=span_of(f.path, item),
    )


def _segment(f: Fields, node: yaml.Node, limb: str) -> Segment:
    m = f.mapping(node, f"a segment of limb {limb}", _SEGMENT)
    if "length" not in m:
        raise f.fail(node, f"a segment of limb {limb} needs a length (mm)")
    length = f.number(m["length"], "segment length", positive=True) / 1000.0
    rest = f.number(m["rest_curvature"], "rest_curvature") if "rest_curvature" in m else 0.0
    full = f.number(m["curvature"], "curvature") if "curvature" in m else rest
    if full == rest:
        raise f.fail(
            node,
            f"a segment of limb {limb} has the same curvature pressurised as vented",
            "give 'curvature' (1/mm) different from 'rest_curvature'",
        )
    return Segment(length, rest * 1000.0, full * 1000.0)


def _dynamics(f: Fields, node: yaml.Node, limb: str) -> Dynamics:
    m = f.mapping(node, f"dynamics of limb {limb}", _DYNAMICS)
    for key in _DYNAMICS:
        if key not in m:
            raise f.fail(node, f"dynamics of limb {limb} needs {key!r}")
    return Dynamics(
        f.number(m["frequency"], "frequency", positive=True),
        f.number(m["damping_ratio"], "damping_ratio", positive=True),
    )


def _stiffness(
    f: Fields, node: yaml.Node, limb: str, segments: int
) -> tuple[tuple[str, Matrix3], ...]:
    if isinstance(node, yaml.SequenceNode):
        entries: list[tuple[str, yaml.Node]] = [("", node)]
    else:
        entries = list(f.mapping(node, f"stiffness of limb {limb}", _any_keys(node)).items())
        wanted = {"".join(bits) for bits in itertools.product("01", repeat=segments)}
        for pattern, value in entries:
            if pattern not in wanted:
                raise f.fail(
                    value,
                    f"stiffness pattern {pattern!r} of limb {limb} must have "
                    f"{segments} digits 0 or 1, one per segment",
                )
        missing = sorted(wanted - {p for p, _ in entries})
        if missing:
            raise f.fail(
                node,
                f"limb {limb} has no stiffness matrix for the steady state {missing[0]!r}",
                "give one matrix per valve pattern, or a single 3x3 matrix for all",
            )
    out = []
    for pattern, value in entries:
        matrix = np.array(f.matrix3(value, f"stiffness of limb {limb}")) * 1000.0
        scale = float(np.abs(matrix).max()) or 1.0
        if (
            not np.allclose(matrix, matrix.T, atol=1e-9 * scale)
            or np.linalg.eigvalsh(matrix).min() < -1e-9 * scale
        ):
            raise f.fail(
                value, f"stiffness of limb {limb} must be a symmetric positive semi-definite matrix"
            )
        out.append((pattern, tuple(tuple(float(v) for v in row) for row in matrix)))
    return tuple(sorted(out))


def _pair(f: Fields, node: yaml.Node, what: str) -> Coefficients:
    static, kinetic = f.vector(node, what, 2)
    if kinetic < 0 or static < kinetic:
        raise f.fail(node, f"{what} must be [static, kinetic] with static >= kinetic >= 0")
    return Coefficients(static, kinetic)


def _friction(f: Fields, node: yaml.Node, limb: str) -> ToeFriction:
    if isinstance(node, yaml.SequenceNode):  # one isotropic pair
        pair = _pair(f, node, f"friction of limb {limb}")
        return ToeFriction(pair, pair, pair, pair)
    m = f.mapping(node, f"friction of limb {limb}", _FRICTION)
    for key in _FRICTION:
        if key not in m:
            raise f.fail(node, f"friction of limb {limb} needs {key!r}", _FRICTION_HINT)
    return ToeFriction(
        *(
            _pair(f, m[key], f"{key} friction of limb {limb}")
            for key in ("heel", "outward", "inward", "lateral")
        )
    )
