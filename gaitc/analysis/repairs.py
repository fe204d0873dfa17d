"""Repairs: edits of a ``.gait`` file that make an unrealizable spec realizable.

The edits are those a roboticist makes by hand: raise one leg's health, raise every working
leg's health to one level, add a cache, unblock a cell, take a region out of a hazard set,
let a hazard wear the legs (``wears k``) rather than fail them, add a gait on the legs the
play left healthy, assume a hazard set is off infinitely often,
drop a ``guarantee`` line, and, last, drop a goal.

* Health is searched exactly, not by a fixed number of steps: the least level of each leg
  (the others as declared) comes from one parametric game per leg over every level up to
  the language's limit, the leg's cap a rigid parameter (:mod:`gaitc.analysis.parametric`,
  the game ``gaitc resilience`` uses); the least uniform level by bisection, since a level
  that suffices stays sufficient above it.
* When no single edit short of dropping a goal works, pairs are tried, within a kind (two
  caches, two unblocked cells, two cells out of hazard sets) and across kinds (a cache and
  more health...), cheapest first.
* Every edit keeps the declared order of legs, gaits and regions: a leg raised out of a
  ``legs A1..A5`` line takes its own line where it stood (the valve digits, the code
  generator's fields and every table keep their columns); a cache joins the ``cache`` line.

Every candidate is an edit of the source text; the edited text is parsed, checked, lowered
and solved again, and only the edits that give a realizable spec are kept, ranked by how
little they change (cost, then the order above). What each kind searched is kept
(:attr:`Repairs.searched`) so that "no repair found" says how far the search went.
"""

from __future__ import annotations

import functools
import itertools
import math
import re
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Final

from gaitc.analysis.oracle import WORKERS, Oracle
from gaitc.analysis.parametric import winning_caps
from gaitc.analysis.variants import with_health
from gaitc.diagnostics import GaitcError, SolverError, source_lines
from gaitc.ir.formula import Var
from gaitc.ir.roles import graded_levels
from gaitc.ir.spec import GR1Spec
from ltlcompiler.checker import MAX_HEALTH
from ltlcompiler.encoding import EncodingName
from ltlcompiler.frontend import model_from_text
from ltlcompiler.lowering import lower
from ltlcompiler.model import Leg, Model

#: Health raises offered in pairs with another edit: one leg by up to this many levels,
#: every leg by up to this many (the exact single raises come from the parametric game).
PAIR_HEALTH_STEP: Final = 2
PAIR_ALL_HEALTH_STEP: Final = 3
#: Cache sites tried alone, in the order of :func:`_cache_sites`.
MAX_CACHE_CANDIDATES: Final = 60
#: Cache sites (the first in that order) whose pairs are tried: at most 276 pairs.
PAIR_CACHE_SITES: Final = 24
#: Pairs of one kind (cells unblocked, cells out of hazard sets) tried, cheapest first.
MAX_KIND_PAIRS: Final = 300
#: Pairs of edits of two kinds: each kind contributes its :data:`PAIR_POOL` cheapest edits.
MAX_MIXED_PAIRS: Final = 60
PAIR_POOL: Final = 12
#: Health vectors (the product of the legs' levels) a game of the health search may have:
#: a refutation runs a fixpoint iteration per level, so robot A (8 legs) uniformly at 9
#: levels took 50 s to refute; at 3^12, the bound of ``gaitc resilience``'s front, it
#: stops at 5. Deterministic, unlike a time budget, so the answers do not depend on load.
HEALTH_VECTORS: Final = 3 ** 12
#: A solve of the health search past this many seconds stops it there (a guard only).
SOLVE_GUARD_SECONDS: Final = 60.0
#: Working pairs kept (the cheapest) once some pair works.
KEPT_PAIRS: Final = 3

#: The kinds of edit, in the order they are preferred at equal cost.
KINDS: Final = ("raise a leg's health", "raise every leg's health", "add a cache",
                "unblock a cell", "take a region out of a hazard set",
                "let a hazard wear the legs less", "add a gait on healthy legs",
                "assume a hazard is off infinitely often", "drop a guarantee", "drop a goal")
LEG_RAISE, ALL_RAISE, CACHE, UNBLOCK, HAZARD_CELL, HAZARD_WEAR, NEW_GAIT, FAIRNESS, \
    GUARANTEE_DROP, GOAL_DROP = KINDS
#: What the pairs are called among the kinds searched.
PAIRS: Final = "two of these edits together"
HEALTH_PAIRS: Final = "another edit with the least health it needs"
#: The other edits tried with a health raise (one solve each, every leg at the limit).
HEALTH_PAIR_POOL: Final = 24


