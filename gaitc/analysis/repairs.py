"""Repairs: single edits of a ``.gait`` file that make an unrealizable spec realizable.

Each candidate is an edit of the source text (raise a leg's health, add a cache, take a
region out of a hazard set, assume a hazard set is off infinitely often, drop a goal or a
``guarantee`` line); the edited text is parsed, checked, lowered and solved again, and only
the edits that give a realizable spec are kept, cheapest first.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from gaitc.analysis.oracle import Oracle
from gaitc.diagnostics import GaitcError, source_lines
from gaitc.ir.formula import Var
from ltlcompiler.encoding import EncodingName
from ltlcompiler.frontend import model_from_text
from ltlcompiler.lowering import lower
from ltlcompiler.model import Model

MAX_HEALTH_STEP = 2  # raise a leg by at most this many levels
MAX_CACHE_CANDIDATES = 60


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
class _Edit:
    change: str
    cost: int
    line: int | None  # 1-based line replaced (None: lines appended at the end)
    new: tuple[str, ...]  # replacement lines (empty: the line is deleted)


def _apply(lines: list[str], edit: _Edit) -> tuple[str, tuple[str, ...]]:
    if edit.line is None:
        text = "\n".join([*lines, *edit.new]) + "\n"
        return text, tuple(f"+{n}" for n in edit.new)
    index = edit.line - 1
    out = [*lines[:index], *edit.new, *lines[index + 1:]]
    return "\n".join(out) + "\n", (f"-{lines[index]}", *(f"+{n}" for n in edit.new))


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
            yield _Edit(f"raise leg {leg.name}'s health to {k}", step, leg.span.line, new)


def _cache_edits(model: Model, visited: list[str]) -> Iterator[_Edit]:
    hazardous = {r for h in model.hazards for r in h.regions}
    names = [r.name for r in model.regions]
    order = list(dict.fromkeys([*visited, *names]))
    candidates = [r for r in order if r not in model.caches and r not in hazardous]
    for region in candidates[:MAX_CACHE_CANDIDATES]:
        yield _Edit(f"add a cache at {region}", 1, None, (f"cache {region}",))


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
            yield _Edit(f"take {region} out of hazard set {hazard.name}", 1,
                        hazard.span.line, new)
        yield _Edit(f"assume hazard set {hazard.name} is off infinitely often", 2, None,
                    (f"assume always eventually !{hazard.name}",))


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
        yield _Edit(f"drop the goal visit {goal.formula.name}", 4, goal.span.line, new)
    for uf in model.guarantees:
        if uf.span is not None:
            yield _Edit(f"drop the guarantee on line {uf.span.line}", 3, uf.span.line, ())


def candidate_edits(model: Model, text: str, visited: list[str]) -> list[_Edit]:
    """Every single edit tried, cheapest first (``visited`` regions get caches first)."""
    lines = source_lines(text)
    edits = [*_health_edits(model, lines), *_cache_edits(model, visited),
             *_hazard_edits(model, lines), *_goal_edits(model, lines)]
    return sorted(edits, key=lambda e: e.cost)


def repairs(model: Model, text: str, filename: str, encoding: EncodingName, oracle: Oracle,
            visited: list[str]) -> tuple[Repair, ...]:
    """The verified single-edit repairs, cheapest first; for each leg only its least raise."""
    lines = source_lines(text)
    found: list[Repair] = []
    raised: set[str] = set()
    for edit in candidate_edits(model, text, visited):
        leg = re.match(r"raise leg (\S+)'s", edit.change)
        if leg is not None and leg.group(1) in raised:
            continue
        edited, diff = _apply(lines, edit)
        try:
            variant, _ = model_from_text(edited, filename)
            realizable = oracle.realizable(lower(variant, encoding))
        except GaitcError:
            continue  # the edit breaks the file (a name it removed is still used)
        if realizable:
            if leg is not None:
                raised.add(leg.group(1))
            found.append(Repair(edit.change, diff, edit.cost, edited))
    return tuple(found)
