"""Independent verification of counter-strategies: the environment really wins.

Shares the BDD translation and the automaton graph of :mod:`gaitc.verifier.strategy` (not
the solver's fixpoint code); the checks are the duals of a strategy's: the environment's
starts are allowed, every system answer allowed by ρs is present, and every cycle the system
can keep alive satisfies every environment assumption while starving some system goal.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from gaitc.ir.controller import Controller, ControllerKind
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.verifier.logic import Bits
from gaitc.verifier.strategy import Check, VerificationReport, few_nodes

if TYPE_CHECKING:
    from dd.cudd import Function


def verify_counterstrategy(
    spec: GR1Spec, controller: Controller, semantics: Semantics = Semantics.DEFAULT
) -> VerificationReport:
    """Prove that ``controller`` (an environment counter-strategy) makes ``spec`` unrealizable.

    Every run must either reach a position where the system has no move allowed by ρs, or
    satisfy every environment liveness assumption while missing some system goal forever.
    """
    check = Check(spec, controller, semantics)
    if controller.kind != ControllerKind.COUNTERSTRATEGY:
        check.problems.append(f"the controller is a {controller.kind}, not a counter-strategy")
    elif check.well_formed():
        _counter_initial(check)
        _counter_safety(check)
        check.label_edges(lambda a, b: False)
        for i, (rule, _) in enumerate(check.logic.clauses("env_liveness")):
            check.problems += [
                f"nodes {few_nodes(c)}: a cycle through them never satisfies {rule}, "
                "so the environment loses there"
                for c in check.fair_sccs("env_liveness", i, None)
            ]
        check.problems += [f"nodes {few_nodes(c)}: a cycle through them lets the system satisfy "
                           "every system goal infinitely often"
                           for c in check.fair_sccs("none", -1, "sys_liveness")]
    return check.report(ControllerKind.COUNTERSTRATEGY)


def _counter_initial(check: Check) -> None:
    logic, b = check.logic, check.logic.bdd
    theta_e, theta_s = check.conj("env_init", None), check.conj("sys_init", None)
    starts = check.ctrl.initial
    check.problems += [f"initial node {n}: its state {check.show(n)} violates "
                       f"{check.failing('env_init', n)}"
                       for n in starts if not logic.holds(theta_e, check.valuations[n])]
    if not starts:
        if b.exist(set(logic.inputs), theta_e & ~b.exist(set(logic.outputs), theta_s)) == b.false:
            check.problems.append("the counter-strategy has no initial node, but the system can "
                                  "always start")
    elif check.semantics == Semantics.ROBOTICS:  # one losing start allowed by θe ∧ θs suffices
        if not any(logic.holds(theta_s, check.valuations[n]) for n in starts):
            check.problems.append("no initial node of the counter-strategy satisfies sys_init")
    else:  # default: for one input, every start the system may choose must be covered
        groups: dict[Bits, Function] = {}
        for n in starts:
            key = tuple(int(check.valuations[n][v]) for v in logic.inputs)
            cube = b.cube({v: check.valuations[n][v] for v in logic.outputs})
            groups[key] = groups.get(key, b.false) | cube
        gaps = []
        for key, covered in sorted(groups.items()):
            start = dict(zip(logic.inputs, (bool(v) for v in key), strict=True))
            allowed = b.let(start, theta_e & theta_s) if start else theta_e & theta_s
            gaps.append((allowed & ~covered, start))
        if all(gap != b.false for gap, _ in gaps):
            example, _ = logic.pick(gaps[0][0], logic.outputs, primed=False)
            check.problems.append(
                f"default semantics: no initial input covers every start the system may "
                f"choose; input {check.show(gaps[0][1], logic.inputs)} lacks outputs "
                f"{check.show(example, logic.outputs)}")


def _counter_safety(check: Check) -> None:
    logic, b = check.logic, check.logic.bdd
    primed_outputs = {n + "'" for n in logic.outputs}
    dead_ends: set[int] = set()
    for node in check.reachable:
        succ = check.trans(node)
        rho_e, rho_s = check.conj("env_trans", node), check.conj("sys_trans", node)
        if not succ:
            stuck = rho_e & ~b.exist(primed_outputs, rho_s)
            if node not in dead_ends and stuck == b.false:
                check.problems.append(f"node {node}: it has no successor, but the system has a "
                                      "move allowed by the guarantees for every input")
            continue
        if len({check.show(t, logic.inputs) for t in succ}) > 1:
            check.problems.append(f"node {node}: the environment must choose one input, but its "
                                  f"successors carry different inputs")
            continue
        chosen = {n + "'": check.valuations[succ[0]][n] for n in logic.inputs}
        answers = b.let(chosen, rho_s) if chosen else rho_s
        covered = b.false
        for target in succ:
            if not check.holds_next(rho_e, target):
                check.problems.append(f"edge {node} -> {target}: the environment's input "
                                      f"violates {check.failing('env_trans', node, target)}")
            if answers == b.false:
                dead_ends.add(target)  # the system has no legal answer: it loses here
            elif not check.holds_next(rho_s, target):
                rules = check.failing("sys_trans", node, target)
                check.problems.append(f"edge {node} -> {target}: the system answer violates "
                                      f"{rules}; the environment need not consider it")
            covered |= check.next_cube(target, logic.outputs)
        if answers & ~covered != b.false:
            example, _ = logic.pick(answers & ~covered, logic.outputs, primed=True)
            check.problems.append(
                f"node {node}: system answer {check.show(example, logic.outputs)} to input "
                f"{check.show(succ[0], logic.inputs)} is allowed by the guarantees but has no "
                "successor")
