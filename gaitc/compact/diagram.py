"""Decision diagrams over fields: a controller's choices, with its freedom used to shrink them.

A strategy relation S(x, y, x', y') of a solved GR(1) game allows, at most states, several
moves; any function that picks one of them wins (Bloem et al., JCSS 78(3) 2012, Sect. 5).
Extracting one bit of y' at a time, as circuit synthesis does, and minimising each with the
don't-cares of the other bits (Coudert and Madre's restrict) is the classic way to spend that
freedom.  Here it is spent on readability instead: the diagram branches on whole fields
(:mod:`gaitc.core.vocabulary`) in a fixed order and stops at the first point where one move
is allowed in every state left, so a leaf says "whatever the rest, make this move".  A child
whose states are all outside the care set (no reachable state of the game goes there) takes
the most common sibling, and equal children collapse their parent: the result is a reduced,
ordered multi-valued decision diagram (Srinivasan, Kam, Malik, Brayton, ICCAD 1990) whose
size depends on the field order, which :func:`build` lets the caller choose (the caller
tries several and keeps the smallest, the analogue of reordering).

Node references: ``r >= 0`` is node ``r``; ``r < 0`` is leaf ``-r - 1`` (a move index, or 0/1
for a boolean diagram).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias

from gaitc.core.vocabulary import Field
from gaitc.ir.cuddlib import cudd

if TYPE_CHECKING:
    from dd.cudd import BDD, Function

and_exists = cudd.and_exists

Ref = int
#: What a build asks at a leaf: the leaf for (care, target) if one settles it, else None.
AtLeaf: TypeAlias = "Callable[[Function, Function], Ref | None]"


def leaf(value: int) -> Ref:
    return -value - 1


def leaf_value(ref: Ref) -> int:
    return -ref - 1


@dataclass(frozen=True)
class Branch:
    """A decision node: which field it reads (its position in the diagram's field list)
    and one child per value of that field."""

    field: int
    kids: tuple[Ref, ...]
    #: values no state of the care set has here (their child was chosen to share a
    #: sibling's); tables say nothing of them
    unused: tuple[int, ...] = ()


@dataclass(frozen=True)
class Slot:
    """A field as the decision function reads it: current (``next=False``) or the value
    the environment just chose (``next=True``, inputs only)."""

    field: Field
    next: bool = False


DONT_CARE: Ref = 2**31  # a child no state of the care set reaches


def branch_bytes(branch: Branch) -> int:
    """The bytes a node takes in generated tables (:mod:`gaitc.codegen.tables`): its slot
    (1), where its children start (2) and a 2-byte reference per child."""
    return 3 + 2 * len(branch.kids)


class TooLarge(Exception):
    """A build passed the byte limit its :class:`Builder` was given."""

    def __init__(self, bytes_: int, limit: int) -> None:
        super().__init__(f"the diagrams take over {bytes_} bytes, past the limit of {limit}")
        self.bytes = bytes_
        self.limit = limit


@dataclass(frozen=True)
class Mark:
    """The size of a :class:`Builder`'s tables at one point, to roll back to."""

    nodes: int
    moves: int
    bytes: int


class Builder:
    """Builds diagrams into one shared node table (roots of several goals share nodes).

    Every node the builder interns is reachable from the root of the diagram it was built
    for (a node is made only as the parent of children that differ), so :attr:`bytes`, the
    bytes of its nodes and moves in generated tables, is a lower bound of the tables of any
    set of roots that includes every root built. With ``limit``, a build that would pass
    that many bytes raises :class:`TooLarge` as soon as it does, instead of finishing
    diagrams that cannot fit (``codegen --recover`` on a board)."""

    def __init__(self, bdd: BDD, slots: Sequence[Slot], outputs: Sequence[Field],
                 greedy: bool = False, limit: int | None = None) -> None:
        self.bdd = bdd
        self.greedy = greedy
        self.limit = limit
        self.bytes = 0
        self.slots = tuple(slots)
        self.outputs = tuple(outputs)
        self.nodes: list[Branch] = []
        self.moves: list[tuple[int, ...]] = []
        self._node_index: dict[Branch, int] = {}
        self._move_index: dict[tuple[int, ...], int] = {}
        self._memo: dict[tuple[int, int, int, int], Ref] = {}
        self._recent: list[int] = []
        self._commons: dict[tuple[int, int], tuple[Function, Function, Function]] = {}
        self._slot_bits = [frozenset(b + ("'" if s.next else "") for b in s.field.bits)
                           for s in self.slots]
        # each slot value's cube and each move's, made once (a greedy build asks millions)
        self._slot_cubes = [[s.field.cube(v, s.next) for v in range(len(s.field.labels))]
                            for s in self.slots]
        self._out_cubes = [[f.cube(v, True) for v in range(len(f.labels))]
                           for f in self.outputs]
        self._move_cubes: dict[int, dict[str, bool]] = {}
        self._decision_bits = frozenset().union(*self._slot_bits) if self._slot_bits \
            else frozenset()

    # ------------------------------------------------------------------ interning
    def _grow(self, added: int) -> None:
        self.bytes += added
        if self.limit is not None and self.bytes > self.limit:
            raise TooLarge(self.bytes, self.limit)

    def _node(self, branch: Branch) -> Ref:
        found = self._node_index.get(branch)
        if found is None:
            self._grow(branch_bytes(branch))
            found = self._node_index[branch] = len(self.nodes)
            self.nodes.append(branch)
        return found

    def _move(self, values: tuple[int, ...]) -> int:
        found = self._move_index.get(values)
        if found is None:
            self._grow(len(values))
            found = self._move_index[values] = len(self.moves)
            self.moves.append(values)
        return found

    def mark(self) -> Mark:
        """The tables as they are now, for :meth:`rollback`."""
        return Mark(len(self.nodes), len(self.moves), self.bytes)

    def rollback(self, mark: Mark) -> None:
        """Forget every node and move made since ``mark`` (a build that did not fit)."""
        for branch in self.nodes[mark.nodes:]:
            del self._node_index[branch]
        for values in self.moves[mark.moves:]:
            del self._move_index[values]
        del self.nodes[mark.nodes:], self.moves[mark.moves:]
        self.bytes = mark.bytes
        self._recent = [i for i in self._recent if i < mark.moves]
        self._move_cubes = {i: c for i, c in self._move_cubes.items() if i < mark.moves}

        def kept(kind: int, ref: Ref) -> bool:
            if ref == DONT_CARE:
                return True
            if ref >= 0:
                return ref < mark.nodes
            return kind == 1 or leaf_value(ref) < mark.moves  # kind 1: a 0/1 leaf

        self._memo = {key: ref for key, ref in self._memo.items() if kept(key[3], ref)}

    def move_cube(self, index: int) -> dict[str, bool]:
        out = self._move_cubes.get(index)
        if out is None:
            out = {}
            for cubes, value in zip(self._out_cubes, self.moves[index], strict=True):
                out.update(cubes[value])
            self._move_cubes[index] = out
        return out

    # ------------------------------------------------------------------ moves
    def build_moves(self, care: Function, relation: Function) -> Ref:
        """The diagram of a function that picks, at every state of ``care``, a move that
        ``relation`` allows (``care`` must lie inside the relation's domain)."""
        return self._build(0, care, relation, self._move_leaf, 0)

    def _common(self, care: Function, relation: Function) -> Function:
        """The moves ``relation`` allows in every state of ``care``."""
        key = (int(care), int(relation))
        kept = self._commons.get(key)
        if kept is not None:
            return kept[0]
        bdd, bits = self.bdd, self._decision_bits
        # CUDD's and-abstract: the conjunctions are never built (half the time of a
        # greedy build, which calls this for every slot and value it weighs)
        found = ~and_exists(care, ~relation, bits)
        if found != bdd.false:
            found &= and_exists(care, relation, bits)
        self._commons[key] = (found, care, relation)  # keeps the ids alive
        return found

    def _move_leaf(self, care: Function, relation: Function) -> Ref | None:
        bdd = self.bdd
        common = self._common(care, relation)
        if common == bdd.false:
            return None
        for index in reversed(self._recent):  # a sibling's move first: equal leaves merge
            if bdd.let(self.move_cube(index), common) != bdd.false:
                return leaf(index)
        values = []
        for cubes in self._out_cubes:
            for k, cube in enumerate(cubes):
                narrowed = bdd.let(cube, common)
                if narrowed != bdd.false:
                    values.append(k)
                    common = narrowed
                    break
            else:
                return None  # the allowed moves encode no value of this field
        index = self._move(tuple(values))
        self._recent = [*[i for i in self._recent if i != index][-7:], index]
        return leaf(index)

    # ------------------------------------------------------------------ booleans
    def build_boolean(self, care: Function, function: Function) -> Ref:
        """The diagram of ``function`` on ``care`` (anything outside it)."""
        return self._build(0, care, function, self._bool_leaf, 1)

    def _bool_leaf(self, care: Function, function: Function) -> Ref | None:
        false = self.bdd.false
        if care & ~function == false:
            return leaf(1)
        if care & function == false:
            return leaf(0)
        return None

    # ------------------------------------------------------------------ the recursion
    def _build(self, level: int, care: Function, target: Function, at_leaf: AtLeaf,
               kind: int) -> Ref:
        bdd = self.bdd
        if care == bdd.false:
            return DONT_CARE
        key = (level, int(care), int(target), kind)
        found = self._memo.get(key)
        if found is not None:
            return found
        result: Ref | None = at_leaf(care, target)
        if result is None:
            result = self._split(level, care, target, at_leaf, kind)
        self._memo[key] = result
        return result

    def _best_slot(self, level: int, care: Function, target: Function, at_leaf: AtLeaf,
                   support: set[str]) -> int:
        """The slot (from ``level`` on) whose values settle the most cases at once: the
        share of its values that lead straight to a leaf or to no state (one step of
        lookahead, as decision-tree learners choose their tests)."""
        bdd = self.bdd
        best, best_score = level, -1.0
        wanted = [i for i in range(level, len(self.slots)) if self._slot_bits[i] & support]
        # the inputs as they were before the environment moved decide last: a controller
        # rarely needs them once it sees the new ones
        chosen_first = [i for i in wanted if self.slots[i].next or not self.slots[i].field.is_input]
        for index in chosen_first or wanted:
            slot = self.slots[index]
            settled = 0
            for cube in self._slot_cubes[index]:
                sub = bdd.let(cube, care)
                if sub == bdd.false or self._settles(at_leaf, sub, bdd.let(cube, target)):
                    settled += 1
            score = settled / len(slot.field.labels)
            if score > best_score:
                best, best_score = index, score
        return best

    def _settles(self, at_leaf: AtLeaf, care: Function, target: Function) -> bool:
        if at_leaf == self._move_leaf:
            return bool(self._common(care, target) != self.bdd.false)
        return at_leaf(care, target) is not None

    def _split(self, level: int, care: Function, target: Function, at_leaf: AtLeaf,
               kind: int) -> Ref:
        bdd = self.bdd
        support = bdd.support(care) | bdd.support(target)
        while level < len(self.slots) and not (self._slot_bits[level] & support):
            level += 1
        if level == len(self.slots):
            raise ValueError("no field decides between the moves: the relation depends on "
                             "bits outside the fields")
        if self.greedy:
            level = self._best_slot(level, care, target, at_leaf, support)
        kids = []
        saved = self._recent
        self._recent = []
        for cube in self._slot_cubes[level]:
            kids.append(self._build(0 if self.greedy else level + 1, bdd.let(cube, care),
                                    bdd.let(cube, target),
                                    at_leaf, kind))
        self._recent = saved
        known = [k for k in kids if k != DONT_CARE]
        if not known:
            return DONT_CARE
        common = Counter(known).most_common(1)[0][0]
        filled = tuple(common if k == DONT_CARE else k for k in kids)
        if all(k == filled[0] for k in filled):
            return filled[0]
        unused = tuple(v for v, k in enumerate(kids) if k == DONT_CARE)
        return self._node(Branch(level, filled, unused))


def evaluate(nodes: Sequence[Branch], root: Ref, values: Sequence[int]) -> int:
    """The leaf that ``values`` (one value index per slot) lead to from ``root``."""
    ref = root
    while ref >= 0:
        branch = nodes[ref]
        ref = branch.kids[values[branch.field]]
    return leaf_value(ref)


def reachable_nodes(nodes: Sequence[Branch], roots: Sequence[Ref]) -> list[int]:
    """The nodes below ``roots``, each once, children before parents."""
    seen: set[int] = set()
    order: list[int] = []
    for root in roots:
        stack = [(root, False)]
        while stack:
            ref, done = stack.pop()
            if ref < 0 or ref == DONT_CARE:
                continue
            if done:
                order.append(ref)
                continue
            if ref in seen:
                continue
            seen.add(ref)
            stack.append((ref, True))
            stack.extend((k, False) for k in reversed(nodes[ref].kids))
    return order


def paths(nodes: Sequence[Branch], root: Ref, n_slots: int
          ) -> list[tuple[tuple[frozenset[int] | None, ...], int]]:
    """Every path from ``root`` to a leaf, as one value set per slot (None: not tested) and
    the leaf; edges of a node to the same child are one path with the values joined, and
    values no state has (:attr:`Branch.unused`) are left out."""
    out: list[tuple[tuple[frozenset[int] | None, ...], int]] = []
    stack: list[tuple[Ref, tuple[frozenset[int] | None, ...]]] = [(root, (None,) * n_slots)]
    while stack:
        ref, cond = stack.pop()
        if ref < 0:
            out.append((cond, leaf_value(ref)))
            continue
        branch = nodes[ref]
        grouped: dict[Ref, list[int]] = {}
        for value, kid in enumerate(branch.kids):
            if value not in branch.unused:
                grouped.setdefault(kid, []).append(value)
        for kid, values in reversed(list(grouped.items())):
            narrowed = list(cond)
            narrowed[branch.field] = frozenset(values)
            stack.append((kid, tuple(narrowed)))
    return out
