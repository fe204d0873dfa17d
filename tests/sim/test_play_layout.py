"""The terminal player's map at any width (issue 51): every row of cells on one line.

A 6-column map of two rooms and a corridor (long cell names, blocked cells), a 3 x 12 grid
and a 16 x 2 grid are played under Textual's pilot at 80 x 24 and 120 x 30. At every step
the rendered screen is read back: each cell's text (robot mark, label, marks) sits in its
grid column on its grid row's line, the robot's ``@`` in front of its own cell, and the map
scrolls (across and down) to keep the robot in view when it does not fit.
"""

from __future__ import annotations

import asyncio
import io
from dataclasses import dataclass
from pathlib import Path

import pytest

import gaitc
from gaitc.play.mapgrid import MapGrid, short_names
from ltlcompiler.frontend import load_model

textual = pytest.importorskip("textual")

LEGS = """\
legs L1..L4 health 2
gait north uses L1 moves north
gait south uses L2 moves south
gait east  uses L3 moves east
gait west  uses L4 moves west
assume always !failed(L1) & !failed(L2) & !failed(L3) & !failed(L4)
"""
ROOM_NAMES = [f"{'westroom' if c < 2 else 'corridor' if c < 4 else 'eastroom'}_{r}{c}"
              for r in range(4) for c in range(6)]
# two rooms of 4 x 2 cells joined by a corridor along row 1
ROOMS = f"""robot "two rooms"
{LEGS}grid 4 x 6 cells {", ".join(ROOM_NAMES)}
block (0, 2), (0, 3), (2, 2), (2, 3), (3, 2), (3, 3)
cache westroom_00
start westroom_00
visit westroom_30, eastroom_35 infinitely often
"""
WIDE = f"""robot "wide"
{LEGS}grid 3 x 12
cache r0, r11
start r0
visit r11, r24 infinitely often
"""
TALL = f"""robot "tall"
{LEGS}grid 16 x 2
cache r0
start r0
visit r31, r1 infinitely often
"""
#: The marks of each spec's cells (cache +, goal *), worked out by hand.
MARKS = {ROOMS: {"westroom_00": "+", "westroom_30": "*", "eastroom_35": "*"},
         WIDE: {"r0": "+", "r11": "+*", "r24": "*"},
         TALL: {"r0": "+", "r31": "*", "r1": "*"}}


def _short(name: str) -> str:
    """The label a cell gets when its name does not fit (worked out by hand)."""
    if "_" in name:  # westroom_12 -> w12
        room, number = name.split("_")
        return room[0] + number
    return name[1:]  # r17 -> 17


@dataclass
class Case:
    text: str
    size: tuple[int, int]
    short: bool  # the labels are the short names
    scrolls: tuple[bool, bool]  # the map scrolls across, down


CASES = {
    "rooms-80x24": Case(ROOMS, (80, 24), True, (False, False)),
    "rooms-120x30": Case(ROOMS, (120, 30), False, (False, False)),
    "wide-80x24": Case(WIDE, (80, 24), True, (True, False)),
    "wide-120x30": Case(WIDE, (120, 30), False, (False, False)),
    "tall-80x24": Case(TALL, (80, 24), False, (False, True)),
}


def _screen(app: object, size: tuple[int, int]) -> list[str]:
    """The app's screen as lines of plain text, as a terminal of ``size`` shows it."""
    from rich.console import Console

    console = Console(width=size[0], height=size[1], file=io.StringIO(), force_terminal=True,
                      color_system=None, record=True)
    console.print(app.screen._compositor.render_update(full=True))  # type: ignore[attr-defined]
    return console.export_text().splitlines()


def _check_map(app: object, size: tuple[int, int], short: bool, marks: dict[str, str]
               ) -> tuple[int, int]:
    """Check the rendered map against the cells of the robot's spec; the map's scroll
    offset. Each cell must read ``@label+`` (or `` label+``) padded to the cell width, at
    its column's place on its row's line, as far as the map's viewport shows it."""
    from textual.containers import ScrollableContainer

    lines = _screen(app, size)
    grid: MapGrid = app.mapgrid  # type: ignore[attr-defined]
    box = app.query_one("#map", ScrollableContainer)  # type: ignore[attr-defined]
    view = box.scrollable_content_region
    sx, sy = box.scroll_offset
    here = app.player.state  # type: ignore[attr-defined]
    width = grid.width
    seen = 0
    for name, (row, col) in grid.cells.items():
        label = _short(name) if short else name
        text = (("@" if here is not None and name == here.region else " ") + label
                + marks.get(name, "")).ljust(width)
        assert len(text) == width  # the cell's text fits its column
        y = view.y + row - sy
        if not view.y <= y < view.bottom:
            assert here is None or name != here.region, "the robot is out of view"
            continue
        start = view.x + col * width - sx  # the cell's first column on the screen
        left, right = max(start, view.x), min(start + width, view.right)
        if left >= right:
            assert here is None or name != here.region, "the robot is out of view"
            continue
        shown = lines[y][left:right]
        assert shown == text[left - start:right - start], (name, row, col, lines[y])
        seen += 1
    assert seen >= 4
    if here is not None:  # one robot mark among the rows of cells, in front of its cell
        rows = [lines[view.y + r - sy][view.x:view.right] for r in range(grid.rows)
                if view.y <= view.y + r - sy < view.bottom]
        assert sum(line.count("@") for line in rows) == 1, rows
        row, col = grid.cells[here.region]
        assert lines[view.y + row - sy][view.x + col * width - sx] == "@"
    return sx, sy


