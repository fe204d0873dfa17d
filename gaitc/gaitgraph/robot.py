"""Robot descriptions: load and validate a robot YAML file into frozen dataclasses.

Lengths are millimetres, masses grams, angles degrees in the file (radians inside).
Every error carries the file, line and column of the offending YAML node.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from gaitc.diagnostics import GaitcError, Span
from gaitc.diagnostics.files import decode_text, read_input
from gaitc.diagnostics.yamltext import compose


class RobotFileError(GaitcError, ValueError):
    """A robot YAML file is malformed or describes an impossible robot."""


@dataclass(frozen=True)
class Chamber:
    """One pressure chamber: the curvature vector (κ, φ) it adds to its leg when open."""

    name: str
    curvature: float  # 1/mm
    angle: float  # bending-plane angle φ in the leg frame, radians


@dataclass(frozen=True)
class Leg:
    """A constant-curvature actuator mounted on the chassis (or on another leg's tip)."""

    name: str
    mount: tuple[float, float, float]  # base point in the parent frame
    yaw: float  # heading of the leg axis in the parent xy-plane, radians
    pitch: float  # angle of the leg axis below the parent xy-plane, radians
    roll: float  # added to every bending-plane angle, radians
    length: float
    mass: float
    tip_mass: float
    foot: bool  # whether the tip can touch the ground
    parent: str | None
    chambers: tuple[Chamber, ...]
    rest: tuple[float, float]  # (κ, φ) with every chamber vented
    table: tuple[tuple[str, float, float], ...]  # measured (pattern, κ, φ) overrides
    first_valve: int  # index of this leg's first chamber in the robot's valve string
    span: Span | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class StoredGait:
    """A gait primitive listed in the robot file (for example the radial robot's twelve)."""

    name: str
    legs: tuple[str, ...]
    direction: str
    valves: tuple[str, ...]
    span: Span | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class Settings:
    """Tolerances of the gait graph (section 2.2); all lengths in mm, angles in degrees."""

    contact_tolerance: float = 0.5  # feet this close to the support plane touch it
    max_slip: float = 2.0  # largest slip of a shared foot an edge may need
    max_tilt: float = 45.0  # steepest support plane (relative to chassis) counted as a pose
    zero_motion: float = 0.5  # |t| (mm) and |r| (deg) below which an edge is a reset edge


@dataclass(frozen=True)
class Robot:
    name: str
    file: str
    chassis_mass: float
    chassis_cg: tuple[float, float, float]
    outline: tuple[tuple[float, float], ...]
    contacts: tuple[tuple[str, tuple[float, float, float]], ...]  # fixed chassis contacts
    legs: tuple[Leg, ...]  # parents come before their children
    settings: Settings
    gaits: tuple[StoredGait, ...]
    #: the chapter 4 models the file's ``model:`` section declares, by their names in
    #: :data:`MODEL_SECTIONS` (in file order; the first is the one searched by default)
    models: tuple[str, ...] = ()

    @property
    def valve_count(self) -> int:
        return sum(len(leg.chambers) for leg in self.legs)

    @property
    def leg_of_valve(self) -> tuple[str, ...]:
        """The leg owning each position of a valve string."""
        return tuple(leg.name for leg in self.legs for _ in leg.chambers)

    @property
    def contact_names(self) -> tuple[str, ...]:
        """Names of the points that can touch the ground: chassis contacts, then feet."""
        return tuple(n for n, _ in self.contacts) + tuple(leg.name for leg in self.legs if leg.foot)

    def leg(self, name: str) -> Leg:
        return next(leg for leg in self.legs if leg.name == name)


def parse_valves(text: str, count: int, span: Span | None = None) -> str:
    """Normalise a valve state (``0``/``1`` per chamber; ``_``, ``.`` and spaces ignored)."""
    bits = "".join(ch for ch in text if ch not in "_. ")
    if len(bits) != count or any(ch not in "01" for ch in bits):
        raise RobotFileError(
            f"valve state {text!r} must have {count} digits 0 or 1, one per chamber",
            span,
            hint="chambers are numbered leg by leg in the order the legs are declared",
        )
    return bits


# ---------------------------------------------------------------- YAML node access


def _span(path: str, node: yaml.Node) -> Span:
    m = node.start_mark
    return Span(path, m.line + 1, m.column + 1)


class FieldReader:
    """Typed readers over the YAML nodes of one robot file, each failure a positioned
    :attr:`error` (the model sections of :mod:`gaitc.models` read with subclasses)."""

    error: type[RobotFileError] = RobotFileError

    def __init__(self, path: str) -> None:
        self.path = path

    def fail(self, node: yaml.Node, message: str, hint: str | None = None) -> RobotFileError:
        return self.error(message, _span(self.path, node), hint)

    def mapping(self, node: yaml.Node, what: str, allowed: set[str]) -> dict[str, yaml.Node]:
        if not isinstance(node, yaml.MappingNode):
            raise self.fail(node, f"{what} must be a mapping of keys to values")
        out: dict[str, yaml.Node] = {}
        for key, value in node.value:
            name = str(key.value)
            if name not in allowed:
                raise self.fail(
                    key,
                    f"unknown key {name!r} in {what}",
                    "expected one of: " + ", ".join(sorted(allowed)),
                )
            if name in out:
                raise self.fail(key, f"key {name!r} appears twice in {what}")
            out[name] = value
        return out

    def sequence(self, node: yaml.Node, what: str) -> list[yaml.Node]:
        if not isinstance(node, yaml.SequenceNode):
            raise self.fail(node, f"{what} must be a list")
        return list(node.value)

    def text(self, node: yaml.Node, what: str) -> str:
        if not isinstance(node, yaml.ScalarNode) or node.value == "":
            raise self.fail(node, f"{what} must be a non-empty text value")
        return str(node.value)

    def number(self, node: yaml.Node, what: str, low: float | None = None) -> float:
        try:
            if not isinstance(node, yaml.ScalarNode):
                raise ValueError
            value = float(node.value)
        except ValueError:
            raise self.fail(node, f"{what} must be a number") from None
        if not math.isfinite(value) or (low is not None and value < low):
            bound = "" if low is None else f" at least {low:g}"
            raise self.fail(node, f"{what} must be a finite number{bound}, not {node.value}")
        return value

    def flag(self, node: yaml.Node, what: str) -> bool:
        if not isinstance(node, yaml.ScalarNode) or node.value not in ("true", "false"):
            raise self.fail(node, f"{what} must be true or false")
        return bool(node.value == "true")

    def vector(self, node: yaml.Node, what: str, size: int) -> tuple[float, ...]:
        items = self.sequence(node, what)
        if len(items) != size:
            raise self.fail(node, f"{what} must have {size} numbers, not {len(items)}")
        return tuple(self.number(item, what) for item in items)


# ---------------------------------------------------------------- the file format

_TOP = {"robot", "description", "chassis", "defaults", "legs", "gait_graph", "gaits"}
_TOP |= {"model"}  # chapter 4 model parameters, read by gaitc.models (docs/models.md)
#: The sections of ``model:``, each a chapter 4 model, and the name the commands give it
#: (``--model``; :data:`gaitc.models.catalogue.MODELS` has a loader for each).
MODEL_SECTIONS = {"spring_damper": "spring-damper", "active_passive": "active-passive"}
_CHASSIS = {"mass", "cg", "outline", "contacts"}
_LEG = {
    "name",
    "mount",
    "yaw",
    "pitch",
    "roll",
    "length",
    "mass",
    "tip_mass",
    "foot",
    "parent",
    "chambers",
    "rest",
    "table",
}
_SHAPE = {"curvature", "angle"}
_CHAMBER = {"name", "curvature", "angle"}
_SETTINGS = {"contact_tolerance", "max_slip", "max_tilt", "zero_motion"}
_GAIT = {"name", "legs", "direction", "valves"}
DIRECTIONS = ("+x", "-x", "+y", "-y")


def load_robot(path: str | Path) -> Robot:
    """Read and validate a robot YAML file; raise :class:`RobotFileError` on any problem."""
    name = str(path)
    data = read_input(path, "robot file")
    return parse_robot(decode_text(data, name, RobotFileError), name)


def parse_robot(text: str, path: str = "<robot>") -> Robot:
    """Validate the YAML text of a robot description."""
    root = compose(text, path, RobotFileError, "robot file")
    r = FieldReader(path)
    if root is None:
        raise RobotFileError("robot file is empty", Span(path, 1, 1))
    top = r.mapping(root, "the robot file", _TOP)
    for key in ("robot", "chassis", "legs"):
        if key not in top:
            raise r.fail(root, f"robot file has no {key!r} section")
    chassis = r.mapping(top["chassis"], "chassis", _CHASSIS)
    if "mass" not in chassis:
        raise r.fail(top["chassis"], "chassis needs a mass (grams)")
    outline = (
        tuple(
            (xy[0], xy[1])
            for xy in (
                r.vector(p, "outline point", 2) for p in r.sequence(chassis["outline"], "outline")
            )
        )
        if "outline" in chassis
        else ()
    )
    contacts: list[tuple[str, tuple[float, float, float]]] = []
    if "contacts" in chassis:
        for key, value in r.mapping(
            chassis["contacts"], "chassis contacts", _any(chassis["contacts"])
        ).items():
            x, y, z = r.vector(value, f"contact {key}", 3)
            contacts.append((key, (x, y, z)))
    defaults = r.mapping(top["defaults"], "defaults", _LEG - {"name"}) if "defaults" in top else {}
    legs = _legs(r, top["legs"], defaults)
    names = [n for n, _ in contacts] + [leg.name for leg in legs]
    if len(set(names)) != len(names):
        raise r.fail(top["legs"], "leg and contact names must be unique")
    settings = Settings()
    if "gait_graph" in top:
        values = {
            key: r.number(node, key, 0.0)
            for key, node in r.mapping(top["gait_graph"], "gait_graph", _SETTINGS).items()
        }
        settings = Settings(**values)
    cg = r.vector(chassis["cg"], "chassis cg", 3) if "cg" in chassis else (0.0, 0.0, 0.0)
    robot = Robot(
        name=r.text(top["robot"], "robot name"),
        file=path,
        chassis_mass=r.number(chassis["mass"], "chassis mass", 0.0),
        chassis_cg=(cg[0], cg[1], cg[2]),
        outline=outline,
        contacts=tuple(contacts),
        legs=legs,
        settings=settings,
        gaits=(),
    )
    if len(robot.contact_names) < 3:
        raise r.fail(top["legs"], "a robot needs at least three points that can touch the ground")
    gaits = (
        tuple(_gait(r, g, robot) for g in r.sequence(top["gaits"], "gaits"))
        if "gaits" in top
        else ()
    )
    models = _models(r, top["model"]) if "model" in top else ()
    return Robot(**{**robot.__dict__, "gaits": gaits, "models": models})


def _models(r: FieldReader, node: yaml.Node) -> tuple[str, ...]:
    """The models a ``model:`` section declares (their own readers check the rest)."""
    sections = r.mapping(node, "model", set(MODEL_SECTIONS))
    if not sections:
        raise r.fail(node, f"the model section declares no model; use "
                     f"{' or '.join(sorted(MODEL_SECTIONS))}")
    return tuple(MODEL_SECTIONS[key] for key in sections)


def _any(node: yaml.Node) -> set[str]:
    return {str(k.value) for k, _ in node.value} if isinstance(node, yaml.MappingNode) else set()


def _shape(r: FieldReader, node: yaml.Node, what: str) -> tuple[float, float]:
    m = r.mapping(node, what, _SHAPE)
    kappa = r.number(m["curvature"], f"{what} curvature", 0.0) if "curvature" in m else 0.0
    angle = r.number(m["angle"], f"{what} angle") if "angle" in m else 0.0
    return kappa, math.radians(angle)


def _legs(r: FieldReader, node: yaml.Node, defaults: dict[str, yaml.Node]) -> tuple[Leg, ...]:
    legs: list[Leg] = []
    first = 0
    for item in r.sequence(node, "legs"):
        own = r.mapping(item, "a leg", _LEG)
        m = {**defaults, **own}
        if "name" not in m:
            raise r.fail(item, "every leg needs a name")
        name = r.text(m["name"], "leg name")
        for key in ("mount", "length", "chambers"):
            if key not in m:
                raise r.fail(item, f"leg {name} needs {key!r}")
        parent = r.text(m["parent"], "parent") if "parent" in m else None
        if parent is not None and parent not in {leg.name for leg in legs}:
            raise r.fail(
                m["parent"],
                f"leg {name} is mounted on {parent!r}, which is not a leg declared above it",
            )
        chambers: list[Chamber] = []
        for c in r.sequence(m["chambers"], f"chambers of leg {name}"):
            cm = r.mapping(c, "a chamber", _CHAMBER)
            if "curvature" not in cm:
                raise r.fail(c, f"a chamber of leg {name} needs a curvature (1/mm)")
            chambers.append(
                Chamber(
                    name=r.text(cm["name"], "chamber name")
                    if "name" in cm
                    else str(len(chambers) + 1),
                    curvature=r.number(cm["curvature"], "chamber curvature"),
                    angle=math.radians(r.number(cm["angle"], "chamber angle"))
                    if "angle" in cm
                    else 0.0,
                )
            )
        table = []
        if "table" in m:
            for key_node, value in (
                m["table"].value if isinstance(m["table"], yaml.MappingNode) else []
            ):
                pattern = parse_valves(str(key_node.value), len(chambers), _span(r.path, key_node))
                kappa, phi = _shape(r, value, f"table entry {pattern}")
                table.append((pattern, kappa, phi))
            if not isinstance(m["table"], yaml.MappingNode):
                raise r.fail(
                    m["table"],
                    "table must map chamber patterns like '1100' to a curvature and angle",
                )
        x, y, z = r.vector(m["mount"], f"mount of leg {name}", 3)
        legs.append(
            Leg(
                name=name,
                mount=(x, y, z),
                yaw=math.radians(r.number(m["yaw"], "yaw")) if "yaw" in m else 0.0,
                pitch=math.radians(r.number(m["pitch"], "pitch")) if "pitch" in m else math.pi / 2,
                roll=math.radians(r.number(m["roll"], "roll")) if "roll" in m else 0.0,
                length=r.number(m["length"], f"length of leg {name}", 1e-9),
                mass=r.number(m["mass"], f"mass of leg {name}", 0.0) if "mass" in m else 0.0,
                tip_mass=r.number(m["tip_mass"], "tip_mass", 0.0) if "tip_mass" in m else 0.0,
                foot=r.flag(m["foot"], "foot") if "foot" in m else True,
                parent=parent,
                chambers=tuple(chambers),
                rest=_shape(r, m["rest"], f"rest shape of leg {name}")
                if "rest" in m
                else (0.0, 0.0),
                table=tuple(sorted(table)),
                first_valve=first,
                span=_span(r.path, item),
            )
        )
        first += len(chambers)
    if not legs:
        raise r.fail(node, "a robot needs at least one leg")
    if first > 62:
        raise r.fail(node, f"{first} chambers: at most 62 valves are supported")
    return tuple(legs)


def _gait(r: FieldReader, node: yaml.Node, robot: Robot) -> StoredGait:
    m = r.mapping(node, "a gait", _GAIT)
    for key in _GAIT:
        if key not in m:
            raise r.fail(node, f"a stored gait needs {key!r}")
    legs = tuple(r.text(n, "leg name") for n in r.sequence(m["legs"], "gait legs"))
    for leg_node, leg in zip(m["legs"].value, legs, strict=False):
        if leg not in {x.name for x in robot.legs}:
            raise r.fail(leg_node, f"gait uses unknown leg {leg!r}")
    direction = r.text(m["direction"], "direction")
    if direction not in DIRECTIONS:
        raise r.fail(m["direction"], f"direction must be one of {', '.join(DIRECTIONS)}")
    valves = tuple(
        parse_valves(r.text(v, "valve state"), robot.valve_count, _span(r.path, v))
        for v in r.sequence(m["valves"], "gait valves")
    )
    if not valves:
        raise r.fail(m["valves"], "a gait needs at least one valve state")
    return StoredGait(r.text(m["name"], "gait name"), legs, direction, valves, _span(r.path, node))
