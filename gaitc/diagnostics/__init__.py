"""diagnostics: the bottom layer, user-facing errors and warnings with source spans.

Every stage of gaitc (the .gait front end, the SLUGS format readers, the solver,
the simulator) raises subclasses of :class:`GaitcError`; the CLI turns them into
``file:line:col: message`` followed by the source line and a caret. :mod:`gaitc.diagnostics.files`
writes result files atomically; :mod:`gaitc.diagnostics.yamltext` reads YAML inputs safely;
:mod:`gaitc.diagnostics.usercache` keeps plain data in the user's private cache folder.
Every package may import this one; it imports none of them.
"""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Final


@dataclass(frozen=True)
class Span:
    """A region of a source file; lines and columns count from 1, ``end_*`` is inclusive."""

    file: str
    line: int
    column: int
    end_line: int | None = None
    end_column: int | None = None

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


class GaitcError(Exception):
    """Base of every error a user can cause; ``span`` locates it when known."""

    kind = "error"

    def __init__(self, message: str, span: Span | None = None, hint: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.span = span
        self.hint = hint

    def __str__(self) -> str:
        where = f"{self.span}: " if self.span is not None else ""
        return f"{where}{self.message}"

    def to_json(self) -> dict[str, Any]:
        """``{type, file, line, column, message, hint}``, null where unknown (docs/json.md)."""
        span = self.span
        return {"type": type(self).__name__,
                "file": None if span is None else span.file,
                "line": None if span is None else span.line,
                "column": None if span is None else span.column,
                "message": self.message, "hint": self.hint}


class SpecSyntaxError(GaitcError, ValueError):
    """A .gait file does not parse."""


class SpecSemanticError(GaitcError, ValueError):
    """A .gait file parses but says something inconsistent (unknown name, bad range, ...)."""


class FormulaError(GaitcError, ValueError):
    """A formula is malformed or lies outside the GR(1) fragment."""


class SlugsFormatError(GaitcError, ValueError):
    """A .slugsin or .structuredslugs file is malformed."""


class PeerFormatError(GaitcError, ValueError):
    """A spec cannot be written for a peer GR(1) solver (gr1c's .spc, omega's automaton):
    its liveness mixes current and next values, or a comparison has too many values."""


class ControllerError(GaitcError, ValueError):
    """A controller file is malformed or does not belong to the given specification."""


class SolverError(GaitcError, RuntimeError):
    """Synthesis could not finish (timeout, memory limit, missing or failing SLUGS binary)."""


class ScenarioError(GaitcError, ValueError):
    """A simulation scenario is malformed or asks for a step the assumptions forbid."""


class RatesError(GaitcError, ValueError):
    """A rates file (``gaitc chances --rates``) is malformed: an unknown leg, gait or hazard,
    a chance outside [0, 1], chances that add up to more than 1."""


class UsageError(GaitcError, ValueError):
    """A call asks for something that cannot be done: a bad option or argument value (the
    command line's exit code 2)."""


class FileAccessError(UsageError, OSError):
    """An input cannot be read or an output cannot be written (an :class:`OSError` too)."""

    def __init__(self, message: str, filename: str | Path | None = None) -> None:
        super().__init__(message)
        self.filename = None if filename is None else str(filename)


class MissingFileError(FileAccessError, FileNotFoundError):
    """An input file does not exist (a :class:`FileNotFoundError` too)."""


#: The byte order mark some editors (on Windows) put before UTF-8 text.
BOM: Final = "\ufeff"


def without_bom(text: str) -> str:
    """``text`` without a leading byte order mark: every reader and the error printer skip
    it, so line 1 and its columns start after it."""
    return text.removeprefix(BOM)


def source_lines(text: str) -> list[str]:
    """The lines of a source text as every reader and the error printer count them: only
    ``\\n`` ends a line (a ``\\r`` before it is dropped), so a form feed, ``\\x1c``, ``\\x85``
    or U+2028 inside a line never shifts the line shown under a caret."""
    lines = text.split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    return [line[:-1] if line.endswith("\r") else line for line in lines]


def span_at(text: str, file: str, offset: int) -> Span:
    """The span of character ``offset`` of ``text`` by the rule of :func:`source_lines`.

    An offset at the very end (a reader that ran out of text after the last ``\n``)
    points just past the end of the last line, which exists, rather than at a line after it.
    For many offsets of one text, :class:`LineTable` gives the same spans in linear time.
    """
    return LineTable(text, file).span(offset)


class LineTable:
    """:func:`span_at` for many offsets of one text: the line ends are found once, and each
    offset's line by bisection (a YAML file's every node is positioned this way)."""

    def __init__(self, text: str, file: str) -> None:
        self.text, self.file = text, file
        self.ends = [m.start() for m in re.finditer("\n", text)]

    def span(self, offset: int) -> Span:
        """The span of character ``offset`` (see :func:`span_at`)."""
        text = self.text
        offset = max(0, min(offset, len(text)))
        if offset == len(text) and text.endswith("\n"):
            offset -= 2 if text.endswith("\r\n") else 1
        line = bisect.bisect_left(self.ends, offset)  # newlines before the offset
        start = self.ends[line - 1] + 1 if line else 0
        column = offset - start + 1
        if column > 1 and text[offset - 1] == "\r" and text[offset:offset + 1] in ("\n", ""):
            column -= 1  # the \r that source_lines drops before a \n
        return Span(self.file, line + 1, column)


@dataclass(frozen=True)
class Diagnostic:
    """A non-fatal finding (a warning), reported with the same layout as errors."""

    message: str
    span: Span | None = None
    severity: str = "warning"
    hint: str | None = None


def _source_line(span: Span, sources: dict[str, str] | None) -> str | None:
    text: str | None = None
    if sources is not None and span.file in sources:
        text = sources[span.file]
    else:
        try:
            # bytes, not read_text: universal newlines would make a lone \r end a line
            text = Path(span.file).read_bytes().decode("utf-8", errors="replace")
        except OSError:
            return None
    lines = source_lines(without_bom(text))
    if 1 <= span.line <= len(lines):
        return lines[span.line - 1]
    return None


def render(
    message: str,
    span: Span | None,
    severity: str = "error",
    hint: str | None = None,
    sources: dict[str, str] | None = None,
) -> str:
    """Format a message as ``file:line:col: severity: message``, source line and caret.

    A line break inside the message or the hint (from a value quoted out of the input) is
    shown as ``\\n``, so the message stays one line and the source line follows it.
    """
    message = message.replace("\r", "\\r").replace("\n", "\\n")
    hint = hint.replace("\r", "\\r").replace("\n", "\\n") if hint else hint
    if span is None:
        out = [f"gaitc: {severity}: {message}"]
    else:
        out = [f"{span}: {severity}: {message}"]
        line = _source_line(span, sources)
        if line is not None:
            col = max(span.column, 1)
            width = 1
            if span.end_line == span.line and span.end_column is not None:
                width = max(1, span.end_column - col + 1)
            width = min(width, max(1, len(line) - col + 1))
            line, col, width = _excerpt(line, col, width)
            out.append(f"    {_printable(line)}")
            out.append("    " + " " * (col - 1) + "^" * width)
    if hint:
        out.append(f"  hint: {hint}")
    return "\n".join(out)


#: The longest source line an error shows whole; a longer one (a controller file written
#: on one line, a minified map) is cut to a window around the column, marked with "...".
EXCERPT = 100


def _excerpt(line: str, col: int, width: int) -> tuple[str, int, int]:
    """``line`` cut to at most :data:`EXCERPT` characters around column ``col`` (1-based),
    with the column and the caret's width within the cut."""
    if len(line) <= EXCERPT:
        return line, col, width
    room = EXCERPT - 6  # the two "..." marks
    width = min(width, room // 2)
    start = max(0, min(col - 1 - room // 3, len(line) - room))
    cut = line[start:start + room]
    head = "..." if start > 0 else ""
    tail = "..." if start + room < len(line) else ""
    return head + cut + tail, col - start + len(head), width


def _printable(line: str) -> str:
    """``line`` as the terminal may show it: a tab as a space, and every other control
    character (ESC, BEL, C1 codes) as ``?``, one column each, so that a file cannot send
    escape sequences to the terminal and the caret below still lines up."""
    return "".join(" " if c == "\t" else "?" if ord(c) < 32 or 0x7F <= ord(c) < 0xA0 else c
                   for c in line)


def render_error(err: GaitcError, sources: dict[str, str] | None = None) -> str:
    """Format a :class:`GaitcError` for the terminal."""
    return render(err.message, err.span, "error", err.hint, sources)


def render_diagnostic(diag: Diagnostic, sources: dict[str, str] | None = None) -> str:
    """Format a :class:`Diagnostic` for the terminal."""
    return render(diag.message, diag.span, diag.severity, diag.hint, sources)
