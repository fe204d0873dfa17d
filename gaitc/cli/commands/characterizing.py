"""The ``characterize`` command: fit spring-damper parameters and write them (thesis 4.2.1).

The work lives in :func:`gaitc.characterize` (:mod:`gaitc.api.characterizing`); this module
reads the options, prints each fit and writes the robot file (atomically, after checking
that it still reads).
"""

from __future__ import annotations

import argparse
from typing import Any

from gaitc.cli.commands.arguments import output_file
from gaitc.cli.exitcodes import ExitCode, exit_code_help

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
    import gaitc
    from gaitc.api.characterizing import Recordings

    data = Recordings(args.curvature, args.stiffness, args.damping, args.mass, args.spring)
    fitted = gaitc.characterize(args.robot, args.limb, data)
    print(fitted)
    out = fitted.write(args.out)
    print(f"wrote {', '.join(fitted.fields)} of limb {fitted.limb} to {out}")
    return ExitCode.OK
