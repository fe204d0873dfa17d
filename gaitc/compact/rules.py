"""The compact controller in words: one table of rules per goal, each rule a path of its
diagram ("in b2 after n1, L3 at level 2 or more, no hazard: e1 to b3").

The rules of a goal partition the states it is pursued in, so exactly one rule applies at a
time; a field a rule does not mention does not matter to it.  Numeric fields (health
levels, integers) are said as ranges, the others as lists of values.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from gaitc.compact.diagram import Slot, paths
from gaitc.ir.spec import Semantics

if TYPE_CHECKING:
    from gaitc.compact.controller import CompactController


@dataclass(frozen=True)
class Rule:
    """When every condition holds, the controller makes ``move``."""

    conditions: tuple[str, ...]
    move: str

    @property
    def when(self) -> str:
        return ", ".join(self.conditions) or "always"


@dataclass(frozen=True)
class RuleTables:
    """Per goal, its label and its rules; plus the sizes a reader wants first."""

    goals: tuple[tuple[str, tuple[Rule, ...]], ...]
    start: tuple[Rule, ...]
    sizes: str

    @property
    def rules(self) -> int:
        return sum(len(rules) for _, rules in self.goals)

    def text(self) -> str:
        lines = [f"compact controller: {self.sizes}"]
        if self.start:
            lines += ["", "start:"] + [f"  {r.when}: {r.move}" for r in self.start]
        for label, rules in self.goals:
            lines += ["", f"pursuing {label} ({len(rules)} rules):"]
            width = max((len(r.when) for r in rules), default=0)
            lines += [f"  {r.when:<{width}}  ->  {r.move}" for r in rules]
        return "\n".join(lines) + "\n"

    def markdown(self) -> str:
        def cell(text: str) -> str:
            return text.replace("|", "\\|")

        out = [f"compact controller: {self.sizes}", ""]
        for label, rules in self.goals:
            out += [f"**pursuing {cell(label)}**", "", "| when | move |", "|---|---|"]
            out += [f"| {cell(r.when)} | {cell(r.move)} |" for r in rules]
            out.append("")
        return "\n".join(out)

    def html(self) -> str:
        parts = [f"<p>compact controller: {html.escape(self.sizes)}</p>"]
        for label, rules in self.goals:
            body = "".join(f"<tr><td>{html.escape(r.when)}</td><td>{html.escape(r.move)}</td>"
                           "</tr>" for r in rules)
            parts.append(f"<table><caption>pursuing {html.escape(label)}</caption>"
                         f"<tr><th>when</th><th>move</th></tr>{body}</table>")
        return "".join(parts)

    def __str__(self) -> str:
        return self.text()

    def _repr_html_(self) -> str:
        return self.html()


def _values(slot: Slot, chosen: frozenset[int]) -> str:
    f = slot.field
    labels = [f.labels[k] for k in sorted(chosen)]
    ordered = sorted(chosen)
    if f.numeric and len(ordered) > 1 and ordered == list(range(ordered[0], ordered[-1] + 1)):
        if ordered[-1] == len(f.labels) - 1:
            return f"at least {f.labels[ordered[0]]}"
        if ordered[0] == 0:
            return f"at most {f.labels[ordered[-1]]}"
        return f"{labels[0]}..{labels[-1]}"
    return " or ".join(labels)


def condition(slot: Slot, chosen: frozenset[int], robot: bool) -> str:
    """One condition in words: the field, whether it is the new value, its values."""
    name, said = slot.field.name, _values(slot, chosen)
    if robot:
        if name == "region":
            return f"in {said}"
        if name == "gait":
            return f"after {said}"
        if name == "hazard":
            when = "" if slot.next else " before"
            return f"no hazard{when}" if said == "none" else f"hazard {said}{when}"
        return f"{name} {'now ' if slot.next else 'was '}{said}"
    return f"{name}{chr(39) if slot.next else ''} = {said}"


def move_words(ctrl: CompactController, move: int) -> str:
    outs = ctrl.vocabulary.outputs
    values = dict(zip((f.name for f in outs), ctrl.moves[move], strict=True))
    if ctrl.vocabulary.domain == "robot" and {"region", "gait"} <= set(values):
        region = ctrl.vocabulary.named("region").labels[values["region"]]
        gait = ctrl.vocabulary.named("gait").labels[values["gait"]]
        return f"stay in {region}" if gait == "noGait" else f"{gait} to {region}"
    return ", ".join(f"{f.name}' = {f.labels[values[f.name]]}" for f in outs)


def _rules(ctrl: CompactController, root: int) -> tuple[Rule, ...]:
    robot = ctrl.vocabulary.domain == "robot"
    out = []
    for cond, leaf in paths(ctrl.nodes, root, len(ctrl.slots)):
        words = tuple(condition(ctrl.slots[k], chosen, robot)
                      for k, chosen in enumerate(cond) if chosen is not None)
        out.append(Rule(words, move_words(ctrl, leaf)))
    return tuple(out)


def rule_tables(ctrl: CompactController, goal_labels: Sequence[str] = (),
                table_bytes: int | None = None) -> RuleTables:
    """The tables of ``ctrl``; ``goal_labels`` name the goals (default: goal 1, 2, ...)."""
    labels = list(goal_labels) or [f"goal {j + 1}" for j in range(ctrl.goal_count)]
    goals = tuple((labels[j], _rules(ctrl, root)) for j, root in enumerate(ctrl.move_roots))
    start: tuple[Rule, ...] = ()
    if ctrl.semantics != Semantics.ROBOTICS:
        start = _rules(ctrl, ctrl.start_root)
    size = (f"{ctrl.rules} rules, {ctrl.decision_nodes} decision nodes "
            f"(+{ctrl.monitor_nodes} for the assumption monitor)")
    if table_bytes is not None:
        size += f", {table_bytes} bytes of tables"
    return RuleTables(goals, start, size)
