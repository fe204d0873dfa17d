"""Names in SLUGS's two formats and the LTL text: which spec names a format carries as they
are, and the reversible renaming of the others.

A name a format cannot carry (a keyword such as ``F`` or ``next`` in the infix formats, a
digit-only token such as ``0`` in slugsin, a character outside the format's identifiers)
is written under a new name that cannot clash; a ``#`` comment at the top of the output
records the renaming as JSON, ``{"written name": "name in the spec", ...}``, and the
readers map the written names back.  See docs/slugs-formats.md, "Names".
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Mapping
from typing import Final, Literal

from gaitc.diagnostics import SlugsFormatError, Span, source_lines

NameFormat = Literal["structuredslugs", "slugsin", "ltl"]
#: The words of the infix formats (SLUGS's structuredslugs lexer and the LTL text).
KEYWORDS: Final = frozenset({"X", "F", "G", "U", "W", "TRUE", "FALSE", "next"})

#: A name each format carries unchanged (the infix ones must also avoid :data:`KEYWORDS`).
#: structuredslugs: SLUGS's identifiers without '@' (SLUGS reserves it for integer bits);
#: slugsin: letters, digits, '_', '.', '@', not digits only (``0``/``1`` are constants, and
#: counts follow ``$`` and ``?``); ltl: the infix identifiers, '@' allowed (bit names).
_VALID: Final[dict[str, re.Pattern[str]]] = {
    "structuredslugs": re.compile(r"[A-Za-z_.][A-Za-z0-9_.]*"),
    "slugsin": re.compile(r"[A-Za-z0-9_.@]*[A-Za-z_.@][A-Za-z0-9_.@]*"),
    "ltl": re.compile(r"[A-Za-z_.@][A-Za-z0-9_.@]*"),
}
_CHAR: Final[dict[str, re.Pattern[str]]] = {
    "structuredslugs": re.compile(r"[A-Za-z0-9_.]"),
    "slugsin": re.compile(r"[A-Za-z0-9_.@]"),
    "ltl": re.compile(r"[A-Za-z0-9_.@]"),
}
#: The comment line that records a renaming; the JSON object maps written names back.
RENAMED: Final = "# renamed names (as written: as in the spec): "


def is_valid_name(name: str, fmt: NameFormat) -> bool:
    """Whether ``fmt`` can carry ``name`` unchanged (and read it back as the same name)."""
    if _VALID[fmt].fullmatch(name) is None:
        return False
    return fmt == "slugsin" or name not in KEYWORDS


def _candidate(name: str, fmt: NameFormat) -> str:
    allowed = _CHAR[fmt]
    out = "".join(ch if allowed.fullmatch(ch) else "_" for ch in name)
    if fmt != "slugsin" and (not out or out[0].isdigit()):
        out = "_" + out
    return out


def renaming(names: Iterable[str], fmt: NameFormat) -> dict[str, str]:
    """``{spec name: written name}`` for the names ``fmt`` cannot carry, in the given order.

    The written name replaces each character the format does not allow by ``_`` (and puts
    a ``_`` before a leading digit in the infix formats), then appends ``_`` until the name
    is valid and differs from every name in ``names`` and every name chosen before it:
    ``F`` becomes ``F_``, ``next`` becomes ``next_``, ``a b`` becomes ``a_b``, ``0`` becomes
    ``0_``.  Deterministic: the same names in the same order give the same renaming.
    """
    ordered = list(dict.fromkeys(names))
    taken = set(ordered)
    out: dict[str, str] = {}
    for name in ordered:
        if is_valid_name(name, fmt):
            continue
        written = _candidate(name, fmt)
        while not is_valid_name(written, fmt) or written in taken:
            written += "_"
        taken.add(written)
        out[name] = written
    return out


def renaming_comment(renamed: Mapping[str, str]) -> list[str]:
    """The comment line recording ``renamed`` (spec name -> written name); none if empty."""
    if not renamed:
        return []
    back = {written: name for name, written in renamed.items()}
    return [RENAMED + json.dumps(back, ensure_ascii=True)]


def one_line(text: str) -> str:
    """``text`` with its line breaks (any that ``str.splitlines`` knows) turned into spaces."""
    lines = source_lines(text)
    return text if lines == [text] else " ".join(lines)


def read_renaming(text: str, filename: str) -> tuple[dict[str, str], Span | None]:
    """``{written name: spec name}`` from the renaming comment among the leading comments.

    Only ``#`` lines (and blank lines) before the first other line are searched; without
    the comment the renaming is empty and every name stands for itself.
    """
    for number, raw in enumerate(source_lines(text), start=1):
        stripped = raw.strip()
        if not stripped:
            continue
        if not stripped.startswith("#"):
            break
        if not stripped.startswith(RENAMED):
            continue
        start = len(raw) - len(raw.lstrip()) + 1
        span = Span(filename, number, start, number, start + len(stripped) - 1)
        try:
            data = json.loads(stripped[len(RENAMED):])
        except json.JSONDecodeError as err:
            raise SlugsFormatError(
                f"the renaming comment is not a JSON object: {err.msg}", span
            ) from None
        if not isinstance(data, dict) or not all(
            isinstance(k, str) and isinstance(v, str) for k, v in data.items()
        ):
            raise SlugsFormatError(
                "the renaming comment must map written names to spec names, e.g. "
                '{"F_": "F"}',
                span,
            )
        return dict(data), span
    return {}, None


def check_renaming(back: Mapping[str, str], declared: Iterable[str], span: Span | None) -> None:
    """Every renamed name must be declared, and the spec names must stay distinct."""
    written = list(declared)
    known = set(written)
    for name in back:
        if name not in known:
            raise SlugsFormatError(
                f"the renaming comment renames '{name}', which is not declared", span
            )
    seen: dict[str, str] = {}
    for name in written:
        original = back.get(name, name)
        if original in seen:
            raise SlugsFormatError(
                f"the renaming comment gives '{seen[original]}' and '{name}' the same "
                f"spec name '{original}'",
                span,
            )
        seen[original] = name
