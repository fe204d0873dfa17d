"""Tests of the .structuredslugs reader and writer (slugs_bridge/structured.py, infix.py)."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import SlugsFormatError
from gaitc.ir.bitblast import bitblast
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    Add,
    And,
    Compare,
    Const,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Not,
    Or,
    Var,
    Xor,
    atoms,
)
from gaitc.ir.spec import GR1Spec, Variable
from slugs_bridge.slugsin import emit_formula, parse_slugsin
from slugs_bridge.structured import emit_structuredslugs, is_prefix_line, parse_structuredslugs

DATA = Path(__file__).parents[1] / "data"
INFIX_FILES = sorted(
    [
        *DATA.glob("slugs_examples/*.structuredslugs"),
        *DATA.glob("slugs_examples/*.structureslugs"),
        *DATA.glob("gr1_corpus/*.structuredslugs"),
    ]
)
CORPUS = sorted(p.stem for p in (DATA / "gr1_corpus").glob("*.structuredslugs"))
SECTIONS = ("env_init", "sys_init", "env_trans", "sys_trans", "env_liveness", "sys_liveness")
HEAD = "[INPUT]\na\nb\nn:0...7\n[OUTPUT]\nc\nm:2...5\n"
a, b, c = Var("a"), Var("b"), Var("c")


def spec_of(body: str) -> GR1Spec:
    return parse_structuredslugs(HEAD + body, "t.structuredslugs")


def one(line: str) -> Expr:
    spec = spec_of("[SYS_TRANS]\n" + line + "\n")
    assert len(spec.sys_trans) == 1
    return spec.sys_trans[0].formula


def test_every_infix_file_is_found() -> None:
    assert len(INFIX_FILES) >= 159


@pytest.mark.parametrize("path", INFIX_FILES, ids=lambda p: p.name)
def test_every_infix_file_parses_and_round_trips(path: Path) -> None:
    spec = parse_structuredslugs(path.read_text(encoding="utf-8"), str(path))
    text = emit_structuredslugs(spec, comments=False)
    again = parse_structuredslugs(text, "again.structuredslugs")
    assert again == spec
    assert emit_structuredslugs(again, comments=False) == text
    assert parse_structuredslugs(emit_structuredslugs(spec), "commented") == spec


def equivalent(f: Expr, g: Expr) -> bool:
    names = sorted({n + ("'" if p else "") for n, p in atoms(f) | atoms(g)})
    for values in itertools.product((0, 1), repeat=len(names)):
        valuation = dict(zip(names, values, strict=True))
        if evaluate(f, valuation) != evaluate(g, valuation):
            return False
    return True


@pytest.mark.parametrize("stem", CORPUS)
def test_corpus_formats_agree(stem: str) -> None:
    prefix = parse_slugsin((DATA / "gr1_corpus" / f"{stem}.slugsin").read_text(), stem)
    infix_text = (DATA / "gr1_corpus" / f"{stem}.structuredslugs").read_text()
    infix = bitblast(parse_structuredslugs(infix_text, stem))
    assert infix.inputs == prefix.inputs
    assert infix.outputs == prefix.outputs
    for section in SECTIONS:
        left, right = prefix.section(section), infix.section(section)
        assert len(left) == len(right)
        for p, q in zip(left, right, strict=True):
            assert equivalent(p.formula, q.formula), (section, p, q)


def test_declarations() -> None:
    spec = parse_structuredslugs(
        "[INPUT]\nflag\nlevel: 3...107\n[OUTPUT]\nk:-2...2\n", "t.structuredslugs"
    )
    assert spec.inputs == (Variable("flag"), Variable("level", 3, 107))
    assert spec.outputs == (Variable("k", -2, 2),)


def test_precedence_follows_slugs_grammar() -> None:
    assert one("a | b & c") == Or((a, And((b, c))))
    assert one("a ^ b | c") == Xor(a, Or((b, c)))
    assert one("a -> b ^ c") == Implies(a, Xor(b, c))
    assert one("a <-> b -> c") == Iff(a, Implies(b, c))
    assert one("!a & b") == And((Not(a), b))
    assert one("a & b & c") == And((a, b, c))
    assert one("(a & b) & c") == And((And((a, b)), c))


def test_binary_operators_associate_to_the_left_like_slugs() -> None:
    assert one("a -> b -> c") == Implies(Implies(a, b), c)
    assert one("a <-> b <-> c") == Iff(Iff(a, b), c)


def test_operator_spellings() -> None:
    assert one("a && b /\\ c") == one("a & b & c")
    assert one("a || b \\/ c") == one("a | b | c")
    assert one("~a --> b <--> c") == one("!a -> b <-> c")
    assert one("c & [a | b]") == one("c & (a | b)")  # a line starting with [ is a header
    assert one("TRUE | FALSE") == Or((Const(True), Const(False)))
    assert one("1 & a") == And((Const(True), a))


def test_next_becomes_primes() -> None:
    assert one("next(a & b) | X c") == Or((And((Var("a", True), Var("b", True))), Var("c", True)))
    assert one("X(n + 1 = m)") == Compare(
        "=", Add(IntVar("n", True), IntConst(1)), IntVar("m", True)
    )


def test_comparisons_and_sums() -> None:
    assert one("n' <= n + 1") == Compare("<=", IntVar("n", True), Add(IntVar("n"), IntConst(1)))
    assert one("(n + 1) + m != 3") == Compare(
        "!=", Add(Add(IntVar("n"), IntConst(1)), IntVar("m")), IntConst(3)
    )
    assert one("((n + 1) = m) | a") == Or((Compare("=", Add(IntVar("n"), IntConst(1)),
                                                   IntVar("m")), a))
    assert one("a -> m > 2") == Implies(a, Compare(">", IntVar("m"), IntConst(2)))
    assert one("!n = 3") == Not(Compare("=", IntVar("n"), IntConst(3)))


def test_prefix_lines_pass_through() -> None:
    booleans = {"a", "b", "c"}
    assert is_prefix_line("| a b'", booleans)
    assert is_prefix_line("$ 2 a ? 0", booleans)
    assert is_prefix_line("! a", booleans)
    assert not is_prefix_line("a | b", booleans)
    assert not is_prefix_line("| a", booleans)
    assert not is_prefix_line("& n a", booleans)
    assert one("| a ^ b c'") == Or((a, Xor(b, Var("c", True))))


def test_writer_is_canonical_and_keeps_shapes() -> None:
    spec = spec_of(
        "[SYS_TRANS]\n(a -> b) -> c\na -> (b -> c)\n!(a & b)\n(n + 1) + 2 = m'\n"
        "[ENV_INIT]\nn = 0\n"
    )
    text = emit_structuredslugs(spec, comments=False)
    assert text == (
        "[INPUT]\na\nb\nn:0...7\n\n[OUTPUT]\nc\nm:2...5\n\n[ENV_INIT]\nn = 0\n\n[SYS_INIT]\n\n"
        "[ENV_TRANS]\n\n[SYS_TRANS]\na -> b -> c\na -> (b -> c)\n!(a & b)\n(n + 1) + 2 = m'\n\n"
        "[ENV_LIVENESS]\n\n[SYS_LIVENESS]\n"
    )
    assert parse_structuredslugs(text, "x") == spec


def test_shared_boolean_clauses_are_written_as_buffers() -> None:
    # 2**30 leaves as a tree: the writer must keep the DAG (a '$' line, passed through).
    parts = ["a"] + [f"^ ? {i} ? {i}" for i in range(30)]
    text = "[INPUT]\na\n[SYS_LIVENESS]\n$ 31 " + " ".join(parts) + "\n"
    spec = parse_slugsin(text, "dag.slugsin")
    written = emit_structuredslugs(spec, comments=False)
    assert len(written) < 1000
    line = written.splitlines()[-1]
    assert line.startswith("$ ")
    again = parse_structuredslugs(written, "dag.structuredslugs")
    assert emit_structuredslugs(again, comments=False) == written


def test_deep_nesting_is_read_and_written_without_recursion() -> None:
    # Formerly a format error (a recursive reader); tests/formats/test_deep.py goes 10,000 deep.
    assert one("(" * 5000 + "a" + ")" * 5000) == a
    deep = parse_slugsin("[INPUT]\na\n[SYS_TRANS]\n" + "! " * 5000 + "a\n", "deep.slugsin")
    text = emit_structuredslugs(deep)
    assert "!" * 5000 + "a\n" in text  # infix, no longer a prefix fallback
    again = parse_structuredslugs(text, "x").sys_trans[0].formula
    assert emit_formula(again) == emit_formula(deep.sys_trans[0].formula)  # no deep hashing
    assert again == deep.sys_trans[0].formula


ERRORS = [
    ("[SYS_TRANS]\n(a & b\n", 9, 1, "missing ')' to close the '(' at column 1"),
    ("[SYS_TRANS]\na & b)\n", 9, 6, "unexpected ')' with no matching opening bracket"),
    ("[SYS_TRANS]\na % b\n", 9, 3, "unexpected character '%' in a formula"),
    ("[OUTPUT]\nx:5...2\n", 9, 1,
     "bad integer range 'x:5...2': the minimum 5 is larger than the maximum 2"),
    ("[OUTPUT]\nx:1..3\n", 9, 1,
     "bad integer range 'x:1..3': write name:MIN...MAX with whole numbers, e.g. x:0...7"),
    ("[OUTPUT]\nx:1:2...3\n", 9, 1,
     "bad declaration 'x:1:2...3': too many ':'; write name:MIN...MAX"),
    ("[SYS_TRANS]\na & zz\n", 9, 5,
     "unknown variable 'zz'; declare it under [INPUT] or [OUTPUT]"),
    ("[SYS_TRANS]\nn == 3\n", 9, 3, "'==' is not an operator here; write '=' for equality"),
    ("[SYS_TRANS]\nn = m - 1\n", 9, 7,
     "subtraction is not supported (SLUGS does not support it either); move the term to the "
     "other side, e.g. 'x + 1 = y' instead of 'x = y - 1'"),
    ("[SYS_TRANS]\nG a\n", 9, 1,
     "temporal operator 'G' (always) is outside GR(1): a section line is a state or "
     "transition formula (use next/X or primes only)"),
    ("[SYS_TRANS]\na U b\n", 9, 3,
     "temporal operator 'U' (until) is outside GR(1): a section line is a state or "
     "transition formula (use next/X or primes only)"),
    ("[SYS_TRANS]\nX(a')\n", 9, 3, "'a' is already a next-state value; 'next' cannot apply twice"),
    ("[SYS_TRANS]\n5\n", 9, 1,
     "the number 5 is not a formula; compare it with an integer variable, e.g. 'x = 5'"),
    ("[SYS_TRANS]\nn + a = 3\n", 9, 5,
     "Boolean variable 'a' cannot be used in arithmetic; only integer variables "
     "(name:MIN...MAX) can"),
    ("[OUTPUT]\nX\n", 9, 1,
     "'X' cannot be a variable name: use letters, digits, '_' and '.', not starting with a "
     "digit, and none of X F G U W TRUE FALSE next"),
    ("[OUTPUT]\nq@1\n", 9, 1,
     "variable name 'q@1' contains '@', which SLUGS reserves for the bits of integer variables"),
    ("[SYS_TRANS]\nn & a\n", 9, 3,
     "unexpected '&': expected a comparison (=, !=, <, <=, >, >=) after an integer expression"),
    ("[SYS_TRANS]\na &\n", 9, 4,
     "the formula ends too early: expected a variable, TRUE, FALSE, a comparison or '('"),
    ("[SYS_TRANS]\nn@1\n", 9, 1,
     "'n@1' is a bit of integer variable 'n'; refer to the integer by name instead"),
    ("[SYS_TRANS]\nn * 2 = m\n", 9, 3,
     "multiplication is not supported; write repeated additions instead"),
    ("[ENV_TRANS]\nc' | a\n", 9, 1,
     "next-state output 'c'' cannot appear in [ENV_TRANS]: the environment moves before the "
     "system and cannot see its next move"),
    ("[SYS_INIT]\nX a\n", 9, 3,
     "next-state variable 'a'' cannot appear in [SYS_INIT]: initial conditions constrain the "
     "first state only"),
    ("[SYS_TRANS]\na b\n", 9, 3, "unexpected 'b': expected an operator or the end of the line"),
    ("[SYSTRANS]\n", 8, 1,
     "unknown section header '[SYSTRANS]'; the known sections are [INPUT], [OUTPUT], "
     "[ENV_INIT], [SYS_INIT], [ENV_TRANS], [SYS_TRANS], [ENV_LIVENESS], [SYS_LIVENESS]"),
    ("[INPUT]\nn:1...2\n", 9, 1,
     "variable 'n' is declared twice (first on line 4); every name must be unique"),
    ("[SYS_TRANS]\n$ 2 a\n", 9, 1,
     "missing operand: the memory buffer '$ 2' needs 2 formulas but the line ends after 1"),
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
    assert (err.span.file, err.span.line, err.span.column) == ("t.structuredslugs", line, column)


SEED_TEXT = (
    "[INPUT]\na\nn:0...7\n[OUTPUT]\nc\nm:2...5\n[ENV_INIT]\nn = 0 & !a\n"
    "[SYS_TRANS]\n(a -> X c) & (m' <= n + 1 | c)\n| a c'\n[SYS_LIVENESS]\nnext(m = 3) <-> a\n"
)
PIECES = ["&", "|", "!", "^", "->", "<->", "(", ")", "[", "]", "=", "<=", "+", "-", "X",
          "next", "G", "TRUE", "0", "1", "9", "a", "n", "m'", "x", "'", ":", "...", "#",
          "$ 1", "? 0", "\n", " ", "[SYS_INIT]", "é"]


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
        spec = parse_structuredslugs(text, "fuzz.structuredslugs")
    except SlugsFormatError as err:
        assert err.span is not None and err.span.file == "fuzz.structuredslugs"
        return
    assert parse_structuredslugs(emit_structuredslugs(spec), "again") == spec
    bitblast(spec)
