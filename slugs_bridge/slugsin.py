"""Reader and writer of SLUGS's prefix input format (``.slugsin``), with ``$``/``?`` memory buffers.

Semantics follow ``GR1Context::init`` and ``parseBooleanFormulaRecurse`` in SLUGS
(src/synthesisContextBasics.cpp): one conjunct per line, ``$ N f0 .. fN-1`` is the
last of N formulas, ``? i`` recalls element ``i`` of the innermost enclosing buffer.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from gaitc.diagnostics import SlugsFormatError, Span
from gaitc.ir.formula import (
    And,
    Const,
    Expr,
    Iff,
    Implies,
    Node,
    Not,
    Or,
    Var,
    Xor,
)
from gaitc.ir.spec import SECTIONS, Clause, GR1Spec, Origin, Variable
from gaitc.ir.traversal import fold
from slugs_bridge.names import check_renaming, read_renaming, renaming
from slugs_bridge.sections import FIELD_HEADERS as FIELD_HEADERS
from slugs_bridge.sections import HEADERS as HEADERS
from slugs_bridge.sections import (
    TOKEN,
    SourceLine,
    check_atoms,
    check_name,
    read_sections,
    write_sections,
)


# ---------------------------------------------------------------- prefix formulas
@dataclass
class _Frame:
    """An operator (or memory buffer) still waiting for operands."""

    op: str
    span: Span
    needed: int
    args: list[Expr]
    recalled: list[bool] = field(default_factory=list)  # per operand: it came from '?'


#: The tokens that open an operator or a buffer (every other token is a leaf).
_OPERATOR_TOKENS = frozenset(("&", "|", "^", "!", "$", "?"))
_NO_SPAN = Span("", 0, 0, 0, 0)  # a leaf's span before it is needed
MAX_COUNT_DIGITS = 9  # '$ N' and '? N' counts: at most 999,999,999


def _span(filename: str, line: int, match: re.Match[str]) -> Span:
    return Span(filename, line, match.start() + 1, line, match.end())


def _parse_count(
    matches: list[re.Match[str]], index: int, op: Span, what: str, filename: str, line: int
) -> int:
    if index >= len(matches):
        raise SlugsFormatError(f"missing operand: {what}, but the line ends here", op)
    text = matches[index].group()
    if not (text.isascii() and text.isdigit()):
        raise SlugsFormatError(f"{what}, found '{text}'", _span(filename, line, matches[index]))
    if len(text) > MAX_COUNT_DIGITS:
        raise SlugsFormatError(f"{what}, found a number of {len(text)} digits; the limit is "
                               f"{MAX_COUNT_DIGITS} digits", _span(filename, line,
                                                                   matches[index]))
    return int(text)


def parse_prefix(
    text: str, filename: str, line: int, declared: set[str],
    names: Mapping[str, str] | None = None,
) -> Expr:
    """Parse one slugsin formula line into the IR; shared subformulas (``$``/``?``) stay shared.

    Nested ``&``/``|`` chains written inline are flattened into one n-ary node.
    Names must be in ``declared`` (plain names; ``x'`` is the next-state copy of ``x``);
    ``names`` maps written names to the spec's names (see :mod:`slugs_bridge.names`).

    Equal subformulas of the line are one node (hash-consing, keyed by the operator and
    the identity of the operands, which are shared already): SLUGS's compiler writes a
    comparison of bit-cut integers as the same bit patterns over and over, and the
    1024 x 1024 gridworld's 2,113 lines held 500,000 nodes each visited by every later
    pass.  A shared node keeps the span of its first occurrence on the line, so a message
    about it still names the line and a column where it is written.
    """
    rename = names or {}
    matches = list(TOKEN.finditer(text))
    stack: list[_Frame] = []
    came_recalled = False  # whether ``value`` came from '?' (then never flattened)
    interned: dict[tuple[object, ...], Expr] = {}
    result: Expr | None = None
    i = 0
    while i < len(matches):
        tok = matches[i].group()
        leaf = tok not in _OPERATOR_TOKENS
        # a leaf's span is made only for a new node or a message (most leaves are interned)
        span = _NO_SPAN if leaf else _span(filename, line, matches[i])
        if result is not None:
            span = _span(filename, line, matches[i])
            raise SlugsFormatError(
                f"unexpected token '{tok}' after a complete formula; each line holds exactly "
                "one formula in prefix notation",
                span,
            )
        i += 1
        value: Expr | None = None
        if tok in ("&", "|") and stack and stack[-1].op == tok:
            # An inline chain: the operands join the enclosing node (flattening in O(n)).
            stack[-1].needed += 1
        elif tok in ("&", "|", "^"):
            stack.append(_Frame(tok, span, 2, []))
        elif tok == "!":
            stack.append(_Frame(tok, span, 1, []))
        elif tok == "$":
            n = _parse_count(
                matches, i, span, "'$' must be followed by the number of buffer elements",
                filename, line,
            )
            if n == 0:
                raise SlugsFormatError(
                    "a memory buffer '$ 0' is empty; it needs at least one formula",
                    _span(filename, line, matches[i]),
                )
            i += 1
            stack.append(_Frame("$", span, n, []))
        elif tok == "?":
            k = _parse_count(
                matches, i, span, "'?' must be followed by a buffer element number",
                filename, line,
            )
            ref = _span(filename, line, matches[i])
            i += 1
            buffer = next((f for f in reversed(stack) if f.op == "$"), None)
            if buffer is None:
                raise SlugsFormatError(
                    f"'? {k}' is outside any memory buffer; '?' may only appear inside '$ N ...'",
                    span,
                )
            if k >= len(buffer.args):
                raise SlugsFormatError(
                    f"'? {k}' recalls buffer element {k}, but only {len(buffer.args)} "
                    f"element(s) of the innermost buffer are complete at this point",
                    ref,
                )
            value = buffer.args[k]
            came_recalled = True
        elif tok == "1" or tok == "0":
            value = interned.get((tok,))
            if value is None:
                span = _span(filename, line, matches[i - 1])
                value = interned[(tok,)] = Const(tok == "1", span=span)
        else:
            value = interned.get((tok,))
            if value is None:
                span = _span(filename, line, matches[i - 1])
                name, primed = (tok[:-1], True) if tok.endswith("'") else (tok, False)
                if name not in declared:
                    raise SlugsFormatError(
                        f"unknown variable '{name}'; declare it under [INPUT] or [OUTPUT]",
                        span)
                value = interned[(tok,)] = Var(rename.get(name, name), primed, span=span)
        # Feed completed values to the waiting operators.
        while value is not None:
            if not stack:
                result = value
                break
            frame = stack[-1]
            frame.args.append(value)
            frame.recalled.append(came_recalled)
            came_recalled = False
            if len(frame.args) < frame.needed:
                break
            stack.pop()
            value, came_recalled = _build(frame, interned)
    if result is None:
        if not stack:
            raise SlugsFormatError(
                "empty formula", Span(filename, line, 1, line, max(1, len(text)))
            )
        frame = stack[-1]
        if frame.op == "$":
            msg = (
                f"missing operand: the memory buffer '$ {frame.needed}' needs {frame.needed} "
                f"formulas but the line ends after {len(frame.args)}"
            )
        else:
            msg = (
                f"missing operand: '{frame.op}' needs {frame.needed} operand(s) but the line "
                f"ends after {len(frame.args)}"
            )
        raise SlugsFormatError(msg, frame.span)
    return result


def _build(frame: _Frame, interned: dict[tuple[object, ...], Expr]) -> tuple[Expr, bool]:
    """The node of a completed operator (the line's equal node if it has one), and whether
    it counts as recalled: a buffer's value does when its last element came from '?'."""
    args = frame.args
    if frame.op == "$":
        return args[-1], frame.recalled[-1]
    if frame.op in ("&", "|"):
        kind = And if frame.op == "&" else Or
        flat: list[Expr] = []
        for a, recalled in zip(args, frame.recalled, strict=True):
            if isinstance(a, kind) and not recalled:
                flat.extend(a.args)
            else:
                flat.append(a)
        args = flat
    key = (frame.op, *map(id, args))
    found = interned.get(key)
    if found is not None:
        return found, False
    node: Expr
    if frame.op == "!":
        node = Not(args[0], span=frame.span)
    elif frame.op == "^":
        node = Xor(args[0], args[1], span=frame.span)
    else:
        node = (And if frame.op == "&" else Or)(tuple(args), span=frame.span)
    interned[key] = node
    return node, False


def intern_formula(expr: Expr) -> Expr:
    """``expr`` with equal subformulas made one node, as :func:`parse_prefix` makes them
    on a line (leaves by name, operators by the identity of their interned operands)."""
    interned: dict[tuple[object, ...], Node] = {}

    def combine(node: Node, kids: list[Node]) -> Node:
        if isinstance(node, Var):
            key: tuple[object, ...] = ("var", node.name, node.primed)
        elif isinstance(node, Const):
            key = ("const", node.value)
        else:
            key = (type(node).__name__, *map(id, kids))
        found = interned.get(key)
        if found is None:
            found = interned[key] = node.with_children(kids) if kids else node
        return found

    return fold(expr, combine)  # type: ignore[return-value]


def parse_slugsin(text: str, filename: str) -> GR1Spec:
    """Read a ``.slugsin`` specification (SLUGS's prefix format) into a Boolean :class:`GR1Spec`.

    Unlike SLUGS, a formula may use a variable declared further down the file.  Names
    renamed by the writer (the renaming comment at the top) get their spec names back.
    """
    back, where = read_renaming(text, filename)
    variables: dict[str, list[Variable]] = {"inputs": [], "outputs": []}
    first_seen: dict[str, Span] = {}
    clauses: dict[str, list[Clause]] = {name: [] for name in SECTIONS}
    formulas: list[SourceLine] = []
    for src in read_sections(text, filename):
        if src.field not in variables:
            formulas.append(src)
        else:
            name = src.text.strip()
            check_name(name, src.span)
            if name in first_seen:
                raise SlugsFormatError(
                    f"variable '{name}' is declared twice (first on line "
                    f"{first_seen[name].line}); every name must be unique",
                    src.span,
                )
            first_seen[name] = src.span
            variables[src.field].append(Variable(back.get(name, name), span=src.span))
    check_renaming(back, first_seen, where)
    declared = set(first_seen)
    for src in formulas:
        formula = parse_prefix(src.text, filename, src.line, declared, back)
        origin = Origin(f"slugsin {src.header}", src.span)
        clauses[src.field].append(Clause(formula, origin))
    spec = GR1Spec(
        inputs=tuple(variables["inputs"]),
        outputs=tuple(variables["outputs"]),
        name=Path(filename).stem,
        **{name: tuple(items) for name, items in clauses.items()},
    )
    check_atoms(spec)
    return spec


# ---------------------------------------------------------------- writer
def _buffered_nodes(root: Expr, nested_too: bool = True) -> list[Expr]:
    """Nodes to write as ``$`` buffer elements, children before parents.

    These are compound nodes reachable more than once, and (with ``nested_too``)
    conjunctions directly inside a conjunction, disjunctions inside a disjunction: the
    reader flattens inline chains, so writing such a child through the buffer keeps the
    shape the reader gives back.
    """
    counts: dict[int, int] = {}
    nested: set[int] = set()
    order: list[Expr] = []
    stack: list[tuple[Node, bool]] = [(root, False)]
    while stack:
        node, done = stack.pop()
        if done:
            order.append(node)  # type: ignore[arg-type]
            continue
        counts[id(node)] = counts.get(id(node), 0) + 1
        if counts[id(node)] > 1:
            continue
        stack.append((node, True))
        children = node.children()
        if nested_too and isinstance(node, (And, Or)):
            nested.update(id(c) for c in children if type(c) is type(node))
        stack.extend((child, False) for child in reversed(children))
    return [
        n for n in order
        if (counts[id(n)] > 1 or id(n) in nested)
        and not isinstance(n, (Var, Const))
        and n is not root
    ]


def has_shared_subformulas(expr: Expr) -> bool:
    """Whether ``expr`` is a DAG that a tree-shaped (infix) writer would have to copy."""
    return bool(_buffered_nodes(expr, nested_too=False))


def _prefix_tokens(
    root: Expr, refs: dict[int, str], out: list[str], names: Mapping[str, str]
) -> None:
    stack: list[Expr | str] = [root]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            out.append(item)
            continue
        if id(item) in refs and item is not root:
            out.append(refs[id(item)])
            continue
        if isinstance(item, Const):
            out.append("1" if item.value else "0")
        elif isinstance(item, Var):
            out.append(names.get(item.name, item.name) + ("'" if item.primed else ""))
        elif isinstance(item, Not):
            out.append("!")
            stack.append(item.arg)
        elif isinstance(item, (And, Or)):
            if not item.args:
                out.append("1" if isinstance(item, And) else "0")
                continue
            if len(item.args) == 1:
                stack.append(item.args[0])
                continue
            op = "&" if isinstance(item, And) else "|"
            out.append(op)  # right-nested, like SLUGS's converter: & a & b c
            seq: list[Expr | str] = [item.args[0]]
            for a in item.args[1:-1]:
                seq.extend((op, a))
            seq.append(item.args[-1])
            stack.extend(reversed(seq))
        elif isinstance(item, Xor):
            out.append("^")
            stack.extend((item.right, item.left))
        elif isinstance(item, Iff):
            out.extend(("!", "^"))
            stack.extend((item.right, item.left))
        elif isinstance(item, Implies):
            out.extend(("|", "!"))
            stack.extend((item.right, item.left))
        else:
            raise ValueError(
                f"cannot write {type(item).__name__} in slugsin: the format is Boolean and "
                "next-free; bit-blast integers (gaitc.ir.bitblast) and push 'next' first"
            )


def emit_formula(expr: Expr, names: Mapping[str, str] | None = None) -> str:
    """One slugsin line for ``expr``; shared subformulas become a ``$``/``?`` memory buffer.

    ``names`` maps spec names to the names written (see :mod:`slugs_bridge.names`).
    """
    rename = names or {}
    shared = _buffered_nodes(expr)
    out: list[str] = []
    if not shared:
        _prefix_tokens(expr, {}, out, rename)
        return " ".join(out)
    refs: dict[int, str] = {}
    out.extend(("$", str(len(shared) + 1)))
    for index, node in enumerate(shared):
        _prefix_tokens(node, refs, out, rename)
        refs[id(node)] = f"? {index}"
    _prefix_tokens(expr, refs, out, rename)
    return " ".join(out)


def emit_slugsin(spec: GR1Spec, *, comments: bool = True) -> str:
    """Write a Boolean :class:`GR1Spec` as ``.slugsin`` text (sections in canonical order).

    With ``comments`` (as ``gaitc compile`` writes it): a ``# <name>: generated by gaitc``
    header and each clause's origin as a ``# line N: rule`` comment.  Names slugsin cannot
    carry are renamed, with the renaming comment at the top (:mod:`slugs_bridge.names`).
    Raises :class:`ValueError` when the spec has integer variables or non-Boolean nodes.
    """
    if spec.has_integers:
        names = ", ".join(v.name for v in spec.variables() if v.is_integer)
        raise ValueError(
            f"spec has integer variables ({names}); bit-blast it first with "
            "gaitc.ir.bitblast.bitblast"
        )
    renamed = slugsin_renaming(spec)
    return write_sections(
        spec,
        lambda v: renamed.get(v.name, v.name),
        lambda f: emit_formula(f, renamed),
        renamed,
        comments,
    )


def slugsin_renaming(spec: GR1Spec) -> dict[str, str]:
    """``{spec name: written name}`` for the names of Boolean ``spec`` slugsin cannot carry.

    SLUGS answers in the written names; :mod:`slugs_bridge.runner` maps them back.
    """
    return renaming((v.name for v in spec.variables()), "slugsin")
