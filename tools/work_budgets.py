"""Record the work budgets of the published instances (tests/data/published/budgets.tsv).

The CI test ``tests/solver/test_work_budget.py`` decides each published instance kept in
``tests/data/published/`` (small and middle ones of ``../shared/bench/``, copied as
published) with the embedded solver's default plan, and holds it to the work recorded here:
CUDD's computed-table lookups (building included) and the fixpoint's CPre steps, counts that
do not depend on the machine or its load, so that a change that makes the engine do several
times the work (the 4.5x regression on SLUGS's ``amba_5``, issue 59) fails the suite on any
machine.  The verdict and the configuration that answered are recorded too and must not
change.

Run ``python tools/work_budgets.py`` after a change that is meant to change the work, and
commit the new table with the change, saying why in its message; ``--check`` prints the
comparison without writing.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Final

ROOT: Final = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import gaitc  # noqa: E402
from gaitc.solver import synthesis  # noqa: E402

FOLDER: Final = ROOT / "tests" / "data" / "published"
TABLE: Final = FOLDER / "budgets.tsv"
#: The forms of an instance file (the test runs every file of the folder in these forms).
FORMS: Final = (".slugsin", ".structuredslugs")
#: A run may do this much more work than recorded before it fails: the counts vary by about
#: 1 % between runs (Python's garbage collector frees BDDs at other moments, and CUDD then
#: collects at other moments), so 30 % is noise-proof while a 1.5x regression still fails.
SLACK: Final = 1.3
#: ... plus this many lookups and steps, for the smallest instances.
FLOOR_LOOKUPS: Final = 20_000
FLOOR_STEPS: Final = 5


@dataclass(frozen=True)
class Work:
    """One instance's verdict, answering configuration and work."""

    file: str
    verdict: str
    engine: str
    lookups: int
    steps: int

    def row(self) -> str:
        return "\t".join((self.file, self.verdict, self.engine, str(self.lookups),
                          str(self.steps)))

    def over(self, budget: Work) -> list[str]:
        """How this run breaks ``budget`` (the recorded work), in words; empty if it keeps it."""
        out = []
        if self.verdict != budget.verdict:
            out.append(f"verdict {self.verdict}, recorded {budget.verdict}")
        if self.engine != budget.engine:
            out.append(f"answered in the {self.engine}, recorded in the {budget.engine}")
        if self.lookups > SLACK * budget.lookups + FLOOR_LOOKUPS:
            out.append(f"{self.lookups:,} computed-table lookups, "
                       f"{self.lookups / max(1, budget.lookups):.2f}x the recorded "
                       f"{budget.lookups:,}")
        if self.steps > SLACK * budget.steps + FLOOR_STEPS:
            out.append(f"{self.steps:,} CPre steps, {self.steps / max(1, budget.steps):.2f}x "
                       f"the recorded {budget.steps:,}")
        return out


def files() -> list[Path]:
    return sorted(p for p in FOLDER.iterdir() if p.suffix in FORMS)


def measure(path: Path) -> Work:
    """Decide ``path`` with the default plan and count its work."""
    result = synthesis.check(gaitc.load(str(path)).gr1)
    return Work(path.name, "realizable" if result.realizable else "unrealizable",
                result.engine, result.stats.lookups, result.stats.x_iterations)


def recorded() -> dict[str, Work]:
    out = {}
    for line in TABLE.read_text(encoding="utf-8").splitlines():
        if line and not line.startswith("#"):
            name, verdict, engine, lookups, steps = line.split("\t")
            out[name] = Work(name, verdict, engine, int(lookups), int(steps))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="compare, do not write")
    args = parser.parse_args(argv)
    old = recorded() if TABLE.exists() else {}
    rows = []
    for path in files():
        work = measure(path)
        before = old.get(path.name)
        ratio = f"{work.lookups / before.lookups:.2f}x" if before and before.lookups else "new"
        print(f"{path.name:<60} {work.verdict:<13} {work.engine:<20} {work.lookups:>12,} "
              f"{work.steps:>6}  {ratio}", flush=True)
        rows.append(work.row())
    if not args.check:
        head = ("# file\tverdict\tengine\tlookups\tsteps  (written by tools/work_budgets.py; "
                "tests/solver/test_work_budget.py)")
        TABLE.write_text("\n".join([head, *rows]) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
