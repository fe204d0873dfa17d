"""Benchmark: ``gaitc synth`` end to end, as a user runs it, beside another checkout.

Each row runs ``python -m gaitc synth SPEC -o FILE --json`` in a child process with the
default options (the race of solver.portfolio, the move preferences of solver.preferences,
``auto`` form, the independent verifier) and reads its JSON record: wall seconds of the
whole command (Python's start-up included), the solver's own seconds, the controller's
size and form.  With ``--baseline DIR`` (another checkout of gaitc, e.g. ``git worktree
add /tmp/base <commit>``) the same command runs there too, with this checkout's Python
environment, and the table puts the two side by side with their ratio.

The rows are the thesis robots in both encodings, thesis-style grids (bench/families/
thesis.py) with health 3 and 4, the hazard patrol of tests/data, the larger shipped
examples (radial8, radial12; centipede24 without --quick), hazard grids (bench/
families/hazard_grid.py, binary, 8 x 8 and 10 x 10), and GenBuf with 8 senders,
whose automaton passes ``--max-nodes`` and is kept symbolic.

Usage: python bench/bench_synth.py [--quick] [--baseline DIR] [--timeout S]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.families.genbuf import genbuf_text  # noqa: E402
from bench.families.hazard_grid import hazard_grid_text  # noqa: E402
from bench.families.thesis import gait_text  # noqa: E402


@dataclass(frozen=True)
class Row:
    name: str
    spec: Path
    argv: tuple[str, ...] = ()


@dataclass(frozen=True)
class Outcome:
    wall: float | None  # None: the command did not finish in time
    seconds: float | None
    size: str


def rows(folder: Path, quick: bool) -> list[Row]:
    """The benchmark's specs, generated into ``folder`` where they are not files of the
    project."""
    out = []
    for robot in ("thesis_robot_a", "thesis_robot_b"):
        for encoding in ("onehot", "binary"):
            out.append(Row(f"{robot} {encoding}", ROOT / "specs" / f"{robot}.gait",
                           ("--encoding", encoding)))
    out.append(Row("hazard_patrol onehot", ROOT / "tests" / "data" / "hazard_patrol.gait"))
    # The larger shipped examples as a new user synthesizes them (radial12 took 165 s
    # instead of 9 s while a sifting turned on for one game stayed on for the extraction).
    for example in ("radial8_patrol", "radial12_patrol") if quick else (
            "radial8_patrol", "radial12_patrol", "centipede24_patrol"):
        out.append(Row(f"{example} onehot", ROOT / "specs" / f"{example}.gait"))
    grids = [(6, 6, 3), (10, 10, 3)] if quick else [(6, 6, 3), (10, 10, 3), (10, 10, 4)]
    for rows_, cols, health in grids:
        path = folder / f"thesis_{rows_}x{cols}_h{health}.gait"
        path.write_text(gait_text(rows_, cols, health), encoding="utf-8")
        for encoding in ("onehot", "binary"):
            out.append(Row(f"thesis {rows_}x{cols} h{health} {encoding}", path,
                           ("--encoding", encoding)))
    # Hazard grids: an input per open cell, so hundreds of inputs per node (binary: the
    # family's encoding; the 10 x 10 automaton has 26,339 nodes, within --max-nodes).
    for side in [8] if quick else [8, 10]:
        path = folder / f"hazard_{side}x{side}.gait"
        path.write_text(hazard_grid_text(side), encoding="utf-8")
        out.append(Row(f"hazard grid {side}x{side} binary", path, ("--encoding", "binary")))
    genbuf = folder / "genbuf8.structuredslugs"
    genbuf.write_text(genbuf_text(8), encoding="utf-8")
    out.append(Row("genbuf 8 senders", genbuf))
    return out


def synth(checkout: Path, row: Row, out: Path, timeout: float) -> Outcome:
    """One ``gaitc synth`` of ``row`` with the gaitc of ``checkout`` (its folder first on
    ``sys.path``, as ``python -m`` puts it)."""
    argv = [sys.executable, "-m", "gaitc", "synth", str(row.spec), *row.argv, "-o", str(out),
            "--json"]
    started = time.monotonic()
    try:
        proc = subprocess.run(argv, cwd=checkout, capture_output=True, text=True,
                              timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        return Outcome(None, None, f"> {timeout:.0f} s")
    wall = time.monotonic() - started
    try:
        record = json.loads(proc.stdout)
    except json.JSONDecodeError:
        return Outcome(wall, None, f"exit {proc.returncode}")
    if record.get("verdict") != "realizable":
        return Outcome(wall, record.get("seconds"), str(record.get("verdict")))
    checked = record.get("verification") or {}
    size = f"{record['nodes']} BDD nodes" if record.get("symbolic") else f"{record['nodes']} nodes"
    if checked and not checked.get("ok"):
        size += " NOT VERIFIED"
    return Outcome(wall, record.get("seconds"), size)


def _cell(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="leave out the 10 x 10 health 4 "
                        "grid (several minutes)")
    parser.add_argument("--baseline", type=Path, help="another gaitc checkout to compare with")
    parser.add_argument("--timeout", type=float, default=900.0,
                        help="seconds each command may take (default 900)")
    args = parser.parse_args()
    header = f"{'spec':28} {'wall s':>8} {'solver s':>9} {'controller':>18}"
    if args.baseline:
        header += f" {'baseline s':>11} {'baseline controller':>20} {'ratio':>6}"
    print(header)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for row in rows(folder, args.quick):
            now = synth(ROOT, row, folder / "now.json", args.timeout)
            line = f"{row.name:28} {_cell(now.wall):>8} {_cell(now.seconds):>9} {now.size:>18}"
            if args.baseline:
                base = synth(args.baseline.resolve(), row, folder / "base.json", args.timeout)
                ratio = (f"{now.wall / base.wall:.2f}" if now.wall and base.wall else "-")
                line += f" {_cell(base.wall):>11} {base.size:>20} {ratio:>6}"
            print(line, flush=True)


if __name__ == "__main__":
    main()
