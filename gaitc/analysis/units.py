"""Units: the parts of a spec an explanation may drop, each tied to its source.

A unit is the set of clauses of one section that came from the same place of the source
with the same rule (a goal, a leg's failed-gait rule, the start, a ``guarantee`` line...).
Clauses without a source span are the lowering's structural ones (one region at a time,
one gait, start with noGait) and are never dropped; nor is the map (eq. 3.3, the moves out
of each region): without it the robot could jump anywhere, which explains nothing.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from gaitc.diagnostics import Span
from gaitc.ir.roles import ClauseRole, Moves
from gaitc.ir.spec import SECTIONS, Clause, GR1Spec

GUARANTEE_SECTIONS = ("sys_init", "sys_trans", "sys_liveness")


def is_structural(clause: Clause) -> bool:
    """Whether ``clause`` stays in every variant (no source, or the map's moves: the region
    graph τ, eq. 3.3)."""
    origin = clause.origin
    return origin is None or origin.span is None or isinstance(origin.role, Moves)
ASSUMPTION_SECTIONS = ("env_init", "env_trans", "env_liveness")


@dataclass(frozen=True)
class Unit:
    """Clauses ``indices`` of ``section`` that share one source span and rule (their
    label), and their role (:mod:`gaitc.ir.roles`; None for a SLUGS spec's)."""

    section: str
    indices: tuple[int, ...]
    rule: str
    span: Span | None
    role: ClauseRole | None = None

    @property
    def side(self) -> str:
        return self.section.split("_", 1)[0]

    def where(self) -> str:
        return str(self.span) if self.span is not None else "(generated)"


def units(spec: GR1Spec, sections: Iterable[str]) -> tuple[Unit, ...]:
    """The droppable units of ``sections``, in section then source order."""
    out: list[Unit] = []
    for section in sections:
        groups: dict[tuple[str, str], list[int]] = {}
        spans: dict[tuple[str, str], Span] = {}
        roles: dict[tuple[str, str], ClauseRole | None] = {}
        for index, clause in enumerate(spec.section(section)):
            origin = clause.origin
            if origin is None or origin.span is None or is_structural(clause):
                continue
            key = (str(origin.span), origin.rule)
            groups.setdefault(key, []).append(index)
            spans[key] = origin.span
            roles.setdefault(key, origin.role)
        for key, indices in groups.items():
            out.append(Unit(section, tuple(indices), key[1], spans[key], roles[key]))
    return tuple(out)


def structural(spec: GR1Spec, section: str) -> tuple[int, ...]:
    """The clauses of ``section`` that no unit holds (kept in every variant)."""
    return tuple(i for i, c in enumerate(spec.section(section)) if is_structural(c))


def keep_only(spec: GR1Spec, kept: Iterable[Unit], sections: Iterable[str]) -> GR1Spec:
    """``spec`` with the units of ``sections`` reduced to ``kept`` (structural clauses stay).

    Sections not listed are unchanged.
    """
    chosen: dict[str, set[int]] = {s: set(structural(spec, s)) for s in sections}
    for unit in kept:
        if unit.section in chosen:
            chosen[unit.section].update(unit.indices)
    changes: dict[str, tuple[Clause, ...]] = {}
    for section, indices in chosen.items():
        clauses = spec.section(section)
        changes[section] = tuple(c for i, c in enumerate(clauses) if i in indices)
    return spec.with_sections(**changes)


def with_clauses(spec: GR1Spec, extra: dict[str, list[Clause]]) -> GR1Spec:
    """``spec`` with ``extra`` clauses appended to their sections."""
    changes = {s: spec.section(s) + tuple(extra[s]) for s in SECTIONS if extra.get(s)}
    return spec.with_sections(**changes)
