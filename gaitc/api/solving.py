"""Solving: realizability, verified controllers and counter-strategies for a loaded spec.

The embedded BDD solver (:mod:`gaitc.solver`) or the SLUGS binary (:mod:`slugs_bridge.runner`)
decides and synthesizes; every automaton is then proved by the independent checker of
:mod:`gaitc.verifier`, which shares no code with either solver.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Final, Literal, TypeGuard, get_args

from gaitc.api.loading import Spec, SpecLike, as_gr1, resolve
from gaitc.api.presentation import table
from gaitc.diagnostics import SolverError, UsageError
from gaitc.diagnostics.files import write_atomically
from gaitc.ir.bddfile import SymbolicController, symbolic_to_json
from gaitc.ir.controller import (
    Controller,
    controller_to_json,
    read_controller_json,
)
from gaitc.ir.costs import Cost
from gaitc.ir.quotient import merge_equivalent
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.solver.game import GameStats, out_of_memory
from gaitc.solver.progress import Progress, Stage
from gaitc.solver.symbolic import Options
from gaitc.solver.synthesis import FORMS
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from typing import TypeAlias

    from gaitc.compact.controller import CompactController
    from gaitc.compact.fields import Vocabulary
    from gaitc.forms.reader import Form
    from gaitc.sim.graphics import Picture
    from gaitc.verifier.strategy import VerificationReport

SolverName = Literal["embedded", "slugs"]
#: ``embedded``: the BDD solver in :mod:`gaitc.solver`; ``slugs``: an installed SLUGS binary.
SOLVERS: Final[tuple[SolverName, ...]] = get_args(SolverName)
Kind = Literal["strategy", "counterstrategy"]
#: Above this many nodes ``synthesize`` keeps the controller symbolic (form ``auto``).
MAX_NODES: Final = 100_000
#: The forms ``synthesize`` writes: the solver's (:data:`gaitc.solver.synthesis.FORMS`) and
#: ``compact``, decision diagrams over the robot's words (:mod:`gaitc.compact`).
COMPACT: Final = "compact"
#: A controller in any of its forms (the compact one is imported where it is used: a
#: plain ``check`` does not load gaitc.compact).
Automaton: TypeAlias = "Controller | SymbolicController | CompactController"


@dataclass(frozen=True)
class Verdict:
    """Whether a spec is realizable, how long deciding took, and the fixpoint statistics."""

    file: str
    realizable: bool
    seconds: float
    semantics: Semantics = Semantics.DEFAULT
    solver: str = "embedded"
    stats: GameStats | None = field(default=None, repr=False)
    engine: str = ""  # embedded solver: the configuration that answered (gaitc.solver.portfolio)

    def __repr__(self) -> str:
        word = "realizable" if self.realizable else "unrealizable"
        return (f"<gaitc.Verdict {self.file!r}: {word} in {self.seconds:.2f} s "
                f"({self.solver} solver, {self.semantics} semantics)>")

    def to_json(self) -> dict[str, Any]:
        """The verdict for ``gaitc check --json`` (docs/json.md)."""
        out: dict[str, Any] = {
            "file": self.file, "verdict": "realizable" if self.realizable else "unrealizable",
            "seconds": round(self.seconds, 3), "semantics": self.semantics,
            "solver": self.solver, "engine": self.engine or None}
        return out

    def _repr_html_(self) -> str:
        rows = [("verdict", "realizable" if self.realizable else "unrealizable"),
                ("seconds", f"{self.seconds:.3f}"), ("solver", self.solver),
                ("semantics", self.semantics)]
        if self.engine:
            rows.append(("engine", self.engine))
        if self.stats is not None:
            rows.append(("peak BDD nodes", str(self.stats.peak_nodes)))
        return table(f"realizability of {self.file}", rows)


@dataclass(frozen=True)
class Synthesis:
    """A solver's automaton for a spec, with the verifier's report on it.

    ``controller`` is None when the spec has no winner of the kind asked for: no strategy
    for an unrealizable spec, no counter-strategy for a realizable one.
    """

    spec: Spec | GR1Spec = field(repr=False)
    kind: Kind
    controller: Automaton | None
    report: VerificationReport | None
    seconds: float
    semantics: Semantics = Semantics.DEFAULT
    solver: str = "embedded"
    #: The automaton's nodes before equivalent ones were merged (gaitc.ir.quotient), when any were.
    merged_from: int | None = None
    #: A compact controller's source: the symbolic controller's BDD nodes.
    symbolic_nodes: int | None = None

    @property
    def realizable(self) -> bool:
        """Whether the spec is realizable (the verdict behind this automaton)."""
        found = self.controller is not None
        return found if self.kind == "strategy" else not found

    @property
    def verified(self) -> bool:
        """An automaton exists and the independent verifier accepted it."""
        return self.report is not None and self.report.ok

    @property
    def size(self) -> str:
        """The controller's size in words: explicit nodes, or a symbolic one's BDD nodes."""
        if self.controller is None:
            return "none"
        if _compact(self.controller):
            from gaitc.codegen.tables import table_bytes

            c = self.controller
            return (f"compact, {c.rules} rules, {c.decision_nodes} decision nodes "
                    f"(+{c.monitor_nodes} for the assumption monitor), {table_bytes(c)} bytes "
                    f"of tables; the symbolic strategy it comes from has {self.symbolic_nodes} "
                    "BDD nodes")
        if isinstance(self.controller, SymbolicController):
            return f"symbolic, {len(self.controller.nodes)} BDD nodes"
        merged = "" if self.merged_from is None else f", {self.merged_from} before merging"
        return f"{len(self.controller.nodes)} nodes{merged}"

    def to_json(self) -> dict[str, Any]:
        """The outcome for ``gaitc synth --json`` and ``counter --json`` (docs/json.md)."""
        symbolic = isinstance(self.controller, SymbolicController)
        out = {
            "file": _name(self.spec), "kind": self.kind,
            "verdict": "realizable" if self.realizable else "unrealizable",
            "seconds": round(self.seconds, 3), "semantics": self.semantics,
            "solver": self.solver, "symbolic": symbolic,
            "nodes": None if self.controller is None else len(self.controller.nodes),
            "nodes_before_merging": self.merged_from,
            "compact": None,
            "verification": None if self.report is None else self.report.to_json()}
        if _compact(self.controller):
            from gaitc.codegen.tables import table_bytes

            c = self.controller
            out["nodes"] = c.decision_nodes
            out["compact"] = {"rules": c.rules, "decision_nodes": c.decision_nodes,
                              "monitor_nodes": c.monitor_nodes,
                              "moves": len(c.moves), "table_bytes": table_bytes(c),
                              "symbolic_nodes": self.symbolic_nodes}
        return out

    def save(self, path: str | Path) -> None:
        """Write the controller as JSON (docs/controller-format.md), atomically."""
        if self.controller is None:
            raise UsageError(f"there is no {self.kind} to save: the spec is "
                             f"{'realizable' if self.realizable else 'unrealizable'}")
        if isinstance(self.controller, SymbolicController):
            write_atomically(path, symbolic_to_json(self.controller))
        elif isinstance(self.controller, Controller):
            write_atomically(path, controller_to_json(self.controller))
        else:
            from gaitc.compact.controller import compact_to_json

            write_atomically(path, compact_to_json(self.controller))

    def picture(self) -> Picture:
        """The automaton drawn in domain terms (needs a ``.gait`` spec and Graphviz)."""
        from gaitc.sim.automaton_view import automaton_view
        from gaitc.sim.domain import Domain
        from gaitc.sim.strategy import strategy_from_controller

        if self.controller is None:
            raise UsageError(f"there is no {self.kind} to draw")
        if not isinstance(self.controller, Controller):
            raise UsageError("a symbolic or compact controller has no automaton to draw; "
                             "draw a run of it (gaitc.simulate(...).picture())")
        if not isinstance(self.spec, Spec) or self.spec.model is None:
            raise UsageError("drawing an automaton needs a .gait spec, which says what its "
                             "variables mean")
        strategy = strategy_from_controller(self.controller, self.spec.gr1, self.spec.path)
        domain = Domain(self.spec.model, self.spec.encoding or EncodingName.ONEHOT)
        return automaton_view(strategy, domain)

    def __repr__(self) -> str:
        file = self.spec.path if isinstance(self.spec, Spec) else self.spec.name or "spec"
        if self.controller is None:
            word = "realizable" if self.realizable else "unrealizable"
            return f"<gaitc.Synthesis {file!r}: {word}, no {self.kind} ({self.seconds:.2f} s)>"
        proof = "not verified" if self.report is None else (
            "verified" if self.report.ok else "FAILED verification")
        return (f"<gaitc.Synthesis {file!r}: {self.kind} ({self.size}), {proof} "
                f"({self.seconds:.2f} s, {self.solver} solver)>")

    def _repr_html_(self) -> str:
        rows = [("kind", self.kind), ("realizable", str(self.realizable)),
                ("seconds", f"{self.seconds:.3f}"), ("solver", self.solver),
                ("semantics", self.semantics)]
        if self.controller is not None:
            rows.append(("size", self.size))
        if self.report is not None:
            rows.append(("verification", self.report.summary()))
        return table(repr(self)[1:-1], rows)


def _semantics(semantics: Semantics | str) -> Semantics:
    return Semantics.parse(semantics, "semantics")


def _solver(solver: str) -> str:
    if solver not in SOLVERS:
        raise UsageError(f"unknown solver '{solver}'; use one of {', '.join(SOLVERS)}")
    return solver


def _name(spec: Spec | GR1Spec) -> str:
    return spec.path if isinstance(spec, Spec) else spec.name or "<spec>"


def _slugsin(spec: GR1Spec) -> str:
    from gaitc.ir.bitblast import bitblast
    from slugs_bridge.slugsin import emit_slugsin

    return emit_slugsin(bitblast(spec))


def check(spec: SpecLike, semantics: Semantics | str = Semantics.DEFAULT, solver: str = "embedded",
          timeout: float | None = None, slugs: str | None = None,
          options: Options | None = None, progress: Progress | None = None) -> Verdict:
    """Decide whether a controller exists for ``spec``.

    ``semantics`` is ``default`` or ``robotics`` (:data:`gaitc.ir.spec.SEMANTICS`), ``solver``
    ``embedded`` or ``slugs`` (then ``slugs`` names the binary, else ``$SLUGS`` or PATH).
    Raises :class:`~gaitc.diagnostics.SolverError` when the solver cannot finish.
    """
    spec = resolve(spec)
    gr1, started = as_gr1(spec), time.monotonic()
    semantics = _semantics(semantics)
    if _solver(solver) == "slugs":
        from slugs_bridge.runner import run_slugs_check

        result = run_slugs_check(_slugsin(gr1), semantics=semantics, timeout=timeout,
                                 slugs=slugs)
        return Verdict(_name(spec), result.realizable, result.seconds, semantics, solver)
    from gaitc.solver import synthesis

    try:
        checked = synthesis.check(gr1, semantics, timeout, progress, options)
    except MemoryError:
        raise out_of_memory() from None
    return Verdict(_name(spec), checked.realizable, time.monotonic() - started, semantics,
                   solver, checked.stats, checked.engine)


def synthesize(spec: SpecLike, semantics: Semantics | str = Semantics.DEFAULT,
               solver: str = "embedded", timeout: float | None = None, *, slugs: str | None = None,
               options: Options | None = None, progress: Progress | None = None,
               verify: bool = True, form: str = "auto", max_nodes: int | None = MAX_NODES,
               prefer: str | Sequence[str] | None = None) -> Synthesis:
    """A controller for ``spec``, proved by the independent verifier unless ``verify`` is
    False; ``.controller`` is None when the spec is unrealizable.

    ``form`` (:data:`gaitc.solver.synthesis.FORMS`): ``explicit`` an automaton, ``symbolic`` BDDs
    (:mod:`gaitc.ir.bddfile`), ``auto`` an automaton unless it would pass ``max_nodes`` nodes,
    ``compact`` decision diagrams over the robot's words (:mod:`gaitc.compact`), made from
    the symbolic strategy and proved on every state by the symbolic verifier.

    ``prefer`` orders the move preferences of the controller (either form) among the winning
    moves (``gaitc.solver.preferences``: ``hazard``, ``health``, ``goal``, ``switches``; a list or
    comma-separated text): None is all four in that order, ``"none"`` the solver's first
    move (the behaviour before them).  They apply to the embedded solver; ``hazard``,
    ``health`` and ``switches`` need a ``.gait`` spec.
    """
    if form not in (*FORMS, COMPACT):
        raise UsageError(f"unknown controller form '{form}'; use one of "
                         f"{', '.join((*FORMS, COMPACT))}")
    if form in ("symbolic", COMPACT) and solver != "embedded":
        raise UsageError(f"{form} controllers come from the embedded solver; drop --solver "
                         f"slugs or --{form}")
    return _solve(
        spec=resolve(spec),
        kind="strategy",
        semantics=_semantics(semantics),
        solver=solver,
        timeout=timeout,
        slugs=slugs,
        options=options,
        progress=progress,
        check_it=verify,
        form=form,
        max_nodes=max_nodes,
        prefer=prefer,
    )


def counterstrategy(spec: SpecLike, semantics: Semantics | str = Semantics.DEFAULT,
                    solver: str = "embedded", timeout: float | None = None,
                    slugs: str | None = None, *, options: Options | None = None,
                    progress: Progress | None = None, verify: bool = True) -> Synthesis:
    """The environment's winning strategy for an unrealizable ``spec``, verified;
    ``.controller`` is None when the spec is realizable."""
    return _solve(
        spec=resolve(spec),
        kind="counterstrategy",
        semantics=_semantics(semantics),
        solver=solver,
        timeout=timeout,
        slugs=slugs,
        options=options,
        progress=progress,
        check_it=verify,
        form="explicit",
        max_nodes=None,
    )


def _solve(spec: Spec | GR1Spec, kind: Kind, semantics: Semantics, solver: str,
           *, timeout: float | None, slugs: str | None, options: Options | None,
           progress: Progress | None, check_it: bool, form: str,
           max_nodes: int | None, prefer: str | Sequence[str] | None = None) -> Synthesis:
    from gaitc.solver.preferences import preference_order

    gr1, started = as_gr1(spec), time.monotonic()
    symbolic_nodes: int | None = None
    order = preference_order(prefer)
    weighed = [name for name in order if name != "goal"]
    if prefer is not None and weighed and not (isinstance(spec, Spec) and spec.model):
        raise UsageError(f"--prefer {','.join(weighed)} weighs moves by the robot model of a "
                         ".gait spec, and this spec has none (SLUGS input); use --prefer goal "
                         "or none")
    automaton: Automaton | None
    try:
        if _solver(solver) == "slugs":
            if prefer is not None and order:
                raise UsageError("move preferences need the embedded solver; use --prefer "
                                 "none with --solver slugs")
            automaton = _slugs_automaton(gr1, kind, semantics, timeout, slugs)
        elif kind == "strategy":
            from gaitc.solver import synthesis

            automaton = synthesis.synthesize_controller(
                spec=gr1,
                semantics=semantics,
                timeout=timeout,
                progress=progress,
                options=options,
                max_nodes=max_nodes,
                form="symbolic" if form == COMPACT else form,
                prefer=order,
                costs=_costs(spec, order),
            )
            if form == COMPACT and isinstance(automaton, SymbolicController):
                if progress is not None:
                    progress(Stage("writing the strategy as decision diagrams"))
                symbolic_nodes = len(automaton.nodes)
                automaton = compact(spec, automaton)
        else:
            from gaitc.solver import synthesis

            automaton = synthesis.counterstrategy(gr1, semantics, timeout, progress, options)
    except MemoryError:
        raise out_of_memory() from None
    seconds = time.monotonic() - started
    report, merged_from = None, None
    if isinstance(automaton, Controller):  # counter-strategies come back unchanged
        merged = merge_equivalent(automaton)
        if merged is not automaton:
            merged_from, automaton = len(automaton.nodes), merged
    if automaton is not None:
        source = spec.source() if isinstance(spec, Spec) else None
        automaton = replace(automaton, source=source, solver=solver)
        if check_it:
            if progress is not None:
                progress(Stage("checking the controller with the independent verifier"))
            report = verify(spec, automaton, semantics)
    return Synthesis(
        spec=spec,
        kind=kind,
        controller=automaton,
        report=report,
        seconds=seconds,
        semantics=semantics,
        solver=solver,
        merged_from=merged_from,
        symbolic_nodes=symbolic_nodes,
    )


def _compact(value: object) -> TypeGuard[CompactController]:
    """Whether ``value`` is a compact controller; none can exist before gaitc.compact is
    imported, so a ``check`` need not import it to ask."""
    module = sys.modules.get("gaitc.compact.controller")
    return module is not None and isinstance(value, module.CompactController)


def _vocabulary(spec: Spec | GR1Spec) -> Vocabulary:
    """The fields a compact controller of ``spec`` decides in: the robot's words for a
    ``.gait`` spec, else one field per declared variable (from the spec alone)."""
    from gaitc.compact.fields import expected_vocabulary

    if isinstance(spec, Spec):
        return expected_vocabulary(spec.gr1, spec.model, spec.encoding)
    return expected_vocabulary(spec)


def vocabulary_of(spec: Spec | GR1Spec, ctrl: SymbolicController) -> Vocabulary:
    """The fields a compact controller of ``spec`` decides in (see :func:`_vocabulary`),
    refused when the symbolic controller ``ctrl`` is of another spec."""
    from gaitc.forms.reader import check_belongs

    check_belongs(ctrl, as_gr1(spec))
    return _vocabulary(spec)


def compact(spec: SpecLike, controller: SymbolicController) -> CompactController:
    """The compact controller (:mod:`gaitc.compact`) of a symbolic controller of ``spec``."""
    from gaitc.compact.extraction import compact_from_symbolic

    resolved = resolve(spec)
    return compact_from_symbolic(controller, vocabulary_of(resolved, controller))


def _costs(spec: Spec | GR1Spec, order: Sequence[str]) -> tuple[Cost, ...]:
    """The robot model's move costs (:mod:`ltlcompiler.costs`) when ``order`` needs them."""
    if not isinstance(spec, Spec) or spec.model is None or set(order) <= {"goal"}:
        return ()
    from ltlcompiler.costs import model_costs

    return model_costs(spec.model, spec.encoding or EncodingName.ONEHOT)


