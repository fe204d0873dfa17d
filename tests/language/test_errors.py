"""The error catalogue: each tests/errors/*.gait fails (or warns) with exactly its message.

A file's ``# expect: LINE:COL: MESSAGE`` line names the error (and an ``# expect hint: HINT``
line the hint under it, such as the keyword a typo was meant to be); files that only warn list
``# expect warning: LINE:COL: MESSAGE`` lines, in the order the checker reports them.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.diagnostics import (
    GaitcError,
    SpecSemanticError,
    render_diagnostic,
    render_error,
)
from ltlcompiler.frontend import load_model

CATALOGUE = sorted((Path(__file__).parents[1] / "errors").glob("*.gait"))


def _expectations(path: Path, tag: str) -> list[str]:
    prefix = f"# {tag}: "
    lines = path.read_text(encoding="utf-8").splitlines()
    return [line[len(prefix):] for line in lines if line.startswith(prefix)]


def test_the_catalogue_is_large() -> None:
    errors = [p for p in CATALOGUE if _expectations(p, "expect")]
    assert len(errors) >= 30
    assert all(_expectations(p, "expect") or _expectations(p, "expect warning") for p in CATALOGUE)


@pytest.mark.parametrize("path", CATALOGUE, ids=lambda p: p.stem)
def test_catalogue_entry(path: Path) -> None:
    expected_error = _expectations(path, "expect")
    expected_warnings = _expectations(path, "expect warning")
    if expected_error:
        with pytest.raises(GaitcError) as info:
            load_model(str(path))
        err = info.value
        assert err.span is not None
        assert f"{err.span.line}:{err.span.column}: {err.message}" == expected_error[0]
        assert [err.hint] == (_expectations(path, "expect hint") or [err.hint])
        rendered = render_error(err).splitlines()
        assert rendered[0] == f"{path}:{expected_error[0].replace(': ', ': error: ', 1)}"
        source = path.read_text(encoding="utf-8").splitlines()
        if err.span.line <= len(source) and source[err.span.line - 1]:
            assert rendered[1] == "    " + source[err.span.line - 1]
            assert rendered[2].index("^") == 4 + err.span.column - 1
    else:
        _, warnings = load_model(str(path))
        got = [f"{w.span.line}:{w.span.column}: {w.message}" for w in warnings if w.span]
        assert got == expected_warnings
        for w in warnings:
            assert render_diagnostic(w).startswith(f"{path}:{w.span.line}:")


def test_error_kinds() -> None:
    """Semantic mistakes are SpecSemanticError, not a syntax error or a crash."""
    with pytest.raises(SpecSemanticError):
        load_model(str(Path(__file__).parents[1] / "errors" / "unknown_leg.gait"))


def test_missing_file_is_a_user_error(tmp_path: Path) -> None:
    with pytest.raises(GaitcError, match="no such file"):
        load_model(str(tmp_path / "absent.gait"))
