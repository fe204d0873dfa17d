"""The GR(1) specification IR: variables and the six named sections of clauses.

A :class:`GR1Spec` is what every reader produces (the .gait compiler, the
``.slugsin`` and ``.structuredslugs`` readers) and what every emitter and the
solver consume.  Each :class:`Clause` keeps an :class:`Origin` (rule and source
span) that does not count in equality; diagnosis and comments in the output use it.

Sections follow the GR(1) game of Bloem et al. (JCSS 2012) and SLUGS: ``env_init``
and ``sys_init`` (unprimed), ``env_trans`` and ``sys_trans`` (may use primes), and
``env_liveness`` / ``sys_liveness`` (□◇ of each clause; primes allowed, as in SLUGS).
The two modes of the game every layer shares live here too: :class:`Semantics` (how the
initial states are read) and :class:`ControllerKind` (whose strategy an automaton is).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Final, Literal, get_args

from gaitc.diagnostics import Span
from gaitc.diagnostics.choices import Choice
from gaitc.ir.formula import Expr
from gaitc.ir.roles import ClauseRole

Section = Literal["env_init", "sys_init", "env_trans", "sys_trans", "env_liveness", "sys_liveness"]
#: The six sections, in the canonical order of SLUGS's files.
SECTIONS: Final[tuple[Section, ...]] = get_args(Section)


def section_named(player: str, part: str) -> Section:
    """The section of ``player`` (env, sys) and ``part`` (init, trans, liveness)."""
    for known in SECTIONS:
        if known == f"{player}_{part}":
            return known
    raise ValueError(f"no section {player}_{part}; the sections are {', '.join(SECTIONS)}")


class Semantics(Choice):
    """How the initial condition is read: ``default``, for every input allowed by θe some
    output satisfying θs is winning (SLUGS's default); ``robotics``, every state allowed by
    θe ∧ θs is winning (SLUGS's ``--sysInitRoboticsSemantics``)."""

    DEFAULT = "default"
    ROBOTICS = "robotics"


SEMANTICS: Final = tuple(Semantics)


def semantics_named(name: str) -> Semantics:
    """``name`` as a :data:`Semantics`; :class:`ValueError` names the choices otherwise."""
    for known in SEMANTICS:
        if name == known:
            return known
    raise ValueError(f"unknown semantics {name!r}; use one of {', '.join(SEMANTICS)}")


class ControllerKind(Choice):
    """Whose winning strategy an automaton is (the game of a spec has two players; the
    automata of :mod:`gaitc.ir.controller` and :mod:`gaitc.ir.bddfile` record which)."""

    STRATEGY = "strategy"  # the system's: a controller the robot runs
    COUNTERSTRATEGY = "counterstrategy"  # the environment's: how it defeats every controller


@dataclass(frozen=True)
class Origin:
    """Where a clause came from: the rule that generated it (a label for people), the
    source span, and what it says about the robot's world (:mod:`gaitc.ir.roles`; None for
    clauses of SLUGS specs and those an analysis adds).  Meaning is read from the role."""

    rule: str
    span: Span | None = None
    role: ClauseRole | None = None


@dataclass(frozen=True)
class Variable:
    """A Boolean variable, or an integer one with the inclusive range ``low..high``."""

    name: str
    low: int | None = None
    high: int | None = None
    span: Span | None = field(default=None, compare=False, repr=False)

    @property
    def is_integer(self) -> bool:
        return self.low is not None

    @property
    def bits(self) -> int:
        """Number of bits SLUGS uses for this variable (1 for a Boolean)."""
        if self.low is None or self.high is None:
            return 1
        width = self.high - self.low
        n = 1
        while (1 << n) <= width:
            n += 1
        return n if width > 0 else 1


@dataclass(frozen=True)
class Clause:
    """One conjunct of a section, with its origin (not part of equality)."""

    formula: Expr
    origin: Origin | None = field(default=None, compare=False)


@dataclass(frozen=True)
class GR1Spec:
    """A GR(1) specification: inputs (environment), outputs (system), six sections."""

    inputs: tuple[Variable, ...] = ()
    outputs: tuple[Variable, ...] = ()
    env_init: tuple[Clause, ...] = ()
    sys_init: tuple[Clause, ...] = ()
    env_trans: tuple[Clause, ...] = ()
    sys_trans: tuple[Clause, ...] = ()
    env_liveness: tuple[Clause, ...] = ()
    sys_liveness: tuple[Clause, ...] = ()
    name: str = field(default="", compare=False)

    def section(self, name: str) -> tuple[Clause, ...]:
        if name not in SECTIONS:
            raise KeyError(name)
        value: tuple[Clause, ...] = getattr(self, name)
        return value

    def variables(self) -> tuple[Variable, ...]:
        return self.inputs + self.outputs

    def variable(self, name: str) -> Variable | None:
        for v in self.inputs + self.outputs:
            if v.name == name:
                return v
        return None

    def with_sections(self, **sections: tuple[Clause, ...]) -> GR1Spec:
        return replace(self, **sections)  # type: ignore[arg-type]

    @property
    def has_integers(self) -> bool:
        return any(v.is_integer for v in self.inputs + self.outputs)
