"""What hovering a name shows: the facts about it a user would otherwise look up by hand.

A leg: its health levels (thesis eq. 3.5: level 1 is failed) and the gaits that use it
(G_L). A gait: its legs in firing order, where it moves, its valve sequence. A region: its
neighbours by direction and the gaits of each move (D_τ), whether it is a cache (eq. 3.6),
in which hazard sets (eq. 3.8), and whether it is the start or a goal. A hazard: its
regions and what it does to the legs (``Hazard.effect``). A goal of ``visit``: whether it
can be reached from the start at all. Built from the checked model when the
file checks, else from the syntax tree alone.
"""

from __future__ import annotations

from collections import deque

from gaitc.ir.formula import unreachable
from gaitc.ir.roles import Fails, WearsUpTo
from gaitc.lsp.index import Index, Kind, Symbol
from ltlcompiler import syntax as s
from ltlcompiler.model import NO_GAIT, GaitKind, Model

#: The compass step of a grid move, by (row, column) change.
STEPS = {(-1, 0): "north", (1, 0): "south", (0, 1): "east", (0, -1): "west", (0, 0): "stay"}


def describe(symbol: Symbol, index: Index, model: Model | None, role: str = "") -> str:
    """Markdown for ``symbol``; ``role`` is that of the mention hovered (``goal``...)."""
    head = f"**{symbol.kind}** `{symbol.name}`"
    if model is None:
        declared = symbol.declaration
        where = f" (declared on line {declared.span.line})" if declared else ""
        return f"{head}{where}\n\n_the file does not check yet: fix its error for more_"
    if symbol.kind is Kind.LEG:
        return f"{head}\n\n{_leg(symbol.name, model)}"
    if symbol.kind is Kind.GAIT:
        return f"{head}\n\n{_gait(symbol.name, index, model)}"
    if symbol.kind is Kind.HAZARD:
        hazard = next((h for h in model.hazards if h.name == symbol.name), None)
        cells = ", ".join(hazard.regions) if hazard and hazard.regions else "(no region)"
        effect = "fails the legs" if hazard is None else hazard.effect
        harm = Fails() if hazard is None else hazard.harm
        match harm:
            case Fails():
                source = "thesis eqs. 3.8, 3.9"
            case WearsUpTo(levels):
                source = (f"thesis eq. 3.9, graded: a loss of up to {levels} "
                          f"level{'s' if levels != 1 else ''} in place of a failure")
            case _:
                unreachable(harm)
        return (f"{head}\n\nregions: {cells}\n\nwhile it is on, entering one of them "
                f"{effect} (those of the gait in use; {source})")
    text = f"{head}\n\n{_region(symbol.name, model)}"
    if role == "goal" or "goal" in symbol.roles():
        text += "\n\n" + _reachable(symbol.name, model)
    return text


def _leg(name: str, model: Model) -> str:
    leg = model.leg(name)
    using = [g for g in model.gaits_using(name) if g != NO_GAIT]
    start = "" if leg.initial == leg.health else f", starts at level {leg.initial}"
    levels = ("permanently failed (1 level)" if leg.health == 1 else
              f"{leg.health} health levels: {leg.health} is full, 1 is failed{start}")
    return (f"{levels}\n\nused by {len(using)} gait{'s' * (len(using) != 1)}: "
            f"{', '.join(using) or '(none)'}")


def _gait(name: str, index: Index, model: Model) -> str:
    gait = model.gait(name)
    lines = [f"legs (firing order): {', '.join(gait.firing_order) or '(none)'}"]
    decl = next((st for st in index.tree.statements
                 if isinstance(st, s.GaitDecl) and st.name.text == name), None)
    if decl is not None and decl.directions:
        lines.append("moves " + ", ".join(d.name for d in decl.directions))
    moves = [t for t in model.transitions if name in t.gaits and t.source != t.target]
    if moves:
        shown = ", ".join(f"{t.source} → {t.target}" for t in moves[:8])
        more = f" and {len(moves) - 8} more" if len(moves) > 8 else ""
        lines.append(f"{len(moves)} move{'s' * (len(moves) != 1)}: {shown}{more}")
    primitive = gait.primitive
    if primitive is None:
        lines.append("no valve sequence bound (add `valves ...` or `primitive \"robot.yaml\"`)")
    elif primitive.valves:
        lines.append("valve sequence: " + " → ".join(primitive.valves))
    else:
        method = f", method {primitive.method}" if primitive.method else ""
        lines.append(f"valve sequence searched in `{primitive.robot}`"
                     f"{f', direction {primitive.direction}' if primitive.direction else ''}"
                     f"{method}")
    if gait.kind is GaitKind.CORRECTION:
        lines.append("a correction gait: it turns the robot and wears no leg (thesis 3.4.1)")
    return "\n\n".join(lines)


def _direction(model: Model, source: str, target: str, given: str | None) -> str:
    if given:
        return given
    where = {r.name: (r.row, r.col) for r in model.regions}
    a, b = where.get(source), where.get(target)
    if a and b and None not in a and None not in b:
        step = (int(b[0] or 0) - int(a[0] or 0), int(b[1] or 0) - int(a[1] or 0))
        return STEPS.get(step, "to")
    return "to"


def _region(name: str, model: Model) -> str:
    lines = []
    region = next((r for r in model.regions if r.name == name), None)
    if region is not None and region.row is not None:
        lines.append(f"grid cell ({region.row}, {region.col})")
    out = [t for t in model.transitions if t.source == name and t.target != name]
    if out:
        lines.append("neighbours:\n" + "\n".join(
            f"- {_direction(model, name, t.target, t.direction)} `{t.target}` by "
            f"{', '.join(t.gaits)}" for t in out))
    else:
        lines.append("no move leaves this region")
    if name in model.caches:
        lines.append("a **cache**: every leg's health is restored here (thesis eq. 3.6)")
    hazards = [h.name for h in model.hazards if name in h.regions]
    if hazards:
        lines.append(f"in hazard set{'s' * (len(hazards) > 1)} {', '.join(hazards)}")
    if name == model.start:
        lines.append("the robot **starts** here")
    return "\n\n".join(lines)


def _reachable(goal: str, model: Model) -> str:
    """Whether ``goal`` can be reached from the start by moves of τ (ignoring health)."""
    steps = {model.start: 0}
    queue = deque([model.start])
    while queue:
        here = queue.popleft()
        for t in model.transitions:
            if t.source == here and t.target not in steps:
                steps[t.target] = steps[here] + 1
                queue.append(t.target)
    if goal not in steps:
        return (f"**goal not reachable**: no sequence of moves leads from the start "
                f"{model.start} to {goal}")
    count = steps[goal]
    return (f"goal reachable from the start {model.start} in {count} move"
            f"{'s' * (count != 1)} (before health is counted: `gaitc check` decides)")
