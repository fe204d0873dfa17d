"""One module per group of subcommands; each defines ``register(subparsers)``.

``register`` adds its subcommands and sets ``run=<function(args) -> int>`` as the
parser default; the function returns an exit code (see :mod:`gaitc.cli`).

:data:`COMMANDS` names the module of every subcommand without importing it, so that the
command line imports only the module of the command it runs (and that module imports the
library it needs when it runs): ``gaitc --version`` or ``gaitc lint`` do not load the
solver, numpy or networkx.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Final

#: Every subcommand and the module (of this package) that registers it, in the order
#: ``gaitc --help`` lists them.
COMMANDS: Final = {
    "lint": "compiling",
    "compile": "compiling",
    "check": "deciding",
    "synth": "solving",
    "counter": "solving",
    "verify": "solving",
    "explain": "explaining",
    "resilience": "resilient",
    "chances": "chances",
    "simulate": "simulating",
    "play": "playing",
    "render": "rendering",
    "gaits": "gaits",
    "learn": "learning",
    "drive": "driving",
    "ros": "ros",
    "firmware": "firmware",
    "codegen": "generating",
    "calibrate": "calibrating",
    "characterize": "characterizing",
    "examples": "examples",
    "lsp": "editing",
}


def command_module(command: str) -> ModuleType:
    """The module that registers ``command`` (one of :data:`COMMANDS`)."""
    return importlib.import_module(f"{__name__}.{COMMANDS[command]}")


def all_modules() -> list[ModuleType]:
    """Every command module, each once, in the order of :data:`COMMANDS`."""
    return [importlib.import_module(f"{__name__}.{name}")
            for name in dict.fromkeys(COMMANDS.values())]
