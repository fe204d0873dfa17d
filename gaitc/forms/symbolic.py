"""The symbolic form: the strategy's per-goal move relations kept as BDDs
(:mod:`gaitc.ir.bddfile`), run by BDD restrictions (:mod:`gaitc.sim.symbolic_view`)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

from gaitc.compact.extraction import compact_from_symbolic
from gaitc.core.modes import Form, Semantics
from gaitc.forms.base import ControllerForm
from gaitc.ir.bddfile import (
    SymbolicController,
    is_symbolic,
    symbolic_from_dict,
    symbolic_to_json,
)
from gaitc.sim.symbolic_view import SymbolicStrategy
from gaitc.verifier.symbolic import verify_symbolic

if TYPE_CHECKING:
    from gaitc.compact.controller import CompactController
    from gaitc.core.spec import Spec
    from gaitc.sim.view import StrategyView
    from gaitc.verifier.strategy import VerificationReport


class SymbolicForm(ControllerForm):
    """BDDs of the winning region, the initial conditions, ρe and one relation per goal."""

    form: ClassVar[Form] = Form.SYMBOLIC

    def owns(self, automaton: object) -> bool:
        return isinstance(automaton, SymbolicController)

    def recognises(self, data: Any) -> bool:
        return is_symbolic(data)

    def parse(self, data: Any, file: str, spec: Spec) -> SymbolicController:
        return symbolic_from_dict(data, file)

    def to_json(self, automaton: SymbolicController) -> str:
        return symbolic_to_json(automaton)

    def verify(self, spec: Spec, automaton: SymbolicController, semantics: Semantics
               ) -> VerificationReport:
        return verify_symbolic(spec.gr1, automaton, semantics)

    def runtime(self, spec: Spec, automaton: SymbolicController, file: str = ""
                ) -> StrategyView:
        return SymbolicStrategy(automaton, spec.gr1, file)

    def size(self, automaton: SymbolicController) -> str:
        return f"symbolic, {len(automaton.nodes)} BDD nodes"

    def size_json(self, automaton: SymbolicController) -> dict[str, Any]:
        return {"nodes": len(automaton.nodes)}

    def to_compact(self, spec: Spec, automaton: SymbolicController) -> CompactController:
        return compact_from_symbolic(automaton, spec.vocabulary)
