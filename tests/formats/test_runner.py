"""The SLUGS binary path, exercised through tests/fake_slugs.py and recorded SLUGS outputs."""

from __future__ import annotations

import csv
import os
import re
import shutil
import time
from pathlib import Path

import pytest

from gaitc.diagnostics import SolverError
from gaitc.verifier.counterstrategy import verify_counterstrategy
from gaitc.verifier.strategy import verify
from slugs_bridge.runner import (
    OPTIONS,
    controller_from_slugs_json,
    counterstrategy_from_slugs_text,
    find_slugs,
    run_slugs_check,
    run_slugs_counter,
    run_slugs_synth,
)
from slugs_bridge.slugsin import parse_slugsin

HERE = Path(__file__).resolve().parents[1]
FAKE = str(HERE / "fake_slugs.py")
RECORDED = HERE / "data" / "slugs_recorded"
EXAMPLES = HERE / "data" / "slugs_examples"
NAMES = ["simple_safety_example", "semantics_diference"]
SEMANTICS = ["default", "robotics"]
#: The live binary named by $SLUGS when the tests start (read before ``_no_ambient_slugs``
#: removes $SLUGS from every test's environment).
LIVE_SLUGS = os.environ.get("SLUGS")


def recorded_verdicts() -> dict[tuple[str, str], bool]:
    """SLUGS's verdicts from the reference table (not from the fake's own index)."""
    out = {}
    with (EXAMPLES / "verdicts.tsv").open(encoding="utf-8") as handle:
        for row in csv.reader((ln for ln in handle if not ln.startswith("#")), delimiter="\t"):
            out[(row[0].rsplit(".", 1)[0], "default")] = row[1] == "realizable"
            out[(row[0].rsplit(".", 1)[0], "robotics")] = row[2] == "realizable"
    return out


def text_of(name: str) -> str:
    return (RECORDED / f"{name}.slugsin").read_text(encoding="utf-8")


@pytest.fixture(autouse=True)
def _no_ambient_slugs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SLUGS", raising=False)
    monkeypatch.delenv("FAKE_SLUGS_BEHAVIOUR", raising=False)