def _slugs_automaton(gr1: GR1Spec, kind: Kind, semantics: Semantics, timeout: float | None,
                     slugs: str | None) -> Controller | None:
    from slugs_bridge import runner

    wanted = kind == "strategy"
    run = runner.run_slugs_synth if wanted else runner.run_slugs_counter
    result = run(_slugsin(gr1), semantics=semantics, timeout=timeout, slugs=slugs)
    if result.realizable != wanted:
        return None
    if result.output is None:
        verdict = "realizable" if result.realizable else "unrealizable"
        raise SolverError(f"SLUGS reported {verdict} but wrote no {kind}")
    if wanted:
        return runner.controller_from_slugs_json(result.output, gr1, semantics)
    return runner.counterstrategy_from_slugs_text(result.output, gr1, semantics)


def verify(spec: SpecLike,
           controller: Automaton | Synthesis | str | Path,
           semantics: Semantics | str | None = None) -> VerificationReport:
    """Prove independently that ``controller`` (a strategy, explicit or symbolic) realizes
    ``spec``, or that a counter-strategy defeats it; a path is read as a controller file.
    ``semantics`` defaults to the one recorded in the controller."""
    from gaitc.forms.reader import belongs, parse_file
    from gaitc.verifier.strategy import VerificationReport

    spec = resolve(spec)
    gr1 = as_gr1(spec)
    automaton: Automaton
    if isinstance(controller, (str, Path)):
        automaton = parse_file(controller, gr1)
    elif isinstance(controller, Synthesis):
        if controller.controller is None:
            raise UsageError(f"there is no {controller.kind} to verify")
        automaton = controller.controller
    else:
        automaton = controller
    chosen = _semantics(semantics or automaton.semantics)
    why = belongs(automaton, gr1, _vocabulary(spec) if _compact(automaton) else None)
    if why is not None:  # the proof covers the whole file: its vocabulary is the spec's
        return VerificationReport(
            ok=False, problems=(f"controller does not belong to this spec: {why}",),
            kind="counterstrategy" if automaton.kind == "counterstrategy" else "strategy",
            semantics=chosen, symbolic=not isinstance(automaton, Controller))
    if _compact(automaton):
        from gaitc.compact.controller import to_symbolic
        from gaitc.verifier.monitor import monitor_check
        from gaitc.verifier.symbolic import verify_symbolic

        if not automaton.monitored:
            report = verify_symbolic(gr1, to_symbolic(automaton), chosen)
            return replace(report, notes=(*report.notes, "the controller carries no "
                                          "assumption monitor: a board running it alone "
                                          "cannot tell when the assumptions break"))
        from gaitc.compact.controller import monitor_function

        ctrl = automaton
        check = monitor_check(lambda bdd: monitor_function(bdd, ctrl), ctrl.vocabulary.fields)
        report = verify_symbolic(gr1, to_symbolic(automaton), chosen, [check])
        if not report.ok:
            return report
        return replace(report, notes=(*report.notes, "the assumption monitor equals env_trans "
                                      "on every state a run reaches"))
    if isinstance(automaton, SymbolicController):
        from gaitc.verifier.symbolic import verify_symbolic

        return verify_symbolic(gr1, automaton, chosen)
    assert isinstance(automaton, Controller)  # the compact form returned above
    if automaton.kind == "counterstrategy":
        from gaitc.verifier.counterstrategy import verify_counterstrategy

        return verify_counterstrategy(gr1, automaton, chosen)
    from gaitc.verifier.strategy import verify as verify_strategy

    return verify_strategy(gr1, automaton, chosen)


