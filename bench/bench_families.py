"""Benchmark tables over every GR(1) family of issue 12, four solvers side by side.

Families (bench/families/): the thesis robots and grids (4x5 to 30x30, health 2-5, both
encodings), AMBA AHB arbiters (N = 2..10, in an integer encoding and in the SYNTCOMP
generator's bit encoding), generalized buffers (GenBuf, 2 to 64 senders), the arbiter and
the lift of the first GR(1) paper (2 to 64 clients or floors), the SYNTCOMP safety games
(Cinderella-Stepmother, moving obstacle), the SLUGS examples, hazard grids, the random
corpus as one row of totals, and whatever else bench/families/catalogue.py lists.

One table per family.  Each instance runs four solvers as whole processes
(bench/families/solvers.py): gaitc (``python -m gaitc check``, the embedded solver's
default), SLUGS on the slugsin gaitc writes, gr1c on the ``.spc`` text of peers/spc.py and
omega (``python -m peers.omega_game``).  Per solver: wall seconds, CPU seconds and peak MB
of the process tree (bench/families/measure.py), and the verdict: R, U, T (past its time
limit), E (it failed), - (not run: not installed, or it cannot take the spec; the reasons
follow the table); ``!`` marks a verdict that differs from the reference (SLUGS's recorded
verdict where there is one, else the majority of the solvers).  ``lag s``: how long past
``--lag-limit`` ``gaitc check --timeout`` returned on instances slower than that limit.
``--repeat N`` runs each solver N times per instance and prints, instead, the least, median
and largest wall seconds and their spread (largest / least).  ``--ablation`` times gaitc's
solver options per row instead (in this process): the default (the race), each of its two
racers alone, one sifting run after the static build, dynamic sifting throughout, and the
static occurrence order; each configuration's fastest of three runs on rows under 5 s.
Run: .venv/bin/python bench/bench_families.py [--quick] [--repeat N] [--family F] [--amba N]
     [--semantics robotics] [--ablation]
"""

from __future__ import annotations

import argparse
import signal
import statistics
import sys
import tempfile
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from bench.families import catalogue, solvers, timing
from bench.families.catalogue import Instance
from bench.families.solvers import TOOLS, Binaries, Inputs, Run
from gaitc.ir.spec import SEMANTICS, Semantics, semantics_named
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
#: --quick's time limit of SLUGS, gr1c and omega (seconds): SLUGS and omega pass 60 s on
#: several of the quick thesis grids, and the run is to stay near 20 minutes.
QUICK_LIMIT = 10.0
QUICK_ROW = 5.0  # seconds: ablation rows faster than this are timed QUICK_REPEATS times
QUICK_REPEATS = 3
NAME = 34  # the instance column's width
#: Per solver, the columns of a run and of a repeated run: (title, width).
SINGLE = (("s", 6), ("cpu s", 6), ("MB", 5), ("v", 3))
REPEATED = (("min s", 6), ("med s", 6), ("max s", 6), ("spread", 6), ("v", 3))
LETTERS = {"realizable": "R", "unrealizable": "U", "timeout": "T", "error": "E", "n/a": "-"}


@dataclass
class Row:
    """One instance's runs, per solver (one run each, or ``--repeat`` runs)."""

    instance: Instance
    runs: dict[str, list[Run]]
    lag: str = "-"
    marks: dict[str, bool] = field(default_factory=dict)

    def verdict(self, tool: str) -> str:
        """The solver's verdict: the most common over its runs (they agree in practice)."""
        return Counter(r.verdict for r in self.runs[tool]).most_common(1)[0][0]


def references(row: Row, semantics: Semantics) -> None:
    """Mark each solver whose verdict differs from the reference: SLUGS's recorded default
    verdict, else the majority of the decided verdicts (on a tie, every decided one)."""
    decided = {t: row.verdict(t) for t in TOOLS
               if row.verdict(t) in ("realizable", "unrealizable")}
    recorded = row.instance.recorded if semantics == Semantics.DEFAULT else None
    if recorded is not None:
        wanted: set[str] = {"realizable" if recorded else "unrealizable"}
    else:
        counts = Counter(decided.values()).most_common()
        tie = len(counts) > 1 and counts[0][1] == counts[1][1]
        wanted = set() if tie or not counts else {counts[0][0]}
    row.marks = {t: v not in wanted for t, v in decided.items()}


def measure_row(instance: Instance, inputs: Inputs, args: argparse.Namespace,
                found: Binaries) -> Row:
    limits = {"gaitc": args.timeout, "slugs": args.slugs_timeout, "gr1c": args.peer_timeout,
              "omega": args.peer_timeout}
    runs: dict[str, list[Run]] = {t: [] for t in TOOLS}
    for _ in range(args.repeat):
        for tool in TOOLS:
            if runs[tool] and not runs[tool][-1].decided:
                continue  # a solver that timed out or failed once is not run again
            runs[tool].append(solvers.run(tool, inputs, args.semantics, found, limits[tool]))
    row = Row(instance, runs)
    gaitc_run = runs["gaitc"][0]
    if args.repeat == 1 and (not gaitc_run.decided or gaitc_run.wall > args.lag_limit):
        past = timing.timeout_lag(instance, args.lag_limit)
        # a CLI run that decided within the limit (the row was close to it) has no lag
        row.lag = f"{past:.2f}" if past >= 0 else "-"
    references(row, args.semantics)
    return row


