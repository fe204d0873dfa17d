"""The robot file's ``model: active_passive:`` section: the robot tuple (A, C, M) of 4.1.2.

Components are actuators (constant curvature/torsion segments driven by one robot-file leg's
valves, a cross-section swept along the backbone as wireframe) or rigid non-actuating parts
(blocks, touch pads: a mass and a fixed wireframe).  Mounting connections carry the
connection tuple (ID_f, ID_t, p_f, p_t, f_f, f_t, d, R) and optionally a passive hinge.
File units: mm, g, degrees, seconds; stiffness N·mm/rad; viscous friction s/mm.
Every error is a :class:`ModelFileError` (a ``RobotFileError``) at the YAML node at fault.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import yaml

from gaitc.diagnostics.files import decode_text
from gaitc.gaitgraph.robot import Robot, parse_robot
from gaitc.models.active_passive.reader import Reader
from gaitc.models.active_passive.robot import (
    ActivePassiveRobot,
    ActiveShape,
    Component,
    Connection,
    PassiveRange,
)
from gaitc.models.fields import ModelFileError
from gaitc.models.spring_damper.description import section_node

SECTION = "active_passive"
NEWTON_MM = 1e6  # one N·mm in the model's energy unit g·mm²/s²


_TOP = {"contact_tolerance", "period", "components", "connections"}
_COMMON = {"name", "mass", "friction"}
_RIGID = _COMMON | {"cg", "wireframe"}
_ACTUATOR = _COMMON | {"leg", "length", "section", "stations", "states", "torsion", "response"}
_STATE = {"curvature", "angle", "torsion"}
_RANGE = {"lower", "upper", "stiffness"}
_JOINT = _RANGE | {"name", "axis"}
_CONNECTION = {"from", "to", "at", "to_point", "offset", "rotation", "joint"}
_RESPONSE = {"natural_frequency", "damping_ratio"}


def load_active_passive(path: str | Path) -> ActivePassiveRobot:
    """Read a robot file and its ``model: active_passive:`` section."""
    name = str(path)
    try:
        data = Path(path).read_bytes()
    except OSError as err:
        raise ModelFileError(f"cannot read robot file {name}: {err.strerror}") from None
    except ValueError:
        raise ModelFileError(
            f"cannot read robot file {name!r}: the name holds a NUL character"
        ) from None
    return parse_active_passive(decode_text(data, name, ModelFileError), name)


def parse_active_passive(text: str, path: str = "<robot>") -> ActivePassiveRobot:
    """Validate a robot file's text including its ``model: active_passive:`` section."""
    robot = parse_robot(text, path)
    node = section_node(text, path, SECTION)
    r = Reader(path)
    top = r.mapping(node, f"model {SECTION}", _TOP)
    for key in ("components", "connections"):
        if key not in top:
            raise r.fail(node, f"model {SECTION} has no {key!r}")
    comps = [_component(r, item, robot) for item in r.sequence(top["components"], "components")]
    if not comps:
        raise r.fail(top["components"], "components must list at least one component")
    names = [c.name for c in comps]
    for c, item in zip(comps, top["components"].value, strict=True):
        if names.count(c.name) > 1:
            raise r.fail(item, f"component name {c.name!r} is used twice")
    driven = [c.leg for c in comps if c.leg is not None]
    for c, item in zip(comps, top["components"].value, strict=True):
        if c.leg is not None and driven.count(c.leg) > 1:
            raise r.fail(item, f"leg {c.leg!r} drives two components")
    for leg in robot.legs:
        if leg.chambers and leg.name not in driven:
            raise r.fail(
                top["components"],
                f"no component is driven by leg {leg.name!r}",
                "give one actuator component 'leg: " + leg.name + "'",
            )
    conns = [_connection(r, item, comps) for item in r.sequence(top["connections"], "connections")]
    ordered, order = _tree(r, top["connections"], comps, conns)
    tol = (
        r.number(top["contact_tolerance"], "contact_tolerance", 0.0)
        if "contact_tolerance" in top
        else 0.5
    )
    period = r.number(top["period"], "period", 1e-3) if "period" in top else 6.0
    return ActivePassiveRobot(robot, tuple(ordered), tuple(order), tol, period)


