"""Round trips through every output format: what gaitc writes, gaitc reads back as the same IR.

For random small ``.gait`` models (random legs, health levels, gaits, grids, hazards, free
assumptions and guarantees) whose names include the words the formats reserve (``F G X U
W TRUE FALSE next`` and more), and for every spec in ``specs/``: each format
(structuredslugs, slugsin, ltl) in each encoding (onehot, binary) is written with
:func:`gaitc.api.compiling.emit` and read back.  structuredslugs and ltl give the spec itself
(:class:`GR1Spec` equality ignores origins); slugsin is bit-blasted and has only ``! & | ^``,
so it gives :func:`slugs_bridge.prefixform.prefix_spec` of the bit-blasted spec.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gaitc.api.compiling import FORMATS, emit
from gaitc.core.spec import parse
from gaitc.ir.bitblast import bitblast
from gaitc.ir.spec import GR1Spec
from slugs_bridge.ltltext import parse_ltl
from slugs_bridge.names import KEYWORDS, RENAMED
from slugs_bridge.prefixform import prefix_spec
from slugs_bridge.slugsin import parse_slugsin
from slugs_bridge.structured import parse_structuredslugs

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "specs").glob("*.gait"))
ENCODINGS = ("onehot", "binary")
RESERVED = ["F", "G", "X", "U", "W", "TRUE", "FALSE", "next"]
# Names a .gait file may use: the reserved words, names a renaming could pick (F_, X_),
# words of the LTL text and of the readers ('in', 'slugsin'), and ordinary names.
POOL = [*RESERVED, "F_", "X_", "G__", "in", "slugsin", "a", "b", "c", "d", "e", "k", "p2",
        "_q", "Z9", "dock", "hall"]
DIRECTIONS = ("north", "south", "east", "west")
STRUCTURED_NAME = re.compile(r"[A-Za-z_.][A-Za-z0-9_.]*")


def read_back(text: str, fmt: str) -> GR1Spec:
    if fmt == "structuredslugs":
        return parse_structuredslugs(text, "again.structuredslugs")
    if fmt == "slugsin":
        return parse_slugsin(text, "again.slugsin")
    return parse_ltl(text, "again.ltl")


def expected(spec: GR1Spec, fmt: str) -> GR1Spec:
    return prefix_spec(bitblast(spec)) if fmt == "slugsin" else spec


def check_round_trips(text: str, name: str = "x.gait") -> list[str]:
    """Every format and encoding of ``text`` reads back as its IR; returns the outputs."""
    outputs = []
    for encoding in ENCODINGS:
        spec = parse(text, name=name, encoding=encoding).gr1
        for fmt in FORMATS:
            written = emit(spec, fmt)
            assert emit(spec, fmt) == written  # deterministic
            again = read_back(written, fmt)
            assert again == expected(spec, fmt), (encoding, fmt, written)
            assert again.inputs == expected(spec, fmt).inputs
            outputs.append(written)
            if fmt == "structuredslugs":
                check_slugs_names(written)
    return outputs


def check_slugs_names(text: str) -> None:
    """Every name declared in structuredslugs text is a word SLUGS's lexer reads as a name."""
    section = ""
    for line in text.splitlines():
        if line.startswith("["):
            section = line
        elif line and not line.startswith("#") and section in ("[INPUT]", "[OUTPUT]"):
            name = line.split(":")[0]
            assert STRUCTURED_NAME.fullmatch(name) and name not in KEYWORDS, name


# ---------------------------------------------------------------- random models
@st.composite
def formulas(draw: st.DrawFn, atoms: list[str], health: dict[str, int], depth: int = 2,
             nexts: bool = False) -> str:
    """A .gait formula over ``atoms`` and health comparisons; ``nexts`` allows next(...)."""
    kinds = ["atom", "atom", "const"] + (["health"] if health else [])
    if depth > 0:
        kinds += ["not", "and", "or", "xor", "implies", "iff"] + (["next"] if nexts else [])
    kind = draw(st.sampled_from(kinds))
    if kind == "atom" and atoms:
        return draw(st.sampled_from(atoms))
    if kind in ("atom", "const"):
        return draw(st.sampled_from(["true", "false"]))
    if kind == "health":
        leg = draw(st.sampled_from(sorted(health)))
        if draw(st.booleans()):
            return f"failed({leg})"
        op = draw(st.sampled_from(["=", "!=", "<", "<=", ">", ">="]))
        return f"health({leg}) {op} {draw(st.integers(1, health[leg]))}"
    if kind == "not":
        return "!" + draw(formulas(atoms, health, depth - 1, nexts))
    if kind == "next":
        return f"next({draw(formulas(atoms, health, depth - 1))})"
    left = draw(formulas(atoms, health, depth - 1, nexts))
    right = draw(formulas(atoms, health, depth - 1, nexts))
    symbol = {"and": "&", "or": "|", "xor": "^", "implies": "->", "iff": "<->"}[kind]
    return f"({left} {symbol} {right})"


