"""The explicit form: an automaton whose every node is listed (``docs/controller-format.md``).

Its compact form is built through the symbolic one: per goal j, the relation of the moves
the automaton makes from its nodes of rank j (the goal each node pursues), the winning
region the states its nodes hold.  A runtime of those relations picks, as the explicit
extraction does, one move per state, input and goal, so an automaton that keeps one node
per state and goal (the embedded solver's and SLUGS's) keeps its moves; any other is
refused by the proof the caller runs on the result.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

from gaitc.core.modes import Form, Semantics
from gaitc.diagnostics import ControllerError, Span
from gaitc.forms.base import ControllerForm
from gaitc.ir.controller import (
    Controller,
    ControllerKind,
    controller_from_dict,
    controller_to_json,
)

if TYPE_CHECKING:
    from gaitc.compact.controller import CompactController
    from gaitc.core.spec import Spec
    from gaitc.ir.bddfile import SymbolicController
    from gaitc.sim.view import StrategyView
    from gaitc.verifier.strategy import VerificationReport

class ExplicitForm(ControllerForm):
    """An explicit Mealy automaton (or an environment's counter-strategy)."""

    form: ClassVar[Form] = Form.EXPLICIT

    def owns(self, automaton: object) -> bool:
        return isinstance(automaton, Controller)

    def recognises(self, data: Any) -> bool:
        return True  # a file that names no other form (the registry asks the others first)

    def parse(self, data: Any, file: str, spec: Spec) -> Controller:
        return controller_from_dict(data, file, spec.gr1)

    def to_json(self, automaton: Controller) -> str:
        return controller_to_json(automaton)

    def verify(self, spec: Spec, automaton: Controller, semantics: Semantics
               ) -> VerificationReport:
        if automaton.kind == ControllerKind.COUNTERSTRATEGY:
            from gaitc.verifier.counterstrategy import verify_counterstrategy

            return verify_counterstrategy(spec.gr1, automaton, semantics)
        from gaitc.verifier.strategy import verify as verify_strategy

        return verify_strategy(spec.gr1, automaton, semantics)

    def runtime(self, spec: Spec, automaton: Controller, file: str = "") -> StrategyView:
        from gaitc.sim.strategy import strategy_from_controller

        return strategy_from_controller(automaton, spec.gr1, file)

    def size(self, automaton: Controller) -> str:
        return f"{len(automaton.nodes)} nodes"

    def size_json(self, automaton: Controller) -> dict[str, Any]:
        return {"nodes": len(automaton.nodes)}

    def to_compact(self, spec: Spec, automaton: Controller) -> CompactController:
        from gaitc.compact.extraction import compact_from_symbolic

        if automaton.kind == ControllerKind.COUNTERSTRATEGY:
            raise ControllerError(
                "a counter-strategy has no compact form: it is the environment's plan, not "
                "a controller a robot runs", Span("<controller>", 1, 1))
        return compact_from_symbolic(symbolic_of_explicit(spec, automaton), spec.vocabulary)


def symbolic_of_explicit(spec: Spec, automaton: Controller) -> SymbolicController:
    """The explicit automaton as BDD relations, one per goal (see the module's text)."""
    from gaitc.ir.bddfile import SymbolicController, node_table
    from gaitc.solver.canonical import spec_integers
    from gaitc.solver.symbolic import SymbolicSpec

    sym = SymbolicSpec(spec.gr1)
    bdd = sym.bdd
    names = automaton.variables

    def cube(node: int, primed: bool) -> Any:
        bits = automaton.bit_values(node)
        return bdd.cube({(n + "'" if primed else n): bool(bits[n]) for n in names})

    goals = len(sym.sys_live)
    strategies = [bdd.false] * goals
    winning = bdd.false
    for k, node in enumerate(automaton.nodes):
        here = cube(k, primed=False)
        winning |= here
        moves = bdd.false
        for succ in node.trans:
            moves |= cube(succ, primed=True)
        rank = node.rank % goals
        strategies[rank] |= here & moves
    roots = {"winning": winning, "env_init": sym.env_init, "sys_init": sym.sys_init,
             "env_trans": sym.env_trans, "goals": list(sym.sys_live),
             "strategies": strategies}
    order, nodes, refs = node_table(bdd, roots)
    return SymbolicController(
        inputs=tuple(sym.input_bits), outputs=tuple(sym.output_bits), order=order,
        nodes=nodes, roots=refs, integers=spec_integers(sym), semantics=automaton.semantics,
        solver=automaton.solver, source=automaton.source,
        choice=tuple(sorted(sym.input_bits + sym.output_bits,
                            key=sym.choice_rank.__getitem__)))
