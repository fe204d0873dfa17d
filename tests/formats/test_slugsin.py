"""Tests of the .slugsin reader and writer (slugs_bridge/slugsin.py)."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import SlugsFormatError
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import And, Const, Expr, Not, Or, Var, Xor, walk
from gaitc.ir.spec import Clause, GR1Spec, Variable
from slugs_bridge.slugsin import emit_formula, emit_slugsin, parse_slugsin

DATA = Path(__file__).parents[1] / "data"
PREFIX_FILES = sorted(
    path
    for folder in ("slugs_examples", "gr1_corpus")
    for pattern in ("*.slugsin", "*.txt")
    for path in (DATA / folder).glob(pattern)
)
SECTIONS = ("env_init", "sys_init", "env_trans", "sys_trans", "env_liveness", "sys_liveness")


def spec_of(body: str) -> GR1Spec:
    return parse_slugsin("[INPUT]\na\nb\n[OUTPUT]\nc\nd\n" + body, "t.slugsin")


def one(body: str) -> Expr:
    spec = spec_of("[SYS_TRANS]\n" + body + "\n")
    assert len(spec.sys_trans) == 1
    return spec.sys_trans[0].formula


def test_every_prefix_file_is_found() -> None:
    assert len(PREFIX_FILES) >= 150


@pytest.mark.parametrize("path", PREFIX_FILES, ids=lambda p: p.name)
def test_every_prefix_file_parses_and_round_trips(path: Path) -> None:
    spec = parse_slugsin(path.read_text(encoding="utf-8"), str(path))
    assert spec.inputs or spec.outputs
    text = emit_slugsin(spec, comments=False)
    again = parse_slugsin(text, "again.slugsin")
    assert again == spec
    assert emit_slugsin(again, comments=False) == text
    assert parse_slugsin(emit_slugsin(spec), "commented.slugsin") == spec  # comments skipped


def test_sections_in_any_order_repeat_and_comments() -> None:
    spec = parse_slugsin(
        "# leading comment\n[SYS_LIVENESS]\nc\n[OUTPUT]\nc\n[INPUT]\n  a  \n"
        "[SYS_LIVENESS]\n# inside\n! c'\n\n[ENV_TRANS]\n",
        "t.slugsin",
    )
    assert [v.name for v in spec.inputs] == ["a"]
    assert [v.name for v in spec.outputs] == ["c"]
    assert [c.formula for c in spec.sys_liveness] == [Var("c"), Not(Var("c", True))]
    assert spec.env_trans == ()


def test_operators() -> None:
    assert one("| a & b ! c'") == Or((Var("a"), And((Var("b"), Not(Var("c", True))))))
    assert one("^ a 1") == Xor(Var("a"), Const(True))
    assert one("0") == Const(False)


def test_nested_chains_are_flattened_in_order() -> None:
    assert one("& & a b & c d") == And((Var("a"), Var("b"), Var("c"), Var("d")))
    assert one("| a | b c") == Or((Var("a"), Var("b"), Var("c")))


def test_memory_buffer_value_is_last_element_and_shares_nodes() -> None:
    f = one("$ 3 & a b | ? 0 c ^ ? 1 ? 0")
    left = And((Var("a"), Var("b")))
    assert f == Xor(Or((left, Var("c"))), left)
    assert isinstance(f, Xor)
    assert isinstance(f.left, Or)
    assert f.left.args[0] is f.right  # shared, not copied
    # A recalled conjunction is not flattened into an enclosing conjunction.
    g = one("$ 2 & a b & ? 0 c")
    assert g == And((And((Var("a"), Var("b"))), Var("c")))


def test_recall_refers_to_innermost_buffer() -> None:
    f = one("$ 2 a $ 2 b & ? 0 a")
    assert f == And((Var("b"), Var("a")))
    g = one("$ 2 a & $ 1 b ? 0")
    assert g == And((Var("b"), Var("a")))


def test_exponential_sharing_stays_linear() -> None:
    # Each element doubles the previous one: the tree has 2**40 leaves, the DAG 41 nodes.
    parts = ["a"] + [f"& ? {i} ? {i}" for i in range(40)]
    f = one(f"$ {len(parts)} " + " ".join(parts))
    assert sum(1 for _ in walk(f)) == 41
    text = emit_formula(f)
    assert len(text) < 1000
    again = one(text)
    assert sum(1 for _ in walk(again)) <= 42  # the leaf may be written twice
    assert emit_formula(again) == text


def test_emit_uses_buffers_only_for_shared_subformulas() -> None:
    a, b = Var("a"), Var("b")
    assert emit_formula(And((a, Not(b)))) == "& a ! b"
    shared = Or((a, b))
    assert emit_formula(Xor(shared, Not(shared))) == "$ 2 | a b ^ ? 0 ! ? 0"


def test_emit_keeps_nested_chains_apart() -> None:
    a, b, c = Var("a"), Var("b"), Var("c")
    nested = And((And((a, b)), c))
    assert emit_formula(nested) == "$ 2 & a b & ? 0 c"
    assert one(emit_formula(nested)) == nested
    assert one("$ 3 | a b | ? 0 c' ^ ? 1 d") == Xor(Or((Or((a, b)), Var("c", True))), Var("d"))


def test_emit_rejects_integers() -> None:
    spec = GR1Spec(outputs=(Variable("n", 0, 3),))
    with pytest.raises(ValueError, match="bit-blast"):
        emit_slugsin(spec)


def test_writer_is_canonical_and_deterministic() -> None:
    spec = GR1Spec(
        inputs=(Variable("a"),),
        outputs=(Variable("c"),),
        sys_trans=(Clause(Or((Var("a"), Var("c", True)))),),
        env_liveness=(Clause(Var("a")),),
    )
    text = emit_slugsin(spec)
    assert text == (
        "[INPUT]\na\n\n[OUTPUT]\nc\n\n[ENV_INIT]\n\n[SYS_INIT]\n\n[ENV_TRANS]\n\n"
        "[SYS_TRANS]\n| a c'\n\n[ENV_LIVENESS]\na\n\n[SYS_LIVENESS]\n"
    )
    assert emit_slugsin(spec) == text


def test_clauses_remember_their_line() -> None:
    spec = spec_of("[ENV_INIT]\n\n  ! a\n")
    origin = spec.env_init[0].origin
    assert origin is not None and origin.span is not None
    assert (origin.span.line, origin.span.column) == (9, 3)
    assert "[ENV_INIT]" in origin.rule


def test_liveness_may_use_primes() -> None:
    spec = spec_of("[ENV_LIVENESS]\n| a' c'\n[SYS_LIVENESS]\nd'\n")
    assert spec.env_liveness[0].formula == Or((Var("a", True), Var("c", True)))


def test_parsed_formula_matches_brute_force_semantics() -> None:
    f = one("$ 2 ^ a b | ! ? 0 & c' ? 0")
    for bits in itertools.product((0, 1), repeat=3):
        val = {"a": bits[0], "b": bits[1], "c'": bits[2]}
        x = bits[0] != bits[1]
        assert evaluate(f, val) == ((not x) or (bool(bits[2]) and x))


ERRORS = [
    ("[SYS_TRANS]\n& a\n", 8, 1,
     "missing operand: '&' needs 2 operand(s) but the line ends after 1"),
    ("[SYS_TRANS]\n| a ! \n", 8, 5,
     "missing operand: '!' needs 1 operand(s) but the line ends after 0"),
    ("[SYS_TRANS]\n& a zz\n", 8, 5, "unknown variable 'zz'; declare it under [INPUT] or [OUTPUT]"),
    ("[SYS_TRANS]\n& a b c\n", 8, 7,
     "unexpected token 'c' after a complete formula; each line holds exactly one formula in "
     "prefix notation"),
    ("[SYS_TRAN]\n", 7, 1,
     "unknown section header '[SYS_TRAN]'; the known sections are [INPUT], [OUTPUT], "
     "[ENV_INIT], [SYS_INIT], [ENV_TRANS], [SYS_TRANS], [ENV_LIVENESS], [SYS_LIVENESS]"),
    ("[SYS_INIT]\n| a c'\n", 8, 5,
     "next-state variable 'c'' cannot appear in [SYS_INIT]: initial conditions constrain the "
     "first state only"),
    ("[ENV_INIT]\nc\n", 8, 1,
     "output 'c' cannot appear in [ENV_INIT]: SLUGS allows only inputs there; move the clause "
     "to [SYS_INIT]"),
    ("[ENV_TRANS]\n| a d'\n", 8, 5,
     "next-state output 'd'' cannot appear in [ENV_TRANS]: the environment moves before the "
     "system and cannot see its next move"),
    ("[SYS_TRANS]\n? 0\n", 8, 1,
     "'? 0' is outside any memory buffer; '?' may only appear inside '$ N ...'"),
    ("[SYS_TRANS]\n$ 2 a ? 1\n", 8, 9,
     "'? 1' recalls buffer element 1, but only 1 element(s) of the innermost buffer are "
     "complete at this point"),
    ("[SYS_TRANS]\n$ x a\n", 8, 3,
     "'$' must be followed by the number of buffer elements, found 'x'"),
    ("[SYS_TRANS]\n$ 3 a b\n", 8, 1,
     "missing operand: the memory buffer '$ 3' needs 3 formulas but the line ends after 2"),
    ("[SYS_TRANS]\n$ 0\n", 8, 3, "a memory buffer '$ 0' is empty; it needs at least one formula"),
    ("[INPUT]\na\n", 8, 1,
     "variable 'a' is declared twice (first on line 2); every name must be unique"),
    ("[OUTPUT]\ne f\n", 8, 1,
     "variable name 'e f' contains white space; a name must be a single word"),
    ("[OUTPUT]\n&\n", 8, 1,
     "'&' cannot be a variable name: it is an operator or constant of the slugsin format"),
]


@pytest.mark.parametrize(("body", "line", "column", "message"), ERRORS)
def test_errors_have_exact_messages_and_positions(
    body: str, line: int, column: int, message: str
) -> None:
    with pytest.raises(SlugsFormatError) as info:
        spec_of(body)
    err = info.value
    assert err.message == message
    assert err.span is not None
    assert (err.span.file, err.span.line, err.span.column) == ("t.slugsin", line, column)


def test_line_before_any_section() -> None:
    with pytest.raises(SlugsFormatError) as info:
        parse_slugsin("a\n[INPUT]\na\n", "f.slugsin")
    assert info.value.message.startswith("this line comes before any section header")
    assert info.value.span is not None and info.value.span.line == 1


def test_all_sections_round_trip_through_the_writer() -> None:
    spec = spec_of(
        "[ENV_INIT]\n! a\n[SYS_INIT]\n| c b\n[ENV_TRANS]\n^ a' c\n[SYS_TRANS]\n& d' a'\n"
        "[ENV_LIVENESS]\na\n[SYS_LIVENESS]\n! d\n"
    )
    again = parse_slugsin(emit_slugsin(spec), "x")
    for name in SECTIONS:
        assert again.section(name) == spec.section(name)
        assert len(spec.section(name)) == 1


SEED_TEXT = (
    "[INPUT]\na\nb\n[OUTPUT]\nc\nd\n[ENV_INIT]\n! a\n[SYS_TRANS]\n$ 3 & a b | ? 0 c' ^ ? 1 d\n"
    "[SYS_LIVENESS]\n| c d'\n"
)
PIECES = ["&", "|", "!", "^", "$", "?", "0", "1", "2", "a", "c'", "x", "'", "#", "[", "]",
          "[SYS_INIT]", "[INPUT]", "\n", " ", "\t", "é"]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(st.integers(0, len(SEED_TEXT)), st.sampled_from(PIECES),
                          st.integers(0, 3)), max_size=6))
def test_mutated_input_raises_only_format_errors(
    edits: list[tuple[int, str, int]]
) -> None:
    text = SEED_TEXT
    for position, piece, cut in edits:
        text = text[:position] + piece + text[position + cut:]
    try:
        spec = parse_slugsin(text, "fuzz.slugsin")
    except SlugsFormatError as err:
        assert err.span is not None and err.span.file == "fuzz.slugsin"
        return
    assert parse_slugsin(emit_slugsin(spec), "again.slugsin") == spec
