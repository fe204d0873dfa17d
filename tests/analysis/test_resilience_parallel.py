"""Resilience reports are the same however the variant checks run: in this process, in
local processes (``jobs=2``), or on a Dask distributed cluster the test starts itself."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import gaitc

# slow: starts local processes and a Dask cluster (about 17 s; docs/background/testing.md)
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "tests" / "data" / "resilience" / "cross5.gait"
TIMING = ("seconds", "notes")


def _report(**how: Any) -> dict[str, Any]:
    data = gaitc.resilience(SPEC, method="lattice", place_caches=1, **how).to_json()
    out = {k: v for k, v in data.items() if k not in TIMING}
    if isinstance(out.get("tolerance"), dict):  # section 5's own time
        out["tolerance"] = {k: v for k, v in out["tolerance"].items() if k not in TIMING}
    return out


@pytest.fixture(scope="module")
def sequential() -> dict[str, Any]:
    return _report()


def test_local_processes_give_the_same_report(sequential: dict[str, Any]) -> None:
    assert _report(jobs=2) == sequential


@pytest.fixture(scope="module")
def cluster() -> Iterator[str]:
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as local:
        yield local.scheduler_address


def test_a_dask_cluster_gives_the_same_report(sequential: dict[str, Any], cluster: str) -> None:
    assert _report(dask=cluster) == sequential


def test_an_unreachable_scheduler_is_a_usage_error() -> None:
    pytest.importorskip("distributed")
    from gaitc.diagnostics import UsageError

    with pytest.raises(UsageError, match="cannot reach the Dask scheduler"):
        gaitc.resilience(SPEC, dask="tcp://127.0.0.1:9")
