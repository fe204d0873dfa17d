"""The formula IR: immutable propositional/integer formulas with primes (next-state copies).

Nodes are frozen dataclasses; the optional ``span`` rides along but does not take
part in equality or hashing, so tests compare trees structurally.  Hashes are
cached, because readers of ``.slugsin`` memory buffers (``$``/``?``) build DAGs
with heavy sharing.  ``Next``/``Always``/``Eventually`` exist only so front ends
can represent user formulas before they are sorted into GR(1) sections; the
sections of a :class:`~gr1.spec.GR1Spec` contain none of them
(:func:`push_next` removes ``Next`` by priming variables).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar

from diagnostics import FormulaError, Span


class Node:
    """Common behaviour of formula nodes: structural equality without spans, cached hash."""

    span: Span | None
    precedence: ClassVar[int] = 100

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
        out: list[Node] = []
        for f in fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            if isinstance(value, Node):
                out.append(value)
            elif isinstance(value, tuple):
                out.extend(v for v in value if isinstance(v, Node))
        return tuple(out)


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


_SPAN = field(default=None, compare=False, repr=False, kw_only=True)


# ---------------------------------------------------------------- integer terms
@dataclass(frozen=True, eq=False)
class Term(Node):
    """An integer-valued term (only inside a :class:`Compare`)."""


@dataclass(frozen=True, eq=False)
class IntConst(Term):
    value: int
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class IntVar(Term):
    name: str
    primed: bool = False
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Add(Term):
    left: Term
    right: Term
    span: Span | None = _SPAN


# ---------------------------------------------------------------- Boolean formulas
@dataclass(frozen=True, eq=False)
class Expr(Node):
    """A Boolean formula."""


@dataclass(frozen=True, eq=False)
class Const(Expr):
    value: bool
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Var(Expr):
    name: str
    primed: bool = False
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Not(Expr):
    arg: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class And(Expr):
    args: tuple[Expr, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Or(Expr):
    args: tuple[Expr, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Xor(Expr):
    left: Expr
    right: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Iff(Expr):
    left: Expr
    right: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Implies(Expr):
    left: Expr
    right: Expr
    span: Span | None = _SPAN


COMPARE_OPS = ("=", "!=", "<", "<=", ">", ">=")


@dataclass(frozen=True, eq=False)
class Compare(Expr):
    op: str
    left: Term
    right: Term
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Next(Expr):
    """``next(arg)``; removed by :func:`push_next` before a formula enters a GR(1) section."""

    arg: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Always(Expr):
    """``always arg``; only in front-end formulas, sorted into sections by the compiler."""

    arg: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Eventually(Expr):
    """``eventually arg``; only in front-end formulas, sorted into sections by the compiler."""

    arg: Expr
    span: Span | None = _SPAN


TRUE = Const(True)
FALSE = Const(False)


# ---------------------------------------------------------------- construction helpers
def conj(items: Iterable[Expr], span: Span | None = None) -> Expr:
    """Conjunction of ``items``; ``TRUE`` when empty, the item itself when single."""
    args = tuple(items)
    if not args:
        return TRUE
    if len(args) == 1:
        return args[0]
    return And(args, span=span)


def disj(items: Iterable[Expr], span: Span | None = None) -> Expr:
    """Disjunction of ``items``; ``FALSE`` when empty, the item itself when single."""
    args = tuple(items)
    if not args:
        return FALSE
    if len(args) == 1:
        return args[0]
    return Or(args, span=span)


def walk(node: Node) -> Iterator[Node]:
    """Every node reachable from ``node``, each shared node once (pre-order)."""
    seen: set[int] = set()
    stack: list[Node] = [node]
    while stack:
        current = stack.pop()
        if id(current) in seen:
            continue
        seen.add(id(current))
        yield current
        stack.extend(reversed(current.children()))


def atoms(node: Node) -> set[tuple[str, bool]]:
    """The ``(name, primed)`` pairs of every Boolean or integer variable in ``node``."""
    out: set[tuple[str, bool]] = set()
    for n in walk(node):
        if isinstance(n, (Var, IntVar)):
            out.add((n.name, n.primed))
    return out


def has_primes(node: Node) -> bool:
    """Whether ``node`` mentions a next-state variable or a ``Next``."""
    return any(
        isinstance(n, Next) or (isinstance(n, (Var, IntVar)) and n.primed) for n in walk(node)
    )


# ---------------------------------------------------------------- transformations
def _rebuild(node: Node, fn: Any, memo: dict[int, Any]) -> Any:
    key = id(node)
    if key in memo:
        return memo[key]
    result = fn(node, lambda child: _rebuild(child, fn, memo))
    memo[key] = result
    return result


def _map_children(node: Node, sub: Any) -> Node:
    changes: dict[str, Any] = {}
    for f in fields(node):  # type: ignore[arg-type]
        value = getattr(node, f.name)
        if isinstance(value, Node):
            changes[f.name] = sub(value)
        elif isinstance(value, tuple) and value and isinstance(value[0], Node):
            changes[f.name] = tuple(sub(v) for v in value)
    if not changes:
        return node
    kwargs = {f.name: getattr(node, f.name) for f in fields(node)}  # type: ignore[arg-type]
    kwargs.update(changes)
    return type(node)(**kwargs)


def push_next(expr: Expr) -> Expr:
    """Replace ``Next(φ)`` by ``φ`` with every variable primed.

    Raises :class:`FormulaError` for ``next`` inside ``next`` (or over an already
    primed variable) and for ``always``/``eventually`` anywhere inside: neither is
    expressible in a GR(1) section.
    """

    def fn(node: Node, sub: Any, primed: bool) -> Node:
        if isinstance(node, Next):
            if primed:
                raise FormulaError(
                    "'next' inside 'next' is outside GR(1): a formula may look one step ahead only",
                    node.span,
                )
            return _rebuild(node.arg, lambda n, s: fn(n, s, True), {})  # type: ignore[no-any-return]
        if isinstance(node, (Always, Eventually)):
            word = "always" if isinstance(node, Always) else "eventually"
            raise FormulaError(
                f"'{word}' cannot appear inside another formula here: GR(1) allows it only "
                "at the top of an assumption or guarantee",
                node.span,
            )
        if isinstance(node, (Var, IntVar)):
            if primed and node.primed:
                raise FormulaError(
                    f"'{node.name}' is already a next-state value; 'next' cannot apply twice",
                    node.span,
                )
            if primed:
                return type(node)(node.name, True, span=node.span)
            return node
        return _map_children(node, sub)

    return _rebuild(expr, lambda n, s: fn(n, s, False), {})  # type: ignore[no-any-return]


def prime(expr: Expr) -> Expr:
    """``expr`` one step later: every variable primed (equivalent to ``push_next(Next(expr))``)."""
    return push_next(Next(expr, span=expr.span))


def substitute(expr: Expr, mapping: Mapping[tuple[str, bool], Expr]) -> Expr:
    """Replace Boolean variables ``(name, primed)`` by formulas."""

    def fn(node: Node, sub: Any) -> Node:
        if isinstance(node, Var) and (node.name, node.primed) in mapping:
            return mapping[(node.name, node.primed)]
        return _map_children(node, sub)

    return _rebuild(expr, fn, {})  # type: ignore[no-any-return]


def simplify(expr: Expr) -> Expr:
    """Fold constants, flatten nested ``And``/``Or``, drop double negations and duplicates.

    The result has the same truth value as ``expr`` under every valuation.
    """

    def fn(node: Node, sub: Any) -> Node:
        if isinstance(node, Not):
            arg = sub(node.arg)
            if isinstance(arg, Const):
                return Const(not arg.value, span=node.span)
            if isinstance(arg, Not):
                return arg.arg
            return Not(arg, span=node.span)
        if isinstance(node, (And, Or)):
            is_and = isinstance(node, And)
            unit, zero = (True, False) if is_and else (False, True)
            out: list[Expr] = []
            seen: set[Expr] = set()
            for child in node.args:
                c = sub(child)
                parts = c.args if type(c) is type(node) else (c,)
                for p in parts:
                    if isinstance(p, Const):
                        if p.value == zero:
                            return Const(zero, span=node.span)
                        continue
                    if p not in seen:
                        seen.add(p)
                        out.append(p)
            for p in out:
                if Not(p) in seen:
                    return Const(zero, span=node.span)
            if not out:
                return Const(unit, span=node.span)
            if len(out) == 1:
                return out[0]
            return type(node)(tuple(out), span=node.span)
        if isinstance(node, (Xor, Iff, Implies)):
            left, right = sub(node.left), sub(node.right)
            if isinstance(node, Implies):
                if isinstance(left, Const):
                    return right if left.value else Const(True, span=node.span)
                if isinstance(right, Const):
                    return Const(True, span=node.span) if right.value else simplify(Not(left))
                return Implies(left, right, span=node.span)
            flip = isinstance(node, Xor)
            if isinstance(left, Const) and isinstance(right, Const):
                return Const((left.value == right.value) != flip, span=node.span)
            for a, b in ((left, right), (right, left)):
                if isinstance(a, Const):
                    keep = a.value != flip
                    return b if keep else simplify(Not(b))
            return type(node)(left, right, span=node.span)
        return _map_children(node, sub)

    return _rebuild(expr, fn, {})  # type: ignore[no-any-return]
