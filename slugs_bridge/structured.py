"""Reader and writer of SLUGS's infix input format (``.structuredslugs``) with integer variables.

Follows SLUGS's tools/StructuredSlugsParser/compiler.py: declarations ``x`` or
``x:MIN...MAX``, one infix formula per line, and lines that already are slugsin prefix
formulas passed through unchanged (detected the way ``isValidRecursiveSlugsProperty`` does).
"""

from __future__ import annotations

from pathlib import Path

from diagnostics import SlugsFormatError, Span
from gr1.formula import (
    Add,
    And,
    Compare,
    Const,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Node,
    Not,
    Or,
    Term,
    Var,
    Xor,
    walk,
)
from gr1.spec import SECTIONS, Clause, GR1Spec, Origin, Variable
from slugs_bridge.infix import IDENT, KEYWORDS, parse_infix
from slugs_bridge.sections import HEADERS, SourceLine, check_atoms, check_name, read_sections
from slugs_bridge.slugsin import emit_formula, has_shared_subformulas, parse_prefix


def is_prefix_line(text: str, booleans: set[str]) -> bool:
    """Whether SLUGS's converter would pass ``text`` through as a slugsin prefix formula.

    Like ``isValidRecursiveSlugsProperty``: any line with a ``$`` token, or a line whose
    tokens, read right to left as a stack machine over ``! & | ^ 0 1`` and (primed)
    Boolean variables, leave exactly one value.
    """
    tokens = text.split()
    if "$" in tokens:
        return True
    depth = 0
    for tok in reversed(tokens):
        if tok in ("&", "|", "^"):
            if depth < 2:
                return False
            depth -= 1
        elif tok == "!":
            continue
        elif tok in ("0", "1") or (tok[:-1] if tok.endswith("'") else tok) in booleans:
            depth += 1
        else:
            return False
    return depth == 1


def _declaration(src: SourceLine) -> Variable:
    text = src.text.strip()
    span = src.span
    if ":" not in text:
        name = text
        _check_structured_name(name, span)
        return Variable(name, span=span)
    parts = [p.strip() for p in text.split(":")]
    if len(parts) != 2:
        raise SlugsFormatError(
            f"bad declaration '{text}': too many ':'; write name:MIN...MAX", span
        )
    name, bounds = parts
    _check_structured_name(name, span)
    ends = bounds.split("...")
    try:
        if len(ends) != 2:
            raise ValueError
        low, high = int(ends[0]), int(ends[1])
    except ValueError:
        raise SlugsFormatError(
            f"bad integer range '{text}': write name:MIN...MAX with whole numbers, e.g. "
            f"{name}:0...7",
            span,
        ) from None
    if low > high:
        raise SlugsFormatError(
            f"bad integer range '{text}': the minimum {low} is larger than the maximum {high}",
            span,
        )
    return Variable(name, low, high, span=span)


def _check_structured_name(name: str, span: Span) -> None:
    check_name(name, span)
    if "@" in name:
        raise SlugsFormatError(
            f"variable name '{name}' contains '@', which SLUGS reserves for the bits of "
            "integer variables",
            span,
        )
    if name in KEYWORDS or IDENT.fullmatch(name) is None:
        raise SlugsFormatError(
            f"'{name}' cannot be a variable name: use letters, digits, '_' and '.', not "
            "starting with a digit, and none of X F G U W TRUE FALSE next",
            span,
        )


def parse_structuredslugs(text: str, filename: str) -> GR1Spec:
    """Read a ``.structuredslugs`` specification; integer variables stay integers.

    Integer variables become ``Variable(name, low, high)`` and comparisons stay
    :class:`~gr1.formula.Compare` nodes; :func:`gr1.bitblast.bitblast`
    lowers them to bits the way SLUGS's converter does.
    """
    variables: dict[str, list[Variable]] = {"inputs": [], "outputs": []}
    first_seen: dict[str, Span] = {}
    formulas: list[SourceLine] = []
    for src in read_sections(text, filename):
        if src.field not in variables:
            formulas.append(src)
            continue
        var = _declaration(src)
        if var.name in first_seen:
            raise SlugsFormatError(
                f"variable '{var.name}' is declared twice (first on line "
                f"{first_seen[var.name].line}); every name must be unique",
                src.span,
            )
        first_seen[var.name] = src.span
        variables[src.field].append(var)
    all_vars = variables["inputs"] + variables["outputs"]
    booleans = {v.name for v in all_vars if not v.is_integer}
    integers = {v.name: v for v in all_vars if v.is_integer}
    clauses: dict[str, list[Clause]] = {name: [] for name in SECTIONS}
    for src in formulas:
        if is_prefix_line(src.text, booleans):
            formula = parse_prefix(src.text, filename, src.line, booleans)
        else:
            formula = parse_infix(src.text, filename, src.line, booleans, integers)
        origin = Origin(f"structuredslugs {src.header}", src.span)
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
# Binding strength in SLUGS's grammar: higher binds tighter; comparisons are atoms.
_LEVEL: dict[type, int] = {Iff: 1, Implies: 2, Xor: 3, Or: 4, And: 5, Not: 7, Next: 7}
_SYMBOL: dict[type, str] = {Iff: "<->", Implies: "->", Xor: "^", Or: "|", And: "&"}


