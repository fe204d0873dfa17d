"""Emission: a spec written in one of the output formats, exactly as ``gaitc compile`` writes it.

``structuredslugs`` and ``slugsin`` are SLUGS's two formats, ``ltl`` the readable LTL text;
each has one writer in :mod:`slugs_bridge` (clauses preceded by a ``#`` comment naming the
rule and ``.gait`` line they came from, names a format cannot carry renamed), and this
module only picks it.  slugsin bit-blasts integer variables first.
"""

from __future__ import annotations

from pathlib import Path
from typing import Final, Literal, get_args

from gaitc.api.loading import SpecLike, as_gr1
from gaitc.diagnostics import UsageError

Format = Literal["structuredslugs", "slugsin", "ltl"]
FORMATS: Final[tuple[Format, ...]] = get_args(Format)


def emit(spec: SpecLike, fmt: str = "structuredslugs") -> str:
    """``spec`` written in ``fmt`` (one of :data:`FORMATS`).

    >>> import gaitc
    >>> s = gaitc.parse("legs L1 health 2\\ngait g uses L1 moves north\\n"
    ...                 "grid 2 x 1\\nstart r0\\n", name="tiny.gait")
    >>> print(gaitc.emit(s, "ltl").splitlines()[0])
    # GR(1) specification in LTL: G = always, F = eventually, X = next state
    """
    gr1 = as_gr1(spec)
    if fmt == "structuredslugs":
        from slugs_bridge.structured import emit_structuredslugs

        return emit_structuredslugs(gr1)
    if fmt == "slugsin":
        from gaitc.ir.bitblast import bitblast
        from slugs_bridge.slugsin import emit_slugsin

        return emit_slugsin(bitblast(gr1))
    if fmt == "ltl":
        from slugs_bridge.ltltext import emit_ltl

        return emit_ltl(gr1)
    raise UsageError(f"unknown format '{fmt}': use one of {', '.join(FORMATS)}")


def output_format(output: str, requested: str | None) -> str:
    """``requested``, else the format the suffix of ``output`` names, as the readers take
    it (:mod:`gaitc.api.loading`: ``.slugsin`` and ``.txt`` are slugsin, ``.ltl`` LTL text),
    else structuredslugs."""
    if requested is not None:
        return requested
    suffix = Path(output).suffix.lstrip(".").lower()
    if suffix == "txt":
        return "slugsin"
    return suffix if suffix in ("slugsin", "ltl") else "structuredslugs"
