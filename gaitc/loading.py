"""Loading a specification file of any supported kind into a GR(1) spec.

``.gait`` goes through the ltlcompiler front end and lowering (thesis eqs. 3.3-3.9);
``.slugsin``/``.txt`` and ``.structuredslugs`` through the SLUGS format readers.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from diagnostics import Diagnostic, UsageError
from gr1.spec import GR1Spec

if TYPE_CHECKING:
    from ltlcompiler.model import Model

ENCODINGS = ("onehot", "binary")
GAIT_SUFFIXES = (".gait",)
SLUGS_SUFFIXES = (".slugsin", ".txt", ".structuredslugs", ".structureslugs")


@dataclass(frozen=True)
class LoadedSpec:
    """A spec ready for a solver, with the domain model when it came from a ``.gait`` file."""

    path: str
    spec: GR1Spec
    model: Model | None = None
    encoding: str | None = None
    diagnostics: tuple[Diagnostic, ...] = field(default=())
    sha256: str = ""

    def source(self) -> dict[str, str]:
        """The ``source`` record written into controller files."""
        out = {"file": self.path, "sha256": self.sha256}
        if self.encoding is not None:
            out["encoding"] = self.encoding
        return out


def _read(path: str) -> bytes:
    try:
        return Path(path).read_bytes()
    except OSError as err:
        raise UsageError(f"cannot read '{path}': {err.strerror}") from None


def load_spec(path: str, encoding: str = "onehot") -> LoadedSpec:
    """Read ``path`` (.gait, .slugsin, .structuredslugs) into a :class:`LoadedSpec`.

    Raises the project's :class:`~diagnostics.GaitcError` subclasses with a
    span for every problem in the file; :class:`UsageError` for an unknown file kind.
    """
    if encoding not in ENCODINGS:
        raise UsageError(f"unknown encoding '{encoding}'; use one of {', '.join(ENCODINGS)}")
    raw = _read(path)
    digest = hashlib.sha256(raw).hexdigest()
    suffix = Path(path).suffix.lower()
    if suffix in GAIT_SUFFIXES:
        from ltlcompiler.frontend import load_model
        from ltlcompiler.lowering import lower

        model, diagnostics = load_model(path)
        spec = lower(model, encoding)
        return LoadedSpec(path, spec, model, encoding, tuple(diagnostics), digest)
    if suffix in SLUGS_SUFFIXES:
        return LoadedSpec(path, _load_slugs(path), sha256=digest)
    raise UsageError(
        f"'{path}': unknown specification kind '{suffix or '(none)'}'; "
        "give a .gait, .slugsin or .structuredslugs file"
    )


def _load_slugs(path: str) -> GR1Spec:
    from slugs_bridge.formats import load_spec_file

    return load_spec_file(path)
