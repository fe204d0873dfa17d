"""The GR(1) fixpoints: the system's winning region and the initial-state check.

Implements the three-nested fixpoint of Bloem, Jobstmann, Piterman, Pnueli, Sa'ar,
"Synthesis of Reactive(1) designs" (JCSS 78(3), 2012) in SLUGS's transition-based form
(Ehlers & Raman, CAV 2016): νZ. ∧_j μY. ∨_i νX. CPre((J^s_j ∧ Z') ∨ Y' ∨ (¬J^e_i ∧ X')) with
CPre(T) = ∀x'. ρe → ∃y'. ρs ∧ T, liveness goals evaluated on the transition, inner X
fixpoints recycled across Z rounds (Browne, Clarke, Jha, Long, Marrero 1997) when asked for;
Z narrowed goal by goal, each goal solved again only while Z shrinks (see Game.solve); each
goal's μY started from the goal's attractor, which decides the goal without an X fixpoint
when it holds Z (Game._attractor).
"""

from __future__ import annotations

import os
import signal
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from gaitc.diagnostics import GaitcError, SolverError
from gaitc.diagnostics.processes import Outcome
from gaitc.ir.cuddlib import cudd
from gaitc.ir.spec import Semantics
from gaitc.solver.options import (
    MISFIT_RATIO,
    MISFIT_WORK,
    REFIT_SIFT_WORK,
    RESIFT_BLOWUP,
    RESIFT_NODES,
    RESIFT_WORK,
    RESTART_NODES,
    SMALL_BITS,
    SMALL_WORK,
    WORK_EVERY,
    WORK_SAMPLES,
)
from gaitc.solver.progress import Progress, Stage, goal_titles
from gaitc.solver.symbolic import BDDNode, SymbolicSpec

__all__ = ["ControllerTooLarge", "Game", "GameResult", "GameStats", "Limits", "OrderMisfit",
           "Progress", "Stage", "out_of_memory", "too_large"]


def time_limit_error(seconds: float, what: str = "synthesis") -> SolverError:
    """The error of a solver run (``what``) stopped by its time limit (here, or killed by a
    parent)."""
    return SolverError(
        f"{what} stopped after the time limit of {seconds:g} s",
        hint="raise --timeout, or simplify the specification (fewer grid cells or health "
        "levels, the binary encoding)",
    )


def out_of_memory() -> SolverError:
    """The error of a solver run that ran out of memory (CUDD's limit, Python's, the OS's)."""
    return SolverError(
        "synthesis ran out of memory",
        hint="raise --memory-limit, or shrink the specification (grid, health levels, encoding)",
    )


def answer_of(outcome: Outcome, seconds: float | None, what: str = "synthesis") -> Any:
    """The answer of a solver run in a child process (:func:`first_success`'s ``outcome``),
    or the error it ended with, raised here: its own exception; out of memory for a
    MemoryError, or a child that died as CUDD's C handler (``exit(1)`` when ``malloc``
    fails) or the kernel's OOM killer (SIGKILL) ends it; the time limit of ``seconds``
    passed (:func:`time_limit_error`, of ``what``)."""
    kind = outcome[0]
    if kind == "ok":
        return outcome[1]
    if kind == "raise":
        err, text = outcome[1], outcome[2]
        if isinstance(err, MemoryError):
            raise out_of_memory()
        if not isinstance(err, GaitcError) and os.environ.get("GAITC_DEBUG"):
            print(text, file=sys.stderr, end="")
        raise err
    if kind == "timeout":
        raise time_limit_error(seconds or 0.0, what)
    code = outcome[1]
    if code in (1, -signal.SIGKILL):
        raise out_of_memory()
    raise SolverError(f"the solver process ended without an answer (exit status {code})")


