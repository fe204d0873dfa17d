"""Deciding a spec: whether a controller exists, without making one.

The embedded BDD solver (:func:`gaitc.solver.synthesis.check`, with the well-separation
check of :mod:`gaitc.analysis.separation` on the same build when asked) or the SLUGS binary
(:mod:`slugs_bridge.runner`) decides; the answer is a :class:`Verdict`.  This is all that
``gaitc check`` loads: the extraction of controllers, their forms, files and proofs are in
:mod:`gaitc.forms.synthesis`, which builds on it.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Final, Literal, get_args

from gaitc.analysis.separation import separation as separated
from gaitc.core.presentation import table
from gaitc.core.spec import Spec
from gaitc.diagnostics import UsageError
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.solver import synthesis
from gaitc.solver.game import GameStats, out_of_memory
from gaitc.solver.progress import Progress
from gaitc.solver.symbolic import Options, SymbolicSpec

if TYPE_CHECKING:
    from gaitc.analysis.separation import Separation

SolverName = Literal["embedded", "slugs"]
#: ``embedded``: the BDD solver in :mod:`gaitc.solver`; ``slugs``: an installed SLUGS binary.
SOLVERS: Final[tuple[SolverName, ...]] = get_args(SolverName)


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
    #: The well-separation check made on the solver's own build, when :func:`decide` was
    #: asked for it (``separation=True``) and the embedded solver decided.
    separation: Separation | None = field(default=None, repr=False, compare=False)

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


def semantics_named(semantics: Semantics | str) -> Semantics:
    """``semantics`` as the enum (a :class:`UsageError` naming the choices otherwise)."""
    return Semantics.parse(semantics, "semantics")


def solver_named(solver: str) -> str:
    """``solver`` when it is one of :data:`SOLVERS` (a :class:`UsageError` otherwise)."""
    if solver not in SOLVERS:
        raise UsageError(f"unknown solver '{solver}'; use one of {', '.join(SOLVERS)}")
    return solver


def spec_name(spec: Spec | GR1Spec) -> str:
    """The name a verdict or synthesis gives ``spec``: its file, else the IR's name."""
    return spec.path if isinstance(spec, Spec) else spec.name or "<spec>"


def slugsin_text(spec: GR1Spec) -> str:
    """``spec`` bit-blasted and written in SLUGS's input format, for the SLUGS binary."""
    # lazy: --solver slugs only; the embedded solver's check needs neither (start-up of check)
    from gaitc.ir.bitblast import bitblast
    from slugs_bridge.slugsin import emit_slugsin

    return emit_slugsin(bitblast(spec))


def decide(spec: Spec | GR1Spec, semantics: Semantics | str = Semantics.DEFAULT,
           solver: str = "embedded", timeout: float | None = None, slugs: str | None = None,
           options: Options | None = None, progress: Progress | None = None, *,
           separation: bool = False) -> Verdict:
    """Decide whether a controller exists for ``spec``.

    ``semantics`` is ``default`` or ``robotics`` (:data:`gaitc.ir.spec.SEMANTICS`), ``solver``
    ``embedded`` or ``slugs`` (then ``slugs`` names the binary, else ``$SLUGS`` or PATH).
    With ``separation``, the embedded solver also checks that the spec is well-separated
    on its own build (:func:`gaitc.analysis.separation.separation`), in ``.separation``.
    Raises :class:`~gaitc.diagnostics.SolverError` when the solver cannot finish.
    """
    gr1 = spec.gr1 if isinstance(spec, Spec) else spec
    started = time.monotonic()
    semantics = semantics_named(semantics)
    if solver_named(solver) == "slugs":
        # lazy: --solver slugs only; the binary's runner needs tempfile (start-up of check)
        from slugs_bridge.runner import run_slugs_check

        result = run_slugs_check(slugsin_text(gr1), semantics=semantics, timeout=timeout,
                                 slugs=slugs)
        return Verdict(spec_name(spec), result.realizable, result.seconds, semantics, solver)

    also = None
    if separation:

        def also(sym: SymbolicSpec, check: Callable[[], None]) -> Separation:
            return separated(spec, check, symbolic=sym)

    try:
        checked = synthesis.check(gr1, semantics, timeout, progress, options, also=also)
    except MemoryError:
        raise out_of_memory() from None
    return Verdict(spec_name(spec), checked.realizable, time.monotonic() - started, semantics,
                   solver, checked.stats, checked.engine, separation=checked.also)
