"""The peer solvers (peers/): gr1c's .spc text and omega's game decide as SLUGS recorded.

Each peer's verdict on every corpus spec and SLUGS example, under both semantics, must equal
SLUGS's recorded one: the translations (initial-condition forms, ranges, comparisons,
liveness) are checked against each other and against SLUGS independently.  Tests that need
gr1c (``$GR1C`` or PATH) or omega (the ``peers`` extra) are skipped cleanly
without them.  Also: the golden .spc text of one small spec (``--update-golden`` rewrites
it), the error for a liveness that mixes current and next values, word for word, and the
comparison expansion against the atom it replaces on every value of small ranges.
"""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import tempfile
from pathlib import Path

import pytest
from games import explicit_realizable, tiny_specs
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gaitc.diagnostics import PeerFormatError, SolverError
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import Add, And, Compare, IntConst, IntVar, Term, Var, atoms, walk
from gaitc.ir.spec import Clause, GR1Spec, Origin, Semantics, Variable
from peers.comparisons import expand_comparison
from peers.game import peer_game
from peers.runners import find_gr1c, omega_installed, run_gr1c, run_omega
from peers.spc import emit_spc, start_form
from slugs_bridge.formats import load_spec_file

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
GOLDEN = ROOT / "tests" / "golden"
SMALL = GOLDEN / "peers_small.structuredslugs"
MIXED = "mixes current and next-state values"


def _recorded() -> list[tuple[Path, str, str]]:
    """(file, default verdict, robotics verdict) of every corpus spec and SLUGS example."""
    out = [(DATA / "gr1_corpus" / f"{r['name']}.slugsin", r["default"], r["robotics"])
           for r in json.loads((DATA / "gr1_corpus" / "verdicts.json").read_text())]
    for line in (DATA / "slugs_examples" / "verdicts.tsv").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            name, default, robotics = line.split("\t")[:3]
            out.append((DATA / "slugs_examples" / name, default, robotics))
    return out


RECORDED = _recorded()
#: The SLUGS examples and the first ten corpus specs run always; the rest of the corpus is
#: marked slow (each peer takes some 15 s over all of them).
CASES = [pytest.param(path, default, robotics, id=path.name,
                      marks=() if "slugs_examples" in str(path) or path.stem < "rand3_0010"
                      else pytest.mark.slow)
         for path, default, robotics in RECORDED]


@pytest.fixture(scope="module")
def gr1c() -> str:
    found = find_gr1c()
    if found is None:
        pytest.skip("no gr1c binary ($GR1C or on PATH)")
    return found


@pytest.fixture(scope="module")
def omega() -> None:
    if not omega_installed():
        pytest.skip("omega is not installed (pip install 'gaitc[peers]')")


def _gr1c_verdict(binary: str, spec: GR1Spec, semantics: Semantics) -> str:
    program = emit_spc(spec, semantics)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp, "spec.spc")
        path.write_text(program.text, encoding="utf-8")
        done = subprocess.run([binary, "-r", *program.flags, str(path)], capture_output=True,
                              text=True, check=False, timeout=60)
    assert done.returncode in (0, 3), done.stdout + done.stderr
    return "realizable" if done.returncode == 0 else "unrealizable"


def _omega_verdict(spec: GR1Spec, semantics: Semantics) -> str:
    from peers.omega_game import decide

    return "realizable" if decide(spec, semantics) else "unrealizable"


def _mixed(spec: GR1Spec) -> bool:
    return any({p for _, p in atoms(c.formula)} == {True, False}
               for c in spec.env_liveness + spec.sys_liveness)


# ---------------------------------------------------------------- verdicts against SLUGS's
@pytest.mark.gr1c
@pytest.mark.parametrize(("path", "default", "robotics"), CASES)
def test_gr1c_decides_as_slugs_recorded(gr1c: str, path: Path, default: str,
                                        robotics: str) -> None:
    spec = load_spec_file(str(path))
    if _mixed(spec):  # neither peer reads a liveness goal on transitions
        with pytest.raises(PeerFormatError, match=MIXED):
            emit_spc(spec)
        return
    assert _gr1c_verdict(gr1c, spec, Semantics.DEFAULT) == default
    assert _gr1c_verdict(gr1c, spec, Semantics.ROBOTICS) == robotics


