"""The map of the code (``docs/background/layout.md``) is the layering test's ``LAYERS``.

The doc's layer table has one row per unit, in ``LAYERS`` order, each with its layer
number; a unit added, removed, moved or renamed in ``LAYERS`` fails here until the doc
follows, so the map cannot drift from the rule the code is held to.
"""

from __future__ import annotations

import re

from packages import ROOT
from test_layout import LAYERS

DOC = ROOT / "docs" / "background" / "layout.md"
HEADER = "| layer | unit | what it owns |"
_ROW = re.compile(r"\|\s*(\d+)\s*\|\s*`([^`]+)`\s*\|(.*)\|\s*$")


def doc_rows() -> list[tuple[int, str, str]]:
    """``(layer, unit, what it owns)`` of each row of the doc's layer table, in order."""
    lines = DOC.read_text(encoding="utf-8").splitlines()
    assert HEADER in lines, f"{DOC.relative_to(ROOT)} has no table headed {HEADER!r}"
    start = lines.index(HEADER) + 2  # past the header and the |---| line
    rows = []
    for number, line in enumerate(lines[start:], start + 1):
        if not line.startswith("|"):
            break
        match = _ROW.match(line)
        assert match, f"{DOC.relative_to(ROOT)}:{number}: not a '| layer | `unit` | ... |' row"
        rows.append((int(match.group(1)), match.group(2), match.group(3).strip()))
    return rows


def expected_rows() -> list[tuple[int, str]]:
    return [(level, unit) for level, layer in enumerate(LAYERS) for unit in layer]


def test_the_layout_doc_lists_every_unit_of_layers_in_order() -> None:
    found = [(level, unit) for level, unit, _ in doc_rows()]
    wanted = expected_rows()
    missing = [unit for _, unit in wanted if unit not in {u for _, u in found}]
    extra = [unit for _, unit in found if unit not in {u for _, u in wanted}]
    assert not missing, f"layout.md has no row for {missing} (they are in LAYERS)"
    assert not extra, f"layout.md has rows for {extra}, which are not in LAYERS"
    assert found == wanted, (
        "layout.md's table is out of order or has wrong layer numbers; it should read\n"
        + "\n".join(f"| {level} | `{unit}` | ... |" for level, unit in wanted))


def test_every_unit_says_what_it_owns() -> None:
    empty = [unit for _, unit, owns in doc_rows() if not owns]
    assert not empty, f"layout.md says nothing about what {empty} own"


def test_a_drifted_table_is_caught() -> None:
    """The comparison above is not vacuous: a swapped pair of rows differs from LAYERS."""
    wanted = expected_rows()
    swapped = [wanted[1], wanted[0], *wanted[2:]]
    assert swapped != wanted
    assert [(level, unit) for level, unit, _ in doc_rows()] == wanted
