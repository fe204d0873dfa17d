"""A session: a ``.gait`` spec bound to a controller, its domain and its run monitor, and
the environment a run plays against, named as a typed value.

:class:`Session` is what simulate, play, drive and the pictures run; :class:`Opponent`
says who plays the environment (:class:`~gaitc.core.modes.EnvironmentKind`, with the
scenario or run file a scripted environment reads) and :func:`environment` builds it for a
session.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from gaitc.core.modes import EnvironmentKind
from gaitc.core.spec import Spec
from gaitc.diagnostics import UsageError
from gaitc.sim.domain import Domain
from gaitc.sim.environments import (
    AdversarialEnvironment,
    Environment,
    RandomEnvironment,
    StochasticEnvironment,
)
from gaitc.sim.monitor import Monitor
from gaitc.sim.rates import Rates, StepLaw, load_rates
from gaitc.sim.replay import RunEnvironment
from gaitc.sim.run import read_jsonl
from gaitc.sim.scenario import Scenario, ScriptedEnvironment, load_scenario

if TYPE_CHECKING:
    from gaitc.sim.scenario import Scenario
    from gaitc.sim.view import StrategyView
    from ltlcompiler.model import Model

#: The suffixes of a run file (``gaitc play``, ``simulate --out``); anything else a scripted
#: environment reads is a scenario (``.yaml``).
RUN_SUFFIXES = (".jsonl", ".json")


def is_run_file(path: str | Path) -> bool:
    """Whether a scripted environment's file is a run file (``.jsonl``, ``.json``) rather
    than a scenario (``.yaml``)."""
    return Path(path).suffix.lower() in RUN_SUFFIXES


@dataclass(frozen=True)
class Opponent:
    """Who plays the environment: ``kind``, and for a scripted one the scenario or run file
    it reads."""

    kind: EnvironmentKind = EnvironmentKind.RANDOM
    file: str | None = None
    rates: str | None = None  # the stochastic environment's rates file (gaitc/sim/rates.py)
    wear: float | None = None  # ... and every leg's wear chance over it (--wear P)

    def __post_init__(self) -> None:
        if (self.rates is not None or self.wear is not None) and \
                self.kind != EnvironmentKind.STOCHASTIC:
            raise UsageError("--rates and --wear give the chances of the stochastic "
                             "environment: use --env stochastic")
        if (self.kind == EnvironmentKind.SCRIPTED) != (self.file is not None):
            raise UsageError("a scripted environment reads one scenario or run file: "
                             "--env scripted FILE.yaml or --env scripted RUN.jsonl"
                             if self.file is None else
                             f"the {self.kind} environment takes no file (got '{self.file}')")

    @property
    def replays_run(self) -> bool:
        """A scripted environment that plays a run file's inputs (and robot moves) again."""
        return self.file is not None and is_run_file(self.file)

    @classmethod
    def parse(cls, value: Opponent | EnvironmentKind | str, file: str | None = None
              ) -> Opponent:
        """``value`` as an opponent: a member or name of :class:`EnvironmentKind` (with
        ``file`` for ``scripted``), or the older text ``scripted:FILE``."""
        if isinstance(value, Opponent):
            return value
        if isinstance(value, str) and not isinstance(value, EnvironmentKind):
            head, colon, rest = value.partition(":")
            if colon and head == EnvironmentKind.SCRIPTED.value and file is None:
                return cls(EnvironmentKind.SCRIPTED, rest)
        return cls(EnvironmentKind.parse(value, "environment"), file)

    def __str__(self) -> str:
        words = [str(self.kind)] + ([self.file] if self.file is not None else []) + (
            [f"--rates {self.rates}"] if self.rates is not None else []) + (
            [f"--wear {self.wear:g}"] if self.wear is not None else [])
        return " ".join(words)


@dataclass(frozen=True)
class Session:
    """A ``.gait`` spec with its model, a controller adapted to it, and the run checker."""

    spec: Spec
    model: Model = field(repr=False)
    strategy: StrategyView = field(repr=False)
    domain: Domain = field(repr=False)
    monitor: Monitor = field(repr=False)

    @classmethod
    def bind(cls, spec: Spec, strategy: StrategyView) -> Session:
        """``spec`` (a ``.gait`` spec) bound to the run view of one of its controllers."""
        model = spec.robot
        return cls(spec, model, strategy, Domain(model, spec.robot_encoding), Monitor(spec.gr1))

    @property
    def full_health(self) -> dict[str, int]:
        """Each leg's number of health levels (the table's reference for marks)."""
        return {leg.name: leg.health for leg in self.model.legs}

    def __repr__(self) -> str:
        return (f"<gaitc.Session {self.spec.path!r}: controller of {len(self.strategy)} "
                f"nodes, {len(self.model.legs)} legs>")


def environment(opponent: Opponent | Scenario | Environment, bound: Session, seed: int = 0
                ) -> Environment:
    """The environment ``opponent`` names for a run of ``bound`` (``seed`` for the random
    one), or ``opponent`` itself when it already is one."""
    if isinstance(opponent, Environment):
        return opponent
    if isinstance(opponent, Scenario):
        return ScriptedEnvironment(opponent, bound.strategy.inputs)
    if opponent.kind == EnvironmentKind.RANDOM:
        return RandomEnvironment(seed)
    if opponent.kind == EnvironmentKind.ADVERSARIAL:
        return AdversarialEnvironment()
    if opponent.kind == EnvironmentKind.STOCHASTIC:

        rates = Rates() if opponent.rates is None else load_rates(opponent.rates, bound.model)
        return StochasticEnvironment(StepLaw(bound.model, rates.with_wear(opponent.wear)), seed)
    assert opponent.file is not None  # a scripted opponent reads a file (__post_init__)
    if opponent.replays_run:

        return RunEnvironment(read_jsonl(opponent.file), bound.strategy.inputs,
                              bound.domain.legs)
    return ScriptedEnvironment(load_scenario(opponent.file, bound.model),
                               bound.strategy.inputs)