@pytest.mark.omega
@pytest.mark.parametrize(("path", "default", "robotics"), CASES)
def test_omega_decides_as_slugs_recorded(omega: None, path: Path, default: str,
                                         robotics: str) -> None:
    spec = load_spec_file(str(path))
    if _mixed(spec):
        with pytest.raises(PeerFormatError, match=MIXED):
            _omega_verdict(spec, Semantics.DEFAULT)
        return
    assert _omega_verdict(spec, Semantics.DEFAULT) == default
    assert _omega_verdict(spec, Semantics.ROBOTICS) == robotics


def test_the_recorded_specs_need_every_initial_form() -> None:
    """The sweeps above exercise each form of peers/spc.py's initial condition."""
    forms = set()
    for path, _, _ in RECORDED[:40]:
        spec = load_spec_file(str(path))
        if not _mixed(spec):
            forms |= {start_form(peer_game(spec), s) for s in Semantics}
    assert forms == {"direct", "started", "vacuous"}


@pytest.mark.gr1c
@pytest.mark.omega
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tiny_specs())
def test_peers_agree_with_the_explicit_solver_on_random_specs(gr1c: str, omega: None,
                                                               spec: GR1Spec) -> None:
    if _mixed(spec):
        with pytest.raises(PeerFormatError, match=MIXED):
            peer_game(spec)
        return
    for semantics in Semantics:
        expected = "realizable" if explicit_realizable(spec, semantics) else "unrealizable"
        assert _gr1c_verdict(gr1c, spec, semantics) == expected, semantics
        assert _omega_verdict(spec, semantics) == expected, semantics


# ---------------------------------------------------------------- the .spc text
@pytest.mark.parametrize("semantics", list(Semantics))
def test_golden_spc(semantics: Semantics, request: pytest.FixtureRequest,
                    monkeypatch: pytest.MonkeyPatch) -> None:
    """A shifted integer (1..3 as [0,2]), comparisons of two variables listed by value, xor,
    a liveness over next values read on the state, and a θs that reads an input (the
    started form by default; robotics is direct)."""
    monkeypatch.chdir(ROOT)
    program = emit_spc(load_spec_file(str(SMALL.relative_to(ROOT))), semantics)
    expected = SMALL.with_name(f"{SMALL.stem}.{semantics}.spc")
    text = f"# gr1c {' '.join(program.flags)}\n{program.text}"
    flag = request.config.getoption("--update-golden", default=False)
    if flag or os.environ.get("GAITC_UPDATE_GOLDEN") == "1":
        expected.write_text(text, encoding="utf-8")
        return
    assert expected.exists(), f"{expected.name} is missing: run with --update-golden"
    assert text == expected.read_text(encoding="utf-8")
    assert program.start == ("started" if semantics == Semantics.DEFAULT else "direct")


def test_a_liveness_mixing_current_and_next_values_is_refused_by_name() -> None:
    spec = GR1Spec(inputs=(Variable("door"),), outputs=(Variable("light"),),
                   sys_liveness=(Clause(Var("light")),
                                 Clause(And((Var("light"), Var("door", True))),
                                        Origin("test")),))
    with pytest.raises(PeerFormatError) as info:
        emit_spc(spec)
    assert info.value.message == (
        "system liveness clause 2 mixes current and next-state values ('light' and "
        "'door''): gr1c and omega read a liveness goal on one state only")
    assert info.value.hint == ("write it over next-state values only (□◇φ' is read as □◇φ) "
                               "or over current values only")


def test_a_liveness_over_next_values_only_is_read_on_the_state() -> None:
    spec = GR1Spec(inputs=(Variable("door"),), outputs=(Variable("light"),),
                   env_liveness=(Clause(Var("door", True)),))
    assert peer_game(spec).env_liveness == (Clause(Var("door")),)
    assert "[]<>(door);" in emit_spc(spec).text


def test_names_gr1c_cannot_read_or_would_confuse_with_bits_are_changed() -> None:
    spec = GR1Spec(inputs=(Variable("a.b"), Variable("x0"), Variable("True")),
                   outputs=(Variable("x", 0, 5), Variable("x0_")))
    text = emit_spc(spec, comments=False).text
    assert text.splitlines()[:2] == ["ENV: a_b x0_ True_;", "SYS: x [0,5] x0__;"]


