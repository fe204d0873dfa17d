"""gaitc runs on Python 3.11 to 3.13: nothing newer than 3.11 is used, and the project says so.

3.10 is not declared: the CUDD binding gaitc's solver stands on, ``dd`` 0.6 with its
``dd.cudd`` wheels, needs 3.11 (on 3.10 the package index has only ``dd`` 0.5.7, whose
``dd.cudd`` must be built from CUDD's sources, which pip cannot fetch), so ``pip install``
failed there (issue 61).  A newer feature (a 3.12 ``typing.override``, ``itertools.batched``)
imports fine on the development machine and breaks only for a 3.11 user; vermin reads the
sources statically and names the oldest Python each construct needs, and mypy checks at
``python_version = "3.11"`` (``pyproject.toml``).  tests/cli/test_package.py installs the
wheel on every declared version this machine has, in a fresh environment, and runs it.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from packages import PACKAGES, ROOT

#: The oldest and the newest Python gaitc supports.
OLDEST, NEWEST = (3, 11), (3, 13)


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
    needs a Python newer than 3.11; a finding is reported as ``file:line: feature``."""
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
    """The check above is not vacuous: on 3.12 features vermin fails and names each line."""
    probe = tmp_path / "probe.py"
    probe.write_text(
        '"""A module that needs Python 3.12."""\n'
        "import itertools\n"
        "from typing import override\n"
        "\n"
        "\n"
        "pairs = list(itertools.batched('abcd', 2))\n",
        encoding="utf-8",
    )
    result = subprocess.run(
        [_vermin(), "-t=3.11-", "--violations", "--no-tips", "--format", "parsable",
         str(probe)],
        capture_output=True, text=True, check=False,
    )
    assert result.returncode != 0
    assert ":3:" in result.stdout and "override" in result.stdout
    assert ":6:" in result.stdout and "batched" in result.stdout


def test_the_project_declares_the_versions_it_is_checked_for() -> None:
    """``requires-python``, the classifiers, mypy's and ruff's targets agree on 3.11-3.13."""
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
