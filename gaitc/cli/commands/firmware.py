"""The ``firmware`` commands: build the valve-board firmware, run it in the simulator.

The work lives in :mod:`gaitc.hw.firmware`; ``simulate`` builds the image into a temporary
folder and runs the harness in the foreground (its first output line is the pty path)
until it is killed.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from typing import Any

from gaitc.cli.exitcodes import ExitCode, exit_code_help
from gaitc.diagnostics import UsageError

EPILOG = """examples:
  gaitc firmware build -o build/          gaitboard.elf, gaitboard.hex, gaitboard-sim
  gaitc firmware simulate --record pins.jsonl
  gaitc drive specs/radial8_patrol.gait --backend serial --port /dev/pts/N

"""


def register(sub: Any) -> None:
    p = sub.add_parser("firmware", help="build the valve-board firmware or simulate it",
                       description="Build the gaitboard firmware (ATmega328P, protocol v2) "
                       "or run it in the simavr harness as a board for 'gaitc drive'.",
                       epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    actions = p.add_subparsers(dest="action", metavar="ACTION", parser_class=type(p))
    b = actions.add_parser("build", help="build the firmware image and the simulator",
                           epilog=exit_code_help({ExitCode.USER: "the toolchain is missing "
                                                  "or a compiler failed"},
                                                 codes=(ExitCode.OK, ExitCode.USER,
                                                        ExitCode.USAGE)),
                           formatter_class=argparse.RawDescriptionHelpFormatter)
    b.add_argument("-o", "--out", metavar="DIR", default="firmware-build",
                   help="output folder (firmware-build)")
    b.add_argument("--no-simulator", action="store_true",
                   help="build only the image (no libsimavr needed)")
    b.set_defaults(run=run_build)
    s = actions.add_parser("simulate", help="run the firmware in simavr; prints the pty path",
                           description="Run the real firmware image in the simavr harness, in "
                           "real time. The first line printed is the board's serial port (a "
                           "pty); standard input takes 'adc CH MV', 'contact I 0|1' and "
                           "'time'. Runs until killed.",
                           formatter_class=argparse.RawDescriptionHelpFormatter)
    s.add_argument("--record", metavar="FILE",
                   help="write every valve pin change as a JSON line {t_ms, valves}")
    s.add_argument("--watchdog-ms", type=int, metavar="N",
                   help="the board's watchdog period (50..10000; firmware default 500)")
    s.add_argument("--adc", type=int, metavar="MV",
                   help="initial millivolts on every waveguide input (4000)")
    s.set_defaults(run=run_simulate)
    p.set_defaults(run=lambda args: _no_action(p))


def _no_action(parser: argparse.ArgumentParser) -> int:
    parser.print_help(sys.stderr)
    return ExitCode.USAGE


def run_build(args: argparse.Namespace) -> int:
    from gaitc.api.firmware import build

    image = build(args.out, simulator=not args.no_simulator)
    for path in (image.elf, image.hex, image.simulator):
        if path is not None:
            print(path)
    return ExitCode.OK


def run_simulate(args: argparse.Namespace) -> int:
    from gaitc.api.firmware import build, simulator_argv

    if args.watchdog_ms is not None and not 50 <= args.watchdog_ms <= 10000:
        raise UsageError("--watchdog-ms must be within 50..10000")
    if args.adc is not None and not 0 <= args.adc <= 5000:
        raise UsageError("--adc must be within 0..5000 millivolts")
    with tempfile.TemporaryDirectory(prefix="gaitboard-") as folder:
        image = build(folder)
        argv = simulator_argv(image, args.record, args.watchdog_ms, args.adc)
        sys.stdout.flush()
        child = subprocess.Popen(argv, preexec_fn=_die_with_parent)
        try:
            return child.wait()
        finally:
            if child.poll() is None:
                child.terminate()
                child.wait()


def _die_with_parent() -> None:
    """In the harness's child process: let the kernel end it when gaitc dies (Linux)."""
    import contextlib
    import ctypes
    import signal

    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None).prctl(1, int(signal.SIGTERM))  # PR_SET_PDEATHSIG
