"""The robot half of the facade (``gaitc.gaits``, ``learn``, ``drive``, ``characterize``,
``calibrate``): each is what its command prints and writes, its options are checked with
the command's messages, and its answers hold when checked by other means.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from recordings import ONE_LEG, curvature_csv, damping_csv, recorded

import gaitc
from gaitc.cli import main
from gaitc.gaitgraph.robot import load_robot
from gaitc.gaitgraph.search import search
from gaitc.hw.sensing import calibrate, read_sensing
from gaitc.models.spring_damper.description import load_spring_damper

ROOT = Path(__file__).resolve().parents[2]
SYMMETRIC6 = str(ROOT / "specs" / "robots" / "symmetric6.yaml")
RADIAL8 = str(ROOT / "specs" / "robots" / "radial8.yaml")
PATROL = str(ROOT / "specs" / "radial8_patrol.gait")


def _cli_json(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, dict]:
    code = main([*argv, "--json"])
    return code, json.loads(capsys.readouterr().out)


def test_gaits_is_what_the_command_prints(capsys: pytest.CaptureFixture[str]) -> None:
    found = gaitc.gaits(SYMMETRIC6, gaitc.GaitOptions(direction="+x", seed=3))
    code, printed = _cli_json(["gaits", SYMMETRIC6, "--seed", "3"], capsys)
    assert code == 0 and found.found
    assert {k: v for k, v in printed.items() if k not in ("schema", "command", "written")} \
        == found.to_json()


def test_gaits_agree_with_the_gait_graph_search_itself() -> None:
    """The facade adds no search of its own: the same seed gives the same cycles."""
    found = gaitc.gaits(SYMMETRIC6, gaitc.GaitOptions(direction="-y", seed=5))
    robot = load_robot(SYMMETRIC6)
    direct = search(robot, (0.0, -1.0), "random", 5, 10_000)
    assert isinstance(found, gaitc.api.gaits.KinematicGaits)
    assert [g.valves for g in found.result.gaits] == [g.valves for g in direct.gaits]


def test_gait_options_are_checked_with_the_commands_words() -> None:
    with pytest.raises(gaitc.UsageError, match="unknown search method 'fastest'; use one of "
                       "chapter2, full"):
        gaitc.gaits(SYMMETRIC6, gaitc.GaitOptions(method="fastest"))
    with pytest.raises(ValueError, match="--goal is for --method astar, lpa, dstar or mcts"):
        gaitc.gaits(SYMMETRIC6, gaitc.GaitOptions(search=gaitc.GlobalSearch(goal="10,0")))
    with pytest.raises(gaitc.UsageError, match="--method lpa needs --goal"):
        gaitc.gaits(SYMMETRIC6, gaitc.GaitOptions(method=gaitc.GaitMethod.LPA))
    with pytest.raises(gaitc.UsageError, match="--max-open must be at least 1"):
        gaitc.gaits(RADIAL8, gaitc.GaitOptions(model="spring-damper", max_open=0))
    assert gaitc.GaitMethod.parse("mcts").is_global and not gaitc.GaitMethod.FULL.is_global
    assert f"{gaitc.GaitMethod.LPA}" == "lpa" and json.dumps(gaitc.GaitMethod.LPA) == '"lpa"'


def test_model_gaits_save_a_versioned_file(tmp_path: Path) -> None:
    found = gaitc.gaits(RADIAL8, gaitc.GaitOptions(model="spring-damper"))
    assert found.found
    assert found.save(tmp_path / "g.json")
    saved = json.loads((tmp_path / "g.json").read_text(encoding="utf-8"))
    assert saved == json.loads(json.dumps(found.to_json())) and saved["format"] == 1
    assert "predicted displacement per cycle of gait 1" in str(found)
    assert "<pre>" in found._repr_html_()


def test_a_global_search_plans_and_draws(tmp_path: Path) -> None:
    toward = gaitc.GlobalSearch(goal="40,0", cell="1")
    planned = gaitc.gaits(SYMMETRIC6, gaitc.GaitOptions(method="lpa", seed=2, search=toward))
    assert planned.found and planned.plan is not None
    # compose the plan's transitions, each in the frame of its source pose, and check the
    # cycle reaches the goal within the tolerance (5 mm) without trusting "reached"
    x = y = heading = 0.0
    for step in planned.plan.to_dict()["transitions"]:
        c, s = math.cos(math.radians(heading)), math.sin(math.radians(heading))
        x, y = x + step["dx"] * c - step["dy"] * s, y + step["dx"] * s + step["dy"] * c
        heading += step["rotation"]
    assert math.hypot(x - 40.0, y) <= 5.0 + 0.01, (x, y)
    drawn = planned.draw(tmp_path / "svg")
    assert [Path(p).name for p in drawn] == ["gait-search.svg"]
    assert Path(drawn[0]).read_text(encoding="utf-8").startswith("<svg")


def test_learn_converges_and_its_options_are_checked() -> None:
    toward = gaitc.GlobalSearch(goal="40,0", cell="1")
    lines: list[str] = []
    learned = gaitc.learn(SYMMETRIC6, gaitc.LearnOptions(seed=2, search=toward), lines.append)
    assert learned.converged and lines
    error = learned.learned.error
    assert (error is not None and error[0] <= 5.0 + 1e-9) or learned.notes
    with pytest.raises(gaitc.UsageError, match="--backend serial is not available"):
        gaitc.learn(SYMMETRIC6, gaitc.LearnOptions(backend="serial", search=toward))
    with pytest.raises(gaitc.UsageError, match="unknown backend 'robot'"):
        gaitc.learn(SYMMETRIC6, gaitc.LearnOptions(backend="robot", search=toward))
    with pytest.raises(gaitc.UsageError, match="--infeasible must lie in"):
        gaitc.learn(SYMMETRIC6, gaitc.LearnOptions(infeasible=1.0, search=toward))


def test_drive_on_a_simulated_board_keeps_the_spec(tmp_path: Path) -> None:
    board = gaitc.SimulatedBoard("random", seed=4)
    driven = gaitc.drive(PATROL, None, board, gaitc.DriveOptions(steps=6))
    assert driven.run is not None and len(driven.run.steps) == 7
    summary = driven.run.summary
    assert summary is not None and summary.assumptions_held and summary.guarantees_held
    # the gaits run are exactly the controller's choices, each bound to its primitive
    spec = gaitc.load(PATROL)
    assert spec.model is not None
    bound = {g.name for g in spec.model.gaits if g.primitive is not None}
    assert {s.gait for s in driven.run.steps[1:]} <= bound | {"noGait"}
    document = driven.to_json()
    assert document["backend"] == driven.board and len(document["steps"]) == 7


def test_drive_options_are_checked_before_any_work() -> None:
    with pytest.raises(gaitc.UsageError, match="--backend serial needs --port"):
        gaitc.drive(PATROL, None, gaitc.SerialBoard(""))
    with pytest.raises(gaitc.UsageError, match="--cycles must be at least 1"):
        gaitc.drive(PATROL, None, options=gaitc.DriveOptions(cycles=0))
    with pytest.raises(gaitc.UsageError, match="unknown --on-violation 'panic'"):
        gaitc.drive(PATROL, None, options=gaitc.DriveOptions(on_violation="panic"))
    with pytest.raises(gaitc.UsageError, match="give --map or --cell-size, not both"):
        gaitc.drive(PATROL, None, gaitc.PhysicsBoard(map="m.yaml", cell_size=50.0))


def test_characterize_fits_and_writes_a_file_that_reads_back(tmp_path: Path) -> None:
    robot = tmp_path / "one_leg.yaml"
    robot.write_bytes(ONE_LEG.read_bytes())
    data = gaitc.Recordings(curvature=curvature_csv(tmp_path / "step.csv"),
                            damping=damping_csv(tmp_path / "drop.csv", 0.004, 50.0, 0.05),
                            mass=50.0, spring=0.05)
    fitted = gaitc.characterize(robot, "L1", data)
    assert set(fitted.fields) == {"dynamics", "damping"} and len(fitted.lines) == 2
    out = fitted.write(tmp_path / "fitted.yaml")
    limb = next(x for x in load_spring_damper(out).limbs if x.name == "L1")
    # read back, not trusted: 0.004 N*s/mm is 4 N*s/m, the unit the model works in
    assert limb.damping == pytest.approx(4.0, rel=0.1)
    assert robot.read_bytes() == ONE_LEG.read_bytes()  # the original is untouched
    with pytest.raises(gaitc.UsageError, match="give at least one of --curvature"):
        gaitc.characterize(robot, "L1", gaitc.Recordings())
    with pytest.raises(gaitc.UsageError, match="has no limb 'L9'"):
        gaitc.characterize(robot, "L9", data)


def test_calibrate_writes_the_sensing_file_drive_reads(tmp_path: Path) -> None:
    rows = ["leg,cycle,level,intensity"]
    cycles = recorded(seed=2, noise=10.0, repeats=1)
    for n, cycle in enumerate(cycles):
        rows += [f"{cycle.leg},{n},{cycle.level},{v:.2f}" for v in cycle.samples]
    path = tmp_path / "legs.csv"
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    calibrated = gaitc.calibrate(path)
    out = calibrated.write()
    assert out == str(tmp_path / "legs.sensing.yaml")
    assert read_sensing(out) == calibrated.calibration
    # the CSV's rows are the cycles recorded: the same thresholds as from the cycles
    assert calibrate(cycles) == calibrated.calibration
    assert set(calibrated.to_json()["legs"]) == {c.leg for c in cycles}
