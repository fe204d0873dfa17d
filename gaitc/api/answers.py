"""Answers beyond the verdict: why a spec is unrealizable and what would fix it
(:func:`explain`, over :mod:`gaitc.analysis.explanation`), and which leg failures, health
levels, caches and hazards its task tolerates or needs (:func:`resilience`, over
:mod:`gaitc.analysis.resilience`). Every answer comes from solving variants of the spec again.
"""

from __future__ import annotations

from pathlib import Path

from gaitc.analysis.explanation import Explanation
from gaitc.analysis.explanation import explain as explain_spec
from gaitc.analysis.pool import Pool, Progress, terminal_progress
from gaitc.analysis.resilience import METHODS, Resilience, cache_sites
from gaitc.analysis.resilience import resilience as analyse
from gaitc.analysis.sanity import NOT_WELL_SEPARATED
from gaitc.api.isolation import HardLimits, run_limited
from gaitc.core.spec import Spec, as_spec, load
from gaitc.diagnostics import UsageError
from gaitc.ir.spec import GR1Spec, Semantics
from ltlcompiler.encoding import EncodingName

__all__ = ["METHODS", "NOT_WELL_SEPARATED", "Explanation", "Resilience", "explain",
           "resilience", "terminal_progress"]


def explain(spec: Spec | GR1Spec | str | Path, semantics: Semantics | str = Semantics.DEFAULT,
            timeout: float | None = None, repairs: bool = True) -> Explanation:
    """The :class:`~gaitc.analysis.explanation.Explanation` of ``spec`` (a path is loaded).

    >>> import gaitc
    >>> why = gaitc.explain("specs/unrealizable_2x2.gait")
    >>> why.kind, why.goals
    ('liveness', ('visit se',))
    >>> why.repairs[0].change
    'add a cache at nw'
    """
    chosen = Semantics.parse(semantics, "semantics")
    return explain_spec(as_spec(spec), semantics=chosen, timeout=timeout,
                        with_repairs=repairs)


def resilience(spec: Spec | str | Path, method: str = "parametric",
               health_bound: int | None = None, place_caches: int | None = None,
               *, semantics: Semantics | str = Semantics.DEFAULT, jobs: int = 1,
               dask: str | None = None, progress: Progress | None = None,
               timeout: float | None = None, tolerate: int | None = 2,
               encoding: EncodingName | str | None = None) -> Resilience:
    """The :class:`~gaitc.analysis.resilience.Resilience` report of a ``.gait`` spec.

    ``method``: ``parametric`` (one game with rigid per-leg caps answers every failure set
    and health vector) or ``lattice`` (one solver call per variant, pruned by
    monotonicity); ``jobs``/``dask`` run variant checks in local processes or on a Dask
    cluster. ``health_bound`` B searches the health front over 1..B for every leg
    (default: each leg within its own declared levels); ``place_caches`` K searches the
    K-sets of regions for caches; ``tolerate`` K the most surprises (broken safety
    assumptions, :mod:`gaitc.analysis.tolerance`) up to K, None for none.  With
    ``timeout`` (seconds) the analysis runs in a child process that is stopped a tenth of a
    second past it, its workers with it: a :class:`SolverError` (exit 4).  ``encoding`` is
    that of the analysis's games: binary unless asked, whatever encoding a given spec was
    loaded in, as ``gaitc resilience`` does (the parametric games use integers, the answers
    are the same in both encodings, and a one-hot analysis of a six-legged robot took 3-4
    times as long: issue 59).

    >>> import gaitc
    >>> report = gaitc.resilience("specs/thesis_robot_b.gait")
    >>> report.single_points_of_failure
    ('L1', 'L4', 'L6', 'L8')
    """
    chosen = Semantics.parse(semantics, "semantics")
    if not isinstance(spec, Spec):
        spec = load(spec, EncodingName.BINARY)
    if spec.model is None or spec.encoding is None:
        raise UsageError(f"'{spec.path}': resilience needs a .gait spec, which says what the "
                         "legs, caches and hazards are")
    if health_bound is not None and health_bound < 1:
        raise UsageError("the health bound must be at least 1")
    if place_caches is not None and place_caches < 1:
        raise UsageError("--place-caches needs a number of caches of at least 1")
    sites = len(cache_sites(spec.model))
    if place_caches is not None and place_caches > sites:
        raise UsageError(f"--place-caches {place_caches}: the map has only {sites} regions "
                         "no hazard covers")
    bound = health_bound
    model, path = spec.model, spec.path
    encoding = (EncodingName.BINARY if encoding is None
                else EncodingName.parse(encoding, "encoding"))

    def analysed() -> Resilience:
        with Pool(encoding, chosen, jobs, dask, progress) as pool:
            return analyse(model=model, encoding=encoding, file=path, semantics=chosen,
                           method=method, health_bound=bound, place_caches=place_caches,
                           tolerate=tolerate, pool=pool)

    return run_limited(analysed, HardLimits(seconds=timeout), "the resilience analysis")