def _component(r: Reader, node: yaml.Node, robot: Robot) -> Component:
    probe = r.mapping(node, "a component", _RIGID | _ACTUATOR)
    actuator = "leg" in probe
    m = r.mapping(
        node, "an actuator" if actuator else "a rigid component", _ACTUATOR if actuator else _RIGID
    )
    if "name" not in m:
        raise r.fail(node, "every component needs a name")
    name = r.text(m["name"], "component name")
    mass = r.number(m["mass"], f"mass of {name}", 0.0) if "mass" in m else 0.0
    if not actuator:
        if "wireframe" not in m:
            raise r.fail(node, f"rigid component {name} needs a wireframe (its vertices)")
        frame = tuple(
            _v3(r, v, f"wireframe vertex of {name}")
            for v in r.sequence(m["wireframe"], f"wireframe of {name}")
        )
        cg = _v3(r, m["cg"], f"cg of {name}") if "cg" in m else (0.0, 0.0, 0.0)
        friction = _friction(r, m, name, len(frame))
        return Component(name, mass, friction, wireframe=frame, cg=cg, span=r.span(node))
    leg_name = r.text(m["leg"], "leg")
    leg = next((x for x in robot.legs if x.name == leg_name), None)
    if leg is None:
        raise r.fail(
            m["leg"],
            f"actuator {name} names leg {leg_name!r}, which the robot file does not declare",
        )
    for key in ("length", "section", "states"):
        if key not in m:
            raise r.fail(node, f"actuator {name} needs {key!r}")
    section = tuple(
        _v2(r, p, f"section point of {name}")
        for p in r.sequence(m["section"], f"section of {name}")
    )
    stations = r.count(m["stations"], "stations", 2) if "stations" in m else 4
    count = len(leg.chambers)
    states: list[tuple[str, ActiveShape]] = []
    if not isinstance(m["states"], yaml.MappingNode):
        raise r.fail(m["states"], f"states of {name} must map chamber patterns to shapes")
    for key, value in m["states"].value:
        pattern = str(key.value)
        if pattern in {p for p, _ in states}:
            raise r.fail(key, f"key {pattern!r} appears twice in states of {name}")
        if len(pattern) != count or set(pattern) - {"0", "1"}:
            raise r.fail(
                key,
                f"state {pattern!r} of {name} must have {count} digits 0 or 1, "
                f"one per chamber of leg {leg_name}",
            )
        s = r.mapping(value, f"state {pattern} of {name}", _STATE)
        states.append(
            (
                pattern,
                ActiveShape(
                    r.number(s["curvature"], "curvature") if "curvature" in s else 0.0,
                    math.radians(r.number(s["angle"], "angle")) if "angle" in s else 0.0,
                    r.number(s["torsion"], "torsion") if "torsion" in s else 0.0,
                ),
            )
        )
    missing = sorted({format(i, f"0{count}b") for i in range(2**count)} - {p for p, _ in states})
    if missing:
        raise r.fail(m["states"], f"states of {name} miss the pattern {missing[0]!r}")
    length = r.number(m["length"], f"length of {name}", 1e-6)
    torsion = _range(r, m["torsion"], f"torsion of {name}", name) if "torsion" in m else None
    response = r.mapping(m["response"], "response", _RESPONSE) if "response" in m else {}
    return Component(
        name,
        mass,
        _friction(r, m, name, len(section)),
        leg=leg_name,
        valves=tuple(range(leg.first_valve, leg.first_valve + count)),
        length=length,
        section=section,
        stations=stations,
        states=tuple(sorted(states)),
        torsion=torsion,
        natural_frequency=r.number(response["natural_frequency"], "natural_frequency", 1e-6)
        if "natural_frequency" in response
        else 4.0,
        damping_ratio=r.number(response["damping_ratio"], "damping_ratio", 1.0)
        if "damping_ratio" in response
        else 1.0,
        span=r.span(node),
    )


def _v3(r: Reader, node: yaml.Node, what: str) -> tuple[float, float, float]:
    x, y, z = r.vector(node, what, 3)
    return x, y, z


def _v2(r: Reader, node: yaml.Node, what: str) -> tuple[float, float]:
    x, y = r.vector(node, what, 2)
    return x, y


def _friction(r: Reader, m: dict[str, yaml.Node], name: str, count: int) -> tuple[float, ...]:
    if count == 0:
        raise r.fail(
            m.get("wireframe", m.get("section", m["name"])),
            f"the wireframe of {name} has no vertices",
        )
    if "friction" not in m:
        return (0.0,) * count
    node = m["friction"]
    if isinstance(node, yaml.SequenceNode):
        if len(node.value) != count:
            raise r.fail(
                node,
                f"friction of {name} must have one value per vertex ({count}), "
                f"not {len(node.value)}",
            )
        return tuple(r.number(v, f"friction of {name}", 0.0) for v in node.value)
    return (r.number(node, f"friction of {name}", 0.0),) * count


