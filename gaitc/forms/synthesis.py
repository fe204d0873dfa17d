"""Solving a spec for a controller: a strategy or counter-strategy in a chosen form, with
its proof.

The embedded BDD solver (:mod:`gaitc.solver`) or the SLUGS binary (:mod:`slugs_bridge.runner`)
synthesizes; a compact controller is made from the symbolic one through the form registry
(:mod:`gaitc.forms.registry`); every automaton is then proved by the independent checker of
:mod:`gaitc.verifier` (:func:`prove`), which shares no code with either solver.  Deciding
alone, without a controller, is :mod:`gaitc.forms.decision`'s.  :mod:`gaitc.api.solving`
converts the facade's arguments and calls here.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Final, Union

from gaitc.analysis.separation import preference_note, stay_separated
from gaitc.compact.controller import CompactController
from gaitc.core.modes import ControllerKind, Form
from gaitc.core.presentation import table
from gaitc.core.spec import Spec, as_spec
from gaitc.diagnostics import SolverError, UsageError
from gaitc.diagnostics.files import write_atomically
from gaitc.forms.base import Automaton
from gaitc.forms.decision import semantics_named, slugsin_text, solver_named, spec_name
from gaitc.forms.reader import belongs, check_belongs
from gaitc.forms.registry import entry
from gaitc.ir.bddfile import SymbolicController
from gaitc.ir.controller import Controller
from gaitc.ir.costs import Cost
from gaitc.ir.formula import unreachable
from gaitc.ir.quotient import merge_equivalent
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.sim.domain import Domain
from gaitc.sim.strategy import strategy_from_controller
from gaitc.solver import synthesis
from gaitc.solver.game import Limits, out_of_memory
from gaitc.solver.preferences import preference_order
from gaitc.solver.progress import Progress, Stage
from gaitc.solver.symbolic import Options
from gaitc.solver.synthesis import Extraction
from gaitc.verifier.strategy import VerificationReport
from ltlcompiler.costs import model_costs
from ltlcompiler.encoding import EncodingName
from slugs_bridge import runner

if TYPE_CHECKING:
    from gaitc.analysis.separation import Separation
    from gaitc.sim.graphics import Picture

#: What the embedded solver leaves of a strategy: an automaton, BDDs, or none.
Solved = Union["Controller", "SymbolicController", None]
#: Above this many nodes ``synthesize`` keeps the controller symbolic (form ``auto``).
MAX_NODES: Final = 100_000


@dataclass(frozen=True)
class Synthesis:
    """A solver's automaton for a spec, with the verifier's report on it.

    ``controller`` is None when the spec has no winner of the kind asked for: no strategy
    for an unrealizable spec, no counter-strategy for a realizable one.
    """

    spec: Spec | GR1Spec = field(repr=False)
    kind: ControllerKind
    controller: Automaton | None
    report: VerificationReport | None
    seconds: float
    semantics: Semantics = Semantics.DEFAULT
    solver: str = "embedded"
    #: The automaton's nodes before equivalent ones were merged (gaitc.ir.quotient), when any were.
    merged_from: int | None = None
    #: A compact controller's source: the symbolic controller's BDD nodes.
    symbolic_nodes: int | None = None
    #: For a spec that is not well-separated (:mod:`gaitc.analysis.separation`): whether the
    #: controller keeps the environment able to keep its assumptions, in words.
    separation: str | None = None

    @property
    def realizable(self) -> bool:
        """Whether the spec is realizable (the verdict behind this automaton)."""
        found = self.controller is not None
        return found if self.kind == ControllerKind.STRATEGY else not found

    @property
    def verified(self) -> bool:
        """An automaton exists and the independent verifier accepted it."""
        return self.report is not None and self.report.ok

    @property
    def size(self) -> str:
        """The controller's size in words: explicit nodes, or a symbolic one's BDD nodes."""
        if self.controller is None:
            return "none"
        size = entry(self.controller).size(self.controller)
        if self.symbolic_nodes is not None:
            size += (f"; the symbolic strategy it comes from has {self.symbolic_nodes} BDD "
                     "nodes")
        if self.merged_from is not None:
            size += f", {self.merged_from} before merging"
        return size

    def to_json(self) -> dict[str, Any]:
        """The outcome for ``gaitc synth --json`` and ``counter --json`` (docs/json.md)."""
        form = None if self.controller is None else self.form
        out: dict[str, Any] = {
            "file": spec_name(self.spec), "kind": self.kind,
            "verdict": "realizable" if self.realizable else "unrealizable",
            "seconds": round(self.seconds, 3), "semantics": self.semantics,
            "solver": self.solver, "symbolic": form == Form.SYMBOLIC, "form": form,
            "nodes": None,
            "nodes_before_merging": self.merged_from,
            "compact": None,
            "verification": None if self.report is None else self.report.to_json(),
            "separation": self.separation}
        if self.controller is not None:
            out.update(entry(self.controller).size_json(self.controller))
            if out["compact"] is not None:
                out["compact"]["symbolic_nodes"] = self.symbolic_nodes
        return out

    @property
    def form(self) -> Form:
        """The controller's form (a :class:`UsageError` when there is no controller)."""
        if self.controller is None:
            raise UsageError(f"there is no {self.kind}: the spec is "
                             f"{'realizable' if self.realizable else 'unrealizable'}")
        return entry(self.controller).form

    def save(self, path: str | Path, layout: str | None = None) -> None:
        """Write the controller file (docs/controller-format.md) atomically: through a
        temporary file renamed over ``path``.  An explicit controller is written in the
        tables layout when ``path`` ends in ``.gz`` or ``layout`` is ``tables``, else as
        SLUGS's JSON (:class:`gaitc.forms.explicit.Layout`)."""
        if self.controller is None:
            raise UsageError(f"there is no {self.kind} to save: the spec is "
                             f"{'realizable' if self.realizable else 'unrealizable'}")
        write_atomically(path, entry(self.controller).to_file(self.controller, path, layout))

    def picture(self) -> Picture:
        """The automaton drawn in domain terms (needs a ``.gait`` spec and Graphviz)."""
        # lazy: pydot, only to draw (start-up of synth, simulate and the other commands)
        from gaitc.sim.automaton_view import automaton_view

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
        if self.separation is not None:
            rows.append(("well-separation", self.separation))
        return table(repr(self)[1:-1], rows)


