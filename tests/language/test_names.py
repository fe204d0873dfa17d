"""Names a format cannot carry: the renaming of slugs_bridge/names.py, its comment, and
SLUGS's answers mapped back to the spec's names (slugs_bridge/runner.py)."""

from __future__ import annotations

import json

import pytest

from gaitc.api.compiling import FORMATS, emit
from gaitc.diagnostics import SlugsFormatError, Span
from gaitc.ir.bitblast import bitblast
from gaitc.ir.formula import And, Compare, Iff, Implies, IntConst, IntVar, Not, Or, Var, Xor
from gaitc.ir.spec import Clause, GR1Spec, Origin, Variable
from slugs_bridge.ltltext import parse_ltl
from slugs_bridge.names import RENAMED, is_valid_name, renaming
from slugs_bridge.prefixform import prefix_spec
from slugs_bridge.runner import controller_from_slugs_json, counterstrategy_from_slugs_text
from slugs_bridge.slugsin import emit_slugsin, parse_slugsin
from slugs_bridge.structured import emit_structuredslugs, parse_structuredslugs

ODD = ["F", "0", "a b", "x'", "#c", "[d", "é", "a@1", "TRUE", "q.r", "", "next", "l\u2028m",
       "2", "ok", "a\nb", '"q"', "k,1"]


def test_renaming_per_format() -> None:
    assert renaming(["F", "next", "a b", "1x", "a@1", "x'", "é", "", "ok"], "structuredslugs") == {
        "F": "F_", "next": "next_", "a b": "a_b", "1x": "_1x", "a@1": "a_1", "x'": "x_",
        "é": "_", "": "__",
    }
    assert renaming(["F", "0", "12", "#c", "[d", "a,b", "x'", "a@0.1.2"], "slugsin") == {
        "0": "0_", "12": "12_", "#c": "_c", "[d": "_d", "a,b": "a_b", "x'": "x_",
    }
    assert renaming(["G", "x@0.1.2", "W", "Wq"], "ltl") == {"G": "G_", "W": "W_"}


def test_renamed_names_never_clash() -> None:
    assert renaming(["F", "F_", "F__"], "ltl") == {"F": "F___"}
    assert renaming(["a b", "a_b", "a-b"], "structuredslugs") == {"a b": "a_b_", "a-b": "a_b__"}
    names = renaming(ODD, "structuredslugs")
    written = [names.get(n, n) for n in ODD]
    assert len(set(written)) == len(ODD)
    assert all(is_valid_name(w, "structuredslugs") for w in written)


def odd_spec() -> GR1Spec:
    """A spec whose names no format can carry as they are, integers among them."""
    booleans = [n for n in ODD if n != "F"]
    v = {n: Var(n) for n in booleans}
    nxt = {n: Var(n, True) for n in booleans}
    return GR1Spec(
        inputs=(Variable("F", 0, 3), *(Variable(n) for n in booleans[:8])),
        outputs=(Variable("k k", -2, 2), *(Variable(n) for n in booleans[8:])),
        env_init=(Clause(And((v["0"], Not(v["a b"]))), Origin("init\nwith [a] line break")),),
        sys_init=(Clause(Or((v["ok"], v["TRUE"], v["l\u2028m"]))),),
        env_trans=(Clause(Implies(v["x'"], Xor(nxt["#c"], nxt["[d"])),
                          Origin("r", Span("f", 3, 1))),
                   Clause(Compare("<", IntVar("F", True), IntConst(3)))),
        sys_trans=(Clause(Iff(nxt["next"], v["é"])), Clause(Not(nxt["q.r"])),
                   Clause(Compare("=", IntVar("k k", True), IntVar("F")))),
        env_liveness=(Clause(Var("a@1")),),
        sys_liveness=(Clause(And((nxt["a\nb"], v['"q"'], v["k,1"], v["2"], v[""]))),),
        name="odd\nname",
    )


@pytest.mark.parametrize("fmt", FORMATS)
def test_odd_names_round_trip_through_every_format(fmt: str) -> None:
    spec = odd_spec()
    text = emit(spec, fmt)
    assert text.count("\n# renamed names") + text.startswith(RENAMED) == 1
    assert all(not line.startswith(("[d", "#c")) for line in text.splitlines())
    if fmt == "structuredslugs":
        assert parse_structuredslugs(text, "odd.structuredslugs") == spec
    elif fmt == "ltl":
        assert parse_ltl(text, "odd.ltl") == spec
    else:
        assert parse_slugsin(text, "odd.slugsin") == prefix_spec(bitblast(spec))


