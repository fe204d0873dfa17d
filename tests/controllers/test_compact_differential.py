"""The differential check of issue 48: a compact controller that verifies is the controller.

Seeded structural mutants of compact controllers (:mod:`fuzz_compact`) go through the one
reader and the verifier; every mutant that passes both drives the Python runner, the
symbolic runtime and the generated C (compiled with -Wall -Wextra -Werror) to the same
moves on random and adversarial runs.  Refusals must be gaitc's own errors.  The long mode
is ``bench/fuzz_compact.py``; docs/reliability.md has its table.
"""

from __future__ import annotations

import random
import shutil
from collections import Counter
from pathlib import Path

import pytest
from fuzz_compact import judge, mutant

import gaitc
from gaitc.compact.controller import CompactController, compact_to_dict

ROOT = Path(__file__).resolve().parents[2]
PER_SPEC = 120
SPECS = ("corridor_hazard.gait", "patrol_2x2.gait")


@pytest.mark.parametrize("name", SPECS)
def test_mutants_that_verify_make_the_same_moves_in_c_python_and_bdds(
        name: str, tmp_path: Path) -> None:
    spec = gaitc.load(ROOT / "specs" / name)
    made = gaitc.synthesize(spec, form="compact")
    assert isinstance(made.controller, CompactController)
    seed = compact_to_dict(made.controller)
    outcomes: Counter[str] = Counter()
    failures = []
    compile_c = shutil.which("gcc") is not None
    for index in range(PER_SPEC):
        data, done = mutant(seed, random.Random(f"48:{name}:{index}"))
        verdict = judge(spec, data, tmp_path, steps=40, compile_c=compile_c)
        outcomes[verdict.outcome] += 1
        if verdict.failed:
            failures.append(f"mutant {index} ({'; '.join(done)}): {verdict.outcome}: "
                            f"{verdict.detail}")
    assert failures == []
    # not vacuous: the reader, the verifier and the runtimes each see some mutants
    assert outcomes["refused by the reader"] >= PER_SPEC // 4, outcomes
    assert outcomes["refused by the verifier"] >= 5, outcomes
    assert outcomes["verified, same moves"] >= 5, outcomes


def test_the_unmutated_controller_is_judged_the_same_everywhere(tmp_path: Path) -> None:
    spec = gaitc.load(ROOT / "specs" / "corridor_hazard.gait")
    made = gaitc.synthesize(spec, form="compact")
    assert isinstance(made.controller, CompactController)
    verdict = judge(spec, compact_to_dict(made.controller), tmp_path, steps=200,
                    compile_c=shutil.which("gcc") is not None)
    assert verdict.outcome == "verified, same moves" and verdict.steps >= 400
