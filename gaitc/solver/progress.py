"""Progress of a solve, told in the user's words: the :class:`Stage` events a solver emits.

A long solve passes through a few stages a user can follow: building the transition
relation, the fixpoint's rounds over the goals (named as the spec names them, "visit r11"),
the extraction of the controller, the independent check.  Each event carries those words,
the solver's own figures apart (BDD sizes and rounds, shown with ``--verbose`` only), and
the share of the stage done when it is known.  The terminal line that shows them is the
command line's (:mod:`gaitc.cli.status`); a notebook can pass ``print``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from gaitc.ir.roles import Goal
from gaitc.ir.spec import Clause, GR1Spec


@dataclass(frozen=True)
class Stage:
    """One progress event: what is being done, the solver's figures, the share done."""

    words: str
    detail: str = ""
    fraction: float | None = None

    def __str__(self) -> str:
        return f"{self.words} ({self.detail})" if self.detail else self.words


#: Called with every event of a solve; events come often, so a display should throttle.
Progress = Callable[[Stage], None]


def goal_titles(spec: GR1Spec) -> tuple[str, ...]:
    """A short name per system goal: the .gait text ("visit r11"), else its line."""
    return tuple(_title(c, k) for k, c in enumerate(spec.sys_liveness, start=1))


def _title(clause: Clause, number: int) -> str:
    origin = clause.origin
    if origin is not None and isinstance(origin.role, Goal):
        return origin.role.title
    if origin is not None and origin.span is not None:
        return f"line {origin.span.line}"
    return f"goal {number}"
