"""Long mode of the compact-controller differential (issue 48): structural mutants of the
compact controllers of several specs through the reader, the verifier and three runtimes.

Usage: python bench/fuzz_compact.py [--per-spec N] [--specs a.gait,b.gait] [--steps K]
       [--seed S]

Each mutant is made from ``(seed, spec, index)`` alone (tests/fuzz_compact.py).  The table
counts, per spec, the mutants the reader refused, those the verifier refused, those that
verified and made the same moves in the Python runner, the symbolic runtime and the
generated C, and the failures: an internal error, or a verified mutant whose runtimes
differ (both must be 0).  docs/reliability.md shows a run.
"""

from __future__ import annotations

import argparse
import random
import shutil
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from fuzz_compact import judge, mutant  # noqa: E402

import gaitc  # noqa: E402
from gaitc.compact.controller import CompactController, compact_to_dict  # noqa: E402

SPECS = ("corridor_hazard.gait", "patrol_2x2.gait", "thesis_robot_b.gait",
         "thesis_robot_a.gait")
COLUMNS = ("refused by the reader", "refused by the verifier", "verified, same moves",
           "internal", "differs")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--per-spec", type=int, default=1000)
    parser.add_argument("--specs", default=",".join(SPECS))
    parser.add_argument("--steps", type=int, default=60, help="steps per compared run")
    parser.add_argument("--seed", type=int, default=48)
    args = parser.parse_args(argv)
    compile_c = shutil.which("gcc") is not None
    print(f"compact-controller differential: {args.per_spec} mutants per spec, seed "
          f"{args.seed}, {args.steps} steps per run, generated C "
          f"{'compared' if compile_c else 'left out (no gcc)'}\n")
    print("| spec | mutants | " + " | ".join(COLUMNS) + " | steps compared | seconds |")
    print("|---" * (len(COLUMNS) + 4) + "|")
    failed = 0
    totals: Counter[str] = Counter()
    for name in args.specs.split(","):
        spec = gaitc.load(ROOT / "specs" / name)
        made = gaitc.synthesize(spec, form="compact")
        if not isinstance(made.controller, CompactController):
            print(f"| {name} | unrealizable |")
            continue
        seed = compact_to_dict(made.controller)
        outcomes: Counter[str] = Counter()
        steps, started = 0, time.monotonic()
        with tempfile.TemporaryDirectory(prefix="gaitc-fuzz-compact-") as folder:
            for index in range(args.per_spec):
                data, done = mutant(seed, random.Random(f"{args.seed}:{name}:{index}"))
                verdict = judge(spec, data, Path(folder), args.steps, compile_c)
                outcomes[verdict.outcome] += 1
                steps += verdict.steps
                if verdict.failed:
                    failed += 1
                    print(f"  {name} mutant {index} ({'; '.join(done)}): {verdict.outcome}: "
                          f"{verdict.detail}", file=sys.stderr)
        totals.update(outcomes)
        totals["steps"] += steps
        print(f"| {name} | {args.per_spec} | "
              + " | ".join(str(outcomes[c]) for c in COLUMNS)
              + f" | {steps} | {time.monotonic() - started:.0f} |")
    print(f"| all | {sum(totals[c] for c in COLUMNS)} | "
          + " | ".join(str(totals[c]) for c in COLUMNS) + f" | {totals['steps']} | |")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
