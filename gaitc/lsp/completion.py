"""Completion in context: the names and keywords the checker accepts where the cursor is.

The statement the cursor is in is found from the tokens before it (every statement starts
with its own keyword, and one continues onto the next line only after a comma or an
operator); within it, the last clause keyword says which place it is. :data:`CONTEXTS` is
the one table of places: for each (statement, clause) the function that lists what
:mod:`ltlcompiler.checker` accepts there. Regions are offered only where they are free
(a blocked cell is refused wherever a region is named), a name is not offered twice where
repeating it is an error (a leg of ``uses``, a cache, a goal, a region of a hazard set),
legs only after ``uses`` and ``with`` and inside ``health(...)``, gaits but never
``noGait`` after ``by``, and in a formula the names and words its place accepts (no leg
as a proposition, only hazards and health under ``next`` in an assumption).

The statement keywords, the directions and the formula keywords are read from the grammar
(:func:`ltlcompiler.parser.keywords`); the clause words are written here, and
``tests/lsp/test_lsp_keywords.py`` holds each of them to the grammar rule it is in.
"""

from __future__ import annotations

import contextlib
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from gaitc.diagnostics import GaitcError
from gaitc.lsp.index import Index, Kind
from ltlcompiler import syntax as s
from ltlcompiler.checker import METHODS
from ltlcompiler.model import NO_GAIT
from ltlcompiler.names import expand
from ltlcompiler.parser import keywords, statement_keywords

_TOKEN = re.compile(r'"[^"\n]*"?|#[^\n]*|[A-Za-z_][A-Za-z0-9_]*|[0-9]+|\.\.|<->|->|<=|>=|!=|\S')
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_CONTINUES = (",", "->", "<->", "..", ":", "=", "&", "|", "^", "!", "(", "<", ">", "<=",
              ">=", "!=")
_COMPARE = ("=", "!=", "<", "<=", ">", ">=")


@dataclass(frozen=True)
class Offer:
    """One completion: the text, what it is, a short detail."""

    label: str
    kind: str  # "keyword", "value" (a number, a method's name) or a Kind value
    detail: str = ""


#: Statement keywords that start the same statement as another (the table's key).
ALIASES = {"leg": "legs", "caches": "cache", "regions": "region"}

#: The clause words of each statement that start a new place in it (contextual, so written
#: by hand; each word is a keyword of its statement's rule in gait.lark).
CLAUSES = {
    "gait": ("uses", "moves", "valves", "primitive", "direction", "method"),
    "legs": ("health",),
    "grid": ("x", "cells"),
    "edge": ("->", "<->", "by"),
    "start": ("with",),
    "hazard": (":",),
    "visit": ("infinitely",),
}


@dataclass(frozen=True)
class Place:
    """Where the cursor is: its statement, the clause it is in and what is written there."""

    statement: str  # the statement keyword, an alias replaced (``caches`` is ``cache``)
    keyword: str  # the statement keyword as written (``correction`` for a correction gait)
    clause: str  # the last clause word before the cursor ("" for none)
    rest: tuple[str, ...]  # the tokens after the statement keyword
    after: tuple[str, ...]  # the tokens after the clause word (all of ``rest`` for none)
    lines: range  # the lines (1-based) from the statement keyword to the cursor
    index: Index | None

    @property
    def previous(self) -> str:
        return self.rest[-1] if self.rest else self.statement

    @property
    def wants_item(self) -> bool:
        """Whether an item of a list comes next: right after the clause or a comma, not
        inside a cell ``(row, col)``."""
        if self.after.count("(") > self.after.count(")"):
            return False
        return not self.after or self.after[-1] == ","

    def listed(self) -> set[str]:
        """The names written in this clause so far (a range ``L1..L3`` counts its names)."""
        out: set[str] = set()
        words = self.after
        for i, word in enumerate(words):
            if not _NAME.fullmatch(word):
                continue
            out.add(word)
            if i + 2 < len(words) and words[i + 1] == "..":
                with contextlib.suppress(GaitcError):  # a range the checker refuses
                    out.update(n.text for n in expand(s.NameRange(s.Name(word),
                                                                  s.Name(words[i + 2]))))
        return out


