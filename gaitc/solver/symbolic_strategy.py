"""The strategy of a solved game kept as BDDs: a :class:`~gaitc.ir.bddfile.SymbolicController`.

The per-goal move relations are those of the explicit extraction (:func:`gaitc.solver.strategy.
goal_strategies`, after Bloem et al., JCSS 78(3) 2012, Sect. 5): for goal j and every
state and input, the moves of the first layer of the last Z round that covers the case.  A
run that keeps to them reaches goal j, whatever the environment does within ρe and its
goals; a runtime picks one move per step (:mod:`gaitc.sim.symbolic_view`).  Nothing is
enumerated here, so the controller's size is that of its BDDs, not of its state space.
Move preferences (:mod:`gaitc.solver.preferences`, issue 13) narrow the relations themselves, so
the runtime needs nothing of them.
"""

from __future__ import annotations

from gaitc.ir.bddfile import SymbolicController, node_table
from gaitc.ir.spec import Semantics
from gaitc.solver.canonical import spec_integers
from gaitc.solver.game import GameResult, Limits, goal_strategies
from gaitc.solver.preferences import MovePreferences
from gaitc.solver.symbolic import SymbolicSpec


def symbolic_controller(sym: SymbolicSpec, result: GameResult, semantics: Semantics,
                        prefer: MovePreferences | None = None,
                        limits: Limits | None = None) -> SymbolicController:
    """The symbolic controller of a realizable game (``result`` needs its layers); with
    ``prefer`` each goal's relation keeps only the preferred moves
    (:meth:`~gaitc.solver.preferences.MovePreferences.relation`)."""
    strategies = goal_strategies(sym, result)
    if prefer is not None:
        narrowed = []
        for j, strategy in enumerate(strategies):
            if limits is not None:
                limits.report(f"choosing the preferred moves: goal {j + 1} of "
                              f"{len(strategies)}", fraction=j / len(strategies))
            narrowed.append(prefer.relation(j, strategy))
        strategies = narrowed
    roots = {
        "winning": result.winning,
        "env_init": sym.env_init,
        "sys_init": sym.sys_init,
        "env_trans": sym.env_trans,
        "goals": list(sym.sys_live),
        "strategies": strategies,
    }
    order, nodes, refs = node_table(sym.bdd, roots)
    return SymbolicController(
        inputs=tuple(sym.input_bits), outputs=tuple(sym.output_bits), order=order,
        nodes=nodes, roots=refs, integers=spec_integers(sym), semantics=semantics,
        choice=tuple(sorted(sym.input_bits + sym.output_bits, key=sym.choice_rank.__getitem__)))
