"""The benchmark families in the peers' shapes: gr1c's gridworlds and troll games and SLUGS's
evasion game (bench/families/gr1c_gridworld.py, trolls.py, evasion_requests.py).

The texts load, the smallest instances are solved by the embedded solver, and each family is
checked to mean what it says by a variant that must be lost (an obstacle or troll without its
liveness) and by its layout.  The benchmark itself runs on demand.
"""

from __future__ import annotations

import re
import sys
from collections import Counter
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import gaitc  # noqa: E402
from bench.families import catalogue  # noqa: E402
from bench.families.evasion_requests import SIZES as EVASION_SIZES  # noqa: E402
from bench.families.evasion_requests import Evasion, evasion_requests_text  # noqa: E402
from bench.families.gr1c_gridworld import (  # noqa: E402
    Gridworld,
    Rect,
    free_cells_connected,
    gr1c_gridworld_text,
)
from bench.families.trolls import Trolls, trolls_text  # noqa: E402
from gaitc.ir.spec import GR1Spec  # noqa: E402
from slugs_bridge.formats import load_spec_file  # noqa: E402

PEER_EXAMPLES = ROOT / "tests" / "data" / "peer_examples"
BASIC_EVASION = PEER_EXAMPLES / "EvasionOnGrid__basicEvasion.structuredslugs"
SECTIONS = ("env_init", "sys_init", "env_trans", "sys_trans", "env_liveness", "sys_liveness")


def _file(tmp_path: Path, stem: str, text: str) -> Path:
    path = tmp_path / f"{stem}.structuredslugs"
    path.write_text(text, encoding="utf-8")
    return path


def _realizable(path: Path) -> bool:
    return gaitc.check(gaitc.load(path)).realizable


def _clauses(spec: GR1Spec) -> dict[str, Counter[object]]:
    return {s: Counter(c.formula for c in getattr(spec, s)) for s in SECTIONS}


# ---------------------------------------------------------------- loading and solving
@pytest.mark.parametrize(("stem", "text", "realizable"), [
    ("grid16", gr1c_gridworld_text(Gridworld(16)), True),
    ("grid16_4goals_2obstacles", gr1c_gridworld_text(Gridworld(16, 4, 2)), True),
    ("trolls8", trolls_text(Trolls(8)), True),
    ("trolls8_3goals", trolls_text(Trolls(8, goals=3)), True),
    ("evasion8x8", evasion_requests_text(Evasion(8, 8)), True),
])
def test_the_smallest_instances_load_and_are_realizable(tmp_path: Path, stem: str, text: str,
                                                        realizable: bool) -> None:
    path = _file(tmp_path, stem, text)
    spec = load_spec_file(str(path))
    assert spec.sys_liveness and spec.env_liveness
    assert _realizable(path) is realizable


def test_the_benchmark_sizes_load(tmp_path: Path) -> None:
    for name, text in [("grid64", gr1c_gridworld_text(Gridworld(64, 4, 2))),
                       ("trolls32", trolls_text(Trolls(32))),
                       ("evasion48x16", evasion_requests_text(Evasion(48, 16)))]:
        assert load_spec_file(str(_file(tmp_path, name, text))).outputs


def test_the_texts_are_deterministic() -> None:
    assert gr1c_gridworld_text(Gridworld(32, 3, 2)) == gr1c_gridworld_text(Gridworld(32, 3, 2))
    assert trolls_text(Trolls(16)) == trolls_text(Trolls(16))
    assert evasion_requests_text(Evasion(32, 16)) == evasion_requests_text(Evasion(32, 16))


# ---------------------------------------------------------------- what the families mean
def test_a_free_obstacle_without_liveness_parks_on_a_goal(tmp_path: Path) -> None:
    """The clash clauses bite: an obstacle that may go anywhere and never has to leave wins;
    given its liveness, or kept in its box, it loses."""
    free = Gridworld(16, box=16, liveness=False)
    assert not _realizable(_file(tmp_path, "free", gr1c_gridworld_text(free)))
    assert _realizable(_file(tmp_path, "free_live",
                             gr1c_gridworld_text(Gridworld(16, box=16))))
    assert _realizable(_file(tmp_path, "boxed", gr1c_gridworld_text(
        Gridworld(16, liveness=False))))


def test_a_troll_without_liveness_guards_its_band(tmp_path: Path) -> None:
    assert not _realizable(_file(tmp_path, "t", trolls_text(Trolls(8, liveness=False))))


def test_an_obstacle_that_never_comes_home_blocks_the_deliveries(tmp_path: Path) -> None:
    game = Evasion(8, 8, liveness=False)
    assert not _realizable(_file(tmp_path, "e", evasion_requests_text(game)))


@pytest.mark.parametrize("world", [Gridworld(16), Gridworld(16, 4, 2), Gridworld(64, 3, 1),
                                   Gridworld(128, 4, 2)], ids=lambda w: w.name)
def test_gridworld_layouts_fit_and_leave_a_connected_free_region(world: Gridworld) -> None:
    grid = Rect(0, 0, world.side, world.side)
    areas = world.blocks() + world.boxes()
    assert all(grid.covers(c) for r in areas for c in r.cells())
    taken = [c for r in areas for c in r.cells()]
    assert len(taken) == len(set(taken))  # blocks and boxes are disjoint
    assert len(set(world.goal_cells())) == world.goals
    assert all(grid.covers(g) and not any(r.covers(g) for r in areas)
               for g in world.goal_cells())
    assert free_cells_connected(world)


