"""Large integer maps (issue 37): gridworlds and position arithmetic, SLUGS side by side.

Rows are the gridworlds of :mod:`bench.families.gridworld` (2^bits cells a side, one or two
obstacles in 8 x 8 boxes, integer or one-hot obstacle, every move its own clause) and the
evasion grids in the style of SLUGS's EvasionOnGrid example (arithmetic position updates,
an obstacle that moves by at most one cell).  Each row runs ``gaitc check`` as a whole
process (the embedded solver's default: the race of two orders), the embedded solver in the
declaration order alone (what SLUGS uses: inputs, then outputs), and SLUGS when $SLUGS is
set, each with its wall time and peak memory (the process's maximum resident set, children
included), and the ratio SLUGS / gaitc.  ``--quick`` takes the rows up to 256 x 256 and
32 x 32 (under 20 minutes with SLUGS on two cores).
Run: .venv/bin/python bench/bench_gridworld.py [--quick] [--timeout S]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.families.gridworld import BITS, QUICK_BITS, evasion_text, gridworld_text  # noqa: E402

GAITC = [sys.executable, "-m", "gaitc"]
DECLARATION = ("import sys\nfrom gaitc.api.loading import as_gr1, load\n"
               "from gaitc.solver.symbolic import Options\n"
               "from gaitc.solver.synthesis import check\n"
               "r = check(as_gr1(load(sys.argv[1])), options=Options(reordering=False, "
               "order='declaration'))\nsys.exit(0 if r.realizable else 3)\n")


def rows(quick: bool) -> list[tuple[str, str]]:
    """(name, structured-SLUGS text) of every row."""
    out = []
    for bits in QUICK_BITS if quick else BITS:
        side = 1 << bits
        out.append((f"grid {side}x{side} int", gridworld_text(bits)))
        if bits <= 7:
            out.append((f"grid {side}x{side} one-hot", gridworld_text(bits, encoding="onehot")))
            out.append((f"grid {side}x{side} 2 obst", gridworld_text(bits, 2)))
    for side in (16, 24, 32) if quick else (16, 24, 32, 48, 64):
        out.append((f"evasion {side}x{side}", evasion_text(side, side)))
    return out


def measure(command: list[str], timeout: float) -> tuple[str, float, float]:
    """(verdict or 'timeout', wall seconds, peak MB) of one process run."""
    began = time.perf_counter()
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                              check=False)
    except subprocess.TimeoutExpired:
        return "timeout", timeout, 0.0
    seconds = time.perf_counter() - began
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    verdict = {0: "realizable", 3: "unrealizable"}.get(done.returncode, f"exit {done.returncode}")
    # ru_maxrss of children is the largest child so far: report it when this run raised it
    return verdict, seconds, max(peak, before) / 1024.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--timeout", type=float, default=600.0)
    args = parser.parse_args()
    slugs = os.environ.get("SLUGS")
    print(f"{'instance':<24} {'gaitc s':>8} {'MB':>6} {'decl s':>8} {'slugs s':>8} {'MB':>6} "
          f"{'ratio':>6}  verdict")
    with tempfile.TemporaryDirectory() as folder:
        for name, text in rows(args.quick):
            path = Path(folder) / (name.replace(" ", "_") + ".structuredslugs")
            path.write_text(text, encoding="utf-8")
            verdict, ours, our_mb = measure([*GAITC, "check", str(path)], args.timeout)
            _, decl, _ = measure([sys.executable, "-c", DECLARATION, str(path)], args.timeout)
            theirs, their_mb, ratio = "-", "-", "-"
            if slugs:
                slugs_verdict, seconds, mb = measure(
                    [*GAITC, "check", "--solver", "slugs", "--slugs", slugs, str(path)],
                    args.timeout)
                theirs, their_mb = f"{seconds:8.2f}", f"{mb:6.0f}"
                ratio = f"{seconds / ours:6.2f}" if verdict != "timeout" else "-"
                if slugs_verdict != verdict and "timeout" not in (slugs_verdict, verdict):
                    verdict += f" (SLUGS: {slugs_verdict})"
            print(f"{name:<24} {ours:8.2f} {our_mb:6.0f} {decl:8.2f} {theirs:>8} "
                  f"{their_mb:>6} {ratio:>6}  {verdict}", flush=True)
    print("ratio: SLUGS seconds / gaitc seconds (above 1: gaitc faster); MB: peak resident "
          "memory of the largest process so far (children included)")


if __name__ == "__main__":
    main()
