"""The ``calibrate`` command: waveguide thresholds per leg from recorded cycles (thesis 3.4.2).

The work lives in :func:`gaitc.calibrate` (:mod:`gaitc.api.characterizing`, over
:mod:`gaitc.hw.sensing`); this module writes the sensing file that ``gaitc drive --sensing``
reads and prints each leg's thresholds.
"""

from __future__ import annotations

import argparse
from typing import Any

from gaitc.cli.commands.arguments import output_file
from gaitc.cli.exitcodes import ExitCode, exit_code_help

EPILOG = """LEGS.csv has the header leg,cycle,level,intensity and one row per sample of a
recorded actuation cycle, in time order: the leg, a name for the cycle, the health level
the actuator is known to have in it (1 = inoperable) and the waveguide intensity (e.g. the
board's ADC value).  The first samples of each cycle must be at rest.

"""
EPILOG += exit_code_help({ExitCode.USER: "the CSV is malformed, a level is missing or two "
                          "levels of a leg overlap"},
                         codes=(ExitCode.OK, ExitCode.USER, ExitCode.USAGE))


def register(sub: Any) -> None:
    p = sub.add_parser("calibrate", help="waveguide health thresholds from recorded cycles",
                       description="Calibrate each leg's curvature thresholds from recorded "
                       "actuation cycles of known health level, with hysteresis, and write "
                       "them for 'gaitc drive --backend serial --sensing FILE'.",
                       epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("cycles", metavar="LEGS.csv")
    p.add_argument("-o", "--out", metavar="FILE", type=output_file,
                   help="sensing file to write (default: LEGS.sensing.yaml)")
    p.set_defaults(run=run_calibrate)


def run_calibrate(args: argparse.Namespace) -> int:
    import gaitc

    calibrated = gaitc.calibrate(args.cycles)
    out = calibrated.write(args.out)
    print(calibrated)
    print(f"wrote {out}")
    return ExitCode.OK
