"""Gridworlds in gr1c's shape: integer positions moved by one clause per value, compared only
with constants, on square grids of any side.

gr1c's specification language compares a variable with a number and nothing else, so its
gridworlds spell everything out value by value: ``x = k -> (x' = k - 1 | x' = k | x' = k + 1)``
for every k, the 4-connected rule as one disjunction of ``(x = k & x' = k)`` over every value
of either coordinate (the form of gr1c's ``contrib/gen4g.py``), and the rule that the robot
never meets an obstacle as one clause per cell the obstacle can be on.  A :class:`Gridworld`
is the robot (two system integers starting in the corner (0, 0)), two to four goal cells it
must visit infinitely often, two static blocks it must never enter (rectangles, written with
``<=`` and ``>=`` against constants), and one or two moving obstacles.  Each obstacle is a pair
of environment integers giving its cell within its own square box on the diagonal; it moves
like the robot, starts at its home (the box's corner nearest the robot's start) and returns
there infinitely often.

Realizable by construction: the goals, the start, the blocks and the boxes are pairwise
disjoint, the blocks and boxes do not touch the grid's border nor one another, so the cells
outside them form one connected region holding the start and every goal, and a robot that
never enters a box never meets an obstacle.  (:func:`free_cells_connected` checks the first
part for any layout.)  With ``box`` equal to the side and no liveness the single obstacle may
park on a goal forever, and the game is lost: the tests use that variant to check that the
clash clauses mean what they say.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

from bench.families.gridworld import _moves as moves

#: Sides of the family in the benchmark table, and the quick subset.
SIDES = [64, 128, 256, 512, 1024]
QUICK_SIDES = [64, 128]
BOX = 4  # an obstacle's box is BOX x BOX cells

Cell = tuple[int, int]  # (x, y): column, row


@dataclass(frozen=True)
class Rect:
    """The cells ``x0 <= x < x0 + width`` and ``y0 <= y < y0 + height``."""

    x0: int
    y0: int
    width: int
    height: int

    def covers(self, cell: Cell) -> bool:
        """Whether ``cell`` is one of the rectangle's."""
        x, y = cell
        return self.x0 <= x < self.x0 + self.width and self.y0 <= y < self.y0 + self.height

    def cells(self) -> list[Cell]:
        """Every cell of the rectangle, row by row."""
        return [(self.x0 + i, self.y0 + j)
                for j in range(self.height) for i in range(self.width)]


@dataclass(frozen=True)
class Gridworld:
    """A gr1c-shaped gridworld of ``side`` x ``side`` cells (see the module's docstring)."""

    side: int
    goals: int = 2
    obstacles: int = 1
    box: int = BOX  # each moving obstacle's box is box x box cells
    liveness: bool = True  # each moving obstacle returns to its home infinitely often

    @property
    def name(self) -> str:
        extra = "" if self.box == BOX else f" box {self.box}"
        extra += "" if self.liveness else " no liveness"
        return f"{self.side}x{self.side} g{self.goals} o{self.obstacles}{extra}"

    def goal_cells(self) -> list[Cell]:
        """The goals: the far corner, the start's neighbour, then the other two corners."""
        n = self.side - 1
        return [(n, n), (1, 0), (0, n), (n, 0)][:self.goals]

    def blocks(self) -> list[Rect]:
        """The static blocks, off the diagonal: an eighth to three eighths of the side from the
        top-left and bottom-right corners (x, y swapped)."""
        lo, size = self.side // 8, self.side // 4
        return [Rect(lo, self.side - lo - size, size, size),
                Rect(self.side - lo - size, lo, size, size)]

    def boxes(self) -> list[Rect]:
        """Each moving obstacle's box: on the diagonal, at a third and two thirds of the side
        (at the middle for one obstacle), kept inside the grid."""
        out = []
        for k in range(self.obstacles):
            at = (k + 1) * self.side // (self.obstacles + 1) - self.box // 2
            at = min(max(at, 0), self.side - self.box)
            out.append(Rect(at, at, self.box, self.box))
        return out


