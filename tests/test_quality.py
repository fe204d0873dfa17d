"""The code base stays ruff- and mypy-clean (the style guide's rule 6)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ["gaitc", "ltlcompiler", "slugs_bridge", "gaitgraph", "gaitsim", "gaithw"]


def _tool(name: str) -> list[str]:
    local = Path(sys.executable).parent / name
    if local.exists():
        return [str(local)]
    found = shutil.which(name)
    if found is None:
        pytest.skip(f"{name} is not installed")
    return [found]


def test_ruff_clean() -> None:
    result = subprocess.run(
        [*_tool("ruff"), "check", *PACKAGES, "tests", "bench"],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_mypy_clean() -> None:
    result = subprocess.run(
        [*_tool("mypy"), *[p for p in PACKAGES if (ROOT / p).is_dir()]],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_every_module_has_a_docstring_and_stays_small() -> None:
    problems = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            text = path.read_text(encoding="utf-8")
            if not text.lstrip().startswith(('"""', "'''")):
                problems.append(f"{path.relative_to(ROOT)}: no module docstring")
            if text.count("\n") > 500:
                problems.append(f"{path.relative_to(ROOT)}: {text.count(chr(10))} lines")
    assert not problems, "\n".join(problems)


def test_slugs_bridge_never_imports_the_front_end() -> None:
    offenders = []
    for path in sorted((ROOT / "slugs_bridge").rglob("*.py")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            stripped = line.strip()
            if stripped.startswith(("import ", "from ")) and (
                "ltlcompiler" in stripped or "gaitc" in stripped.split()[1]
            ):
                offenders.append(f"{path.relative_to(ROOT)}:{number}: {stripped}")
    assert not offenders, "\n".join(offenders)


def test_lark_stays_in_the_parser() -> None:
    offenders = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            if path.name == "parser.py" and path.parent.name == "ltlcompiler":
                continue
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if line.strip().startswith(("import lark", "from lark")):
                    offenders.append(f"{path.relative_to(ROOT)}:{number}")
    assert not offenders, "\n".join(offenders)