def test_the_renaming_comment_heads_the_text_and_maps_written_to_spec_names() -> None:
    spec = GR1Spec(outputs=(Variable("X"), Variable("y")),
                   sys_trans=(Clause(Implies(Var("X"), Var("y", True))),))
    text = emit_structuredslugs(spec)
    assert text == (
        f'{RENAMED}{{"X_": "X"}}\n\n[INPUT]\n\n[OUTPUT]\nX_\ny\n\n[ENV_INIT]\n\n[SYS_INIT]\n\n'
        "[ENV_TRANS]\n\n[SYS_TRANS]\nX_ -> y'\n\n[ENV_LIVENESS]\n\n[SYS_LIVENESS]\n"
    )
    bare = text.split("\n", 2)[2]  # without the comment the names are as written
    assert [v.name for v in parse_structuredslugs(bare, "bare").outputs] == ["X_", "y"]
    assert emit_slugsin(spec) == emit_slugsin(spec, comments=False)  # no name, no origins
    assert RENAMED not in emit_slugsin(spec)  # slugsin has no keywords


BAD_COMMENTS = [
    (RENAMED + "{not json", "the renaming comment is not a JSON object: Expecting property "
     "name enclosed in double quotes"),
    (RENAMED + '["a"]', "the renaming comment must map written names to spec names, e.g. "
     '{"F_": "F"}'),
    (RENAMED + '{"zz": "F"}', "the renaming comment renames 'zz', which is not declared"),
    (RENAMED + '{"a": "b"}', "the renaming comment gives 'a' and 'b' the same spec name 'b'"),
]


@pytest.mark.parametrize(("comment", "message"), BAD_COMMENTS)
def test_bad_renaming_comments_are_positioned_errors(comment: str, message: str) -> None:
    for parse, name in ((parse_slugsin, "f.slugsin"), (parse_structuredslugs, "f.ss")):
        with pytest.raises(SlugsFormatError) as info:
            parse(f"# title\n{comment}\n[INPUT]\na\nb\n", name)
        assert info.value.message == message
        assert info.value.span is not None and (info.value.span.file, info.value.span.line) == (
            name, 2)


def test_a_renaming_comment_after_the_first_section_is_an_ordinary_comment() -> None:
    spec = parse_slugsin(f'[INPUT]\na\n{RENAMED}{{"a": "F"}}\n', "late.slugsin")
    assert [v.name for v in spec.inputs] == ["a"]


# ---------------------------------------------------------------- SLUGS's answers
def slugs_spec() -> GR1Spec:
    """semantics_diference.slugsin of tests/data/slugs_recorded with names slugsin cannot
    carry: SLUGS would see ``per_son`` and ``0_`` and answer in those names."""
    person, bit = Var("per son"), Var("0")
    return GR1Spec(inputs=(Variable("per son"),), outputs=(Variable("0"),),
                   env_liveness=(Clause(person), Clause(Not(person))), sys_trans=(Clause(bit),))


def test_slugs_strategies_get_the_spec_names_back() -> None:
    spec = slugs_spec()
    assert "\nper_son\n" in emit_slugsin(spec) and "\n0_\n" in emit_slugsin(spec)
    answer = {"version": 0, "slugs": "0.0.1", "variables": ["per_son", "0_"],
              "nodes": {"0": {"rank": 0, "state": [0, 1], "trans": [0, 1]},
                        "1": {"rank": 0, "state": [1, 1], "trans": [0, 1]}}}
    ctrl = controller_from_slugs_json(json.dumps(answer), spec)
    assert ctrl.variables == ("per son", "0")
    assert (ctrl.inputs, ctrl.outputs) == (("per son",), ("0",))
    assert ctrl.values(1) == {"per son": 1, "0": 1}


def test_slugs_counterstrategies_get_the_spec_names_back() -> None:
    text = ("State 0 with rank (0,0) -> <per_son:0, 0_:0>\n\tWith successors : 1\n"
            "State 1 with rank (0,0) -> <per_son:1>\n\tWith no successors.\n")
    ctrl = counterstrategy_from_slugs_text(text, slugs_spec())
    assert ctrl.variables == ("per son", "0")
    assert [n.state for n in ctrl.nodes] == [(0, 0), (1, 0)]


def test_integer_bits_keep_their_names_in_slugsin() -> None:
    spec = GR1Spec(inputs=(Variable("F", 1, 2),), env_init=(Clause(Compare(
        "=", IntVar("F"), IntConst(2))),))
    text = emit(spec, "slugsin")
    assert RENAMED not in text and "\nF@0.1.2\n" in text


def test_a_spec_name_that_looks_like_the_renaming_comment_is_quoted() -> None:
    name = RENAMED[2:] + "{}"
    spec = GR1Spec(outputs=(Variable("y"),), name=name)
    text = emit_structuredslugs(spec)
    assert text.startswith("# " + json.dumps(name) + ": generated by gaitc\n")
    assert parse_structuredslugs(text, "x.structuredslugs") == spec