@dataclass(frozen=True)
class Repair:
    """An edit (``change``, as ``diff`` lines) and the edited source it was verified on."""

    change: str
    diff: tuple[str, ...]
    cost: int
    text: str
    verdict: str = "realizable"
    kind: str = ""

    def to_json(self) -> dict[str, object]:
        return {"change": self.change, "diff": "\n".join(self.diff), "verdict": self.verdict,
                "cost": self.cost, "kind": self.kind}


@dataclass(frozen=True)
class Repairs:
    """The repairs found; the kinds of edit tried, and what each searched (kind, limits in
    words), to say how far the search went when none worked."""

    found: tuple[Repair, ...]
    tried: tuple[str, ...]
    searched: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class _Edit:
    """Lines replaced (1-based line, its new lines; none: the line is deleted) and lines
    appended at the end of the file. ``subject``: the leg a health raise raises (``*``
    for every leg), the cache site, the cell..., to pair edits of one kind."""

    change: str
    cost: int
    kind: str
    replaced: tuple[tuple[int, tuple[str, ...]], ...] = ()
    appended: tuple[str, ...] = ()
    subject: str = ""

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
        old = lines[line - 1]
        if old in new:  # lines added around an unchanged one
            diff += [f"+{n}" for n in new if n != old]
        else:
            diff += [f"-{old}", *(f"+{n}" for n in new)]
    out += edit.appended
    diff += [f"+{n}" for n in edit.appended]
    return "\n".join(out) + "\n", tuple(diff)


# ------------------------------------------------------------------ the source's statements

_NUMBERED = re.compile(r"^(.*?)(\d+)$")


def name_list(names: Sequence[str]) -> str:
    """``names`` as a ``.gait`` list, runs of consecutive numbered names as ranges
    (``A1..A3, B``); a run keeps its numbers' width, as the language's ranges do."""
    parts: list[str] = []
    run: list[str] = []

    def close() -> None:
        if len(run) > 2:
            parts.append(f"{run[0]}..{run[-1]}")
        else:
            parts.extend(run)
        run.clear()

    for name in names:
        if run:
            a, b = _NUMBERED.match(run[-1]), _NUMBERED.match(name)
            if a is None or b is None or a.group(1) != b.group(1) \
                    or len(a.group(2)) != len(b.group(2)) \
                    or int(b.group(2)) != int(a.group(2)) + 1:
                close()
        run.append(name)
    close()
    return ", ".join(parts)


def _split(line: str) -> tuple[str, str]:
    """A line's statement and its comment (with the spaces before it)."""
    found = re.match(r"^(.*?)(\s*#.*)?$", line)
    assert found is not None
    return found.group(1), found.group(2) or ""


def _legs_on_line(model: Model, leg: Leg) -> list[Leg]:
    assert leg.span is not None
    return [x for x in model.legs if x.span is not None and x.span.line == leg.span.line]


def _leg_lines(model: Model, lines: list[str], leg: Leg, level: int) -> tuple[str, ...] | None:
    """The lines that declare ``leg`` at ``level`` where it stood: a leg raised out of a
    ``legs`` line takes a line of its own between the legs before and after it, so the
    declared order (valve digits, code fields, table columns) does not change."""
    if leg.span is None:
        return None
    line = lines[leg.span.line - 1]
    statement, comment = _split(line)
    found = re.search(r"\bhealth\s+(\d+)", statement)
    if found is None or not re.match(r"\s*legs?\b", statement):
        return None
    group = _legs_on_line(model, leg)
    if group == [leg]:
        return (statement[: found.start(1)] + str(level) + statement[found.end(1):]
                + comment,)
    indent = statement[: len(statement) - len(statement.lstrip())]
    tail = statement[found.end(1):]  # anything after the number (nothing, usually)
    at = group.index(leg)
    parts = [(group[:at], leg.health), ([leg], level), (group[at + 1:], leg.health)]
    out = [f"{indent}{'legs' if len(part) > 1 else 'leg'} {name_list([x.name for x in part])}"
           f" health {h}{tail}" for part, h in parts if part]
    out[0] += comment
    return tuple(out)


def _cache_line(model: Model, lines: list[str]) -> tuple[int, str, str] | None:
    """The one-line ``cache`` statement new caches join (line, statement, comment)."""
    spans = [s for s in model.cache_spans if s is not None]
    if not spans:
        return None
    number = spans[-1].line
    statement, comment = _split(lines[number - 1])
    if not re.match(r"\s*caches?\s+\w", statement) or statement.rstrip().endswith(","):
        return None
    return number, statement.rstrip(), comment


# ------------------------------------------------------------------ the kinds of edit


