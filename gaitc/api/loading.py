"""Loading, as the facade names it: :mod:`gaitc.core.spec` reads every spec format."""

from __future__ import annotations

from gaitc.core.spec import (
    Spec,
    SpecLike,
    as_gr1,
    as_spec,
    encoding_named,
    load,
    parse,
    reader_of,
    resolve,
)

__all__ = ["Spec", "SpecLike", "as_gr1", "as_spec", "encoding_named", "load", "parse", "reader_of",
           "resolve"]