# ---------------------------------------------------------------------- the offers
def _keywords(*words: str) -> list[Offer]:
    return [Offer(word, "keyword") for word in words]


def _legs(place: Place, without: Iterable[str] = ()) -> list[Offer]:
    if place.index is None:
        return []
    skip = set(without)
    return [Offer(name, Kind.LEG.value, f"leg, health {place.index.health.get(name, '?')}")
            for name in place.index.of_kind(Kind.LEG) if name not in skip]


def _gaits(place: Place, without: Iterable[str] = (), no_gait: bool = False) -> list[Offer]:
    if place.index is None:
        return []
    skip = set(without)
    names = place.index.of_kind(Kind.GAIT) + ([NO_GAIT] if no_gait else [])
    return [Offer(name, Kind.GAIT.value, Kind.GAIT.value) for name in names if name not in skip]


def _regions(place: Place, without: Iterable[str] = ()) -> list[Offer]:
    """The free regions (blocked cells left out), but for ``without``."""
    if place.index is None:
        return []
    skip = set(without)
    return [Offer(name, Kind.REGION.value, Kind.REGION.value)
            for name in place.index.free_regions() if name not in skip]


def _hazards(place: Place) -> list[Offer]:
    if place.index is None:
        return []
    return [Offer(name, Kind.HAZARD.value, Kind.HAZARD.value)
            for name in place.index.of_kind(Kind.HAZARD)]


def _levels(place: Place, leg: str) -> list[Offer]:
    """The health levels ``1..h`` of ``leg``."""
    if place.index is None:
        return []
    health = place.index.health.get(leg)
    if health is None:
        return []
    return [Offer(str(level), "value", f"health level of {leg}")
            for level in range(1, health + 1)]


def _elsewhere(place: Place, role: str) -> set[str]:
    """The names with ``role`` in the other statements of the file."""
    return set() if place.index is None else place.index.named_as(role, place.lines)


def _nothing(place: Place) -> list[Offer]:
    del place
    return []


# ---------------------------------------------------------------------- each place
def _gait(place: Place) -> list[Offer]:
    if not place.rest:
        return []  # the new gait's name
    correction = place.keyword == "correction"  # it may not use legs
    return _keywords(*(w for w in ("uses", "moves", "valves", "primitive")
                       if w != "uses" or not correction))


def _uses(place: Place) -> list[Offer]:
    if place.wants_item:
        return _legs(place, without=place.listed())  # a leg listed twice is an error
    return _keywords("moves", "valves", "primitive")


def _moves(place: Place) -> list[Offer]:
    """``moves north, east`` or ``moves a -> b, b -> c``: one kind in one list."""
    directions = keywords("direction")
    written = place.after
    if written and written[-1] == "->":
        return _regions(place)
    if place.wants_item:
        if any(w in directions for w in written):
            return _keywords(*(d for d in directions if d not in written))
        if "->" in written:
            return _regions(place)
        return _keywords(*directions) + _regions(place)
    if (written and written[-1] in directions) or (len(written) >= 3 and written[-2] == "->"):
        return _keywords("valves", "primitive")
    return []


def _primitive(place: Place) -> list[Offer]:
    if place.after and place.after[-1].startswith('"'):
        return _keywords("direction", "method")
    return []


def _axis(place: Place) -> list[Offer]:
    return _keywords("method") if len(place.after) >= 2 else []


def _method(place: Place) -> list[Offer]:
    return [Offer(m, "value", "gait-graph method") for m in METHODS] if not place.after \
        else []


def _legs_decl(place: Place) -> list[Offer]:
    return [] if place.wants_item or place.after[-1] == ".." else _keywords("health")


def _grid(place: Place) -> list[Offer]:
    return _keywords("x") if len(place.after) == 1 else []


def _grid_x(place: Place) -> list[Offer]:
    return _keywords("cells") if len(place.after) == 1 else []


def _block(place: Place) -> list[Offer]:
    """Grid cells only (an explicit region cannot be blocked), not blocked already."""
    if not place.wants_item or place.index is None:
        return []
    skip = place.listed() | place.index.blocked
    return [Offer(name, Kind.REGION.value, "grid cell")
            for name in place.index.cells.values() if name not in skip]


