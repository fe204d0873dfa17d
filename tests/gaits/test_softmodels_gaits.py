"""``gaitc gaits --model spring-damper``: forward gaits for radial8 on predicted motion."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.models.catalogue import load_model, search_gaits
from gaitc.models.gait_graph import ModelGraph, cycle_motion, find_gaits, valve_states
from gaitc.models.motion import Pose2D

RADIAL8 = str(Path(__file__).parents[2] / "specs" / "robots" / "radial8.yaml")
UNIT = {"+x": (1.0, 0.0), "-x": (-1.0, 0.0), "+y": (0.0, 1.0), "-y": (0.0, -1.0)}


@pytest.mark.parametrize("direction", ["+x", "+y", "-x", "-y"])
def test_gaits_cli_finds_a_forward_gait_for_radial8(
    direction: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "gaits.json"
    code = main(
        ["gaits", RADIAL8, "--model", "spring-damper", f"--direction={direction}", "-o", str(out)]
    )
    text = capsys.readouterr().out
    assert code == 0, text
    assert "robot radial8: model spring-damper, 9 valve states, 72 simulated transitions" in text
    line = re.search(r"predicted displacement per cycle of gait 1: (\S+) mm, (\S+) mm", text)
    assert line is not None
    dx, dy = float(line.group(1)), float(line.group(2))
    ux, uy = UNIT[direction]
    assert dx * ux + dy * uy > 10.0  # at least 10 mm forward per cycle
    assert abs(-dx * uy + dy * ux) < 2.0  # and little sideways
    doc = json.loads(out.read_text())
    assert doc["model"] == "spring-damper" and doc["gaits"][0]["displacement"] == [
        pytest.approx(dx, abs=0.051),
        pytest.approx(dy, abs=0.051),
    ]


def test_the_thesis_two_leg_primitive_is_found_and_goes_north() -> None:
    loaded = load_model("spring-damper", RADIAL8)
    found = search_gaits(loaded, (0.0, 1.0))
    assert ("00000100", "00000001") in {tuple(sorted(g.valves, reverse=True)) for g in found.gaits}
    # the rotationally symmetric robot gives the same gait turned by 90 degrees for +x
    east = find_gaits(found.graph, (1.0, 0.0), loaded.body_length)
    north = found.gaits[0].net
    assert math.hypot(east[0].net.x, east[0].net.y) == pytest.approx(
        math.hypot(north.x, north.y), rel=0.02
    )


def test_cycle_motion_composes_in_the_body_frame() -> None:
    quarter = Pose2D(10.0, 0.0, math.pi / 2)
    net = cycle_motion([quarter] * 4)
    assert (net.x, net.y) == pytest.approx((0.0, 0.0), abs=1e-9)
    assert net.theta == pytest.approx(2 * math.pi)


def test_a_graph_without_forward_motion_has_no_gait() -> None:
    states = valve_states(2, 2)
    assert len(states) == 4
    still = ModelGraph(
        "none",
        tuple(states),
        {(a, b): Pose2D(0.1, 0.0, 0.0) for a in states for b in states if a != b},
        6.0,
    )
    assert find_gaits(still, (1.0, 0.0), 100.0) == []


def test_model_options_are_checked(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["gaits", RADIAL8, "--model", "spring-damper", "--max-open", "0"]) == 2
    assert "--max-open must be at least 1" in capsys.readouterr().err
    assert (
        main(["gaits", str(Path(RADIAL8).with_name("symmetric6.yaml")), "--model", "spring-damper"])
        == 1
    )
    assert "robot file has no 'model' section" in capsys.readouterr().err


def test_gaits_model_json_prints_the_documented_keys(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code = main(["gaits", RADIAL8, "--model", "spring-damper", "--direction", "+y", "--json"])
    out = capsys.readouterr().out
    assert code == 0
    doc = json.loads(out)
    table = (Path(__file__).parents[2] / "docs" / "json.md").read_text(encoding="utf-8")
    section = table.split("### gaits --model", 1)[1].split("###", 1)[0]
    documented = set(re.findall(r"^\| `([a-z_0-9]+)` \|", section, re.MULTILINE))
    assert set(doc) == documented | {"schema", "command"}
    assert doc["command"] == "gaits" and doc["valve_states"] == 9
    assert doc["gaits"][0]["valves"] == ["00000001", "00000100"]


SILICONE6 = str(Path(__file__).parents[2] / "specs" / "robots" / "silicone6.yaml")


def test_gaits_cli_finds_a_forward_gait_for_silicone6_with_the_active_passive_model(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """The chapter 4 six-leg robot, through the catalogue's active/passive entry."""
    code = main(["gaits", SILICONE6, "--model", "active-passive", "--direction", "+x"])
    text = capsys.readouterr().out
    assert code == 0, text
    assert text.startswith("robot silicone6: model active-passive")
    line = re.search(r"predicted displacement per cycle of gait 1: (\S+) mm, (\S+) mm", text)
    assert line is not None
    dx, dy = float(line.group(1)), float(line.group(2))
    assert dx > 2.0 and abs(dy) < dx  # forward more than sideways
