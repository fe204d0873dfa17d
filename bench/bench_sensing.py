"""Health classification from waveguide curves: confusion matrices and level flaps (issue 14).

Thresholds are calibrated (``gaitc.hw.sensing.calibrate``) on synthetic curves shaped like
thesis Figure 3.5 (nine cycles of a progressively damaged actuator: 1-5 healthy, 6-8
degraded, 9 inoperable; three legs, three repeats, sensor noise 12 counts on a rest value of
700-800), then fresh curves of known level are classified at rising noise.  The flap count
is the number of level changes over 200 cycles of an actuator whose dip sits on the
healthy/degraded threshold, ±0.02 from cycle to cycle, with the calibrated hysteresis and
without it.  Deterministic.  Run: ``.venv/bin/python bench/bench_sensing.py``.
"""

from __future__ import annotations

import itertools
import sys

from gaitc.hw.sensing import (
    HealthSensing,
    LegCalibration,
    calibrate,
    confusion,
    curve_feature,
    figure_3_5_cycles,
    synthetic_cycle,
)

LEGS = ("L1", "L2", "L3")
NOISE = (12.0, 30.0, 60.0, 100.0)


def flaps(calibration: LegCalibration, cycles: int = 200) -> int:
    sensing = HealthSensing({"L1": 3}, {"L1": calibration})
    levels = []
    for i in range(cycles):
        depth = calibration.thresholds[0] + ((i * 37) % 11 - 5) / 250
        low = 700.0 * (1 - curve_feature(synthetic_cycle(depth, 700.0, 12.0, 5000 + i), 700.0))
        levels.append(sensing.update({"L1": 700.0}, {"L1": low}, ("L1",), False)["L1"])
    return sum(a != b for a, b in itertools.pairwise(levels))


def main() -> int:
    calibration = calibrate(figure_3_5_cycles(LEGS, seed=1, noise=12.0))
    print("calibrated thresholds (healthy|degraded, degraded|inoperable) and hysteresis:")
    for leg, cal in calibration.items():
        print(f"  {leg}: {cal.thresholds[0]:.4f}, {cal.thresholds[1]:.4f}  "
              f"hysteresis {cal.hysteresis:.4f}")
    for noise in NOISE:
        matrix = confusion(calibration, figure_3_5_cycles(LEGS, seed=2, noise=noise))
        right = sum(matrix[i][i] for i in range(3))
        print(f"\nnoise {noise:g} counts: {right}/{sum(map(sum, matrix))} right")
        print("  true \\ sensed   3 healthy  2 degraded  1 inoperable")
        for name, row in zip(("3 healthy", "2 degraded", "1 inoperable"), matrix, strict=True):
            print(f"  {name:<14} {row[0]:>9} {row[1]:>11} {row[2]:>13}")
    cal = calibration["L1"]
    print(f"\nlevel flaps over 200 cycles on the threshold: {flaps(cal)} with hysteresis "
          f"{cal.hysteresis:.4f}, {flaps(LegCalibration(cal.thresholds, 0.0))} without")
    return 0


if __name__ == "__main__":
    sys.exit(main())
