"""The GR(1) game as gr1c and omega read it: checked sections and liveness over one state.

Both peers take the game of Bloem et al. (JCSS 78(3), 2012) in its textbook shape: θe over
inputs, θs over the first state, ρe over the state and the next inputs, ρs over the state
and the whole next state, and each liveness goal □◇φ over one state.  gaitc's IR allows
what SLUGS allows, which is the same except that a liveness clause may mention next-state
values (a goal on transitions).  A clause whose variables are all primed is read on the
state it reaches: □◇φ' holds on a play exactly when □◇φ does, since the two sequences of
truth values differ by one step, so the set of winning plays, and with it every verdict,
is the same.  A clause that mixes current and next values has no such reading and is a
:class:`~gaitc.diagnostics.PeerFormatError` that names it.
"""

from __future__ import annotations

from gaitc.diagnostics import PeerFormatError
from gaitc.ir.formula import Expr, IntVar, Var, atoms, walk
from gaitc.ir.spec import Clause, GR1Spec, Section, Variable
from gaitc.ir.traversal import Node, rebuild

#: How a section is named in messages.
_WORDS: dict[Section, str] = {
    "env_init": "environment initial", "sys_init": "system initial",
    "env_trans": "environment transition", "sys_trans": "system transition",
    "env_liveness": "environment liveness", "sys_liveness": "system liveness",
}


def peer_game(spec: GR1Spec) -> GR1Spec:
    """``spec`` with every liveness clause over one state, checked for the peers' shape.

    Raises :class:`~gaitc.diagnostics.PeerFormatError` for a liveness clause that mixes
    current and next-state values, and for what no GR(1) reader accepts (an undeclared
    variable, a prime in an initial condition, an output in θe, a next output in ρe).
    """
    _check_atoms(spec)
    return spec.with_sections(
        env_liveness=tuple(_one_state(c, "env_liveness", k)
                           for k, c in enumerate(spec.env_liveness, 1)),
        sys_liveness=tuple(_one_state(c, "sys_liveness", k)
                           for k, c in enumerate(spec.sys_liveness, 1)),
    )


def _shown(name: str, primed: bool) -> str:
    return name + "'" if primed else name


def _one_state(clause: Clause, section: Section, number: int) -> Clause:
    """The clause itself, or its formula unprimed when every variable in it is primed."""
    used = atoms(clause.formula)
    primes = {primed for _, primed in used}
    if primes != {True}:
        if primes == {True, False}:
            now = min(name for name, primed in used if not primed)
            later = min(name for name, primed in used if primed)
            span = clause.origin.span if clause.origin is not None else None
            raise PeerFormatError(
                f"{_WORDS[section]} clause {number} mixes current and next-state values "
                f"('{now}' and '{later}''): gr1c and omega read a liveness goal on one "
                "state only",
                span,
                hint="write it over next-state values only (□◇φ' is read as □◇φ) or over "
                "current values only",
            )
        return clause
    return Clause(_unprimed(clause.formula), clause.origin)


def _unprimed(expr: Expr) -> Expr:
    def swap(node: Node) -> Node | None:
        if isinstance(node, (Var, IntVar)) and node.primed:
            return type(node)(node.name, False, span=node.span)
        return None

    return rebuild(expr, swap)


def _check_atoms(spec: GR1Spec) -> None:
    inputs = {v.name: v for v in spec.inputs}
    outputs = {v.name: v for v in spec.outputs}
    for section in _WORDS:
        for number, clause in enumerate(spec.section(section), 1):
            where = f"{_WORDS[section]} clause {number}"
            for node in walk(clause.formula):
                if isinstance(node, (Var, IntVar)):
                    _check_atom(node, section, where, inputs, outputs)


def _check_atom(node: Var | IntVar, section: Section, where: str,
                inputs: dict[str, Variable], outputs: dict[str, Variable]) -> None:
    shown = _shown(node.name, node.primed)
    declared = inputs.get(node.name) or outputs.get(node.name)
    if declared is None:
        raise PeerFormatError(f"{where} uses '{node.name}', which is not declared", node.span)
    if declared.is_integer != isinstance(node, IntVar):
        kind = "an integer" if declared.is_integer else "a Boolean"
        raise PeerFormatError(f"{where} uses {kind} variable '{node.name}' as the other kind",
                              node.span)
    if node.primed and section in ("env_init", "sys_init"):
        raise PeerFormatError(f"{where} uses the next-state value '{shown}'", node.span)
    if section == "env_init" and node.name in outputs:
        raise PeerFormatError(f"{where} uses the output '{node.name}': θe may constrain "
                              "inputs only", node.span)
    if section == "env_trans" and node.primed and node.name in outputs:
        raise PeerFormatError(f"{where} uses the next output '{shown}': the environment "
                              "moves before the system", node.span)
