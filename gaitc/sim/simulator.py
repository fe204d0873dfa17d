"""Stepping a controller: the environment picks inputs, the controller answers (Mealy machine).

Every state is decoded into domain terms and every step is checked by the
:class:`~gaitc.sim.monitor.Monitor` against the spec's clauses, not trusted from the
controller.  A request the controller cannot follow stops the run with a message naming
the assumption it breaks (the clause's origin rule) and the step.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field, fields
from typing import Any

from gaitc.diagnostics import ControllerError, GaitcError, ScenarioError, Span
from gaitc.sim.domain import Domain, Goal, State
from gaitc.sim.environments import Environment, Move, Request, Situation
from gaitc.sim.monitor import Monitor, Violation
from gaitc.sim.play import pursued
from gaitc.sim.run import Run, Step, Summary
from gaitc.sim.strategy import InputKey, Strategy, StrategyView

MAX_REPORTED = 20


@dataclass
class Verdicts:
    """The run monitor's findings along a run: the safety clauses broken, and how many
    times each □◇ assumption and guarantee held (by index)."""

    violations: list[Violation] = field(default_factory=list)
    env_live: Counter[int] = field(default_factory=Counter)
    sys_live: Counter[int] = field(default_factory=Counter)


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

    def step(self, index: int, node: int, previous: Step | None) -> Step:
        """Step ``index`` of a run: ``node`` decoded, compared with ``previous``."""
        return self._step(index, node, previous)

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

    def _step(self, index: int, node: int, previous: Step | None) -> Step:
        key = (node, -1 if previous is None else previous.node)
        found = self._steps.get(key)
        if found is None:
            found = self._new_step(node, previous)
            self._steps[key] = found
            self._fields[key] = tuple(getattr(found, f.name) for f in fields(Step))[1:]
        return Step(index, *self._fields[key])

    def _new_step(self, node: int, previous: Step | None) -> Step:
        st = self.state(node)
        repaired: list[str] = []
        if previous is not None:
            before = dict(previous.health)
            repaired = [leg for leg, level in st.health if level > before.get(leg, level)]
        prev_state = None if previous is None else self.state(previous.node)
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
            return cls(f"step {index}{what}: the environment breaks the assumption "
                       f"{rules}{more}; the controller has no successor for this input", span)
        return ControllerError(
            f"step {index}{what}: the controller has no successor for an input the "
            "assumptions allow; it is incomplete for this spec", span)

    def run(self, environment: Environment, steps: int, spec_file: str = "") -> Run:
        """Simulate up to ``steps`` transitions (``steps + 1`` states) and summarize."""
        run = Run(legs=self.domain.legs, environment=environment.name, spec_file=spec_file,
                  model=self.domain.model)
        goals = self.domain.goals
        goal_index = 0
        verdicts = Verdicts()
        node: int | None = None
        previous: Step | None = None
        for index in range(steps + 1):
            situation = self.situation(index, node, goals[goal_index] if goals else None)
            moves = situation.moves
            try:
                if node is not None and not moves:
                    raise self._refuse(index, node, Request(()))
                request = environment.choose(situation)
                if request is None:
                    break
                chosen = next((m for m in moves if m.inputs == request.inputs), None)
                if chosen is None:
                    raise self._refuse(index, node, request)
            except GaitcError as err:
                run.error = err
                break
            before = None if node is None else self.strategy.values[node]
            self.observe(verdicts, index, before, self.strategy.values[chosen.node])
            step = self._step(index, chosen.node, previous)
            run.add(step)
            goal_index = pursued(goals, goal_index, step.goals)
            node, previous = chosen.node, step
        run.summary = self.summarize(run, verdicts)
        return run

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
            legs_failed=tuple((s.index, leg) for s in run.steps for leg in s.failed),
            legs_degraded=tuple((s.index, leg) for s in run.steps for leg in s.degraded),
            assumptions_held=not any(v.is_assumption for v in violations),
            guarantees_held=not any(not v.is_assumption for v in violations),
            violations=tuple(v.describe() for v in violations[:MAX_REPORTED]),
            env_liveness=tuple((self.monitor.rule("env_liveness", i), env_live[i])
                               for i in range(len(spec.env_liveness))),
            sys_liveness=tuple((self.monitor.rule("sys_liveness", i), sys_live[i])
                               for i in range(len(spec.sys_liveness))),
            stopped=None if run.error is None else run.error.message,
        )


def simulate(strategy: StrategyView, domain: Domain, monitor: Monitor, environment: Environment,
             steps: int = 50, spec_file: str = "") -> Run:
    """Simulate ``environment`` against ``strategy`` for up to ``steps`` steps."""
    return Simulator(strategy, domain, monitor).run(environment, steps, spec_file)
