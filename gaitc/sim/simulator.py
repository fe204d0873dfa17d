"""Stepping a controller: the environment picks inputs, the controller answers (Mealy machine).

Every state is decoded into domain terms and every step is checked by the
:class:`~gaitc.sim.monitor.Monitor` against the spec's clauses, not trusted from the
controller.  A request the controller cannot follow stops the run with a message naming
the assumption it breaks (the clause's origin rule) and the step.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from typing import TYPE_CHECKING, Any

from gaitc.core.modes import SurprisePolicy
from gaitc.diagnostics import ControllerError, GaitcError, ScenarioError, Span
from gaitc.ir.spec import Semantics
from gaitc.sim.domain import Domain, Goal, State
from gaitc.sim.environments import Environment, Move, Request, Situation
from gaitc.sim.events import ALLOWED_NOTE, Event, Surprise, broken_words
from gaitc.sim.jumps import Jump, forced, jump
from gaitc.sim.monitor import Monitor, Violation
from gaitc.sim.play import pursued
from gaitc.sim.recovery import Fallback
from gaitc.sim.run import Run, Step, Summary, dropped_at
from gaitc.sim.strategy import InputKey, Strategy, StrategyView

if TYPE_CHECKING:
    from gaitc.sim.recovery import Fallback

MAX_REPORTED = 20


@dataclass
class Verdicts:
    """The run monitor's findings along a run: the safety clauses broken, and how many
    times each □◇ assumption and guarantee held (by index)."""

    violations: list[Violation] = field(default_factory=list)
    env_live: Counter[int] = field(default_factory=Counter)
    sys_live: Counter[int] = field(default_factory=Counter)


@dataclass(frozen=True)
class SurpriseOptions:
    """How a run meets surprises: the events planned by step (``--violate``), what to do
    when an input breaks an assumption, and the semantics of the games recovery solves."""

    planned: Mapping[int, Event] = field(default_factory=dict)
    policy: SurprisePolicy = SurprisePolicy.RECOVER
    semantics: Semantics = Semantics.DEFAULT
    #: the games recovery solves, shared by the runs given the same options (solved when
    #: first needed); None: each run solves its own
    fallback: Fallback | None = field(default=None, compare=False)


class Simulator:
    """Runs one environment against one controller; decodes and checks every step."""

    def __init__(self, strategy: StrategyView, domain: Domain, monitor: Monitor) -> None:
        if strategy.variables != monitor.variables:
            raise ControllerError("controller and spec list different variables")
        self.strategy = strategy
        self.domain = domain
        self.monitor = monitor
        self._states: dict[int, State] = {}
        self._moves: dict[int, tuple[Move, ...]] = {}
        self._values: dict[int, tuple[tuple[str, int], ...]] = {}
        self._steps: dict[tuple[int, int], Step] = {}
        self._fields: dict[tuple[int, int], tuple[Any, ...]] = {}
        self._by_values: dict[tuple[int, ...], State] = {}
        self._succ_values: dict[int, tuple[tuple[int, ...], ...]] = {}
        self._fallback: Fallback | None = None  # the games recovery solves, made when needed

    def state(self, node: int) -> State:
        found = self._states.get(node)
        if found is None:
            values = self.strategy.values[node]
            found = self._by_values.get(values)
            if found is None:
                found = self.domain.node_state(self.strategy, node)
                self._by_values[values] = found
            self._states[node] = found
        return found

    def moves(self, node: int | None) -> tuple[Move, ...]:
        key = -1 if node is None else node
        found = self._moves.get(key)
        if found is None:
            options = (self.strategy.initial_options() if node is None
                       else self.strategy.options(node))
            found = tuple(Move(k, n, self.state(n)) for k, n in options.items())
            self._moves[key] = found
        return found

    def _successor_values(self, node: int | None,
                          moves: tuple[Move, ...]) -> tuple[tuple[int, ...], ...]:
        key = -1 if node is None else node
        found = self._succ_values.get(key)
        if found is None:
            found = tuple(self.strategy.values[m.node] for m in moves)
            self._succ_values[key] = found
        return found

    def _named(self, node: int) -> tuple[tuple[str, int], ...]:
        found = self._values.get(node)
        if found is None:
            found = tuple(sorted(zip(self.strategy.variables, self.strategy.values[node],
                                     strict=True)))
            self._values[node] = found
        return found

    def step(self, index: int, node: int, previous: Step | None, foreign: bool = False
             ) -> Step:
        """Step ``index`` of a run: ``node`` decoded, compared with ``previous`` (a state of
        another controller when ``foreign``: the run jumped here after a surprise)."""
        return self._step(index, node, previous, foreign)

    def situation(self, index: int, node: int | None, goal: Goal | None) -> Situation:
        """What an environment sees before choosing the input of step ``index`` at ``node``
        (None before the first state), the robot pursuing ``goal``."""
        moves = self.moves(node)
        return Situation(
            step=index,
            node=node,
            state=None if node is None else self.state(node),
            moves=moves,
            domain=self.domain,
            next_goal=goal,
            monitor=self.monitor,
            values=None if node is None else self.strategy.values[node],
            successor_values=self._successor_values(node, moves),
            strategy=self.strategy if isinstance(self.strategy, Strategy) else None,
        )

    def observe(self, verdicts: Verdicts, index: int, before: tuple[int, ...] | None,
                values: tuple[int, ...]) -> None:
        """Check the move into ``values`` at step ``index`` (the first state when there is
        no ``before``) and add what the monitor finds to ``verdicts``."""
        verdicts.violations.extend(self.check(index, before, values))
        held_env, held_sys = self.monitor.liveness_at(before, values)
        verdicts.env_live.update(held_env)
        verdicts.sys_live.update(held_sys)

    def check(self, index: int, before: tuple[int, ...] | None,
              values: tuple[int, ...]) -> list[Violation]:
        """The clauses broken by the move into ``values`` at step ``index`` (the initial
        clauses when there is no ``before``)."""
        if before is None:
            return self.monitor.check_initial(values)
        found = self.monitor.check_step(before, values)
        return ([self.monitor.violation(index, "env_trans", i) for i in found.env_failed]
                + [self.monitor.violation(index, "sys_trans", i) for i in found.sys_failed])

    def _step(self, index: int, node: int, previous: Step | None,
              foreign: bool = False) -> Step:
        """Step ``index`` at ``node`` after ``previous``; ``foreign`` when ``previous`` is a
        node of another controller (the run jumped here after a surprise)."""
        if foreign:
            return replace(self._new_step(node, previous, foreign), index=index)
        key = (node, -1 if previous is None else previous.node)
        found = self._steps.get(key)
        if found is None:
            found = self._new_step(node, previous)
            self._steps[key] = found
            self._fields[key] = tuple(getattr(found, f.name) for f in fields(Step))[1:]
        return Step(index, *self._fields[key])

    def _new_step(self, node: int, previous: Step | None, foreign: bool = False) -> Step:
        st = self.state(node)
        repaired: list[str] = []
        if previous is not None:
            before = dict(previous.health)
            repaired = [leg for leg, level in st.health if level > before.get(leg, level)]
        prev_state = None if previous is None else (
            self.domain.decode(dict(previous.values)) if foreign else self.state(previous.node))
        # degraded/failed are set on this step once the next one is known (Run.add)
        return Step(
            index=0,
            node=node,
            region=st.region,
            gait=st.gait,
            legs_used=self.domain.legs_used(st.gait),
            health=st.health,
            hazard=st.hazard,
            goals=self.domain.goals_reached(st, prev_state),
            degraded=(),
            failed=(),
            repaired=tuple(repaired),
            values=self._named(node),
        )

    def _input_names(self, inputs: InputKey) -> dict[str, int]:
        return dict(zip(self.strategy.inputs, inputs, strict=True))

    def _refuse(self, index: int, node: int | None, request: Request) -> GaitcError:
        """The error for a request the controller has no successor for."""
        what = f" ({request.what})" if request.what else ""
        span = request.span if isinstance(request.span, Span) else None
        if node is None:
            return ControllerError(
                f"step 0{what}: no initial state of the controller has these inputs; the "
                "initial assumptions may forbid them", span)
        if not self.strategy.successors[node]:
            return ControllerError(
                f"step {index}: controller node {node} has no successor (a dead end); "
                "the controller is not a winning strategy for this spec", span)
        failed = self.monitor.failed_assumptions(self.strategy.values[node],
                                                 self._input_names(request.inputs))
        if failed:
            rules = "; ".join(f"'{self.monitor.rule('env_trans', i)}'" for i in failed[:3])
            more = f" (and {len(failed) - 3} more)" if len(failed) > 3 else ""
            cls = ScenarioError if span is not None else ControllerError
            told = self._told(index, node, request, failed)
            return cls(f"step {index}{what}: {told}: the environment breaks the assumption "
                       f"{rules}{more}; the controller has no successor for this input", span)
        return ControllerError(
            f"step {index}{what}: the controller has no successor for an input the "
            "assumptions allow; it is incomplete for this spec", span)

    def run(self, environment: Environment, steps: int, spec_file: str = "",
            surprises: SurpriseOptions | None = None) -> Run:
        """Simulate up to ``steps`` transitions (``steps + 1`` states) and summarize.

        Without ``surprises``, an input the controller has no move for ends the run with an
        error naming the assumption it breaks.  With them, the planned events are performed
        whatever the assumptions say, and under :attr:`SurprisePolicy.RECOVER` an input
        that breaks ρe is recovered from (:mod:`gaitc.sim.recovery`): the run goes on, with
        every goal or fewer, or heads for a cache and stops; each such event is recorded in
        :attr:`Run.surprises`."""
        run = Run(legs=self.domain.legs, environment=environment.name, spec_file=spec_file,
                  model=self.domain.model)
        opts = surprises or SurpriseOptions(policy=SurprisePolicy.STOP)
        goals = self.domain.goals
        goal_index = 0
        verdicts = Verdicts()
        node: int | None = None
        previous: Step | None = None
        sim = previous_sim = self
        caches: tuple[str, ...] = ()  # a stopped robot heads for these, then halts
        for index in range(steps + 1):
            situation = sim.situation(index, node, goals[goal_index] if goals else None)
            moves = situation.moves
            event = opts.planned.get(index) if node is not None else None
            try:
                if node is not None and not moves and event is None:
                    raise sim._refuse(index, node, Request(()))
                request = (forced(sim, node, event) if node is not None and event is not None
                           else environment.choose(situation))
                if request is None:
                    break
                chosen = next((m for m in moves if m.inputs == request.inputs), None)
                if chosen is None and (node is None or opts.policy == SurprisePolicy.STOP
                                       or not sim.breaks(node, request)):
                    raise sim._refuse(index, node, request)
            except GaitcError as err:
                run.error = err
                break
            assert node is not None or chosen is not None
            before = None if node is None else sim.strategy.values[node]
            pursuing = self.domain.goals.index(goals[goal_index]) if goals else 0
            if chosen is None:
                assert node is not None
                jumped = sim._jump(index, node, request, pursuing, opts)
                run.surprises.append(jumped.surprise)
                if jumped.sim is None or jumped.node is None:
                    run.halted = jumped.surprise.note
                    break
                sim, target = jumped.sim, jumped.node
                goals, goal_index, caches = jumped.goals, jumped.goal, jumped.caches
            else:
                if event is not None:
                    run.surprises.append(Surprise(index, event.words, None,
                                                  note=ALLOWED_NOTE))
                target = chosen.node
            self.observe(verdicts, index, before, sim.strategy.values[target])
            step = sim._step(index, target, previous, foreign=sim is not previous_sim)
            run.add(step)
            goal_index = pursued(goals, goal_index, step.goals) if goals else 0
            node, previous, previous_sim = target, step, sim
            if caches and step.region in caches:
                run.halted = f"stopped in cache {step.region} (step {index})"
                break
        run.summary = self.summarize(run, verdicts)
        return run

    def breaks(self, node: int, request: Request) -> bool:
        """Whether the request's inputs at ``node`` break an assumption (ρe)."""
        return bool(self.monitor.failed_assumptions(self.strategy.values[node],
                                                    self._input_names(request.inputs)))

    def after(self, node: int, inputs: Mapping[str, int]) -> State:
        """The state at ``node`` with the next ``inputs`` (spec-level names): what the
        environment's move leaves before the robot answers."""
        return self.domain.decode(self.strategy.valuation(node) | dict(inputs))

    def _told(self, index: int, node: int, request: Request, failed: list[int]) -> str:
        """The broken assumption in the robot's words (:func:`gaitc.sim.events.broken_words`)."""
        after = self.after(node, self._input_names(request.inputs))
        broken = [self.monitor.violation(index, "env_trans", i) for i in failed]
        allowed = [m.state for m in self.moves(node)]
        return broken_words(self.state(node), after, self.domain, broken, allowed)

    def _jump(self, index: int, node: int, request: Request, pursuing: int,
              opts: SurpriseOptions) -> Jump:
        """Where the run goes after the request at ``node`` broke an assumption
        (:func:`gaitc.sim.jumps.jump`, with this run's games)."""
        if self._fallback is None:
            self._fallback = opts.fallback or Fallback(self.monitor.spec, self.domain,
                                                       opts.semantics)
        fallback = self._fallback

        def simulator(strategy: StrategyView) -> Simulator:
            found = Simulator(strategy, self.domain, self.monitor)
            found._fallback = fallback
            return found

        return jump(self, fallback, index, node, request, pursuing, simulator)

    def summarize(self, run: Run, verdicts: Verdicts) -> Summary:
        """The summary of ``run`` from the monitor's ``verdicts`` along it."""
        violations, env_live, sys_live = verdicts.violations, verdicts.env_live, verdicts.sys_live
        goal_counts = Counter(label for s in run.steps for label in s.goals)
        caches = Counter(s.region for s in run.steps if s.region in self.domain.model.caches)
        spec = self.monitor.spec
        return Summary(
            steps=max(0, len(run.steps) - 1),
            goal_visits=tuple((g.label, goal_counts[g.label]) for g in self.domain.goals),
            cache_visits=tuple((c, caches[c]) for c in self.domain.model.caches),
            legs_failed=tuple((dropped_at(s, leg), leg) for s in run.steps for leg in s.failed),
            legs_degraded=tuple((dropped_at(s, leg), leg) for s in run.steps
                                for leg in s.degraded),
            assumptions_held=not any(v.is_assumption for v in violations),
            guarantees_held=not any(not v.is_assumption for v in violations),
            violations=tuple(v.describe() for v in violations[:MAX_REPORTED]),
            env_liveness=tuple((self.monitor.rule("env_liveness", i), env_live[i])
                               for i in range(len(spec.env_liveness))),
            sys_liveness=tuple((self.monitor.rule("sys_liveness", i), sys_live[i])
                               for i in range(len(spec.sys_liveness))),
            stopped=run.error.message if run.error is not None else run.halted,
        )


def simulate(strategy: StrategyView, domain: Domain, monitor: Monitor, environment: Environment,
             steps: int = 50, spec_file: str = "", surprises: SurpriseOptions | None = None
             ) -> Run:
    """Simulate ``environment`` against ``strategy`` for up to ``steps`` steps (meeting
    ``surprises`` as :meth:`Simulator.run` says)."""
    return Simulator(strategy, domain, monitor).run(environment, steps, spec_file, surprises)