def _range(r: Reader, node: yaml.Node, what: str, name: str) -> PassiveRange:
    m = r.mapping(node, what, _JOINT if what.startswith("joint") else _RANGE)
    for key in ("lower", "upper"):
        if key not in m:
            raise r.fail(node, f"{what} needs {key!r} (degrees)")
    lower, upper = (
        math.radians(r.number(m[k], f"{k} bound of {what}")) for k in ("lower", "upper")
    )
    if lower > upper:
        raise r.fail(
            m["upper"],
            f"{what}: upper bound {math.degrees(upper):g} is below the "
            f"lower bound {math.degrees(lower):g}",
        )
    k = r.number(m["stiffness"], f"stiffness of {what}", 0.0) if "stiffness" in m else 0.0
    return PassiveRange(name, lower, upper, k * NEWTON_MM)


def _rotation(r: Reader, node: yaml.Node) -> tuple[tuple[float, float, float], ...]:
    """R from roll, pitch, yaw in degrees (applied about x, then y, then z)."""
    roll, pitch, yaw = (math.radians(a) for a in r.vector(node, "rotation", 3))
    cx, sx, cy, sy, cz, sz = (
        math.cos(roll),
        math.sin(roll),
        math.cos(pitch),
        math.sin(pitch),
        math.cos(yaw),
        math.sin(yaw),
    )
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    m = rz @ ry @ rx
    return tuple((float(a), float(b), float(c)) for a, b, c in m)


def _connection(r: Reader, node: yaml.Node, comps: list[Component]) -> Connection:
    m = r.mapping(node, "a connection", _CONNECTION)
    for key in ("from", "to", "at"):
        if key not in m:
            raise r.fail(node, f"a connection needs {key!r}")
    by_name = {c.name: c for c in comps}
    ends = []
    for key in ("from", "to"):
        name = r.text(m[key], key)
        if name not in by_name:
            raise r.fail(m[key], f"connection {key} unknown component {name!r}")
        ends.append(by_name[name])
    source, target = ends
    point: tuple[float, float, float] | None = None
    arc: float | None = None
    at = m["at"]
    if isinstance(at, yaml.ScalarNode) and at.value in ("tip", "base"):
        if not source.is_actuator:
            raise r.fail(at, f"'at: {at.value}' needs an actuator, and {source.name} is rigid")
        arc = source.length if at.value == "tip" else 0.0
    elif isinstance(at, yaml.MappingNode):
        a = r.mapping(at, "at", {"arc"})
        if not source.is_actuator or "arc" not in a:
            raise r.fail(at, "'at: {arc: s}' needs an actuator as the from component")
        arc = r.number(a["arc"], "arc length", 0.0)
        if arc > source.length:
            raise r.fail(
                a["arc"],
                f"arc length {arc:g} is beyond the end of {source.name} (length {source.length:g})",
            )
    else:
        point = _v3(r, at, "at")
    joint = None
    axis = (0.0, 1.0, 0.0)
    if "joint" in m:
        jm = r.mapping(m["joint"], "joint", _JOINT)
        jname = r.text(jm["name"], "joint name") if "name" in jm else f"{target.name}_hinge"
        joint = _range(r, m["joint"], f"joint {jname}", jname)
        if "axis" in jm:
            v = np.array(_v3(r, jm["axis"], "joint axis"))
            if np.linalg.norm(v) < 1e-9:
                raise r.fail(jm["axis"], "joint axis must not be the zero vector")
            v = v / np.linalg.norm(v)
            axis = (float(v[0]), float(v[1]), float(v[2]))
    return Connection(

        source=source.name,
        target=target.name,
        point=point,
        arc=arc,
        target_point=_v3(r, m["to_point"], "to_point") if "to_point" in m else (0.0, 0.0, 0.0),
        offset=_v3(r, m["offset"], "offset") if "offset" in m else (0.0, 0.0, 0.0),
        rotation=_rotation(r, m["rotation"])
        if "rotation" in m
        else ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
        joint=joint,
        axis=axis,
    )


def _tree(
    r: Reader, node: yaml.Node, comps: list[Component], conns: list[Connection]
) -> tuple[list[Component], list[Connection]]:
    """Order the components from the root (the first one) along the connections."""
    incoming: dict[str, Connection] = {}
    for c, item in zip(conns, node.value, strict=True):
        if c.target in incoming:
            raise r.fail(item, f"component {c.target} is mounted twice")
        if c.target == comps[0].name:
            raise r.fail(
                item,
                f"{c.target} is the root (the first component) and cannot be mounted on another",
            )
        incoming[c.target] = c
    ordered = [comps[0]]
    order: list[Connection] = []
    placed = {comps[0].name}
    while len(ordered) < len(comps):
        ready = [c for c in conns if c.source in placed and c.target not in placed]
        if not ready:
            lost = next(c for c in comps if c.name not in placed)
            raise r.fail(
                node, f"component {lost.name} is not connected to the root {comps[0].name}"
            )
        for c in ready:
            placed.add(c.target)
            order.append(c)
            ordered.append(next(x for x in comps if x.name == c.target))
    return ordered, order
