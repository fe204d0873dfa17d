"""Fitting the spring-damper parameters to recorded data (thesis section 4.2.1).

Three fits, each from a CSV file with a header row:

* curvature step response (``time,curvature``; s, 1/mm): the second-order model
  κ̈ = ω²(κ_f − κ) − 2ζω κ̇ from rest at κ_0 ("Modeling Actuator Curvature");
* force/deflection data per steady state (``state,dx,dy,dz,fx,fy,fz``; valve pattern,
  mm, N): a linear least-squares fit F = K d for each state, K symmetrised ("Measuring
  Actuator Stiffness and Damping", figure 4.7);
* the step response of a known mass hung on the end effector (``time,displacement``; s,
  mm) with the stiffness known: the damping b of m ẍ + b ẋ + k x = m g.

Errors in the files are :class:`CharacterizationError` with the file, line and column.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares

from gaitc.diagnostics import Span
from gaitc.diagnostics.files import csv_rows, decode_text, read_input
from gaitc.models.fields import ModelFileError

Array = NDArray[np.float64]


class CharacterizationError(ModelFileError):
    """A characterization CSV file is malformed or its data cannot be fitted."""


def step_response(t: Array, start: float, final: float, frequency: float, zeta: float) -> Array:
    """The closed-form response of x'' = ω²(x_f − x) − 2ζω x' from rest at ``start``."""
    w, z = frequency, zeta
    if abs(z - 1.0) < 1e-6:
        shape = np.exp(-w * t) * (1.0 + w * t)
    elif z < 1.0:
        wd = w * math.sqrt(1.0 - z * z)
        shape = np.exp(-z * w * t) * (np.cos(wd * t) + z * w / wd * np.sin(wd * t))
    else:
        r = w * math.sqrt(z * z - 1.0)
        s1, s2 = -z * w + r, -z * w - r
        shape = (s2 * np.exp(s1 * t) - s1 * np.exp(s2 * t)) / (s2 - s1)
    out: Array = final + (start - final) * shape
    return out


def read_columns(path: str | Path, columns: tuple[str, ...]) -> tuple[list[str], Array, str]:
    """The first column as text and the others as numbers (rows, columns), with the path."""
    name = str(path)
    data = read_input(path, "recording")
    text = decode_text(data, name, CharacterizationError)
    rows = csv_rows(text, name, CharacterizationError)
    if not rows or [c.strip() for c in rows[0]] != list(columns):
        raise CharacterizationError(
            f"{name} must start with the header {','.join(columns)}", Span(name, 1, 1)
        )
    labels: list[str] = []
    values: list[list[float]] = []
    for line, row in enumerate(rows[1:], start=2):
        if not row or all(not c.strip() for c in row):
            continue
        if len(row) != len(columns):
            raise CharacterizationError(
                f"row has {len(row)} values, the header {len(columns)}", Span(name, line, 1)
            )
        labels.append(row[0].strip())
        numbers = []
        column = len(row[0]) + 2
        for cell in row[1:]:
            try:
                value = float(cell)
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                raise CharacterizationError(
                    f"{cell.strip()!r} is not a finite number", Span(name, line, column)
                )
            numbers.append(value)
            column += len(cell) + 1
        values.append(numbers)
    if len(values) < 4:
        raise CharacterizationError(f"{name} has {len(values)} data rows; a fit needs at least 4")
    return labels, np.array(values), name


@dataclass(frozen=True)
class CurvatureFit:
    """Second-order curvature model of one segment; curvatures in 1/mm."""

    rest_curvature: float
    curvature: float
    frequency: float  # rad/s
    damping_ratio: float
    residual: float  # RMS, 1/mm