def _extraction(form: Form | None) -> Extraction:
    """What the solver leaves for a controller of ``form`` (None: ``auto``): a compact
    controller is made from the symbolic strategy."""
    match form:
        case None:
            return Extraction.AUTO
        case Form.EXPLICIT:
            return Extraction.EXPLICIT
        case Form.SYMBOLIC | Form.COMPACT:
            return Extraction.SYMBOLIC
        case _:
            unreachable(form)


@dataclass(frozen=True)
class SolveOptions:
    """How :func:`solve` runs: the solver and its limits, whether the result is proved, the
    form of a strategy (None: ``auto``), the node limit of ``auto`` and the move
    preferences."""

    solver: str = "embedded"
    timeout: float | None = None
    slugs: str | None = None
    options: Options | None = None
    progress: Progress | None = None
    check_it: bool = True
    form: Form | None = None
    max_nodes: int | None = MAX_NODES
    prefer: str | Sequence[str] | None = None
    separate: bool = True  # prefer a controller that never forces an assumption to break


def solve(spec: Spec | GR1Spec, kind: ControllerKind, semantics: Semantics,
          opts: SolveOptions | None = None) -> Synthesis:
    """A strategy (``kind`` STRATEGY) or a counter-strategy of ``spec`` as ``opts`` say,
    proved unless ``opts.check_it`` is False; its ``controller`` is None when none exists."""
    opts = opts or SolveOptions()
    solver, timeout, slugs, progress = opts.solver, opts.timeout, opts.slugs, opts.progress
    form, prefer = opts.form, opts.prefer
    gr1 = spec.gr1 if isinstance(spec, Spec) else spec
    started = time.monotonic()
    symbolic_nodes: int | None = None
    order = preference_order(prefer)
    weighed = [name for name in order if name != "goal"]
    if prefer is not None and weighed and not (isinstance(spec, Spec) and spec.model):
        raise UsageError(f"--prefer {','.join(weighed)} weighs moves by the robot model of a "
                         ".gait spec, and this spec has none (SLUGS input); use --prefer goal "
                         "or none")
    automaton: Automaton | None
    separation: str | None = None
    try:
        if solver_named(solver) == "slugs":
            if prefer is not None and order:
                raise UsageError("move preferences need the embedded solver; use --prefer "
                                 "none with --solver slugs")
            automaton = _slugs_automaton(gr1, kind, semantics, timeout, slugs)
        elif kind == ControllerKind.STRATEGY:
            separated = _stay_separated(spec, semantics, opts) if opts.separate else None
            target = gr1 if separated is None else separated[0]
            automaton = synthesis.synthesize_controller(
                spec=target,
                semantics=semantics,
                timeout=timeout,
                progress=progress,
                options=opts.options,
                max_nodes=opts.max_nodes,
                form=_extraction(form),
                prefer=order,
                costs=_costs(spec, order),
            )
            if separated is not None:
                automaton, separation = _separated_controller(
                    automaton, separated[1], lambda: synthesis.synthesize_controller(
                        spec=gr1, semantics=semantics, timeout=timeout, progress=progress,
                        options=opts.options, max_nodes=opts.max_nodes,
                        form=_extraction(form), prefer=order,
                        costs=_costs(spec, order)))
            if form is Form.COMPACT and isinstance(automaton, SymbolicController):
                if progress is not None:
                    progress(Stage("writing the strategy as decision diagrams"))
                symbolic_nodes = len(automaton.nodes)
                automaton = compacted(spec, automaton)
        else:
            automaton = synthesis.counterstrategy(gr1, semantics, timeout, progress,
                                                  opts.options)
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
        if opts.check_it:
            if progress is not None:
                progress(Stage("checking the controller with the independent verifier"))
            report = prove(spec, automaton, semantics)
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
        separation=separation,
    )