# ---------------------------------------------------------------- the text of the tables
def _cells(widths: Sequence[tuple[str, int]], values: Sequence[str]) -> str:
    return " ".join(v.rjust(w) for (_, w), v in zip(widths, values, strict=True))


def _letter(row: Row, tool: str) -> str:
    return LETTERS[row.verdict(tool)] + ("!" if row.marks.get(tool) else "")


def _seconds(run: Run, limit: float) -> str:
    if run.verdict == "timeout":
        return f">{limit:g}"
    return "-" if run.verdict == "n/a" else f"{run.wall:.2f}"


def _single(row: Row, tool: str, limit: float) -> list[str]:
    run = row.runs[tool][0]
    if run.verdict == "n/a":
        return ["-", "-", "-", _letter(row, tool)]
    return [_seconds(run, limit), f"{run.cpu:.2f}", f"{run.peak_mb:.0f}", _letter(row, tool)]


def _repeated(row: Row, tool: str, limit: float) -> list[str]:
    runs = row.runs[tool]
    if not all(r.decided for r in runs):
        return [_seconds(runs[-1], limit), "-", "-", "-", _letter(row, tool)]
    walls = sorted(r.wall for r in runs)
    spread = f"{walls[-1] / walls[0]:.2f}" if walls[0] > 0 else "-"
    return [f"{walls[0]:.2f}", f"{statistics.median(walls):.2f}", f"{walls[-1]:.2f}", spread,
            _letter(row, tool)]


class Table:
    """One family's table: a header naming the solvers over their columns, a line per
    instance (the corpus: one line of totals), the reasons for the solvers not run."""

    def __init__(self, family: str, args: argparse.Namespace) -> None:
        self.args = args
        self.columns = REPEATED if args.repeat > 1 else SINGLE
        self.limits = {"gaitc": args.timeout, "slugs": args.slugs_timeout,
                       "gr1c": args.peer_timeout, "omega": args.peer_timeout}
        group = sum(w for _, w in self.columns) + len(self.columns) - 1
        lag = "" if args.repeat > 1 else " " + "lag s".rjust(6)
        print(f"\n{family}")
        print(" " * NAME + "".join(f" | {t.center(group)}" for t in TOOLS))
        print("instance".ljust(NAME) + "".join(
            " | " + " ".join(title.rjust(w) for title, w in self.columns) for _ in TOOLS) + lag)
        self.notes: dict[str, tuple[list[str], list[str]]] = {}  # reason: solvers, instances

    def row(self, row: Row) -> None:
        pick = _repeated if self.args.repeat > 1 else _single
        cells = "".join(" | " + _cells(self.columns, pick(row, t, self.limits[t]))
                        for t in TOOLS)
        lag = "" if self.args.repeat > 1 else " " + row.lag.rjust(6)
        print(row.instance.name[:NAME].ljust(NAME) + cells + lag, flush=True)
        self.note(row)

    def note(self, row: Row) -> None:
        """Remember why a solver did not run or failed on ``row`` (said once per reason)."""
        for tool in TOOLS:
            for run in row.runs[tool][:1]:
                if run.note:
                    tools, names = self.notes.setdefault(run.note, ([], []))
                    if tool not in tools:
                        tools.append(tool)
                    if row.instance.name not in names:
                        names.append(row.instance.name)

    def totals(self, rows: list[Row]) -> None:
        """One line for many instances (the corpus): sums of seconds, the largest MB, and
        per solver the number of verdicts marked ``!`` (``ok`` when none)."""
        cells = []
        for tool in TOOLS:
            runs = [r.runs[tool] for r in rows]
            wrong = sum(1 for r in rows if r.marks.get(tool))
            mark = "-" if all(not rs[0].decided for rs in runs) else f"{wrong}!" if wrong else "ok"
            decided = [rs for rs in runs if all(r.decided for r in rs)]
            if self.args.repeat > 1:
                sums = [sum(sorted(r.wall for r in rs)[0] for rs in decided),
                        sum(statistics.median(r.wall for r in rs) for rs in decided),
                        sum(max(r.wall for r in rs) for rs in decided)]
                spread = f"{sums[2] / sums[0]:.2f}" if sums[0] else "-"
                values = [f"{s:.2f}" for s in sums] + [spread, mark]
            else:
                values = [f"{sum(rs[0].wall for rs in decided):.2f}",
                          f"{sum(rs[0].cpu for rs in decided):.2f}",
                          f"{max((rs[0].peak_mb for rs in decided), default=0):.0f}", mark]
            cells.append(_cells(self.columns, values))
        counts = Counter(r.instance.recorded for r in rows)
        name = f"{len(rows)} specs ({counts[True]}R {counts[False]}U)"
        lag = "" if self.args.repeat > 1 else " " + "-".rjust(6)
        print(name.ljust(NAME) + "".join(" | " + c for c in cells) + lag, flush=True)
        for row in rows:
            self.note(row)

    def close(self) -> None:
        for reason, (tools, names) in self.notes.items():
            shown = ", ".join(names[:4]) + (f" and {len(names) - 4} more" if len(names) > 4 else "")
            print(f"  - {', '.join(tools)}: {reason} ({shown})")


