"""The hazard-grid and thesis generators and the instance catalogue of bench/bench_families.py.

Only the smallest instances are solved; the benchmark itself runs on demand.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bench.families import catalogue  # noqa: E402
from bench.families.hazard_grid import hazard_grid_text, open_cells  # noqa: E402
from bench.families.thesis import gait_text  # noqa: E402
from gaitc.core.spec import parse  # noqa: E402
from gaitc.solver.synthesis import check  # noqa: E402


def _realizable(text: str) -> bool:
    return check(parse(text, "grid.gait", "binary").gr1, "default", 60).realizable


def test_small_hazard_grids_are_realizable() -> None:
    assert _realizable(hazard_grid_text(3))
    assert _realizable(hazard_grid_text(4))


def test_without_its_assumption_the_environment_blocks_a_corridor_forever() -> None:
    text = "".join(line for line in hazard_grid_text(3).splitlines(keepends=True)
                   if not line.startswith("assume"))
    assert not _realizable(text)


def test_entering_a_hazard_is_forbidden() -> None:
    text = hazard_grid_text(3)
    assert "guarantee always (next(h1) & !r1 -> next(!r1))" in text
    spec = parse(text, "grid.gait", "binary").gr1
    hazard = spec.variable("hazard")
    assert hazard is not None and hazard.high == len(open_cells(3, 2))  # one value per cell


@pytest.mark.parametrize("n", [3, 6, 10, 20])
def test_every_open_cell_has_its_own_hazard(n: int) -> None:
    text = hazard_grid_text(n)
    hazards = [line for line in text.splitlines() if line.startswith("hazard ")]
    caches = text.split("\ncache ")[1].split("\n")[0].count("(")
    assert len(hazards) == len(open_cells(n, 2)) == n * n - caches
    assert text == hazard_grid_text(n)


def test_tiny_grids_are_refused() -> None:
    with pytest.raises(ValueError, match="at least 2 x 2"):
        hazard_grid_text(1)


def test_the_thesis_family_compiles_and_is_realizable_when_small() -> None:
    assert _realizable(gait_text(4, 5, 2))


def test_the_catalogue_lists_every_family_in_a_fixed_order(tmp_path: Path) -> None:
    quick = catalogue.instances(tmp_path, quick=True)
    assert [f for f in catalogue.FAMILIES if any(i.family == f for i in quick)] == list(
        catalogue.FAMILIES)
    assert quick == catalogue.instances(tmp_path, quick=True)
    assert all(i.path.exists() for i in quick)
    assert len([i for i in quick if i.family == "corpus"]) == 150
    assert [i.name for i in quick if i.family == "amba"] == ["N=2", "N=3", "N=4", "N=5"]
    full = catalogue.instances(tmp_path, quick=False, families=("thesis", "amba"))
    assert {i.name for i in full} >= {"30x30 h5 binary", "30x30 h5 onehot", "N=10"}
    assert all(i.recorded is not None for i in quick)


def test_the_synth_bench_reads_what_gaitc_synth_reports(tmp_path: Path) -> None:
    """bench/bench_synth.py: every row's spec exists, and a row runs as a user runs it."""
    from bench.bench_synth import rows, synth

    table = rows(tmp_path, quick=True)
    assert all(row.spec.is_file() for row in table)
    robot_b = next(row for row in table if row.name == "thesis_robot_b binary")
    outcome = synth(ROOT, robot_b, tmp_path / "b.json", timeout=120)
    assert outcome.wall is not None and outcome.seconds is not None
    assert outcome.size == "195 nodes"
    assert (tmp_path / "b.json").is_file()
