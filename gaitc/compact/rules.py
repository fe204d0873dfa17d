"""The compact controller in words: one table of rules per goal, each rule a path of its
diagram ("in b2 after n1, L3 at level 2 or more, no hazard: e1 to b3").

The rules of a goal partition the states it is pursued in, so exactly one rule applies at a
time; a field a rule does not mention does not matter to it.  Numeric fields (health
levels, integers) are said as ranges, the others as lists of values.

Given the spec, the tables say only what a run can meet (:func:`reach`): the care set is
every state a run of the controller reaches under the spec's assumptions (θe, ρe and the
controller's own moves, with the goal counter), with every input ρe allows there.  A rule
no such state takes is never used: it is left out of the text (counted) or marked; a rule
that is used says only the values its reachable states have.
"""

from __future__ import annotations

import html
import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from gaitc.compact.controller import diagram_order, relations
from gaitc.compact.diagram import Slot, paths
from gaitc.compact.extraction import counter_moves, reachable
from gaitc.ir.bitblast import bitblast
from gaitc.ir.spec import Semantics
from gaitc.verifier.logic import Logic

if TYPE_CHECKING:
    from dd.cudd import BDD, Function

    from gaitc.compact.controller import CompactController
    from gaitc.ir.spec import GR1Spec

NEVER_USED = "never used"


@dataclass(frozen=True)
class Rule:
    """When every condition holds, the controller makes ``move``; ``used`` is False when no
    state a run reaches meets the conditions (known only when the tables were made with
    the spec)."""

    conditions: tuple[str, ...]
    move: str
    used: bool = True

    @property
    def when(self) -> str:
        return ", ".join(self.conditions) or "always"

    @property
    def said(self) -> str:
        """The move, marked when the rule is never used."""
        return self.move if self.used else f"{self.move}  ({NEVER_USED})"

    def to_dict(self) -> dict[str, Any]:
        return {"when": list(self.conditions), "move": self.move, "used": self.used}


@dataclass(frozen=True)
class RuleTables:
    """Per goal, its label and its rules; plus the sizes a reader wants first.

    ``reached``: whether the rules were checked against the states a run reaches (with the
    spec); ``all_rules``: whether the text lists the never used rules too (marked)."""

    goals: tuple[tuple[str, tuple[Rule, ...]], ...]
    start: tuple[Rule, ...]
    sizes: str
    reached: bool = False
    all_rules: bool = False

    @property
    def rules(self) -> int:
        """Every rule of the diagrams, used or not."""
        return sum(len(rules) for _, rules in self.goals)

    @property
    def never_used(self) -> int:
        """The rules (goals and start) no state a run reaches takes."""
        return sum(not r.used for _, rules in self.goals for r in rules) + sum(
            not r.used for r in self.start)

    def shown(self, rules: Sequence[Rule]) -> tuple[Rule, ...]:
        """The rules the text lists: the used ones, or all of them with ``all_rules``."""
        return tuple(r for r in rules if r.used or self.all_rules)

    def shown_goals(self) -> tuple[tuple[str, tuple[Rule, ...]], ...]:
        return tuple((label, self.shown(rules)) for label, rules in self.goals)

    def reach_line(self) -> str | None:
        """What the tables say of the rules no run uses (None when not checked)."""
        if not self.reached:
            return None
        n = self.never_used
        if n == 0:
            return "every rule is used by some state a run reaches"
        some = "1 rule that no run reaches is" if n == 1 else \
            f"{n} rules that no run reaches are"
        if self.all_rules:
            return f"{some} marked ({NEVER_USED})"
        return f"{some} left out (--all-rules lists {'it' if n == 1 else 'them'})"

    def _head(self) -> list[str]:
        line = self.reach_line()
        return [f"compact controller: {self.sizes}"] + ([line] if line else [])

    def text(self) -> str:
        lines = self._head()
        start = self.shown(self.start)
        if start:
            lines += ["", "start:"] + [f"  {r.when}: {r.said}" for r in start]
        for label, rules in self.shown_goals():
            lines += ["", f"pursuing {label} ({_count(rules)}):"]
            width = max((len(r.when) for r in rules), default=0)
            lines += [f"  {r.when:<{width}}  ->  {r.said}" for r in rules]
        return "\n".join(lines) + "\n"

    def markdown(self) -> str:
        def cell(text: str) -> str:
            return text.replace("|", "\\|")

        out = [line for head in self._head() for line in (head, "")]
        for label, rules in self.shown_goals():
            out += [f"**pursuing {cell(label)}**", "", "| when | move |", "|---|---|"]
            out += [f"| {cell(r.when)} | {cell(r.said)} |" for r in rules]
            out.append("")
        return "\n".join(out)

    def html(self) -> str:
        parts = [f"<p>{html.escape(line)}</p>" for line in self._head()]
        for label, rules in self.shown_goals():
            body = "".join(f"<tr><td>{html.escape(r.when)}</td><td>{html.escape(r.said)}</td>"
                           "</tr>" for r in rules)
            parts.append(f"<table><caption>pursuing {html.escape(label)}</caption>"
                         f"<tr><th>when</th><th>move</th></tr>{body}</table>")
        return "".join(parts)

    def to_dict(self) -> dict[str, Any]:
        """Every rule, used or not (``"used": false`` marks the never used ones)."""
        return {"sizes": self.sizes, "reach_checked": self.reached,
                "never_used": self.never_used if self.reached else None,
                "start": [r.to_dict() for r in self.start],
                "goals": [{"goal": label, "rules": [r.to_dict() for r in rules]}
                          for label, rules in self.goals]}

    def json(self) -> str:
        return json.dumps(self.to_dict(), indent=1, ensure_ascii=False) + "\n"

    def __str__(self) -> str:
        return self.text()

    def _repr_html_(self) -> str:
        return self.html()


