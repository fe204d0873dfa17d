"""``gaitc drive --backend physics``: a gait that carries the chassis off the map is an
error at that gait in the .gait file, naming the step (it was located at a pseudo-file
``<physics model ...>:1:1``), and the backend's region centres are the map's."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.hw.localisation import RegionMap
from gaitc.hw.physics import centre

ROOT = Path(__file__).resolve().parents[2]
RADIAL8 = str(ROOT / "specs" / "robots" / "radial8.yaml")

# radial8 on 2 x 2 cells of 100 mm; its east gait drifts south (tests/hardware/test_drift.py):
# ten cycles of it carry the chassis past the map's eastern and southern edges
DRIFTING = """\
robot "radial8 drifting"
legs L1..L8 health 2
gait west uses L2, L8 moves west valves 00000001, 01000000
gait east uses L3, L4, L6 moves east valves 00000100, 00010000, 00100000
grid 2 x 2 cells a, b, c, d
cache a
start a
visit a, b infinitely often
"""


def test_a_gait_that_leaves_the_map_is_located_at_the_gait(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "drifting.gait"
    spec.write_text(DRIFTING, encoding="utf-8")
    code = main(["drive", str(spec), "--backend", "physics", "--robot", RADIAL8, "--steps",
                 "4", "--cycles", "10", "--cell-size", "100"])
    err = capsys.readouterr().err
    assert code == 1, err
    assert err.splitlines()[-4:] == [
        f"{spec}:4:1: error: step 2: after gait east the model puts the robot at "
        "(251.9, -31.2) mm, outside every region of the map; stopped with all valves vented",
        "    gait east uses L3, L4, L6 moves east valves 00000100, 00010000, 00100000",
        "    " + "^" * 72,
        "  hint: the gait carried the robot off the map: run fewer cycles (--cycles), grow "
        "the cells (--cell-size) or choose a primitive closer to the move",
    ]
    assert "<physics model" not in err


def test_the_centre_of_a_region_is_the_maps() -> None:
    regions = RegionMap({"a": ((0, 0), (100, 0), (100, 60), (0, 60)),
                         "b": ((100, 0), (300, 0), (200, 90))})
    for name in regions.polygons:
        pose = centre(regions, name)
        assert (pose.x, pose.y, pose.theta) == (*regions.centre(name), 0.0)
    assert (centre(regions, "b").x, centre(regions, "b").y) == (200.0, 30.0)