def _pair_health_edits(model: Model, lines: list[str]) -> Iterator[_Edit]:
    """Small health raises (one leg, every working leg) to pair with other edits."""
    for leg in model.legs:
        for step in range(1, PAIR_HEALTH_STEP + 1):
            new = _leg_lines(model, lines, leg, leg.health + step)
            if new is not None and leg.span is not None:
                yield _Edit(f"raise leg {leg.name}'s health to {leg.health + step}", step,
                            LEG_RAISE, ((leg.span.line, new),), subject=leg.name)
    working = [leg.health for leg in model.legs if leg.health > 1]
    for step in range(1, PAIR_ALL_HEALTH_STEP + 1):
        if working:
            edit = _all_health_edit(model, lines, min(working) + step, step + 1)
            if edit is not None:
                yield edit


def _all_health_edit(model: Model, lines: list[str], level: int, cost: int) -> _Edit | None:
    """Every working leg (health above 1) below ``level`` raised to it, line by line."""
    declared = sorted({leg.span.line for leg in model.legs
                       if leg.span is not None and 1 < leg.health < level})
    if len([leg for leg in model.legs if leg.health > 1]) < 2 or not declared:
        return None
    replaced = []
    for number in declared:
        statement, comment = _split(lines[number - 1])
        found = re.search(r"\bhealth\s+(\d+)", statement)
        if found is None:
            return None
        replaced.append((number, (statement[: found.start(1)] + str(level)
                                  + statement[found.end(1):] + comment,)))
    raised = [leg.name for leg in model.legs if 1 < leg.health < level]
    if len(raised) < len([leg for leg in model.legs if leg.health > 1]):
        # the others have the level already: the label names the legs the edit raises
        what = (f"raise legs {name_list(raised)} to health {level} (the other working "
                f"legs have {level} or more)")
    else:
        failed = any(leg.health == 1 for leg in model.legs)
        what = f"raise {'every working leg' if failed else 'every leg'}'s health to {level}"
    return _Edit(what, cost, ALL_RAISE, tuple(replaced), subject="*")


def _cache_sites(model: Model, visited: Sequence[str]) -> list[str]:
    """Regions a cache may be added in (no cache or hazard there yet): the goals' regions
    and those the play visited first, then the others in declaration order."""
    hazardous = {r for h in model.hazards for r in h.regions}
    goals = [g.formula.name for g in model.goals if isinstance(g.formula, Var)]
    order = list(dict.fromkeys([*goals, *visited, *(r.name for r in model.regions)]))
    regions = {r.name for r in model.regions}
    return [r for r in order if r in regions and r not in model.caches and r not in hazardous]


def _cache_edit(model: Model, lines: list[str], sites: Sequence[str]) -> _Edit:
    """New caches at ``sites``, on the ``cache`` line when there is one."""
    where = _cache_line(model, lines)
    what = (f"add a cache at {sites[0]}" if len(sites) == 1
            else f"add caches at {' and '.join(sites)}")
    if where is None:
        return _Edit(what, len(sites), CACHE, appended=(f"cache {', '.join(sites)}",),
                     subject=",".join(sites))
    number, statement, comment = where
    return _Edit(what, len(sites), CACHE,
                 ((number, (f"{statement}, {', '.join(sites)}{comment}",)),),
                 subject=",".join(sites))


_BLOCK = re.compile(r"(\s*block\s+)([^#]*?)(\s*(#.*)?)$")


def _blocked_cells(lines: list[str]) -> list[tuple[int, str]]:
    """(line, cell as written) of every cell of the ``block`` lines."""
    out = []
    for number, line in enumerate(lines, 1):
        found = _BLOCK.match(line)
        if found is not None:
            out += [(number, c.strip()) for c in re.split(r",(?![^()]*\))", found.group(2))
                    if c.strip()]
    return out


def _unblock_edit(lines: list[str], cells: Sequence[tuple[int, str]]) -> _Edit:
    """The ``cells`` taken out of their ``block`` lines (a line goes with its last cell)."""
    replaced = []
    for number in sorted({n for n, _ in cells}):
        found = _BLOCK.match(lines[number - 1])
        assert found is not None
        gone = {c for n, c in cells if n == number}
        rest = [c.strip() for c in re.split(r",(?![^()]*\))", found.group(2))
                if c.strip() and c.strip() not in gone]
        replaced.append((number, (f"{found.group(1)}{', '.join(rest)}{found.group(3)}",)
                         if rest else ()))
    names = [c for _, c in cells]
    what = (f"unblock the cell {names[0]}" if len(names) == 1
            else f"unblock the cells {' and '.join(names)}")
    return _Edit(what, len(names), UNBLOCK, tuple(replaced), subject=",".join(names))


_HAZARD = re.compile(r"(\s*hazard\s+\w+\s*:\s*)([^#]*?)(\s+wears\s+\d+)?(\s*(#.*)?)$")


