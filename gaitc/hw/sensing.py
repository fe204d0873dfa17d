"""Actuator health from the waveguides: curvature feature, calibration, levels (thesis 3.4.2).

Each actuator carries an optical waveguide; bending strains it and the light reaching its
phototransistor drops.  Over one actuation cycle the intensity, filtered and normalised to
its at-rest value, dips; the depth of the dip (``1 - min(normalised)``) is the curvature
feature: a healthy actuator bends fully, a damaged one less, an inoperable one hardly
(Figure 3.5: cycles 1-5 healthy, 6-8 degraded, 9 inoperable).  Per-leg thresholds on the
feature, calibrated from recorded cycles of known level, map it to the spec's health levels;
a hysteresis margin around each threshold keeps noise from flapping a level.  Only legs in
use by the step's gait are graded (the others keep their level, as eq. 3.5 says), and a
step in a cache resets every leg to healthy (eq. 3.6: the actuators were replaced).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from gaitc.diagnostics import GaitcError, Span
from gaitc.diagnostics.files import csv_rows, decode_text, read_input
from gaitc.diagnostics.yamltext import finite_number, keyed_section, mapping_of, node_span
from ltlcompiler.checker import MAX_HEALTH

NOMINAL_DEPTH = 0.6  # curvature feature of a healthy actuator when nothing is calibrated
DEFAULT_HYSTERESIS = 0.03
WINDOW = 5  # samples of the moving average that filters a recorded curve
REST_SAMPLES = 3  # the first samples of a recorded cycle, before actuation: its rest value


class CalibrationError(GaitcError, ValueError):
    """Recorded cycles that cannot be calibrated, or a sensing file that cannot be read."""


@dataclass(frozen=True)
class LegCalibration:
    """One leg's grading: descending thresholds on the curvature feature, one per level
    above 1 (``thresholds[0]`` separates the top level from the next), and the hysteresis."""

    thresholds: tuple[float, ...]
    hysteresis: float = DEFAULT_HYSTERESIS
    span: Span | None = field(default=None, compare=False, repr=False)  # in a sensing file

    @property
    def levels(self) -> int:
        return len(self.thresholds) + 1


def default_calibration(levels: int) -> LegCalibration:
    """Evenly spaced thresholds below the nominal healthy depth, for an uncalibrated leg."""
    return LegCalibration(tuple(NOMINAL_DEPTH * (levels - k) / levels
                                for k in range(1, levels)))


def smooth(samples: Sequence[float], window: int = WINDOW) -> list[float]:
    """A centred moving average (shorter at the ends)."""
    half = window // 2
    out = []
    for i in range(len(samples)):
        part = samples[max(0, i - half):i + half + 1]
        out.append(sum(part) / len(part))
    return out


def curve_feature(samples: Sequence[float], rest: float | None = None) -> float:
    """The curvature feature of one recorded cycle: filter, normalise to the at-rest value
    (``rest``, else the mean of the first samples), and take the depth of the dip."""
    filtered = smooth(samples)
    if not filtered:
        return 0.0
    at_rest = rest if rest is not None else sum(filtered[:REST_SAMPLES]) / len(
        filtered[:REST_SAMPLES])
    return dip(at_rest, min(filtered))


def dip(rest: float, lowest: float) -> float:
    """``1 - lowest/rest``, within 0..1 (0 when there is no light at rest)."""
    if rest <= 0:
        return 0.0
    return min(1.0, max(0.0, 1.0 - lowest / rest))


def grade(calibration: LegCalibration, level: int, feature: float) -> int:
    """The next level from ``level`` for ``feature``: a threshold counts only when the
    feature is beyond it by the hysteresis, so noise around a threshold keeps the level."""
    th, margin, top = calibration.thresholds, calibration.hysteresis, calibration.levels
    level = min(max(level, 1), top)
    while level > 1 and feature < th[top - level] - margin:
        level -= 1
    while level < top and feature >= th[top - level - 1] + margin:
        level += 1
    return level


class HealthSensing:
    """Grades each leg's waveguide reading into a health level, step by step."""

    def __init__(self, full: Mapping[str, int],
                 calibration: Mapping[str, LegCalibration] | None = None) -> None:
        self.full = dict(full)
        given = dict(calibration or {})
        for leg, cal in given.items():
            if leg not in self.full:  # a misspelt leg would leave the real one uncalibrated
                raise CalibrationError(
                    f"the sensing file calibrates leg {leg}, which the spec has not (its legs: "
                    f"{', '.join(self.full)})", cal.span or _where("sensing"))
        self.calibration = {leg: given.get(leg, default_calibration(n))
                            for leg, n in self.full.items()}
        for leg, cal in self.calibration.items():
            if cal.levels != self.full[leg]:
                raise CalibrationError(f"leg {leg} is calibrated for {cal.levels} levels but "
                                       f"the spec gives it {self.full[leg]}",
                                       cal.span or _where("sensing"))
        self.levels = dict(self.full)
        self.rest: dict[str, float] = {}
        self.features: dict[str, float] = {}  # the last feature of each graded leg

    def update(self, now: Mapping[str, float], lowest: Mapping[str, float],
               in_use: Iterable[str], in_cache: bool) -> dict[str, int]:
        """The levels after a step: ``now`` and ``lowest`` are each leg's intensity at the
        reading (vented) and its lowest during the step; ``in_use`` the legs the gait
        pressurised.  The at-rest value is the highest intensity seen (no bend, most light)."""
        for leg, value in now.items():
            self.rest[leg] = max(self.rest.get(leg, 0.0), value)
        if in_cache:
            self.levels = dict(self.full)
            return dict(self.levels)
        for leg in in_use:
            if leg in lowest and leg in self.levels:
                feature = dip(self.rest.get(leg, 0.0), lowest[leg])
                self.features[leg] = feature
                self.levels[leg] = grade(self.calibration[leg], self.levels[leg], feature)
        return dict(self.levels)


