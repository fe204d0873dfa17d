"""The controller projected on the map: per region, which gait towards which region under
which condition (goal pursued, active hazard, leg health), condensed into readable rules.

Every controller move is a *decision*: at node n (the robot in region R after the move
into it) the environment picks the next health and hazard, and the controller answers with
the gait and region of the successor (the Mealy turn order of ``docs/simulation.md``).  A
decision's *condition* is the goal n pursues, the hazard the controller sees and each leg's
health band (healthy: full, failed: level 1, degraded: between).  Per region, the rules
are the leaves of a decision tree over these variables (:mod:`gaitc.sim.condensation`), each
as exact as the variables allow: a row that lists several moves means the controller's
memory (its node) decides between them, not the condition.  The counts say how many
decisions each move covers.  The rules of a region partition its decisions.
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

from gaitc.sim.condensation import Condition, Decision, Move, condense
from gaitc.sim.domain import Domain, State
from gaitc.sim.strategy import Strategy
from gaitc.sim.view import StrategyView, reachable

HAZARD, GOAL = "hazard", "goal"
BANDS = ("healthy", "degraded", "failed")
NO_HAZARD = "none"


@dataclass(frozen=True)
class Rule:
    """In ``region``, when ``condition`` holds, the controller makes one of ``moves``
    (with the number of decisions that make it)."""

    region: str
    condition: Condition
    moves: tuple[tuple[Move, int], ...]
    exact: bool = True  # False: a coarse rule (--max-rules) over conditions told apart

    def matches(self, features: Mapping[str, str]) -> bool:
        return all(features[name] in values for name, values in self.condition)

    def when(self) -> str:
        """The condition in words ("always" when no variable matters)."""
        words = ", ".join(_words(name, values) for name, values in self.condition) or "always"
        return words if self.exact else f"~ {words}"

    def what(self) -> str:
        return ", ".join(f"{m.text(self.region)} ({n})" for m, n in self.moves)

    @property
    def decisions(self) -> int:
        return sum(n for _, n in self.moves)


@dataclass(frozen=True)
class Policy:
    """The projected controller: rules in region order, and what they were built from."""

    rules: tuple[Rule, ...]
    regions: tuple[str, ...]  # the regions the controller is in, in map order
    variables: dict[str, tuple[str, ...]]  # per region, the condition variables its rules test
    nodes: int  # controller nodes projected
    decisions: int  # controller moves projected
    notes: tuple[str, ...] = ()

    def rule_for(self, region: str, features: Mapping[str, str]) -> Rule | None:
        """The rule of ``region`` whose condition ``features`` satisfy."""
        for rule in self.rules:
            if rule.region == region and rule.matches(features):
                return rule
        return None

    def rows(self) -> list[tuple[str, str, str]]:
        return [(r.region, r.when(), r.what()) for r in self.rules]

    def summary(self) -> str:
        return (
            f"{self.nodes} controller nodes, {self.decisions} moves in "
            f"{len(self.regions)} regions: {len(self.rules)} rules"
        )

    def text(self) -> str:
        """A plain text table (what the terminal shows)."""
        head = ("region", "when", "gait → next region (decisions)")
        rows = [head, *self.rows()]
        widths = [max(len(row[i]) for row in rows) for i in range(2)]
        lines = []
        previous = ""
        for k, (region, when, what) in enumerate(rows):
            shown = region if region != previous or k == 0 else ""
            previous = region
            lines.append(f"{shown:<{widths[0]}}  {when:<{widths[1]}}  {what}".rstrip())
            if k == 0:
                lines.append("-" * min(len(lines[0]) + 10, 100))
        return "\n".join([*lines, "", self.summary(), *self.notes]) + "\n"

    def markdown(self) -> str:
        def cell(text: str) -> str:
            return text.replace("|", "\\|")

        lines = ["| region | when | gait → next region (decisions) |", "|---|---|---|"]
        lines += [f"| {cell(a)} | {cell(b)} | {cell(c)} |" for a, b, c in self.rows()]
        return "\n".join([*lines, "", self.summary() + ".", *self.notes]) + "\n"

    def html(self) -> str:
        body = "".join(
            f"<tr><td>{html.escape(a)}</td><td>{html.escape(b)}</td><td>{html.escape(c)}</td></tr>"
            for a, b, c in self.rows()
        )
        notes = "".join(f"<p>{html.escape(n)}</p>" for n in self.notes)
        return (
            f"<table><caption>{html.escape(self.summary())}</caption><tr><th>region</th>"
            f"<th>when</th><th>gait → next region (decisions)</th></tr>{body}</table>" + notes
        )

    def __str__(self) -> str:
        return self.text()

    def _repr_html_(self) -> str:
        return self.html()

    def _repr_markdown_(self) -> str:
        return self.markdown()


def band(level: int, full: int) -> str:
    """The health band of a leg level: healthy (full), failed (level 1), else degraded."""
    if level >= full:
        return BANDS[0]
    return BANDS[2] if level <= 1 else BANDS[1]


def features(domain: Domain, goal: str, seen: State) -> dict[str, str]:
    """The condition of a decision: the goal pursued, the hazard and leg bands it sees."""
    out = {GOAL: goal}
    if domain.hazard_regions:
        out[HAZARD] = seen.hazard or NO_HAZARD
    out.update({leg: band(level, domain.full[leg]) for leg, level in seen.health})
    return out


def goal_label(domain: Domain, rank: int) -> str:
    labels = [g.label for g in domain.goals]
    return labels[rank] if 0 <= rank < len(labels) else f"goal {rank + 1}"


def decisions(
    strategy: StrategyView, domain: Domain, nodes: Iterable[int]
) -> dict[str, list[Decision]]:
    """Per region, every move the controller makes from ``nodes`` (successors in order)."""
    out: dict[str, list[Decision]] = {}
    for node in nodes:
        here = domain.node_state(strategy, node)
        goal = goal_label(domain, strategy.ranks[node])
        for succ in strategy.options(node).values():
            there = domain.node_state(strategy, succ)
            out.setdefault(here.region, []).append(
                (features(domain, goal, there), Move(there.gait, there.region))
            )
    return out


def project(
    strategy: StrategyView,
    domain: Domain,
    nodes: Sequence[int] | None = None,
    notes: Sequence[str] = (),
    max_rules: int | None = None,
) -> Policy:
    """Project ``strategy`` on the map, from ``nodes`` (default: every node, which needs an
    explicit controller; for a symbolic one pass the nodes a bounded search reached), with
    at most ``max_rules`` rules per region (default: as many as exact rules need)."""
    chosen = list(range(len(strategy))) if nodes is None else sorted(set(nodes))
    found = decisions(strategy, domain, chosen)
    order = _value_order(domain)
    names = [GOAL, *([HAZARD] if domain.hazard_regions else []), *domain.legs]
    rules: list[Rule] = []
    variables: dict[str, tuple[str, ...]] = {}
    regions = tuple(r for r in domain.regions if r in found)
    for region in regions:
        cases = found[region]
        leaves = condense(cases, names, order, (GOAL,), max_rules)
        tested = {name for condition, _, _ in leaves for name, _ in condition}
        variables[region] = tuple(n for n in names if n in tested)
        rules.extend(Rule(region, cond, _ranked(moves), exact) for cond, moves, exact in leaves)
    total = sum(len(c) for c in found.values())
    coarse = [r for r in regions if any(not x.exact for x in rules if x.region == r)]
    if coarse:
        notes = [
            *notes,
            f"at most {max_rules} rules per region: the rules marked ~ in "
            f"{', '.join(coarse)} join conditions under which the controller moves "
            "differently (every move they cover is listed)",
        ]
    return Policy(tuple(rules), regions, variables, len(chosen), total, tuple(notes))


def _ranked(moves: Mapping[Move, int]) -> tuple[tuple[Move, int], ...]:
    """Moves by how many decisions make them, then by gait and region."""
    return tuple(sorted(moves.items(), key=lambda mn: (-mn[1], mn[0].gait, mn[0].target)))


def _value_order(domain: Domain) -> dict[str, dict[str, int]]:
    """Display order of each variable's values: goals and hazards as declared (no hazard
    first), bands from healthy to failed."""
    out = {
        GOAL: {g.label: i for i, g in enumerate(domain.goals)},
        HAZARD: {NO_HAZARD: 0} | {h: i + 1 for i, h in enumerate(domain.hazard_regions)},
    }
    out.update({leg: {b: i for i, b in enumerate(BANDS)} for leg in domain.legs})
    return out


def _words(name: str, values: Sequence[str]) -> str:
    listed = " or ".join(values)
    if name == GOAL:
        return f"heading for {listed}"
    if name == HAZARD:
        return "no hazard" if values == (NO_HAZARD,) else f"hazard {listed}"
    return f"{name} {listed}"


#: Bounded search for a symbolic controller (whose nodes are found by running it).
SYMBOLIC_STEPS = 10
DEFAULT_CAP = 2000


def controller_policy(
    strategy: StrategyView,
    domain: Domain,
    steps: int | None = None,
    cap: int = DEFAULT_CAP,
    max_rules: int | None = None,
) -> Policy:
    """The projected controller: from every node of an explicit controller, or from the
    nodes within ``steps`` moves of the start (at most ``cap``; a symbolic controller is
    always bounded, by default to :data:`SYMBOLIC_STEPS` moves); ``max_rules`` as for
    :func:`project`."""
    if steps is None and isinstance(strategy, Strategy):
        return project(strategy, domain, max_rules=max_rules)
    bound = SYMBOLIC_STEPS if steps is None else steps
    depth, capped = reachable(strategy, bound, cap)
    symbolic = "" if isinstance(strategy, Strategy) else "the controller is symbolic: "
    beyond = any(
        s not in depth for n, d in depth.items() if d == bound for s in strategy.successors[n]
    )
    if not capped and not beyond:
        note = f"{symbolic}projected from all {len(depth)} nodes a run can reach"
    else:
        note = (
            f"{symbolic}projected from the {len(depth)} nodes within {bound} "
            f"move{'s' if bound != 1 else ''} of the start, not from every node"
        )
        if capped:
            note += f" (stopped at {cap} nodes)"
        if symbolic and steps is None:
            note += "; --steps K widens the search"
    return project(strategy, domain, sorted(depth), [note], max_rules)
