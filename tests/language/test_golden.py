"""Golden files: every tests/golden/*.gait compiled to structuredslugs and slugsin, both encodings.

Expected outputs live next to each spec as ``<stem>.<encoding>.<format>``.  After an
intended change, regenerate them with
``pytest tests/language/test_golden.py --update-golden`` (or ``GAITC_UPDATE_GOLDEN=1``)
and review the diff.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from gaitc.cli.commands.compiling import compile_text

GOLDEN = Path(__file__).resolve().parents[1] / "golden"
SPECS = sorted(GOLDEN.glob("*.gait"))
CASES = [(spec, enc, fmt) for spec in SPECS for enc in ("onehot", "binary")
         for fmt in ("structuredslugs", "slugsin")]


def _updating(request: pytest.FixtureRequest) -> bool:
    flag = request.config.getoption("--update-golden", default=False)
    return bool(flag) or os.environ.get("GAITC_UPDATE_GOLDEN") == "1"


@pytest.mark.parametrize(("spec", "encoding", "fmt"), CASES,
                         ids=[f"{s.stem}-{e}-{f}" for s, e, f in CASES])
def test_golden_output(spec: Path, encoding: str, fmt: str, request: pytest.FixtureRequest,
                       monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(GOLDEN.parent.parent)
    text, _ = compile_text(str(spec.relative_to(GOLDEN.parent.parent)), fmt, encoding)
    expected = spec.with_name(f"{spec.stem}.{encoding}.{fmt}")
    if _updating(request):
        expected.write_text(text, encoding="utf-8")
        return
    assert expected.exists(), f"{expected.name} is missing: run with --update-golden"
    assert text == expected.read_text(encoding="utf-8")


def test_there_are_golden_specs_with_every_feature() -> None:
    assert len(SPECS) >= 2
    assert all(spec.with_name(f"{spec.stem}.binary.slugsin").exists() for spec in SPECS)
