"""Explanations: everything :mod:`gaitc.analysis` can say about one spec, as one object.

For an unrealizable spec: the kind of failure and the goals the environment can block
(:mod:`gaitc.analysis.failure`), a minimal core (:mod:`gaitc.analysis.core`), the freedoms
the environment needs (:mod:`gaitc.analysis.freedoms`), a play it wins (chosen by
:mod:`gaitc.sim.counterplay`, told by :mod:`gaitc.analysis.story`) and verified repairs
(:mod:`gaitc.analysis.repairs`). For a realizable one: the sanity checks of
:mod:`gaitc.analysis.sanity`. Rendered as text for the terminal, JSON, or HTML in a notebook.
"""

from __future__ import annotations

import contextlib
import html
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from gaitc.analysis.core import guarantee_core
from gaitc.analysis.failure import Kind, classify
from gaitc.analysis.freedoms import Freedom, needed_freedoms, restricted
from gaitc.analysis.freedoms import freedoms as all_freedoms
from gaitc.analysis.mechanism import connection
from gaitc.analysis.oracle import Oracle
from gaitc.analysis.repairs import Repair, repairs
from gaitc.analysis.sanity import ROBOT, Warning_, player_of, sanity
from gaitc.analysis.story import deadlock_move, last_move, narrate, narrate_values, summarise
from gaitc.analysis.units import GUARANTEE_SECTIONS, Unit, keep_only, units
from gaitc.diagnostics import render, source_lines
from gaitc.ir.controller import Controller
from gaitc.ir.formula import atoms
from gaitc.ir.roles import Goal
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.sim.counterplay import choose_play
from gaitc.sim.domain import Domain
from gaitc.sim.monitor import Monitor
from gaitc.sim.play import Play
from gaitc.sim.replay import replay
from gaitc.sim.simulator import Simulator
from gaitc.sim.strategy import strategy_from_controller
from ltlcompiler.decoding import decode
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.core.spec import Spec
    from gaitc.sim.run import Run
    from ltlcompiler.model import Model


