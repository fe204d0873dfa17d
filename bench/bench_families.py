"""One benchmark table over every GR(1) family of issue 12, SLUGS side by side.

Families (bench/families/): the thesis robots and grids (4x5 to 30x30, health 2-5, both
encodings), AMBA AHB arbiters (N = 2..10, in an integer encoding and in the SYNTCOMP
generator's bit encoding), generalized buffers (GenBuf, 2 to 64 senders), the arbiter and
the lift of the first GR(1) paper (2 to 64 clients or floors), the SYNTCOMP safety games
(Cinderella-Stepmother, moving obstacle), the SLUGS examples, hazard grids, and the random
corpus as one row of totals. Columns: gaitc wall seconds (embedded solver,
default options, ``--timeout`` per instance), the verdict (``!`` marks a verdict that
differs from SLUGS's recorded or live one), SLUGS's seconds when $SLUGS is set (``> T`` past
its own limit), the gaitc/SLUGS ratio, and how long past ``--lag-limit`` ``gaitc check
--timeout`` returned on instances slower than that limit. ``--ablation`` times solver
options per row instead: the default (the race), each of its two racers alone, one sifting
run after the static build, dynamic sifting throughout, and the static occurrence order;
each configuration's fastest of three runs on rows under five seconds.
Run: .venv/bin/python bench/bench_families.py [--quick] [--ablation] [--family F] [--amba N]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import gaitc
from bench.families import catalogue, timing
from bench.families.catalogue import Instance
from bench.families.timing import Outcome
from gaitc.solver.portfolio import SIFTED, STATIC, engine_options
from gaitc.solver.symbolic import Options

ABLATION = {
    "default": Options(),  # the race of gaitc/solver/portfolio.py
    "static": engine_options(STATIC),
    "sifted": engine_options(SIFTED),  # the race's second racer
    "sift-once": Options(reorder_once=True, reordering=False),
    "reorder": Options(reordering=True),
    "occurrence": Options(order="occurrence", reordering=False),
}
QUICK_ROW = 5.0  # seconds: ablation rows faster than this are timed QUICK_REPEATS times
QUICK_REPEATS = 3
WIDTHS = (9, 34, 9, 14, 9, 7, 7)
HEADER = ("family", "instance", "gaitc s", "verdict", "slugs s", "ratio", "lag s")


@dataclass
class Totals:
    """Sums over the corpus rows."""

    count: int = 0
    gaitc: float = 0.0
    slugs: float = 0.0
    slugs_runs: int = 0
    realizable: int = 0
    unrealizable: int = 0
    undecided: int = 0
    disagree: int = 0


def line(cells: tuple[str, ...], widths: tuple[int, ...] = WIDTHS) -> str:
    return " ".join(c.rjust(w) if k != 1 else c.ljust(w)
                    for k, (c, w) in enumerate(zip(cells, widths, strict=True))).rstrip()


def seconds(outcome: Outcome | None, limit: float) -> str:
    if outcome is None:
        return "-"
    return f"{outcome.seconds:.2f}" if outcome.decided else f"> {limit:g}"


def verdict(instance: Instance, ours: Outcome, theirs: Outcome | None) -> str:
    expected = instance.recorded
    if theirs is not None and theirs.decided:
        expected = theirs.realizable
    mark = "!" if ours.decided and expected is not None and ours.realizable != expected else ""
    return ours.verdict + mark


def ratio(ours: Outcome, theirs: Outcome | None) -> str:
    if theirs is None or not (ours.decided and theirs.decided) or theirs.seconds <= 0:
        return "-"
    return f"{ours.seconds / theirs.seconds:.2f}"


def run_row(instance: Instance, args: argparse.Namespace) -> tuple[Outcome, Outcome | None, str]:
    ours = timing.embedded(instance, args.timeout)
    theirs = timing.slugs(instance, args.slugs_timeout)
    lag = "-"
    if not ours.decided or ours.seconds > args.lag_limit:
        past = timing.timeout_lag(instance, args.lag_limit)
        # a CLI run that decided within the limit (the row was close to it) has no lag
        lag = f"{past:.2f}" if past >= 0 else "-"
    return ours, theirs, lag


def table(rows: list[Instance], args: argparse.Namespace) -> None:
    print(line(HEADER), flush=True)
    totals = Totals()
    worst: tuple[float, str] | None = None
    for instance in rows:
        ours, theirs, lag = run_row(instance, args)
        if lag != "-" and (worst is None or float(lag) > worst[0]):
            worst = (float(lag), f"{instance.family} {instance.name}")
        if instance.family == "corpus":
            _add(totals, instance, ours, theirs)
            continue
        print(line((instance.family, instance.name, seconds(ours, args.timeout),
                    verdict(instance, ours, theirs), seconds(theirs, args.slugs_timeout),
                    ratio(ours, theirs), lag)), flush=True)
    if totals.count:
        summary = (f"{totals.realizable}R {totals.unrealizable}U"
                   + (f" {totals.undecided}?" if totals.undecided else "")
                   + (f" {totals.disagree}!" if totals.disagree else ""))
        slugs_s = f"{totals.slugs:.2f}" if totals.slugs_runs == totals.count else "-"
        rat = f"{totals.gaitc / totals.slugs:.2f}" if slugs_s != "-" and totals.slugs else "-"
        print(line(("corpus", f"{totals.count} specs (totals)", f"{totals.gaitc:.2f}", summary,
                    slugs_s, rat, "-")), flush=True)
    if worst is not None:
        print(f"worst --timeout lag: {worst[0]:.2f} s past {args.lag_limit:g} s ({worst[1]})")
    else:
        print(f"worst --timeout lag: no instance took longer than {args.lag_limit:g} s")


def _add(totals: Totals, instance: Instance, ours: Outcome, theirs: Outcome | None) -> None:
    totals.count += 1
    totals.gaitc += ours.seconds
    if theirs is not None and theirs.decided:
        totals.slugs += theirs.seconds
        totals.slugs_runs += 1
    if not ours.decided:
        totals.undecided += 1
    elif ours.realizable:
        totals.realizable += 1
    else:
        totals.unrealizable += 1
    if verdict(instance, ours, theirs).endswith("!"):
        totals.disagree += 1


def ablation(rows: list[Instance], args: argparse.Namespace) -> None:
    names = list(ABLATION)
    widths = (9, 34, *([11] * len(names)), 13)
    print(line(("family", "instance", *names, "default/best"), widths), flush=True)
    for instance in rows:
        outcomes = [timing.embedded(instance, args.timeout, o) for o in ABLATION.values()]
        # Rows that take seconds are timed once; quicker ones, whose differences are a few
        # hundredths of a second (a fork, the machine's noise), are timed QUICK_REPEATS
        # times in turn, and each configuration keeps its fastest run.
        if max(o.seconds for o in outcomes) < QUICK_ROW:
            for _ in range(QUICK_REPEATS - 1):
                again = [timing.embedded(instance, args.timeout, o) for o in ABLATION.values()]
                outcomes = [min(a, b, key=lambda o: (not o.decided, o.seconds))
                            for a, b in zip(outcomes, again, strict=True)]
        decided = [o.seconds for o in outcomes if o.decided]
        best = min(decided) if decided else None
        rat = (f"{outcomes[0].seconds / best:.2f}" if outcomes[0].decided and best
               else ("> " + f"{args.timeout / best:.1f}" if best else "-"))
        print(line((instance.family, instance.name, *(seconds(o, args.timeout) for o in outcomes),
                    rat), widths), flush=True)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true",
                        help="thesis grids up to 10x10 at health 2-3, AMBA N = 2..5, "
                        "arbiters and lifts up to 24, hazard grids up to 8x8")
    parser.add_argument("--ablation", action="store_true", help="compare solver options")
    parser.add_argument("--timeout", type=float, default=300.0,
                        help="embedded solver limit per instance (default 300 s)")
    parser.add_argument("--slugs-timeout", type=float, default=600.0,
                        help="SLUGS limit per instance (default 600 s)")
    parser.add_argument("--lag-limit", type=float, default=10.0,
                        help="the --timeout given to 'gaitc check' on slower instances")
    parser.add_argument("--family", action="append", choices=catalogue.FAMILIES,
                        help="only this family (repeatable)")
    parser.add_argument("--amba", type=int, action="append", help="only AMBA with N masters")
    args = parser.parse_args(argv)
    families = tuple(args.family or catalogue.FAMILIES)
    # warm up (the grammar, and dd with what it imports, some 0.15 s), so that the first
    # row does not pay for what every later one finds loaded
    gaitc.check(gaitc.load(str(catalogue.ROOT / "specs" / "patrol_2x2.gait")))
    with tempfile.TemporaryDirectory(prefix="bench-families-") as tmp:
        rows = catalogue.instances(Path(tmp), args.quick, families, args.amba)
        (ablation if args.ablation else table)(rows, args)


if __name__ == "__main__":
    main()
