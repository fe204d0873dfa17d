"""Differential campaign: seeded random GR(1) specs of structured shapes, gaitc against SLUGS.

Role: look for specs where the embedded solver's verdict differs from SLUGS's, where it is
much slower than SLUGS (gaitc/SLUGS > 1.5 with SLUGS over 0.2 s), or where it takes more than
20 s while SLUGS is fast.  The shapes are ones that the fixed families (bench/families/) and
the tiny random corpus (tests/data/gr1_corpus) do not cover, each of 15-45 Boolean variables:

* ``counter``  integer counters stepped, held or reset by input bits, with targets;
* ``compare``  integer trackers/comparators of two slowly changing integer inputs;
* ``mutex``    requests and grants in one-hot or at-most-one groups, blocking pairs;
* ``graph``    robots on random graphs (integer positions) avoiding a moving obstacle and
  closed doors, with reachability goals;
* ``automata`` products of small random automata (integer states), input-driven, with
  forbidden joint states and accepting-state goals;
* ``invariant`` random 3-4 literal clauses with next-state literals, random liveness.

Every spec has 1-4 liveness assumptions and 1-4 liveness guarantees, and is decided under
the default semantics, or the robotics one for one seed in four.  SLUGS runs first on the
slugsin text gaitc compiles (``slugs [--sysInitRoboticsSemantics] FILE``; this SLUGS build
has no ``--onlyRealizability``, plain ``slugs FILE`` only decides), and specs SLUGS does not
decide within ``--slugs-timeout`` are left out.  gaitc then runs with its default options
(one process, the plan of gaitc/solver/portfolio.py) in a forked child killed at the time
limit; the table names the configuration that answered.

Run: .venv/bin/python bench/bench_random_families.py [--per-shape N] [--minutes M]
     [--shapes a,b] [--findings DIR] [--log FILE]
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import multiprocessing.connection
import shutil
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import gaitc
from bench.families.random_shapes import SHAPES, shape_text
from gaitc.diagnostics import GaitcError, SolverError
from gaitc.solver.portfolio import STATIC
from gaitc.solver.symbolic import Options
from gaitc.solver.synthesis import state_bits
from slugs_bridge.runner import run_slugs_check

MIN_BITS, MAX_BITS = 15, 45
SLOW_RATIO, SLOW_SLUGS, PATHOLOGICAL = 1.5, 0.2, 20.0
GRACE = 0.5  # seconds past its limit before a child is killed

# ----------------------------------------------------------------------------- running
@dataclass
class Row:
    """One spec's outcome."""

    shape: str
    seed: int
    semantics: str
    bits: int
    slugs_s: float | None = None
    slugs: str = "-"  # realizable, unrealizable, timeout, error
    gaitc_s: float | None = None
    gaitc: str = "-"
    engine: str = "-"
    static_s: float | None = None
    sifted_s: float | None = None
    note: str = ""
    stats: dict[str, float] = field(default_factory=dict)

    @property
    def ratio(self) -> float | None:
        if self.gaitc_s is None or not self.slugs_s:
            return None
        return self.gaitc_s / self.slugs_s

    @property
    def agree(self) -> str:
        decided = ("realizable", "unrealizable")
        if self.slugs in decided and self.gaitc in decided:
            return "yes" if self.slugs == self.gaitc else "NO"
        return "-"


def run_slugs(path: Path, semantics: str, timeout: float) -> tuple[str, float]:
    """SLUGS's verdict on the slugsin file and its own seconds (slugs_bridge.runner, the
    binary of ``$SLUGS`` or PATH); "timeout" or "error" when it gives none."""
    started = time.perf_counter()
    try:
        result = run_slugs_check(path.read_text(encoding="utf-8"), semantics=semantics,
                                 timeout=timeout)
    except SolverError:
        elapsed = time.perf_counter() - started
        return ("timeout" if elapsed >= timeout else "error"), elapsed
    return ("realizable" if result.realizable else "unrealizable"), result.seconds


def _child(conn: multiprocessing.connection.Connection, path: str, semantics: str,
           options: Options) -> None:
    try:
        started = time.perf_counter()
        spec = gaitc.load(path)
        verdict = gaitc.check(spec, semantics=semantics, options=options)
        seconds = time.perf_counter() - started
        stats: dict[str, object] = asdict(verdict.stats) if verdict.stats is not None else {}
        stats["engine"] = verdict.engine
        conn.send(("realizable" if verdict.realizable else "unrealizable", seconds, stats))
    except GaitcError as err:
        conn.send(("error", 0.0, {"message": str(err)}))
    except Exception as err:  # a crash is a finding too
        conn.send(("error", 0.0, {"message": f"{type(err).__name__}: {err}"}))


