"""The compact form: decision diagrams over the robot's words (:mod:`gaitc.compact`), the
form generated C and the valve board run; proved with its assumption monitor."""

from __future__ import annotations

import sys
from dataclasses import replace
from typing import TYPE_CHECKING, Any, ClassVar

from gaitc.codegen.tables import table_bytes
from gaitc.compact.controller import (
    compact_from_dict,
    compact_to_json,
    is_compact,
    monitor_function,
    to_symbolic,
)
from gaitc.core.modes import Form, Semantics
from gaitc.forms.base import ControllerForm
from gaitc.sim.symbolic_view import SymbolicStrategy
from gaitc.verifier.monitor import monitor_check
from gaitc.verifier.symbolic import verify_symbolic

if TYPE_CHECKING:
    from gaitc.compact.controller import CompactController
    from gaitc.core.spec import Spec
    from gaitc.core.vocabulary import Vocabulary
    from gaitc.sim.view import StrategyView
    from gaitc.verifier.strategy import VerificationReport

#: The notes ``verify`` adds about a compact controller's assumption monitor.
NO_MONITOR = ("the controller carries no assumption monitor: a board running it alone "
              "cannot tell when the assumptions break")
MONITOR_PROVED = "the assumption monitor equals env_trans on every state a run reaches"


class CompactForm(ControllerForm):
    """Decision diagrams per goal, the start and the assumption monitor, over fields."""

    form: ClassVar[Form] = Form.COMPACT

    def owns(self, automaton: object) -> bool:
        # none can exist before gaitc.compact is imported: a plain check need not load it
        module = sys.modules.get("gaitc.compact.controller")
        return module is not None and isinstance(automaton, module.CompactController)

    def recognises(self, data: Any) -> bool:
        return is_compact(data)

    def parse(self, data: Any, file: str, spec: Spec) -> CompactController:
        return compact_from_dict(data, file)

    def vocabulary(self, automaton: CompactController) -> Vocabulary:
        return automaton.vocabulary

    def to_json(self, automaton: CompactController) -> str:
        return compact_to_json(automaton)

    def verify(self, spec: Spec, automaton: CompactController, semantics: Semantics
               ) -> VerificationReport:
        if not automaton.monitored:
            report = verify_symbolic(spec.gr1, to_symbolic(automaton), semantics)
            return replace(report, notes=(*report.notes, NO_MONITOR))
        check = monitor_check(lambda bdd: monitor_function(bdd, automaton),
                              automaton.vocabulary.fields)
        report = verify_symbolic(spec.gr1, to_symbolic(automaton), semantics, [check])
        if not report.ok:
            return report
        return replace(report, notes=(*report.notes, MONITOR_PROVED))

    def runtime(self, spec: Spec, automaton: CompactController, file: str = ""
                ) -> StrategyView:
        return SymbolicStrategy(to_symbolic(automaton, spec.gr1), spec.gr1, file)

    def size(self, automaton: CompactController) -> str:
        c = automaton
        return (f"compact, {c.rules} rules, {c.decision_nodes} decision nodes "
                f"(+{c.monitor_nodes} for the assumption monitor), {table_bytes(c)} bytes "
                "of tables")

    def size_json(self, automaton: CompactController) -> dict[str, Any]:
        c = automaton
        return {"nodes": c.decision_nodes,
                "compact": {"rules": c.rules, "decision_nodes": c.decision_nodes,
                            "monitor_nodes": c.monitor_nodes, "moves": len(c.moves),
                            "table_bytes": table_bytes(c)}}

    def to_compact(self, spec: Spec, automaton: CompactController) -> CompactController:
        return automaton
