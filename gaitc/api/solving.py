"""Solving, as the facade offers it: verified controllers and counter-strategies for a
spec given as a path, a loaded spec or its IR, and the controller files they are saved in.

The work is :mod:`gaitc.forms.synthesis`'s (synthesizing in a form, proving); this module
converts the arguments, and reads controller files through the one reader
(:mod:`gaitc.forms.reader`).  Deciding alone is :mod:`gaitc.api.deciding`'s.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TypeVar

from gaitc.analysis.tolerance import ToleranceOptions, ToleranceReport, tolerance
from gaitc.compact.controller import CompactController
from gaitc.core.modes import FORM_CHOICES, ControllerKind, Form, form_choice
from gaitc.core.spec import Spec, SpecLike, as_spec, resolve
from gaitc.core.vocabulary import Vocabulary
from gaitc.diagnostics import ControllerError, UsageError
from gaitc.forms.base import Automaton
from gaitc.forms.explicit import Layout, layout_for
from gaitc.forms.reader import ControllerFile, check_belongs, parse_file, read_document
from gaitc.forms.reader import read_controller as read_checked
from gaitc.forms.registry import form_of
from gaitc.forms.synthesis import (
    MAX_NODES,
    SolveOptions,
    Synthesis,
    compacted,
    prove,
    solve,
)
from gaitc.ir.bddfile import SymbolicController
from gaitc.ir.quotient import merge_equivalent
from gaitc.ir.spec import Semantics
from gaitc.solver.preferences import PREFERENCES as PREFERENCES
from gaitc.solver.preferences import preference_order as preference_order
from gaitc.solver.progress import Progress
from gaitc.solver.symbolic import Options
from gaitc.solver.synthesis import Extraction
from gaitc.verifier.strategy import VerificationReport as VerificationReport
from ltlcompiler.encoding import EncodingName

__all__ = ["FORM_CHOICES", "MAX_NODES", "PREFERENCES", "Automaton",
           "Synthesis", "Tolerance", "compact", "controller_form",
           "counterstrategy", "preference_order", "read_controller", "read_once",
           "recorded_encoding", "synthesize", "tolerate", "verify", "vocabulary_of"]

T = TypeVar("T")


def synthesize(spec: SpecLike, semantics: Semantics | str = Semantics.DEFAULT,
               solver: str = "embedded", timeout: float | None = None, *, slugs: str | None = None,
               options: Options | None = None, progress: Progress | None = None,
               verify: bool = True, form: Form | str | None = "auto",
               max_nodes: int | None = MAX_NODES,
               prefer: str | Sequence[str] | None = None) -> Synthesis:
    """A controller for ``spec``, proved by the independent verifier unless ``verify`` is
    False; ``.controller`` is None when the spec is unrealizable.

    ``form`` (:data:`FORM_CHOICES`, or a :class:`Form`): ``explicit`` an automaton,
    ``symbolic`` BDDs (:mod:`gaitc.ir.bddfile`), ``auto`` an automaton unless it would pass
    ``max_nodes`` nodes, ``compact`` decision diagrams over the robot's words
    (:mod:`gaitc.compact`), made from the symbolic strategy and proved on every state by
    the symbolic verifier.

    ``prefer`` orders the move preferences of the controller (either form) among the winning
    moves (``gaitc.solver.preferences``: ``hazard``, ``health``, ``goal``, ``switches``; a list or
    comma-separated text): None is all four in that order, ``"none"`` the solver's first
    move (the behaviour before them).  They apply to the embedded solver; ``hazard``,
    ``health`` and ``switches`` need a ``.gait`` spec.

    For a spec that is not well-separated (:func:`gaitc.separation`), the embedded solver
    first looks for a controller that does not rely on the environment breaking an
    assumption, and ``.separation`` says which kind it wrote
    (docs/background/well-separation.md).
    """
    written = form_choice(form)
    if written in (Form.SYMBOLIC, Form.COMPACT) and solver != "embedded":
        raise UsageError(f"{written} controllers come from the embedded solver; drop --solver "
                         f"slugs or --{written}")
    chosen = Semantics.parse(semantics, "semantics")
    return solve(resolve(spec), ControllerKind.STRATEGY, chosen, SolveOptions(
        solver=solver, timeout=timeout, slugs=slugs, options=options, progress=progress,
        check_it=verify, form=written, max_nodes=max_nodes, prefer=prefer))


@dataclass(frozen=True)
class Tolerance:
    """What :func:`tolerate` found: the report (the most surprises survived, the assumption
    that limits it) and the controller of the original spec for that many surprises."""

    report: ToleranceReport
    synthesis: Synthesis


def tolerate(spec: SpecLike, k: int, semantics: Semantics | str = Semantics.DEFAULT, *,
             breakable: str | None = None, form: Form | str | None = "auto", verify: bool = True,
             max_nodes: int | None = MAX_NODES, options: Options | None = None,
             timeout: float | None = None, progress: Progress | None = None) -> Tolerance:
    """A controller of ``spec`` that keeps every guarantee through up to ``k`` surprises
    (broken safety assumptions; :mod:`gaitc.analysis.tolerance`, after Ehlers and Topcu,
    HSCC 2014), or through the most it can, proved against ``spec`` itself unless ``verify``
    is False; ``.synthesis.controller`` is None when the spec is unrealizable.

    ``breakable`` names the one group of assumptions that may break (default: every one).
    ``form`` is as :func:`synthesize`'s: ``explicit``, ``symbolic``, ``compact``, or
    ``auto`` (explicit unless the automaton would pass ``max_nodes`` nodes); each is the
    strategy of the game with the surprise counter, projected onto the spec's own bits;
    when no surprise can be planned for (the most reached is 0) it is :func:`synthesize`'s
    controller, with its move preferences.
    """
    written = form_choice(form)
    chosen = Semantics.parse(semantics, "semantics")
    bound = resolve(spec)
    started = time.monotonic()
    wanted = (None if written is Form.COMPACT
              else Extraction.AUTO if written is None else Extraction(written.value))
    report = tolerance(bound, chosen, k, ToleranceOptions(
        breakable=breakable, controller=True, planned_only=True,
        explicit=wanted in (Extraction.EXPLICIT, Extraction.AUTO),
        max_nodes=max_nodes if wanted is Extraction.AUTO else None, options=options,
        timeout=timeout, progress=progress))
    if report.reached == 0:  # no surprise planned for: the plain controller, as synth's
        return Tolerance(report, synthesize(bound, chosen, timeout=timeout, options=options,
                                            progress=progress, verify=verify, form=form,
                                            max_nodes=max_nodes))
    automaton: Automaton | None = report.controller
    symbolic_nodes, merged_from = None, None
    if report.automaton is not None:
        automaton = merge_equivalent(report.automaton)
        if automaton is not report.automaton:
            merged_from = len(report.automaton.nodes)
    elif written is Form.COMPACT and report.controller is not None:
        symbolic_nodes = len(report.controller.nodes)
        automaton = compacted(bound, report.controller)
    if automaton is not None:
        automaton = replace(automaton, source=bound.source() if isinstance(bound, Spec)
                            else None)
    proof = prove(bound, automaton, chosen) if automaton is not None and verify else None
    return Tolerance(report, Synthesis(
        spec=bound, kind=ControllerKind.STRATEGY, controller=automaton, report=proof,
        seconds=time.monotonic() - started, semantics=chosen, merged_from=merged_from,
        symbolic_nodes=symbolic_nodes))


def counterstrategy(spec: SpecLike, semantics: Semantics | str = Semantics.DEFAULT,
                    solver: str = "embedded", timeout: float | None = None,
                    slugs: str | None = None, *, options: Options | None = None,
                    progress: Progress | None = None, verify: bool = True) -> Synthesis:
    """The environment's winning strategy for an unrealizable ``spec``, verified;
    ``.controller`` is None when the spec is realizable."""
    chosen = Semantics.parse(semantics, "semantics")
    return solve(resolve(spec), ControllerKind.COUNTERSTRATEGY, chosen,
                 SolveOptions(solver=solver, timeout=timeout, slugs=slugs, options=options,
                              progress=progress, check_it=verify, form=Form.EXPLICIT,
                              max_nodes=None))


def vocabulary_of(spec: SpecLike, ctrl: SymbolicController) -> Vocabulary:
    """The fields a compact controller of ``spec`` decides in
    (:attr:`gaitc.core.spec.Spec.vocabulary`), refused when the symbolic controller ``ctrl``
    is of another spec."""
    bound = as_spec(spec)
    check_belongs(ctrl, bound)
    return bound.vocabulary


def compact(spec: SpecLike, controller: Automaton) -> CompactController:
    """The compact controller (:mod:`gaitc.compact`) of a controller of ``spec`` in any form
    (:func:`gaitc.forms.synthesis.compacted`); it is not proved here."""
    return compacted(as_spec(spec), controller)


def verify(spec: SpecLike,
           controller: Automaton | Synthesis | str | Path | ControllerFile,
           semantics: Semantics | str | None = None) -> VerificationReport:
    """Prove independently that ``controller`` (a strategy in any form, or a
    counter-strategy) realizes ``spec``, or defeats it; a path is read as a controller
    file.  ``semantics`` defaults to the one recorded in the controller
    (:func:`gaitc.forms.synthesis.prove`)."""
    bound = as_spec(spec)
    automaton: Automaton
    if isinstance(controller, (str, Path, ControllerFile)):
        automaton = parse_file(controller, bound)
    elif isinstance(controller, Synthesis):
        if controller.controller is None:
            raise UsageError(f"there is no {controller.kind} to verify")
        automaton = controller.controller
    else:
        automaton = controller
    return prove(bound, automaton, semantics)


def read_controller(path: str | Path | ControllerFile, spec: SpecLike) -> Automaton:
    """A controller file of any form (an explicit automaton, a symbolic or a compact one),
    checked against ``spec``: a file whose bits, integers or fields differ from the spec's
    is a :class:`~gaitc.diagnostics.ControllerError` naming the first difference
    (:mod:`gaitc.forms.reader`, the one reader every command uses)."""
    return read_checked(path, as_spec(spec))


def controller_form(path: str | Path) -> Form:
    """The form of the controller file ``path`` (explicit, symbolic or compact), read from
    the file's header alone; either layout of an explicit controller
    (:func:`gaitc.forms.reader.read_document`)."""
    return form_of(read_document(path))


def recorded_encoding(path: str | Path | ControllerFile) -> EncodingName | None:
    """The encoding a controller file says its spec was compiled with, if it says one
    (a file of any form and layout, :func:`gaitc.forms.reader.read_document`, or a file
    read already); None also when the file cannot be read (the reader that follows names
    what is wrong)."""
    if isinstance(path, ControllerFile):
        return path.encoding
    try:
        return ControllerFile.read(path).encoding
    except (ControllerError, OSError):
        return None


def read_once(controller: T) -> T | ControllerFile:
    """A controller given as a path, read once (:class:`~gaitc.forms.reader.ControllerFile`)
    so that a command asks its encoding and parses its controller from one reading;
    anything else as it is, and so is a path whose file cannot be read (the reader that
    follows names what is wrong)."""
    if not isinstance(controller, (str, Path)):
        return controller
    try:
        return ControllerFile.read(controller)
    except (ControllerError, OSError):
        return controller


#: A SLUGS-JSON explicit controller past this many bytes gets a hint of the tables layout.
LARGE_JSON = 1 << 20


def tables_hint(output: str | Path) -> str | None:
    """For a large explicit controller written as SLUGS's JSON (``NAME.json`` past
    :data:`LARGE_JSON` bytes), a hint that ``NAME.ctl.gz`` writes the compact tables layout
    (about 80 times smaller; docs/controller-format.md); None otherwise."""
    path = Path(output)
    try:
        large = layout_for(path) is Layout.SLUGS_JSON and path.stat().st_size > LARGE_JSON
    except OSError:
        return None
    if not large or path.suffix.lower() != ".json":
        return None
    return (f"{path.stem}.ctl.gz would hold the same controller in the compact tables "
            "layout, about 80 times smaller (docs/controller-format.md)")