def _hazard_cells(model: Model, lines: list[str]) -> list[tuple[str, str]]:
    """(hazard set, region) of every hazard cell whose set is declared on one line."""
    out = []
    for hazard in model.hazards:
        if hazard.span is not None and _HAZARD.match(lines[hazard.span.line - 1]):
            out += [(hazard.name, r) for r in hazard.regions]
    return out


def _hazard_cell_edit(model: Model, lines: list[str], cells: Sequence[tuple[str, str]]
                      ) -> _Edit | None:
    """The ``cells`` taken out of their hazard sets (a set left with no region goes, with
    its line: the edited text is checked, so a formula that names it keeps it)."""
    replaced = []
    for hazard in model.hazards:
        gone = {r for h, r in cells if h == hazard.name}
        if not gone:
            continue
        rest = [r for r in hazard.regions if r not in gone]
        found = _HAZARD.match(lines[hazard.span.line - 1]) if hazard.span else None
        if found is None or hazard.span is None:
            return None
        replaced.append((hazard.span.line, (f"{found.group(1)}{', '.join(rest)}"
                                            f"{found.group(3) or ''}{found.group(4)}",)
                         if rest else ()))
    what = " and ".join(f"take {r} out of hazard set {h}" for h, r in cells)
    return _Edit(what, len(cells), HAZARD_CELL, tuple(replaced),
                 subject=",".join(f"{h}.{r}" for h, r in cells))


def _wear_edit(model: Model, lines: list[str], hazard: str, wears: int) -> _Edit | None:
    """Hazard set ``hazard`` made to wear the legs by up to ``wears`` levels (``wears k``,
    a graded hazard) instead of failing them or wearing them more."""
    found_hazard = next(h for h in model.hazards if h.name == hazard)
    if found_hazard.span is None:
        return None
    found = _HAZARD.match(lines[found_hazard.span.line - 1])
    if found is None:
        return None
    new = f"{found.group(1)}{found.group(2)} wears {wears}{found.group(4)}"
    harm = found_hazard.harm
    levels = graded_levels(harm)
    was = "failing them" if levels is None else f"by {levels}"
    return _Edit(f"let hazard set {hazard} wear the legs by up to {wears} "
                 f"level{'s' if wears > 1 else ''} instead of {was}", 1, HAZARD_WEAR,
                 ((found_hazard.span.line, (new,)),), subject=hazard)


def _wear_edits(model: Model, search: _Search, plan: _Plan) -> list[_Edit]:
    """For each hazard set, the most wear (``wears k``) it may keep and the task still be
    realizable, found by bisection (less wear never hurts the robot): a hazard that fails
    the legs is tried at ``wears`` 2 .. h - 2 (h the most levels a leg has; from h - 1 on,
    wearing is as bad as failing for the robot), a graded one below its own wear. ``wears
    1`` is never offered: it is the normal wear of a move, so the hazard would do nothing
    (the checker warns of it); taking its regions out says that plainly."""
    top_health = max(leg.health for leg in model.legs)
    edits: list[_Edit] = []
    for hazard in model.hazards:
        levels = graded_levels(hazard.harm)
        high = top_health - 2 if levels is None else levels - 1
        if high < 2:
            continue

        def works(k: int, name: str = hazard.name) -> bool:
            edit = _wear_edit(model, search.lines, name, k)
            made = search.variant(edit) if edit is not None else None
            return made is not None and search.oracle.realizable(made[2])

        if not works(2):
            continue
        low = 2  # works
        while low < high:
            middle = (low + high + 1) // 2
            if works(middle):
                low = middle
            else:
                high = middle - 1
        edit = _wear_edit(model, search.lines, hazard.name, low)
        if edit is not None:
            edits.append(edit)
    if model.hazards:
        plan.searched[HAZARD_WEAR] = ("for each hazard set, the most wear (wears k) that "
                                      "still works (exact, by bisection)")
    return edits


def _fairness_edits(model: Model) -> Iterator[_Edit]:
    for hazard in model.hazards:
        yield _Edit(f"assume hazard set {hazard.name} is off infinitely often", 2, FAIRNESS,
                    appended=(f"assume always eventually !{hazard.name}",),
                    subject=hazard.name)


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
        statement, _ = _split(line)  # the gait's comment is about the gait, not the new one
        found = re.match(r"(\s*gait\s+)(\w+)(\s+uses\s+)(.*?)(\s+moves\b.*?)"
                         r"(\s+(valves|primitive)\b.*)?$", statement.rstrip())
        if found is None:
            continue
        new_name = next(f"{gait.name}_{k}" for k in range(2, 100)
                        if f"{gait.name}_{k}" not in names)
        order = {leg.name: i for i, leg in enumerate(model.legs)}
        legs = ", ".join(sorted(healthy[: len(gait.legs)], key=order.__getitem__))
        added = f"{found.group(1)}{new_name}{found.group(3)}{legs}{found.group(5)}"
        yield _Edit(f"add gait {new_name} on {legs}, moving as {gait.name} does", 2, NEW_GAIT,
                    ((gait.span.line, (line, added)),), subject=new_name)


