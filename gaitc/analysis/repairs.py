"""Repairs: edits of a ``.gait`` file that make an unrealizable spec realizable.

The edits are those a roboticist makes: raise one leg's health, raise every leg's health at
once, add a cache, unblock a cell, take a region out of a hazard set, add a gait on the legs
the play left healthy, assume a hazard set is off infinitely often, drop a ``guarantee``
line, and, last, drop a goal. When no single edit short of
dropping a goal works, pairs of the cheaper edits are tried (a cache and more health, a
fairness assumption and a cache...). Every candidate is an edit of the source text; the
edited text is parsed, checked, lowered and solved again, and only the edits that give a
realizable spec are kept, ranked by how little they change (cost, then the order above).
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Final

from gaitc.analysis.oracle import WORKERS, Oracle
from gaitc.diagnostics import GaitcError, source_lines
from gaitc.ir.formula import Var
from gaitc.ir.spec import GR1Spec
from ltlcompiler.encoding import EncodingName
from ltlcompiler.frontend import model_from_text
from ltlcompiler.lowering import lower
from ltlcompiler.model import Model

MAX_HEALTH_STEP = 2  # raise one leg by at most this many levels
MAX_ALL_HEALTH_STEP = 3  # raise every leg by at most this many levels
MAX_CACHE_CANDIDATES = 60
#: The most pairs of edits solved when no single edit works.
MAX_PAIRS: Final = 40
#: The single edits a pair is made of: the cheapest of each kind.
PAIR_POOL: Final = 12

#: The kinds of edit, in the order they are preferred at equal cost.
KINDS: Final = ("raise a leg's health", "raise every leg's health", "add a cache",
                "unblock a cell", "take a region out of a hazard set",
                "add a gait on healthy legs", "assume a hazard is off infinitely often",
                "drop a guarantee", "drop a goal")
UNBLOCK, NEW_GAIT = KINDS[3], KINDS[5]
GOAL_DROP: Final = KINDS[-1]


@dataclass(frozen=True)
class Repair:
    """An edit (``change``, as ``diff`` lines) and the edited source it was verified on."""

    change: str
    diff: tuple[str, ...]
    cost: int
    text: str
    verdict: str = "realizable"

    def to_json(self) -> dict[str, object]:
        return {"change": self.change, "diff": "\n".join(self.diff), "verdict": self.verdict,
                "cost": self.cost}


@dataclass(frozen=True)
class Repairs:
    """The repairs found, and the kinds of edit tried (to say so when none worked)."""

    found: tuple[Repair, ...]
    tried: tuple[str, ...]


@dataclass(frozen=True)
class _Edit:
    """Lines replaced (1-based line, its new lines; none: the line is deleted) and lines
    appended at the end of the file."""

    change: str
    cost: int
    kind: str
    replaced: tuple[tuple[int, tuple[str, ...]], ...] = ()
    appended: tuple[str, ...] = ()

    def lines(self) -> frozenset[int]:
        return frozenset(line for line, _ in self.replaced)

    def rank(self) -> tuple[int, int]:
        return self.cost, KINDS.index(self.kind)


def _apply(lines: list[str], edit: _Edit) -> tuple[str, tuple[str, ...]]:
    out = list(lines)
    diff: list[str] = []
    for line, new in sorted(edit.replaced, reverse=True):
        out[line - 1:line] = list(new)
    for line, new in sorted(edit.replaced):
        if new and new[0] == lines[line - 1]:  # lines added after an unchanged one
            diff += [f"+{n}" for n in new[1:]]
        else:
            diff += [f"-{lines[line - 1]}", *(f"+{n}" for n in new)]
    out += edit.appended
    diff += [f"+{n}" for n in edit.appended]
    return "\n".join(out) + "\n", tuple(diff)


def _joined(first: _Edit, second: _Edit) -> _Edit | None:
    """Both edits at once, or None where they touch the same line or are of one kind."""
    if first.kind == second.kind or first.lines() & second.lines():
        return None
    return _Edit(f"{first.change} and {second.change}", first.cost + second.cost,
                 max(first.kind, second.kind, key=KINDS.index),
                 first.replaced + second.replaced, first.appended + second.appended)


def _health_edits(model: Model, lines: list[str]) -> Iterator[_Edit]:
    for leg in model.legs:
        if leg.span is None:
            continue
        line = lines[leg.span.line - 1]
        found = re.search(r"\bhealth\s+(\d+)", line)
        if found is None:
            continue
        others = [x.name for x in model.legs
                  if x.span is not None and x.span.line == leg.span.line and x is not leg]
        indent = line[: len(line) - len(line.lstrip())]
        for step in range(1, MAX_HEALTH_STEP + 1):
            k = leg.health + step
            if not others:
                new: tuple[str, ...] = (line[: found.start(1)] + str(k) + line[found.end(1):],)
            else:
                keep = f"{indent}legs {', '.join(others)} health {leg.health}"
                new = (keep, f"{indent}leg {leg.name} health {k}")
            yield _Edit(f"raise leg {leg.name}'s health to {k}", step, KINDS[0],
                        ((leg.span.line, new),))


def _all_health_edits(model: Model, lines: list[str]) -> Iterator[_Edit]:
    """Every leg's health raised by the same step, on every line that declares legs."""
    declared = sorted({leg.span.line for leg in model.legs if leg.span is not None})
    if len(model.legs) < 2 or not declared:
        return
    for step in range(1, MAX_ALL_HEALTH_STEP + 1):
        replaced = []
        for number in declared:
            line = lines[number - 1]
            found = re.search(r"\bhealth\s+(\d+)", line)
            if found is None:
                return
            raised = str(int(found.group(1)) + step)
            replaced.append((number, (line[: found.start(1)] + raised + line[found.end(1):],)))
        levels = sorted({leg.health + step for leg in model.legs})
        what = (f"to {levels[0]}" if len(levels) == 1
                else f"by {step} level{'s' if step > 1 else ''}")
        yield _Edit(f"raise every leg's health {what}", step + 1, KINDS[1], tuple(replaced))


