"""Checking many variants of a robot model: in this process, in local processes, or on a
Dask distributed cluster.

A variant is a checked :class:`~ltlcompiler.model.Model` (a frozen dataclass, so it pickles);
each check lowers it and solves it with the embedded solver. ``jobs > 1`` uses a
``ProcessPoolExecutor``; ``dask="tcp://HOST:PORT"`` sends the checks to an existing
``dask.distributed`` scheduler (an optional dependency). Answers come back in order, so
every way of running gives the same report.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from gaitc.diagnostics import SolverError, UsageError
from gaitc.diagnostics.processes import as_worker
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.solver import synthesis
from gaitc.solver.symbolic import Options
from ltlcompiler.encoding import EncodingName
from ltlcompiler.lowering import lower
from ltlcompiler.model import Model

Progress = Callable[[int, int, float], None]  # (done, total, seconds so far)


def variant_realizable(model: Model, encoding: EncodingName, semantics: Semantics) -> bool:
    """Lower ``model`` and decide it (the unit of work sent to workers)."""
    return spec_realizable(lower(model, encoding), semantics)


def spec_realizable(spec: GR1Spec, semantics: Semantics, first: tuple[str, ...] = ()) -> bool:
    """Decide a ready-made spec, ``first`` pinned to the top of the BDD order. The static
    order, without the solver's race (gaitc.solver.portfolio): variants of a robot's task are
    the family it is tuned for, and the workers of --jobs and --dask already fill the
    machine."""
    options = Options(first=first, reordering=False)
    return synthesis.check(spec, semantics, options=options).realizable


@dataclass
class Pool:
    """Where variant checks run, and how many have run."""

    encoding: EncodingName
    semantics: Semantics = Semantics.DEFAULT
    jobs: int = 1
    dask: str | None = None
    progress: Progress | None = None
    deadline: float | None = None
    calls: int = 0
    _executor: Any = field(default=None, repr=False)
    _client: Any = field(default=None, repr=False)

    def __post_init__(self) -> None:
        if self.jobs < 1:
            raise UsageError("--jobs must be at least 1")
        if self.dask is not None:
            try:
                from distributed import Client  # lazy: the cluster extra (Dask) may be missing
            except ImportError:
                raise UsageError("--dask needs the 'distributed' package: pip install "
                                 "'dask[distributed]' (scripts/setup.sh installs it)") from None
            try:
                self._client = Client(self.dask, timeout=10)  # type: ignore[no-untyped-call,unused-ignore]
            except (OSError, TimeoutError) as err:
                raise UsageError(f"cannot reach the Dask scheduler at {self.dask}: {err}"
                                 ) from None
        elif self.jobs > 1:
            # workers die with the run, even one killed by SIGKILL (issue 38)
            self._executor = ProcessPoolExecutor(self.jobs, initializer=as_worker)

    def close(self) -> None:
        if self._executor is not None:
            self._executor.shutdown(cancel_futures=True)
        if self._client is not None:
            self._client.close()

    def __enter__(self) -> Pool:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _check_time(self) -> None:
        if self.deadline is not None and time.monotonic() > self.deadline:
            raise SolverError("the resilience analysis ran out of time (see --timeout)")

    def models(self, variants: Sequence[Model]) -> list[bool]:
        """Realizability of each variant, in order."""
        return self._run(variant_realizable, [(m, self.encoding, self.semantics)
                                              for m in variants])

    def specs(self, variants: Sequence[GR1Spec], first: tuple[str, ...] = ()) -> list[bool]:
        """Realizability of ready-made specs, in order; ``first``: variables to put at the
        top of the BDD order (names a spec lacks are ignored)."""
        return self._run(spec_realizable, [(s, self.semantics, first) for s in variants])

    def _run(self, fn: Callable[..., bool], args: list[tuple[Any, ...]]) -> list[bool]:
        self._check_time()
        started = time.monotonic()
        total = len(args)
        out: list[bool] = []
        if self._client is not None:
            futures = self._client.map(fn, *zip(*args, strict=True), pure=False) if args else []
            for future in futures:
                out.append(bool(future.result()))
                self._tick(len(out), total, started)
        elif self._executor is not None:
            for answer in self._executor.map(fn, *zip(*args, strict=True)):
                out.append(bool(answer))
                self._tick(len(out), total, started)
        else:
            for item in args:
                self._check_time()
                out.append(fn(*item))
                self._tick(len(out), total, started)
        self.calls += total
        return out

    def _tick(self, done: int, total: int, started: float) -> None:
        if self.progress is not None:
            self.progress(done, total, time.monotonic() - started)


def terminal_progress(label: str) -> Progress | None:
    """A progress line on stderr (variants done, of how many, time left), on a terminal."""
    if not sys.stderr.isatty():
        return None

    def show(done: int, total: int, seconds: float) -> None:
        left = seconds / done * (total - done) if done else 0.0
        end = "\n" if done == total else ""
        print(f"\r{label}: {done}/{total} variants, about {left:.0f} s left   ", end=end,
              file=sys.stderr, flush=True)

    return show