def test_a_spec_without_variables_gets_a_free_bit() -> None:
    text = emit_spc(GR1Spec(), comments=False).text
    assert text.splitlines()[:2] == ["ENV:;", "SYS: gaitc_free;"]


def test_a_comparison_with_too_many_values_is_refused() -> None:
    big = (Variable("a", 0, 299), Variable("b", 0, 299))
    spec = GR1Spec(outputs=big, sys_trans=(Clause(Compare("<", IntVar("a"), IntVar("b"))),))
    with pytest.raises(PeerFormatError, match="over a, b ranges over 90000 combinations"):
        emit_spc(spec)


# ---------------------------------------------------------------- comparisons
def _terms(names: list[str]) -> st.SearchStrategy[Term]:
    leaf = st.one_of(
        st.builds(IntConst, st.integers(-4, 6)),
        st.builds(IntVar, st.sampled_from(names), st.booleans()),
    )
    return st.recursive(leaf, lambda inner: st.builds(Add, inner, inner), max_leaves=4)


DOMAINS = {"a": (0, 3), "b": (-2, 1), "c": (1, 4)}


@settings(max_examples=300, deadline=None)
@given(st.sampled_from(["=", "!=", "<", "<=", ">", ">="]), _terms(list(DOMAINS)),
       _terms(list(DOMAINS)))
def test_the_expansion_of_a_comparison_is_equivalent_on_every_value(op: str, left: Term,
                                                                     right: Term) -> None:
    atom = Compare(op, left, right)
    expanded = expand_comparison(atom, DOMAINS)
    for node in walk(expanded):  # only one variable against a number in its range
        if isinstance(node, Compare):
            assert isinstance(node.left, IntVar) and isinstance(node.right, IntConst)
            low, high = DOMAINS[node.left.name]
            assert low <= node.right.value <= high and node.op in ("=", "!=", "<=", ">=")
    keys = sorted(atoms(atom))
    for values in itertools.product(*(range(DOMAINS[n][0], DOMAINS[n][1] + 1)
                                      for n, _ in keys)):
        valuation = {n + ("'" if p else ""): v for (n, p), v in zip(keys, values, strict=True)}
        assert evaluate(expanded, valuation) == evaluate(atom, valuation), valuation


def test_a_comparison_of_one_variable_with_a_number_stays_itself() -> None:
    assert expand_comparison(Compare("=", IntVar("a"), IntConst(2)), DOMAINS) == Compare(
        "=", IntVar("a"), IntConst(2))
    assert expand_comparison(Compare("<", IntVar("a"), IntConst(2)), DOMAINS) == Compare(
        "<=", IntVar("a"), IntConst(1))
    assert expand_comparison(Compare("!=", IntVar("c", True), IntConst(3)), DOMAINS) == Compare(
        "!=", IntVar("c", True), IntConst(3))


# ---------------------------------------------------------------- the runners
@pytest.mark.gr1c
def test_run_gr1c_reads_gr1c_s_answer(gr1c: str) -> None:
    spec = load_spec_file(str(SMALL))
    result = run_gr1c(spec, Semantics.DEFAULT, timeout=60)
    assert (result.solver, result.verdict) == ("gr1c", "realizable")
    assert result.command[1:4] == ("-r", "-n", "ALL_INIT")


def test_a_missing_gr1c_named_by_the_environment_is_an_error(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("GR1C", "/nonexistent/gr1c")
    with pytest.raises(SolverError, match=r"\$GR1C \('/nonexistent/gr1c'\) does not exist"):
        find_gr1c()


@pytest.mark.omega
def test_run_omega_runs_a_whole_process(omega: None) -> None:
    spec = load_spec_file(str(SMALL))
    assert run_omega(spec, Semantics.ROBOTICS, timeout=120).verdict == "realizable"


@pytest.mark.omega
def test_omega_game_main_prints_the_verdict(omega: None,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    from peers.omega_game import main

    path = str(DATA / "gr1_corpus" / "rand3_0005.slugsin")
    assert main([path]) == 3
    assert main([path, "--semantics", "robotics"]) == 0
    assert capsys.readouterr().out == "unrealizable\nrealizable\n"
    assert main([str(DATA / "slugs_examples" / "networks.slugsin")]) == 1
    assert MIXED in capsys.readouterr().err
