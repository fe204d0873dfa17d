"""Bit-blasting: integer variables to Boolean bits and comparisons to adder/comparator circuits.

Reproduces SLUGS's tools/StructuredSlugsParser/compiler.py: bits ``x@0.MIN.MAX``
(named in :mod:`gaitc.ir.bits`),
``x@1`` .. (little-endian, value = MIN + bits), ripple-carry ``+`` that keeps the carry
(no overflow), and range constraints (value - MIN < MAX - MIN + 1) in init and primed trans.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from gaitc.ir.bits import integer_bits
from gaitc.ir.formula import (
    FALSE,
    TRUE,
    Add,
    Always,
    And,
    Compare,
    Const,
    Eventually,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Or,
    Term,
    Var,
    Xor,
    formula_kind,
    term_kind,
    unreachable,
    walk,
)
from gaitc.ir.spec import SECTIONS, Clause, GR1Spec, Origin, Variable
from gaitc.ir.traversal import Memo, Node, fold

Bits = list[Expr]  # little-endian bit vector; missing high bits are 0


# ---------------------------------------------------------------- gates with constant folding
def _not(a: Expr) -> Expr:
    if isinstance(a, Const):
        return FALSE if a.value else TRUE
    if isinstance(a, Not):
        return a.arg
    return Not(a)


def _chain(kind: type[And] | type[Or], a: Expr, b: Expr) -> Expr:
    # Same-kind operands are spliced in, as the slugsin reader does for inline chains.
    args: list[Expr] = []
    for x in (a, b):
        args.extend(x.args if type(x) is kind else (x,))
    return kind(tuple(args))


def _and(a: Expr, b: Expr) -> Expr:
    if isinstance(a, Const):
        return b if a.value else FALSE
    if isinstance(b, Const):
        return a if b.value else FALSE
    return _chain(And, a, b)


def _or(a: Expr, b: Expr) -> Expr:
    if isinstance(a, Const):
        return TRUE if a.value else b
    if isinstance(b, Const):
        return TRUE if b.value else a
    return _chain(Or, a, b)


def _xor(a: Expr, b: Expr) -> Expr:
    if isinstance(a, Const):
        return _not(b) if a.value else b
    if isinstance(b, Const):
        return _not(a) if b.value else a
    return Xor(a, b)


def constant_bits(value: int) -> Bits:
    """The bits of a natural number (empty for 0, as in SLUGS)."""
    if value < 0:
        raise ValueError(f"negative constant {value} has no bit vector")
    out: Bits = []
    while value:
        out.append(TRUE if value & 1 else FALSE)
        value >>= 1
    return out


def add_bits(a: Bits, b: Bits) -> Bits:
    """Ripple-carry sum, one bit longer than the longer operand (SLUGS keeps the carry)."""
    if not a:
        return b
    if not b:
        return a
    if len(b) < len(a):
        a, b = b, a
    out: Bits = [_xor(a[0], b[0])]
    carry = _and(a[0], b[0])
    for i in range(1, len(a)):
        out.append(_xor(_xor(a[i], b[i]), carry))
        carry = _or(_or(_and(a[i], b[i]), _and(carry, a[i])), _and(carry, b[i]))
    for i in range(len(a), len(b)):
        out.append(_xor(b[i], carry))
        carry = _and(b[i], carry)
    out.append(carry)
    return out


def equal_bits(a: Bits, b: Bits) -> Expr:
    """``a = b`` bit by bit; extra high bits of the longer vector must be 0."""
    result: Expr = TRUE
    for i in range(max(len(a), len(b))):
        x = a[i] if i < len(a) else FALSE
        y = b[i] if i < len(b) else FALSE
        result = _and(_not(_xor(x, y)), result)
    return result


def less_bits(a: Bits, b: Bits, or_equal: bool) -> Expr:
    """``a < b`` (or ``a <= b``), decided from the most significant differing bit."""
    result: Expr = TRUE if or_equal else FALSE
    for i in range(min(len(a), len(b))):
        result = _or(_and(_not(a[i]), b[i]), _and(_or(b[i], _not(a[i])), result))
    for i in range(len(b), len(a)):
        result = _and(_not(a[i]), result)
    for i in range(len(a), len(b)):
        result = _or(b[i], result)
    return result


# ---------------------------------------------------------------- comparisons
def _flatten(term: Term, variables: Mapping[str, Variable]) -> tuple[tuple[Bits, ...], int]:
    """The bit vectors of a sum's variables, left to right, and the sum of its constants and
    MINs (a fold: each shared subterm is flattened once)."""

    def combine(node: Node, kids: list[tuple[tuple[Bits, ...], int]]) -> tuple[
        tuple[Bits, ...], int
    ]:
        kind = term_kind(node)
        match kind:
            case IntConst():
                return (), kind.value
            case Add():
                (left, low), (right, high) = kids
                return left + right, low + high
            case IntVar():
                var = variables.get(kind.name)
                if var is None or not var.is_integer:
                    raise ValueError(f"'{kind.name}' is not an integer variable of this spec")
                assert var.low is not None
                return ([Var(bit, kind.primed) for bit in integer_bits(var)],), var.low
            case _:
                unreachable(kind)

    return fold(term, combine, lambda n: n.children() if isinstance(n, Add) else ())


def compare_bits(node: Compare, variables: Mapping[str, Variable]) -> Expr:
    """A Boolean circuit equivalent to the integer comparison ``node``."""
    left_vectors, left_shift = _flatten(node.left, variables)
    right_vectors, right_shift = _flatten(node.right, variables)
    left, right = list(left_vectors), list(right_vectors)
    shift = left_shift - right_shift
    # Move the constants to one side so that every vector is a natural number.
    (left if shift > 0 else right).append(constant_bits(abs(shift)))
    a: Bits = []
    for vec in left:
        a = add_bits(a, vec)
    b: Bits = []
    for vec in right:
        b = add_bits(b, vec)
    if node.op in ("=", "!="):
        eq = equal_bits(a, b)
        return eq if node.op == "=" else _not(eq)
    if node.op in ("<", "<="):
        return less_bits(a, b, node.op == "<=")
    if node.op in (">", ">="):
        return less_bits(b, a, node.op == ">=")
    raise ValueError(f"unknown comparison operator {node.op!r}")


def lower(expr: Expr, variables: Mapping[str, Variable], memo: Memo[Expr]) -> Expr:
    """``expr`` with every :class:`Compare` replaced by its circuit; shared nodes stay shared.

    A fold (children before parents, no recursion), memoised in ``memo`` across calls.
    """

    def combine(node: Node, kids: list[Expr]) -> Expr:
        return _lower_node(node, kids, variables)

    def children(node: Node) -> Sequence[Node]:
        return () if isinstance(node, (Const, Var, Compare)) else node.children()

    return fold(expr, combine, children, memo)


def _lower_node(node: Node, kids: list[Expr], variables: Mapping[str, Variable]) -> Expr:
    kind = formula_kind(node)
    match kind:
        case Const() | Var():
            return kind
        case Compare():
            return compare_bits(kind, variables)
        case Not():
            return Not(kids[0], span=kind.span)
        case And() | Or():
            return type(kind)(tuple(kids), span=kind.span)
        case Xor() | Iff() | Implies():
            return type(kind)(kids[0], kids[1], span=kind.span)
        case Next() | Always() | Eventually():
            raise ValueError(f"{type(kind).__name__} cannot appear in a GR(1) section")
        case _:
            unreachable(kind)


def range_constraint(var: Variable, primed: bool) -> Expr | None:
    """SLUGS's limit ``bits < MAX - MIN + 1``, or None when every bit pattern is in range."""
    assert var.low is not None and var.high is not None
    limit = var.high - var.low + 1
    bits = integer_bits(var)
    if 1 << len(bits) == limit:
        return None
    result: Expr = FALSE
    for i, bit in enumerate(bits):
        negated = Not(Var(bit, primed))
        result = _chain(Or if limit >> i & 1 else And, negated, result)
    return result