# ---------------------------------------------------------------------------- synthetic curves
FIGURE_3_5_DEPTHS = (0.62, 0.61, 0.60, 0.60, 0.58, 0.36, 0.33, 0.30, 0.06)
"""Dip depths of nine cycles of a progressively damaged actuator, shaped like Figure 3.5
(cycles 1-5 healthy, 6-8 degraded, 9 inoperable; the thesis gives the curves, not numbers)."""


def synthetic_cycle(depth: float, rest: float = 800.0, noise: float = 0.0, seed: int = 0,
                    samples: int = 60) -> tuple[float, ...]:
    """One actuation cycle of a waveguide: at rest, a smooth dip to ``rest * (1 - depth)``,
    held, and back; plus uniform noise of ``noise`` counts (deterministic in ``seed``)."""
    state = seed * 2654435761 % 2**32 or 1

    def jitter() -> float:
        nonlocal state
        state = (state * 1103515245 + 12345) % 2**31
        return (state / 2**30 - 1.0) * noise

    out = []
    ramp = samples // 6
    for i in range(samples):
        if i < ramp or i >= samples - ramp:
            bend = 0.0
        elif i < 2 * ramp:
            bend = 0.5 - 0.5 * math.cos(math.pi * (i - ramp) / ramp)
        elif i >= samples - 2 * ramp:
            bend = 0.5 + 0.5 * math.cos(math.pi * (i - (samples - 2 * ramp)) / ramp)
        else:
            bend = 1.0
        out.append(rest * (1.0 - depth * bend) + jitter())
    return tuple(out)


def figure_3_5_cycles(legs: Sequence[str], seed: int, noise: float, repeats: int = 3
                      ) -> list[Cycle]:
    """Figure 3.5's nine cycles for each leg, ``repeats`` times, with a cycle-to-cycle spread
    of the depth (±0.01), a rest value per leg and sensor noise of ``noise`` counts."""
    levels = (3, 3, 3, 3, 3, 2, 2, 2, 1)
    cycles = []
    for k, leg in enumerate(legs):
        for r in range(repeats):
            for i, (depth, level) in enumerate(zip(FIGURE_3_5_DEPTHS, levels, strict=True)):
                spread = 0.01 * ((i + r + k) % 3 - 1)
                samples = synthetic_cycle(depth + spread, 700.0 + 50 * k, noise,
                                          seed * 1000 + r * 100 + i * 10 + k)
                cycles.append(Cycle(leg, level, samples))
    return cycles


def confusion(calibration: Mapping[str, LegCalibration], cycles: Iterable[Cycle]
              ) -> list[list[int]]:
    """How ``cycles`` of known level are classified (each from the healthy level, so one
    cycle's feature alone decides): ``matrix[i][j]`` counts true level ``top - i`` taken as
    level ``top - j``."""
    top = max(cal.levels for cal in calibration.values())
    matrix = [[0] * top for _ in range(top)]
    for cycle in cycles:
        cal = calibration[cycle.leg]
        level = grade(cal, cal.levels, curve_feature(cycle.samples))
        matrix[top - cycle.level][top - level] += 1
    return matrix


# ---------------------------------------------------------------------------- calibration
@dataclass(frozen=True)
class Cycle:
    """One recorded actuation cycle of a leg, with the level it is known to have."""

    leg: str
    level: int
    samples: tuple[float, ...]


