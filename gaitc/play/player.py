"""A play stepped by hand: the legal moves of one side, the other side's answers, undo and redo.

The player is the model under every front end (the terminal app of
:mod:`gaitc.play.terminal`, the notebook widget of :mod:`gaitc.play.widget`) and is usable
on its own from Python. It binds a :class:`gaitc.sim.session.Session` and plays one of
two roles, after the interactive modes of SLUGS (``--interactiveStrategy``) and of LTLMoP's
counter-strategy visualiser:

- :attr:`Role.ENVIRONMENT`: the user picks the environment's inputs (which legs degrade or
  fail, which hazard is on) among the ones the controller accepts, which for a complete
  controller are exactly those the assumptions allow; the controller answers (Mealy).
  Besides them, the "break an assumption" moves of :meth:`Player.breaks` (a leg failing or
  losing a level, a hazard switched, where ρe forbids it) are performed through the
  recovery of ``simulate --violate`` (:mod:`gaitc.sim.jumps`, after Ehlers and Topcu,
  HSCC 2014): the play goes on with the fallback strategy, with every goal, fewer goals,
  or towards a cache where the robot stops.
- :attr:`Role.ROBOT`: for an unrealizable spec the roles swap. The environment follows its
  counter-strategy (:mod:`gaitc.solver.counter`), whose nodes fix its next input and list
  every answer the robot's guarantees allow; the user picks one, and each choice says why
  it loses: a dead end the environment forces within k steps, a goal it can no longer
  reach, or the goal every loop from there misses.

Each step is decoded and checked by the run monitor as in ``gaitc simulate``; the play
(:attr:`Player.play`, a :class:`gaitc.sim.play.Play` like ``explain``'s and ``simulate``'s
counter-plays) is a :class:`gaitc.sim.run.Run` at any time, with the surprises it met,
saved in the format that ``render map --run`` draws and ``simulate --env scripted
RUN.jsonl`` replays.
"""

from __future__ import annotations

import random
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from gaitc.core.modes import ControllerKind, Role
from gaitc.diagnostics import ScenarioError, UsageError
from gaitc.diagnostics.choices import Choice as Named
from gaitc.ir.spec import Semantics
from gaitc.play.words import distinguished, environment_words, robot_words
from gaitc.sim.counterplay import careful_chooser, random_chooser
from gaitc.sim.domain import Goal, State
from gaitc.sim.environments import (
    AdversarialEnvironment,
    Environment,
    RandomEnvironment,
    Request,
)
from gaitc.sim.events import Event, Surprise, parse_event
from gaitc.sim.jumps import breaking, entered, forced, jump
from gaitc.sim.map_view import run_view
from gaitc.sim.play import Losses, Play, pursued
from gaitc.sim.recovery import Fallback
from gaitc.sim.replay import HINT, follow, last_step, recorded, step_span
from gaitc.sim.run import Run, Step, checked_steps, save_run
from gaitc.sim.simulator import Simulator, Verdicts
from gaitc.sim.strategy import explicit

if TYPE_CHECKING:
    from gaitc.sim.recovery import Fallback
    from gaitc.sim.session import Session
    from gaitc.sim.strategy import StrategyView


class Autopilot(Named):
    """Who plays the user's side for a few steps."""

    STRONGEST = "strongest"  # the adversarial environment, or the robot that holds out longest
    RANDOM = "random"  # uniform among the legal moves (seeded)


#: What the player writes as the environment of a saved run.
BY_HAND = "played by hand"
#: The answer shown for a move that breaks an assumption (the recovery decides it).
RECOVERS = "the controller recovers if it can: every goal, fewer goals, or it stops"


@dataclass(frozen=True)
class Choice:
    """One move of the user's side, with the other side's part of the same step; a move
    that breaks an assumption (:meth:`Player.breaks`) has its ``event`` and ``breaks``."""

    number: int  # 1-based, as the move lists show it
    words: str  # the user's move, in the robot's words
    node: int  # the controller (or counter-strategy) node the move leads to (-1: a break)
    state: State
    answer: str  # the other side's part: the controller's answer, or the environment's input
    loses_in: int | None = None  # robot role: a dead end is forced within this many steps
    why: str = ""  # robot role: why this choice loses
    event: Event | None = None  # a move that breaks an assumption: the event performed
    breaks: str = ""  # ... and the first assumption it breaks, in the robot's words

    def __str__(self) -> str:
        return f"{self.number}. {self.words}"


