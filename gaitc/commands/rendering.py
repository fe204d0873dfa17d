"""The ``render`` commands: draw a controller automaton, the region map (with a run) or the
spec's region graph and gait map, with pydot and Graphviz (see :mod:`gaitsim.graphics`).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

import gaitc
from diagnostics import UsageError
from gaitc.commands.arguments import add_prefer
from gaitc.exitcodes import ExitCode
from gaitsim.graphics import FORMATS, Picture, output_format

FORMAT_HELP = (f"output format: {', '.join(FORMATS)} (default: from the -o extension); every "
               "format but dot needs Graphviz's 'dot' program")


def _output(p: argparse.ArgumentParser) -> None:
    p.add_argument("-o", "--output", required=True, metavar="FILE")
    p.add_argument("--format", choices=FORMATS, help=FORMAT_HELP)


def register(sub: Any) -> None:
    render = sub.add_parser("render", help="draw automata, maps and runs",
                            description="Draw with Graphviz: a controller automaton, the map "
                            "(optionally with a simulated run), or a spec's regions and gaits.")
    what = render.add_subparsers(dest="what", metavar="WHAT", parser_class=type(render))

    p = what.add_parser("automaton", help="a controller as a graph",
                        description="Nodes show region, gait and the goal pursued; edges the "
                        "environment's inputs (health changes, hazards); initial nodes have a "
                        "double border. Above --max-nodes the quotient by region and gait (or "
                        "by region) is drawn and the merges are listed.")
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("controller", metavar="CONTROLLER", nargs="?",
                   help="controller JSON (default: synthesize one)")
    p.add_argument("--quotient", choices=("none", "region-gait", "region"),
                   help="merge nodes with the same region and gait, or region (default: "
                   "automatic above --max-nodes)")
    p.add_argument("--max-nodes", type=int, default=40, metavar="N",
                   help="size above which a quotient is drawn (default 40)")
    p.add_argument("--encoding", choices=("onehot", "binary"))
    add_prefer(p, "without CONTROLLER: ")
    _output(p)
    p.set_defaults(run=run_automaton)

    p = what.add_parser("map", help="the region map, optionally with a run",
                        description="Regions with caches, hazard sets, goals and start; with "
                        "--run the path with step numbers (✗ a leg fails, ↓ degrades) and the "
                        "leg-health timeline.")
    p.add_argument("spec", metavar="SPEC")
    p.add_argument("--run", dest="run_file", metavar="RUN.jsonl",
                   help="a run saved by 'gaitc simulate --out'")
    p.add_argument("--max-steps", type=int, default=30, metavar="N",
                   help="draw the first N steps of the run (default 30)")
    _output(p)
    p.set_defaults(run=run_map)

    p = what.add_parser("spec", help="a spec's region graph and gait map (no controller)")
    p.add_argument("spec", metavar="SPEC")
    _output(p)
    p.set_defaults(run=run_spec)

    from gaitc.commands.gaits import run_render, search_arguments

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


def _model(path: str) -> Any:
    loaded = gaitc.load(path)
    if loaded.model is None:
        raise UsageError(f"'{path}': maps need a .gait spec")
    return loaded.model


def run_automaton(args: argparse.Namespace) -> int:
    from gaitsim.automaton_view import automaton_view
    from gaitsim.strategy import explicit

    output_format(args.output, args.format)  # fail on a bad format before synthesizing
    if args.max_nodes < 1:
        raise UsageError("--max-nodes must be at least 1")
    loaded = gaitc.session(args.spec, args.controller, args.encoding, prefer=args.prefer)
    if loaded is None:
        print(f"{args.spec}: unrealizable: no controller to draw", file=sys.stderr)
        return ExitCode.UNREALIZABLE
    strategy = explicit(loaded.strategy, "drawing the automaton")
    view = automaton_view(strategy, loaded.domain, args.quotient, args.max_nodes)
    if args.quotient == "none" and len(loaded.strategy) > args.max_nodes:
        print(f"gaitc: the automaton has {len(loaded.strategy)} nodes; --quotient region-gait "
              "or --quotient region draws a smaller picture", file=sys.stderr)
    return _save(view, args)


def run_map(args: argparse.Namespace) -> int:
    from gaitsim.map_view import map_view
    from gaitsim.run import read_jsonl

    output_format(args.output, args.format)
    model = _model(args.spec)
    run = None
    if args.run_file is not None:
        run = read_jsonl(args.run_file)
        _check_run(run, model, args.run_file)
    return _save(map_view(model, run, args.max_steps), args)


def _check_run(run: Any, model: Any, path: str) -> None:
    from diagnostics import ScenarioError, Span

    regions = {r.name for r in model.regions}
    legs = {leg.name for leg in model.legs}
    for step in run.steps:
        if step.region not in regions or not {leg for leg, _ in step.health} <= legs:
            raise ScenarioError(f"this run does not belong to '{model.file or 'the spec'}': "
                                f"step {step.index} is in region '{step.region}'",
                                Span(path, 1, 1))


def run_spec(args: argparse.Namespace) -> int:
    from gaitsim.map_view import spec_view

    output_format(args.output, args.format)
    return _save(spec_view(_model(args.spec)), args)