def _drop_edits(model: Model, lines: list[str]) -> Iterator[_Edit]:
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
                    ((goal.span.line, new),), subject=goal.formula.name)
    for uf in model.guarantees:
        if uf.span is not None:
            yield _Edit(f"drop the guarantee on line {uf.span.line}", 3, GUARANTEE_DROP,
                        ((uf.span.line, ()),), subject=str(uf.span.line))


@dataclass
class _Plan:
    """The single edits (health apart), the pairs, and what each kind searches."""

    singles: list[_Edit] = field(default_factory=list)
    pairs: list[_Edit] = field(default_factory=list)
    searched: dict[str, str] = field(default_factory=dict)


def _plan(model: Model, text: str, visited: Sequence[str], failed: Sequence[str]) -> _Plan:
    lines = source_lines(text)
    plan = _Plan()
    sites = _cache_sites(model, visited)
    plan.singles += [_cache_edit(model, lines, [s]) for s in sites[:MAX_CACHE_CANDIDATES]]
    if sites:
        plan.searched[CACHE] = (f"each of the {min(len(sites), MAX_CACHE_CANDIDATES)} regions "
                                "with no cache or hazard"
                                + (f" (of {len(sites)})" if len(sites) > MAX_CACHE_CANDIDATES
                                   else ""))
    blocked = _blocked_cells(lines)
    plan.singles += [_unblock_edit(lines, [c]) for c in blocked]
    if blocked:
        plan.searched[UNBLOCK] = f"each of the {len(blocked)} blocked cells"
    cells = _hazard_cells(model, lines)
    plan.singles += [e for c in cells if (e := _hazard_cell_edit(model, lines, [c]))]
    if cells:
        plan.searched[HAZARD_CELL] = f"each of the {len(cells)} cells of hazard sets"
    gaits = list(_gait_edits(model, lines, failed))
    plan.singles += gaits
    if gaits:
        plan.searched[NEW_GAIT] = (f"{len(gaits)} copies of the gaits using legs the play "
                                   "failed, on legs that did not fail")
    fair = list(_fairness_edits(model))
    plan.singles += fair
    if fair:
        plan.searched[FAIRNESS] = f"each of the {len(fair)} hazard sets"
    drops = list(_drop_edits(model, lines))
    plan.singles += drops
    if any(e.kind == GUARANTEE_DROP for e in drops):
        plan.searched[GUARANTEE_DROP] = "each guarantee line"
    if any(e.kind == GOAL_DROP for e in drops):
        plan.searched[GOAL_DROP] = "each goal alone"
    # pairs of one kind
    same: list[_Edit] = []
    cache_pairs = list(itertools.combinations(sites[:PAIR_CACHE_SITES], 2))
    same += [_cache_edit(model, lines, list(p)) for p in cache_pairs]
    if cache_pairs:
        plan.searched[CACHE] += (f"; every pair of the first {min(len(sites), PAIR_CACHE_SITES)}"
                                 f" ({len(cache_pairs)} pairs)")
    block_pairs = list(itertools.combinations(blocked, 2))[:MAX_KIND_PAIRS]
    same += [_unblock_edit(lines, list(p)) for p in block_pairs]
    if block_pairs:
        plan.searched[UNBLOCK] += f"; {len(block_pairs)} pairs of them"
    hazard_pairs = list(itertools.combinations(cells, 2))[:MAX_KIND_PAIRS]
    same += [e for p in hazard_pairs if (e := _hazard_cell_edit(model, lines, list(p)))]
    if hazard_pairs:
        plan.searched[HAZARD_CELL] += f"; {len(hazard_pairs)} pairs of them"
    # pairs of two kinds, small health raises among them
    pool: list[_Edit] = []
    small_raises = list(_pair_health_edits(model, lines))
    for kind in KINDS[:-1]:
        pool += [e for e in [*small_raises, *plan.singles] if e.kind == kind][:PAIR_POOL]
    mixed = sorted((j for a, b in itertools.combinations(pool, 2)
                    if (j := _joined(a, b)) is not None), key=_Edit.rank)[:MAX_MIXED_PAIRS]
    plan.pairs = sorted([*same, *mixed], key=_Edit.rank)
    if plan.pairs:
        plan.searched[PAIRS] = (f"{len(same)} pairs of one kind and the {len(mixed)} cheapest "
                                "pairs of two kinds")
    return plan


