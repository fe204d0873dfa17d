"""The test command: README.md's second command is what ``.ci/run`` runs, and its fast stage
(``scripts/check.sh``: ruff, mypy, the shape tests) stops the run with a clear message.

The failing tools are stand-ins in a scratch virtual environment (``VENV``), so these tests
say nothing about the code base itself; ``tests/codebase/test_quality.py`` does that.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from packages import ROOT


def _readme_commands() -> list[str]:
    """The commands of README.md's first lines (indented by four spaces)."""
    commands = []
    for line in (ROOT / "README.md").read_text(encoding="utf-8").splitlines():
        if line.startswith("    "):
            commands.append(line.strip())
        elif commands:
            break
    return commands


def test_ci_runs_exactly_the_readme_test_command() -> None:
    commands = _readme_commands()
    assert len(commands) == 2, commands
    ci = [line.strip() for line in (ROOT / ".ci" / "run").read_text(encoding="utf-8")
          .splitlines() if line.strip() and not line.lstrip().startswith("#")]
    assert ci[-1] == commands[1]
    assert commands[1] == "scripts/setup.sh && scripts/check.sh"


def _fake_venv(tmp_path: Path, ruff: int, mypy: int) -> Path:
    """A virtual environment whose ruff and mypy print a finding and exit with the codes
    given; its python is this one."""
    bin_dir = tmp_path / "venv" / "bin"
    bin_dir.mkdir(parents=True)
    for tool, code in (("ruff", ruff), ("mypy", mypy)):
        script = bin_dir / tool
        script.write_text(f"#!/bin/sh\necho '{tool} stand-in: x.py:1: a finding'\nexit {code}\n",
                          encoding="utf-8")
        script.chmod(0o755)
    (bin_dir / "python").symlink_to(sys.executable)
    return bin_dir.parent


def _check(venv: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        ["bash", str(ROOT / "scripts" / "check.sh")],
        env=dict(os.environ, VENV=str(venv), FAST_ONLY="1"),
        capture_output=True, text=True, check=False, timeout=120,
    )


@pytest.mark.parametrize(("ruff", "mypy", "stage"), [(1, 0, "ruff"), (0, 1, "mypy")])
def test_the_fast_stage_stops_the_run_naming_the_tool(
        tmp_path: Path, ruff: int, mypy: int, stage: str) -> None:
    result = _check(_fake_venv(tmp_path, ruff, mypy))
    assert result.returncode == 1
    assert f"check: FAILED at the fast stage: {stage} found" in result.stderr
    assert "the test suite was not run" in result.stderr
    assert f"{stage} stand-in: x.py:1: a finding" in result.stdout
    assert "check: layering" not in result.stderr  # nothing after the failing tool ran


def test_a_missing_tool_is_a_failure_not_a_skip(tmp_path: Path) -> None:
    venv = _fake_venv(tmp_path, 0, 0)
    (venv / "bin" / "mypy").unlink()
    result = _check(venv)
    assert result.returncode == 1
    assert "mypy is not installed" in result.stderr