def _cache_edits(model: Model, visited: Sequence[str]) -> Iterator[_Edit]:
    hazardous = {r for h in model.hazards for r in h.regions}
    names = [r.name for r in model.regions]
    order = list(dict.fromkeys([*visited, *names]))
    candidates = [r for r in order if r not in model.caches and r not in hazardous]
    for region in candidates[:MAX_CACHE_CANDIDATES]:
        yield _Edit(f"add a cache at {region}", 1, KINDS[2], appended=(f"cache {region}",))


def _hazard_edits(model: Model, lines: list[str]) -> Iterator[_Edit]:
    for hazard in model.hazards:
        if hazard.span is None:
            continue
        line = lines[hazard.span.line - 1]
        head, sep, _ = line.partition(":")
        for region in hazard.regions:
            rest = [r for r in hazard.regions if r != region]
            new = (f"{head}{sep} {', '.join(rest)}",) if rest and sep else ()
            if not sep:
                continue
            yield _Edit(f"take {region} out of hazard set {hazard.name}", 1, KINDS[4],
                        ((hazard.span.line, new),))
        yield _Edit(f"assume hazard set {hazard.name} is off infinitely often", 2, KINDS[6],
                    appended=(f"assume always eventually !{hazard.name}",))


def _unblock_edits(lines: list[str]) -> Iterator[_Edit]:
    """Each blocked cell of a ``block`` line taken out of it (the line goes with its last)."""
    for number, line in enumerate(lines, 1):
        found = re.match(r"(\s*block\s+)([^#]*?)(\s*(#.*)?)$", line)
        if found is None:
            continue
        cells = [c.strip() for c in re.split(r",(?![^()]*\))", found.group(2)) if c.strip()]
        for cell in cells:
            rest = [c for c in cells if c != cell]
            new = (f"{found.group(1)}{', '.join(rest)}{found.group(3)}",) if rest else ()
            yield _Edit(f"unblock the cell {cell}", 1, UNBLOCK, ((number, new),))


def _gait_edits(model: Model, lines: list[str], failed: Sequence[str]) -> Iterator[_Edit]:
    """For each gait that uses a leg the play failed, the same moves on as many legs that
    did not fail (the first in declaration order), as a new gait after it."""
    used = {leg for g in model.gaits for leg in g.legs}
    healthy = sorted((leg.name for leg in model.legs if leg.name not in failed
                      and leg.health > 1), key=lambda name: name in used)  # spare legs first
    names = {g.name for g in model.gaits}
    for gait in model.gaits:
        if gait.span is None or not set(gait.legs) & set(failed):
            continue
        if len(healthy) < len(gait.legs) or set(gait.legs) <= set(healthy):
            continue
        line = lines[gait.span.line - 1]
        found = re.match(r"(\s*gait\s+)(\w+)(\s+uses\s+)(.*?)(\s+moves\b.*?)"
                         r"(\s+(valves|primitive)\b.*)?$", line)
        if found is None:
            continue
        new_name = next(f"{gait.name}_{k}" for k in range(2, 100)
                        if f"{gait.name}_{k}" not in names)
        legs = ", ".join(healthy[: len(gait.legs)])
        added = f"{found.group(1)}{new_name}{found.group(3)}{legs}{found.group(5)}"
        yield _Edit(f"add gait {new_name} on {legs}, moving as {gait.name} does", 2, NEW_GAIT,
                    ((gait.span.line, (line, added)),))


def _goal_edits(model: Model, lines: list[str]) -> Iterator[_Edit]:
    for goal in model.goals:
        if goal.span is None or not isinstance(goal.formula, Var):
            continue
        line = lines[goal.span.line - 1]
        same = [g.formula.name for g in model.goals if isinstance(g.formula, Var)
                and g.span is not None and g.span.line == goal.span.line]
        rest = [n for n in same if n != goal.formula.name]
        found = re.match(r"(\s*visit\s+).*?(\s+infinitely\s+often.*)$", line)
        if rest and found:
            new: tuple[str, ...] = (f"{found.group(1)}{', '.join(rest)}{found.group(2)}",)
        else:
            new = ()
        yield _Edit(f"drop the goal visit {goal.formula.name}", 5, GOAL_DROP,
                    ((goal.span.line, new),))
    for uf in model.guarantees:
        if uf.span is not None:
            yield _Edit(f"drop the guarantee on line {uf.span.line}", 3, KINDS[7],
                        ((uf.span.line, ()),))


