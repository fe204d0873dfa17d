"""The words a compact controller decides in: fields, each a spec-level quantity with values.

A *field* groups the bits of one quantity the user thinks in (the robot's region, its gait,
a leg's health level, the active hazard set; or, for a plain GR(1) spec, one declared
variable) and lists its legal values, each as the cube of bits that encodes it.  Decision
diagrams (:mod:`gaitc.compact.diagram`) branch on fields, not on bits, so a rule reads "L3
at level 2 or 3" whatever the encoding, and generated code takes one small integer per
field.  Bit patterns that encode no value (two regions at once in the one-hot encoding, an
integer out of its declared range) are no state of the robot; a controller never meets them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from gaitc.diagnostics import ControllerError
from gaitc.ir.bits import spec_bits
from gaitc.ir.controller import IntegerVar, spec_integers
from gaitc.ir.spec import GR1Spec
from ltlcompiler.decoding import RobotState, encode
from ltlcompiler.encoding import EncodingName, health_prop
from ltlcompiler.model import Model

Cube = tuple[tuple[str, bool], ...]
#: The field of the active hazard set in a robot's vocabulary (its first value ``none``).
HAZARD_FIELD = "hazard"


@dataclass(frozen=True)
class Field:
    """One quantity: its name, whether the environment sets it, its values and their cubes.

    ``numeric`` fields have ordered values (health levels, integers), so a set of them can
    be said as a range ("at least 2").
    """

    name: str
    is_input: bool
    labels: tuple[str, ...]
    cubes: tuple[Cube, ...]
    numeric: bool = False

    @property
    def bits(self) -> frozenset[str]:
        return frozenset(bit for cube in self.cubes for bit, _ in cube)

    def cube(self, value: int, primed: bool = False) -> dict[str, bool]:
        suffix = "'" if primed else ""
        return {bit + suffix: on for bit, on in self.cubes[value]}

    def value_of(self, bits: Mapping[str, object], primed: bool = False) -> int | None:
        """The value whose cube ``bits`` satisfy (None when no value's does)."""
        suffix = "'" if primed else ""
        for k, cube in enumerate(self.cubes):
            if all(bool(bits[b + suffix]) == on for b, on in cube):
                return k
        return None


@dataclass(frozen=True)
class Vocabulary:
    """The fields of a spec: every input and output bit belongs to exactly one field."""

    fields: tuple[Field, ...]
    domain: str  # "robot" for a .gait model's words, "spec" for the spec's own variables

    @property
    def inputs(self) -> tuple[Field, ...]:
        return tuple(f for f in self.fields if f.is_input)

    @property
    def outputs(self) -> tuple[Field, ...]:
        return tuple(f for f in self.fields if not f.is_input)

    def named(self, name: str) -> Field:
        for f in self.fields:
            if f.name == name:
                return f
        raise KeyError(name)


def _integer_cube(iv: IntegerVar, value: int) -> Cube:
    raw = value - iv.low
    return tuple((bit, bool(raw >> k & 1)) for k, bit in enumerate(iv.bits))


def spec_vocabulary(spec: GR1Spec, integers: Mapping[str, IntegerVar]) -> Vocabulary:
    """One field per declared variable of ``spec`` (booleans: 0 and 1; integers: their
    range), the bits of integers as ``integers`` (the controller's) lays them out."""
    fields = []
    for owner, variables in ((True, spec.inputs), (False, spec.outputs)):
        for v in variables:
            iv = integers.get(v.name)
            if iv is None:
                fields.append(Field(v.name, owner, ("0", "1"),
                                    (((v.name, False),), ((v.name, True),)), numeric=True))
                continue
            values = range(iv.low, iv.high + 1)
            fields.append(Field(v.name, owner, tuple(str(k) for k in values),
                                tuple(_integer_cube(iv, k) for k in values), numeric=True))
    return Vocabulary(tuple(fields), "spec")


def robot_vocabulary(model: Model, encoding: EncodingName,
                     integers: Mapping[str, IntegerVar]) -> Vocabulary:
    """The robot's words for a spec compiled from ``model``: region and gait (outputs),
    each leg's health level and the active hazard set (inputs), whatever the encoding.

    A field's bits are found by encoding states that differ in that field alone, so the
    grouping follows :func:`ltlcompiler.decoding.encode` and cannot drift from it.
    """
    regions = [r.name for r in model.regions]
    gaits = [g.name for g in model.gaits]
    hazards = [h.name for h in model.hazards]
    base = RobotState(regions[0], gaits[0], tuple((leg.name, leg.health) for leg in model.legs),
                      None)

    def states(name: str) -> list[RobotState]:
        if name == "region":
            return [RobotState(r, base.gait, base.health, None) for r in regions]
        if name == "gait":
            return [RobotState(base.region, g, base.health, None) for g in gaits]
        if name == HAZARD_FIELD:
            return [RobotState(base.region, base.gait, base.health, h)
                    for h in [None, *hazards]]
        leg = next(leg for leg in model.legs if leg.name == name)
        return [RobotState(base.region, base.gait,
                           tuple((n, level if n == name else h) for n, h in base.health), None)
                for level in range(1, leg.health + 1)]

    def field(name: str, is_input: bool, labels: Sequence[str], numeric: bool) -> Field:
        encoded = [encode(model, encoding, s) for s in states(name)]
        keys = sorted(k for k in encoded[0] if len({e[k] for e in encoded}) > 1)
        if len(encoded) == 1:  # a leg of one level: its constant bits
            own = {name} | {health_prop(name, j) for j in range(1, 2)}
            keys = sorted(k for k in encoded[0] if k in own)
        cubes = []
        for values in encoded:
            cube: list[tuple[str, bool]] = []
            for key in keys:
                iv = integers.get(key)
                cube.extend(_integer_cube(iv, values[key]) if iv is not None
                            else [(key, bool(values[key]))])
            cubes.append(tuple(cube))
        return Field(name, is_input, tuple(labels), tuple(cubes), numeric)

    fields = [field("region", False, regions, False), field("gait", False, gaits, False)]
    if len(regions) < 2 or len(gaits) < 2:
        fields = [f for f in fields if len(f.labels) > 1]
    for leg in model.legs:
        fields.append(field(leg.name, True, [str(k) for k in range(1, leg.health + 1)], True))
    if hazards:
        fields.append(field(HAZARD_FIELD, True, ["none", *hazards], False))
    return Vocabulary(tuple(fields), "robot")


def expected_vocabulary(spec: GR1Spec, model: Model | None = None,
                        encoding: EncodingName | None = None) -> Vocabulary:
    """The fields a compact controller of ``spec`` decides in, from the spec alone: the
    robot's words when ``spec`` was compiled from ``model`` (and they cover its bits), else
    one field per declared variable.  A controller file must carry exactly these."""
    integers = spec_integers(spec)
    ins, outs = spec_bits(spec)
    if model is not None:
        robot = robot_vocabulary(model, encoding or EncodingName.ONEHOT, integers)
        try:
            check_covers(robot, ins, outs)
            return robot
        except ControllerError:
            pass  # a model whose bits the robot's words do not cover: the spec's own
    found = spec_vocabulary(spec, integers)
    check_covers(found, ins, outs)
    return found


def _labels(labels: Sequence[str]) -> str:
    """Labels quoted (a label read from a file may hold anything, a newline too)."""
    return ", ".join(repr(label) for label in labels[:6]) + (", ..." if len(labels) > 6 else "")


def _values(f: Field) -> str:
    return f"{len(f.labels)} value(s): {_labels(f.labels)}"


def vocabulary_difference(found: Vocabulary, expected: Vocabulary) -> str | None:
    """The first way the fields of a controller file differ from those of its spec (field
    order, names, owners, value order, labels, encodings), in words; None when equal."""
    if found.domain != expected.domain:
        return (f"its fields are the {found.domain}'s words, the spec's are the "
                f"{expected.domain}'s")
    names = [f.name for f in found.fields]
    wanted = [f.name for f in expected.fields]
    if names != wanted:
        if sorted(names) == sorted(wanted):
            return f"it lists its fields as {names}, the spec's order is {wanted}"
        missing = [n for n in wanted if n not in names]
        extra = [n for n in names if n not in wanted]
        parts = ([f"it lacks field(s) {missing}"] if missing else []) + (
            [f"it has field(s) {extra} the spec does not have"] if extra else [])
        return "; ".join(parts)
    for f, e in zip(found.fields, expected.fields, strict=True):
        if f.is_input != e.is_input:
            owner = "an input" if e.is_input else "an output"
            return f"field {f.name!r} is {owner} of the spec"
        if f.labels != e.labels:
            if sorted(f.labels) == sorted(e.labels):
                return (f"field {f.name!r} lists its values as {_labels(f.labels)}; the "
                        f"spec's order is {_labels(e.labels)}")
            return f"field {f.name!r} has {_values(f)}; the spec's has {_values(e)}"
        for label, cube, wanted_cube in zip(f.labels, f.cubes, e.cubes, strict=True):
            if cube != wanted_cube:
                return (f"field {f.name!r} encodes its value {label!r} with other bits than "
                        "the spec does")
        if f.numeric != e.numeric:
            return f"field {f.name!r} is {'not ' if f.numeric else ''}numeric in the spec"
    return None


def check_covers(vocabulary: Vocabulary, inputs: Sequence[str], outputs: Sequence[str]) -> None:
    """Raise when the fields do not split the spec's bits exactly (each bit in one field)."""
    seen: dict[str, str] = {}
    for f in vocabulary.fields:
        for bit in f.bits:
            if bit in seen:
                raise ControllerError(f"bit {bit!r} belongs to fields {seen[bit]!r} and "
                                      f"{f.name!r}")
            seen[bit] = f.name
    missing = [b for b in [*inputs, *outputs] if b not in seen]
    extra = sorted(set(seen) - set(inputs) - set(outputs))
    if missing or extra:
        raise ControllerError("the fields do not match the spec's bits: "
                              f"missing {missing[:4]}, unknown {extra[:4]}")
