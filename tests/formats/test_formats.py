"""Tests of load_spec_file, which picks the SLUGS reader by extension (slugs_bridge/formats.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.diagnostics import SlugsFormatError
from slugs_bridge.formats import load_spec_file

DATA = Path(__file__).parents[1] / "data" / "slugs_examples"


def test_extensions_choose_the_reader(tmp_path: Path) -> None:
    assert load_spec_file(str(DATA / "unrealizable_waiter.txt")).inputs
    spec = load_spec_file(str(DATA / "water_reservoir.structuredslugs"))
    assert spec.has_integers
    odd = DATA / "specification_debugging_examples__abstract_counterstrategy_example.structureslugs"
    assert load_spec_file(str(odd)).has_integers
    infix = tmp_path / "x.structuredslugs"
    infix.write_text("[OUTPUT]\ny\n[SYS_INIT]\n| y y\n", encoding="utf-8")
    assert load_spec_file(str(infix)).sys_init


def test_unknown_extension(tmp_path: Path) -> None:
    path = tmp_path / "spec.ltl"
    path.write_text("[INPUT]\n", encoding="utf-8")
    with pytest.raises(SlugsFormatError) as info:
        load_spec_file(str(path))
    assert info.value.message == (
        f"cannot tell the format of '{path}' from its extension; known extensions are "
        ".slugsin, .txt, .structuredslugs, .structureslugs (prefix: .slugsin, .txt; infix: "
        ".structuredslugs, .structureslugs)"
    )


def test_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "none.slugsin"
    with pytest.raises(SlugsFormatError) as info:
        load_spec_file(str(path))
    assert info.value.message == f"cannot read '{path}': no such file"


def test_not_utf8(tmp_path: Path) -> None:
    path = tmp_path / "latin.slugsin"
    path.write_bytes(b"[INPUT]\nx\n[ENV_INIT]\n  caf\xe9\n")
    with pytest.raises(SlugsFormatError) as info:
        load_spec_file(str(path))
    err = info.value
    assert err.message.startswith(f"'{path}' is not UTF-8 text (byte 0xe9")
    assert err.span is not None and (err.span.line, err.span.column) == (4, 6)
