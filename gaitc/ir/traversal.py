"""The formula DAG itself: the node base class and the one iterative traversal every module uses.

:class:`Node` gives the nodes of :mod:`gaitc.ir.formula` their children, structural equality
(spans ignored) and cached hashes.  :func:`fold` is the traversal: it computes a value for
every node from the values of its children, children first, with an explicit stack, so a
formula nested far deeper than Python's recursion limit folds like a shallow one, and a
node shared in the DAG is folded once.  :func:`rebuild` is the fold that maps a formula to
a new one.  Writers build text as a :data:`Text` rope in a fold and :func:`join_text` joins
it, so the cost stays linear in the size of the text even for a deep formula.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import fields
from typing import Any, ClassVar, TypeAlias, TypeVar, cast

from gaitc.diagnostics import Span

R = TypeVar("R")
NodeT = TypeVar("NodeT", bound="Node")
#: A memo of :func:`fold`: ``id(node)`` -> ``(node, value)``; holding the node keeps its id
#: from being reused while the memo lives.
Memo: TypeAlias = "dict[int, tuple[Node, R]]"
#: Text as a rope: a string, or a tuple of ropes to be joined in order (:func:`join_text`).
Text: TypeAlias = "str | tuple[Text, ...]"

_FIELD_NAMES: dict[type, tuple[str, ...]] = {}


class Node:
    """Common behaviour of formula nodes: structural equality without spans, cached hash."""

    span: Span | None
    precedence: ClassVar[int] = 100

    def _names(self) -> tuple[str, ...]:
        names = _FIELD_NAMES.get(type(self))
        if names is None:
            layout = fields(self)  # type: ignore[arg-type]
            names = _FIELD_NAMES[type(self)] = tuple(f.name for f in layout)
        return names

    def _key(self) -> tuple[Any, ...]:
        return tuple(getattr(self, f.name) for f in fields(self) if f.compare)  # type: ignore[arg-type]

    def __eq__(self, other: object) -> bool:
        if self is other:
            return True
        if type(self) is not type(other):
            return False
        assert isinstance(other, Node)
        return hash(self) == hash(other) and _structurally_equal(self, other)

    def __hash__(self) -> int:
        cached = self.__dict__.get("_hash")
        if cached is None:
            _hash_bottom_up(self)
            cached = self.__dict__["_hash"]
        return int(cached)

    def children(self) -> tuple[Node, ...]:
        """The subformulas and terms of this node, in field order (found once, then kept:
        a spec's formulas are walked several times, and the 20 x 20 hazard grid's clauses,
        walked one by one, visit 1.8 million nodes)."""
        cached: tuple[Node, ...] | None = self.__dict__.get("_children")
        if cached is not None:
            return cached
        out: list[Node] = []
        for name in self._names():
            value = getattr(self, name)
            if isinstance(value, Node):
                out.append(value)
            elif isinstance(value, tuple):
                out.extend(v for v in value if isinstance(v, Node))
        kids = self.__dict__["_children"] = tuple(out)
        return kids

    def with_children(self, kids: Sequence[Node]) -> Node:
        """A node like this one (span included) with ``kids`` for its :meth:`children`.

        A node without children is returned as it is; any other is built anew.
        """
        changes: dict[str, Any] = {}
        position = 0
        for name in self._names():
            value = getattr(self, name)
            if isinstance(value, Node):
                changes[name] = kids[position]
                position += 1
            elif isinstance(value, tuple) and value and isinstance(value[0], Node):
                changes[name] = tuple(kids[position:position + len(value)])
                position += len(value)
        if not changes:
            return self
        kwargs = {name: getattr(self, name) for name in self._names()}
        kwargs.update(changes)
        return type(self)(**kwargs)


def _hash_bottom_up(root: Node) -> None:
    """Cache the hash of ``root`` and its descendants, children first (no deep recursion)."""
    stack: list[tuple[Node, bool]] = [(root, False)]
    while stack:
        node, children_done = stack.pop()
        if "_hash" in node.__dict__:
            continue
        if not children_done:
            stack.append((node, True))
            stack.extend((c, False) for c in node.children() if "_hash" not in c.__dict__)
            continue
        object.__setattr__(node, "_hash", hash((type(node).__name__, node._key())))


def _structurally_equal(left: Node, right: Node) -> bool:
    """Equality of two trees or DAGs, comparing each pair of shared nodes once."""
    seen: set[tuple[int, int]] = set()
    stack = [(left, right)]
    while stack:
        a, b = stack.pop()
        if a is b or (id(a), id(b)) in seen:
            continue
        seen.add((id(a), id(b)))
        if type(a) is not type(b) or hash(a) != hash(b):
            return False
        for x, y in zip(a._key(), b._key(), strict=True):
            if isinstance(x, Node) and isinstance(y, Node):
                stack.append((x, y))
            elif isinstance(x, tuple) and isinstance(y, tuple) and len(x) == len(y) and all(
                isinstance(v, Node) for v in x + y
            ):
                stack.extend(zip(x, y, strict=True))
            elif x != y:
                return False
    return True


# ---------------------------------------------------------------- the traversal
def fold(
    root: Node,
    combine: Callable[[Node, list[R]], R],
    children: Callable[[Node], Sequence[Node]] = Node.children,
    memo: Memo[R] | None = None,
) -> R:
    """``combine(node, values of its children)`` for ``root``, computed children first.

    The order is exactly that of the recursive definition: ``children(node)`` is called
    once per distinct node when the traversal reaches it (pre-order, left to right), so it
    may raise to reject a node before its subformulas are looked at, or return ``()`` to
    make the node a leaf; ``combine`` runs in post-order.  A node reached again (a shared
    subformula) is looked up in ``memo``, which may be shared between calls.
    """
    done: Memo[R] = {} if memo is None else memo
    hit = done.get(id(root))
    if hit is not None:
        return hit[1]
    stack: list[tuple[Node, Sequence[Node] | None]] = [(root, None)]
    while stack:
        node, kids = stack.pop()
        if kids is None:
            if id(node) in done:
                continue
            kids = children(node)
            if kids:
                waiting = [(k, None) for k in reversed(kids) if id(k) not in done]
                if waiting:
                    stack.append((node, kids))
                    stack += waiting
                    continue
        done[id(node)] = (node, combine(node, [done[id(k)][1] for k in kids]))
    return done[id(root)][1]


def rebuild(root: NodeT, replace: Callable[[Node], Node | None]) -> NodeT:
    """``root`` with nodes swapped top-down: where ``replace(node)`` gives a node, that node
    takes the place of the whole subformula; every other node is rebuilt from its rebuilt
    children (:meth:`Node.with_children`).  ``replace`` sees nodes in pre-order, once per
    shared node, and must give a formula for a formula and a term for a term."""
    swapped: dict[int, Node] = {}

    def enter(node: Node) -> Sequence[Node]:
        new = replace(node)
        if new is None:
            return node.children()
        swapped[id(node)] = new
        return ()

    def combine(node: Node, kids: list[Node]) -> Node:
        new = swapped.get(id(node))
        return node.with_children(kids) if new is None else new

    return cast(NodeT, fold(root, combine, enter))


def join_text(text: Text) -> str:
    """The string a :data:`Text` rope stands for (shared pieces repeated)."""
    out: list[str] = []
    stack: list[Text] = [text]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            out.append(item)
        else:
            stack.extend(reversed(item))
    return "".join(out)


def separated(separator: str, texts: Sequence[Text]) -> Text:
    """The rope of ``texts`` with ``separator`` between each two (``str.join`` for ropes)."""
    out: list[Text] = []
    for text in texts:
        out.extend((separator, text) if out else (text,))
    return tuple(out)


def height(root: Node, children: Callable[[Node], Sequence[Node]] = Node.children) -> int:
    """The number of nodes on the longest path from ``root`` down to a leaf."""
    return fold(root, lambda _, kids: 1 + max(kids, default=0), children)