def run_config(path: Path, semantics: str, options: Options,
               limit: float) -> tuple[str, float, dict[str, float]]:
    """One configuration in a forked child, killed ``GRACE`` s after ``limit``."""
    ctx = multiprocessing.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_child, args=(child, str(path), semantics, options))
    started = time.perf_counter()
    proc.start()
    child.close()
    answer = None
    if parent.poll(limit + GRACE):
        try:
            answer = parent.recv()
        except EOFError:
            answer = None
    elapsed = time.perf_counter() - started
    if proc.is_alive():
        proc.kill()
    proc.join()
    parent.close()
    if answer is None:
        return ("timeout" if elapsed >= limit else "error"), elapsed, {}
    verdict, seconds, stats = answer
    if verdict in ("realizable", "unrealizable") and seconds > limit:
        return "timeout", seconds, {}
    return verdict, seconds, stats


def run_gaitc(row: Row, path: Path, limit: float, bits: int) -> None:
    """gaitc's default engine in a child process (``bits``: kept for the table)."""
    verdict, seconds, stats = run_config(path, row.semantics, Options(), limit)
    engine = str(stats.pop("engine", "-")) if stats else "-"
    row.gaitc, row.gaitc_s, row.engine, row.static_s, row.stats = (
        verdict, seconds, engine, seconds if engine == STATIC else None, stats)
    if row.gaitc not in ("realizable", "unrealizable"):
        row.gaitc_s = limit


def count_bits(slugsin: str) -> int:
    """Boolean variables in the [INPUT] and [OUTPUT] sections of a slugsin text."""
    total, counting = 0, False
    for raw in slugsin.splitlines():
        text = raw.strip()
        if text.startswith("["):
            counting = text in ("[INPUT]", "[OUTPUT]")
        elif counting and text and not text.startswith("#"):
            total += 1
    return total


def generate(shape: str, seed: int, workdir: Path) -> tuple[Path, Path, int] | str:
    """The spec's structuredslugs and slugsin files and its bits, or why it was skipped."""
    text = shape_text(shape, seed)
    path = workdir / f"{shape}_{seed:04d}.structuredslugs"
    path.write_text(text, encoding="utf-8")
    try:
        spec = gaitc.load(str(path))
        slugsin = gaitc.emit(spec, "slugsin")
    except GaitcError as err:
        return f"generator error: {err}"
    bits = state_bits(spec.gr1)
    if bits != count_bits(slugsin):
        return "bit count mismatch"
    if not MIN_BITS <= bits <= MAX_BITS:
        return f"{bits} bits"
    out = path.with_suffix(".slugsin")
    out.write_text(slugsin, encoding="utf-8")
    return path, out, bits


WIDTHS = (9, 5, 4, 4, 8, 8, 6, 13, 13, 5, 12)
HEADER = ("shape", "seed", "sem", "bits", "gaitc s", "slugs s", "ratio", "gaitc", "slugs",
          "agree", "engine")


def fmt(cells: tuple[str, ...]) -> str:
    return " ".join(c.rjust(w) if k else c.ljust(w)
                    for k, (c, w) in enumerate(zip(cells, WIDTHS, strict=True))).rstrip()


def show(row: Row) -> str:
    ratio = "-" if row.ratio is None else f"{row.ratio:.2f}"
    return fmt((row.shape, str(row.seed), row.semantics[:3], str(row.bits),
                "-" if row.gaitc_s is None else f"{row.gaitc_s:.3f}",
                "-" if row.slugs_s is None else f"{row.slugs_s:.3f}", ratio, row.gaitc,
                row.slugs, row.agree, row.engine.replace(" order", ""))) + (
                    f"  {row.note}" if row.note else "")


def finding(row: Row) -> str | None:
    """Why ``row`` is a finding, or None."""
    if row.agree == "NO":
        return "verdicts differ"
    if row.gaitc == "error":
        return "gaitc error"
    if row.slugs not in ("realizable", "unrealizable") or row.slugs_s is None:
        return None
    if row.gaitc_s is not None and row.gaitc_s > PATHOLOGICAL and row.slugs_s < 5.0:
        return "pathologically slow"
    if row.ratio is not None and row.ratio > SLOW_RATIO and row.slugs_s > SLOW_SLUGS:
        return "slow"
    if row.gaitc_s is not None and row.gaitc_s > 2.0 and row.ratio is not None and row.ratio > 10:
        return "slow on a spec SLUGS decides at once"
    if row.note:
        return row.note
    return None


