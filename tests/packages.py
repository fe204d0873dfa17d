"""The project's packages, read from the one list in ``pyproject.toml``.

The layering and quality tests walk exactly these, so a package added to the project is
checked as soon as it is installed.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def top_level_packages() -> list[str]:
    """The top-level packages the wheel installs (``[tool.setuptools.packages.find]``)."""
    with (ROOT / "pyproject.toml").open("rb") as handle:
        config = tomllib.load(handle)
    patterns = config["tool"]["setuptools"]["packages"]["find"]["include"]
    return [pattern.rstrip("*").rstrip(".") for pattern in patterns]


def subpackages() -> list[str]:
    """Every package directory under the top-level packages, as dotted names."""
    found = []
    for top in top_level_packages():
        for init in sorted((ROOT / top).rglob("__init__.py")):
            found.append(".".join(init.parent.relative_to(ROOT).parts))
    return found


PACKAGES = top_level_packages()
