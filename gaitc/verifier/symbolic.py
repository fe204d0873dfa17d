"""Independent checker of symbolic controllers: the closed loop model-checked with BDDs.

The controller file (:mod:`gaitc.ir.bddfile`) is read into the verifier's own manager, next to
its own translation of the spec's clauses (:class:`gaitc.verifier.logic.Logic`), and the run
machine of :mod:`gaitc.sim.symbolic_view` is modelled as it executes: a state of every bit,
a goal counter g (fresh bits), moves of goal g's relation for every input, the counter
advanced with the file's own goals.  Every move the relation offers counts, so what holds
here holds for whichever one the runtime picks.  Checked, over the states reachable from
the initial ones (a least fixpoint of images):

* initial coverage under the semantics, and initial states inside θe ∧ θs;
* completeness (every input ρe allows has a move) and safety (every move keeps ρs);
* liveness: for each system goal j, no reachable state starts a path that satisfies every
  environment goal infinitely often and never goal j: the fair-EG fixpoint
  νZ. ∧_i μY. EX(¬J_j ∧ ((J^e_i ∧ Z) ∨ Y)) of symbolic model checking (Emerson and Lei,
  LICS 1986; Clarke, Grumberg, Hamaguchi, "Another look at LTL model checking", CAV 1994),
  on transition-labelled goals.

It shares no code with the solver's game (the file reader is pure data).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from gaitc.ir.bddfile import SymbolicController, materialize
from gaitc.ir.bitblast import bitblast
from gaitc.ir.bits import bits_mismatch, integer_bits
from gaitc.ir.controller import ControllerKind
from gaitc.ir.cuddlib import cudd
from gaitc.ir.spec import GR1Spec, Semantics, Variable
from gaitc.verifier.logic import Logic
from gaitc.verifier.strategy import MAX_PROBLEMS, VerificationReport

if TYPE_CHECKING:
    from dd.cudd import Function

GOAL_BIT = "#goal"  # no spec name starts with '#', so the counter's bits cannot clash


class _Loop:
    """The closed loop of one controller and one spec, over pre, post and counter bits."""

    def __init__(self, spec: GR1Spec, ctrl: SymbolicController) -> None:
        self.logic = Logic(bitblast(spec), ctrl.order)
        self.bdd, self.ctrl = self.logic.bdd, ctrl
        self.width = max(1, (ctrl.goal_count - 1).bit_length())
        self.g = [f"{GOAL_BIT}{k}" for k in range(self.width)]
        for bit in self.g:
            self.bdd.declare(bit, bit + "'")
        # the counter on top: the loop's relation is then a choice of the goal pair first,
        # each pair's moves below it, not every goal's moves interleaved with the counter
        counter = [n for bit in self.g for n in (bit, bit + "'")]
        rest = sorted(set(self.bdd.vars) - set(counter), key=self.bdd.level_of_var)
        cudd.reorder(self.bdd, {n: k for k, n in enumerate(counter + rest)})
        self.pre = list(self.logic.inputs + self.logic.outputs) + self.g
        self.post = [n + "'" for n in self.pre]
        self.rename = dict(zip(self.post, self.pre, strict=True))
        self.post_in = {n + "'" for n in self.logic.inputs}
        self.post_out = {n + "'" for n in self.logic.outputs}
        self.source = spec  # the spec as written (integers whole), for the witnesses

    def witness(self, bad: Function, moves: bool) -> tuple[dict[str, bool], str]:
        """One assignment of the non-empty ``bad`` (over the state, the next inputs and,
        with ``moves``, the next outputs), and its words: the state, the inputs the
        environment chooses and the move, each variable at its value as the spec names it
        (an integer whole, not its bits), as the explicit verifier names a node's."""
        care = {*self.logic.inputs, *self.logic.outputs, *self.post_in}
        if moves:
            care |= self.post_out
        found = next(self.bdd.pick_iter(bad, care_vars=care))
        state = _values(self.source.variables(), found, "")
        chosen = _values(self.source.inputs, found, "'")
        words = f"for example from the state {state}, the environment choosing {chosen}"
        if moves:
            words += f", moving to {_values(self.source.outputs, found, chr(39))}"
        return found, words

    def section(self, name: str) -> Function:
        out = self.bdd.true
        for _, u in self.logic.clauses(name):
            out &= u
        return out

    def goals(self, name: str) -> list[Function]:
        return [u for _, u in self.logic.clauses(name)] or [self.bdd.true]

    def counter(self, g: int, primed: bool = False) -> Function:
        suffix = "'" if primed else ""
        return self.bdd.cube({b + suffix: bool(g >> k & 1) for k, b in enumerate(self.g)})

    def advance(self, g: int, goals: list[Function]) -> Function:
        """The counter's next value from g: past every goal the move satisfies, in turn."""
        n, out, met = len(goals), self.bdd.false, self.bdd.true
        for t in range(n):
            here = goals[(g + t) % n]
            out |= met & ~here & self.counter((g + t) % n, primed=True)
            met &= here
        return out | (met & self.counter(g, primed=True))

    def image(self, states: Function, trans: Function) -> Function:
        return self.bdd.let(self.rename, self.bdd.exist(set(self.pre), states & trans))

    def pre_image(self, trans: Function, target: Function) -> Function:
        primed = self.bdd.let(dict(zip(self.pre, self.post, strict=True)), target)
        return cudd.and_exists(trans, primed, set(self.post))


