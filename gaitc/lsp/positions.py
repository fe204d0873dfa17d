"""Positions between the compiler and the protocol.

gaitc's spans count lines and columns from 1, in characters, with an inclusive end
(:class:`gaitc.diagnostics.Span`); the Language Server Protocol counts from 0, in UTF-16
code units by default, with an exclusive end. A span without an end covers the word at its
start (a name, a number), or one character.
"""

from __future__ import annotations

import re

from lsprotocol import types

from gaitc.diagnostics import Span, source_lines

_WORD = re.compile(r"[A-Za-z0-9_]+")


class Lines:
    """The lines of a document, for converting positions both ways."""

    def __init__(self, text: str) -> None:
        self.lines = source_lines(text)

    def line(self, index: int) -> str:
        return self.lines[index] if 0 <= index < len(self.lines) else ""

    def units(self, line: int, column: int) -> int:
        """UTF-16 units before 0-based character ``column`` of 0-based ``line``."""
        text = self.line(line)[:max(0, column)]
        return sum(2 if ord(ch) > 0xFFFF else 1 for ch in text)

    def column(self, line: int, units: int) -> int:
        """The 0-based character column at ``units`` UTF-16 units into 0-based ``line``."""
        count = 0
        for i, ch in enumerate(self.line(line)):
            if count >= units:
                return i
            count += 2 if ord(ch) > 0xFFFF else 1
        return len(self.line(line))

    def position(self, line: int, column: int) -> types.Position:
        """The protocol position of 0-based ``line`` and character ``column``."""
        return types.Position(line=max(0, line), character=self.units(line, column))

    def span_range(self, span: Span | None) -> types.Range:
        """The protocol range of ``span`` (the first character of the file for None)."""
        if span is None:
            return types.Range(start=self.position(0, 0), end=self.position(0, 0))
        line, column = span.line - 1, span.column - 1
        if span.end_line is not None and span.end_column is not None:
            end_line, end_column = span.end_line - 1, span.end_column
        else:
            word = _WORD.match(self.line(line), max(0, column))
            end_line = line
            end_column = word.end() if word is not None and word.start() == column \
                else column + 1
        return types.Range(start=self.position(line, column),
                           end=self.position(end_line, end_column))

    def at(self, position: types.Position) -> tuple[int, int, str]:
        """The 1-based line and column of a protocol position, and the word under it."""
        line = position.line
        column = self.column(line, position.character)
        text = self.line(line)
        word = ""
        for match in _WORD.finditer(text):
            if match.start() <= column <= match.end():
                word = match.group()
                break
        return line + 1, column + 1, word
