"""Compiling: the checks gaitc makes of a spec without solving it (:func:`lint`), and the
spec written in one of the output formats exactly as ``gaitc compile`` writes it
(:func:`emit`).

Linting a ``.gait`` spec gives the checker's warnings, lowers it in both encodings (which
catches names that clash once encoded) and pairs gaits with their valve primitives
(:mod:`gaitc.search.primitives`: a robot file's declared model is searched as ``gaitc
gaits`` searches it); a ``.slugsin``, ``.structuredslugs`` or ``.ltl`` spec is
read (every syntax and type error with its span).  Either kind is then checked for
well-separation (:func:`separation`: can the system force the environment to break an
assumption?).

``structuredslugs`` and ``slugsin`` are SLUGS's two formats, ``ltl`` the readable LTL text;
each has one writer in :mod:`slugs_bridge` (clauses preceded by a ``#`` comment naming the
rule and ``.gait`` line they came from, names a format cannot carry renamed), and this
module only picks it.  slugsin bit-blasts integer variables first.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import TYPE_CHECKING, Final, NoReturn

from gaitc.analysis.separation import separation as analyse
from gaitc.core.spec import Spec, SpecLike, as_gr1, load, reader_of
from gaitc.diagnostics import Diagnostic, SolverError
from gaitc.diagnostics.choices import Choice
from ltlcompiler.encoding import ENCODINGS
from ltlcompiler.lowering import lower

if TYPE_CHECKING:
    from gaitc.analysis.separation import Separation
    from ltlcompiler.model import Model


class OutputFormat(Choice):
    """The formats ``gaitc compile`` writes."""

    STRUCTUREDSLUGS = "structuredslugs"
    SLUGSIN = "slugsin"
    LTL = "ltl"


FORMATS: Final = tuple(OutputFormat)


def lint(spec: Spec | str | Path, primitives: bool = False,
         timeout: float | None = None) -> tuple[Diagnostic, ...]:
    """The warnings (and primitive errors) of a spec; a path is read as ``.gait`` unless its
    suffix names another format (:func:`gaitc.core.spec.reader_of`).

    Gaits without a valve primitive are reported when ``primitives`` is set or once any
    gait of the spec binds one. Errors in the spec itself raise, as :func:`gaitc.load` does.
    The search behind a primitive bound to a robot file can take seconds; with ``timeout``
    the whole lint runs in a child process stopped that many seconds in (a SolverError).
    """
    if timeout is not None:
        # lazy: lint's child process only with --timeout (start-up of lint)
        from gaitc.api.isolation import HardLimits, run_limited

        try:
            return run_limited(lambda: lint(spec, primitives), HardLimits(seconds=timeout),
                               "the lint")
        except SolverError as err:
            raise SolverError(err.message, err.span, hint=(
                "raise --timeout: the slow part is the search behind a gait's primitive "
                "from a robot file, which explicit valves ('valves 0100, 1000') skip"
            )) from None

    if not isinstance(spec, Spec):
        spec = load(spec, kind=reader_of(str(spec)))
    model = spec.model
    if model is None:
        return (*spec.diagnostics, *separation(spec).warnings())
    for encoding in ENCODINGS:
        if encoding != spec.encoding:
            lower(model, encoding)
    diagnostics = list(spec.diagnostics)
    if primitives or any(g.primitive is not None for g in model.gaits):
        # lazy: numpy and the gait searches, for primitives only (lint's start-up)
        from gaitc.search.primitives import check_gaits

        folder = str(Path(spec.path).resolve().parent)
        diagnostics += check_gaits(model.gaits, folder, legs=[leg.name for leg in model.legs],
                                   moves=gait_moves(model))
    if not any(d.severity == "error" for d in diagnostics):
        diagnostics += separation(spec).warnings()
    return tuple(diagnostics)


def separation(spec: Spec | str | Path, timeout: float | None = None) -> Separation:
    """Whether the system of ``spec`` can force the environment to break an assumption
    (the spec is then not well-separated: Maoz and Ringert, FSE 2016), with each assumption
    it can break and a play of a strategy that forces it
    (:mod:`gaitc.analysis.separation`); a path is read as :func:`lint` reads it.
    ``gaitc lint`` and ``gaitc check`` print its warnings (:meth:`Separation.warnings`).

    >>> import gaitc
    >>> gaitc.separation("specs/thesis_robot_a.gait").well_separated
    True
    """
    if not isinstance(spec, Spec):
        spec = load(spec, kind=reader_of(str(spec)))
    if timeout is None:
        return analyse(spec)

    started = time.monotonic()

    def deadline() -> None:
        if time.monotonic() - started > timeout:
            raise SolverError(f"the well-separation check stopped after {timeout:g} s",
                              hint="raise --timeout")

    return analyse(spec, deadline)


def gait_moves(model: Model) -> dict[str, frozenset[tuple[str, str]]]:
    """Each gait's moves on the map, (source, target) pairs: what its primitive must drive."""
    moves: dict[str, frozenset[tuple[str, str]]] = {}
    for move in model.transitions:
        for name in move.gaits:
            moves[name] = moves.get(name, frozenset()) | {(move.source, move.target)}
    return moves


def emit(spec: SpecLike, fmt: OutputFormat | str = OutputFormat.STRUCTUREDSLUGS) -> str:
    """``spec`` written in ``fmt`` (an :class:`OutputFormat` or its name).

    >>> import gaitc
    >>> s = gaitc.parse("legs L1 health 2\\ngait g uses L1 moves north\\n"
    ...                 "grid 2 x 1\\nstart r0\\n", name="tiny.gait")
    >>> print(gaitc.emit(s, "ltl").splitlines()[0])
    # GR(1) specification in LTL: G = always, F = eventually, X = next state
    """
    chosen = OutputFormat.parse(fmt, "format")
    gr1 = as_gr1(spec)
    if chosen is OutputFormat.STRUCTUREDSLUGS:
        # lazy: one output format's writer, loaded for it only (start-up of lint)
        from slugs_bridge.structured import emit_structuredslugs

        return emit_structuredslugs(gr1)
    if chosen is OutputFormat.SLUGSIN:
        # lazy: one output format's writer, loaded for it only (start-up of lint)
        from gaitc.ir.bitblast import bitblast
        from slugs_bridge.slugsin import emit_slugsin

        return emit_slugsin(bitblast(gr1))
    if chosen is OutputFormat.LTL:
        # lazy: one output format's writer, loaded for it only (start-up of lint)
        from slugs_bridge.ltltext import emit_ltl

        return emit_ltl(gr1)
    every_format_is_written: NoReturn = chosen  # mypy: no format left over
    raise AssertionError(every_format_is_written)


def output_format(output: str, requested: str | None) -> OutputFormat:
    """``requested``, else the format the suffix of ``output`` names, as the readers take
    it (:mod:`gaitc.core.spec`: ``.slugsin`` and ``.txt`` are slugsin, ``.ltl`` LTL text),
    else structuredslugs."""
    if requested is not None:
        return OutputFormat.parse(requested, "format")
    suffix = Path(output).suffix.lstrip(".").lower()
    if suffix == "txt":
        return OutputFormat.SLUGSIN
    return OutputFormat(suffix) if suffix in ("slugsin", "ltl") else OutputFormat.STRUCTUREDSLUGS