def read_controller(path: str | Path, spec: SpecLike) -> Automaton:
    """A controller file of any form (an explicit automaton, a symbolic or a compact one),
    checked against ``spec``: a file whose bits, integers or fields differ from the spec's
    is a :class:`~gaitc.diagnostics.ControllerError` naming the first difference
    (:mod:`gaitc.forms.reader`, the one reader every command uses)."""
    from gaitc.forms.reader import read_controller as read_checked

    resolved = resolve(spec)
    if isinstance(resolved, Spec):
        return read_checked(path, resolved.gr1, resolved.model, resolved.encoding)
    return read_checked(path, resolved)


def controller_form(path: str | Path) -> Form:
    """The form of the controller file ``path`` (explicit, symbolic or compact), read from
    the file's header alone."""
    from gaitc.forms.reader import form_of

    return form_of(read_controller_json(str(path)))


def recorded_encoding(path: str | Path) -> EncodingName | None:
    """The encoding a controller file says its spec was compiled with, if it says one."""
    import json

    from ltlcompiler.encoding import ENCODINGS

    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        encoding = data["gaitc"]["source"]["encoding"]
    except (OSError, ValueError, KeyError, TypeError, RecursionError):
        return None
    return EncodingName(encoding) if encoding in ENCODINGS else None