def bitblast(spec: GR1Spec) -> GR1Spec:
    """The Boolean spec SLUGS's converter would produce from ``spec`` (identity if Boolean).

    Bits replace each integer variable in place; range constraints are appended to
    ``env_init``/``env_trans`` for inputs and ``sys_init``/``sys_trans`` for outputs.
    """
    has_compare = any(
        isinstance(node, (Compare, IntVar))
        for name in SECTIONS
        for clause in spec.section(name)
        for node in walk(clause.formula)
    )
    if not spec.has_integers and not has_compare:
        return spec
    variables = {v.name: v for v in spec.variables()}
    memo: Memo[Expr] = {}
    sections: dict[str, list[Clause]] = {}
    for name in SECTIONS:
        sections[name] = [
            Clause(lower(c.formula, variables, memo), c.origin) for c in spec.section(name)
        ]
    for var in spec.variables():
        if not var.is_integer:
            continue
        player, kind = ("env", "input") if var in spec.inputs else ("sys", "output")
        rule = f"range of integer {kind} {var.name}: {var.low} <= {var.name}"
        for primed, section in ((False, "init"), (True, "trans")):
            limit = range_constraint(var, primed)
            if limit is not None:
                mark = "'" if primed else ""
                origin = Origin(f"{rule}{mark} <= {var.high}", var.span)
                sections[f"{player}_{section}"].append(Clause(limit, origin))

    def blast(vs: tuple[Variable, ...]) -> tuple[Variable, ...]:
        return tuple(Variable(b, span=v.span) for v in vs for b in integer_bits(v))

    return GR1Spec(
        inputs=blast(spec.inputs),
        outputs=blast(spec.outputs),
        name=spec.name,
        **{name: tuple(items) for name, items in sections.items()},
    )
