"""The thesis family: robot A of the thesis (specs/thesis_robot_a.gait) scaled to any grid.

Eight legs, three gaits per direction on two legs each, caches on a lattice of corridors
close enough for the legs' health (a leg survives health-1 moves, two gait families give
2(health-1) moves in a row), hazard sets only off the corridors, goals in two far corners;
so every task is realizable.  :mod:`bench.families.hazard_grid` reuses the robot and the
corridors.
"""

from __future__ import annotations

#: Rows x columns of the benchmark grids and their health levels (the issue's range).
SIZES = [(4, 5), (6, 6), (10, 10), (15, 15), (20, 20), (30, 30)]
HEALTH = [2, 3, 4, 5]

#: The legs of each gait, three gaits per compass direction (as robot A's).
GAITS = {
    "north": ["L4, L6", "L4, L7", "L3, L6"],
    "east": ["L2, L4", "L2, L5", "L1, L4"],
    "south": ["L2, L8", "L3, L8", "L2, L7"],
    "west": ["L6, L8", "L1, L6", "L5, L8"],
}


def corridor_lines(n: int, step: int) -> list[int]:
    """Every ``step``-th index of ``range(n)``, and always the last one."""
    out = list(range(0, n, step))
    return out if out[-1] == n - 1 else [*out, n - 1]


def corridor_step(health: int) -> int:
    """Cells between two caches on a corridor for legs with ``health`` levels."""
    return max(1, 2 * (health - 1))


def robot_lines(name: str, health: int) -> list[str]:
    """The ``robot``, ``legs`` and ``gait`` statements of the scaled robot A."""
    out = [f'robot "{name}"', f"legs L1..L8 health {health}"]
    for direction, pairs in GAITS.items():
        for k, legs in enumerate(pairs):
            out.append(f"gait {direction}_{'abc'[k]} uses {legs} moves {direction}")
    return out


def cells(items: list[tuple[int, int]]) -> str:
    """``(row, col)`` cells as a ``.gait`` list."""
    return ", ".join(f"({i}, {j})" for i, j in items)


def gait_text(rows: int, cols: int, health: int) -> str:
    """A realizable thesis-style task on a ``rows`` x ``cols`` grid (see the module doc)."""
    step = corridor_step(health)
    row_lines, col_lines = corridor_lines(rows, step), corridor_lines(cols, step)
    caches = [(i, j) for i in row_lines for j in col_lines]
    interior = [
        (i, j)
        for i in range(rows)
        for j in range(cols)
        if i not in row_lines and j not in col_lines
    ]
    out = robot_lines(f"bench {rows}x{cols} h{health}", health)
    out += [f"grid {rows} x {cols}", f"cache {cells(caches)}"]
    for name, first in (("blue", 0), ("red", 3)):
        chosen = interior[first::7][:6]
        if chosen:
            out.append(f"hazard {name}: {cells(chosen)}")
    out += ["start (0, 0)", f"visit ({rows - 1}, {cols - 1}), ({rows - 1}, 0) infinitely often"]
    return "\n".join(out) + "\n"
