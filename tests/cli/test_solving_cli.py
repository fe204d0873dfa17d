"""Tests of the check/synth/counter/verify commands (gaitc/cli/commands/solving.py)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.ir.controller import load_controller

DATA = Path(__file__).parents[1] / "data" / "slugs_examples"
REALIZABLE = str(DATA / "firefighting.slugsin")
UNREALIZABLE = str(DATA / "unrealizable1.slugsin")
SEMANTICS = str(DATA / "semantics_diference.slugsin")
SPECS = Path(__file__).parents[2] / "specs"


def test_check_prints_one_line_per_file_and_exit_code_3_if_any_unrealizable(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["check", REALIZABLE]) == 0
    assert main(["check", REALIZABLE, UNREALIZABLE]) == 3
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith(f"{REALIZABLE}: realizable (")
    assert out[-1].startswith(f"{UNREALIZABLE}: unrealizable (")


def test_check_json_and_robotics_semantics(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", "--json", SEMANTICS]) == 0
    assert main(["check", "--json", "--robotics-semantics", SEMANTICS]) == 3
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [r["verdict"] for r in lines] == ["realizable", "unrealizable"]
    assert all({"file", "verdict", "seconds"} <= set(r) for r in lines)


def test_check_reports_a_broken_file_as_a_user_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "bad.slugsin"
    bad.write_text("[INPUT]\na\n[SYS_TRANS]\n& a\n", encoding="utf-8")
    assert main(["check", str(bad), REALIZABLE]) == 1
    captured = capsys.readouterr()
    assert f"{bad}:4:" in captured.err
    assert "realizable" in captured.out


def test_check_timeout_is_a_solver_failure(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["check", "--timeout", "1e-9", REALIZABLE]) == 4  # -1 is a usage error now
    assert "time limit" in capsys.readouterr().err


def test_synth_writes_a_verified_controller(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "c.json"
    assert main(["synth", REALIZABLE, "-o", str(out)]) == 0
    assert "verified: strategy ok" in capsys.readouterr().out
    controller = load_controller(str(out))
    assert controller.kind == "strategy" and controller.source is not None
    assert main(["verify", REALIZABLE, str(out)]) == 0


def test_synth_on_unrealizable_spec_writes_nothing(tmp_path: Path) -> None:
    out = tmp_path / "c.json"
    assert main(["synth", UNREALIZABLE, "-o", str(out)]) == 3
    assert not out.exists()


def test_counter_writes_a_counterstrategy_that_verifies(tmp_path: Path) -> None:
    out = tmp_path / "u.json"
    assert main(["counter", UNREALIZABLE, "-o", str(out)]) == 0
    assert load_controller(str(out)).kind == "counterstrategy"
    assert main(["verify", UNREALIZABLE, str(out)]) == 0
    assert main(["counter", REALIZABLE, "-o", str(tmp_path / "none.json")]) == 3


def test_verify_rejects_a_controller_for_another_spec(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "c.json"
    assert main(["synth", str(DATA / "networks.slugsin"), "-o", str(out), "--no-verify"]) == 0
    assert main(["verify", REALIZABLE, str(out)]) == 1
    capsys.readouterr()


def test_gait_specs_give_the_same_verdict_in_both_encodings(
    capsys: pytest.CaptureFixture[str],
) -> None:
    gaits = sorted(str(p) for p in SPECS.glob("*.gait"))
    if not gaits:
        pytest.skip("no .gait specs in specs/")
    for spec in gaits:
        onehot = main(["check", "--encoding", "onehot", spec])
        binary = main(["check", "--encoding", "binary", spec])
        assert onehot == binary and onehot in (0, 3), spec
    capsys.readouterr()


def test_help_documents_the_exit_codes(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["check", "--help"])
    text = capsys.readouterr().out
    assert "3  a spec is unrealizable" in text and "4  the solver could not finish" in text