def _joined(first: _Edit, second: _Edit) -> _Edit | None:
    """Both edits at once, or None where they are of one kind (pairs of one kind are made
    by their kinds) or touch the same line."""
    if first.kind == second.kind or first.lines() & second.lines():
        return None
    return _Edit(f"{first.change} and {second.change}", first.cost + second.cost,
                 max(first.kind, second.kind, key=KINDS.index),
                 first.replaced + second.replaced, first.appended + second.appended)


class _Search:
    """Solves edited variants of one source text, many at once (:meth:`Oracle.realizable_all`)."""

    def __init__(self, text: str, filename: str, encoding: EncodingName,
                 oracle: Oracle) -> None:
        self.lines = source_lines(text)
        self.filename, self.encoding, self.oracle = filename, encoding, oracle

    def variant(self, edit: _Edit, encoding: EncodingName | None = None
                ) -> tuple[str, tuple[str, ...], GR1Spec] | None:
        edited, diff = _apply(self.lines, edit)
        try:
            model, _ = model_from_text(edited, self.filename)
            return edited, diff, lower(model, encoding or self.encoding)
        except GaitcError:
            return None  # the edit breaks the file (a name it removed is still used)

    @functools.cache  # noqa: B019 (one search a spec; edits are hashable values)
    def edited_model(self, edit: _Edit) -> Model | None:
        """The checked model of the source with ``edit`` made (None: the edit breaks it),
        parsed once however many health searches start from it."""
        try:
            return model_from_text(_apply(self.lines, edit)[0], self.filename)[0]
        except GaitcError:
            return None

    def working(self, edits: Sequence[_Edit]) -> list[tuple[_Edit, Repair]]:
        """The edits among ``edits`` that make the spec realizable, with their repairs."""
        ready = [(edit, *made) for edit in edits if (made := self.variant(edit)) is not None]
        answers = self.oracle.realizable_all([spec for *_, spec in ready])
        return [(edit, Repair(edit.change, diff, edit.cost, edited, kind=edit.kind))
                for (edit, edited, diff, _), works in zip(ready, answers, strict=True) if works]


# ------------------------------------------------------------------ exact health


def _raised(model: Model, levels: dict[str, int]) -> GR1Spec:
    """``model`` with the given legs' health raised, lowered on the binary encoding (the
    verdict does not depend on the encoding; the binary one grows by bits, not levels)."""
    return lower(with_health(model, levels), EncodingName.BINARY)


@dataclass
class _Levels:
    """Least sufficient levels found, the highest level the search went to, and whether a
    solve passed :data:`SOLVE_GUARD_SECONDS` and stopped it there."""

    found: dict[str, int]
    reached: int
    stopped: bool = False


def _vector_top(model: Model, raised: Sequence[str], top: int) -> int:
    """The highest common level of the legs ``raised`` (the others as declared) with at most
    :data:`HEALTH_VECTORS` health vectors in the game, and at most ``top``: a deterministic
    limit on the cost of a refutation, which runs a fixpoint iteration per level."""
    others = math.prod(leg.health for leg in model.legs if leg.name not in raised)
    level = top
    while level > 1 and level ** len(raised) * others > HEALTH_VECTORS:
        level -= 1
    return level


def _doubling(oracle: Oracle, starts: dict[str, int], tops: dict[str, int],
              variant: Callable[[str, int], GR1Spec]) -> tuple[dict[str, tuple[int, int]], int,
                                                                bool]:
    """Brackets (last level that fails, first that works) for each key of ``starts``
    (its known-failing level), raising by 1, 2, 4... up to its top: one round of solves at
    a time, all keys at once. Also the highest level solved, and whether a solve passed
    :data:`SOLVE_GUARD_SECONDS` (a guard: the tops keep games small) and stopped the search."""
    low = {k: v for k, v in starts.items() if v < tops[k]}
    brackets: dict[str, tuple[int, int]] = {}
    step = 1
    reached = max(tops.values(), default=0)
    while low:
        round_ = {k: min(v + step, tops[k]) for k, v in low.items()}
        limit = time.monotonic() + SOLVE_GUARD_SECONDS
        probe = Oracle(oracle.semantics, limit if oracle.deadline is None
                       else min(limit, oracle.deadline), _options=oracle._options)
        try:
            answers = probe.realizable_all([variant(k, level) for k, level in round_.items()])
        except SolverError:
            if oracle.deadline is not None and time.monotonic() >= oracle.deadline:
                raise
            return brackets, max(low.values()), True
        finally:
            oracle.calls += probe.calls
        for (key, level), works in zip(round_.items(), answers, strict=True):
            if works:
                brackets[key] = (low.pop(key), level)
            elif level >= tops[key]:
                low.pop(key)
            else:
                low[key] = level
        step *= 2
    return brackets, reached, False


