"""Property test: mutated .gait texts only ever raise GaitcError subclasses, never a crash.

Valid specifications are mutated (tokens deleted, duplicated or swapped, random
characters inserted, text truncated) and fed to ``model_from_text``.
"""

from __future__ import annotations

import contextlib
import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import GaitcError
from ltlcompiler.frontend import model_from_text

SEEDS = [
    """robot "thesis robot A"
legs L1..L8 health 3
gait north_a uses L1, L5 moves north valves 10001000, 00001000
gait south_a uses L1, L5 moves south
gait east_a uses L3, L7 moves east primitive "r.yaml" direction +x method reset
gait west_a uses L3, L7 moves west
correction gait adjust
grid 4 x 5 cells r0..r19
block r8, (3, 4)
cache r3, r14
hazard blue: r7, r9, r10
hazard red: r2, r5, r6, r15
start r12 with L1 = 2, L2..L3 = 1
visit r11, r12 infinitely often
assume always eventually !blue & !red
assume always (blue -> next(blue | !red))
guarantee always (r3 -> next(!north_a))
guarantee always eventually (health(L1) >= 2 | r3 | failed(L2))
""",
    """legs L1, L2 health 2
gait hop uses L1 moves dock -> hall, hall -> dock
gait fwd uses L2 moves east
correction gait turn moves hall -> hall
region dock, hall, lab
edge hall <-> lab east
edge lab -> dock by hop, fwd
start dock
visit lab infinitely often
guarantee !lab & (dock xor hall) <-> true
""",
]
SPECS = Path(__file__).resolve().parents[2] / "specs"
SEEDS += [p.read_text(encoding="utf-8") for p in sorted(SPECS.glob("*.gait"))[:6]]

TOKEN = re.compile(r"\s+|[A-Za-z_0-9]+|\S")
ALPHABET = "()!&|^-<>=.,:#\"'@$+ \n\tLrx0123456789"


def test_seeds_are_valid() -> None:
    for seed in SEEDS[:2]:
        model_from_text(seed, "seed.gait")


@st.composite
def mutated(draw: st.DrawFn) -> str:
    text = draw(st.sampled_from(SEEDS))
    tokens = TOKEN.findall(text)
    for _ in range(draw(st.integers(1, 4))):
        if not tokens:
            break
        op = draw(st.sampled_from(["delete", "duplicate", "swap", "insert", "truncate"]))
        i = draw(st.integers(0, len(tokens) - 1))
        if op == "delete":
            del tokens[i]
        elif op == "duplicate":
            tokens.insert(i, tokens[i])
        elif op == "swap":
            j = draw(st.integers(0, len(tokens) - 1))
            tokens[i], tokens[j] = tokens[j], tokens[i]
        elif op == "insert":
            tokens.insert(i, draw(st.text(alphabet=ALPHABET, min_size=1, max_size=4)))
        else:
            tokens = tokens[:i]
    return "".join(tokens)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_mutations_raise_only_gaitc_errors(text: str) -> None:
    try:
        model_from_text(text, "fuzz.gait")
    except GaitcError as err:
        assert err.message
        if err.span is not None:
            assert err.span.file == "fuzz.gait"
            assert err.span.line >= 1 and err.span.column >= 1


@settings(max_examples=100, deadline=None)
@given(st.text(alphabet=ALPHABET + "abcdefghijklmnopqrstuvwxyz", max_size=80))
def test_random_text_raises_only_gaitc_errors(text: str) -> None:
    with contextlib.suppress(GaitcError):
        model_from_text(text, "fuzz.gait")
