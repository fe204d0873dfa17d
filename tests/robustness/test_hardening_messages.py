"""Messages that hold whatever the input (issue 38): a malformed controller named by file
and node in every command that reads it, and error excerpts of one screen line however
long the source line."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.diagnostics import EXCERPT, Span, render

PATROL = str(Path(__file__).parents[2] / "gaitc" / "examples" / "patrol_2x2.gait")


@pytest.fixture(scope="module")
def two_regions(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """An explicit controller of the 2 x 2 patrol whose node 1 is in two regions at once."""
    folder = tmp_path_factory.mktemp("ctrl")
    good = folder / "ctrl.json"
    assert main(["synth", PATROL, "-o", str(good)]) == 0
    data = json.loads(good.read_text(encoding="utf-8"))
    names = data["variables"]
    state = data["nodes"]["1"]["state"]
    regions = [i for i, name in enumerate(names) if name in ("nw", "ne", "sw", "se")]
    here = next(i for i in regions if state[i])
    other = next(i for i in regions if i != here)
    state[other] = 1
    bad = folder / "two-regions.json"
    bad.write_text(json.dumps(data), encoding="utf-8")
    return bad


@pytest.mark.parametrize("command", [
    ["simulate", PATROL, "{ctrl}", "--steps", "5"],
    ["render", "automaton", PATROL, "{ctrl}", "-o", "{out}"],
    ["render", "policy", PATROL, "{ctrl}", "-o", "{out}"],
])
def test_a_node_in_two_regions_is_named_with_its_file(
        two_regions: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str],
        command: list[str]) -> None:
    words = [w.format(ctrl=two_regions, out=tmp_path / "out.dot") for w in command]
    assert main(words) == 1
    err = capsys.readouterr().err
    first = err.splitlines()[0]
    assert first.startswith(f"{two_regions}:1:1: error: node 1 of the controller: "
                            "inconsistent state: several regions are true at once: ")
    assert "check it with 'gaitc verify SPEC CONTROLLER'" in err
    assert not (tmp_path / "out.dot").exists()


def test_a_long_source_line_is_cut_around_the_column(tmp_path: Path) -> None:
    path = tmp_path / "long.txt"
    path.write_text("x" * 50 + "ERR" + "y" * 300 + "\n", encoding="utf-8")
    shown = render("bad", Span(str(path), 1, 51, 1, 53)).splitlines()
    assert shown[0] == f"{path}:1:51: error: bad"
    assert shown[1] == "    ..." + "x" * 31 + "ERR" + "y" * 60 + "..."
    assert shown[2] == "    " + " " * 34 + "^^^"
    assert all(len(line) <= EXCERPT + 4 for line in shown[1:])


@pytest.mark.parametrize("column", [1, 60, 353])
def test_the_caret_stays_under_its_character(tmp_path: Path, column: int) -> None:
    text = "".join(chr(ord("a") + i % 26) for i in range(353))
    path = tmp_path / "long.txt"
    path.write_text(text + "\n", encoding="utf-8")
    _, line, caret = render("bad", Span(str(path), 1, column)).splitlines()
    assert line[caret.index("^")] == text[column - 1]
    assert len(line) <= EXCERPT + 4


HUGE = "99999999999999999999"


@pytest.mark.parametrize("command", [
    ["simulate", PATROL, "--steps", HUGE],
    ["simulate", PATROL, "--env", "adversarial", "--steps", HUGE],
    ["drive", PATROL, "--steps", HUGE],
])
def test_more_steps_than_a_run_may_have_are_refused_at_once(
        command: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 60: a run is kept whole, so ``--steps`` past :data:`MAX_STEPS` is a usage
    error before any work, not a run that grows until it is killed."""
    assert main(command) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"gaitc: usage error: --steps is {HUGE}, more than the 1,000,000 "
                          "steps a run may have")
    assert "Traceback" not in err


def test_the_library_bounds_the_steps_of_every_run() -> None:
    import gaitc
    from gaitc.api.runs import MAX_STEPS
    from gaitc.diagnostics import UsageError

    with pytest.raises(UsageError, match="more than the 1,000,000 steps a run may have"):
        gaitc.simulate(PATROL, steps=MAX_STEPS + 1)
    player = gaitc.player(PATROL)
    before = player.step
    with pytest.raises(UsageError, match="more than the 1,000,000 steps"):
        player.autoplay(MAX_STEPS + 1)
    assert player.step == before  # nothing was played
