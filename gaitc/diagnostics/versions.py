"""The versions of the file formats gaitc writes, and the one check their readers make.

Each format that gaitc writes and reads back (explicit controllers, symbolic controllers,
runs) and each it writes for other tools (gaits files) carries an integer format version.
A reader accepts every version up to its own; a file from a newer gaitc gets a message that
says so and what to do, instead of a misleading complaint about some field further in.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final

from gaitc.diagnostics import GaitcError, Span

#: gaitc's own version (``gaitc.__version__``, ``gaitc --version``; pyproject.toml's, which
#: tests/cli/test_package.py checks). Caches made by another version are built again.
PACKAGE: Final = "0.1.0"


@dataclass(frozen=True)
class FileFormat:
    """One file format: what a user calls it and the newest version this gaitc writes."""

    name: str
    version: int

    def check(self, found: object, span: Span, error: type[GaitcError]) -> int:
        """``found``, the version a file declares, when this gaitc can read it; otherwise
        ``error`` with a message for a malformed, an unknown or a newer version."""
        if isinstance(found, bool) or not isinstance(found, int):
            raise error(f"the {self.name}'s format version must be an integer, not {found!r}",
                        span)
        if found > self.version:
            raise error(
                f"this {self.name} is format version {found}, written by a newer gaitc; this "
                f"gaitc reads versions up to {self.version}", span,
                hint="upgrade gaitc (pip install --upgrade gaitc), or write the file again "
                     "with this version")
        if found < 1:
            raise error(f"the {self.name}'s format version {found} does not exist "
                        f"(versions start at 1)", span)
        return found


#: The explicit controller JSON file (``gaitc.format``, docs/controller-format.md).
CONTROLLER: Final = FileFormat("controller file", 1)
#: The symbolic controller JSON file (``gaitc.version``, docs/controller-format.md).
SYMBOLIC_CONTROLLER: Final = FileFormat("symbolic controller file", 1)
#: A run written by ``simulate --out FILE.jsonl`` (the ``format`` of its ``run`` line).
RUN: Final = FileFormat("run file", 2)
#: A gaits file written by ``gaitc gaits -o FILE.json`` (its ``format`` key).
GAITS: Final = FileFormat("gaits file", 1)