def _edge(place: Place) -> list[Offer]:
    return _regions(place) if not place.rest else []


def _edge_target(place: Place) -> list[Offer]:
    if not place.after:
        return _regions(place)
    if len(place.after) == 1:
        return _keywords("by", *keywords("direction"))
    return []


def _edge_by(place: Place) -> list[Offer]:
    """Moving gaits: noGait keeps the robot in place and cannot label an edge."""
    return _gaits(place, without=place.listed()) if place.wants_item else []


def _cache(place: Place) -> list[Offer]:
    """Free regions that are not a cache already (twice is an error) nor in a hazard set
    (caches and hazards are disjoint)."""
    if not place.wants_item:
        return []
    taken = place.listed() | _elsewhere(place, "cache") | _elsewhere(place, "hazard")
    return _regions(place, without=taken)


def _hazard_regions(place: Place) -> list[Offer]:
    """Free regions not listed yet and no cache; after the list, its wear (when the
    grammar has graded hazards)."""
    if place.wants_item:
        return _regions(place, without=place.listed() | _elsewhere(place, "cache"))
    graded = "wears" in keywords("hazard_decl")
    return _keywords("wears") if graded and "wears" not in place.after else []


def _start(place: Place) -> list[Offer]:
    if not place.rest:
        return _regions(place)
    return _keywords("with") if len(place.rest) == 1 else []


def _with(place: Place) -> list[Offer]:
    """``with L1 = 2, L2 = 3``: legs, then the levels 1..h of the leg."""
    written = place.after
    if written and written[-1] == "=" and len(written) >= 2:
        return _levels(place, written[-2])
    if place.wants_item:
        given = {w for i, w in enumerate(written) if i + 1 < len(written)
                 and written[i + 1] == "="}
        return _legs(place, without=given)
    return []


def _visit(place: Place) -> list[Offer]:
    if place.wants_item:
        return _regions(place, without=place.listed() | _elsewhere(place, "goal"))
    return _keywords("infinitely")


def _often(place: Place) -> list[Offer]:
    return _keywords("often") if not place.after else []


def _formula(place: Place) -> list[Offer]:
    """A formula: ``always``/``eventually`` only as its prefix, ``next`` only after
    ``always`` and not inside another ``next``, bare names that are propositions (free
    regions, gaits, noGait, hazards), legs inside ``health(...)``/``failed(...)``, a
    leg's levels after a comparison; under ``next`` an assumption names only what the
    environment chooses."""
    rest = list(place.rest)
    prefix = 0
    while prefix < len(rest) and rest[prefix] in ("always", "eventually"):
        prefix += 1
    head, body = rest[:prefix], rest[prefix:]
    if not body:
        if not head:
            return _keywords("always") + _operand(place, next_ok=False, under_next=False)
        if head == ["always"]:
            return _keywords("eventually") + _operand(place, True, False)
        return _operand(place, next_ok=head == ["always", "eventually"], under_next=False)
    previous = body[-1]
    if len(body) >= 2 and previous == "(" and body[-2] in ("health", "failed"):
        return _legs(place)
    if len(body) >= 5 and previous in _COMPARE and body[-2] == ")" and body[-5] == "health":
        return _levels(place, body[-3])
    if previous in ("health", "failed") or (len(body) >= 3 and body[-3] in ("health",
                                                                          "failed")) \
            or (previous == ")" and len(body) >= 4 and body[-4] == "health"):
        return []  # "(", ")" or a comparison comes next
    if (_NAME.fullmatch(previous) and previous not in ("not", "next", "and", "or", "xor")) \
            or previous == ")" or previous.isdigit():
        return _keywords("and", "or", "xor")
    return _operand(place, next_ok=bool(head), under_next=_under_next(body))


def _operand(place: Place, next_ok: bool, under_next: bool) -> list[Offer]:
    assumption = place.statement == "assume"
    words = ["not", *(["next"] if next_ok and not under_next else []), "true", "false",
             "health", "failed"]
    if under_next and assumption:
        return _hazards(place) + _keywords(*words)
    return (_regions(place) + _gaits(place, no_gait=True) + _hazards(place)
            + _keywords(*words))