def check_layout(world: Gridworld) -> None:
    """Refuse parameters the family is not defined for (raises ``ValueError``)."""
    if world.side < 16 or not 2 <= world.goals <= 4 or not 1 <= world.obstacles <= 2:
        raise ValueError("a gr1c gridworld needs at least 16 cells a side, two to four goals "
                         "and one or two obstacles")
    if not 1 <= world.box <= world.side:
        raise ValueError(f"an obstacle's box of side {world.box} does not fit the grid")


def free_cells_connected(world: Gridworld) -> bool:
    """Whether the cells outside the blocks and boxes are one 4-connected region holding the
    start and every goal (a breadth-first search; meant for small sides)."""
    walls = world.blocks() + world.boxes()
    free = {(x, y) for x in range(world.side) for y in range(world.side)
            if not any(r.covers((x, y)) for r in walls)}
    if (0, 0) not in free or not all(g in free for g in world.goal_cells()):
        return False
    seen, todo = {(0, 0)}, deque([(0, 0)])
    while todo:
        x, y = todo.popleft()
        for step in ((x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)):
            if step in free and step not in seen:
                seen.add(step)
                todo.append(step)
    return seen == free


def one_axis(first: tuple[str, int], second: tuple[str, int]) -> str:
    """The 4-connected rule as gr1c writes it: one of the two variables (each given with its
    number of values) keeps its value, one disjunct per value."""
    terms = [f"({var} = {k} & {var}' = {k})" for var, size in (first, second)
             for k in range(size)]
    return " | ".join(terms)


def point(x: str, y: str, cell: Cell, primed: bool = True) -> str:
    """``x = cx & y = cy``, primed by default."""
    tick = "'" if primed else ""
    return f"{x}{tick} = {cell[0]} & {y}{tick} = {cell[1]}"


def outside(rect: Rect, x: str = "x", y: str = "y") -> str:
    """The next position is not in ``rect`` (constant comparisons only)."""
    return (f"!({x}' >= {rect.x0} & {x}' <= {rect.x0 + rect.width - 1} & "
            f"{y}' >= {rect.y0} & {y}' <= {rect.y0 + rect.height - 1})")


def gr1c_gridworld_text(world: Gridworld) -> str:
    """The structured-SLUGS text of ``world``."""
    check_layout(world)
    n = world.side
    inputs: list[str] = []
    env_init: list[str] = []
    env_trans: list[str] = []
    env_live: list[str] = []
    clash: list[str] = []
    for k, box in enumerate(world.boxes()):
        ox, oy = f"ox{k}", f"oy{k}"
        inputs += [f"{ox}:0...{box.width - 1}", f"{oy}:0...{box.height - 1}"]
        env_init += [f"{ox} = 0", f"{oy} = 0"]
        env_trans += moves(ox, box.width) + moves(oy, box.height)
        env_trans.append(one_axis((ox, box.width), (oy, box.height)))
        if world.liveness:
            env_live.append(point(ox, oy, (0, 0), primed=False))
        # the robot's next cell is never the obstacle's next cell
        clash += [f"!({point('x', 'y', (box.x0 + i, box.y0 + j))} & "
                  f"{point(ox, oy, (i, j))})"
                  for j in range(box.height) for i in range(box.width)]
    out = [f"# gr1c-shaped gridworld {world.name}", "", "[INPUT]", *inputs, ""]
    out += ["[OUTPUT]", f"x:0...{n - 1}", f"y:0...{n - 1}", ""]
    out += ["[ENV_INIT]", *env_init, "", "[SYS_INIT]", "x = 0", "y = 0", ""]
    out += ["[ENV_TRANS]", *env_trans, ""]
    out += ["[SYS_TRANS]", *moves("x", n), *moves("y", n), one_axis(("x", n), ("y", n))]
    out += [outside(block) for block in world.blocks()]
    out += [*clash, ""]
    if env_live:
        out += ["[ENV_LIVENESS]", *env_live, ""]
    out += ["[SYS_LIVENESS]"]
    out += [point("x", "y", goal, primed=False) for goal in world.goal_cells()]
    return "\n".join([*out, ""])
