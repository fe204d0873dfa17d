"""A play stepped by hand: the legal moves of one side, the other side's answers, undo and redo.

The player is the model under every front end (the terminal app of
:mod:`gaitc.play.terminal`, the notebook widget of :mod:`gaitc.play.widget`) and is usable
on its own from Python. It binds a :class:`gaitc.sim.session.Session` and plays one of
two roles, after the interactive modes of SLUGS (``--interactiveStrategy``) and of LTLMoP's
counter-strategy visualiser:

- :attr:`Role.ENVIRONMENT`: the user picks the environment's inputs (which legs degrade or
  fail, which hazard is on) among the ones the controller accepts, which for a complete
  controller are exactly those the assumptions allow; the controller answers (Mealy).
- :attr:`Role.ROBOT`: for an unrealizable spec the roles swap. The environment follows its
  counter-strategy (:mod:`gaitc.solver.counter`), whose nodes fix its next input and list
  every answer the robot's guarantees allow; the user picks one, and each choice says why
  it loses: a dead end the environment forces within k steps, a goal it can no longer
  reach, or the goal every loop from there misses.

Each step is decoded and checked by the run monitor as in ``gaitc simulate``; the play
(:attr:`Player.play`, a :class:`gaitc.sim.play.Play` like ``explain``'s and ``simulate``'s
counter-plays) is a :class:`gaitc.sim.run.Run` at any time (:func:`gaitc.sim.replay.replay`),
saved in the format that ``render map --run`` draws and ``simulate --env scripted
RUN.jsonl`` replays.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from gaitc.core.modes import ControllerKind, Role
from gaitc.diagnostics import UsageError
from gaitc.diagnostics.choices import Choice as Named
from gaitc.play.words import distinguished, environment_words, robot_words
from gaitc.sim.counterplay import careful_chooser, random_chooser
from gaitc.sim.domain import State
from gaitc.sim.environments import AdversarialEnvironment, Environment, RandomEnvironment
from gaitc.sim.play import Losses, Play, pursued
from gaitc.sim.replay import follow, last_step, replay
from gaitc.sim.run import Run, Step, save_run
from gaitc.sim.simulator import Simulator
from gaitc.sim.strategy import explicit

if TYPE_CHECKING:
    from gaitc.sim.session import Session


class Autopilot(Named):
    """Who plays the user's side for a few steps."""

    STRONGEST = "strongest"  # the adversarial environment, or the robot that holds out longest
    RANDOM = "random"  # uniform among the legal moves (seeded)


#: What the player writes as the environment of a saved run.
BY_HAND = "played by hand"