def _under_next(body: list[str]) -> bool:
    """Whether the cursor is inside the operand of a ``next`` (its unary, or the brackets
    that open it)."""
    pending = False  # a next whose operand has not started
    groups: list[bool] = []  # each open bracket: whether it is under a next
    for word in body:
        if word == "next":
            pending = True
        elif word in ("!", "not"):
            continue
        elif word == "(":
            groups.append(pending or (bool(groups) and groups[-1]))
            pending = False
        elif word == ")":
            if groups:
                groups.pop()
        elif _NAME.fullmatch(word) or word.isdigit():
            pending = False
    return pending or (bool(groups) and groups[-1])


#: The one table of places: (statement, clause word) to what the checker accepts there.
CONTEXTS: dict[tuple[str, str], Callable[[Place], list[Offer]]] = {
    ("robot", ""): _nothing,
    ("correction", ""): lambda place: [] if place.rest else _keywords("gait"),
    ("legs", ""): _legs_decl,
    ("legs", "health"): _nothing,
    ("gait", ""): _gait,
    ("gait", "uses"): _uses,
    ("gait", "moves"): _moves,
    ("gait", "valves"): _nothing,
    ("gait", "primitive"): _primitive,
    ("gait", "direction"): _axis,
    ("gait", "method"): _method,
    ("grid", ""): _grid,
    ("grid", "x"): _grid_x,
    ("grid", "cells"): _nothing,
    ("block", ""): _block,
    ("region", ""): _nothing,
    ("edge", ""): _edge,
    ("edge", "->"): _edge_target,
    ("edge", "<->"): _edge_target,
    ("edge", "by"): _edge_by,
    ("cache", ""): _cache,
    ("hazard", ""): _nothing,
    ("hazard", ":"): _hazard_regions,
    ("start", ""): _start,
    ("start", "with"): _with,
    ("visit", ""): _visit,
    ("visit", "infinitely"): _often,
    ("assume", ""): _formula,
    ("guarantee", ""): _formula,
}


def _tokens(text: str) -> list[tuple[str, int]]:
    """The tokens of ``text`` (comments left out), each with its offset."""
    return [(m.group(), m.start()) for m in _TOKEN.finditer(text)
            if not m.group().startswith("#")]


def place_of(before: str, index: Index | None) -> Place | None:
    """The place at the end of ``before`` (the document up to the cursor); None at the
    start of a statement."""
    tokens = _tokens(before)
    if tokens and re.fullmatch(r"\w+", tokens[-1][0]) and before.endswith(tokens[-1][0]):
        tokens = tokens[:-1]  # the word or number being typed
    words = [t for t, _ in tokens]
    previous = words[-1] if words else ""
    line_start = before.rsplit("\n", 1)[-1]
    at_line_start = re.fullmatch(r"\s*[A-Za-z_0-9]*", line_start) is not None
    statements = statement_keywords()
    if not words or (at_line_start and previous not in _CONTINUES):
        return None
    start = max((i for i, w in enumerate(words) if w in statements), default=-1)
    if start < 0:
        return None
    statement = ALIASES.get(words[start], words[start])
    keyword = "correction" if statement == "gait" and words[start - 1:start] == [
        "correction"] else words[start]
    rest = tuple(words[start + 1:])
    marks = [i for i, w in enumerate(rest) if w in CLAUSES.get(statement, ())]
    clause = rest[marks[-1]] if marks else ""
    after = rest[marks[-1] + 1:] if marks else rest
    first = before.count("\n", 0, tokens[start][1]) + 1
    return Place(statement, keyword, clause, rest, after,
                 range(first, before.count("\n") + 2), index)


def offers(before: str, index: Index | None) -> list[Offer]:
    """What may be typed at the end of ``before`` (the document up to the cursor)."""
    place = place_of(before, index)
    if place is None:
        return _keywords(*statement_keywords())
    handler = CONTEXTS.get((place.statement, place.clause), _nothing)
    return handler(place)
