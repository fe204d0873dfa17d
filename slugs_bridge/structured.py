"""Reader and writer of SLUGS's infix input format (``.structuredslugs``) with integer variables.

Follows SLUGS's tools/StructuredSlugsParser/compiler.py: declarations ``x`` or
``x:MIN...MAX``, one infix formula per line, and lines that already are slugsin prefix
formulas passed through unchanged (detected the way ``isValidRecursiveSlugsProperty`` does).
The writer is the one ``gaitc compile`` uses: origin comments, a header, renamed names
(:mod:`slugs_bridge.names`), and prefix lines for shared Boolean formulas.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from gaitc.diagnostics import SlugsFormatError, Span
from gaitc.ir.formula import Compare, Expr, IntVar, walk
from gaitc.ir.spec import SECTIONS, Clause, GR1Spec, Origin, Variable
from slugs_bridge.infix import IDENT, KEYWORDS, parse_infix
from slugs_bridge.infixtext import emit_infix as emit_infix
from slugs_bridge.names import check_renaming, read_renaming, renaming
from slugs_bridge.sections import (
    SourceLine,
    check_atoms,
    check_name,
    read_sections,
    write_sections,
)
from slugs_bridge.shapes import MAX_DIGITS, prefix_exact, tree_size
from slugs_bridge.slugsin import emit_formula, has_shared_subformulas, parse_prefix

#: A shared formula whose tree would have more nodes than this is written in prefix form
#: even when slugsin spells it only up to equivalence (see :func:`prefix_line`).
TREE_LIMIT = 100_000


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
        if len(ends) != 2 or any(len(e.strip().lstrip("-")) > MAX_DIGITS for e in ends):
            raise ValueError  # (a range beyond MAX_DIGITS digits could never be solved)
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
    :class:`~gaitc.ir.formula.Compare` nodes; :func:`gaitc.ir.bitblast.bitblast`
    lowers them to bits the way SLUGS's converter does.  Names renamed by the writer (the
    renaming comment at the top) get their spec names back.
    """
    back, where = read_renaming(text, filename)
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
    check_renaming(back, first_seen, where)
    all_vars = variables["inputs"] + variables["outputs"]
    booleans = {v.name for v in all_vars if not v.is_integer}
    integers = {v.name: v for v in all_vars if v.is_integer}
    clauses: dict[str, list[Clause]] = {name: [] for name in SECTIONS}
    for src in formulas:
        if is_prefix_line(src.text, booleans):
            formula = parse_prefix(src.text, filename, src.line, booleans, back)
        else:
            formula = parse_infix(src.text, filename, src.line, booleans, integers, back)
        origin = Origin(f"structuredslugs {src.header}", src.span)
        clauses[src.field].append(Clause(formula, origin))
    spec = GR1Spec(
        inputs=tuple(replace(v, name=back.get(v.name, v.name)) for v in variables["inputs"]),
        outputs=tuple(replace(v, name=back.get(v.name, v.name)) for v in variables["outputs"]),
        name=Path(filename).stem,
        **{name: tuple(items) for name, items in clauses.items()},
    )
    check_atoms(spec)
    return spec


# ---------------------------------------------------------------- writer
def emit_structuredslugs(spec: GR1Spec, *, comments: bool = True) -> str:
    """Write a :class:`GR1Spec` as ``.structuredslugs`` text (sections in canonical order).

    With ``comments`` (as ``gaitc compile`` writes it): a ``# <name>: generated by gaitc``
    header and each clause's origin as a ``# line N: rule`` comment.  Names the format
    cannot carry (``F``, ``next``, ``a@1``, ...) are renamed, with the renaming comment at
    the top; a clause :func:`prefix_line` picks is written as a slugsin prefix line.
    """
    renamed = renaming((v.name for v in spec.variables()), "structuredslugs")

    def declaration(v: Variable) -> str:
        name = renamed.get(v.name, v.name)
        return f"{name}:{v.low}...{v.high}" if v.is_integer else name

    def clause_line(formula: Expr) -> str:
        if prefix_line(formula):
            return emit_formula(formula, renamed)
        return emit_infix(formula, names=renamed)

    return write_sections(spec, declaration, clause_line, renamed, comments)


def prefix_line(formula: Expr) -> bool:
    """Whether a clause is written as a slugsin prefix line (which the reader passes through).

    A Boolean formula with shared subformulas (a DAG, e.g. one read from a slugsin ``$``
    line) would grow as a tree, up to exponentially: it goes out in prefix form, with the
    DAG kept in a ``$`` buffer, when slugsin spells it node for node
    (:func:`slugs_bridge.shapes.prefix_exact`) or when its tree would exceed
    :data:`TREE_LIMIT` nodes (then the line read back is only equivalent).
    """
    if any(isinstance(n, (Compare, IntVar)) for n in walk(formula)):
        return False
    if not has_shared_subformulas(formula):
        return False
    return prefix_exact(formula) or tree_size(formula, TREE_LIMIT) > TREE_LIMIT