def _count(rules: Sequence[Rule]) -> str:
    return "1 rule" if len(rules) == 1 else f"{len(rules)} rules"


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


# -------------------------------------------------------------------- the care set
Condition = tuple[frozenset[int] | None, ...]  # per slot, the values a path takes (None: any)


@dataclass(frozen=True)
class Reach:
    """Where a run of a compact controller can be, as BDDs of ``bdd`` over the spec's bits:
    per goal, the current states a run pursues it in with every input ρe allows next
    (primed); and the first inputs θe allows (primed, as the start diagram reads them)."""

    bdd: BDD
    moves: tuple[Function, ...]
    first: Function

    def path(self, ctrl: CompactController, cond: Condition) -> Function:
        """The states and inputs a path of ``ctrl``'s diagrams takes."""
        out = self.bdd.true
        for slot, chosen in zip(ctrl.slots, cond, strict=True):
            if chosen is not None:
                out &= self.values(slot, chosen)
        return out

    def values(self, slot: Slot, chosen: frozenset[int]) -> Function:
        out = self.bdd.false
        for value in sorted(chosen):
            out |= self.bdd.cube(slot.field.cube(value, slot.next))
        return out


def reach(ctrl: CompactController, spec: GR1Spec) -> Reach:
    """The care set of ``ctrl``'s rules under ``spec``: the states a run of the controller
    reaches from its initial states (θe and its start), each step an input ρe allows and the
    controller's own move, the goal counter moved by its goal diagrams.  The fixpoint is
    the one compaction shrinks its care sets with (:func:`gaitc.compact.extraction.reachable`),
    here over the controller's relations alone, as the verifier models the closed loop."""
    logic = Logic(bitblast(spec), diagram_order(ctrl))
    bdd = logic.bdd
    env_init, env_trans = logic.conjunction("env_init"), logic.conjunction("env_trans")
    made = relations(bdd, ctrl)
    outputs = set(ctrl.outputs)
    if ctrl.semantics == Semantics.ROBOTICS:
        init = env_init & made["start"]
    else:
        init = bdd.exist(outputs, env_init) & made["start"]
    per_goal = reachable(bdd, init, made["strategies"], env_trans,
                         counter_moves(bdd, made["goals"]), ctrl.inputs, ctrl.outputs)
    post_out = {b + "'" for b in ctrl.outputs}
    moves = tuple(bdd.exist(post_out, here & env_trans) for here in per_goal)
    prime = {b: b + "'" for b in ctrl.inputs}
    first = bdd.let(prime, bdd.exist(outputs, env_init))
    return Reach(bdd, moves, first)