def _least_leg_levels(model: Model, oracle: Oracle, top: int = MAX_HEALTH) -> _Levels:
    """For each leg, the least health that makes the spec realizable with every other leg
    as declared, up to ``top`` (the language's :data:`MAX_HEALTH`, or less where the game
    would have more than :data:`HEALTH_VECTORS` health vectors), found exactly: the level is
    bracketed by doubling the raise (:func:`_doubling`, all legs a round) and read off one
    parametric game over the bracket, the leg's cap a rigid parameter
    (:func:`gaitc.analysis.parametric.winning_caps`)."""
    tops = {leg.name: _vector_top(model, [leg.name], top) for leg in model.legs}
    brackets, reached, stopped = _doubling(
        oracle, {leg.name: leg.health for leg in model.legs}, tops,
        lambda name, level: _raised(model, {name: level}))
    found: dict[str, int] = {}
    names = [x.name for x in model.legs]
    for name, (low, high) in brackets.items():
        if high - low == 1:
            found[name] = high
            continue
        domains = {x.name: ((x.health,) if x.name != name else tuple(range(low + 1, high + 1)))
                   for x in model.legs}
        oracle.calls += 1
        result = winning_caps(model, EncodingName.BINARY, domains, oracle.semantics)
        levels = [v[names.index(name)] for v in result.winning]
        found[name] = min(levels, default=high)
    return _Levels({n: found[n] for n in names if n in found}, reached, stopped)


def _least_uniform(model: Model, search: _Search, base: _Edit | None = None,
                   top: int = MAX_HEALTH) -> tuple[_Edit | None, int, bool]:
    """The edit raising every working leg to the least sufficient common level up to
    ``top`` (with the edit ``base`` made too): bracketed by doubling (:func:`_doubling`),
    then bisected on the binary encoding, since a level that suffices stays sufficient
    above it. Also the level the search reached, and whether it stopped early."""
    working = [leg.health for leg in model.legs if leg.health > 1]
    if len(working) < 2:
        return None, top, False
    target = model if base is None else search.edited_model(base)
    if target is None:
        return None, top, False

    def spec(level: int) -> GR1Spec:
        return _raised(target, {leg.name: level for leg in target.legs
                                if 1 < leg.health < level})

    def edit(level: int, cost: int) -> _Edit | None:
        raised = _all_health_edit(model, search.lines, level, cost)
        if raised is None or base is None:
            return raised
        return _joined(base, raised)

    first = min(working)
    if base is not None and search.oracle.realizable(spec(first)):
        return None, top, False  # the other edit alone suffices: no raise is needed
    ceiling = _vector_top(target, [leg.name for leg in target.legs if leg.health > 1], top)
    brackets, reached, stopped = _doubling(search.oracle, {"*": first}, {"*": ceiling},
                                           lambda _, level: spec(level))
    if "*" not in brackets:
        return None, reached, stopped
    low, high = brackets["*"]
    while high - low > 1:
        middle = (low + high) // 2
        if search.oracle.realizable(spec(middle)):
            high = middle
        else:
            low = middle
    return edit(high, high - first + 1), reached, stopped


def _limit_text(reached: int, stopped: bool) -> str:
    if stopped:
        return (f"up to {reached} (the search stops there: a solve took over "
                f"{SOLVE_GUARD_SECONDS:.0f} s)")
    if reached < MAX_HEALTH:
        return f"up to {reached} (games of at most {HEALTH_VECTORS:,} health vectors)"
    return f"up to {reached}"


def _health_edits(model: Model, search: _Search, plan: _Plan,
                  base: _Edit | None = None, top: int = MAX_HEALTH) -> list[_Edit]:
    """The least raise of each leg alone and the least uniform raise up to level ``top``,
    each found exactly; with ``base``, on the spec with that edit made, and joined to it."""
    lines = search.lines
    edits: list[_Edit] = []
    target = model if base is None else search.edited_model(base)
    if target is None:
        return []
    levels = _least_leg_levels(target, search.oracle, top)
    for name, level in levels.found.items():
        leg = model.leg(name)
        new = _leg_lines(model, lines, leg, level)
        if new is not None and leg.span is not None:
            raised = _Edit(f"raise leg {name}'s health to {level}", level - leg.health,
                           LEG_RAISE, ((leg.span.line, new),), subject=name)
            joined = raised if base is None else _joined(base, raised)
            if joined is not None:
                edits.append(joined)
    uniform, reached, stopped = _least_uniform(model, search, base, top)
    if uniform is not None:
        edits.append(uniform)
    if base is None:
        plan.searched[LEG_RAISE] = (f"each of the {len(model.legs)} legs alone, "
                                    f"every level {_limit_text(levels.reached, levels.stopped)}"
                                    " (exact: "
                                    "doubling, then a parametric game)")
        if len([leg for leg in model.legs if leg.health > 1]) >= 2:
            plan.searched[ALL_RAISE] = ("every working leg to one common level "
                                        f"{_limit_text(reached, stopped)} (exact: doubling, "
                                        "then bisection)")
    return edits


