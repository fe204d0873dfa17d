"""The hazard-grid family: an N x N grid with one environment hazard per open cell (``.gait``).

The robot and the corridors with their caches are those of the thesis family
(:mod:`bench.families.thesis`).  Every cell that is not a cache is open and has its own
hazard set ``h<k>`` holding just that cell, so the environment chooses among N^2 - caches
hazards (one at a time: hazard sets are mutually exclusive in ``.gait``) at every step and
may switch them on and off freely.  A hazard forbids entering its cell: the robot may not
step into a cell whose hazard is on when it arrives (it may stay where it is).  The
environment turns every hazard off infinitely often, so the robot can always wait for its
next corridor cell to clear; the task is therefore realizable, and an explicit controller
needs a node for about every (cell, active hazard, health) combination, so it grows with N^4
and more, while the BDDs stay small.
"""

from __future__ import annotations

from bench.families.thesis import cells, corridor_lines, corridor_step, robot_lines

#: Grid sides of the family in the benchmark table.
SIDES = [3, 4, 6, 8, 10, 15, 20]


def open_cells(n: int, health: int) -> list[tuple[int, int]]:
    """The cells of the ``n`` x ``n`` grid that are not caches, row by row."""
    lines = set(corridor_lines(n, corridor_step(health)))
    return [(i, j) for i in range(n) for j in range(n) if not (i in lines and j in lines)]


def hazard_grid_text(n: int, health: int = 2) -> str:
    """The ``.gait`` text of the ``n`` x ``n`` hazard grid with legs of ``health`` levels."""
    if n < 2:
        raise ValueError(f"a hazard grid needs at least 2 x 2 cells, not {n} x {n}")
    lines = corridor_lines(n, corridor_step(health))
    caches = [(i, j) for i in lines for j in lines]
    hazards = open_cells(n, health)
    out = robot_lines(f"hazard grid {n}x{n} h{health}", health)
    out += [f"grid {n} x {n}", f"cache {cells(caches)}"]
    names = {cell: f"h{cell[0] * n + cell[1]}" for cell in hazards}
    out += [f"hazard {name}: {cells([cell])}" for cell, name in names.items()]
    out += ["start (0, 0)", f"visit ({n - 1}, {n - 1}), ({n - 1}, 0) infinitely often"]
    if names:
        out.append("assume always eventually " + " & ".join(f"!{h}" for h in names.values()))
    for (i, j), name in names.items():
        region = f"r{i * n + j}"
        out.append(f"guarantee always (next({name}) & !{region} -> next(!{region}))")
    return "\n".join(out) + "\n"