def read_cycles(path: str | Path) -> list[Cycle]:
    """``leg,cycle,level,intensity`` rows (one per sample, in time order) → cycles."""
    name = str(path)
    text = decode_text(read_input(path, "recording"), name, CalibrationError)
    rows = csv_rows(text, name, CalibrationError)
    if not rows or [c.strip() for c in rows[0]] != ["leg", "cycle", "level", "intensity"]:
        raise CalibrationError("the first line must be the header leg,cycle,level,intensity",
                               Span(name, 1, 1))
    grouped: dict[tuple[str, str], tuple[int, list[float]]] = {}
    for number, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        try:
            leg, cycle, level, value = (c.strip() for c in row)
            key, lv, sample = (leg, cycle), int(level), float(value)
        except ValueError:
            raise CalibrationError(f"line {number}: expected leg,cycle,level,intensity with a "
                                   "whole level and a number", Span(name, number, 1)) from None
        if not 1 <= lv <= MAX_HEALTH or not math.isfinite(sample):
            raise CalibrationError(f"line {number}: levels run from 1 to {MAX_HEALTH} (the "
                                   "health levels a .gait leg may have) and intensities are "
                                   "finite numbers", Span(name, number, 1))
        known = grouped.setdefault(key, (lv, []))
        if known[0] != lv:
            raise CalibrationError(f"line {number}: cycle {cycle} of leg {leg} changes its "
                                   f"level from {known[0]} to {lv}", Span(name, number, 1))
        known[1].append(sample)
    return [Cycle(leg, lv, tuple(s)) for (leg, _), (lv, s) in grouped.items()]


def calibrate(cycles: Sequence[Cycle]) -> dict[str, LegCalibration]:
    """Per leg: each threshold midway between the lowest feature of a level and the highest
    of the level below; the hysteresis a quarter of the narrowest gap.  Every level from 1 to
    the leg's highest must be recorded, and the levels must not overlap."""
    by_leg: dict[str, dict[int, list[float]]] = {}
    for cycle in cycles:
        by_leg.setdefault(cycle.leg, {}).setdefault(cycle.level, []).append(
            curve_feature(cycle.samples))
    out = {}
    for leg, features in by_leg.items():
        top = max(features)
        missing = [lv for lv in range(1, top + 1) if lv not in features]
        if missing or top < 2:
            raise CalibrationError(f"leg {leg}: no recorded cycle of level(s) "
                                   f"{', '.join(map(str, missing or [2]))}", _where("calibrate"))
        thresholds, gaps = [], []
        for level in range(top, 1, -1):
            low, high = min(features[level]), max(features[level - 1])
            if low <= high:
                raise CalibrationError(
                    f"leg {leg}: levels {level} and {level - 1} overlap (curvature features "
                    f"down to {low:.3f} and up to {high:.3f}); they cannot be told apart",
                    _where("calibrate"), "record more distinct cycles, or merge the levels")
            thresholds.append(round((low + high) / 2, 4))
            gaps.append(low - high)
        out[leg] = LegCalibration(tuple(thresholds), round(min(gaps) / 4, 4))
    return out


def write_sensing(path: str | Path, calibration: Mapping[str, LegCalibration]) -> None:
    """The sensing file: one line per leg, in a YAML subset :func:`read_sensing` reads."""
    lines = ["# waveguide thresholds per leg (gaitc calibrate; thesis section 3.4.2)", "legs:"]
    for leg, cal in calibration.items():
        th = ", ".join(f"{t:g}" for t in cal.thresholds)
        lines.append(f"  {leg}: {{thresholds: [{th}], hysteresis: {cal.hysteresis:g}}}")
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")


def read_sensing(path: str | Path) -> dict[str, LegCalibration]:
    """Read a sensing file written by :func:`write_sensing` (or by hand, in YAML); every
    error names the file and the position of the value at fault."""
    name, legs = keyed_section(path, CalibrationError, "sensing file", "legs",
                               "a sensing file maps 'legs' to thresholds")
    out = {}
    for leg, (key, value) in legs.items():
        fields = mapping_of(value)
        wrong = (f"leg {leg}: thresholds must be a descending list of finite numbers and "
                 "hysteresis a finite number >= 0")
        listed = None if fields is None else fields.get("thresholds")
        if fields is None or listed is None or not isinstance(listed[1], yaml.SequenceNode) \
                or not listed[1].value:
            raise CalibrationError(wrong, node_span(name, value if fields is None else key))
        thresholds = []
        for item in listed[1].value:
            number = finite_number(item)
            if number is None:
                raise CalibrationError(wrong, node_span(name, item))
            thresholds.append(number)
        margin = DEFAULT_HYSTERESIS
        if "hysteresis" in fields:
            found = finite_number(fields["hysteresis"][1])
            if found is None or found < 0:
                raise CalibrationError(wrong, node_span(name, fields["hysteresis"][1]))
            margin = found
        if any(a <= b for a, b in itertools.pairwise(thresholds)):
            raise CalibrationError(wrong, node_span(name, listed[1]))
        out[leg] = LegCalibration(tuple(thresholds), margin, node_span(name, key))
    return out


def _where(what: str) -> Span:
    return Span(f"<{what}>", 1, 1)
