"""Condensing a region's controller moves into few readable rules: a decision tree over the
condition variables (goal pursued, hazard, leg bands) whose leaves are the rules.

The tree is grown top-down as in ID3 (Quinlan, "Induction of decision trees", Machine
Learning 1, 1986): each split is a test ``variable = value`` against the rest, the one
that leaves the least entropy of the moves (weighted by how many decisions each side
holds; ties to the first variable and value in display order).  A leaf is made as soon as
it is *exact*: every decision in it has, under its full condition, the same set of moves
as the leaf lists.  So a rule never hides a distinction the condition variables could
make; where a leaf still lists several moves, the controller's memory (its node) decides
between them.  Decisions with the same condition and move are counted once, with a weight.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass


@dataclass(frozen=True)
class Move:
    """What the controller does: the gait it walks and the region it walks into."""

    gait: str
    target: str

    def text(self, region: str) -> str:
        return f"{self.gait} (stays)" if self.target == region else f"{self.gait} → {self.target}"


Decision = tuple[dict[str, str], Move]  # (condition variable → value, the move made)
Condition = tuple[tuple[str, tuple[str, ...]], ...]  # (variable, allowed values), in order
Leaf = tuple[Condition, dict[Move, int]]


@dataclass(frozen=True)
class _Case:
    key: tuple[str, ...]  # the full condition, in variable order
    move: Move
    weight: int
    spread: int  # how many moves the full condition allows


def _entropy(cases: Sequence[_Case]) -> float:
    total = sum(c.weight for c in cases)
    counts: dict[Move, int] = {}
    for c in cases:
        counts[c.move] = counts.get(c.move, 0) + c.weight
    return -sum(n / total * math.log2(n / total) for n in counts.values()) * total


def condense(
    cases: Sequence[Decision],
    names: Sequence[str],
    order: Mapping[str, Mapping[str, int]],
    context: Sequence[str] = (),
) -> list[Leaf]:
    """The rules for ``cases``: leaves of the decision tree, yes-branch first.  A leaf's
    condition lists, per variable it tests, the values it allows (in ``order``); a
    variable whose every value the region sees is allowed is left out.  The variables in
    ``context`` are read off the leaf even when untested (the values its decisions have),
    so a rule says the goal it serves."""
    varying = [n for n in names if len({f[n] for f, _ in cases}) > 1]
    weights: dict[tuple[tuple[str, ...], Move], int] = {}
    for feats, move in cases:
        pair = (tuple(feats[n] for n in varying), move)
        weights[pair] = weights.get(pair, 0) + 1
    moves_of: dict[tuple[str, ...], set[Move]] = {}
    for key, move in weights:
        moves_of.setdefault(key, set()).add(move)
    grouped = [_Case(key, move, w, len(moves_of[key])) for (key, move), w in weights.items()]
    values = [_ordered({c.key[i] for c in grouped}, order[n]) for i, n in enumerate(varying)]
    out: list[tuple[Condition, dict[Move, int], list[_Case]]] = []
    _grow(grouped, [tuple(v) for v in values], (varying, [len(v) for v in values]), out)
    shown = [i for i, n in enumerate(varying) if n in context]
    return [_with_context(leaf, shown, varying, values) for leaf in out]


def _with_context(
    leaf: tuple[Condition, dict[Move, int], list[_Case]],
    shown: Sequence[int],
    varying: Sequence[str],
    values: Sequence[Sequence[str]],
) -> Leaf:
    condition, moves, cases = leaf
    given = dict(condition)
    for i in shown:
        present = tuple(v for v in values[i] if any(c.key[i] == v for c in cases))
        if varying[i] not in given and len(present) < len(values[i]):
            given[varying[i]] = present
    return tuple((n, given[n]) for n in varying if n in given), moves


def _ordered(values: set[str], order: Mapping[str, int]) -> list[str]:
    return sorted(values, key=lambda v: (order.get(v, len(order)), v))


def _grow(
    cases: list[_Case],
    allowed: list[tuple[str, ...]],
    names: tuple[Sequence[str], Sequence[int]],
    out: list[tuple[Condition, dict[Move, int], list[_Case]]],
) -> None:
    """Split ``cases`` (whose variable ``i`` takes the values ``allowed[i]``) until exact;
    ``names`` holds the variables and how many values the region sees of each."""
    moves: dict[Move, int] = {}
    for c in cases:
        moves[c.move] = moves.get(c.move, 0) + c.weight
    if all(c.spread == len(moves) for c in cases):
        variables, sizes = names
        condition = tuple(
            (variables[i], allowed[i]) for i in range(len(variables)) if len(allowed[i]) < sizes[i]
        )
        out.append((condition, moves, cases))
        return
    best: tuple[float, int, str] | None = None
    for i, options in enumerate(allowed):
        present = [v for v in options if any(c.key[i] == v for c in cases)]
        if len(present) < 2:
            continue
        for v in present:
            yes = [c for c in cases if c.key[i] == v]
            no = [c for c in cases if c.key[i] != v]
            score = _entropy(yes) + _entropy(no)
            if best is None or score < best[0] - 1e-9:
                best = (score, i, v)
            if len(present) == 2:
                break  # the other value gives the same split
    assert best is not None  # a leaf that is not exact has two conditions to tell apart
    _, i, v = best
    rest = tuple(x for x in allowed[i] if x != v and any(c.key[i] == x for c in cases))
    _grow([c for c in cases if c.key[i] == v], [*allowed[:i], (v,), *allowed[i + 1 :]], names, out)
    _grow([c for c in cases if c.key[i] != v], [*allowed[:i], rest, *allowed[i + 1 :]], names, out)
