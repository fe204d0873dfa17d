"""The ``characterize`` command: fit spring-damper parameters and write them (thesis 4.2.1).

The fits live in :mod:`gaitc.models.characterization`, the file edit in
:mod:`gaitc.models.robot_edit`; this module reads the options, prints each fit and writes
the robot file (atomically, after checking that it still reads).
"""

from __future__ import annotations

import argparse
from typing import Any

from gaitc.cli.commands.arguments import output_file
from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.diagnostics import UsageError

EPILOG = """CSV files (a header row, then one row per sample):
  --curvature FILE   time,curvature          s, 1/mm: a segment's response to a valve step
  --stiffness FILE   state,dx,dy,dz,fx,fy,fz valve pattern of the limb's segments, the end
                     effector's deflection (mm, limb frame) and the force (N) on it
  --damping FILE     time,displacement       s, mm: a known --mass (g) hung on the end
                     effector, released at the first row (stiffness: --spring, else the
                     limb's vented z-z stiffness)

"""
EPILOG += exit_code_help(
    {ExitCode.USER: "a CSV or the robot file is malformed, or the data cannot be fitted"},
    codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE),
)


def register(sub: Any) -> None:
    p = sub.add_parser(
        "characterize",
        help="fit a limb's spring-damper parameters from recorded data (thesis 4.2.1)",
        description="Fit the second-order curvature model, the stiffness matrices and the "
        "damping of one limb of ROBOT.yaml from CSV recordings, and write the fitted values "
        "into the robot file's 'model: spring_damper:' section.",
        epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("robot", metavar="ROBOT.yaml")
    p.add_argument("limb", metavar="LIMB")
    p.add_argument("--curvature", metavar="FILE", help="curvature step response (time,curvature)")
    p.add_argument("--stiffness", metavar="FILE", help="force/deflection data per steady state")
    p.add_argument("--damping", metavar="FILE", help="mass step response (time,displacement)")
    p.add_argument("--mass", type=float, metavar="G", help="--damping: the mass hung, grams")
    p.add_argument("--spring", type=float, metavar="N/mm", help="--damping: the stiffness")
    p.add_argument("-o", "--out", metavar="FILE", type=output_file,
                   help="write here instead of ROBOT.yaml")
    p.set_defaults(run=run_characterize)


def run_characterize(args: argparse.Namespace) -> int:
    from gaitc.models.characterization import fit_curvature, fit_damping, fit_stiffness
    from gaitc.models.description import load_spring_damper
    from gaitc.models.robot_edit import matrix, number, write_fields

    if not (args.curvature or args.stiffness or args.damping):
        raise UsageError("give at least one of --curvature, --stiffness and --damping")
    if args.damping and args.mass is None:
        raise UsageError("--damping needs --mass G, the mass hung on the end effector")
    robot = load_spring_damper(args.robot)
    limb = next((x for x in robot.limbs if x.name == args.limb), None)
    if limb is None:
        raise UsageError(f"robot {robot.name} has no limb {args.limb!r} in its model section")
    fields: dict[str, str] = {}
    if args.curvature:
        c = fit_curvature(args.curvature)
        fields["dynamics"] = (
            f"{{frequency: {number(c.frequency)}, damping_ratio: {number(c.damping_ratio)}}}"
        )
        print(
            f"curvature: {number(c.rest_curvature)} -> {number(c.curvature)} 1/mm, "
            f"frequency {number(c.frequency)} rad/s, damping ratio {number(c.damping_ratio)}, "
            f"RMS error {c.residual:.3g} 1/mm"
        )
    spring = args.spring
    if args.stiffness:
        s = fit_stiffness(args.stiffness)
        want = {p for p, _ in limb.stiffness if p}
        if not want and len(s.matrices) > 1:
            raise UsageError(
                f"{args.stiffness}: states {', '.join(sorted(s.matrices))}, but limb "
                f"{limb.name} has one stiffness matrix for every state; give one state, or "
                "a matrix per valve pattern in the robot file"
            )
        if want and set(s.matrices) != want:
            raise UsageError(
                f"{args.stiffness}: states {', '.join(sorted(s.matrices))}; limb "
                f"{limb.name} needs {', '.join(sorted(want))}"
            )
        entries = ", ".join(f'"{p}": {matrix(m)}' for p, m in sorted(s.matrices.items()))
        fields["stiffness"] = (
            "{" + entries + "}" if want else matrix(next(iter(s.matrices.values())))
        )
        for p, fitted in sorted(s.matrices.items()):
            print(f"stiffness {p}: {matrix(fitted)} N/mm, RMS error {s.residual[p]:.3g} N")
        vented = s.matrices.get("0" * len(limb.segments)) or next(iter(s.matrices.values()))
        spring = spring if spring is not None else vented[2][2]
    if args.damping:
        if spring is None:
            table = dict(limb.stiffness)
            known = table.get("0" * len(limb.segments)) or next(iter(table.values()))
            spring = known[2][2] / 1000.0
        d = fit_damping(args.damping, args.mass, spring)
        fields["damping"] = number(d.damping)
        print(
            f"damping: {number(d.damping)} N*s/mm (damping ratio {d.damping_ratio:.3g} with "
            f"{number(spring)} N/mm and {number(args.mass)} g), RMS error {d.residual:.3g} mm"
        )
    out = args.out or args.robot
    write_fields(args.robot, limb.name, fields, out)
    print(f"wrote {', '.join(fields)} of limb {limb.name} to {out}")
    return ExitCode.OK
