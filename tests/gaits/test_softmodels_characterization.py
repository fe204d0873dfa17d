"""Characterization (thesis 4.2.1) recovers known parameters from noisy generated data."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
from recordings import ONE_LEG, curvature_csv, damping_csv

from gaitc.cli import main
from gaitc.models.characterization import (
    CharacterizationError,
    fit_curvature,
    fit_damping,
    fit_stiffness,
)
from gaitc.models.spring_damper.description import load_spring_damper


def _stiffness_csv(path: Path, seed: int = 2) -> tuple[Path, dict[str, np.ndarray]]:
    rng = np.random.default_rng(seed)
    truth = {
        "0": np.array([[0.12, 0.01, 0.0], [0.01, 0.08, 0.0], [0.0, 0.0, 0.15]]),
        "1": np.array([[0.20, 0.0, 0.02], [0.0, 0.12, 0.0], [0.02, 0.0, 0.25]]),
    }
    lines = ["state,dx,dy,dz,fx,fy,fz"]
    for state, k in truth.items():
        for size in (2.0, 5.0, 10.0):  # small, medium and large deflections (figure 4.7)
            for _ in range(20):
                d = rng.normal(0, size, 3)
                f = k @ d + rng.normal(0, 0.01, 3)
                lines.append(state + "," + ",".join(f"{v:.5f}" for v in (*d, *f)))
    path.write_text("\n".join(lines) + "\n")
    return path, truth




def test_curvature_fit_recovers_the_second_order_model(tmp_path: Path) -> None:
    fit = fit_curvature(curvature_csv(tmp_path / "step.csv"))
    assert fit.rest_curvature == pytest.approx(0.022, abs=3e-4)
    assert fit.curvature == pytest.approx(0.008, abs=1e-4)
    assert fit.frequency == pytest.approx(11.0, rel=0.03)
    assert fit.damping_ratio == pytest.approx(0.75, rel=0.05)
    assert fit.residual < 0.0003


def test_stiffness_fit_recovers_each_steady_state_matrix(tmp_path: Path) -> None:
    path, truth = _stiffness_csv(tmp_path / "fd.csv")
    fit = fit_stiffness(path)
    assert sorted(fit.matrices) == ["0", "1"]
    for state, k in truth.items():
        assert np.abs(np.array(fit.matrices[state]) - k).max() < 0.005  # N/mm
        assert fit.residual[state] < 0.02


def test_damping_fit_recovers_b(tmp_path: Path) -> None:
    path = damping_csv(tmp_path / "mass.csv", b=0.0015, mass=50.0, k=0.15)
    fit = fit_damping(path, 50.0, 0.15)
    assert fit.damping == pytest.approx(0.0015, rel=0.05)


def test_a_malformed_csv_is_a_positioned_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("time,curvature\n0,0.02\n0.1,0.019\n0.2,oops\n0.3,0.01\n0.4,0.01\n")
    with pytest.raises(CharacterizationError) as info:
        fit_curvature(bad)
    assert str(info.value) == f"{bad}:4:5: 'oops' is not a finite number"
    bad.write_text("t,k\n")
    with pytest.raises(CharacterizationError) as info:
        fit_curvature(bad)
    assert str(info.value) == f"{bad}:1:1: {bad} must start with the header time,curvature"


def test_characterize_writes_the_fitted_values_into_the_robot_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    robot = tmp_path / "one_leg.yaml"
    shutil.copy(ONE_LEG, robot)
    step = curvature_csv(tmp_path / "step.csv")
    fd, truth = _stiffness_csv(tmp_path / "fd.csv")
    mass = damping_csv(tmp_path / "mass.csv", b=0.002, mass=50.0, k=0.15)
    code = main(
        [
            "characterize",
            str(robot),
            "L1",
            "--curvature",
            str(step),
            "--stiffness",
            str(fd),
            "--damping",
            str(mass),
            "--mass",
            "50",
        ]
    )
    out = capsys.readouterr().out
    assert code == 0, out
    assert f"wrote dynamics, stiffness, damping of limb L1 to {robot}" in out
    limb = load_spring_damper(robot).limbs[0]
    assert limb.dynamics.frequency == pytest.approx(11.0, rel=0.03)
    assert limb.damping == pytest.approx(2.0, rel=0.05)  # N·s/m
    assert np.abs(np.array(dict(limb.stiffness)["1"]) / 1000 - truth["1"]).max() < 0.005
    text = robot.read_text()
    assert text.startswith("# A one-leg test robot")  # comments and layout are kept
    assert "skid_left" in text and text.count("damping:") == 3


def test_a_fitted_value_is_added_to_a_limb_that_took_the_defaults(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    robot = tmp_path / "radial8.yaml"
    shutil.copy(ONE_LEG.parents[3] / "specs" / "robots" / "radial8.yaml", robot)
    mass = damping_csv(tmp_path / "mass.csv", b=0.003, mass=40.0, k=0.15)
    assert main(["characterize", str(robot), "L3", "--damping", str(mass), "--mass", "40"]) == 0
    assert "      - {name: L3, damping: 0.00" in robot.read_text()
    limbs = {x.name: x for x in load_spring_damper(robot).limbs}
    assert limbs["L3"].damping == pytest.approx(3.0, rel=0.05)
    assert limbs["L4"].damping == pytest.approx(1.5)
    capsys.readouterr()