class OrderMisfit(Exception):
    """A game stops once its fixed order misfits, for its caller to build it again in
    another order: a small game asked to (``Options.restart_misfit``), where sifting a
    manager in place can cost far more than a fresh build (a random 18-bit spec of two
    counters: the first sifting 15 s, with a million nodes in the tables; the sifted build
    solves in 0.04 s), is built in the sifted order; a game whose steps work too hard for
    their sets (:data:`~gaitc.solver.options.MISFIT_RATIO`, ``dynamic``) is built with
    CUDD's sifting throughout."""

    def __init__(self, dynamic: bool = False) -> None:
        super().__init__("the variable order misfits the game's sets")
        self.dynamic = dynamic


@dataclass
class WorkMeter:
    """The work of a game's fixpoint steps, in CUDD's computed-table lookups, read at
    sample steps (:data:`~gaitc.solver.options.WORK_SAMPLES`, then every
    :data:`~gaitc.solver.options.WORK_EVERY`): a count of operations, so that what the
    solver decides from it does not depend on the machine's speed or load."""

    steps: int = 0
    lookups: float = 0.0  # in the game's steps, up to the last sample
    nodes: float = 0.0  # of the steps' targets and results (each window by its sample)
    window: float = 0.0  # lookups a step, averaged over the last window
    _start: float = 0.0  # the counter when the count started
    _last_step: int = 0

    def due(self) -> bool:
        """Count a step; whether it is a sample step."""
        self.steps += 1
        n = self.steps
        return n in WORK_SAMPLES or (n > WORK_SAMPLES[-1] and n % WORK_EVERY == 0)

    def start(self, lookups: float) -> None:
        """Count anew from the counter's value ``lookups`` (before a solve's first step)."""
        self.steps = self._last_step = 0
        self.lookups = self.nodes = self.window = 0.0
        self._start = lookups

    def sample(self, lookups: float, nodes: int) -> None:
        """Record the counter ``lookups`` and this step's ``nodes`` (target and result)."""
        done = lookups - self._start - self.lookups
        width = self.steps - self._last_step
        self.lookups += done
        self.nodes += width * nodes
        self.window = done / max(1, width)
        self._last_step = self.steps

    @property
    def ratio(self) -> float:
        """Lookups per node of the steps' sets, so far."""
        return self.lookups / self.nodes if self.nodes else 0.0


#: What a step shows of the order (:meth:`Game._order_misfits`): it fits; sift it (in
#: place, or a small game's new build in the sifted order); build the game again with
#: CUDD's sifting throughout.
_FITS, _SIFT, _REBUILD = 0, 1, 2


class ControllerTooLarge(SolverError):
    """An explicit automaton would pass its node limit (a symbolic one may still fit)."""


def too_large(what: str, max_nodes: int) -> ControllerTooLarge:
    """The error of an explicit ``what`` (controller, counter-strategy) over ``max_nodes``."""
    return ControllerTooLarge(f"the {what} has more than {max_nodes} nodes",
                              hint="raise --max-nodes, or write a symbolic controller "
                              "(synth --symbolic)")


@dataclass
class Limits:
    """A wall-clock deadline, a memory check and a progress callback, checked inside the
    fixpoint loops and the extraction."""

    timeout: float | None = None
    progress: Progress | None = None
    started: float = field(default_factory=time.monotonic)
    memory: Callable[[], None] | None = None  # raises MemoryError near the memory budget

    def check(self) -> None:
        if self.memory is not None:
            self.memory()
        if self.timeout is not None and time.monotonic() - self.started > self.timeout:
            raise time_limit_error(self.timeout)

    def report(self, words: str, detail: str = "", fraction: float | None = None) -> None:
        """Tell the progress callback, if any, a :class:`~gaitc.solver.progress.Stage`."""
        if self.progress is not None:
            self.progress(Stage(words, detail, fraction))


@dataclass
class GameStats:
    z_iterations: int = 0
    y_iterations: int = 0
    x_iterations: int = 0
    peak_nodes: int = 0  # CUDD's peak of live nodes while solving
    winning_nodes: int = 0
    longest_step: float = 0.0  # seconds of the slowest CPre: how late a timeout can fire
    #: CUDD's computed-table lookups of the game's manager when the game ended, building
    #: included: a count of the work done that does not depend on the machine or its load
    #: (tests/solver/test_work_budget.py holds the published instances to a budget of it)
    lookups: int = 0
    #: whether a misfit turned CUDD's sifting on for the rest of the game
    #: (:meth:`Game.resume_sifting`; it is off again when the game ends)
    resumed_sifting: bool = False