@dataclass(frozen=True)
class Played:
    """One state of a play: the controller it is a node of (after a surprise, a fallback
    strategy), the node, the decoded step, the goals pursued from there and the one next,
    the surprise that led into it, and the caches a stopped robot heads for."""

    sim: Simulator
    node: int
    step: Step
    goals: tuple[Goal, ...]
    goal: int  # index into ``goals``
    surprise: Surprise | None = None
    caches: tuple[str, ...] = ()


class Player:
    """A play of ``session``'s controller (or counter-strategy) stepped by hand.

    Moves are chosen by number or by their words; each returns the new state:

        >>> import gaitc
        >>> player = gaitc.player("specs/patrol_2x2.gait")
        >>> player.choose("start at full health").region
        'nw'
        >>> player.choose("nothing").gait
        'south'
        >>> [(c.words, c.answer) for c in player.choices()]
        [('fail L2', 'stay in sw'), ('nothing', 'stay in sw')]
    """

    def __init__(self, session: Session, role: Role | str | None = None,
                 semantics: Semantics | str = Semantics.DEFAULT) -> None:
        counter = session.strategy.kind == ControllerKind.COUNTERSTRATEGY
        wanted = Role(role) if role is not None else (Role.ROBOT if counter else Role.ENVIRONMENT)
        if wanted is Role.ROBOT and not counter:
            raise UsageError("playing the robot needs the environment's counter-strategy: the "
                             "spec is realizable, so play the environment against its "
                             "controller instead")
        if wanted is Role.ENVIRONMENT and counter:
            raise UsageError("the spec is unrealizable: there is no controller to play the "
                             "environment against; play the robot against the counter-strategy")
        self.session = session
        self.role = wanted
        self.semantics = Semantics.parse(semantics)
        self.domain = session.domain
        self.strategy = session.strategy
        self._sim = Simulator(session.strategy, session.domain, session.monitor)
        self._full = session.full_health
        self._played: list[Played] = []
        self._future: list[Played] = []  # undone states, the next one last
        self._halted: Surprise | None = None  # a surprise after which the robot stopped
        self._choices: dict[tuple[int, int], tuple[Choice, ...]] = {}
        self._breaks: dict[tuple[int, int], tuple[Choice, ...]] = {}
        self._fallback: Fallback | None = None  # the games recovery solves, made when needed
        self._sims: dict[int, Simulator] = {}  # a simulator per fallback strategy
        self._adversary: AdversarialEnvironment | None = None
        self._losses: Losses | None = None
        if wanted is Role.ROBOT:
            counter_strategy = explicit(session.strategy, "playing the robot")
            states = [self._sim.state(n) for n in range(len(counter_strategy))]
            self._losses = Losses(counter_strategy, states, session.domain)

    # ------------------------------------------------------------------ where the play is
    @property
    def path(self) -> tuple[int, ...]:
        """The controller nodes of the play so far (after a surprise, of the fallback
        strategy it went on with)."""
        return tuple(p.node for p in self._played)

    @property
    def play(self) -> Play:
        """The play so far; a deadlock when the side to move has no move left."""
        return Play(self.path, deadlock=self.over is not None)

    @property
    def steps(self) -> tuple[Step, ...]:
        """The decoded states of the play so far (step 0 is the first state)."""
        return tuple(p.step for p in self._played)

    @property
    def step(self) -> int:
        """The index of the last state played (-1 before the first)."""
        return len(self._played) - 1

    @property
    def moves(self) -> int:
        """The steps played after the first state: a run's count of its steps, as its
        summary and ``simulate --steps`` have it (a play of 2 states is 1 step)."""
        return max(0, self.step)

    def played_words(self) -> str:
        """"a play of N step(s)", counted as :attr:`moves`."""
        return f"a play of {self.moves} step{'' if self.moves == 1 else 's'}"

    @property
    def length(self) -> int:
        """The number of states played and undone: :meth:`jump` reaches ``0..length - 1``."""
        return len(self._played) + len(self._future)

    @property
    def state(self) -> Step | None:
        """The last state played (None before the first)."""
        return self._played[-1].step if self._played else None

    @property
    def goal(self) -> str | None:
        """The label of the goal the robot is to reach next (the goals taken in turn; after
        a surprise, only those it still pursues; None when it pursues none)."""
        if not self._played:
            goals = self.domain.goals
            return goals[0].label if goals else None
        last = self._played[-1]
        return last.goals[last.goal].label if last.goals else None

    @property
    def surprises(self) -> tuple[Surprise, ...]:
        """The assumptions broken along the play so far, each with what became of it."""
        found = [p.surprise for p in self._played if p.surprise is not None]
        return (*found, self._halted) if self._halted is not None else tuple(found)

    @property
    def over(self) -> str | None:
        """Why no move is left, or None while the play goes on."""
        if self._halted is not None:
            return f"step {self._halted.step}: {self._halted.note}"
        if not self._played:
            return None
        last = self._played[-1]
        if last.caches and last.step.region in last.caches:
            return f"stopped in cache {last.step.region} (step {last.step.index})"
        if not self._options(last.node):
            if self.role is Role.ROBOT:
                return (f"step {self.step}: dead end: the robot has no move that keeps its "
                        "guarantees; the environment wins")
            return (f"step {self.step}: controller node {last.node} has no successor; "
                    "it is not a winning strategy for this spec")
        return None

    def pending(self) -> str:
        """Robot role: the environment's next move, which the counter-strategy fixes."""
        found = self.choices()
        return found[0].answer if found and self.role is Role.ROBOT else ""

    # ------------------------------------------------------------------ the legal moves
    @property
    def _current(self) -> Simulator:
        """The simulator of the controller the play is in now."""
        return self._played[-1].sim if self._played else self._sim

    def _options(self, node: int | None) -> tuple[int, ...]:
        if self.role is Role.ROBOT:
            return (tuple(self.strategy.initial) if node is None
                    else tuple(self.strategy.successors[node]))
        return tuple(m.node for m in self._current.moves(node))

    def _stopped(self) -> bool:
        last = self._played[-1] if self._played else None
        return self._halted is not None or (
            last is not None and bool(last.caches) and last.step.region in last.caches)

    def choices(self) -> tuple[Choice, ...]:
        """The legal moves of the user's side from here, numbered from 1."""
        if self._stopped():
            return ()
        node = self._played[-1].node if self._played else None
        key = (id(self._current), -1 if node is None else node)
        found = self._choices.get(key)
        if found is None:
            found = self._make_choices(node)
            self._choices[key] = found
        return found

    def breaks(self) -> tuple[Choice, ...]:
        """Environment role: the moves that break an assumption here (numbered after
        :meth:`choices`): for each leg, failing it and taking a level from it, and each
        hazard set switched, where ρe forbids it (:func:`gaitc.sim.jumps.breaking`)."""
        if self.role is not Role.ENVIRONMENT or not self._played or self._stopped():
            return ()
        last = self._played[-1]
        key = (id(last.sim), last.node)
        found = self._breaks.get(key)
        if found is None:
            first = len(self.choices()) + 1
            found = tuple(
                Choice(first + i, b.event.words, -1,
                       b.event.apply(last.sim.state(last.node), self.domain),
                       RECOVERS, event=b.event, breaks=b.breaks)
                for i, b in enumerate(breaking(last.sim, last.node, self.step + 1)))
            self._breaks[key] = found
        return found

    def _make_choices(self, node: int | None) -> tuple[Choice, ...]:
        sim = self._current
        before = None if node is None else sim.state(node)
        nodes = self._options(node)
        states = [sim.state(n) for n in nodes]
        env = [environment_words(before, s, self._full) for s in states]
        robot = [robot_words(before, s) for s in states]
        if self.role is Role.ENVIRONMENT:
            strategy = sim.strategy
            inputs = [dict(zip(strategy.inputs, strategy.input_key(n), strict=True))
                      for n in nodes]
            words, answers = distinguished(env, inputs), robot
        else:
            values = [self.strategy.valuation(n) for n in nodes]
            words, answers = distinguished(robot, values), env
        losses = self._losses
        return tuple(
            Choice(i + 1, words[i], n, states[i], answers[i],
                   None if losses is None else losses.level[n],
                   "" if losses is None else losses.why(n))
            for i, n in enumerate(nodes))

    def _find(self, move: int | str, found: tuple[Choice, ...], first: int = 1) -> Choice:
        if not found:
            raise UsageError(self.over or "no move is left")
        if isinstance(move, int) and not isinstance(move, bool):
            if first <= move < first + len(found):
                return found[move - first]
            raise UsageError(f"there are {len(found)} moves here; choose one of "
                             f"{first}..{first + len(found) - 1}")
        wanted = str(move).strip().lower()
        for choice in found:
            if choice.words.lower() == wanted:
                return choice
        listed = "; ".join(c.words for c in found[:8]) + ("; ..." if len(found) > 8 else "")
        what = "a legal move" if first == 1 else "a move that breaks an assumption"
        raise UsageError(f"'{move}' is not {what} here; the moves are: {listed}")

    # ------------------------------------------------------------------ playing
    def choose(self, move: int | str) -> Step:
        """Play the legal ``move`` (its number in :meth:`choices`, or its words) and
        return the new state; the undone moves are forgotten."""
        choice = self._find(move, self.choices())
        self._future.clear()
        return self._push(choice.node)

    def break_assumption(self, move: int | str | Event) -> Step:
        """Play a move of :meth:`breaks` (its number, its words, or any event of
        :func:`gaitc.sim.events.parse_event`'s words that breaks an assumption here)
        through the recovery; return the new state (the last one when the robot stops
        where it is). The surprise is in :attr:`surprises`, its words in
        :meth:`Surprise.words`."""
        if isinstance(move, Event):
            event = move
        else:
            found = self.breaks()
            first = len(self.choices()) + 1
            if isinstance(move, str) and not any(c.words.lower() == move.strip().lower()
                                                 for c in found):
                event = parse_event(move.strip(), self.domain, "break an assumption")
            else:
                picked = self._find(move, found, first).event
                assert picked is not None
                event = picked
        return self._perform(event)

    def _perform(self, event: Event) -> Step:
        if not self._played or self._stopped():
            raise UsageError(self.over or "an assumption can be broken only after the first "
                             "state")
        last = self._played[-1]
        return self._surprise(forced(last.sim, last.node, event))

    def _surprise(self, request: Request) -> Step:
        """Perform the inputs of ``request`` at the last state, through the recovery."""
        last = self._played[-1]
        sim = last.sim
        if not sim.breaks(last.node, request):
            raise UsageError(f"'{request.what}' breaks no assumption here; play it among the "
                             "legal moves")
        index = len(self._played)
        pursuing = self.domain.goals.index(last.goals[last.goal]) if last.goals else 0
        if self._fallback is None:

            self._fallback = Fallback(self.session.monitor.spec, self.domain, self.semantics)
        jumped = jump(sim, self._fallback, index, last.node, request, pursuing,
                      self._simulator)
        self._future.clear()
        if jumped.sim is None or jumped.node is None:
            self._halted = jumped.surprise
            return last.step
        step = entered(jumped.sim, index, jumped.node, last.step)
        goal = pursued(jumped.goals, jumped.goal, step.goals) if jumped.goals else 0
        self._played.append(Played(jumped.sim, jumped.node, step, jumped.goals, goal,
                                   jumped.surprise, jumped.caches))
        return step

    def _simulator(self, strategy: StrategyView) -> Simulator:
        found = self._sims.get(id(strategy))
        if found is None:
            found = Simulator(strategy, self.domain, self.session.monitor)
            self._sims[id(strategy)] = found
        return found

    def _push(self, node: int) -> Step:
        last = self._played[-1] if self._played else None
        sim = self._current
        step = sim.step(len(self._played), node, None if last is None else last.step)
        goals = self.domain.goals if last is None else last.goals
        goal = 0 if last is None else last.goal
        goal = pursued(goals, goal, step.goals) if goals else 0
        self._played.append(Played(sim, node, step, goals, goal,
                                   caches=() if last is None else last.caches))
        return step

    def undo(self) -> bool:
        """Take the last move back (False when there is none); a surprise after which the
        robot stopped where it was is undone first (and cannot be redone)."""
        if self._halted is not None:
            self._halted = None
            return True
        if not self._played:
            return False
        self._future.append(self._played.pop())
        return True

    def redo(self) -> bool:
        """Play the last undone move again (False when there is none)."""
        if not self._future:
            return False
        self._played.append(self._future.pop())
        return True

    def jump(self, step: int) -> None:
        """Go back or forward (over undone moves) to step ``step``; -1 is before the first."""
        if not -1 <= step < self.length:
            raise UsageError(f"step {step} is not in this play; it has steps 0..{self.length - 1}")
        while self.step > step:
            self.undo()
        while self.step < step:
            self.redo()

    def autoplay(self, steps: int, pilot: Autopilot | str = Autopilot.STRONGEST,
                 seed: int = 0) -> int:
        """Let ``pilot`` play the user's side for up to ``steps`` moves; the number played.

        Playing the environment, the strongest pilot is ``simulate``'s adversarial
        environment (hostile within the assumptions, fair to them); playing the robot, it
        is the robot that avoids forced dead ends and delays them (``simulate --env
        adversarial`` of a counter-strategy). A pilot keeps the assumptions.
        """
        checked_steps(steps)
        kind = Autopilot(pilot)
        self._future.clear()
        played = 0
        rng = random.Random(f"{seed}:{len(self._played)}")
        environment: Environment | None = None
        if self.role is Role.ENVIRONMENT:
            if kind is Autopilot.STRONGEST:
                if self._adversary is None:
                    self._adversary = AdversarialEnvironment()
                environment = self._adversary
            else:
                environment = RandomEnvironment(rng.randrange(2**31))
        robot = None
        if self._losses is not None:
            robot = (careful_chooser(self._losses.level) if kind is Autopilot.STRONGEST
                     else random_chooser(rng))
        while played < steps and not self._stopped():
            node = self._played[-1].node if self._played else None
            options = self._options(node)
            if not options:
                break
            if environment is not None:
                target = self._environment_move(environment, node)
            else:
                assert robot is not None
                target = options[robot(list(self.path), options)]
            if target is None:
                break
            self._push(target)
            played += 1
        return played

    def _environment_move(self, environment: Environment, node: int | None) -> int | None:
        last = self._played[-1] if self._played else None
        goals = self.domain.goals if last is None else last.goals
        goal = goals[0 if last is None else last.goal] if goals else None
        situation = self._current.situation(len(self._played), node, goal)
        request = environment.choose(situation)
        if request is None:
            return None
        return next((m.node for m in situation.moves if m.inputs == request.inputs), None)

    # ------------------------------------------------------------------ the play as a run
    def run(self) -> Run:
        """The play so far as a run checked against the spec (``simulate``'s format), with
        the surprises it met (``violation`` lines in a run file)."""
        run = Run(legs=self.domain.legs, environment=f"{BY_HAND} ({self.role})",
                  spec_file=self.session.spec.path, model=self.domain.model)
        verdicts = Verdicts()
        before: tuple[int, ...] | None = None
        for index, played in enumerate(self._played):
            values = played.sim.strategy.values[played.node]
            self._sim.observe(verdicts, index, before, values)
            run.add(replace(played.step))
            before = values
        run.surprises.extend(self.surprises)
        stopped = self.over
        if self._stopped():
            run.halted = stopped
        summary = self._sim.summarize(run, verdicts)
        run.summary = summary if stopped is None else replace(summary, stopped=stopped)
        return run

    def save(self, path: str | Path) -> Run:
        """Save the play as a run file (``.jsonl``: ``render map --run`` draws it and
        ``simulate --env scripted`` replays it; ``.csv``: a table)."""
        run = self.run()
        save_run(run, path)
        return run

    def resume(self, run: Run, at: int | None = None) -> None:
        """Replay steps ``0..at`` of ``run`` (a run file of this spec: a saved play, a
        simulation, or explain's play) and go on from there; ``at`` defaults to its last.
        A step of the run that broke an assumption (a ``violation`` of the run file) is
        performed again through the recovery."""
        last = last_step(run, self.domain.legs, at)
        self.jump(-1)
        self._future.clear()
        if self.role is Role.ROBOT:
            for move in follow(run, last, self.strategy.variables, self._options,
                               lambda n: self.strategy.values[n],
                               "the counter-strategy has no such move"):
                self._push(move)
            return
        broke = {s.step: s for s in run.surprises if s.assumption is not None}
        for index in range(last + 1):
            wanted = recorded(run, index, self.strategy.inputs)
            node = self._played[-1].node if self._played else None
            key = self._current.strategy.input_key
            found = next((n for n in self._options(node) if key(n) == wanted), None)
            if found is not None:
                self._push(found)
                continue
            surprise = broke.get(index)
            if surprise is None or node is None:
                raise ScenarioError(f"step {index} of the run cannot be played here: the "
                                    "controller accepts no such input", step_span(run, index),
                                    "the run was played against another controller or spec")
            try:  # the recorded inputs, whatever words the run gives the event
                self._surprise(Request(wanted, surprise.event))
            except UsageError as err:
                raise ScenarioError(f"step {index} of the run cannot be played here: "
                                    f"{err.message}", step_span(run, index), HINT) from None
            if self._halted is not None:
                return

    def __repr__(self) -> str:
        return (f"<gaitc.Player of {self.session.spec.path!r}: you play the {self.role}, "
                f"step {self.step}, {len(self.choices())} moves>")

    def _repr_svg_(self) -> str:
        return run_view(self.run()).svg()
