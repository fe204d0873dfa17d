"""Readable LTL text of a GR(1) spec: (θe ∧ □ρe ∧ □◇Je) → (θs ∧ □ρs ∧ □◇Js), one conjunct a line.

ASCII operators: ``G`` always, ``F`` eventually, ``X`` next state, ``! & | ^ -> <->``;
each conjunct carries a ``#`` comment naming the rule and source line it came from.
:func:`emit_ltl` writes it and :func:`parse_ltl` reads it back to the same IR: the
declarations live in the leading comments, names that are operators here (``G``, ``X``,
...) are renamed as in :mod:`slugs_bridge.names`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from gaitc.diagnostics import SlugsFormatError, Span, source_lines
from gaitc.ir.formula import Compare, Expr, IntVar, walk
from gaitc.ir.spec import Clause, GR1Spec, Origin, Section, Variable, section_named
from slugs_bridge.infix import parse_infix
from slugs_bridge.infixtext import emit_infix
from slugs_bridge.names import (
    check_renaming,
    is_valid_name,
    one_line,
    read_renaming,
    renaming,
    renaming_comment,
)
from slugs_bridge.sections import FIELD_HEADERS, check_atoms
from slugs_bridge.shapes import tree_size
from slugs_bridge.slugsin import emit_formula, parse_prefix

_PARTS = (
    ("assumptions (environment)", "env"),
    ("guarantees (system)", "sys"),
)
_PREFIX = {"init": "", "trans": "G ", "liveness": "G F "}
_DECLARED = {"inputs": "# inputs (environment): ", "outputs": "# outputs (system): "}
_FALLBACK = "slugsin: "
#: A formula whose tree would exceed this many nodes is written as a slugsin line.
TREE_LIMIT = 100_000


def _declare(variables: tuple[Variable, ...], renamed: dict[str, str]) -> str:
    if not variables:
        return "(none)"
    return ", ".join(
        renamed.get(v.name, v.name) + (f" in {v.low}..{v.high}" if v.is_integer else "")
        for v in variables
    )


def _comment(clause: Clause) -> str:
    origin = clause.origin
    if origin is None:
        return ""
    where = f" ({origin.span})" if origin.span is not None else ""
    return "  # " + one_line(f"{origin.rule}{where}")


def _body(formula: Expr, renamed: dict[str, str]) -> str:
    if tree_size(formula, TREE_LIMIT) > TREE_LIMIT and not any(
        isinstance(n, (Compare, IntVar)) for n in walk(formula)
    ):
        return _FALLBACK + emit_formula(formula, renamed)
    return emit_infix(formula, as_next=True, names=renamed)


def _side(spec: GR1Spec, player: str, renamed: dict[str, str]) -> list[str]:
    rows: list[tuple[str, str]] = []
    for part, prefix in _PREFIX.items():
        for clause in spec.section(section_named(player, part)):
            body = _body(clause.formula, renamed)
            rows.append((f"{prefix}({body})" if prefix else body, _comment(clause)))
    if not rows:
        return ["    TRUE"]
    if rows[0][0] == "TRUE" and len(rows) == 1:
        rows[0] = ("(TRUE)", rows[0][1])  # one clause TRUE, not an empty side
    return [
        f"  {'  ' if i == 0 else '& '}{text}{comment}" for i, (text, comment) in enumerate(rows)
    ]


def emit_ltl(spec: GR1Spec) -> str:
    """The spec as one LTL implication, assumptions first, one conjunct per line."""
    renamed = renaming((v.name for v in spec.variables()), "ltl")
    title = f" of {one_line(spec.name)}" if spec.name else ""
    lines = [f"# GR(1) specification{title} in LTL: G = always, F = eventually, X = next state"]
    lines.extend(renaming_comment(renamed))
    lines.append(_DECLARED["inputs"] + _declare(spec.inputs, renamed))
    lines.append(_DECLARED["outputs"] + _declare(spec.outputs, renamed))
    for index, (label, player) in enumerate(_PARTS):
        if index:
            lines.append("->")
        lines.append(f"(  # {label}")
        lines.extend(_side(spec, player, renamed))
        lines.append(")")
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- reader
@dataclass(frozen=True)
class _Line:
    text: str  # without its comment and surrounding blanks
    number: int
    column: int  # of the text's first character
    raw: str


def _lines(text: str) -> tuple[list[_Line], dict[str, _Line]]:
    body: list[_Line] = []
    declared: dict[str, _Line] = {}
    for number, raw in enumerate(source_lines(text), start=1):
        stripped = raw.strip()
        for field, marker in _DECLARED.items():
            if stripped.startswith(marker) and not body and field not in declared:
                start = raw.index(marker) + len(marker)
                declared[field] = _Line(raw[start:].strip(), number, start + 1, raw)
        content = raw.split("#", 1)[0].rstrip()
        if content.strip():
            column = len(content) - len(content.lstrip()) + 1
            body.append(_Line(content.strip(), number, column, raw))
    return body, declared


def _declarations(
    line: _Line | None, field: str, filename: str, seen: dict[str, Span]
) -> list[Variable]:
    span = Span(filename, line.number if line else 1, line.column if line else 1)
    if line is None:
        raise SlugsFormatError(
            f"the LTL text has no '{_DECLARED[field].strip()}' comment declaring its {field}",
            span,
        )
    if line.text == "(none)":
        return []
    out: list[Variable] = []
    for item in line.text.split(","):
        name, _, bounds = item.strip().partition(" in ")
        low = high = None
        if bounds:
            ends = bounds.split("..")
            try:
                low, high = int(ends[0]), int(ends[1])
            except (ValueError, IndexError):
                raise SlugsFormatError(
                    f"bad integer range '{item.strip()}': write name in MIN..MAX", span
                ) from None
        if not is_valid_name(name, "ltl"):
            raise SlugsFormatError(f"'{name}' cannot be a variable name in LTL text", span)
        if name in seen:
            raise SlugsFormatError(f"variable '{name}' is declared twice", span)
        seen[name] = span
        out.append(Variable(name, low, high, span=span))
    return out


def parse_ltl(text: str, filename: str) -> GR1Spec:
    """Read the text :func:`emit_ltl` writes back into a :class:`GR1Spec`.

    Declarations come from the ``# inputs``/``# outputs`` comments, renamed names from the
    renaming comment; each conjunct line is an initial condition, ``G (…)`` (safety) or
    ``G F (…)`` (liveness) on the side of the implication it stands on.
    """
    back, where = read_renaming(text, filename)
    body, declared = _lines(text)
    seen: dict[str, Span] = {}
    inputs = _declarations(declared.get("inputs"), "inputs", filename, seen)
    outputs = _declarations(declared.get("outputs"), "outputs", filename, seen)
    check_renaming(back, seen, where)
    booleans = {v.name for v in inputs + outputs if not v.is_integer}
    integers = {v.name: v for v in inputs + outputs if v.is_integer}
    clauses: dict[str, list[Clause]] = {}
    sides = _split_sides(body, filename)
    for player, lines in zip(("env", "sys"), sides, strict=True):
        for index, line in enumerate(lines):
            if len(lines) == 1 and line.text == "TRUE":
                continue  # an empty side
            section, formula = _conjunct(line, index, player, filename, booleans, integers, back)
            origin = Origin(f"ltl {FIELD_HEADERS[section]}",
                            Span(filename, line.number, line.column))
            clauses.setdefault(section, []).append(Clause(formula, origin))
    spec = GR1Spec(
        inputs=tuple(Variable(back.get(v.name, v.name), v.low, v.high, v.span) for v in inputs),
        outputs=tuple(Variable(back.get(v.name, v.name), v.low, v.high, v.span)
                      for v in outputs),
        name=Path(filename).stem,
        **{name: tuple(items) for name, items in clauses.items()},
    )
    check_atoms(spec)
    return spec


def _split_sides(body: list[_Line], filename: str) -> tuple[list[_Line], list[_Line]]:
    texts = [line.text for line in body]
    shape = "'(' conjuncts ')' '->' '(' conjuncts ')'"
    try:
        close_env = texts.index(")")
        close_sys = len(texts) - 1
        if texts[0] != "(" or texts[close_env + 1] != "->" or texts[close_env + 2] != "(" \
                or texts[close_sys] != ")" or close_sys <= close_env + 2:
            raise ValueError
    except (ValueError, IndexError):
        at = body[0] if body else None
        raise SlugsFormatError(
            f"this is not the LTL text gaitc writes: expected {shape}",
            Span(filename, at.number if at else 1, at.column if at else 1),
        ) from None
    return body[1:close_env], body[close_env + 3:close_sys]


def _conjunct(
    line: _Line, index: int, player: str, filename: str, booleans: set[str],
    integers: dict[str, Variable], back: dict[str, str],
) -> tuple[Section, Expr]:
    text, column = line.text, line.column
    if index and not text.startswith("& "):
        raise SlugsFormatError("a conjunct after the first must start with '& '",
                               Span(filename, line.number, column))
    if index:
        text, column = text[2:].lstrip(), column + len(text) - len(text[2:].lstrip())
    part = "init"
    for name, prefix in (("liveness", "G F ("), ("trans", "G (")):
        if text.startswith(prefix) and text.endswith(")"):
            part, text, column = name, text[len(prefix):-1], column + len(prefix)
            break
    section = section_named(player, part)
    pad = " " * (column - 1)
    if text.startswith(_FALLBACK):
        pad += " " * len(_FALLBACK)
        return section, parse_prefix(pad + text[len(_FALLBACK):], filename, line.number,
                                     booleans, back)
    return section, parse_infix(pad + text, filename, line.number, booleans, integers, back,
                                next_atoms=True)
