"""Tests for the shared error family and its terminal layout."""

from __future__ import annotations

from pathlib import Path

from gaitc.diagnostics import (
    Diagnostic,
    GaitcError,
    Span,
    SpecSemanticError,
    render_diagnostic,
    render_error,
)


def test_error_renders_location_source_line_and_caret() -> None:
    source = "legs L1..L8 health 3\ngait north uses L9 moves north\n"
    err = SpecSemanticError("unknown leg 'L9'", Span("robot.gait", 2, 17, 2, 18))
    text = render_error(err, sources={"robot.gait": source})
    assert text.splitlines() == [
        "robot.gait:2:17: error: unknown leg 'L9'",
        "    gait north uses L9 moves north",
        "                    ^^",
    ]


def test_error_reads_source_from_disk(tmp_path: Path) -> None:
    spec = tmp_path / "x.gait"
    spec.write_text("start nowhere\n", encoding="utf-8")
    err = GaitcError("start region 'nowhere' is not declared", Span(str(spec), 1, 7, 1, 13))
    lines = render_error(err).splitlines()
    assert lines[0] == f"{spec}:1:7: error: start region 'nowhere' is not declared"
    assert lines[2] == "          ^^^^^^^"


def test_caret_is_clipped_to_the_line_and_hint_is_printed() -> None:
    err = GaitcError("bad", Span("f", 1, 3, 1, 99), hint="try this")
    text = render_error(err, sources={"f": "abcd"})
    assert text.splitlines()[2] == "      ^^"
    assert text.splitlines()[3] == "  hint: try this"


def test_missing_file_or_span_still_renders() -> None:
    assert render_error(GaitcError("no span")) == "gaitc: error: no span"
    err = GaitcError("gone", Span("/nonexistent/file.gait", 4, 2))
    assert render_error(err) == "/nonexistent/file.gait:4:2: error: gone"


def test_warning_layout() -> None:
    diag = Diagnostic("goal 'r9' is unreachable from the start", Span("m.gait", 1, 1, 1, 2))
    text = render_diagnostic(diag, sources={"m.gait": "r9 r8\n"})
    assert text.splitlines()[0] == "m.gait:1:1: warning: goal 'r9' is unreachable from the start"


def test_str_of_error_names_location() -> None:
    assert str(GaitcError("oops", Span("a.gait", 3, 4))) == "a.gait:3:4: oops"
