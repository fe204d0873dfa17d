"""gaitc runs on Python 3.10 to 3.13: nothing newer than 3.10 is used, and the project says so.

The development machine runs a newer Python, so a 3.11 feature (``enum.StrEnum``,
``typing.Self``, ``tomllib``, ``ExceptionGroup``, ``except*``) imports fine here and breaks
only for a 3.10 user. vermin reads the sources statically and names the oldest Python each
construct needs; code behind a ``sys.version_info`` test counts for the versions it runs on.
mypy checks at ``python_version = "3.10"`` too (``pyproject.toml``), which catches the
typing side (a name a 3.10 stub lacks).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from packages import PACKAGES, ROOT

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

#: The oldest and the newest Python gaitc supports.
OLDEST, NEWEST = (3, 10), (3, 13)


def _vermin() -> str:
    local = Path(sys.executable).parent / "vermin"
    if local.exists():
        return str(local)
    found = shutil.which("vermin")
    if found is None:
        pytest.skip("vermin is not installed (pip install vermin, or scripts/setup.sh)")
    return found


def _pyproject() -> dict[str, object]:
    with (ROOT / "pyproject.toml").open("rb") as handle:
        return tomllib.load(handle)


def test_no_source_needs_more_than_the_oldest_python() -> None:
    """vermin finds nothing in the packages, the tests, the benchmarks and the tools that
    needs a Python newer than 3.10; a finding is reported as ``file:line: feature``."""
    folders = [p for p in [*PACKAGES, "tests", "bench", "tools"] if (ROOT / p).is_dir()]
    target = f"-t={OLDEST[0]}.{OLDEST[1]}-"
    result = subprocess.run(
        [_vermin(), target, "--violations", "--no-tips", "--eval-annotations",
         "--format", "parsable", *folders],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )
    # parsable lines: file:line:column:py2:py3:feature; the per-file and total verdict lines
    # have an empty line number and are left out
    findings = []
    for line in result.stdout.splitlines():
        parts = line.split(":", 5)
        if len(parts) == 6 and parts[0] and parts[1]:
            path, lineno, _column, _py2, py3, feature = parts
            findings.append(f"{Path(path).as_posix()}:{lineno}: {feature} needs Python {py3}")
    assert not findings, (
        f"code that Python {OLDEST[0]}.{OLDEST[1]} cannot run (use a version test or an "
        "older spelling):\n" + "\n".join(findings))
    assert result.returncode == 0, result.stdout + result.stderr


def test_vermin_sees_what_it_is_for(tmp_path: Path) -> None:
    """The check above is not vacuous: on 3.11 features vermin fails and names each line."""
    probe = tmp_path / "probe.py"
    probe.write_text(
        '"""A module that needs Python 3.11."""\n'
        "import enum\n"
        "import tomllib\n"
        "\n"
        "\n"
        "class Kind(enum.StrEnum):\n"
        '    A = "a"\n',
        encoding="utf-8",
    )
    result = subprocess.run(
        [_vermin(), "-t=3.10-", "--violations", "--no-tips", "--format", "parsable",
         str(probe)],
        capture_output=True, text=True, check=False,
    )
    assert result.returncode != 0
    assert ":3:" in result.stdout and "tomllib" in result.stdout
    assert ":6:" in result.stdout and "StrEnum" in result.stdout


def test_the_project_declares_the_versions_it_is_checked_for() -> None:
    """``requires-python``, the classifiers, mypy's and ruff's targets agree on 3.10-3.13."""
    config = _pyproject()
    project = config["project"]
    tool = config["tool"]
    assert isinstance(project, dict) and isinstance(tool, dict)
    oldest = f"{OLDEST[0]}.{OLDEST[1]}"
    assert project["requires-python"] == f">={oldest}"
    assert tool["mypy"]["python_version"] == oldest
    assert tool["ruff"]["target-version"] == f"py{OLDEST[0]}{OLDEST[1]}"
    declared = sorted(
        tuple(int(n) for n in m.group(1).split("."))
        for c in project["classifiers"]
        if (m := re.fullmatch(r"Programming Language :: Python :: (\d+\.\d+)", c)))
    wanted = [(3, minor) for minor in range(OLDEST[1], NEWEST[1] + 1)]
    assert declared == wanted, f"classifiers name Python {declared}, expected {wanted}"
