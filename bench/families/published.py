"""The published GR(1) instances, read as their authors publish them (issue 59).

``../shared/bench/`` (or ``$GAITC_PUBLISHED``) holds instances of gr1c, SLUGS, SYNTCOMP and
Spectra's benchmark set, each in every form given: ``.slugsin`` and ``.structuredslugs``
(SLUGS's two formats, also ``.txt`` for a structured SLUGS example), ``.spc`` and
``.bits.spc`` (gr1c's own language).  An instance is a folder and a stem; its forms are the
files of that stem.  Its reference verdict is the folder's ``verdicts.tsv`` where it names
the instance, else the benchmark's naming rule (the ``w_guar_*`` and ``wo_ass_*`` variants
of Spectra's set and the ``*_unrealizable*`` specs are unrealizable, all else realizable;
``../shared/bench/README.md``).

No instance is changed: gaitc reads the SLUGS forms as they are, SLUGS its ``.slugsin``,
gr1c its ``.spc`` and omega a SLUGS form (:mod:`peers.omega_game`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Final

ROOT: Final = Path(__file__).resolve().parent.parent.parent
#: Where the published instances are unless ``$GAITC_PUBLISHED`` says otherwise.
DEFAULT_FOLDER: Final = ROOT.parent / "shared" / "bench"
#: The forms gaitc reads, in the order their columns are printed.
GAITC_FORMS: Final = (".slugsin", ".structuredslugs")
#: File endings of each form (a structured SLUGS example may be a ``.txt``).
_ENDINGS: Final = {".bits.spc": ".spc", ".spc": ".spc", ".slugsin": ".slugsin",
                   ".structuredslugs": ".structuredslugs", ".txt": ".structuredslugs"}


@dataclass(frozen=True)
class Published:
    """One published instance: its folder (the source), stem, forms and reference verdict."""

    source: str
    name: str
    forms: dict[str, Path]
    verdict: str

    @property
    def title(self) -> str:
        return f"{self.source}/{self.name}"

    def size(self) -> int:
        """Bytes of its smallest SLUGS form (the order rows are printed in)."""
        sizes = [self.forms[f].stat().st_size for f in GAITC_FORMS if f in self.forms]
        return min(sizes) if sizes else 0


def folder() -> Path:
    """The folder of published instances: ``$GAITC_PUBLISHED`` or ``../shared/bench``."""
    named = os.environ.get("GAITC_PUBLISHED")
    return Path(named) if named else DEFAULT_FOLDER


def _form(path: Path) -> tuple[str, str] | None:
    """(stem, form) of a file of an instance, or None for any other file."""
    for ending, form in _ENDINGS.items():
        if path.name.endswith(ending):
            return path.name[: -len(ending)], form
    return None


def _verdicts(where: Path) -> dict[str, str]:
    table = where / "verdicts.tsv"
    if not table.is_file():
        return {}
    out = {}
    for line in table.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            name, verdict = line.split("\t")[:2]
            out[name.strip()] = verdict.strip()
    return out


def _by_name(stem: str) -> str:
    unrealizable = ("_w_guar_" in stem or "_wo_ass_" in stem or "unrealizable" in stem)
    return "unrealizable" if unrealizable else "realizable"


def instances(where: Path | None = None) -> list[Published]:
    """Every instance under ``where`` (default :func:`folder`), by source, then by size."""
    base = where or folder()
    found: list[Published] = []
    for source in sorted(p for p in base.iterdir() if p.is_dir()) if base.is_dir() else []:
        verdicts = _verdicts(source)
        stems: dict[str, dict[str, Path]] = {}
        for path in sorted(source.iterdir()):
            named = _form(path)
            if named is not None:
                stems.setdefault(named[0], {}).setdefault(named[1], path)
        for stem, forms in stems.items():
            verdict = verdicts.get(stem) or _by_name(stem)
            found.append(Published(source.name, stem, forms, verdict))
    return sorted(found, key=lambda p: (p.source, p.size(), p.name))