def _stay_separated(spec: Spec | GR1Spec, semantics: Semantics, opts: SolveOptions
                    ) -> tuple[GR1Spec, Separation] | None:
    """The spec whose controllers never force the environment to break an assumption, when
    ``spec`` is not well-separated (:func:`gaitc.analysis.separation.stay_separated`)."""
    if opts.progress is not None:
        opts.progress(Stage("checking well-separation (Maoz and Ringert)"))
    return stay_separated(spec, semantics, Limits(opts.timeout).check)


def _separated_controller(found: Solved, why: Separation, fallback: Callable[[], Solved]
                          ) -> tuple[Solved, str | None]:
    """The controller of the separated spec (``found``) with the words saying it never
    forces an assumption to break; when there is none, the controller of the spec itself
    (``fallback()``) with the words saying it may (no words when there is none either)."""
    if found is not None:
        return found, preference_note(why, kept=True)
    plain = fallback()
    return plain, None if plain is None else preference_note(why, kept=False)


def _costs(spec: Spec | GR1Spec, order: Sequence[str]) -> tuple[Cost, ...]:
    """The robot model's move costs (:mod:`ltlcompiler.costs`) when ``order`` needs them."""
    if not isinstance(spec, Spec) or spec.model is None or set(order) <= {"goal"}:
        return ()
    return model_costs(spec.model, spec.encoding or EncodingName.ONEHOT)


def _slugs_automaton(gr1: GR1Spec, kind: ControllerKind, semantics: Semantics,
                     timeout: float | None, slugs: str | None) -> Controller | None:
    wanted = kind == ControllerKind.STRATEGY
    run = runner.run_slugs_synth if wanted else runner.run_slugs_counter
    result = run(slugsin_text(gr1), semantics=semantics, timeout=timeout, slugs=slugs)
    if result.realizable != wanted:
        return None
    if result.output is None:
        verdict = "realizable" if result.realizable else "unrealizable"
        raise SolverError(f"SLUGS reported {verdict} but wrote no {kind}")
    if wanted:
        return runner.controller_from_slugs_json(result.output, gr1, semantics)
    return runner.counterstrategy_from_slugs_text(result.output, gr1, semantics)


def compacted(spec: Spec | GR1Spec, automaton: Automaton) -> CompactController:
    """The compact controller (:mod:`gaitc.compact`) of a controller of ``spec`` in any form
    (:meth:`gaitc.forms.base.ControllerForm.to_compact`), refused when it belongs to another
    spec; it is not proved here."""
    bound = as_spec(spec)
    check_belongs(automaton, bound)
    return entry(automaton).to_compact(bound, automaton)


def prove(spec: Spec | GR1Spec, automaton: Automaton, semantics: Semantics | str | None = None
          ) -> VerificationReport:
    """The independent proof that ``automaton`` (a strategy in any form, or a
    counter-strategy) realizes ``spec``, or defeats it: first that it belongs to the spec
    (its whole vocabulary), then its form's proof.  ``semantics`` defaults to the one
    recorded in the controller."""
    bound = as_spec(spec)
    chosen = semantics_named(semantics or automaton.semantics)
    form = entry(automaton)
    why = belongs(automaton, bound)
    if why is not None:  # the proof covers the whole file: its vocabulary is the spec's
        return VerificationReport(
            ok=False, problems=(f"controller does not belong to this spec: {why}",),
            kind=automaton.kind, semantics=chosen, symbolic=form.form != Form.EXPLICIT)
    return form.verify(bound, automaton, chosen)
