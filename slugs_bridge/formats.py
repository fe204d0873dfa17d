"""Loading a GR(1) spec from a SLUGS file, choosing the reader by file extension."""

from __future__ import annotations

from pathlib import Path

from gaitc.diagnostics import SlugsFormatError
from gaitc.diagnostics.files import decode_text
from gaitc.ir.spec import GR1Spec
from slugs_bridge.slugsin import parse_slugsin
from slugs_bridge.structured import parse_structuredslugs

PREFIX_EXTENSIONS = (".slugsin", ".txt")
INFIX_EXTENSIONS = (".structuredslugs", ".structureslugs")


def load_spec_file(path: str) -> GR1Spec:
    """Read a ``.slugsin``/``.txt`` (prefix) or ``.structuredslugs``/``.structureslugs`` file."""
    suffix = Path(path).suffix.lower()
    if suffix not in PREFIX_EXTENSIONS + INFIX_EXTENSIONS:
        known = ", ".join(PREFIX_EXTENSIONS + INFIX_EXTENSIONS)
        raise SlugsFormatError(
            f"cannot tell the format of '{path}' from its extension; known extensions are "
            f"{known} (prefix: .slugsin, .txt; infix: .structuredslugs, .structureslugs)"
        )
    try:
        data = Path(path).read_bytes()
    except FileNotFoundError:
        raise SlugsFormatError(f"cannot read '{path}': no such file") from None
    except OSError as err:
        raise SlugsFormatError(f"cannot read '{path}': {err.strerror or err}") from None
    text = decode_text(data, path, SlugsFormatError)
    if suffix in PREFIX_EXTENSIONS:
        return parse_slugsin(text, path)
    return parse_structuredslugs(text, path)
