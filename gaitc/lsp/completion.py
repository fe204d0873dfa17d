"""Completion in context: the names and keywords that can come next where the cursor is.

The statement the cursor is in is found from the tokens before it (every statement starts
with its own keyword, and one continues onto the next line only after a comma or an
operator); within it, the last clause keyword says what is expected: legs after ``uses``,
regions after ``cache``, ``visit``, ``start`` or a hazard's colon, gaits after ``by``,
any name and the formula keywords after ``assume`` and ``guarantee``.

The statement keywords, the directions and the formula keywords are read from the grammar
(:func:`ltlcompiler.parser.keywords`); the words that may follow each clause are written
here, and ``tests/lsp/test_lsp_keywords.py`` holds each of them to the grammar rule it is in.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from gaitc.lsp.index import Index, Kind
from ltlcompiler.parser import keywords, statement_keywords

_TOKEN = re.compile(r'"[^"\n]*"?|#[^\n]*|[A-Za-z_][A-Za-z0-9_]*|\.\.|<->|->|\S')
_CONTINUES = (",", "->", "<->", "..", ":", "=", "&", "|", "^", "!", "(")


@dataclass(frozen=True)
class Offer:
    """One completion: the text, what it is, a short detail."""

    label: str
    kind: str  # "keyword" or a Kind value
    detail: str = ""


def _tokens(text: str) -> list[str]:
    return [t for t in _TOKEN.findall(text) if not t.startswith("#")]


def _names(index: Index | None, kind: Kind) -> list[Offer]:
    if index is None:
        return []
    return [Offer(name, kind.value, kind.value) for name in index.of_kind(kind)]


def _keywords(*words: str) -> list[Offer]:
    return [Offer(word, "keyword") for word in words]


def offers(before: str, index: Index | None) -> list[Offer]:
    """What may be typed at the end of ``before`` (the document up to the cursor)."""
    line_start = before.rsplit("\n", 1)[-1]
    tokens = _tokens(before)
    if tokens and re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", tokens[-1]) and \
            before.endswith(tokens[-1]):
        tokens = tokens[:-1]  # the word being typed
    previous = tokens[-1] if tokens else ""
    at_line_start = re.fullmatch(r"\s*[A-Za-z_0-9]*", line_start) is not None
    statements = statement_keywords()
    if not tokens or (at_line_start and previous not in _CONTINUES):
        return _keywords(*statements)
    start = max((i for i, t in enumerate(tokens) if t in statements), default=-1)
    if start < 0:
        return _keywords(*statements)
    statement, rest = tokens[start], tokens[start + 1:]
    if statement == "correction":
        statement = "gait"
    clause = next((t for t in reversed(rest) if t in CLAUSES.get(statement, ())), "")
    return _in(statement, clause, rest, previous, index)


#: The clause keywords of each statement that say what comes after them (contextual, so
#: written by hand; each is a keyword of its statement's rule in gait.lark).
CLAUSES = {
    "gait": ("uses", "moves", "valves", "primitive"),
    "legs": ("health",), "leg": ("health",),
    "grid": ("cells",),
    "edge": ("by",),
    "start": ("with",),
    "hazard": (":",),
}


def _in(statement: str, clause: str, rest: list[str], previous: str,
        index: Index | None) -> list[Offer]:
    regions = _names(index, Kind.REGION)
    if statement == "gait":
        if not rest:
            return []  # the new gait's name
        if clause == "uses":
            return _names(index, Kind.LEG) + _keywords("moves", "valves", "primitive")
        if clause == "moves":
            return (_keywords(*keywords("direction")) + regions
                    + _keywords("valves", "primitive"))
        if clause == "primitive":
            return _keywords("direction", "method")
        if clause == "valves":
            return []
        return _keywords("uses", "moves", "valves", "primitive")
    if statement in ("legs", "leg"):
        return [] if clause == "health" else _keywords("health")
    if statement == "grid":
        return [] if clause == "cells" else _keywords("x", "cells")
    if statement in ("cache", "caches", "block"):
        return regions
    if statement == "visit":
        return regions + _keywords("infinitely", "often")
    if statement == "start":
        if clause == "with":
            return _names(index, Kind.LEG)
        return regions if not rest else _keywords("with")
    if statement == "hazard":
        return regions if clause == ":" else []
    if statement == "edge":
        if clause == "by":
            return _names(index, Kind.GAIT)
        arrows = [i for i, t in enumerate(rest) if t in ("->", "<->")]
        if arrows and len(rest) > arrows[0] + 1 and previous not in ("->", "<->"):
            return _keywords("by", *keywords("direction"))
        return regions
    if statement in ("assume", "guarantee"):
        names: list[Offer] = []
        for kind in Kind:
            names += _names(index, kind)
        if previous == "(" and len(rest) >= 2 and rest[-2] in ("health", "failed"):
            return _names(index, Kind.LEG)
        return names + _keywords(*keywords("formula"))
    return []
