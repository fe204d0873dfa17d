"""The ``render`` commands: draw a controller automaton (whole, or its first steps), the
controller projected on the map (``render policy``), the region map (with a run) or the
spec's region graph and gait map, with pydot and Graphviz (see :mod:`gaitc.sim.graphics`).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gaitc
from gaitc.api.drawing import (
    FORMATS,
    Picture,
    compact_rules,
    draw_policy,
    draw_rules,
    output_format,
)
from gaitc.api.modes import EncodingName
from gaitc.cli.commands.arguments import add_prefer, output_file, positive_count
from gaitc.cli.exitcodes import ExitCode
from gaitc.cli.status import progress_display
from gaitc.diagnostics import UsageError

FORMAT_HELP = (f"output format: {', '.join(FORMATS)} (default: from the -o extension); every "
               "format but dot needs Graphviz's 'dot' program")


TABLE_FORMATS = ("text", "md", "html", "json")
_TABLE_SUFFIXES = {".txt": "text", ".text": "text", ".md": "md", ".html": "html",
                   ".htm": "html", ".json": "json"}


def _output(p: argparse.ArgumentParser) -> None:
    p.add_argument("-o", "--output", required=True, metavar="FILE", type=output_file)
    p.add_argument("--format", choices=FORMATS, help=FORMAT_HELP)


def register(sub: Any) -> None:
    render = sub.add_parser("render", help="draw automata, maps and runs",
                            description="Draw with Graphviz: a controller automaton (or its "
                            "first steps), the controller projected on the map (policy), the "
                            "map (optionally with a simulated run), or a spec's regions and "
                            "gaits.")
    what = render.add_subparsers(dest="what", metavar="WHAT", parser_class=type(render))

    p = what.add_parser("automaton", help="a controller as a graph",
                        description="Nodes show region, gait and the goal pursued; edges the "
                        "environment's inputs (health changes, hazards); initial nodes have a "
                        "double border. Above --max-nodes the quotient by region and gait (or "
                        "by region) is drawn and the merges are listed. --steps K draws only "
                        "the nodes within K moves of the initial nodes (at most --max-nodes "
                        "of them), symbolic controllers too, and says what it cut.")
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?",
                   help="controller JSON (default: synthesize one)")
    p.add_argument("--quotient", choices=("none", "region-gait", "region"),
                   help="merge nodes with the same region and gait, or region (default: "
                   "automatic above --max-nodes)")
    p.add_argument("--max-nodes", type=int, default=40, metavar="N",
                   help="size above which a quotient is drawn; with --steps, the most nodes "
                   "drawn (default 40)")
    p.add_argument("--steps", type=int, metavar="K",
                   help="draw only the first K steps from the initial nodes (breadth first; "
                   "K = 3 is a good start)")
    p.add_argument("--encoding", choices=EncodingName.values())
    add_prefer(p, "without CONTROLLER: ")
    _output(p)
    p.set_defaults(run=run_automaton)

    p = what.add_parser("policy", help="the controller projected on the map: per region, "
                        "which gait under which condition",
                        description="For each region, the rules the controller follows: "
                        "under which goal, active hazard and leg health (healthy, degraded, "
                        "failed) it walks which gait into which region, with the number of "
                        "controller moves each covers. Without -o a text table is printed; "
                        "-o FILE.txt/.md/.html writes the table, .svg/.png/.pdf/.dot draws "
                        "one table per region with arrows for its moves (in rows when the "
                        "map would be too wide to read). A symbolic controller is projected "
                        "from the nodes within --steps moves of the start (default 10), as is "
                        "an explicit one when --steps is given. A compact controller (or "
                        "--compact) gives one table of rules per goal, only the rules some "
                        "state a run reaches uses (the others are counted; --all-rules lists "
                        "them marked 'never used', as .json always does); a picture of it "
                        "stacks one table per goal.")
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?",
                   help="controller JSON (default: synthesize one)")
    p.add_argument("--steps", type=int, metavar="K",
                   help="project only the nodes within K moves of the start (default: every "
                   "node; symbolic controllers: 10)")
    p.add_argument("--max-nodes", type=int, default=2000, metavar="N",
                   help="with a bounded search, stop after N nodes (default 2000)")
    p.add_argument("--max-rules", type=int, metavar="N",
                   help="at most N rules per region: the most mixed conditions stay joined, "
                   "marked ~, listing every move they cover (default: exact rules)")
    p.add_argument("--compact", action="store_true",
                   help="the compact controller whole: one table of rules per goal, every "
                   "state covered (a compact or symbolic CONTROLLER, or one synthesized); "
                   "the default for a compact CONTROLLER")
    p.add_argument("--all-rules", action="store_true",
                   help="with a compact controller: list the rules no state a run reaches "
                   "uses too, marked 'never used' (default: leave them out and count them)")
    p.add_argument("--encoding", choices=EncodingName.values())
    add_prefer(p, "without CONTROLLER: ")
    p.add_argument("-o", "--output", metavar="FILE", type=output_file,
                   help="write the table or picture here (default: print the table)")
    p.add_argument("--format", choices=TABLE_FORMATS + FORMATS,
                   help="text, md, html, json (compact controllers), or a picture format "
                   "(default: from the -o extension; pictures other than dot need Graphviz)")
    p.set_defaults(run=run_policy)

    p = what.add_parser("map", help="the region map, optionally with a run",
                        description="Regions with caches, hazard sets, goals and start; with "
                        "--run the path with step numbers (✗ a leg fails, ↓ degrades) and the "
                        "leg-health timeline.")
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("--run", dest="run_file", metavar="RUN.jsonl",
                   help="a run saved by 'gaitc simulate --out'")
    p.add_argument("--max-steps", type=positive_count, default=30, metavar="N",
                   help="draw the first N steps of the run (default 30)")
    _output(p)
    p.set_defaults(run=run_map)

    p = what.add_parser("spec", help="a spec's region graph and gait map (no controller)")
    p.add_argument("spec", metavar="SPEC")
    _output(p)
    p.set_defaults(run=run_spec)

    from gaitc.cli.commands.gaits import run_render, search_arguments

    p = what.add_parser("gaits", help="a robot's gait graph and the poses of its gaits (SVG)",
                        description="Search gaits for ROBOT.yaml as 'gaitc gaits' does, then "
                        "write the gait graph around each gait and a top view of every pose "
                        "(legs, contacts, contact polygon, centre of gravity) into DIR.")
    search_arguments(p)
    p.add_argument("-o", "--output", dest="output_dir", required=True, metavar="DIR",
                   help="folder for the SVG files")
    p.set_defaults(run=run_render)


def _save(picture: Picture, args: argparse.Namespace) -> int:
    fmt = output_format(args.output, args.format)
    picture.save(args.output, fmt)
    for note in picture.notes:
        print(f"gaitc: {note}", file=sys.stderr)
    print(f"wrote {args.output} ({fmt})", file=sys.stderr)
    return ExitCode.OK


def _unrealizable(args: argparse.Namespace, what: str) -> int:
    print(f"{args.spec}: unrealizable: no controller to {what}", file=sys.stderr)
    return ExitCode.UNREALIZABLE


def run_automaton(args: argparse.Namespace) -> int:
    output_format(args.output, args.format)  # fail on a bad format before synthesizing
    with progress_display() as progress:
        picture = gaitc.draw_automaton(
            args.spec, args.controller, quotient=args.quotient, steps=args.steps,
            max_nodes=args.max_nodes, encoding=args.encoding, prefer=args.prefer,
            progress=progress)
    return _unrealizable(args, "draw") if picture is None else _save(picture, args)


def _policy_format(path: str | None, fmt: str | None) -> str:
    if fmt is not None:
        return fmt
    if path is None:
        return "text"
    from pathlib import Path

    found = _TABLE_SUFFIXES.get(Path(path).suffix.lower())
    return found if found is not None else output_format(path)


def run_policy(args: argparse.Namespace) -> int:
    fmt = _policy_format(args.output, args.format)  # fail on a bad format before synthesizing
    if args.output is None and fmt not in TABLE_FORMATS:
        raise UsageError(f"--format {fmt} draws a picture: give -o FILE")
    if args.compact or _is_compact_file(args.controller):
        tables = compact_rules(args.spec, args.controller, all_rules=args.all_rules,
                               prefer=args.prefer)
        if tables is None:
            return _unrealizable(args, "tabulate")
        if fmt not in TABLE_FORMATS:
            return _save(draw_rules(tables), args)
        return _write_table({"text": tables.text, "md": tables.markdown, "html": tables.html,
                             "json": tables.json}[fmt](), fmt, args)
    if fmt == "json" or args.all_rules:
        what = "--format json writes" if fmt == "json" else "--all-rules lists"
        raise UsageError(f"{what} a compact controller's rules: give a compact CONTROLLER "
                         "or --compact")
    with progress_display() as progress:
        found = gaitc.controller_policy(
            args.spec, args.controller, steps=args.steps, max_nodes=args.max_nodes,
            max_rules=args.max_rules, encoding=args.encoding, prefer=args.prefer,
            progress=progress)
    if found is None:
        return _unrealizable(args, "project")
    policy, bound = found
    if fmt not in TABLE_FORMATS:
        return _save(draw_policy(policy, bound), args)
    text = {"text": policy.text, "md": policy.markdown, "html": policy.html}[fmt]()
    return _write_table(text, fmt, args)


def _is_compact_file(path: str | None) -> bool:
    if path is None:
        return False
    from gaitc.api.modes import Form
    from gaitc.api.solving import controller_form

    return controller_form(path) == Form.COMPACT


def _write_table(text: str, fmt: str, args: argparse.Namespace) -> int:
    from gaitc.diagnostics.files import write_atomically

    if args.output is None:
        sys.stdout.write(text)
        return ExitCode.OK
    write_atomically(args.output, text.encode("utf-8"))
    print(f"wrote {args.output} ({fmt})", file=sys.stderr)
    return ExitCode.OK


def run_map(args: argparse.Namespace) -> int:
    output_format(args.output, args.format)
    return _save(gaitc.draw_map(args.spec, args.run_file, args.max_steps), args)


def run_spec(args: argparse.Namespace) -> int:
    output_format(args.output, args.format)
    return _save(gaitc.draw_spec(args.spec), args)
