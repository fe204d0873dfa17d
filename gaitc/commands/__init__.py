"""One module per group of subcommands; each defines ``register(subparsers)``.

``register`` adds its subcommands and sets ``run=<function(args) -> int>`` as the
parser default; the function returns an exit code (see :mod:`gaitc.cli`).
"""

from __future__ import annotations

import importlib
from types import ModuleType

_NAMES = ("compiling", "solving", "simulating", "rendering", "gaits")


def _load() -> list[ModuleType]:
    modules = []
    for name in _NAMES:
        try:
            modules.append(importlib.import_module(f"gaitc.commands.{name}"))
        except ModuleNotFoundError as err:
            if err.name != f"gaitc.commands.{name}":
                raise
    return modules


COMMAND_MODULES = _load()