def fit_curvature(path: str | Path) -> CurvatureFit:
    """Fit κ_0, κ_f, ω_n and ζ to a recorded step response (the step at the first row)."""
    labels, values, name = read_columns(path, ("time", "curvature"))
    _numeric(labels, name)
    t = np.array([float(x) for x in labels])
    kappa = values[:, 0]
    t = t - t[0]
    _increasing(t, name)
    _plausible(kappa, name, "curvature", "1/mm")
    start, final = float(kappa[0]), float(np.mean(kappa[-max(2, len(kappa) // 10) :]))
    # ω_n's first guess settles the step within the recording, kept inside its bound
    guess = [start, final, max(4.0 / float(t[-1]), 2e-6), 0.7]

    def residual(p: Array) -> Array:
        out: Array = step_response(t, p[0], p[1], p[2], p[3]) - kappa
        return out

    fit = _least_squares(residual, guess, ([-np.inf, -np.inf, 1e-6, 1e-3], np.inf), name)
    k0, kf, w, z = (float(v) for v in fit.x)
    return CurvatureFit(k0, kf, w, z, float(np.sqrt(np.mean(fit.fun**2))))


#: The largest magnitude a recorded value may have: far beyond any limb's curvature (1/mm)
#: or displacement (mm), and small enough that the fit's squares stay finite.
MAX_RECORDED = 1e6


def _plausible(values: Array, name: str, what: str, unit: str) -> None:
    """Every recorded value within :data:`MAX_RECORDED`; the first that is not is an error
    at its line."""
    for row, value in enumerate(values):
        if abs(float(value)) > MAX_RECORDED:
            raise CharacterizationError(
                f"{name}: row {row + 1} gives a {what} of {float(value):.3g} {unit}; recorded "
                f"values are at most {MAX_RECORDED:g} {unit} in size", Span(name, row + 2, 1))


def _least_squares(residual: Callable[[Array], Array], guess: list[float],
                   bounds: tuple[list[float], float], name: str) -> Any:
    """scipy's bounded least squares; a recording it cannot fit (its numbers overflow the
    solver) is an error of the file, not of gaitc."""
    try:
        return least_squares(residual, guess, bounds=bounds)
    except (ValueError, FloatingPointError, OverflowError) as err:
        raise CharacterizationError(f"{name}: the recording cannot be fitted ({err})",
                                    Span(name, 1, 1)) from None


def _increasing(t: Array, name: str) -> None:
    """A recording's times (from 0) must increase from row to row; the first row that does
    not is an error at its line."""
    if len(t) < 2:
        raise CharacterizationError(f"{name}: a step response needs at least two rows",
                                    Span(name, 2, 1))
    for row in range(1, len(t)):
        if not t[row] > t[row - 1]:
            raise CharacterizationError(
                f"{name}: the times must increase from row to row, but row {row + 1} "
                f"({t[row] + 0:.6g} s after the first) is not later than the row before",
                Span(name, row + 2, 1))


def _numeric(labels: list[str], name: str) -> None:
    for line, label in enumerate(labels, start=2):
        try:
            if not math.isfinite(float(label)):
                raise ValueError
        except ValueError:
            raise CharacterizationError(
                f"time {label!r} is not a finite number", Span(name, line, 1)
            ) from None


@dataclass(frozen=True)
class StiffnessFit:
    """One stiffness matrix per steady state (N/mm, limb frame) and the fit's RMS error (N)."""

    matrices: dict[str, tuple[tuple[float, ...], ...]]
    residual: dict[str, float]


def fit_stiffness(path: str | Path) -> StiffnessFit:
    """Linear least-squares F = K d per steady state, symmetrised (thesis figure 4.7)."""
    states, values, name = read_columns(path, ("state", "dx", "dy", "dz", "fx", "fy", "fz"))
    for column, what, unit in ((0, "deflection", "mm"), (3, "force", "N")):
        _plausible(np.abs(values[:, column:column + 3]).max(axis=1), name, what, unit)
    matrices: dict[str, tuple[tuple[float, ...], ...]] = {}
    residual: dict[str, float] = {}
    for state in sorted(set(states)):
        if not state or set(state) - {"0", "1"}:
            line = states.index(state) + 2
            raise CharacterizationError(
                f"state {state!r} must be a valve pattern of 0 and 1", Span(name, line, 1)
            )
        rows = values[[i for i, s in enumerate(states) if s == state]]
        d, f = rows[:, :3], rows[:, 3:]
        if len(rows) < 3 or np.linalg.matrix_rank(d) < 3:
            raise CharacterizationError(
                f"{name}: state {state} needs deflections along three independent directions"
            )
        solution, *_ = np.linalg.lstsq(d, f, rcond=None)
        k = solution.T
        k = 0.5 * (k + k.T)
        matrices[state] = tuple(tuple(round(float(v), 6) for v in row) for row in k)
        residual[state] = float(np.sqrt(np.mean((d @ k.T - f) ** 2)))
    return StiffnessFit(matrices, residual)


@dataclass(frozen=True)
class DampingFit:
    """The damping coefficient b (N·s/mm) from a mass step response."""

    damping: float
    damping_ratio: float
    residual: float  # RMS, mm


def fit_damping(path: str | Path, mass_g: float, stiffness: float) -> DampingFit:
    """Fit b to the step response of ``mass_g`` grams on a spring of ``stiffness`` N/mm.

    The mass is released from rest at the first row; its displacement (mm, along the load)
    settles at m g / k.  The amplitude is fitted with b, so a load-cell offset does not bias b.
    """
    labels, values, name = read_columns(path, ("time", "displacement"))
    _numeric(labels, name)
    t = np.array([float(x) for x in labels])
    t = t - t[0]
    _increasing(t, name)
    x = values[:, 0]
    _plausible(x, name, "displacement", "mm")
    if mass_g <= 0 or stiffness <= 0:
        raise CharacterizationError("the mass and the stiffness must be positive")
    m, k = mass_g / 1000.0, stiffness * 1000.0  # kg, N/m
    w = math.sqrt(k / m)

    def residual(p: Array) -> Array:
        zeta = p[1] / (2.0 * math.sqrt(k * m))
        out: Array = step_response(t, 0.0, p[0], w, zeta) - x
        return out

    guess = [float(np.mean(x[-max(2, len(x) // 10) :])), 2.0 * math.sqrt(k * m) * 0.3]
    fit = _least_squares(residual, guess, ([-np.inf, 1e-9], np.inf), name)
    b = float(fit.x[1])
    return DampingFit(b / 1000.0, b / (2.0 * math.sqrt(k * m)), float(np.sqrt(np.mean(fit.fun**2))))
