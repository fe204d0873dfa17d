"""Gait graph building and gait synthesis (thesis Algorithm 1, sections 2.3 and 2.5)."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from gaitc.cli import main
from gaitc.gaitgraph.cycles import edge_weights
from gaitc.gaitgraph.graph import GaitGraph, full_graph
from gaitc.gaitgraph.kinematics import body_length, valve_int
from gaitc.gaitgraph.report import gaits_json
from gaitc.gaitgraph.resets import search_around
from gaitc.gaitgraph.robot import load_robot
from gaitc.gaitgraph.search import search

ROBOTS = Path(__file__).resolve().parents[2] / "specs" / "robots"


@pytest.fixture(scope="module")
def symmetric():  # type: ignore[no-untyped-def]
    return load_robot(ROBOTS / "symmetric6.yaml")


def test_reset_search_closes_a_tripod_stride_with_zero_motion_edges(symmetric) -> None:  # type: ignore[no-untyped-def]
    # tripod L1 L3 L5 bent to +x with the other tripod lifted (two chambers), then to -x
    up, fwd, back = "1100", "1000", "0010"
    u = valve_int("".join([fwd, up, fwd, up, fwd, up]))
    v = valve_int("".join([back, up, back, up, back, up]))
    graph = GaitGraph(symmetric)
    graph.add_states([u, v])
    driving = next(i for i in range(len(graph.edges)) if graph.motion(i).dx > 50)
    found = search_around(graph, driving, 3000)
    assert found is not None
    cycle, around = found
    kappa, length = 0.010, 95.0
    stride = 2 * (1 - math.cos(kappa * length)) / kappa
    assert math.isclose(cycle.displacement[0], stride, abs_tol=1e-6)
    assert abs(cycle.displacement[1]) < 1e-6 and abs(cycle.rotation) < 1e-6
    zero = symmetric.settings.zero_motion
    for m in cycle.motions[1:]:
        assert math.hypot(m.dx, m.dy) <= zero and abs(m.rotation) <= zero
    # every edge of the reset graph except the driving one is a zero-motion edge
    e = around.edges
    assert np.all(np.hypot(e.dx[1:], e.dy[1:]) <= zero)
    assert cycle.keys[0][0] == "".join([fwd, up, fwd, up, fwd, up])


def test_random_gait_of_symmetric_robot_moves_forward(symmetric) -> None:  # type: ignore[no-untyped-def]
    result = search(symmetric, (1.0, 0.0), "random", seed=1)
    assert result.gaits, "no gait found"
    best = result.gaits[0]
    ratio = best.displacement[0] / body_length(symmetric)
    assert 0.1 <= ratio <= 0.5
    assert abs(best.rotation) < 5.0 and abs(best.displacement[1]) < 0.2 * best.displacement[0]
    assert best.valves[0] == best.keys[0][0] and len(best.valves) == len(best.motions)


def test_search_is_deterministic_for_a_seed(symmetric) -> None:  # type: ignore[no-untyped-def]
    a = gaits_json(symmetric, search(symmetric, (1.0, 0.0), "random", seed=4), "+x", 4)
    b = gaits_json(symmetric, search(symmetric, (1.0, 0.0), "random", seed=4), "+x", 4)
    c = gaits_json(symmetric, search(symmetric, (1.0, 0.0), "random", seed=5), "+x", 5)
    assert a == b and a != c


def test_full_graph_of_silicone_robot_and_weights() -> None:
    robot = load_robot(ROBOTS / "silicone6.yaml")
    graph = full_graph(robot)
    assert len(graph.states) == 64 and len(graph.edges) > 0
    assert set(graph.poses.state.tolist()) <= set(range(64))
    moving = int(np.argmax(np.hypot(graph.edges.dx, graph.edges.dy)))
    w = edge_weights(graph, moving)
    assert w[moving] == pytest.approx(1e-4)
    still = np.hypot(graph.edges.dx, graph.edges.dy) <= robot.settings.zero_motion
    assert np.all(w[still] == 1e-2) and np.all(w <= 16.0)
    nxg = graph.to_networkx()
    assert nxg.number_of_nodes() == len(graph)


def test_full_method_refuses_large_robots(symmetric, capsys) -> None:  # type: ignore[no-untyped-def]
    assert main(["gaits", str(ROBOTS / "symmetric6.yaml"), "--method", "full"]) == 1
    assert "too many to enumerate" in capsys.readouterr().err


def test_cli_writes_json_and_svgs(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    out = tmp_path / "g.json"
    code = main(
        [
            "gaits",
            str(ROBOTS / "symmetric6.yaml"),
            "--method",
            "random",
            "--seed",
            "1",
            "-o",
            str(out),
            "--svg",
            str(tmp_path / "svg"),
        ]
    )
    assert code == 0
    text = capsys.readouterr().out
    assert "rank" in text and "valve sequence" in text
    assert '"method": "random"' in out.read_text()
    svgs = sorted(p.name for p in (tmp_path / "svg").iterdir())
    assert "gait1-pose0.svg" in svgs and any(n.startswith("gait-graph") for n in svgs)
    assert "<circle" in (tmp_path / "svg" / "gait1-pose0.svg").read_text()


def test_reset_method_synthesises_a_forward_gait(symmetric) -> None:  # type: ignore[no-untyped-def]
    result = search(symmetric, (1.0, 0.0), "reset", seed=0, max_states=1000)
    assert result.gaits, "no reset gait found"
    best = result.gaits[0]
    assert 0.1 <= best.displacement[0] / body_length(symmetric) <= 0.5
    assert abs(best.rotation) < 1.0 and abs(best.displacement[1]) < 1.0
    zero = symmetric.settings.zero_motion
    moving = [m for m in best.motions if math.hypot(m.dx, m.dy) > zero]
    assert len(moving) == 1 and best.slip <= symmetric.settings.max_slip


def test_render_gaits_draws_the_same_gaits_as_the_gaits_command(tmp_path: Path) -> None:
    robot = str(ROBOTS / "symmetric6.yaml")
    common = ["--method", "random", "--seed", "1"]
    assert main(["gaits", robot, *common, "--svg", str(tmp_path / "a")]) == 0
    assert main(["render", "gaits", robot, *common, "-o", str(tmp_path / "b")]) == 0
    first = sorted(p.name for p in (tmp_path / "a").iterdir())
    second = sorted(p.name for p in (tmp_path / "b").iterdir())
    assert first == second and {"gait-graph.svg", "gait-graph.png", "gait-graph.dot"} <= set(second)
    for name in second:
        if name.endswith(".svg"):
            ET.parse(tmp_path / "b" / name)  # well-formed SVG
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()


def test_render_gaits_of_a_model_robot_says_what_has_no_drawing(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 60: ``render gaits`` of a robot with a chapter 4 model complained about an
    ``--svg`` the user never gave. The message names the model and what is drawn."""
    robot = str(ROBOTS / "silicone6.yaml")
    assert main(["render", "gaits", robot, "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err == ("gaitc: usage error: the gaits of the active-passive model have no "
                   "drawing yet: the drawings are of the chapter 2 gait graph, which "
                   "--model kinematic searches\n")
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_a_cycle_far_off_the_direction_is_not_a_gait_towards_it() -> None:
    """Issue 60: a gait moving 29.9 mm sideways and 2.7 mm the way asked (85 degrees off)
    was ranked first for that direction. Only cycles within 30 degrees count; the rest
    stay ranked by score."""
    from gaitc.gaitgraph.cycles import MAX_HEADING_DEG, GaitCycle, rank

    def cycle(poses: tuple[int, ...], dx: float, dy: float) -> GaitCycle:
        return GaitCycle(poses, (), (), (dx, dy), 0.0, 0.0, 0.0)

    off = cycle((0, 1), 29.9, -2.7)  # towards -y: 2.7 along, 29.9 across
    edge = cycle((0, 2), 5.0, -8.7)  # 29.9 degrees off
    past = cycle((0, 3), 5.0, -8.6)  # 30.2 degrees off
    straight = cycle((0, 4), 0.5, -3.0)
    ranked = rank([off, edge, past, straight], (0.0, -1.0), 0.0)
    assert [c.poses for c in ranked] == [(0, 2), (0, 4)]
    assert MAX_HEADING_DEG == 30.0