def _level(node: Node) -> int:
    return _LEVEL.get(type(node), 9)


def _atom(name: str, primed: bool, as_next: bool) -> str:
    if not primed:
        return name
    return f"X {name}" if as_next else name + "'"


def _term(term: Term, as_next: bool = False) -> str:
    if isinstance(term, IntConst):
        if term.value < 0:
            raise ValueError(
                f"cannot write the negative constant {term.value} in structuredslugs"
            )
        return str(term.value)
    if isinstance(term, IntVar):
        return _atom(term.name, term.primed, as_next)
    if isinstance(term, Add):
        # '+' is right-recursive in SLUGS's grammar, so a sum on the left needs brackets.
        left = _term(term.left, as_next)
        if isinstance(term.left, Add):
            left = f"({left})"
        return f"{left} + {_term(term.right, as_next)}"
    raise ValueError(f"not an integer term: {term!r}")


def emit_infix(expr: Expr, as_next: bool = False) -> str:
    """A formula in structuredslugs infix syntax, with the fewest brackets that keep its shape.

    With ``as_next`` a primed variable ``x'`` is written ``X x`` (readable LTL, not SLUGS).
    """
    if isinstance(expr, Const):
        return "TRUE" if expr.value else "FALSE"
    if isinstance(expr, Var):
        return _atom(expr.name, expr.primed, as_next)
    if isinstance(expr, (Not, Next)):
        inner = emit_infix(expr.arg, as_next)
        if _level(expr.arg) < _level(expr):
            inner = f"({inner})"
        return ("!" if isinstance(expr, Not) else "X ") + inner
    if isinstance(expr, (And, Or)):
        if not expr.args:
            return "TRUE" if isinstance(expr, And) else "FALSE"
        if len(expr.args) == 1:
            return emit_infix(expr.args[0], as_next)
        level = _level(expr)
        parts = [emit_infix(a, as_next) for a in expr.args]
        parts = [
            f"({p})" if _level(a) <= level else p for a, p in zip(expr.args, parts, strict=True)
        ]
        return f" {_SYMBOL[type(expr)]} ".join(parts)
    if isinstance(expr, (Iff, Implies, Xor)):
        level = _level(expr)
        left, right = emit_infix(expr.left, as_next), emit_infix(expr.right, as_next)
        if _level(expr.left) < level:
            left = f"({left})"
        if _level(expr.right) <= level:
            right = f"({right})"
        return f"{left} {_SYMBOL[type(expr)]} {right}"
    if isinstance(expr, Compare):
        return f"{_term(expr.left, as_next)} {expr.op} {_term(expr.right, as_next)}"
    raise ValueError(
        f"cannot write {type(expr).__name__} in structuredslugs: sections hold state and "
        "transition formulas only"
    )


def emit_structuredslugs(spec: GR1Spec) -> str:
    """Write a :class:`GR1Spec` as ``.structuredslugs`` text (sections in canonical order).

    Boolean clauses with shared subformulas are written as slugsin ``$`` lines.
    """
    lines: list[str] = []
    for header, field in HEADERS.items():
        if lines:
            lines.append("")
        lines.append(header)
        if field in ("inputs", "outputs"):
            variables: tuple[Variable, ...] = getattr(spec, field)
            for v in variables:
                lines.append(f"{v.name}:{v.low}...{v.high}" if v.is_integer else v.name)
        else:
            lines.extend(_clause_line(c.formula) for c in spec.section(field))
    return "\n".join(lines) + "\n"


def _clause_line(formula: Expr) -> str:
    # A Boolean DAG (e.g. bit-blasted adders) would grow exponentially as a tree; the
    # reader passes '$' lines through, so such clauses are written in prefix form.
    # Formulas nested too deeply for the recursive infix writer also go out in prefix form.
    has_integers = any(isinstance(n, (Compare, IntVar)) for n in walk(formula))
    if not has_integers and has_shared_subformulas(formula):
        return emit_formula(formula)
    try:
        return emit_infix(formula)
    except RecursionError:
        if has_integers:
            raise ValueError("an integer formula nests too deeply to write") from None
        return emit_formula(formula)