# ---------------------------------------------------------------- finding the binary
def test_find_slugs_prefers_explicit_then_env_then_path(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    on_path = tmp_path / "slugs"
    shutil.copy(FAKE, on_path)
    on_path.chmod(0o755)
    monkeypatch.setenv("PATH", str(tmp_path))
    assert find_slugs() == str(on_path)
    monkeypatch.setenv("SLUGS", FAKE)
    assert find_slugs() == FAKE
    assert find_slugs(str(on_path)) == str(on_path)


def test_find_slugs_none_and_bad_paths(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("PATH", str(tmp_path))
    assert find_slugs() is None
    with pytest.raises(SolverError, match=r"given by --slugs \('/nonexistent/slugs'\) does not"):
        find_slugs("/nonexistent/slugs")
    monkeypatch.setenv("SLUGS", str(tmp_path))
    with pytest.raises(SolverError, match=r"given by \$SLUGS"):
        find_slugs()
    monkeypatch.delenv("SLUGS")
    with pytest.raises(SolverError, match="no SLUGS binary found"):
        run_slugs_check(text_of(NAMES[0]))


# ---------------------------------------------------------------- verdicts and strategies
@pytest.mark.parametrize("semantics", SEMANTICS)
@pytest.mark.parametrize("name", NAMES)
def test_check_reads_the_result_line(name: str, semantics: str) -> None:
    result = run_slugs_check(text_of(name), semantics=semantics, slugs=FAKE, timeout=60)
    assert result.realizable == recorded_verdicts()[(name, semantics)]
    assert result.command[1:-1] == OPTIONS[("check", semantics)]
    assert "RESULT: Specification is" in result.stderr
    assert result.seconds > 0


@pytest.mark.parametrize("semantics", SEMANTICS)
@pytest.mark.parametrize("name", NAMES)
def test_synth_strategy_is_read_and_verified(name: str, semantics: str) -> None:
    spec = parse_slugsin(text_of(name), name)
    result = run_slugs_synth(text_of(name), semantics=semantics, slugs=FAKE, timeout=60)
    assert result.command[-2].endswith("spec.slugsin")  # input first, then output
    assert result.command[-1].endswith("strategy.json")
    if not result.realizable:
        assert result.output is None
        return
    assert result.output is not None
    ctrl = controller_from_slugs_json(result.output, spec, semantics)
    assert ctrl.solver == "slugs" and ctrl.semantics == semantics
    assert ctrl.inputs + ctrl.outputs == ctrl.variables
    assert ctrl.initial  # computed from env_init/sys_init: SLUGS does not mark them
    report = verify(spec, ctrl, semantics)
    assert report.ok, report.problems


def test_initial_nodes_of_recorded_strategy() -> None:
    spec = parse_slugsin(text_of("simple_safety_example"), "simple")
    text = (RECORDED / "simple_safety_example.default.json").read_text(encoding="utf-8")
    ctrl = controller_from_slugs_json(text, spec)
    # θe = !(a & b), θs = c: exactly the first three recorded states.
    assert ctrl.initial == (0, 1, 2)
    assert [n.trans for n in ctrl.nodes] == [(1, 3, 4)] * 5


def test_counterstrategy_is_read_and_verified() -> None:
    name = "semantics_diference"
    spec = parse_slugsin(text_of(name), name)
    result = run_slugs_counter(text_of(name), semantics="robotics", slugs=FAKE, timeout=60)
    assert not result.realizable
    assert result.command[-2].endswith("counter.txt")  # output file before the input file
    assert result.command[-1].endswith("spec.slugsin")
    assert result.output is not None
    ctrl = counterstrategy_from_slugs_text(result.output, spec, "robotics")
    assert ctrl.kind == "counterstrategy"
    assert ctrl.initial == (0, 1)
    assert [n.trans for n in ctrl.nodes] == [(2,), (2,), ()]
    assert ctrl.nodes[2].state == (0, 0)  # dead end: only inputs printed, outputs filled with 0
    report = verify_counterstrategy(spec, ctrl, "robotics")
    assert report.ok, report.problems


def test_counter_on_realizable_spec_writes_nothing() -> None:
    result = run_slugs_counter(text_of("semantics_diference"), slugs=FAKE, timeout=60)
    assert result.realizable and result.output is None


# ---------------------------------------------------------------- failures
def test_timeout_kills_slugs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("FAKE_SLUGS_BEHAVIOUR", "sleep")
    start = time.perf_counter()
    with pytest.raises(SolverError, match=r"^SLUGS did not finish within 0\.5 s$"):
        run_slugs_check(text_of(NAMES[0]), slugs=FAKE, timeout=0.5)
    assert time.perf_counter() - start < 20


def test_error_in_the_input_becomes_solver_error() -> None:
    text = text_of(NAMES[0]).replace("^ c' a'", "^ c' q'")
    with pytest.raises(SolverError) as info:
        run_slugs_check(text, slugs=FAKE, timeout=60)
    assert "The variable q' has not been found" in info.value.message
    assert info.value.message.startswith("SLUGS failed (exit code 1): Error")


@pytest.mark.parametrize(
    ("behaviour", "message"),
    [("crash", "SLUGS failed (exit code 139): Segmentation fault"),
     ("signal", "SLUGS failed (killed by signal 9)"),
     ("no-result", "SLUGS printed 0 RESULT lines instead of one")],
)
def test_crash_and_missing_verdict(
    behaviour: str, message: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("FAKE_SLUGS_BEHAVIOUR", behaviour)
    with pytest.raises(SolverError, match=re.escape(message)):
        run_slugs_check(text_of(NAMES[0]), slugs=FAKE, timeout=60)


def test_malformed_strategy_outputs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("FAKE_SLUGS_BEHAVIOUR", "garbage")
    spec = parse_slugsin(text_of(NAMES[0]), "x")
    result = run_slugs_synth(text_of(NAMES[0]), slugs=FAKE, timeout=60)
    assert result.output == "{not json"
    with pytest.raises(SolverError, match="not valid JSON"):
        controller_from_slugs_json(result.output, spec)
    with pytest.raises(SolverError, match="cannot read SLUGS's counter-strategy"):
        counterstrategy_from_slugs_text("State zero\n", spec)
    with pytest.raises(SolverError, match="unknown variable or value 'z:1'"):
        counterstrategy_from_slugs_text("State 0 with rank (0,0) -> <z:1>\n", spec)


# ---------------------------------------------------------------- the real binary
def _live_binary() -> str:
    binary = find_slugs(LIVE_SLUGS)
    if binary is None or Path(binary).resolve() == Path(FAKE).resolve():
        pytest.skip("no slugs binary on PATH or in $SLUGS")
    return binary


@pytest.mark.slugs
@pytest.mark.parametrize("semantics", SEMANTICS)
def test_live_slugs_agrees_with_recorded_verdicts(semantics: str) -> None:
    binary = _live_binary()
    verdicts = recorded_verdicts()
    for path in sorted(EXAMPLES.glob("*.slugsin")):
        name = path.stem
        result = run_slugs_check(path.read_text(encoding="utf-8"), semantics=semantics,
                                 slugs=binary, timeout=600)
        assert result.realizable == verdicts[(name, semantics)], name
        if result.realizable and name in NAMES:
            spec = parse_slugsin(path.read_text(encoding="utf-8"), name)
            synth = run_slugs_synth(path.read_text(encoding="utf-8"), semantics=semantics,
                                    slugs=binary, timeout=600)
            assert synth.output is not None
            assert verify(spec, controller_from_slugs_json(synth.output, spec, semantics),
                          semantics).ok


@pytest.mark.slugs
@pytest.mark.parametrize("semantics", SEMANTICS)
def test_live_slugs_agrees_on_gaitcs_translation_of_every_example(semantics: str) -> None:
    """Every example, in whichever format, read by gaitc and written back as slugsin."""
    from gaitc.api.compiling import emit
    from gaitc.core.spec import load

    binary = _live_binary()
    verdicts = recorded_verdicts()
    paths = sorted(p for p in EXAMPLES.iterdir() if p.name != "verdicts.tsv")
    assert len(paths) == len({name for name, _ in verdicts}) >= 26
    for path in paths:
        result = run_slugs_check(emit(load(str(path)), "slugsin"), semantics=semantics,
                                 slugs=binary, timeout=600)
        assert result.realizable == verdicts[(path.name.rsplit(".", 1)[0], semantics)], path.name


# ---------------------------------------------------------------- through the command line
def test_cli_slugs_path_end_to_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from gaitc.cli import main

    spec_file = str(RECORDED / "semantics_diference.slugsin")
    common = ["--solver", "slugs", "--slugs", FAKE, "--timeout", "60"]
    assert main(["check", *common, spec_file]) == 0
    assert main(["check", *common, "--robotics-semantics", spec_file]) == 3
    out = str(tmp_path / "ctrl.json")
    assert main(["synth", *common, spec_file, "-o", out]) == 0
    assert "verified: strategy ok" in capsys.readouterr().out
    assert main(["verify", spec_file, out]) == 0
    counter = str(tmp_path / "counter.json")
    assert main(["counter", *common, "--robotics-semantics", spec_file, "-o", counter]) == 0
    assert main(["verify", "--robotics-semantics", spec_file, counter]) == 0
    assert "verified: counterstrategy ok" in capsys.readouterr().out
