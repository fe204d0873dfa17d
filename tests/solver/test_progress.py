"""Progress in the user's words (issue 13): the stages a solve reports, the goal names they
use, the terminal status line and the ``--verbose`` log, and the commands that show them."""

from __future__ import annotations

import io
import os
import select
import subprocess
import sys
from pathlib import Path

import pytest

import gaitc
from gaitc.cli import main
from gaitc.cli.status import StageLog, StatusLine, progress_display
from gaitc.solver.progress import Stage, goal_titles

ROOT = Path(__file__).resolve().parents[2]
PATROL = ROOT / "specs" / "patrol_2x2.gait"
HAZARD = ROOT / "tests" / "data" / "hazard_patrol.gait"


def _stages(path: Path, **options: object) -> list[Stage]:
    seen: list[Stage] = []
    found = gaitc.synthesize(gaitc.load(path), progress=seen.append, **options)  # type: ignore[arg-type]
    assert found.verified
    return seen


def test_a_synthesis_tells_its_stages_in_order_with_the_specs_goal_names() -> None:
    spec = gaitc.load(PATROL)
    titles = goal_titles(spec.gr1)
    assert titles and all(t.startswith("visit ") for t in titles)
    words = [s.words for s in _stages(PATROL, prefer="none")]
    first = {w: words.index(w) for w in dict.fromkeys(words)}
    solving = [w for w in first if w.startswith("solving the game: round 1, goal ")]
    assert [w.rsplit("(", 1)[1].rstrip(")") for w in solving] == list(titles)
    order = ["building the transition relation", solving[0], "extracting the controller",
             "checking the controller with the independent verifier"]
    assert [first[w] for w in order] == sorted(first[w] for w in order)


def test_figures_stay_in_the_detail_and_fractions_are_shares() -> None:
    seen = _stages(HAZARD)
    assert any(s.words.startswith("solving the game without entries into active hazards: "
                                  "round 1, goal 1 of ") for s in seen)
    for stage in seen:
        assert "BDD" not in stage.words and "|Y|" not in stage.words
        assert stage.fraction is None or 0.0 <= stage.fraction <= 1.0
    assert any("live BDD nodes" in s.detail for s in seen)


def test_a_symbolic_synthesis_tells_the_preference_stage() -> None:
    words = {s.words for s in _stages(HAZARD, form="symbolic")}
    assert "writing the strategy as BDDs" in words
    assert "choosing the preferred moves: goal 1 of 2" in words


def test_goal_titles_of_files_without_goal_names_are_their_lines() -> None:
    spec = gaitc.load(ROOT / "tests" / "data" / "gr1_corpus" / "rand3_0000.slugsin")
    titles = goal_titles(spec.gr1)
    assert titles and all(t.startswith("line ") for t in titles)


def test_the_status_line_shows_words_bar_and_clock_and_clears() -> None:
    out = io.StringIO()
    status = StatusLine(out, width=90)
    status(Stage("solving the game: round 2, goal 1 of 2 (visit r11)", "ring 3", 0.5))
    line = status.line()
    assert line.startswith("solving the game: round 2, goal 1 of 2 (visit r11)")
    assert "[#####-----]" in line and line.endswith(" s") and "ring" not in line
    assert len(line) <= 90
    status(Stage("x" * 200))
    assert status.line().count("x") < 90 and "x..." in status.line()
    status.close()
    assert out.getvalue().endswith("\r" + " " * 90 + "\r")


def test_the_verbose_log_prints_each_change_once_with_the_figures() -> None:
    out = io.StringIO()
    log = StageLog(out)
    for stage in (Stage("a", "ring 1", 0.0), Stage("a", "ring 2", 0.0), Stage("a", "n=5", 0.5),
                  Stage("b")):
        log(stage)
    lines = out.getvalue().splitlines()
    assert len(lines) == 3
    assert lines[0].endswith("a (ring 1)") and lines[1].endswith("a (n=5)")
    assert lines[2].endswith(" b")


def test_no_display_off_a_terminal_unless_verbose() -> None:
    with progress_display(stream=io.StringIO()) as shown:
        assert shown is None
    with progress_display(verbose=True, stream=io.StringIO()) as shown:
        assert isinstance(shown, StageLog)


def test_synth_verbose_prints_the_stages_and_plain_synth_prints_none(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "c.json"
    assert main(["synth", str(PATROL), "-o", str(out), "--verbose"]) == 0
    err = capsys.readouterr().err
    assert "building the transition relation" in err and "live BDD nodes" in err
    assert "checking the controller with the independent verifier" in err
    assert main(["check", str(PATROL)]) == 0
    assert capsys.readouterr().err == ""


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs a pseudo-terminal")
def test_on_a_terminal_the_status_line_is_drawn_and_cleared(tmp_path: Path) -> None:
    master, slave = os.openpty()
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "gaitc", "synth", str(HAZARD), "-o",
             str(tmp_path / "c.json")],
            stderr=slave, stdout=subprocess.PIPE, text=True, cwd=ROOT, timeout=300,
            check=False)
        screen = b""
        while select.select([master], [], [], 0.2)[0]:
            chunk = os.read(master, 65536)
            if not chunk:
                break
            screen += chunk
    finally:
        os.close(master)
        os.close(slave)
    assert proc.returncode == 0 and "realizable" in proc.stdout
    text = screen.decode()
    assert "\rbuilding the transition relation" in text or "building the transition" in text
    assert "solving the game: round 1" in text
    assert text.endswith("\r")  # the line was cleared before the results printed