@dataclass(frozen=True)
class Choice:
    """One legal move of the user's side, with the other side's part of the same step."""

    number: int  # 1-based, as the move lists show it
    words: str  # the user's move, in the robot's words
    node: int  # the controller (or counter-strategy) node the move leads to
    state: State
    answer: str  # the other side's part: the controller's answer, or the environment's input
    loses_in: int | None = None  # robot role: a dead end is forced within this many steps
    why: str = ""  # robot role: why this choice loses

    def __str__(self) -> str:
        return f"{self.number}. {self.words}"


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

    def __init__(self, session: Session, role: Role | str | None = None) -> None:
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
        self.domain = session.domain
        self.strategy = session.strategy
        self._sim = Simulator(session.strategy, session.domain, session.monitor)
        self._full = session.full_health
        self._path: list[int] = []
        self._steps: list[Step] = []
        self._goal: list[int] = []  # per step, the index of the goal pursued after it
        self._future: list[int] = []  # undone nodes, the next one last
        self._choices: dict[int, tuple[Choice, ...]] = {}
        self._adversary: AdversarialEnvironment | None = None
        self._losses: Losses | None = None
        if wanted is Role.ROBOT:
            counter_strategy = explicit(session.strategy, "playing the robot")
            states = [self._sim.state(n) for n in range(len(counter_strategy))]
            self._losses = Losses(counter_strategy, states, session.domain)

    # ------------------------------------------------------------------ where the play is
    @property
    def path(self) -> tuple[int, ...]:
        """The controller nodes of the play so far."""
        return tuple(self._path)

    @property
    def play(self) -> Play:
        """The play so far; a deadlock when the side to move has no move left."""
        return Play(self.path, deadlock=self.over is not None)

    @property
    def steps(self) -> tuple[Step, ...]:
        """The decoded states of the play so far (step 0 is the first state)."""
        return tuple(self._steps)

    @property
    def step(self) -> int:
        """The index of the last state played (-1 before the first)."""
        return len(self._path) - 1

    @property
    def length(self) -> int:
        """The number of states played and undone: :meth:`jump` reaches ``0..length - 1``."""
        return len(self._path) + len(self._future)

    @property
    def state(self) -> Step | None:
        """The last state played (None before the first)."""
        return self._steps[-1] if self._steps else None

    @property
    def goal(self) -> str | None:
        """The label of the goal the robot is to reach next (the goals taken in turn)."""
        goals = self.domain.goals
        if not goals:
            return None
        return goals[self._goal[-1] if self._goal else 0].label

    @property
    def over(self) -> str | None:
        """Why no move is left, or None while the play goes on."""
        if self._path and not self._options(self._path[-1]):
            if self.role is Role.ROBOT:
                return (f"step {self.step}: dead end: the robot has no move that keeps its "
                        "guarantees; the environment wins")
            return (f"step {self.step}: controller node {self._path[-1]} has no successor; "
                    "it is not a winning strategy for this spec")
        return None

    def pending(self) -> str:
        """Robot role: the environment's next move, which the counter-strategy fixes."""
        found = self.choices()
        return found[0].answer if found and self.role is Role.ROBOT else ""

    # ------------------------------------------------------------------ the legal moves
    def _options(self, node: int | None) -> tuple[int, ...]:
        if self.role is Role.ROBOT:
            return (tuple(self.strategy.initial) if node is None
                    else tuple(self.strategy.successors[node]))
        return tuple(m.node for m in self._sim.moves(node))

    def choices(self) -> tuple[Choice, ...]:
        """The legal moves of the user's side from here, numbered from 1."""
        node = self._path[-1] if self._path else None
        key = -1 if node is None else node
        found = self._choices.get(key)
        if found is None:
            found = self._make_choices(node)
            self._choices[key] = found
        return found

    def _make_choices(self, node: int | None) -> tuple[Choice, ...]:
        before = None if node is None else self._sim.state(node)
        nodes = self._options(node)
        states = [self._sim.state(n) for n in nodes]
        env = [environment_words(before, s, self._full) for s in states]
        robot = [robot_words(before, s) for s in states]
        if self.role is Role.ENVIRONMENT:
            inputs = [dict(zip(self.strategy.inputs, self.strategy.input_key(n), strict=True))
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

    def _find(self, move: int | str) -> Choice:
        found = self.choices()
        if not found:
            raise UsageError(self.over or "no move is left")
        if isinstance(move, int) and not isinstance(move, bool):
            if 1 <= move <= len(found):
                return found[move - 1]
            raise UsageError(f"there are {len(found)} moves here; choose one of 1..{len(found)}")
        wanted = str(move).strip().lower()
        for choice in found:
            if choice.words.lower() == wanted:
                return choice
        listed = "; ".join(c.words for c in found[:8]) + ("; ..." if len(found) > 8 else "")
        raise UsageError(f"'{move}' is not a legal move here; the moves are: {listed}")

    # ------------------------------------------------------------------ playing
    def choose(self, move: int | str) -> Step:
        """Play ``move`` (its number in :meth:`choices`, or its words) and return the new
        state; the undone moves are forgotten."""
        choice = self._find(move)
        self._future.clear()
        return self._push(choice.node)

    def _push(self, node: int) -> Step:
        previous = self._steps[-1] if self._steps else None
        step = self._sim.step(len(self._path), node, previous)
        index = pursued(self.domain.goals, self._goal[-1] if self._goal else 0, step.goals)
        self._path.append(node)
        self._steps.append(step)
        self._goal.append(index)
        return step

    def undo(self) -> bool:
        """Take the last move back (False when there is none)."""
        if not self._path:
            return False
        self._future.append(self._path.pop())
        self._steps.pop()
        self._goal.pop()
        return True

    def redo(self) -> bool:
        """Play the last undone move again (False when there is none)."""
        if not self._future:
            return False
        self._push(self._future.pop())
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
        adversarial`` of a counter-strategy).
        """
        if steps < 0:
            raise UsageError("the number of steps must not be negative")
        kind = Autopilot(pilot)
        self._future.clear()
        played = 0
        rng = random.Random(f"{seed}:{len(self._path)}")
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
        while played < steps:
            node = self._path[-1] if self._path else None
            options = self._options(node)
            if not options:
                break
            if environment is not None:
                target = self._environment_move(environment, node)
            else:
                assert robot is not None
                target = options[robot(self._path, options)]
            if target is None:
                break
            self._push(target)
            played += 1
        return played

    def _environment_move(self, environment: Environment, node: int | None) -> int | None:
        goals = self.domain.goals
        situation = self._sim.situation(
            len(self._path), node, goals[self._goal[-1] if self._goal else 0] if goals else None)
        request = environment.choose(situation)
        if request is None:
            return None
        return next((m.node for m in situation.moves if m.inputs == request.inputs), None)

    # ------------------------------------------------------------------ the play as a run
    def run(self) -> Run:
        """The play so far as a run checked against the spec (``simulate``'s format)."""
        return replay(self._sim, self.play.path, self.session.spec.path,
                      f"{BY_HAND} ({self.role})", self.over)

    def save(self, path: str | Path) -> Run:
        """Save the play as a run file (``.jsonl``: ``render map --run`` draws it and
        ``simulate --env scripted`` replays it; ``.csv``: a table)."""
        run = self.run()
        save_run(run, path)
        return run

    def resume(self, run: Run, at: int | None = None) -> None:
        """Replay steps ``0..at`` of ``run`` (a run file of this spec: a saved play, a
        simulation, or explain's play) and go on from there; ``at`` defaults to its last."""
        last = last_step(run, self.domain.legs, at)
        self.jump(-1)
        self._future.clear()
        if self.role is Role.ENVIRONMENT:
            played = follow(run, last, self.strategy.inputs, self._options,
                            self.strategy.input_key, "the controller accepts no such input")
        else:
            played = follow(run, last, self.strategy.variables, self._options,
                            lambda n: self.strategy.values[n],
                            "the counter-strategy has no such move")
        for node in played:
            self._push(node)

    def __repr__(self) -> str:
        return (f"<gaitc.Player of {self.session.spec.path!r}: you play the {self.role}, "
                f"step {self.step}, {len(self.choices())} moves>")

    def _repr_svg_(self) -> str:
        from gaitc.sim.map_view import run_view

        return run_view(self.run()).svg()

