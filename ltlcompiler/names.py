"""Name handling for the checker: range expansion (``L1..L8``) and the one shared namespace.

Legs, gaits, regions and hazards share a namespace, because formulas refer to all
of them by bare name.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable

from gaitc.diagnostics import Span, SpecSemanticError
from ltlcompiler import syntax as s

MAX_RANGE = 10_000
MAX_NUMBER_DIGITS = 9  # in the number ending a range's names, as in other .gait numbers
_NUMBERED = re.compile(r"^(.*?)([0-9]+)$")  # ASCII digits: \d also takes '٣'


def _where(span: Span | None) -> str:
    return f"line {span.line}" if span is not None else "the built-in names"


def expand(item: s.NameItem) -> list[s.Name]:
    """The names an item stands for: itself, or every name of a range ``L1..L8``."""
    if isinstance(item, s.Name):
        return [item]
    first, last = item.first.text, item.last.text
    m1, m2 = _NUMBERED.match(first), _NUMBERED.match(last)
    if m1 is None or m2 is None or m1.group(1) != m2.group(1):
        raise SpecSemanticError(
            f"range {first}..{last} must run between two names with the same prefix and a "
            f"number, like L1..L8",
            item.span,
        )
    longest = max(len(m1.group(2)), len(m2.group(2)))
    if longest > MAX_NUMBER_DIGITS:
        raise SpecSemanticError(
            f"range {first[:20]}..{last[:20]}: a number of {longest} digits; the names of a "
            f"range end in numbers of at most {MAX_NUMBER_DIGITS} digits", item.span)
    low, high = int(m1.group(2)), int(m2.group(2))
    if low > high:
        raise SpecSemanticError(
            f"range {first}..{last} counts down; write {last}..{first}", item.span
        )
    if high - low >= MAX_RANGE:
        raise SpecSemanticError(
            f"range {first}..{last} has {high - low + 1} names; at most {MAX_RANGE} are allowed",
            item.span,
        )
    digits = m1.group(2)
    width = len(digits) if digits.startswith("0") and len(digits) > 1 else 0
    prefix = m1.group(1)
    return [s.Name(f"{prefix}{n:0{width}d}", span=item.span) for n in range(low, high + 1)]


def expand_all(items: Iterable[s.NameItem]) -> list[s.Name]:
    return [name for item in items for name in expand(item)]


def describe(names: Iterable[str], limit: int = 12) -> str:
    """``L1..L8`` for a consecutive run, otherwise a comma-separated list (shortened)."""
    parts: list[str] = []
    run: list[tuple[str, int, str]] = []

    def flush() -> None:
        if len(run) >= 3:
            parts.append(f"{run[0][2]}..{run[-1][2]}")
        else:
            parts.extend(r[2] for r in run)
        run.clear()

    for name in names:
        m = _NUMBERED.match(name)
        numbered = m is not None and len(m.group(2)) <= MAX_NUMBER_DIGITS
        key = (m.group(1), int(m.group(2)), name) if m and numbered else None
        if key and run and run[-1][0] == key[0] and run[-1][1] + 1 == key[1]:
            run.append(key)
            continue
        flush()
        if key:
            run.append(key)
        else:
            parts.append(name)
    flush()
    if not parts:
        return "(none)"
    if len(parts) > limit:
        return ", ".join(parts[:limit]) + f", ... ({len(parts) - limit} more)"
    return ", ".join(parts)


class Namespace:
    """Every declared name with its kind (leg, gait, region, hazard) and declaration span."""

    def __init__(self) -> None:
        self.kinds: dict[str, str] = {}
        self.spans: dict[str, Span | None] = {}

    def declare(self, name: s.Name, kind: str) -> None:
        old = self.kinds.get(name.text)
        if old is not None:
            first = _where(self.spans[name.text])
            if old == kind:
                raise SpecSemanticError(
                    f"{kind} '{name.text}' is declared twice (first at {first}); "
                    "remove one declaration",
                    name.span,
                )
            raise SpecSemanticError(
                f"'{name.text}' is already declared as a {old} (at {first}); legs, gaits, "
                "regions and hazards share one namespace, so rename one of them",
                name.span,
            )
        self.kinds[name.text] = kind
        self.spans[name.text] = name.span

    def of_kind(self, kind: str) -> list[str]:
        return [n for n, k in self.kinds.items() if k == kind]

    def require(self, name: s.Name, kind: str, context: str,
                valid: Iterable[str] | None = None) -> str:
        """``name`` if it is a ``kind``; otherwise an error naming what it is or could be:
        the declared names of ``kind`` that are ``valid`` in ``context`` (all by default)."""
        found = self.kinds.get(name.text)
        if found == kind:
            return name.text
        plural = {"hazard": "hazards"}.get(kind, kind + "s")
        if found is not None:
            raise SpecSemanticError(
                f"'{name.text}' {context} is a {found}, not a {kind}", name.span
            )
        known = self.of_kind(kind) if valid is None else list(valid)
        message = f"unknown {kind} '{name.text}' {context}; declared {plural} are {describe(known)}"
        close = difflib.get_close_matches(name.text, known, n=1)
        hint = f"did you mean '{close[0]}'?" if close else None
        raise SpecSemanticError(message, name.span, hint=hint)