@st.composite
def models(draw: st.DrawFn) -> str:
    """The text of a small valid .gait model whose names are drawn from :data:`POOL`."""
    rows, cols = draw(st.integers(1, 2)), draw(st.integers(1, 3))
    legs_n, gaits_n = draw(st.integers(1, 2)), draw(st.integers(1, 2))
    hazards_n = draw(st.integers(0, 1)) if rows * cols > 1 else 0
    count = legs_n + gaits_n + rows * cols + hazards_n
    names = draw(st.lists(st.sampled_from(POOL), min_size=count, max_size=count, unique=True))
    legs, names = names[:legs_n], names[legs_n:]
    gaits, names = names[:gaits_n], names[gaits_n:]
    regions, hazards = names[: rows * cols], names[rows * cols:]
    health = {leg: draw(st.integers(1, 3)) for leg in legs}
    lines = [f'robot "{draw(st.sampled_from(["m", "F", "next x"]))}"']
    lines += [f"leg {leg} health {h}" for leg, h in health.items()]
    for gait in gaits:
        if draw(st.integers(0, 4)) == 0:
            lines.append(f"correction gait {gait}")
        else:
            used = draw(st.lists(st.sampled_from(legs), min_size=1, unique=True))
            moves = draw(st.lists(st.sampled_from(DIRECTIONS), min_size=1, unique=True))
            lines.append(f"gait {gait} uses {', '.join(used)} moves {', '.join(moves)}")
    lines.append(f"grid {rows} x {cols} cells {', '.join(regions)}")
    start = draw(st.sampled_from(regions))
    if hazards:
        spots = [r for r in regions if r != start] or regions
        lines.append(f"hazard {hazards[0]}: {draw(st.sampled_from(spots))}")
    lines.append(f"start {start}")
    goals = draw(st.lists(st.sampled_from(regions), max_size=2, unique=True))
    if goals:
        lines.append(f"visit {', '.join(goals)} infinitely often")
    robot = [n for n in regions + gaits + hazards if n != "next"]
    env = [n for n in hazards if n != "next"]
    for _ in range(draw(st.integers(0, 3))):
        shape = draw(st.sampled_from(["", "always ", "always eventually "]))
        if draw(st.booleans()):
            body = draw(formulas(robot, health, nexts=shape == "always "))
            lines.append(f"guarantee {shape}{body}")
        else:
            body = draw(formulas(env, health, nexts=shape == "always "))
            lines.append(f"assume {shape}{body}")
    return "\n".join(lines) + "\n"


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(models())
def test_random_models_round_trip_in_every_format_and_encoding(text: str) -> None:
    check_round_trips(text)


@pytest.mark.parametrize("path", SPECS, ids=[p.stem for p in SPECS])
def test_every_example_spec_round_trips(path: Path) -> None:
    outputs = check_round_trips(path.read_text(encoding="utf-8"), name=str(path))
    assert not any(RENAMED in text for text in outputs)  # ordinary names stay as they are


# ---------------------------------------------------------------- the reserved words
RESERVED_MODEL = """\
robot "reserved"
legs F, next health 2
gait G uses F moves east
gait W uses next moves west
grid 2 x 2 cells F_, X, U, TRUE
hazard FALSE: U
start X
visit TRUE infinitely often
guarantee always (X -> next(!U))
guarantee always eventually (G | health(F) > 1)
assume always eventually !FALSE
"""


def test_reserved_words_are_renamed_and_read_back() -> None:
    outputs = check_round_trips(RESERVED_MODEL)
    onehot = dict(zip(FORMATS, outputs[:3], strict=True))
    infix = onehot["structuredslugs"]
    assert infix.splitlines()[1] == (
        RENAMED + '{"FALSE_": "FALSE", "X_": "X", "U_": "U", "TRUE_": "TRUE", "G_": "G", '
        '"W_": "W"}'
    )
    assert "\nX_ -> !U_'\n" in infix and "\nF_\n" in infix  # F_ is a region of its own
    assert RENAMED not in onehot["slugsin"]  # slugsin has no keywords: nothing to rename
    assert "G (X_ -> !X U_)" in onehot["ltl"]
    binary = dict(zip(FORMATS, outputs[3:], strict=True))
    assert binary["structuredslugs"].splitlines()[1] == RENAMED + '{"F_": "F", "next_": "next"}'
    assert "\nF_:1...2\n" in binary["structuredslugs"]
    assert "\nF@0.1.2\n" in binary["slugsin"]


def test_a_name_that_already_exists_is_not_reused() -> None:
    text = "leg L1 health 2\ngait g uses L1 moves east\ngrid 1 x 3 cells F, F_, F__\nstart F\n"
    spec = parse(text, name="clash.gait").gr1
    written = emit(spec, "structuredslugs")
    assert RENAMED + '{"F___": "F"}' in written
    assert parse_structuredslugs(written, "again.structuredslugs") == spec
