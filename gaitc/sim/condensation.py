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
Leaf = tuple[Condition, dict[Move, int], bool]  # condition, moves with counts, exact


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
    limit: int | None = None,
) -> list[Leaf]:
    """The rules for ``cases``: leaves of the decision tree, in tree order (yes-branch
    first).  A leaf's condition lists, per variable it tests, the values it allows (in
    ``order``); a variable whose every value the region sees is allowed is left out.  The
    variables in ``context`` are read off the leaf even when untested (the values its
    decisions have), so a rule says the goal it serves.  With ``limit``, the tree stops at
    that many leaves: the most mixed leaf (largest weighted entropy of its moves, first in
    tree order on ties) is split first, and a leaf left unsplit lists every move it covers."""
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
    leaves: list[tuple[list[_Case], list[tuple[str, ...]]]] = [
        (grouped, [tuple(v) for v in values])
    ]
    while limit is None or len(leaves) < limit:
        open_ = [(k, _entropy(c)) for k, (c, _) in enumerate(leaves) if not _exact(c)]
        if not open_:
            break
        k = max(open_, key=lambda ke: (ke[1], -ke[0]))[0]
        leaves[k : k + 1] = _split(*leaves[k])
    out = []
    for leaf_cases, allowed in leaves:
        given = {
            varying[i]: allowed[i] for i in range(len(varying)) if len(allowed[i]) < len(values[i])
        }
        for i, name in enumerate(varying):
            present = tuple(v for v in values[i] if any(c.key[i] == v for c in leaf_cases))
            if name in context and name not in given and len(present) < len(values[i]):
                given[name] = present
        moves: dict[Move, int] = {}
        for c in leaf_cases:
            moves[c.move] = moves.get(c.move, 0) + c.weight
        condition = tuple((n, given[n]) for n in varying if n in given)
        out.append((condition, moves, _exact(leaf_cases)))
    return out


def _ordered(values: set[str], order: Mapping[str, int]) -> list[str]:
    return sorted(values, key=lambda v: (order.get(v, len(order)), v))


def _exact(cases: Sequence[_Case]) -> bool:
    """Whether every case's full condition allows the moves of all ``cases``."""
    moves = len({c.move for c in cases})
    return all(c.spread == moves for c in cases)


def _split(
    cases: list[_Case], allowed: list[tuple[str, ...]]
) -> list[tuple[list[_Case], list[tuple[str, ...]]]]:
    """The best test ``variable = value`` on ``cases`` (least entropy left), as two leaves."""
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
    return [
        ([c for c in cases if c.key[i] == v], [*allowed[:i], (v,), *allowed[i + 1 :]]),
        ([c for c in cases if c.key[i] != v], [*allowed[:i], rest, *allowed[i + 1 :]]),
    ]