@dataclass(frozen=True)
class Explanation:
    """Why ``file`` is (un)realizable; see the module docstring for each part."""

    file: str
    realizable: bool
    kind: Kind | None = None
    goals: tuple[str, ...] = ()
    core: tuple[Unit, ...] = ()
    freedoms: tuple[Freedom, ...] = ()
    connection: tuple[str, ...] = ()  # how the goal, core and freedoms connect (mechanism)
    play: Play | None = None
    counter: Controller | None = field(default=None, repr=False)
    run: Run | None = field(default=None, repr=False)
    story: tuple[str, ...] = ()
    repairs: tuple[Repair, ...] = ()
    repairs_tried: tuple[str, ...] = ()  # the kinds of edit the repair search tried
    repairs_searched: tuple[tuple[str, str], ...] = ()  # (kind, how far it searched)
    warnings: tuple[Warning_, ...] = ()
    solver_calls: int = 0
    seconds: float = 0.0
    source: str = field(default="", repr=False)
    player: str = ROBOT  # who the spec controls (gaitc.analysis.sanity.player_of)

    @property
    def sane(self) -> bool:
        return self.realizable and not self.warnings

    def verdict(self) -> str:
        return "realizable" if self.realizable else "unrealizable"

    def core_json(self) -> list[dict[str, Any]]:
        lines = source_lines(self.source)
        out = []
        for unit in self.core:
            span = unit.span
            text = lines[span.line - 1].strip() if span and 0 < span.line <= len(lines) else ""
            out.append({"line": span.line if span else None,
                        "column": span.column if span else None,
                        "text": text, "rule": unit.rule, "section": unit.section})
        return out

    def to_json(self) -> dict[str, Any]:
        play: dict[str, Any] | None = None
        if self.play is not None:
            play = {"nodes": list(self.play.path), "deadlock": self.play.deadlock,
                    "loop_start": self.play.loop_start, "story": list(self.story)}
            if self.run is not None:
                play["steps"] = [s.to_json() for s in self.run.steps]
        return {
            "file": self.file, "verdict": self.verdict(), "kind": self.kind,
            "goals": list(self.goals), "core": self.core_json(),
            "environment": [f.to_json() for f in self.freedoms],
            "connection": list(self.connection), "play": play,
            "repairs": [r.to_json() for r in self.repairs],
            "repairs_tried": list(self.repairs_tried),
            "repairs_searched": [{"kind": k, "searched": what}
                                 for k, what in self.repairs_searched],
            "warnings": [w.to_json() for w in self.warnings],
            "solver_calls": self.solver_calls, "seconds": round(self.seconds, 3),
        }

    def lines(self) -> list[str]:
        """The explanation for the terminal."""
        sources = {self.file: self.source} if self.source else None
        if self.realizable:
            out = [f"{self.file}: realizable"]
            if not self.warnings:
                out.append(f"  sanity checks passed: the assumptions can be met, the "
                           f"{self.player} cannot block them, no goal is vacuous, every part "
                           "is used")
            out.extend(f"  warning: {w.message}" for w in self.warnings)
            return out
        out = [f"{self.file}: unrealizable ({self.kind} failure)",
               f"  {kind_text(self.kind, self.player)}"]
        if self.goals:
            out.append(f"  the environment can keep the {self.player} from: "
                       f"{', '.join(self.goals)}")
        elif self.kind == "liveness":
            out.append("  no goal is lost on its own: only the goals together")
        if self.connection:
            out.append("  how:" if len(self.connection) > 1 else f"  how: {self.connection[0]}")
            if len(self.connection) > 1:
                out.extend(f"    - {line}" for line in self.connection)
        if self.core:
            these = ("this guarantee" if len(self.core) == 1
                     else f"these {len(self.core)} guarantees")
            out.append(f"core: {these}, with all the assumptions, cannot be met; dropping "
                       f"{'it' if len(self.core) == 1 else 'any one of them'} makes the spec "
                       "realizable")
            out.extend(render(u.rule, u.span, "note", None, sources) for u in self.core)
        elif self.player == ROBOT:
            out.append("core: the structural rules alone (one region and one gait at a time) "
                       "with the assumptions cannot be met")
        else:
            out.append("core: no guarantee is needed: with the assumptions alone the spec "
                       "cannot be met")
        if self.freedoms:
            out.append("the environment needs only these freedoms to win:")
            out.extend(f"  - {f.describe()}" for f in self.freedoms)
        if self.story:
            out.append("a play the environment wins:")
            out.extend(f"  {line}" for line in self.story)
        if self.repairs:
            out.append("repairs (each verified by solving the edited spec):")
            for number, repair in enumerate(self.repairs, 1):
                out.append(f"  {number}. {repair.change}")
                out.extend(f"       {d}" for d in repair.diff)
        elif self.repairs_tried:
            out.append("no repair found; searched:")
            searched = dict(self.repairs_searched)
            out.extend(f"  - {kind}: {searched[kind]}" if kind in searched else f"  - {kind}"
                       for kind in self.repairs_tried)
        out.append(f"({self.solver_calls} solver calls, {self.seconds:.2f} s)")
        return out

    def __repr__(self) -> str:
        what = f"{self.kind} failure, core of {len(self.core)}, {len(self.repairs)} repairs" \
            if not self.realizable else f"{len(self.warnings)} sanity warning(s)"
        return f"<Explanation {self.file!r}: {self.verdict()}, {what}>"

    def _repr_html_(self) -> str:
        parts = [f"<h4>{html.escape(self.file)}: {self.verdict()}"
                 f"{f' ({self.kind} failure)' if self.kind else ''}</h4>"]
        marked = {u.span.line for u in self.core if u.span is not None}
        if self.source and marked:
            rows = []
            for number, line in enumerate(source_lines(self.source), 1):
                style = " style='background:#fde0dd'" if number in marked else ""
                rows.append(f"<span{style}>{number:4d}  {html.escape(line)}</span>")
            parts.append("<pre>" + "\n".join(rows) + "</pre>")
        parts.append("<pre>" + html.escape("\n".join(self.lines())) + "</pre>")
        if self.run is not None and self.run.model is not None:
            with contextlib.suppress(Exception):
                parts.append(self.run._repr_svg_())
        return "".join(parts)


def kind_text(kind: Kind | None, player: str = ROBOT) -> str:
    """What a failure of ``kind`` means, said of ``player`` (:func:`~gaitc.analysis.sanity.
    player_of`)."""
    if kind == "initial":
        return (f"the {player} cannot choose a legal initial state for some initial state of "
                "the environment")
    if kind == "safety":
        return f"the environment can force the {player} into a state with no legal move"
    if kind == "liveness":
        return (f"the {player} can always move, but the environment can keep it from a goal "
                "for ever")
    return ""