def _taken(found: Reach, slot: Slot, within: Function, chosen: frozenset[int] | None
           ) -> frozenset[int]:
    """The values of ``slot`` (among ``chosen``; None: all) that states of ``within`` have."""
    values = range(len(slot.field.labels)) if chosen is None else sorted(chosen)
    return frozenset(v for v in values
                     if within & found.values(slot, frozenset([v])) != found.bdd.false)


def _narrowed(ctrl: CompactController, cond: Condition, care: Function, found: Reach
              ) -> Condition | None:
    """``cond`` said of the reachable states only: each tested slot narrowed to the values
    they have there, and the robot's own state (a current output field the path does not
    test) named when they all have one value of it and the goal's care set more; None when
    no state of ``care`` takes the path."""
    on_path = care & found.path(ctrl, cond)
    if on_path == found.bdd.false:
        return None
    out: list[frozenset[int] | None] = []
    for slot, chosen in zip(ctrl.slots, cond, strict=True):
        if chosen is not None:
            out.append(_taken(found, slot, on_path, chosen))
        elif slot.next or slot.field.is_input:
            out.append(None)
        else:
            here = _taken(found, slot, on_path, None)
            out.append(here if len(here) == 1 and here < _taken(found, slot, care, None)
                       else None)
    return tuple(out)


def _rules(ctrl: CompactController, root: int, care: Function | None = None,
           found: Reach | None = None) -> tuple[Rule, ...]:
    robot = ctrl.vocabulary.domain == "robot"
    out = []
    for cond, leaf in paths(ctrl.nodes, root, len(ctrl.slots)):
        shown: Condition | None = cond
        if found is not None and care is not None:  # given together
            shown = _narrowed(ctrl, cond, care, found)
        used = shown is not None
        words = tuple(condition(ctrl.slots[k], chosen, robot)
                      for k, chosen in enumerate(shown if shown is not None else cond)
                      if chosen is not None)
        out.append(Rule(words, move_words(ctrl, leaf), used))
    return tuple(out)


def rule_tables(ctrl: CompactController, goal_labels: Sequence[str] = (),
                table_bytes: int | None = None, *, spec: GR1Spec | None = None,
                all_rules: bool = False) -> RuleTables:
    """The tables of ``ctrl``; ``goal_labels`` name the goals (default: goal 1, 2, ...).
    With ``spec``, each rule is checked against the states a run reaches (:func:`reach`):
    the text leaves out the never used ones (``all_rules``: lists them, marked)."""
    labels = list(goal_labels) or [f"goal {j + 1}" for j in range(ctrl.goal_count)]
    found = None if spec is None else reach(ctrl, spec)
    goals = tuple((labels[j], _rules(ctrl, root, None if found is None else found.moves[j],
                                     found))
                  for j, root in enumerate(ctrl.move_roots))
    start: tuple[Rule, ...] = ()
    if ctrl.semantics != Semantics.ROBOTICS:
        start = _rules(ctrl, ctrl.start_root, None if found is None else found.first, found)
    size = (f"{ctrl.rules} rules, {ctrl.decision_nodes} decision nodes "
            f"(+{ctrl.monitor_nodes} for the assumption monitor)")
    if table_bytes is not None:
        size += f", {table_bytes} bytes of tables"
    return RuleTables(goals, start, size, reached=found is not None, all_rules=all_rules)