#: A further check on the states a run reaches: given the verifier's reading of the spec and
#: those states (current bits), the problem found, or None.
ReachCheck = Callable[[Logic, "Function"], "str | None"]


def verify_symbolic(spec: GR1Spec, ctrl: SymbolicController,
                    semantics: Semantics | None = None,
                    reach_checks: Sequence[ReachCheck] = ()) -> VerificationReport:
    """Prove that the symbolic controller ``ctrl`` realizes ``spec`` (see the module text),
    and run ``reach_checks`` on the reachable states (a compact controller's monitor)."""
    chosen = semantics or ctrl.semantics
    loop = _Loop(spec, ctrl)
    expected = loop.logic.inputs + loop.logic.outputs
    mismatch = bits_mismatch(ctrl.variables, expected)
    if mismatch is not None:
        return _report([mismatch], 0, chosen)
    spec_goals = loop.goals("sys_liveness")
    if ctrl.goal_count != len(spec_goals):
        return _report([f"the controller pursues {ctrl.goal_count} goal(s), the "
                        f"specification has {len(spec_goals)}"], 0, chosen)
    return _check(loop, materialize(loop.bdd, ctrl), chosen, reach_checks)


def _check(loop: _Loop, roots: dict[str, Any], semantics: Semantics,
           reach_checks: Sequence[ReachCheck] = ()) -> VerificationReport:
    b, problems = loop.bdd, []
    outs = set(loop.logic.outputs)
    theta_e, theta_s = loop.section("env_init"), loop.section("sys_init")
    rho_e, rho_s = loop.section("env_trans"), loop.section("sys_trans")
    start = roots["sys_init"] & roots["winning"]
    if semantics == Semantics.ROBOTICS:
        init = roots["env_init"] & start
        if theta_e & theta_s & ~init != b.false:
            problems.append("robotics semantics: a state allowed by env_init and sys_init has "
                            "no initial state of the controller")
    else:
        allowed = b.exist(outs, theta_e)
        init = b.exist(outs, roots["env_init"]) & allowed & start
        if allowed & ~b.exist(outs, init) != b.false:
            problems.append("default semantics: an input allowed by env_init has no initial "
                            "state of the controller")
    if init & ~(theta_e & theta_s) != b.false:
        problems.append("an initial state of the controller violates env_init or sys_init")
    init &= loop.counter(0)
    file_goals, strategies = roots["goals"], roots["strategies"]
    trans = b.false
    for g, relation in enumerate(strategies):
        trans |= loop.counter(g) & relation & rho_e & loop.advance(g, file_goals)
    reach = _reachable(loop, init, trans)
    inputs_ok = b.exist(loop.post_out, rho_e)
    for g, relation in enumerate(strategies):
        here = reach & loop.counter(g)
        offered = b.exist(loop.post_out, relation) & b.exist(loop.post_out, roots["env_trans"])
        stuck = here & inputs_ok & ~offered
        if stuck != b.false:
            _, words = loop.witness(b.exist(set(loop.g), stuck), moves=False)
            problems.append(f"goal {g + 1}: a reachable state has an input the assumptions "
                            f"allow but no move ({words})")
        wrong = here & relation & rho_e & ~rho_s
        if wrong != b.false:
            found, words = loop.witness(b.exist(set(loop.g), wrong), moves=True)
            broken = [rule for rule, u in loop.logic.clauses("sys_trans")
                      if b.let(found, u) == b.false]
            problems.append(f"goal {g + 1}: a move from a reachable state violates sys_trans "
                            f"({words}; it breaks {'; '.join(broken)})")
    env_goals = loop.goals("env_liveness")
    edges = reach & trans
    for rule, goal in _goal_rules(loop):
        if _fair_avoiding(loop, edges & ~goal, env_goals, reach) != b.false:
            problems.append(f"a reachable state starts a run that satisfies every environment "
                            f"liveness assumption infinitely often but never {rule}")
    if reach_checks:
        states = b.exist(set(loop.g), reach)
        for check in reach_checks:
            problem = check(loop.logic, states)
            if problem is not None:
                problems.append(problem)
    count = int(b.count(reach, nvars=len(loop.pre)))
    return _report(problems, count, semantics)


