"""Recordings that tests of several concerns share: the one-leg robot file of the
characterization tests, synthetic curvature and displacement step responses written as the
CSV files ``gaitc characterize`` reads, and the waveguide cycles of thesis figure 3.5."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gaitc.hw.sensing import Cycle, figure_3_5_cycles
from gaitc.models.characterization import step_response

ONE_LEG = Path(__file__).resolve().parent / "data" / "softmodels" / "one_leg.yaml"
#: The legs of the sensing tests' three-leg robot.
SENSED_LEGS = ("L1", "L2", "L3")


def recorded(seed: int, noise: float, repeats: int = 3) -> list[Cycle]:
    """Waveguide cycles of figure 3.5 for :data:`SENSED_LEGS`, with seeded noise."""
    return figure_3_5_cycles(SENSED_LEGS, seed, noise, repeats)


def curvature_csv(path: Path, seed: int = 1) -> Path:
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.5, 301)
    kappa = step_response(t, 0.022, 0.008, 11.0, 0.75) + rng.normal(0, 0.0002, len(t))
    path.write_text(
        "time,curvature\n" + "".join(f"{a:.4f},{b:.6f}\n" for a, b in zip(t, kappa, strict=True))
    )
    return path


def damping_csv(path: Path, b: float, mass: float, k: float, seed: int = 3) -> Path:
    rng = np.random.default_rng(seed)
    m, kk, bb = mass / 1000, k * 1000, b * 1000
    t = np.linspace(0.0, 0.6, 241)
    x = step_response(t, 0.0, m * 9.81 / kk * 1000, math.sqrt(kk / m), bb / (2 * math.sqrt(kk * m)))
    x += rng.normal(0, 0.02, len(t))
    path.write_text(
        "time,displacement\n" + "".join(f"{a:.4f},{v:.5f}\n" for a, v in zip(t, x, strict=True))
    )
    return path