@dataclass
class GameResult:
    """The winning region and, when asked for, the per-goal transition layers of the last round.

    ``layers[j]`` lists, ring by ring and for each environment goal, the transitions
    (over pre and post variables, without ρs) that make progress towards system goal ``j``.
    """

    winning: BDDNode
    layers: list[list[BDDNode]]
    stats: GameStats
    care: BDDNode  # ``winning`` is exact on these states (all states without a care set)
    decided_early: bool = False  # stopped once the initial states were lost (check only)
    rings: list[list[BDDNode]] = field(default_factory=list)  # with layers: Y_0 ⊆ Y_1 ⊆ ...


class Game:
    """The GR(1) game of a :class:`SymbolicSpec`: controllable predecessors and fixpoints."""

    def __init__(self, sym: SymbolicSpec, limits: Limits | None = None,
                 purpose: str = "solving the game") -> None:
        self.sym = sym
        self.limits = limits or Limits()
        self.purpose = purpose  # the words its progress events start with
        self.stats = GameStats()
        # A fixed order sifts again once a step shows it misfits (_order_misfits), unless
        # variables are pinned (Options.first: an order chosen on purpose, which sifting
        # would undo; the resilience games split each sub-game at the top).
        self._resift = not sym.options.reordering and not sym.options.first
        self._resumed = False  # whether this game turned CUDD's sifting on (resume_sifting)
        # the work a step that shows a misfit averages, the smaller of a small game's and a
        # refitted build's (restarted, or sifted once built); None: only the image's
        # growth and the work's ratio to the sets do
        slow: list[int] = [limit for limit, applies in (
            (SMALL_WORK, len(sym.input_bits) + len(sym.output_bits) <= SMALL_BITS),
            (RESIFT_WORK, sym.refitted)) if applies]
        self._slow_work = min(slow) if slow else None
        self.work = WorkMeter()
        self._care_post = sym.bdd.false  # the care set's primed copy, set by solve
        # whether the environment has a liveness assumption (else μY's rings are the
        # attractor's already, and _attractor would only compute them twice)
        self._assumed = any(live != sym.bdd.true for live in sym.env_live)

    def cpre(self, target: BDDNode) -> BDDNode:
        """States from which the system can force the next transition into ``target``.

        ``target`` ranges over pre and post variables; the result over pre variables.
        """
        return self._cpre_parts(target)[1]

    def _cpre_parts(self, target: BDDNode) -> tuple[BDDNode, BDDNode]:
        """The system's half of CPre(``target``), its ∃y' image, and CPre itself."""
        sym = self.sym
        if sym.options.partitioned and len(sym.sys_clusters) > 1:
            acc = target
            for cluster, qvars in sym.sys_clusters:
                acc = cudd.and_exists(acc, cluster, qvars) if qvars else acc & cluster
            rest = sym.post_outputs & sym.bdd.support(acc)
            sys_can = sym.bdd.exist(rest, acc) if rest else acc
        else:
            sys_can = cudd.and_exists(sym.game_sys_trans, target, sym.post_outputs)
        # ∀x'. (∃y'.¬ρe) ∨ sys_can  ==  ¬∃x'. ¬(∃y'.¬ρe) ∧ ¬sys_can
        return sys_can, ~cudd.and_exists(~sym.game_env_blocks, ~sys_can, sym.post_inputs)

    def solve(self, keep_layers: bool = False, stop_if_lost: Semantics | None = None,
              within: BDDNode | None = None) -> GameResult:
        """Compute the winning region; with ``keep_layers``, also the strategy layers.

        Every set is kept inside ``sym.care`` (exact there, see SymbolicSpec._care_set).  With
        ``stop_if_lost`` (a semantics), stop as soon as Z fails the initial condition: the
        winning region lies inside every Z, so it fails too.  ``within``, a set known to
        hold the winning region (that of a game where the system has more moves), is where
        Z starts instead of the care set: the same greatest fixpoint, by the argument
        below, often in fewer rounds.

        νZ is iterated goal by goal, Z ← Z ∧ Y_j(Z) (a chaotic iteration), and a goal is
        solved again only while Z has shrunk since its last solution: once every goal's Y
        was computed at the current Z and contains it, Z ⊆ ∧_j Y_j(Z) is a post-fixpoint,
        so Z lies in the greatest fixpoint (Knaster-Tarski), and every Z stays above the
        greatest fixpoint because each Y_j is monotone.  On the thesis grids, where the
        first goal decides Z, two goals cost three solutions instead of four.
        """
        sym, st = self.sym, self.stats
        n_goals = len(sym.sys_live)
        titles = goal_titles(sym.spec) or ("true",)
        z, z_post = sym.care, sym.prime(sym.care)
        self._care_post = z_post
        if self._resift:
            self.work.start(self._lookups())
        if within is not None:
            z, z_post = z & within, z_post & sym.prime(within)
        layers: list[list[BDDNode]] = [[] for _ in range(n_goals)]
        rings: list[list[BDDNode]] = [[] for _ in range(n_goals)]
        recycled: dict[tuple[int, int], BDDNode] = {}
        stable: set[int] = set()  # goals whose Y was computed at the current Z and holds it
        solved: set[int] = set()
        j = 0
        while len(stable) < n_goals:
            if j == 0:
                st.z_iterations += 1
            words = (f"{self.purpose}: round {st.z_iterations}, goal {j + 1} of "
                     f"{n_goals} ({titles[j]})")
            y, y_post, layers[j], rings[j] = self._goal(j, (z, z_post), words, keep_layers,
                                                         recycled, j in solved)
            solved.add(j)
            shrunk = z & y
            if shrunk == z:
                stable.add(j)
            else:
                z, z_post = shrunk, z_post & y_post
                stable = set()
                if stop_if_lost is not None and not self.initially_winning(z, stop_if_lost):
                    return self._result(z, layers, decided_early=True)
            j = (j + 1) % n_goals
        return self._result(z, layers, decided_early=False, rings=rings)

    def _goal(self, j: int, zs: tuple[BDDNode, BDDNode], words: str, keep_layers: bool,
              recycled: dict[tuple[int, int], BDDNode], again: bool
              ) -> tuple[BDDNode, BDDNode, list[BDDNode], list[BDDNode]]:
        """μY. ∨_i νX. CPre((J^s_j ∧ Z') ∨ Y' ∨ (¬J^e_i ∧ X')) for goal ``j`` at Z (``zs``:
        Z and Z'), as Y and Y', with the transitions of each ring and assumption
        (``keep_layers``) and the rings.

        Y is kept over pre and over post variables, each ring's Y' the union of the
        X' that its X fixpoints renamed anyway: renaming Y anew each ring cost as much as
        all the X steps (thesis grid 30 x 30 at health 5, binary: the solve went from
        129 s to 81 s CPU without it; docs/design-notes.md, section 6).  Z' comes the same
        way, from the Y' that narrowed it.

        A ring whose target (J^s_j ∧ Z') ∨ Y' is the last ring's has the last ring's X
        fixpoints, so Y is complete without computing them again: in a safety game (no
        liveness on either side) every round then costs one CPre step instead of four.

        Once Y contains Z, the rings stop: the caller keeps only Z ∧ Y, which later rings
        cannot change, and the strategy layers of the rings so far already lead every state
        of Z to the goal (their targets lie in the rings, never beyond them).  GenBuf with
        24 senders: 942 CPre steps instead of 1,212.

        The rings start from the goal's attractor (:meth:`_attractor`), which needs one
        CPre a ring; when it holds Z, the goal is decided without an X fixpoint."""
        sym, lim, st = self.sym, self.limits, self.stats
        n_goals, n_assm = len(sym.sys_live), len(sym.env_live)
        z, z_post = zs
        live = sym.sys_live[j] & z_post  # in a misfit order, the largest set of the goal
        if self._restarts():  # a small game whose manager holds that many nodes misfits
            raise OrderMisfit
        bound, bound_post = (z, z_post) if sym.options.recycle else (sym.care, self._care_post)
        layers: list[BDDNode] = []
        rings: list[BDDNode] = []
        y, y_post, ring = sym.bdd.false, sym.bdd.false, 0
        if sym.options.attractor and self._assumed:
            y, y_post, ring = self._attractor(live, z, bound, (words, j / n_goals),
                                              layers if keep_layers else None, rings, n_assm)
            if z <= y:
                self._track(words, f"|Y| = {y.dag_size}, {ring} rings (attractor)",
                            (j + 1) / n_goals)
                return y, y_post, layers, rings
        first_middle = True
        last_target = None
        while True:
            st.y_iterations += 1
            ring += 1
            lim.check()
            lim.report(words, f"ring {ring}", j / n_goals)
            live_or_lower = live | y_post
            if live_or_lower == last_target:  # Y' added nothing to the target
                if keep_layers:
                    layers.extend(layers[-n_assm:])
                    rings.append(y)
                break
            last_target = live_or_lower
            good, good_post = y, y_post
            for i in range(n_assm):
                x, x_post = bound, bound_post
                if sym.options.recycle and first_middle and again and (j, i) in recycled:
                    x = recycled[(j, i)] & z  # absent after a round the attractor decided
                    x_post = sym.prime(x)
                not_assm = ~sym.env_live[i]
                x, x_post = self._nu_x(live_or_lower, not_assm, x, x_post, bound)
                good, good_post = good | x, good_post | x_post
                recycled[(j, i)] = x
                if keep_layers:  # the transitions of the fixpoint's last step
                    layers.append(live_or_lower | (x_post & not_assm))
            first_middle = False
            if keep_layers:
                rings.append(good)
            if good == y:
                break
            y, y_post = good, good_post
            if z <= y:  # Z ⊆ Y: later rings add only states that Z ∧ Y drops
                break
            if sym.options.attractor and self._assumed:  # the cheap rings again from Y
                y, y_post, ring = self._attractor(live, z, bound, (words, j / n_goals),
                                                  layers if keep_layers else None, rings,
                                                  n_assm, start=(y, y_post, ring))
                if z <= y:
                    break
        self._track(words, f"|Y| = {y.dag_size}, {ring} rings", (j + 1) / n_goals)
        return y, y_post, layers, rings

    def _nu_x(self, lower: BDDNode, not_assm: BDDNode, x: BDDNode, x_post: BDDNode,
              bound: BDDNode) -> tuple[BDDNode, BDDNode]:
        """νX. CPre(lower ∨ (¬J^e_i ∧ X')) ∧ bound from ``x`` (``x_post`` its primed copy)
        down: the fixpoint over pre and over post variables."""
        st = self.stats
        stuck = not_assm == self.sym.bdd.false  # the step ignores X: one step is the fixpoint
        while True:
            st.x_iterations += 1
            self.limits.check()
            new_x = self._step(lower | (x_post & not_assm), bound)
            if new_x == x:
                return x, x_post
            x, x_post = new_x, self.sym.prime(new_x)
            if stuck:
                return x, x_post

    def _step(self, target: BDDNode, bound: BDDNode) -> BDDNode:
        """CPre(``target``) ∧ ``bound``, timed; a step that shows the order misfits the sets
        sifts the order (or, for a small game, raises :class:`OrderMisfit`)."""
        st = self.stats
        step = time.monotonic()
        image, result = self._cpre_parts(target)
        step = time.monotonic() - step
        st.longest_step = max(st.longest_step, step)  # reported only: nothing depends on it
        misfit = self._resift and self._order_misfits(image, target, result)
        del image, target  # live nodes steer sifting: hold only the sets the loop needs
        new = result & bound
        del result
        if misfit == _REBUILD:
            raise OrderMisfit(dynamic=True)
        if misfit and self._restarts():
            raise OrderMisfit
        if misfit:
            self.resume_sifting()
        return new

    def _attractor(self, live: BDDNode, z: BDDNode, bound: BDDNode,
                   progress: tuple[str, float], layers: list[BDDNode] | None,
                   rings: list[BDDNode], n_assm: int, *,
                   start: tuple[BDDNode, BDDNode, int] | None = None
                   ) -> tuple[BDDNode, BDDNode, int]:
        """μY. CPre(``live`` ∨ Y') ∧ ``bound``, stopped once it holds ``z``: the states
        from which the system forces the goal whatever the environment does, its liveness
        assumptions aside.  With Y and Y' and the number of rings.

        The attractor lies inside the goal's μY (νX. CPre(T ∨ (¬J^e ∧ X')) contains
        CPre(T): CPre(T) is a post-fixpoint), and μY's iteration may start from any set
        below its least fixpoint that its step does not shrink, as the attractor is
        (Tarski; the same warm start as Firman, Maoz and Ringert's fixpoint recycling,
        "Performance heuristics for GR(1) synthesis", Acta Informatica 2020).  A ring of
        the attractor costs one CPre; a ring of μY an X fixpoint per assumption, as many
        steps as the environment can put off its liveness: on a map whose obstacle must
        come home (gridworld 256 x 256), 16 steps a ring.  When the attractor holds Z the
        goal is decided without an X fixpoint.  Each ring's strategy layer is its target
        (the system moves one ring down), once per assumption, as the rings of μY have.

        ``start`` (Y, Y' and the ring count of a μY ring) continues from a set of μY's
        iteration instead of the empty set: :meth:`_goal` saturates every μY ring with the
        attractor's cheap rings, so that only the rings that need the environment's
        liveness pay for X fixpoints.  This is sound for the same reason: Y stays below
        μY's least fixpoint (CPre(T ∨ Y') lies in μY's step from Y), and the iteration ends
        at a fixpoint of μY's own step.  On the 1024 x 1024 gridworld, where a goal next to
        the obstacle's box needs the obstacle to move only near it, the 2,000 rings of
        distance beyond then cost one CPre each instead of an X fixpoint of 13 (issue 59)."""
        sym, st, lim = self.sym, self.stats, self.limits
        words, fraction = progress
        y, y_post, ring = start if start is not None else (sym.bdd.false, sym.bdd.false, 0)
        while True:
            ring += 1
            st.y_iterations += 1
            st.x_iterations += 1
            lim.check()
            lim.report(words, f"ring {ring} (attractor)", fraction)
            target = live | y_post
            new = self._step(target, bound) | y
            if layers is not None:
                layers.extend([target] * n_assm)
                rings.append(new)
            if new == y:
                return y, y_post, ring
            y, y_post = new, sym.prime(new)
            if z <= y:
                return y, y_post, ring

    def _order_misfits(self, image: BDDNode, target: BDDNode, result: BDDNode) -> int:
        """Whether a CPre step from ``target`` to ``result`` through the ∃y' ``image``
        shows that the fixed order does not fit the fixpoint's sets, by counts of nodes and
        of CUDD's operations (:class:`WorkMeter`), never by time: in a game of at most
        :data:`SMALL_BITS` state bits, steps averaging over :data:`SMALL_WORK` lookups
        between two samples; after a refitted build (``SymbolicSpec.refitted``), over
        :data:`RESIFT_WORK`; in any other, an image of over :data:`RESIFT_NODES` nodes and
        over :data:`RESIFT_BLOWUP` times the nodes of the target and the result together
        (counted only then: counting is linear in the sets), or, when the caller can build
        the game again (``Options.rebuild_misfit``), past :data:`MISFIT_WORK` lookups in
        all, over :data:`MISFIT_RATIO` lookups a node of the steps' sets, which asks for a
        new build sifting throughout (:data:`_REBUILD`)."""
        meter = self.work
        if meter.due():
            meter.sample(self._lookups(), target.dag_size + result.dag_size)
            if self._slow_work is not None and meter.window > self._slow_work:
                return _SIFT
            if (self.sym.options.refit_sift and self.sym.refitted
                    and meter.lookups > REFIT_SIFT_WORK):
                return _SIFT
            if (self.sym.options.rebuild_misfit and not self.sym.refitted
                    and meter.lookups > MISFIT_WORK and meter.ratio > MISFIT_RATIO):
                return _REBUILD
        if self.sym.refitted:
            return _FITS
        size: int = image.dag_size
        blown = size > RESIFT_NODES and size > RESIFT_BLOWUP * (target.dag_size
                                                                + result.dag_size)
        return _SIFT if blown else _FITS

    def _lookups(self) -> float:
        """CUDD's count of computed-table lookups so far (reading it scans CUDD's tables)."""
        with warnings.catch_warnings():  # dd warns that the unrelated 'mem' changed unit
            warnings.simplefilter("ignore")
            return float(self.sym.bdd.statistics()["cache_lookups"])

    def _restarts(self) -> bool:
        """Whether a misfit now stops the game (:class:`OrderMisfit`) instead of sifting in
        place: when asked to and the manager holds over :data:`RESTART_NODES` live nodes,
        which sifting in place would move about (below that, in-place sifting is cheaper
        than a new build: random graph tasks of 18 bits, 1.2-1.8x)."""
        return (self.sym.options.restart_misfit and self._resift
                and self.sym.node_count() > RESTART_NODES)

    def resume_sifting(self) -> None:
        """Turn CUDD's sifting on for the rest of the game, once a step showed that the
        fixed order misfits (:meth:`_order_misfits`): the order was chosen, or sifted,
        for ρ, and the fixpoint's sets outgrow it."""
        self._resift = False
        self._resumed = self.stats.resumed_sifting = True
        self.sym.bdd.configure(reordering=True)

    def _result(self, z: BDDNode, layers: list[list[BDDNode]], decided_early: bool,
                rings: list[list[BDDNode]] | None = None) -> GameResult:
        if self._resumed:  # the sifting a misfit turned on was for this game only: left on,
            # CUDD sifts the whole manager, the kept layers too, inside whatever operation
            # next passes its threshold (radial12: a 3 s extraction took 150 s, issue 61)
            self._resumed = False
            self.sym.bdd.configure(reordering=False)
        self.stats.winning_nodes = z.dag_size
        with warnings.catch_warnings():  # dd warns that the unrelated 'mem' field changed unit
            warnings.simplefilter("ignore")
            peak = int(self.sym.bdd.statistics()["peak_live_nodes"])
        self.stats.peak_nodes = max(self.stats.peak_nodes, peak)
        self.stats.lookups = int(self._lookups())
        return GameResult(z, layers, self.stats, self.sym.care, decided_early, rings or [])

    def _track(self, words: str, detail: str, fraction: float) -> None:
        nodes = self.sym.node_count()
        self.stats.peak_nodes = max(self.stats.peak_nodes, nodes)
        self.limits.report(words, f"{detail}, {nodes} live BDD nodes", fraction)

    def initially_winning(self, winning: BDDNode, semantics: Semantics) -> bool:
        """The initial-state condition of SLUGS.

        default: ∀x. θe → ∃y. θs ∧ W;  robotics (``--sysInitRoboticsSemantics``):
        ∀x, y. θe ∧ θs → W.
        """
        sym = self.sym
        if semantics == Semantics.ROBOTICS:
            bad = sym.env_init & sym.sys_init & ~winning
        elif semantics == Semantics.DEFAULT:
            good = sym.bdd.exist(sym.pre_outputs, sym.sys_init & winning)
            bad = sym.env_init & ~good
        else:
            raise ValueError(f"unknown semantics {semantics!r}")
        return bool(bad == sym.bdd.false)


def goal_strategies(sym: SymbolicSpec, result: GameResult) -> list[BDDNode]:
    """Per goal j, the transitions the controller takes: the first layer covering each case."""
    out = []
    for layers in result.layers:
        covered = sym.bdd.false
        strategy = sym.bdd.false
        for paths in layers:
            allowed = sym.sys_trans & paths
            new_cases = sym.bdd.exist(sym.post_outputs, allowed) & ~covered
            strategy |= new_cases & allowed
            covered |= new_cases
        out.append(strategy)
    return out
