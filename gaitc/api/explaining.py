"""Explaining: why a spec is unrealizable and what would fix it, or whether a realizable
spec is realizable for the right reasons (:mod:`gaitc.analysis.explanation`)."""

from __future__ import annotations

from pathlib import Path

from gaitc.analysis.explanation import Explanation
from gaitc.analysis.explanation import explain as explain_spec
from gaitc.api.loading import Spec, load
from gaitc.ir.spec import GR1Spec, Semantics


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
    if isinstance(spec, (str, Path)):
        spec = load(spec)
    if isinstance(spec, GR1Spec):
        return explain_spec(spec, spec.name or "<spec>", semantics=chosen, timeout=timeout,
                            with_repairs=repairs)
    return explain_spec(spec.gr1, spec.path, spec.text, spec.model, encoding=spec.encoding,
                        semantics=chosen, timeout=timeout, with_repairs=repairs)
