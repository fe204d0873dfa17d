"""Constant curvature and torsion backbones: the Frenet-Serret formulas in closed form.

Thesis section 4.2.2 ("Active and Passive Deformations"): each silicone segment has constant
curvature κ (active) and torsion τ (passive for the middle segment); its shape is the
Frenet-Serret frame integrated for constant κ and τ.  With T' = κN, N' = −κT + τB, B' = −τN
the Darboux vector D = τT + κB is constant, so the frame turns about D at the rate |D| and
the backbone is a circular helix (a circle for τ = 0, a twisted straight rod for κ = 0).
Everything here is vectorised over a leading batch axis of (κ, τ) pairs.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]

_SMALL = 1e-3  # below this |u| the series forms are used (error far below 1e-12)


def _sinc(u: Array) -> Array:
    """sin(u)/u."""
    small = np.abs(u) < _SMALL
    safe = np.where(small, 1.0, u)
    return np.where(small, 1.0 - u * u / 6.0 + u**4 / 120.0, np.sin(safe) / safe)


def _cosc(u: Array) -> Array:
    """(1 − cos u)/u²."""
    small = np.abs(u) < _SMALL
    safe = np.where(small, 1.0, u)
    return np.where(small, 0.5 - u * u / 24.0 + u**4 / 720.0, (1.0 - np.cos(safe)) / safe**2)


def _sinc3(u: Array) -> Array:
    """(u − sin u)/u³."""
    small = np.abs(u) < _SMALL
    safe = np.where(small, 1.0, u)
    return np.where(
        small, 1.0 / 6.0 - u * u / 120.0 + u**4 / 5040.0, (safe - np.sin(safe)) / safe**3
    )


def _quart(u: Array) -> Array:
    """(u²/2 − 1 + cos u)/u⁴."""
    small = np.abs(u) < 2e-2
    safe = np.where(small, 1.0, u)
    return np.where(
        small,
        1.0 / 24.0 - u * u / 720.0 + u**4 / 40320.0,
        (safe**2 / 2 - 1 + np.cos(safe)) / safe**4,
    )


def _split(kappa: Array, tau: Array) -> tuple[Array, Array, Array]:
    """|D| and the shares τ²/|D|², κ²/|D|² (1 and 0 for a straight, untwisted rod)."""
    w2 = kappa * kappa + tau * tau
    w = np.sqrt(w2)
    flat = w2 < 1e-300
    safe = np.where(flat, 1.0, w2)
    return w, np.where(flat, 1.0, tau * tau / safe), np.where(flat, 0.0, kappa * kappa / safe)


def frenet_points(kappa: Array, tau: Array, s: Array) -> Array:
    """Backbone points r(s) in the Frenet frame at s = 0 (columns T, N, B).

    ``kappa`` and ``tau`` have shape (B,), ``s`` shape (S,); the result has shape (B, S, 3):
    x = s(τ²/w² + κ²/w² · sin(ws)/(ws)), y = κs²(1 − cos ws)/(ws)², z = τκs³(ws − sin ws)/(ws)³.
    """
    w, a, b = _split(kappa, tau)
    ss = s[None, :]
    u = w[:, None] * ss
    x = ss * (a[:, None] + b[:, None] * _sinc(u))
    y = kappa[:, None] * ss**2 * _cosc(u)
    z = (tau * kappa)[:, None] * ss**3 * _sinc3(u)
    return np.stack([x, y, z], axis=-1)


def frenet_frames(kappa: Array, tau: Array, s: Array) -> Array:
    """The rotations taking the frame at 0 to the frame at s (Rodrigues about D), (B, S, 3, 3).

    R(s) = I + s·sinc(ws)[D]× + s²(1 − cos ws)/(ws)²[D]×², D = (τ, 0, κ) in the frame at 0.
    """
    w, _, _ = _split(kappa, tau)
    zero = np.zeros_like(kappa)
    skew = np.stack(
        [
            np.stack([zero, -kappa, zero], axis=-1),
            np.stack([kappa, zero, -tau], axis=-1),
            np.stack([zero, tau, zero], axis=-1),
        ],
        axis=-2,
    )  # (B, 3, 3)
    skew2 = skew @ skew
    u = w[:, None] * s[None, :]
    c1 = (s[None, :] * _sinc(u))[..., None, None]
    c2 = (s[None, :] ** 2 * _cosc(u))[..., None, None]
    frames: Array = np.eye(3) + c1 * skew[:, None] + c2 * skew2[:, None]
    return frames


def frenet_centroid(kappa: Array, tau: Array, length: float) -> Array:
    """The mean of r(s) over 0 ≤ s ≤ length (a uniform rod's centre of mass), shape (B, 3)."""
    w, a, b = _split(kappa, tau)
    u = w * length
    x = a * length / 2 + b * length * _cosc(u)
    y = kappa * length**2 * _sinc3(u)
    z = tau * kappa * length**3 * _quart(u)
    return np.stack([x, y, z], axis=-1)


def bending_basis(angle: Array) -> Array:
    """Columns T, N, B of the Frenet frame at s = 0 in the actuator frame, shape (B, 3, 3).

    The backbone leaves along +x; N points in the cross-section plane at ``angle`` from +y
    towards +z (the direction the segment bends to), B = T × N.
    """
    c, s = np.cos(angle), np.sin(angle)
    zero, one = np.zeros_like(angle), np.ones_like(angle)
    cols = [
        np.stack([one, zero, zero], -1),
        np.stack([zero, c, s], -1),
        np.stack([zero, -s, c], -1),
    ]
    return np.stack(cols, axis=-1)


def backbone(kappa: Array, tau: Array, angle: Array, s: Array) -> tuple[Array, Array]:
    """Points (B, S, 3) and cross-section frames (B, S, 3, 3) in the actuator frame."""
    basis = bending_basis(angle)
    points = np.einsum("bij,bsj->bsi", basis, frenet_points(kappa, tau, s))
    frames = basis[:, None] @ frenet_frames(kappa, tau, s) @ np.swapaxes(basis, -1, -2)[:, None]
    return points, frames


def centroid(kappa: Array, tau: Array, angle: Array, length: float) -> Array:
    """Centre of mass of a uniform segment in the actuator frame, (B, 3)."""
    out: Array = np.einsum("bij,bj->bi", bending_basis(angle), frenet_centroid(kappa, tau, length))
    return out


_SKEW = np.zeros((3, 3, 3))  # [d]× = d · _SKEW
_SKEW[0, 2, 1], _SKEW[0, 1, 2] = 1.0, -1.0
_SKEW[1, 0, 2], _SKEW[1, 2, 0] = 1.0, -1.0
_SKEW[2, 1, 0], _SKEW[2, 0, 1] = 1.0, -1.0


def segment(
    kappa: float, angle: float, tau: Array, s: Array, length: float
) -> tuple[Array, Array, Array]:
    """:func:`backbone` and :func:`centroid` at once for one curvature and a batch of
    torsions: points (B, S, 3), frames (B, S, 3, 3), centre of mass (B, 3).  One sine and
    cosine serve every term, and [D]×² = D Dᵀ − |D|² I builds the frames from D directly."""
    c, n = math.cos(angle), math.sin(angle)
    basis = np.array([[1.0, 0.0, 0.0], [0.0, c, -n], [0.0, n, c]])  # columns T, N, B
    w2 = kappa * kappa + tau * tau
    if kappa == 0.0:  # straight: x = s whatever the twist
        a, b = np.ones((tau.size, 1)), np.zeros((tau.size, 1))
    else:
        a, b = (tau * tau / w2)[:, None], (kappa * kappa / w2)[:, None]
    u = np.sqrt(w2)[:, None] * s  # never negative
    small = u < _SMALL
    safe_u = np.where(small, 1.0, u)
    sin, cos = np.sin(safe_u), np.cos(safe_u)
    u2 = u * u
    sinc = np.where(small, 1.0 - u2 / 6.0 + u2 * u2 / 120.0, sin / safe_u)
    cosc = np.where(small, 0.5 - u2 / 24.0 + u2 * u2 / 720.0, (1.0 - cos) / safe_u**2)
    sinc3 = np.where(small, 1.0 / 6.0 - u2 / 120.0, (safe_u - sin) / safe_u**3)
    x = s * (a + b * sinc)
    y = kappa * s * s * cosc
    z = (tau * kappa)[:, None] * s**3 * sinc3
    points = x[..., None] * basis[:, 0] + y[..., None] * basis[:, 1] + z[..., None] * basis[:, 2]
    d = tau[:, None] * basis[:, 0] + kappa * basis[:, 2]  # the Darboux vector, (B, 3)
    skew = np.tensordot(d, _SKEW, axes=1)
    square = d[:, :, None] * d[:, None, :] - w2[:, None, None] * np.eye(3)
    frames = (
        np.eye(3)
        + (s * sinc)[..., None, None] * skew[:, None]
        + (s * s * cosc)[..., None, None] * square[:, None]
    )
    ul = np.sqrt(w2) * length
    mean = (
        (a[:, 0] * length / 2 + b[:, 0] * length * _cosc(ul))[:, None] * basis[:, 0]
        + (kappa * length**2 * _sinc3(ul))[:, None] * basis[:, 1]
        + (tau * kappa * length**3 * _quart(ul))[:, None] * basis[:, 2]
    )
    return points, frames, mean
