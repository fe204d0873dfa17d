"""GR(1) fragment check for assume/guarantee formulas: resolve atoms, sort into sections.

``φ`` is an initial condition, ``always φ`` safety, ``always eventually φ`` liveness
(Bloem et al., "Synthesis of Reactive(1) Designs", 2012; thesis section 3.2.1).
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping, Sequence

from gaitc.diagnostics import FormulaError, Span, SpecSemanticError
from gaitc.ir import formula as f
from gaitc.ir.traversal import Node, fold
from ltlcompiler.model import Section, UserFormula
from ltlcompiler.names import Namespace

_SHAPES = "'φ' (initial), 'always φ' (safety) or 'always eventually φ' (liveness)"


def _strip_prefix(expr: f.Expr) -> tuple[Section, f.Expr]:
    """Split the temporal prefix off; reject the shapes GR(1) cannot express."""
    if isinstance(expr, f.Always):
        inner = expr.arg
        if isinstance(inner, f.Eventually):
            return Section.LIVENESS, inner.arg
        if isinstance(inner, f.Always):
            raise FormulaError(
                "'always always φ' is not a GR(1) shape; write 'always φ' once", inner.span
            )
        return Section.TRANS, inner
    if isinstance(expr, f.Eventually):
        if isinstance(expr.arg, f.Always):
            raise FormulaError(
                "'eventually always φ' (persistence) is outside GR(1); a GR(1) formula must "
                f"have the shape {_SHAPES}",
                expr.span,
            )
        raise FormulaError(
            "'eventually φ' alone is outside GR(1), which can only demand that φ holds "
            "infinitely often: write 'always eventually φ'",
            expr.span,
        )
    return Section.INIT, expr


class FormulaChecker:
    """Checks user formulas against the declared names (legs with their health levels)."""

    def __init__(self, ns: Namespace, health: Mapping[str, int], blocked: set[str]) -> None:
        self.ns = ns
        self.health = health
        self.blocked = blocked

    def check(self, expr: f.Expr, span: Span | None, assumption: bool) -> UserFormula:
        section, body = _strip_prefix(expr)
        self._walk(body, section, assumption, under_next=False)
        return UserFormula(section, body, span=span)

    def _walk(self, root: f.Expr, section: Section, assumption: bool, under_next: bool) -> None:
        """Check every node of ``root``, top-down and left to right (the first error wins)."""

        def enter(node: Node) -> Sequence[Node]:
            if isinstance(node, (f.Always, f.Eventually)):
                word = "always" if isinstance(node, f.Always) else "eventually"
                raise FormulaError(
                    f"'{word}' cannot appear inside a formula: GR(1) allows only {_SHAPES}, "
                    "with the temporal words at the very start",
                    node.span,
                )
            if isinstance(node, f.Next):
                if section is Section.INIT:
                    raise FormulaError(
                        "an initial condition cannot use 'next', since it describes only the "
                        "first state; start the formula with 'always' to make it a safety "
                        "formula",
                        node.span,
                    )
                if under_next:
                    raise FormulaError(
                        "'next' inside 'next' is outside GR(1): a formula may look one step "
                        "ahead only",
                        node.span,
                    )
                self._walk(node.arg, section, assumption, under_next=True)
                return ()
            if isinstance(node, f.Var):
                self._proposition(node, assumption, under_next)
                return ()
            if isinstance(node, f.Compare):
                self._comparison(node)
                return ()
            return [child for child in node.children() if isinstance(child, f.Expr)]

        fold(root, lambda node, results: None, enter)

    def robot_free(self, expr: f.Expr) -> bool:
        """Whether ``expr`` names nothing the robot chooses (no region, gait or noGait):
        only hazards, leg health and constants, all the environment's.  Iterative: a
        formula may nest thousands deep (tests/language/test_deep_nesting.py)."""
        stack = [expr]
        while stack:
            node = stack.pop()
            if isinstance(node, f.Var) and self.ns.kinds.get(node.name) in ("region", "gait"):
                return False
            stack.extend(c for c in node.children() if isinstance(c, f.Expr))
        return True

    def _proposition(self, var: f.Var, assumption: bool, under_next: bool) -> None:
        kind = self.ns.kinds.get(var.name)
        if kind == "leg":
            raise SpecSemanticError(
                f"leg '{var.name}' is not a proposition; compare its health, e.g. "
                f"health({var.name}) >= 2 or failed({var.name})",
                var.span,
            )
        if kind is None:
            usable = [n for n, k in self.ns.kinds.items()
                      if k in ("region", "gait", "hazard") and n not in self.blocked]
            raise SpecSemanticError(
                f"unknown name '{var.name}' in formula; formulas may use regions, gaits, "
                "hazards, noGait and health(LEG)",
                var.span,
                hint=_nearest(var.name, [*usable, "noGait"]),
            )
        if var.name in self.blocked:
            raise SpecSemanticError(
                f"region '{var.name}' is a blocked cell, so the robot is never there; "
                "remove it from the formula",
                var.span,
            )
        if assumption and under_next and kind in ("region", "gait"):
            raise FormulaError(
                f"assumption uses next({var.name}), but {var.name} is a {kind}, which the robot "
                "chooses after the environment moves; an assumption may apply next only to "
                "hazards and leg health (move it to a guarantee)",
                var.span,
            )

    def _comparison(self, cmp: f.Compare) -> None:
        leg, value = cmp.left, cmp.right
        if not isinstance(leg, f.IntVar) or not isinstance(value, f.IntConst):
            raise FormulaError("health comparisons have the form health(LEG) OP k", cmp.span)
        kind = self.ns.kinds.get(leg.name)
        if kind != "leg":
            what = f"a {kind}" if kind else "not declared"
            legs = [n for n, k in self.ns.kinds.items() if k == "leg"]
            raise SpecSemanticError(
                f"health({leg.name}) needs a leg, but '{leg.name}' is {what}", leg.span,
                hint=_nearest(leg.name, legs),
            )
        levels = self.health[leg.name]
        if not 1 <= value.value <= levels:
            raise SpecSemanticError(
                f"health({leg.name}) is compared with {value.value}, but {leg.name} has health "
                f"levels 1..{levels}",
                value.span,
            )


def _nearest(word: str, names: list[str]) -> str | None:
    """"did you mean" the declared name closest to a misspelt one (None if none is close)."""
    close = difflib.get_close_matches(word, names, n=1, cutoff=0.6)
    return f"did you mean '{close[0]}'?" if close else None
