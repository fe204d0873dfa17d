"""The closed-form Frenet-Serret backbones of the active/passive model (thesis 4.2.2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp, trapezoid

from gaitc.models.active_passive.frenet import (
    backbone,
    centroid,
    frenet_centroid,
    frenet_frames,
    frenet_points,
    segment,
)


def _one(value: float) -> np.ndarray:
    return np.array([value])


def test_constant_curvature_without_torsion_is_a_circular_arc() -> None:
    kappa, s = 0.02, np.linspace(0.0, 120.0, 13)
    points = frenet_points(_one(kappa), _one(0.0), s)[0]
    expected = np.stack([np.sin(kappa * s) / kappa, (1 - np.cos(kappa * s)) / kappa, 0 * s], 1)
    np.testing.assert_allclose(points, expected, atol=1e-12)
    radius = np.linalg.norm(points - np.array([0.0, 1 / kappa, 0.0]), axis=1)
    np.testing.assert_allclose(radius, 1 / kappa, rtol=1e-12)
    tangent = frenet_frames(_one(kappa), _one(0.0), s)[0][:, :, 0]
    np.testing.assert_allclose(tangent[:, 0], np.cos(kappa * s), atol=1e-12)
    np.testing.assert_allclose(tangent[:, 1], np.sin(kappa * s), atol=1e-12)


def test_constant_curvature_and_torsion_is_a_helix() -> None:
    kappa, tau = 0.03, 0.01
    w2 = kappa**2 + tau**2
    s = np.linspace(0.0, 400.0, 41)
    points = frenet_points(_one(kappa), _one(tau), s)[0]
    axis = np.array([tau, 0.0, kappa]) / math.sqrt(w2)  # the Darboux vector's direction
    centre = np.array([0.0, kappa / w2, 0.0])  # the helix axis passes here
    rel = points - centre
    along = rel @ axis
    np.testing.assert_allclose(along, tau * s / math.sqrt(w2), atol=1e-9)  # climbs evenly
    radial = np.linalg.norm(rel - along[:, None] * axis, axis=1)
    np.testing.assert_allclose(radial, kappa / w2, rtol=1e-10)  # at the helix radius
    pitch = 2 * math.pi * tau / w2  # rise per turn
    turn = 2 * math.pi / math.sqrt(w2)
    one_turn = frenet_points(_one(kappa), _one(tau), np.array([0.0, turn]))[0]
    np.testing.assert_allclose((one_turn[1] - one_turn[0]) @ axis, pitch, rtol=1e-10)


def _integrate(kappa: float, tau: float, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    def rhs(_: float, y: np.ndarray) -> np.ndarray:
        t, n, b = y[3:6], y[6:9], y[9:12]
        return np.concatenate([t, kappa * n, -kappa * t + tau * b, -tau * n])

    y0 = np.concatenate([np.zeros(3), np.eye(3).ravel()])
    sol = solve_ivp(rhs, (0.0, s[-1]), y0, t_eval=s, rtol=1e-11, atol=1e-12)
    frames = sol.y[3:].T.reshape(-1, 3, 3).transpose(0, 2, 1)  # columns T, N, B
    return sol.y[:3].T, frames


@pytest.mark.parametrize(
    ("kappa", "tau"), [(0.0196, 0.0), (0.008, 0.006), (0.0, 0.01), (1e-7, 3e-7), (0.05, -0.02)]
)
def test_closed_form_matches_integrating_the_frenet_serret_formulas(
    kappa: float, tau: float
) -> None:
    s = np.linspace(0.0, 90.0, 10)
    points, frames = _integrate(kappa, tau, s)
    np.testing.assert_allclose(frenet_points(_one(kappa), _one(tau), s)[0], points, atol=1e-7)
    np.testing.assert_allclose(frenet_frames(_one(kappa), _one(tau), s)[0], frames, atol=1e-8)
    dense = np.linspace(0.0, 90.0, 20001)
    mean = trapezoid(frenet_points(_one(kappa), _one(tau), dense)[0], dense, axis=0) / 90.0
    np.testing.assert_allclose(frenet_centroid(_one(kappa), _one(tau), 90.0)[0], mean, atol=1e-6)


def test_frames_stay_rotations() -> None:
    frames = frenet_frames(np.array([0.02, 0.0]), np.array([0.01, 0.03]), np.linspace(0, 80, 5))
    eye = np.broadcast_to(np.eye(3), frames.shape)
    np.testing.assert_allclose(frames @ np.swapaxes(frames, -1, -2), eye, atol=1e-12)
    np.testing.assert_allclose(np.linalg.det(frames), 1.0, atol=1e-12)


def test_bending_angle_sets_the_direction_of_the_curl() -> None:
    kappa = np.array([0.0196])
    down, _ = backbone(kappa, np.zeros(1), np.radians([-90.0]), np.array([80.0]))
    tip = down[0, 0]
    radius = 1 / 0.0196
    np.testing.assert_allclose(
        tip, [radius * math.sin(80 / radius), 0.0, -radius * (1 - math.cos(80 / radius))], atol=1e-9
    )
    left = centroid(kappa, np.zeros(1), np.radians([0.0]), 80.0)[0]
    assert left[1] > 0 and abs(left[2]) < 1e-12


@pytest.mark.parametrize("kappa", [0.0, 1e-6, 0.0196])
def test_fused_segment_matches_backbone_and_centroid(kappa: float) -> None:
    tau = np.array([0.0, 1e-7, 0.004, -0.01])
    s = np.linspace(0.0, 90.0, 6)
    angle = math.radians(-90.0)
    points, frames, centre = segment(kappa, angle, tau, s, 90.0)
    k, a = np.full(4, kappa), np.full(4, angle)
    want_points, want_frames = backbone(k, tau, a, s)
    np.testing.assert_allclose(points, want_points, atol=1e-10)
    np.testing.assert_allclose(frames, want_frames, atol=1e-12)
    np.testing.assert_allclose(centre, centroid(k, tau, a, 90.0), atol=1e-10)