def _health_pairs(model: Model, search: _Search, plan: _Plan) -> list[_Edit]:
    """Pairs of an edit of another kind and the least health raise it needs: each of the
    cheapest other edits is tried with every working leg raised (one solve
    each, at :func:`pair_health_limit`), and for the first :data:`KEPT_PAIRS` that work the
    least raises are found exactly on the edited spec."""
    level = pair_health_limit(model)
    top = _all_health_edit(model, search.lines, level, 0)
    if top is None:
        return []
    others = [e for e in plan.singles if e.kind not in (GOAL_DROP, GUARANTEE_DROP)]
    pool = [e for kind in KINDS[2:] for e in others if e.kind == kind][:HEALTH_PAIR_POOL]
    probes = [(e, j) for e in pool if (j := _joined(e, top)) is not None]
    ready = [(e, made) for e, j in probes
             if (made := search.variant(j, EncodingName.BINARY)) is not None]
    answers = search.oracle.realizable_all([made[2] for _, made in ready])
    bases = [e for (e, _), ok in zip(ready, answers, strict=True) if ok][:KEPT_PAIRS]
    plan.searched[HEALTH_PAIRS] = (f"the {len(pool)} cheapest other edits, each with the "
                                   f"least health it needs up to level {level} (exact)")
    return [pair for base in bases
            for pair in _health_edits(model, search, plan, base, level)]


def pair_health_limit(model: Model) -> int:
    """The highest level tried with another edit: twice the largest declared health or the
    number of regions (a walk that visits every region once), whichever is more. The
    limit of the language is not used here: a spec whose environment has fairness to
    spare takes minutes to refute at a hundred levels (a hazard assumed off infinitely
    often and health 100 on an 8-leg robot: 79 s), where the single raises take
    milliseconds."""
    return min(MAX_HEALTH, max(2 * max(leg.health for leg in model.legs), len(model.regions)))


def repairs(model: Model, text: str, filename: str, encoding: EncodingName, oracle: Oracle,
            visited: Sequence[str], failed: Sequence[str] = ()) -> Repairs:
    """The verified repairs, ranked: the least health raises (exact), then every single edit
    that works; when none short of dropping a goal does, the cheapest working pairs (of one
    kind or two); the goal drops last. ``visited``: regions of the play (cache sites tried
    first); ``failed``: legs the play failed (replaced in new gaits)."""
    search = _Search(text, filename, encoding, oracle)
    plan = _plan(model, text, visited, failed)
    health = _health_edits(model, search, plan)
    wear = _wear_edits(model, search, plan)
    singles = [*health, *wear, *(e for e in plan.singles if e.kind != GOAL_DROP)]
    found = search.working(singles)
    if not found:
        pairs = sorted([*plan.pairs, *_health_pairs(model, search, plan)], key=_Edit.rank)
        chunk = 4 * WORKERS
        for start in range(0, len(pairs), chunk):
            works = search.working(pairs[start:start + chunk])
            if works:  # the cheapest: more would repeat them with further edits
                found = _distinct(works)[:KEPT_PAIRS]
                break
    found = _distinct(found)
    drops = search.working([e for e in plan.singles if e.kind == GOAL_DROP])
    order = [*KINDS[:-1], PAIRS, HEALTH_PAIRS, GOAL_DROP]
    searched = tuple((kind, plan.searched[kind]) for kind in order if kind in plan.searched)
    return Repairs(tuple(r for _, r in [*found, *drops]), tuple(k for k, _ in searched),
                   searched)


def _distinct(found: list[tuple[_Edit, Repair]]) -> list[tuple[_Edit, Repair]]:
    """``found`` ranked, each edited text once (a pair is found from either of its edits)."""
    seen: set[str] = set()
    out = []
    for edit, repair in sorted(found, key=lambda item: item[0].rank()):
        if repair.text not in seen:
            seen.add(repair.text)
            out.append((edit, repair))
    return out


def candidate_edits(model: Model, text: str, visited: Sequence[str],
                    failed: Sequence[str] = ()) -> list[_Edit]:
    """Every single edit of a fixed size tried (the health raises apart: they are found
    exactly), cheapest first."""
    return sorted(_plan(model, text, visited, failed).singles, key=_Edit.rank)