def save(row: Row, why: str, files: tuple[Path, Path], folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for f in files:
        shutil.copy(f, folder / f.name)
    with (folder / "README.txt").open("a", encoding="utf-8") as readme:
        robotics = " --robotics-semantics" if row.semantics == "robotics" else ""
        readme.write(f"{files[0].name}: {why}; gaitc {row.gaitc} {row.gaitc_s}, slugs "
                     f"{row.slugs} {row.slugs_s}, bits {row.bits}, engine {row.engine}; "
                     f"gaitc check {files[0].name} --json{robotics}\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-shape", type=int, default=60)
    parser.add_argument("--first-seed", type=int, default=0)
    parser.add_argument("--shapes", default=",".join(SHAPES))
    parser.add_argument("--minutes", type=float, default=70.0, help="stop after this long")
    parser.add_argument("--slugs-timeout", type=float, default=30.0)
    parser.add_argument("--workdir", type=Path, default=None)
    parser.add_argument("--findings", type=Path, default=Path("/tmp/fuzz_findings"))
    parser.add_argument("--log", type=Path, default=None, help="JSON lines of every row")
    parser.add_argument("--slugs-only", action="store_true", help="tune: skip gaitc")
    args = parser.parse_args(argv)
    shapes = [s for s in args.shapes.split(",") if s]
    unknown = [s for s in shapes if s not in SHAPES]
    if unknown:
        parser.error(f"unknown shapes {unknown}; known: {', '.join(SHAPES)}")
    workdir = args.workdir or Path(tempfile.mkdtemp(prefix="random-families-"))
    workdir.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    rows: list[Row] = []
    skipped: dict[str, int] = {}
    print(f"specs in {workdir}", flush=True)
    print(fmt(HEADER), flush=True)
    for seed in range(args.first_seed, args.first_seed + args.per_shape):
        for shape in shapes:
            if time.perf_counter() - started > args.minutes * 60:
                break
            made = generate(shape, seed, workdir)
            if isinstance(made, str):
                skipped[made.split(":")[0]] = skipped.get(made.split(":")[0], 0) + 1
                if made.startswith("generator"):
                    print(f"{shape} {seed}: {made}", flush=True)
                continue
            structured, slugsin, bits = made
            semantics = "robotics" if seed % 4 == 3 else "default"
            row = Row(shape, seed, semantics, bits)
            row.slugs, row.slugs_s = run_slugs(slugsin, semantics, args.slugs_timeout)
            if row.slugs in ("realizable", "unrealizable") and not args.slugs_only:
                limit = min(45.0, max(PATHOLOGICAL + 5.0, 10 * row.slugs_s))
                run_gaitc(row, structured, limit, bits)
            rows.append(row)
            print(show(row), flush=True)
            why = finding(row)
            if why is not None:
                save(row, why, (structured, slugsin), args.findings)
            if args.log is not None:
                with args.log.open("a", encoding="utf-8") as log:
                    log.write(json.dumps({**asdict(row), "ratio": row.ratio,
                                          "finding": why}) + "\n")
    summary(rows, skipped, time.perf_counter() - started)
    return 0


def summary(rows: list[Row], skipped: dict[str, int], seconds: float) -> None:
    print(f"\n{len(rows)} specs in {seconds / 60:.1f} min; skipped: {skipped or 'none'}")
    print(fmt(("shape", "n", "", "", "R", "U", "", "slugs ?", "gaitc ?", "NO", "slow")))
    for shape in SHAPES:
        mine = [r for r in rows if r.shape == shape]
        if not mine:
            continue
        real = sum(r.slugs == "realizable" for r in mine)
        unreal = sum(r.slugs == "unrealizable" for r in mine)
        print(fmt((shape, str(len(mine)), "", "", str(real), str(unreal), "",
                   str(len(mine) - real - unreal),
                   str(sum(r.gaitc in ("timeout", "error") for r in mine)),
                   str(sum(r.agree == "NO" for r in mine)),
                   str(sum(finding(r) in ("slow", "pathologically slow") for r in mine)))))
    ranked = sorted((r for r in rows if r.ratio is not None and (r.slugs_s or 0) > SLOW_SLUGS),
                    key=lambda r: -(r.ratio or 0))
    print("\nworst ratios (SLUGS > 0.2 s):")
    for r in ranked[:10]:
        print(show(r))
    print("\nslowest gaitc:")
    timed = [r for r in rows if r.gaitc_s is not None]
    for r in sorted(timed, key=lambda r: -(r.gaitc_s or 0))[:10]:
        print(show(r))


if __name__ == "__main__":
    raise SystemExit(main())
