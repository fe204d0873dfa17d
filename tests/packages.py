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


def checked_packages() -> list[str]:
    """The wheel's packages and those the checkout keeps for bench/ and tests/ only
    (``[tool.gaitc] checked-only``): what the layering and quality tests walk."""
    with (ROOT / "pyproject.toml").open("rb") as handle:
        config = tomllib.load(handle)
    return top_level_packages() + list(config["tool"]["gaitc"]["checked-only"])


def subpackages() -> list[str]:
    """Every package directory under the top-level packages, as dotted names."""
    found = []
    for top in checked_packages():
        for init in sorted((ROOT / top).rglob("__init__.py")):
            found.append(".".join(init.parent.relative_to(ROOT).parts))
    return found


PACKAGES = checked_packages()
WHEEL_PACKAGES = top_level_packages()
