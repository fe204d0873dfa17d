"""Kinematics, stable poses and Kabsch transitions of the gait graph (thesis 2.2)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.gaitgraph.kinematics import arc_point, arc_rotation, forward, valve_int
from gaitc.gaitgraph.motion import kabsch_2d, rotate
from gaitc.gaitgraph.poses import inside_hull, stable_poses
from gaitc.gaitgraph.robot import load_robot

ROBOTS = Path(__file__).resolve().parents[2] / "specs" / "robots"


def test_straight_limit_is_continuous() -> None:
    for k in (1e-12, 1e-8, 1e-5):
        p = arc_point(np.array(k), np.array(0.3), 95.0)
        assert np.allclose(
            p, [k * 95**2 / 2 * math.cos(0.3), k * 95**2 / 2 * math.sin(0.3), 95.0], atol=1e-6
        )
    assert np.allclose(arc_point(np.array(0.0), np.array(1.0), 95.0), [0, 0, 95])


def test_quarter_circle() -> None:
    k = math.pi / 2 / 95.0
    assert np.allclose(arc_point(np.array(k), np.array(0.0), 95.0), [1 / k, 0, 1 / k])


@given(st.floats(0, 0.03), st.floats(-math.pi, math.pi))
@settings(max_examples=60, deadline=None)
def test_arc_length_and_tangent(kappa: float, phi: float) -> None:
    s = np.linspace(0, 95.0, 400)
    pts = arc_point(np.full(400, kappa), np.full(400, phi), s)
    assert abs(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum() - 95.0) < 1e-2
    tangent = arc_rotation(np.array(kappa), np.array(phi), 95.0) @ np.array([0, 0, 1.0])
    numeric = (pts[-1] - pts[-2]) / np.linalg.norm(pts[-1] - pts[-2])
    assert np.allclose(tangent, numeric, atol=5e-3)  # chord of the last step lags by κΔs/2
    mirror = arc_point(np.array(kappa), np.array(phi + math.pi), 95.0)
    tip = pts[-1]
    assert np.allclose(mirror, [-tip[0], -tip[1], tip[2]], atol=1e-9)


def test_symmetric_robot_legs() -> None:
    robot = load_robot(ROBOTS / "symmetric6.yaml")
    g = forward(robot, [0, valve_int("1000"), valve_int("1010"), valve_int("0010")])
    assert np.allclose(g.tips[0, :, 2], -95.0)
    assert g.tips[1, 0, 0] > 100 and g.tips[3, 0, 0] < 100  # c1 bends to +x, c3 to -x
    assert np.allclose(g.tips[2], g.tips[0])  # opposite chambers cancel
    assert np.allclose(g.cg[1, 1:], g.cg[3, 1:]) and g.cg[1, 0] == -g.cg[3, 0]


def test_table_overrides_vector_sum() -> None:
    robot = load_robot(ROBOTS / "asymmetric6.yaml")
    from gaitc.gaitgraph.kinematics import leg_shapes

    kappa, _ = leg_shapes(robot, np.array([valve_int("1100"), valve_int("1010")]))
    assert math.isclose(kappa[0, 0], 0.013) and abs(kappa[1, 0]) < 1e-12


def _tri(point: tuple[float, float], pts: list[tuple[float, float]]) -> bool:
    xy = np.array([pts], dtype=float)
    return bool(inside_hull(np.array([point], dtype=float), xy, (1 << len(pts)) - 1)[0])


def test_stability_on_triangles_and_degenerate_sets() -> None:
    tri = [(0.0, 0.0), (10.0, 0.0), (0.0, 10.0)]
    assert _tri((2, 2), tri)
    assert not _tri((6, 6), tri)
    assert not _tri((5, 0), tri)  # on an edge: not strictly inside
    assert not _tri((1, 0), [(0, 0), (2, 0), (4, 0)])  # collinear
    assert not _tri((1, 0), [(0, 0), (2, 0)])  # two contacts
    assert _tri((1, 1), [(0, 0), (4, 0), (4, 4), (0, 4)])


def test_vented_symmetric_robot_stands_on_all_feet() -> None:
    robot = load_robot(ROBOTS / "symmetric6.yaml")
    poses = stable_poses(robot, forward(robot, [0]))
    assert len(poses) == 1 and int(poses.mask[0]) == 0b111111
    assert np.allclose(poses.z[0], 0.0)


@given(
    st.floats(-math.pi, math.pi),
    st.floats(-200, 200),
    st.floats(-200, 200),
    st.integers(0, 2**31),
)
@settings(max_examples=80, deadline=None)
def test_kabsch_recovers_planar_motions(theta: float, tx: float, ty: float, seed: int) -> None:
    pts = np.random.default_rng(seed).uniform(-100, 100, (1, 5, 2))
    moved = rotate(pts, np.array([theta])) + np.array([tx, ty])
    got, trans, resid = kabsch_2d(pts, moved)
    assert abs(math.remainder(got[0] - theta, 2 * math.pi)) < 1e-9
    assert np.allclose(trans[0], [tx, ty], atol=1e-8) and resid.max() < 1e-8
    mirrored = moved * np.array([1.0, -1.0])  # a reflection is never returned as a fit
    _, _, resid = kabsch_2d(pts, mirrored)
    spread = np.ptp(pts[0, :, 1])
    assert resid.max() > 1e-3 * spread


def test_a_valve_state_can_have_several_stable_poses() -> None:
    robot = load_robot(ROBOTS / "symmetric6.yaml")
    state = valve_int("0010 1100 0010 1100 0010 1100".replace(" ", ""))
    poses = stable_poses(robot, forward(robot, [state]))
    masks = sorted(int(m) for m in poses.mask)
    assert len(masks) >= 2 and len(set(masks)) == len(masks)
    assert 0b010101 in masks  # the tripod L1 L3 L5 with the other legs lifted
