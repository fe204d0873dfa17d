"""The command-line shell: usage errors, user errors and internal errors get exit codes, no
tracebacks."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.cli.exitcodes import ExitCode


def test_no_command_prints_help_and_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main([]) == 2
    assert "usage: gaitc" in capsys.readouterr().err


def test_unknown_option_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["compile", "x.gait", "--format", "xml"]) == 2
    assert capsys.readouterr().err.startswith("gaitc: usage error: argument --format")


def test_user_error_is_rendered_with_location(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    spec = tmp_path / "bad.gait"
    spec.write_text("legs L1 health 0\n", encoding="utf-8")
    assert main(["lint", str(spec)]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"{spec}:1:")
    assert "Traceback" not in err


def test_internal_error_is_reported_without_traceback(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    def broken(_args: object) -> int:
        raise RuntimeError("boom")

    from gaitc.cli.commands import compiling

    monkeypatch.setattr(compiling, "run_lint", broken)
    monkeypatch.delenv("GAITC_DEBUG", raising=False)
    assert main(["lint", "whatever.gait"]) == ExitCode.INTERNAL
    err = capsys.readouterr().err
    assert "internal error: RuntimeError: boom" in err and "Traceback" not in err
