"""One module per group of subcommands; each defines ``register(subparsers)``.

``register`` adds its subcommands and sets ``run=<function(args) -> int>`` as the
parser default; the function returns an exit code (see :mod:`gaitc.cli`).
"""

from __future__ import annotations

from gaitc.cli.commands import (
    calibrating,
    characterizing,
    compiling,
    driving,
    examples,
    explaining,
    firmware,
    gaits,
    generating,
    learning,
    rendering,
    resilient,
    simulating,
    solving,
)

COMMAND_MODULES = (compiling, solving, explaining, resilient, simulating, rendering, gaits,
                   learning, driving, firmware, generating, calibrating, characterizing,
                   examples)
