"""The published instances' work budget: no silent regression of the solver (issue 59).

Each file of ``tests/data/published/`` (small and middle instances of gr1c, SLUGS,
SYNTCOMP and Spectra's benchmark set, copied as published, in both SLUGS forms where both
are given) is decided with the default plan, and its work, CUDD's computed-table lookups and
the fixpoint's CPre steps, is held to the budget ``tools/work_budgets.py`` recorded in
``budgets.tsv`` (see its docstring for the slack).  The counts do not depend on the machine
or its load, so the test fails the same way everywhere; the verdict and the configuration
that answered must not change either.  A change meant to change the work records the table
again.  The test is also shown to fail: an engine switch that regresses (the attractor
start off) breaks the budget of the gridworld-shaped instance.
"""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import replace
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

import gaitc
from gaitc.solver import synthesis
from gaitc.solver.symbolic import Options

ROOT = Path(__file__).resolve().parent.parent.parent


def _budgets() -> ModuleType:
    spec = importlib.util.spec_from_file_location("work_budgets",
                                                  ROOT / "tools" / "work_budgets.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up
    spec.loader.exec_module(module)
    return module


BUDGETS = _budgets()
RECORDED: dict[str, Any] = BUDGETS.recorded()


def test_every_instance_has_a_budget() -> None:
    names = {p.name for p in BUDGETS.files()}
    assert names == set(RECORDED), "run: python tools/work_budgets.py"
    assert len(names) >= 15


@pytest.mark.parametrize("name", sorted(RECORDED))
def test_published_instance_keeps_its_work_budget(name: str) -> None:
    work = BUDGETS.measure(BUDGETS.FOLDER / name)
    broken = work.over(RECORDED[name])
    assert not broken, (f"{name}: " + "; ".join(broken)
                        + " (if this is meant, run python tools/work_budgets.py and say why)")


def test_a_regressing_engine_switch_breaks_the_budget() -> None:
    """The gate closes: the 2trolls gridworld without the attractor start does several
    times the recorded work, and the budget says so."""
    name = "2trolls.structuredslugs"
    gr1 = gaitc.load(str(BUDGETS.FOLDER / name)).gr1
    slow = synthesis.check(gr1, options=replace(Options(), attractor=False))
    work = BUDGETS.Work(name, "realizable" if slow.realizable else "unrealizable",
                        slow.engine, slow.stats.lookups, slow.stats.x_iterations)
    broken = work.over(RECORDED[name])
    assert broken and any("lookups" in b or "steps" in b for b in broken), broken
