"""Readable LTL text of a GR(1) spec: (θe ∧ □ρe ∧ □◇Je) → (θs ∧ □ρs ∧ □◇Js), one conjunct a line.

ASCII operators: ``G`` always, ``F`` eventually, ``X`` next state, ``! & | ^ -> <->``;
each conjunct carries a ``#`` comment naming the rule and source line it came from.
"""

from __future__ import annotations

from gr1.spec import Clause, GR1Spec, Variable
from slugs_bridge.slugsin import emit_formula
from slugs_bridge.structured import emit_infix

_PARTS = (
    ("assumptions (environment)", ("env_init", "env_trans", "env_liveness")),
    ("guarantees (system)", ("sys_init", "sys_trans", "sys_liveness")),
)
_PREFIX = {"init": "", "trans": "G ", "liveness": "G F "}


def _declare(variables: tuple[Variable, ...]) -> str:
    if not variables:
        return "(none)"
    return ", ".join(
        f"{v.name} in {v.low}..{v.high}" if v.is_integer else v.name for v in variables
    )


def _comment(clause: Clause) -> str:
    origin = clause.origin
    if origin is None:
        return ""
    where = f" ({origin.span})" if origin.span is not None else ""
    return f"  # {origin.rule}{where}"


def _side(spec: GR1Spec, sections: tuple[str, ...]) -> list[str]:
    rows: list[tuple[str, str]] = []
    for section in sections:
        prefix = _PREFIX[section.split("_", 1)[1]]
        for clause in spec.section(section):
            try:
                body = emit_infix(clause.formula, as_next=True)
            except RecursionError:
                body = "slugsin: " + emit_formula(clause.formula)
            text = f"{prefix}({body})" if prefix else body
            rows.append((text, _comment(clause)))
    if not rows:
        return ["    TRUE"]
    return [
        f"  {'  ' if i == 0 else '& '}{text}{comment}" for i, (text, comment) in enumerate(rows)
    ]


def emit_ltl(spec: GR1Spec) -> str:
    """The spec as one LTL implication, assumptions first, one conjunct per line."""
    title = f" of {spec.name}" if spec.name else ""
    lines = [
        f"# GR(1) specification{title} in LTL: G = always, F = eventually, X = next state",
        f"# inputs (environment): {_declare(spec.inputs)}",
        f"# outputs (system): {_declare(spec.outputs)}",
    ]
    for index, (label, sections) in enumerate(_PARTS):
        if index:
            lines.append("->")
        lines.append(f"(  # {label}")
        lines.extend(_side(spec, sections))
        lines.append(")")
    return "\n".join(lines) + "\n"