@pytest.mark.parametrize("name", list(CASES))
def test_every_row_of_cells_is_one_line_and_the_robot_is_in_its_column(
        name: str, tmp_path: Path) -> None:
    from gaitc.play.terminal import PlayApp

    case = CASES[name]
    spec = tmp_path / f"{name.split('-')[0]}.gait"
    spec.write_text(case.text, encoding="utf-8")
    player = gaitc.player(spec)
    app = PlayApp(player)
    offsets: list[tuple[int, int]] = []
    cells: set[tuple[int, int]] = set()

    def visit() -> None:
        assert player.state is not None
        cells.add(app.mapgrid.cells[player.state.region])

    async def script() -> None:
        async with app.run_test(size=case.size) as pilot:
            await pilot.pause()
            offsets.append(_check_map(app, case.size, case.short, MARKS[case.text]))
            await pilot.press("1")
            visit()
            for _ in range(30):
                await pilot.press("a", "1", "enter")  # the strongest pilot plays one step
                await pilot.pause()
                offsets.append(_check_map(app, case.size, case.short, MARKS[case.text]))
                visit()
            await pilot.press("q")

    asyncio.run(script())
    assert app.mapgrid.abbreviated is case.short
    grid = app.mapgrid
    assert len({c for _, c in cells}) >= min(4, grid.cols)  # the robot went around
    assert len({r for r, _ in cells}) >= min(4, grid.rows)
    across, down = case.scrolls
    assert any(x > 0 for x, _ in offsets) is across
    assert any(y > 0 for _, y in offsets) is down


def test_the_map_takes_the_room_a_larger_terminal_gives(tmp_path: Path) -> None:
    """Growing the terminal from 80 x 24 to 120 x 30 gives the 3 x 12 map back its names;
    at 80 x 24 tab focuses the map and the arrows scroll it across."""
    from textual.containers import ScrollableContainer

    from gaitc.play.terminal import PlayApp

    spec = tmp_path / "wide.gait"
    spec.write_text(WIDE, encoding="utf-8")
    app = PlayApp(gaitc.player(spec))
    seen: list[object] = []

    async def script() -> None:
        async with app.run_test(size=(80, 24)) as pilot:
            await pilot.press("1")
            await pilot.pause()
            box = app.query_one("#map", ScrollableContainer)
            seen.append((app.mapgrid.abbreviated, box.scroll_offset.x))
            await pilot.press("tab", "right", "right", "right")
            await pilot.pause()
            seen.append((box.has_focus, box.scroll_offset.x))
            await pilot.resize_terminal(120, 30)
            await pilot.pause()
            seen.append(app.mapgrid.abbreviated)
            _check_map(app, (120, 30), False, MARKS[WIDE])

    asyncio.run(script())
    assert seen[0] == (True, 0)
    assert seen[1] == (True, 3)
    assert seen[2] is False


def test_short_names_are_unambiguous_and_the_legend_spells_them_out(tmp_path: Path) -> None:
    names = short_names([f"r{i}" for i in range(36)])
    assert names.labels == {f"r{i}": str(i) for i in range(36)}
    assert names.key == ("names less 'r'",)
    rooms = short_names(ROOM_NAMES)
    assert rooms.labels == {name: _short(name) for name in ROOM_NAMES}
    assert rooms.key == ("c02: corridor_02", "c: corridor", "e: eastroom", "w: westroom")
    words = short_names(["hall", "hallway", "lab", "lobby"])
    assert words.labels == {"hall": "hall", "hallway": "hallw", "lab": "la", "lobby": "lo"}
    assert words.key == ("hallw: hallway", "la: lab", "lo: lobby")
    for case in (["hall", "hallway", "lab", "lobby"], ROOM_NAMES, ["a_1_2", "a_12", "a"]):
        labels = short_names(case).labels
        assert len(set(labels.values())) == len(case) and all(labels.values())
    spec = tmp_path / "rooms.gait"
    spec.write_text(ROOMS, encoding="utf-8")
    grid = MapGrid(load_model(str(spec))[0])
    assert not grid.fit(6 * 14) and grid.width == 14  # "@westroom_00+ "
    assert grid.text().splitlines()[1] == (
        " westroom_10   westroom_11   corridor_12   corridor_13   eastroom_14   eastroom_15")
    assert not grid.fit(6 * 13) and grid.width == 13  # names before the blank after each
    assert grid.text().splitlines()[1] == (
        " westroom_10  westroom_11  corridor_12  corridor_13  eastroom_14  eastroom_15")
    assert grid.fit(6 * 13 - 1) and grid.width == 6
    assert grid.text("corridor_12").splitlines() == [
        " w00+  w01               e04   e05",
        " w10   w11  @c12   c13   e14   e15",
        " w20   w21               e24   e25",
        " w30*  w31               e34   e35*"]
    assert grid.legend()[2:] == ["c12: corridor_12  c: corridor", "e: eastroom  w: westroom"]
    assert grid.fit(6 * 5) and grid.width == 5 and grid.fit(1) and grid.width == 5