def explain(loaded: Spec, *, semantics: Semantics = Semantics.DEFAULT,
            timeout: float | None = None, with_repairs: bool = True) -> Explanation:
    """Explain ``loaded``; a ``.gait`` spec's model, encoding and source add the robot's
    words: the environment's freedoms, a play in the robot's terms and repairs."""
    started = time.monotonic()
    spec, file, source = loaded.gr1, loaded.path, loaded.text
    model = loaded.model
    encoding = loaded.robot_encoding
    player = player_of(model)
    oracle = Oracle.within(semantics, timeout)
    if oracle.realizable(spec):
        found = sanity(loaded, oracle)
        return Explanation(file, True, warnings=found, solver_calls=oracle.calls,
                           seconds=time.monotonic() - started, source=source, player=player)
    failure = classify(spec, oracle)
    goals = tuple(_goal_label(spec, j) for j in failure.blocked_goals)
    # One story: the core holds the first goal the environment can keep the robot from,
    # the freedoms are those it needs against that core, and the play heads for that goal
    # against an environment with just those freedoms (it wins the whole spec with them,
    # since the spec only adds guarantees to the core).
    lost = failure.blocked_goals[:1]
    core = guarantee_core(spec, oracle, _goal_units(spec, lost))
    freedoms: tuple[Freedom, ...] = ()
    if model is not None:
        freedoms = needed_freedoms(loaded, oracle,
                                   within=keep_only(spec, core, GUARANTEE_SECTIONS))
    focused = spec
    if freedoms and model is not None:
        taken = tuple(f for f in all_freedoms(model) if f not in freedoms)
        focused = restricted(loaded, taken)
    counter = oracle.counterstrategy(focused)
    play = run = None
    story: list[str] = []
    if counter is not None and not counter.initial:
        story = [f"the environment's first state leaves the {player} no initial state that "
                 "keeps its initial guarantees (see the core)"]
    elif counter is not None:
        play = _trying_play(counter, spec, model, encoding, lost or failure.blocked_goals)
        if model is not None:
            run = _run(counter, spec, model, encoding, play, file)
            labels = [_goal_label(spec, j) for j in range(len(spec.sys_liveness))]
            story = [*summarise(run, play, labels, lost), *narrate(
                run, play, labels, _final_move(focused, counter, play, model, encoding, run))]
        else:
            story = narrate_values(counter, play)
    how: tuple[str, ...] = ()
    if model is not None:
        target = lost[0] if lost else None
        how = tuple(connection(model, core, freedoms,
                               sorted(_goal_regions(spec, model, lost)) if lost else [],
                               _goal_label(spec, target) if target is not None else None,
                               run))
    fixes: tuple[Repair, ...] = ()
    tried: tuple[str, ...] = ()
    searched_kinds: tuple[tuple[str, str], ...] = ()
    if with_repairs and model is not None and source:
        visited = [s.region for s in run.steps] if run is not None else []
        failed = sorted({leg for s in run.steps for leg in s.failed}) if run is not None else []
        searched = repairs(model, source, file, encoding, oracle, visited, failed)
        fixes, tried, searched_kinds = searched.found, searched.tried, searched.searched
    return Explanation(
        file=file,
        realizable=False,
        kind=failure.kind,
        goals=goals,
        core=core,
        freedoms=freedoms,
        connection=how,
        play=play,
        counter=counter,
        run=run,
        story=tuple(story),
        repairs=fixes,
        repairs_tried=tried,
        repairs_searched=searched_kinds,
        warnings=(),
        solver_calls=oracle.calls,
        seconds=time.monotonic() - started,
        source=source,
        player=player,
    )


def _goal_units(spec: GR1Spec, goals: tuple[int, ...]) -> tuple[Unit, ...]:
    """The guarantee units of the liveness clauses ``goals`` (indices)."""
    return tuple(u for u in units(spec, GUARANTEE_SECTIONS)
                 if u.section == "sys_liveness" and set(u.indices) & set(goals))


def _final_move(spec: GR1Spec, counter: Controller, play: Play, model: Model,
                encoding: EncodingName, run: Run) -> str | None:
    if not play.deadlock or not run.steps:
        return None

    values = deadlock_move(spec, counter, play.path[-1])
    if values is None:
        return None
    state = Domain(model, encoding).decode(values)
    return last_move(run.steps[-1], state.health, state.hazard)


