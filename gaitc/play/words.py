"""The moves of a play in the robot's words: what the environment does, what the robot does.

An environment move is told as the changes it makes to the state before it, in the words
of :mod:`gaitc.core.changes` (``degrade L3``, ``fail L5``, ``switch spill on``) or
``nothing``; the first state as how it starts
(``start with L3 at level 2``). A robot move is told as its gait and where it goes
(``north_a to r0``). Moves that the words cannot tell apart (inputs the decoding does not
show) get the differing values appended, so a list of moves never shows one line twice.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from gaitc.core.changes import between, words
from gaitc.sim.domain import State
from ltlcompiler.model import NO_GAIT

NOTHING = "nothing"


def environment_words(before: State | None, after: State, full: Mapping[str, int]) -> str:
    """The environment's move from ``before`` to ``after`` (its inputs: leg health and
    hazard) as the changes it makes (:func:`gaitc.core.changes.between`), in the words
    ``break an assumption`` and ``--violate`` read back; or how the first state starts when
    ``before`` is None."""
    if before is None:
        parts = [f"{leg} at level {level}" for leg, level in after.health
                 if level != full.get(leg, level)]
        if after.hazard is not None:
            parts.append(f"{after.hazard} on")
        return "start with " + ", ".join(parts) if parts else "start at full health"
    changes = between(dict(before.health), dict(after.health), full, before.hazard,
                      after.hazard)
    return words(changes) or NOTHING


def robot_words(before: State | None, after: State) -> str:
    """The robot's answer: the gait it takes and the region it is in after the move."""
    if after.gait == NO_GAIT or not after.gait:
        if before is None:
            return f"start in {after.region}"
        return f"stay in {after.region}" if after.region == before.region else \
            f"to {after.region} (no gait)"
    return f"{after.gait} to {after.region}"


def distinguished(words: Sequence[str], values: Sequence[Mapping[str, int]]) -> list[str]:
    """``words`` with the values that tell equal lines apart appended (``name=value``)."""
    out = list(words)
    for i, text in enumerate(words):
        same = [j for j, other in enumerate(words) if other == text]
        if len(same) < 2:
            continue
        differ = sorted(name for name in values[i]
                        if any(values[j].get(name) != values[i][name] for j in same))
        out[i] = f"{text} ({', '.join(f'{n}={values[i][n]}' for n in differ)})"
    return out
