"""Fitting a robot to its measurements: ``characterize`` (a limb's spring-damper parameters,
thesis 4.2.1) and ``calibrate`` (the waveguide thresholds of each leg's health levels,
thesis 3.4.2).

Both read CSV recordings, fit, and return a result that prints the fits, shows itself in a
notebook and writes its file on request: the robot file's ``model: spring_damper:`` section
(checked to read back before it replaces the file), or the sensing file ``gaitc drive
--sensing`` reads.
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.diagnostics import UsageError
from gaitc.hw.sensing import calibrate as fit
from gaitc.hw.sensing import read_cycles, write_sensing
from gaitc.models.characterization import fit_curvature, fit_damping, fit_stiffness
from gaitc.models.robot_edit import matrix, number, write_fields
from gaitc.models.spring_damper.description import load_spring_damper

if TYPE_CHECKING:
    from gaitc.hw.sensing import Cycle, LegCalibration


@dataclass(frozen=True)
class Recordings:
    """The CSV files of one limb: ``curvature`` (time,curvature: a segment's step response),
    ``stiffness`` (state,dx,dy,dz,fx,fy,fz: deflection and force per valve pattern) and
    ``damping`` (time,displacement: a known ``mass`` in grams hung on the end effector and
    released, with the stiffness ``spring`` in N/mm, else the fitted or known z-z one)."""

    curvature: str | Path | None = None
    stiffness: str | Path | None = None
    damping: str | Path | None = None
    mass: float | None = None
    spring: float | None = None


@dataclass(frozen=True)
class Characterization:
    """The fitted fields of one limb (as robot-file text) and a line per fit."""

    robot: str
    limb: str
    fields: dict[str, str]
    lines: tuple[str, ...]

    def __str__(self) -> str:
        return "\n".join(self.lines)

    def _repr_html_(self) -> str:
        return (f"<b>limb {html.escape(self.limb)} of {html.escape(self.robot)}</b>"
                f"<pre>{html.escape(str(self))}</pre>")

    def to_json(self) -> dict[str, Any]:
        return {"robot": self.robot, "limb": self.limb, "fields": dict(self.fields),
                "fits": list(self.lines)}

    def write(self, out: str | Path | None = None) -> str:
        """Write the fields into the robot file's model section (``out``: a copy there
        instead); the file is replaced only if the result still reads. Returns the path."""
        target = str(out) if out is not None else self.robot
        write_fields(self.robot, self.limb, self.fields, target)
        return target


def characterize(robot: str | Path, limb: str, data: Recordings) -> Characterization:
    """Fit the second-order curvature model, the stiffness matrices and the damping of
    ``limb`` of the robot file ``robot`` from ``data`` (thesis 4.2.1)."""
    if not (data.curvature or data.stiffness or data.damping):
        raise UsageError("give at least one of --curvature, --stiffness and --damping")
    if data.damping and data.mass is None:
        raise UsageError("--damping needs --mass G, the mass hung on the end effector")
    described = load_spring_damper(str(robot))
    found = next((x for x in described.limbs if x.name == limb), None)
    if found is None:
        raise UsageError(f"robot {described.name} has no limb {limb!r} in its model section")
    fields: dict[str, str] = {}
    lines: list[str] = []
    if data.curvature:
        c = fit_curvature(str(data.curvature))
        fields["dynamics"] = (
            f"{{frequency: {number(c.frequency)}, damping_ratio: {number(c.damping_ratio)}}}")
        lines.append(
            f"curvature: {number(c.rest_curvature)} -> {number(c.curvature)} 1/mm, "
            f"frequency {number(c.frequency)} rad/s, damping ratio {number(c.damping_ratio)}, "
            f"RMS error {c.residual:.3g} 1/mm")
    spring = data.spring
    if data.stiffness:
        s = fit_stiffness(str(data.stiffness))
        want = {p for p, _ in found.stiffness if p}
        if not want and len(s.matrices) > 1:
            raise UsageError(
                f"{data.stiffness}: states {', '.join(sorted(s.matrices))}, but limb "
                f"{found.name} has one stiffness matrix for every state; give one state, or "
                "a matrix per valve pattern in the robot file")
        if want and set(s.matrices) != want:
            raise UsageError(
                f"{data.stiffness}: states {', '.join(sorted(s.matrices))}; limb "
                f"{found.name} needs {', '.join(sorted(want))}")
        entries = ", ".join(f'"{p}": {matrix(m)}' for p, m in sorted(s.matrices.items()))
        fields["stiffness"] = (
            "{" + entries + "}" if want else matrix(next(iter(s.matrices.values()))))
        for p, fitted in sorted(s.matrices.items()):
            lines.append(f"stiffness {p}: {matrix(fitted)} N/mm, RMS error "
                         f"{s.residual[p]:.3g} N")
        vented = s.matrices.get("0" * len(found.segments)) or next(iter(s.matrices.values()))
        spring = spring if spring is not None else vented[2][2]
    if data.damping:
        assert data.mass is not None
        if spring is None:
            table = dict(found.stiffness)
            known = table.get("0" * len(found.segments)) or next(iter(table.values()))
            spring = known[2][2] / 1000.0
        d = fit_damping(str(data.damping), data.mass, spring)
        fields["damping"] = number(d.damping)
        lines.append(
            f"damping: {number(d.damping)} N*s/mm (damping ratio {d.damping_ratio:.3g} with "
            f"{number(spring)} N/mm and {number(data.mass)} g), RMS error {d.residual:.3g} mm")
    return Characterization(str(robot), found.name, fields, tuple(lines))


@dataclass(frozen=True)
class Calibrated:
    """Each leg's health thresholds (top level first) and hysteresis, from recorded cycles."""

    source: str
    cycles: tuple[Cycle, ...]
    calibration: dict[str, LegCalibration]

    def __str__(self) -> str:
        lines = [f"{'leg':<6} {'cycles':>6} {'levels':>6}  thresholds (top level first)  "
                 "hysteresis"]
        for leg, cal in self.calibration.items():
            count = sum(c.leg == leg for c in self.cycles)
            th = ", ".join(f"{t:.4f}" for t in cal.thresholds)
            lines.append(f"{leg:<6} {count:>6} {cal.levels:>6}  {th:<28} "
                         f"{cal.hysteresis:.4f}")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        return f"<pre>{html.escape(str(self))}</pre>"

    def to_json(self) -> dict[str, Any]:
        return {"source": self.source, "legs": {
            leg: {"levels": cal.levels, "thresholds": list(cal.thresholds),
                  "hysteresis": cal.hysteresis,
                  "cycles": sum(c.leg == leg for c in self.cycles)}
            for leg, cal in self.calibration.items()}}

    def write(self, out: str | Path | None = None) -> str:
        """Write the sensing file (default: the CSV's name with ``.sensing.yaml``)."""
        target = str(out) if out is not None else str(
            Path(self.source).with_suffix(".sensing.yaml"))
        write_sensing(target, self.calibration)
        return target


def calibrate(cycles: str | Path) -> Calibrated:
    """Calibrate each leg's waveguide thresholds, with hysteresis, from the CSV of recorded
    actuation cycles of known health level ``cycles`` (thesis 3.4.2)."""
    recorded = read_cycles(str(cycles))
    return Calibrated(str(cycles), tuple(recorded), fit(recorded))