def tables(rows: list[Instance], args: argparse.Namespace, folder: Path) -> None:
    found = Binaries.find(args.slugs, args.gr1c)
    print(f"semantics {args.semantics}; slugs: {found.slugs or 'not found'}; "
          f"gr1c: {found.gr1c or 'not found'}; omega: "
          f"{'installed' if found.omega else 'not installed'}; "
          f"{args.repeat} run(s) per solver and instance")
    worst: tuple[float, str] | None = None
    for family in dict.fromkeys(i.family for i in rows):
        table = Table(family, args)
        members = [i for i in rows if i.family == family]
        done = []
        for instance in members:
            inputs = solvers.prepare(instance.path, instance.encoding, args.semantics, folder)
            row = measure_row(instance, inputs, args, found)
            if row.lag != "-" and (worst is None or float(row.lag) > worst[0]):
                worst = (float(row.lag), f"{instance.family} {instance.name}")
            if family != "corpus":
                table.row(row)
            done.append(row)
        if family == "corpus":
            table.totals(done)
        table.close()
    print("\nR realizable, U unrealizable, T past the time limit, E failed, - not run; "
          "! differs from the reference")
    if args.repeat > 1:
        return
    if worst is not None:
        print(f"worst --timeout lag: {worst[0]:.2f} s past {args.lag_limit:g} s ({worst[1]})")
    else:
        print(f"worst --timeout lag: no instance took longer than {args.lag_limit:g} s")


def _seconds_of(outcome: timing.Outcome, limit: float) -> str:
    return f"{outcome.seconds:.2f}" if outcome.decided else f"> {limit:g}"


def ablation(rows: list[Instance], args: argparse.Namespace) -> None:
    names = list(ABLATION)
    widths = (9, 34, *([11] * len(names)), 13)
    print(" ".join(c.rjust(w) if k != 1 else c.ljust(w) for k, (c, w) in
                   enumerate(zip(("family", "instance", *names, "default/best"), widths,
                                 strict=True))).rstrip(), flush=True)
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
        cells = (instance.family, instance.name,
                 *(_seconds_of(o, args.timeout) for o in outcomes), rat)
        print(" ".join(c.rjust(w) if k != 1 else c.ljust(w)
                       for k, (c, w) in enumerate(zip(cells, widths, strict=True))).rstrip(),
              flush=True)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true",
                        help="thesis grids up to 10x10 at health 2-3, AMBA N = 2..5, "
                        "arbiters and lifts up to 24, hazard grids up to 8x8; the time limits "
                        "default to 60 s for gaitc and 10 s for the others")
    parser.add_argument("--ablation", action="store_true", help="compare solver options")
    parser.add_argument("--repeat", type=int, default=1, metavar="N",
                        help="run each solver N times per instance (min/median/max wall)")
    parser.add_argument("--semantics", choices=SEMANTICS, default=Semantics.DEFAULT,
                        help="how the initial condition is read (default: default)")
    parser.add_argument("--timeout", type=float,
                        help="gaitc's limit per instance (default 300 s, --quick 60 s)")
    parser.add_argument("--slugs-timeout", type=float,
                        help="SLUGS's limit per instance (default 600 s, --quick 10 s)")
    parser.add_argument("--peer-timeout", type=float,
                        help="gr1c's and omega's limit per instance (default 600 s, --quick 10 s)")
    parser.add_argument("--lag-limit", type=float, default=10.0,
                        help="the --timeout given to 'gaitc check' on slower instances")
    parser.add_argument("--slugs", help="the SLUGS binary (else $SLUGS or PATH)")
    parser.add_argument("--gr1c", help="the gr1c binary (else $GR1C or PATH)")
    parser.add_argument("--family", action="append", choices=catalogue.FAMILIES,
                        help="only this family (repeatable)")
    parser.add_argument("--amba", type=int, action="append", help="only AMBA with N masters")
    args = parser.parse_args(argv)
    if args.repeat < 1:
        parser.error("--repeat needs a positive count")
    args.semantics = semantics_named(args.semantics)
    for name, full, quick in (("timeout", 300.0, 60.0), ("slugs_timeout", 600.0, QUICK_LIMIT),
                              ("peer_timeout", 600.0, QUICK_LIMIT)):
        if getattr(args, name) is None:
            setattr(args, name, quick if args.quick else full)
    # a SIGTERM ends the solver being measured too (bench/families/measure.py)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    families = tuple(args.family or catalogue.FAMILIES)
    with tempfile.TemporaryDirectory(prefix="bench-families-") as tmp:
        rows = catalogue.instances(Path(tmp), args.quick, families, args.amba)
        if args.ablation:
            ablation(rows, args)
        else:
            inputs = Path(tmp, "inputs")
            inputs.mkdir()
            tables(rows, args, inputs)


if __name__ == "__main__":
    main()
