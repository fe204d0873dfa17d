"""Timed runs of one benchmark instance: the embedded solver, SLUGS, and the ``--timeout`` lag.

All times are wall-clock seconds (``time.perf_counter``): with a time limit the embedded
solver runs in a forked child, whose CPU time the parent's clock would not see.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import gaitc
from bench.families.catalogue import Instance
from gaitc.diagnostics import SolverError
from gaitc.solver.symbolic import Options

CLI = [sys.executable, "-m", "gaitc.cli"]


@dataclass(frozen=True)
class Outcome:
    """A verdict (``realizable``, ``unrealizable``, ``timeout`` or ``error``) and its time."""

    verdict: str
    seconds: float

    @property
    def decided(self) -> bool:
        return self.verdict in ("realizable", "unrealizable")

    @property
    def realizable(self) -> bool | None:
        return self.verdict == "realizable" if self.decided else None


def _spec(instance: Instance) -> gaitc.Spec:
    return gaitc.load(str(instance.path), instance.encoding)


def _failure(err: SolverError) -> str:
    return "timeout" if "time limit" in err.message or "within" in err.message else "error"


def embedded(instance: Instance, timeout: float, options: Options | None = None) -> Outcome:
    """``gaitc check`` through the API with the embedded solver, loading included."""
    started = time.perf_counter()
    try:
        verdict = gaitc.check(_spec(instance), timeout=timeout, options=options)
    except SolverError as err:
        return Outcome(_failure(err), time.perf_counter() - started)
    seconds = time.perf_counter() - started
    return Outcome("realizable" if verdict.realizable else "unrealizable", seconds)


def slugs(instance: Instance, timeout: float) -> Outcome | None:
    """SLUGS on the instance's slugsin text (as ``gaitc check --solver slugs``), or None
    when ``$SLUGS`` is not set.  The time is SLUGS's own run, without gaitc's translation."""
    if not os.environ.get("SLUGS"):
        return None
    try:
        verdict = gaitc.check(_spec(instance), solver="slugs", timeout=timeout)
    except SolverError as err:
        return Outcome(_failure(err), timeout)
    return Outcome("realizable" if verdict.realizable else "unrealizable", verdict.seconds)


def timeout_lag(instance: Instance, limit: float) -> float:
    """How long past ``limit`` seconds ``gaitc check --timeout limit`` returned (CLI run)."""
    command = [*CLI, "check", "--timeout", f"{limit:g}", str(instance.path)]
    if instance.path.suffix == ".gait":
        command += ["--encoding", instance.encoding]
    started = time.perf_counter()
    subprocess.run(command, capture_output=True, check=False, cwd=Path(__file__).parent)
    return time.perf_counter() - started - limit