def _trying_play(counter: Controller, spec: GR1Spec, model: Model | None,
                 encoding: EncodingName | None, blocked: tuple[int, ...]) -> Play:
    """The play in which the robot heads for the goal it is kept from. Where the failure
    analysis named no blocked goal, the robot heads for each goal in turn, and the first
    play that the environment wins by keeping that very goal away is shown."""
    def attempt(goals: tuple[int, ...]) -> Play:
        toward = (_region_progress(counter, spec, model, encoding, goals)
                  if model is not None and encoding is not None else None)
        return choose_play(counter, spec, goals, toward)

    if blocked:
        return attempt(blocked)
    plays = [(j, attempt((j,))) for j in range(len(spec.sys_liveness))]

    inputs = set(counter.inputs)

    def acts(play: Play) -> bool:
        """Whether the environment changes its inputs somewhere on the play (wears a leg,
        switches a hazard): a play that shows its freedoms at work."""
        def env(node: int) -> dict[str, int]:
            return {k: v for k, v in counter.bit_values(node).items() if k in inputs}
        return any(env(a) != env(b) for a, b in zip(play.path, play.path[1:], strict=False))

    def shows(j: int, play: Play) -> tuple[bool, bool, bool, int]:
        """A play worth showing: lost, with the robot moving; best where the environment
        acts (its freedoms at work), then where the robot loses the very goal it heads for,
        then where it tries most (distinct states on its path)."""
        tried = len(set(play.path))
        return ((play.deadlock or bool(play.missed)) and tried > 1, acts(play),
                j in play.missed, tried)

    best = max(plays, key=lambda item: (shows(*item), -item[0]), default=None)
    return best[1] if best is not None and shows(*best)[0] else attempt(())


def _goal_regions(spec: GR1Spec, model: Model, goals: tuple[int, ...]) -> set[str]:
    """The regions the blocked goals (``sys_liveness`` indices) name: the goal statements'
    clauses come first among the liveness clauses, in the order of ``model.goals``."""
    from_goals = [j for j, c in enumerate(spec.sys_liveness)
                  if c.origin is not None and isinstance(c.origin.role, Goal)]
    if len(from_goals) != len(model.goals):
        return set()
    regions = {r.name for r in model.regions}
    found: set[str] = set()
    for j, goal in zip(from_goals, model.goals, strict=True):
        if j in goals:
            found |= {name for name, _ in atoms(goal.formula) if name in regions}
    return found


def _region_progress(counter: Controller, spec: GR1Spec, model: Model,
                     encoding: EncodingName, goals: tuple[int, ...]
                     ) -> Callable[[int], int] | None:
    """For each counter-strategy node, the robot's distance on the map (moves along τ) to
    the regions of the goals it is kept from; None where the goals name no region."""
    targets = _goal_regions(spec, model, goals)
    if not targets:
        return None
    into: dict[str, list[str]] = {}
    for t in model.transitions:
        if t.source != t.target and t.gaits:
            into.setdefault(t.target, []).append(t.source)
    distance = dict.fromkeys(targets, 0)
    queue = deque(targets)
    while queue:
        here = queue.popleft()
        for before in into.get(here, ()):
            if before not in distance:
                distance[before] = distance[here] + 1
                queue.append(before)
    far = len(model.regions) + 1
    regions: dict[int, str] = {}

    def progress(node: int) -> int:
        if node not in regions:
            regions[node] = decode(model, encoding, counter.values(node)).region
        return distance.get(regions[node], far)

    return progress


def _goal_label(spec: GR1Spec, j: int) -> str:
    origin = spec.sys_liveness[j].origin
    if origin is None:
        return f"goal {j + 1}"
    return origin.role.title if isinstance(origin.role, Goal) else origin.rule


def _run(counter: Controller, spec: GR1Spec, model: Model, encoding: EncodingName,
         play: Play, file: str) -> Run:
    """The run of ``play``, every step checked against ``spec``."""
    strategy = strategy_from_controller(counter, spec, file)
    stopped = None
    if play.deadlock:
        stopped = f"step {len(play.path) - 1}: deadlock: the robot has no legal move"
    return replay(Simulator(strategy, Domain(model, encoding), Monitor(spec)), play.path,
                  file, "counter-strategy", stopped)