def candidate_edits(model: Model, text: str, visited: Sequence[str],
                    failed: Sequence[str] = ()) -> list[_Edit]:
    """Every single edit tried, cheapest first (``visited`` regions get caches first; the
    legs ``failed`` in the play are replaced in new gaits)."""
    lines = source_lines(text)
    edits = [*_health_edits(model, lines), *_all_health_edits(model, lines),
             *_cache_edits(model, visited), *_unblock_edits(lines),
             *_hazard_edits(model, lines), *_gait_edits(model, lines, failed),
             *_goal_edits(model, lines)]
    return sorted(edits, key=_Edit.rank)


class _Search:
    """Solves edited variants of one source text, many at once (:meth:`Oracle.realizable_all`)."""

    def __init__(self, text: str, filename: str, encoding: EncodingName,
                 oracle: Oracle) -> None:
        self.lines = source_lines(text)
        self.filename, self.encoding, self.oracle = filename, encoding, oracle

    def working(self, edits: Sequence[_Edit]) -> list[tuple[_Edit, Repair]]:
        """The edits among ``edits`` that make the spec realizable, with their repairs."""
        ready: list[tuple[_Edit, str, tuple[str, ...], GR1Spec]] = []
        for edit in edits:
            edited, diff = _apply(self.lines, edit)
            try:
                variant, _ = model_from_text(edited, self.filename)
                ready.append((edit, edited, diff, lower(variant, self.encoding)))
            except GaitcError:
                continue  # the edit breaks the file (a name it removed is still used)
        answers = self.oracle.realizable_all([spec for *_, spec in ready])
        return [(edit, Repair(edit.change, diff, edit.cost, edited))
                for (edit, edited, diff, _), works in zip(ready, answers, strict=True) if works]


def repairs(model: Model, text: str, filename: str, encoding: EncodingName, oracle: Oracle,
            visited: Sequence[str], failed: Sequence[str] = ()) -> Repairs:
    """The verified repairs, ranked; for each leg only its least raise, and every leg's
    health only its least raise. When no single edit short of dropping a goal works, pairs
    of the cheaper edits (at most :data:`MAX_PAIRS`) are tried before the goal drops.

    Candidates are solved in rounds, each round at once: the single edits with the first
    step of every health raise, then the next step of the raises that did not work yet."""
    search = _Search(text, filename, encoding, oracle)
    candidates = candidate_edits(model, text, visited, failed)
    tried = [kind for kind in KINDS if any(e.kind == kind for e in candidates)]
    singles = [e for e in candidates if e.kind != GOAL_DROP]
    found: list[tuple[_Edit, Repair]] = []
    raised: set[str] = set()
    steps = sorted({_step(e) for e in singles})
    for step in steps:
        batch = [e for e in singles if _step(e) == step
                 and (_raised_subject(e) is None or _raised_subject(e) not in raised)]
        for edit, repair in search.working(batch):
            subject = _raised_subject(edit)
            if subject is not None:
                raised.add(subject)
            found.append((edit, repair))
    if not found:
        pairs = _pairs(singles)
        if pairs:
            tried.insert(len(tried) - (GOAL_DROP in tried), "two of these edits together")
        chunk = 2 * WORKERS
        for start in range(0, len(pairs), chunk):
            works = search.working(pairs[start:start + chunk])
            if works:  # the least pair: more would repeat it with extra edits
                found.append(min(works, key=lambda item: item[0].rank()))
                break
    found.sort(key=lambda item: item[0].rank())
    drops = search.working([e for e in candidates if e.kind == GOAL_DROP])
    return Repairs(tuple(r for _, r in [*found, *drops]), tuple(tried))


def _step(edit: _Edit) -> int:
    """The round an edit is solved in: a health raise by k levels in round k, others in 1."""
    if edit.kind == KINDS[0]:
        return edit.cost
    return edit.cost - 1 if edit.kind == KINDS[1] else 1


def _raised_subject(edit: _Edit) -> str | None:
    """The leg a health raise raises (``*`` for every leg), to keep only its least raise."""
    if edit.kind == KINDS[1]:
        return "*"
    leg = re.match(r"raise leg (\S+)'s", edit.change)
    return leg.group(1) if leg is not None and edit.kind == KINDS[0] else None


def _pairs(singles: list[_Edit]) -> list[_Edit]:
    """The cheapest pairs of edits of different kinds, cheapest first, at most
    :data:`MAX_PAIRS`; each kind contributes its :data:`PAIR_POOL` cheapest edits."""
    pool: list[_Edit] = []
    for kind in KINDS[:-1]:
        pool += [e for e in singles if e.kind == kind][:PAIR_POOL]
    joined = [j for a, b in itertools.combinations(pool, 2) if (j := _joined(a, b)) is not None]
    return sorted(joined, key=_Edit.rank)[:MAX_PAIRS]