def _values(variables: Sequence[Variable], found: Mapping[str, bool], mark: str) -> str:
    """``variables`` at their values in the assignment ``found`` (``mark``: "'" for the next
    values), integers read off their bits (:func:`gaitc.ir.bits.integer_bits`)."""
    out = []
    for var in variables:
        bits = integer_bits(var)
        if not var.is_integer:
            out.append(f"{var.name}={int(found.get(var.name + mark, False))}")
            continue
        low = var.low or 0
        value = low + sum(1 << k for k, bit in enumerate(bits) if found.get(bit + mark, False))
        out.append(f"{var.name}={value}")
    return ", ".join(out) or "nothing"


def _goal_rules(loop: _Loop) -> list[tuple[str, Function]]:
    found = loop.logic.clauses("sys_liveness")
    return found or [("the trivial goal", loop.bdd.true)]


def _reachable(loop: _Loop, init: Function, trans: Function) -> Function:
    reach, frontier = init, init
    while frontier != loop.bdd.false:
        frontier = loop.image(frontier, trans) & ~reach
        reach |= frontier
    return reach


def _fair_avoiding(loop: _Loop, avoiding: Function, env_goals: list[Function],
                   within: Function) -> Function:
    """The states of ``within`` (closed under ``avoiding``) with a path of ``avoiding``
    edges crossing every environment goal infinitely often: νZ. ∧_i μY. Z ∧ EX over
    avoiding edges of (J^e_i ∧ Z) ∨ Y.  Each μY grows from the goal's image of Z by the images of
    its newest states only (EX distributes over union)."""
    b = loop.bdd
    z = within
    crossing = [avoiding & goal for goal in env_goals]
    while True:
        new_z = z
        for edges in crossing:
            y = loop.pre_image(edges, z) & z
            frontier = y
            while frontier != b.false:
                frontier = loop.pre_image(avoiding, frontier) & z & ~y
                y |= frontier
            new_z &= y
        if new_z == z:
            return z
        z = new_z


def _report(problems: list[str], count: int, semantics: Semantics) -> VerificationReport:
    shown = problems[:MAX_PROBLEMS]
    return VerificationReport(
        ok=not shown,
        problems=tuple(shown),
        notes=(),
        nodes=count,
        edges=0,
        sccs=0,
        kind=ControllerKind.STRATEGY,
        semantics=semantics,
        symbolic=True,
    )
