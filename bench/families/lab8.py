"""The 8-leg lab robot of issues 34 and 35: health 3 (or as asked), twelve two-leg gaits.

:data:`GAITS` is its gait list; :func:`lab8` puts it on a rows x cols grid with two caches,
a spill hazard down one column, fumes on one cell and goals at opposite corners (the
realizable family of ``bench_compact.py``).
"""

from __future__ import annotations

GAITS = """gait n1 uses L1, L5 moves north
gait n2 uses L2, L6 moves north
gait n3 uses L3, L7 moves north
gait s1 uses L4, L8 moves south
gait s2 uses L1, L6 moves south
gait s3 uses L2, L7 moves south
gait e1 uses L3, L8 moves east
gait e2 uses L4, L5 moves east
gait e3 uses L1, L7 moves east
gait w1 uses L2, L8 moves west
gait w2 uses L3, L5 moves west
gait w3 uses L4, L6 moves west
"""


def lab8(rows: int, cols: int, health: int = 3) -> str:
    """The robot on a rows x cols grid (see the module text)."""
    cells = [f"c{r}_{c}" for r in range(rows) for c in range(cols)]
    mid = cols // 2
    spill = ", ".join(f"c{r}_{mid + 1}" for r in range(1, rows))
    return (f'robot "lab8 {rows}x{cols}"\nlegs L1..L8 health {health}\n{GAITS}'
            f"grid {rows} x {cols} cells {', '.join(cells)}\n"
            f"cache c0_0, c{rows - 1}_{mid}\n"
            f"hazard spill: {spill}\nhazard fumes: c{rows // 2}_1\n"
            f"start c0_0\nvisit c{rows - 1}_{cols - 1}, c0_0 infinitely often\n")