def test_gridworld_clash_clauses_cover_every_cell_of_every_box() -> None:
    world = Gridworld(32, 2, 2)
    text = gr1c_gridworld_text(world)
    assert sum(line.startswith("!(x' = ") and "& ox" in line
               for line in text.splitlines()) == 2 * 4 * 4
    for box in world.boxes():
        assert f"!(x' = {box.x0} & y' = {box.y0} & " in text


@pytest.mark.parametrize("text", [gr1c_gridworld_text(Gridworld(32, 4, 2)),
                                  trolls_text(Trolls(16, goals=3))],
                         ids=["gridworld", "trolls"])
def test_gr1c_shapes_compare_variables_with_constants_only(text: str) -> None:
    """What gr1c can write: every comparison has a number on its right."""
    body = [line.replace("<->", " iff ").replace("->", " implies ")
            for line in text.splitlines() if line and not line.startswith(("#", "["))]
    comparisons = [m for line in body
                   for m in re.findall(r"(?:!=|<=|>=|=|<|>)\s*([^\s()&|]+)", line)]
    assert comparisons and all(value.isdigit() for value in comparisons)
    assert "+" not in text


def test_troll_bands_span_the_grid_between_free_strips() -> None:
    for side in (8, 16, 32, 64, 128):
        game = Trolls(side)
        first, second = game.band_rows()
        assert first >= 1 and first + game.height < second
        assert second + game.height < side  # a free strip below the second band
        rows = {r for top in (first, second) for r in range(top, top + game.height)}
        assert not any(y in rows for _, y in game.goal_cells())
        assert side - 1 > game.height  # the trolls' homes are farther than a band is high


def test_at_24_by_8_the_evasion_game_is_slugs_basic_evasion(tmp_path: Path) -> None:
    ours = load_spec_file(str(_file(tmp_path, "e", evasion_requests_text(Evasion(24, 8)))))
    theirs = load_spec_file(str(BASIC_EVASION))
    assert ours.inputs == theirs.inputs and ours.outputs == theirs.outputs
    assert _clauses(ours) == _clauses(theirs)


def test_slugs_recorded_basic_evasion_as_realizable() -> None:
    rows = [line.split("\t") for line in
            (PEER_EXAMPLES / "verdicts.tsv").read_text(encoding="utf-8").splitlines()
            if line.strip() and not line.startswith("#")]
    assert [row[:3] for row in rows] == [[BASIC_EVASION.name, "realizable", "realizable"]]
    assert (24, 8) in catalogue.CONFIRMED_EVASION


def _footprint(x: int, y: int) -> set[tuple[int, int]]:
    return {(x + i, y + j) for i in (0, 1) for j in (0, 1)}


@pytest.mark.parametrize("size", EVASION_SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
def test_evasion_layouts_leave_the_obstacle_its_home(size: tuple[int, int]) -> None:
    """The obstacle's start and home are legal for it (else the environment could never meet
    its liveness and every robot would win), and the areas lie between the walls."""
    game = Evasion(*size)
    (c0, c1), (top, bottom) = game.wall_columns, game.wall_rows
    (b0, b1) = game.block_columns
    solid = {(x, y) for x in range(c0, c1 + 1) for y in (top, bottom)}
    solid |= {(x, y) for x in range(b0, b1 + 1) for y in range(top + 1, bottom)}
    for x, y in (game.start, game.home):
        cells = _footprint(x, y)
        assert not cells & solid
        assert all(0 <= cx < game.width and 0 <= cy < game.height for cx, cy in cells)
    for first, last in game.areas():
        assert c0 <= first <= last <= c1 and not (b0 <= first <= b1 or b0 <= last <= b1)
    assert top + 1 < bottom  # rows between the walls


def test_tiny_grids_are_refused() -> None:
    with pytest.raises(ValueError, match="at least 16 cells"):
        gr1c_gridworld_text(Gridworld(8))
    with pytest.raises(ValueError, match="at least 8 cells"):
        trolls_text(Trolls(4))
    with pytest.raises(ValueError, match="at least 8 x 8"):
        evasion_requests_text(Evasion(24, 4))


# ---------------------------------------------------------------- the catalogue
def test_the_catalogue_lists_the_peer_families(tmp_path: Path) -> None:
    families = ("gr1c-grid", "trolls", "evasion")
    quick = catalogue.instances(tmp_path, quick=True, families=families)
    assert [i.family for i in quick] == sorted([i.family for i in quick], key=families.index)
    assert all(i.path.exists() and i.recorded is True for i in quick)
    assert [i.name for i in quick if i.family == "evasion"] == ["8x8", "12x8"]
    full = catalogue.instances(tmp_path, quick=False, families=families)
    names = {(i.family, i.name): i.recorded for i in full}
    assert names[("gr1c-grid", "1024x1024 g2 o1")] is True
    assert names[("evasion", "24x8")] is True
    assert names[("evasion", "48x16")] is None
    assert sum(i.family == "trolls" for i in full) == 10
