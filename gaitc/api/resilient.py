"""Resilience: which leg failures and health levels a ``.gait`` task tolerates, and which
caches and hazard sets it needs or survives (:mod:`gaitc.analysis.resilience`)."""

from __future__ import annotations

from pathlib import Path

from gaitc.analysis.pool import Pool, Progress
from gaitc.analysis.resilience import Resilience, cache_sites
from gaitc.analysis.resilience import resilience as analyse
from gaitc.api.loading import Spec, load
from gaitc.diagnostics import UsageError
from gaitc.ir.spec import Semantics
from ltlcompiler.encoding import EncodingName


def resilience(spec: Spec | str | Path, method: str = "parametric",
               health_bound: int | None = None, place_caches: int | None = None,
               *, semantics: Semantics | str = Semantics.DEFAULT, jobs: int = 1,
               dask: str | None = None, progress: Progress | None = None) -> Resilience:
    """The :class:`~gaitc.analysis.resilience.Resilience` report of a ``.gait`` spec.

    ``method``: ``parametric`` (one game with rigid per-leg caps answers every failure set
    and health vector) or ``lattice`` (one solver call per variant, pruned by
    monotonicity); ``jobs``/``dask`` run variant checks in local processes or on a Dask
    cluster. ``health_bound`` limits the health front (default: the spec's largest health,
    at most 3); ``place_caches`` K searches the K-sets of regions for caches.

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
    bound = health_bound or min(3, max(leg.health for leg in spec.model.legs))
    with Pool(spec.encoding, chosen, jobs, dask, progress) as pool:
        return analyse(
            model=spec.model,
            encoding=spec.encoding,
            file=spec.path,
            semantics=chosen,
            method=method,
            health_bound=bound,
            place_caches=place_caches,
            pool=pool,
        )
