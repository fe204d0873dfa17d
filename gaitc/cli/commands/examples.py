"""The ``examples`` command: copy the example robots and specs shipped in the package.

The work lives in :func:`gaitc.copy_examples` (:mod:`gaitc.api.examples`).
"""

from __future__ import annotations

import argparse
import json
from typing import Any

from gaitc.cli.exitcodes import ExitCode, exit_code_help

EPILOG = """examples:
  gaitc examples my-robots
  gaitc synth my-robots/thesis_robot_a.gait -o robot_a.controller.json
  gaitc gaits my-robots/robots/radial8.yaml --direction +x

""" + exit_code_help({ExitCode.USAGE: "a file exists already (use --force) or the folder "
                      "cannot be written"}, codes=(ExitCode.OK, ExitCode.USAGE))


def register(sub: Any) -> None:
    p = sub.add_parser("examples", help="copy the example specs and robot files into a folder",
                       description="Copy the example .gait specs and robot files that come "
                       "with gaitc into FOLDER, to start from without a checkout.",
                       epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("folder", metavar="FOLDER", nargs="?", default="gaitc-examples",
                   help="where to copy them (gaitc-examples)")
    p.add_argument("--force", action="store_true", help="replace files that exist already")
    p.add_argument("--json", action="store_true", help="print the files copied as JSON")
    p.set_defaults(run=run_examples)


def run_examples(args: argparse.Namespace) -> int:
    from gaitc import copy_examples

    copied = copy_examples(args.folder, overwrite=args.force)
    print(json.dumps(copied.to_json(), indent=2) if args.json else copied)
    return ExitCode.OK
