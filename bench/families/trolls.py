"""Troll games in gr1c's shape: a robot crosses two bands, each patrolled by a troll, to visit
goals at opposite corners of a square grid, and never shares a cell with a troll.

Written as gr1c writes gridworlds (constant comparisons only, one move clause per value, the
clash as one clause per cell of a troll's band; see :mod:`bench.families.gr1c_gridworld`).
The grid of ``side`` x ``side`` cells has, from top to bottom, a free strip, troll 0's band,
a free strip, troll 1's band and a free strip; each band is ``side // 8`` rows high (at least
two) and spans the grid's whole width, so the robot must cross both.  A troll is a pair of
environment integers, its column and its row within its band; it moves to a neighbouring
cell of its band or stays, and comes home infinitely often: troll 0's home is the band's
left end, troll 1's the right end.  The robot's goals are the top-left corner (its start),
the bottom-right corner and, from three goals on, the middle of the middle strip.

Realizable by construction: the robot waits just outside a band at the end opposite the
troll's home, seeing the troll's move before it makes its own; once the troll is home it
crosses straight through in as many steps as the band has rows, while the troll needs
``side - 1`` steps to reach that column, more than the band's height.  Without the trolls'
liveness the game is lost: a troll mirrors the robot's column in its band's first row, and a
robot that sees the troll's move before its own still never finds the way in free.
"""

from __future__ import annotations

from dataclasses import dataclass

from bench.families.gr1c_gridworld import one_axis, point
from bench.families.gridworld import _moves as moves

#: Sides of the family in the benchmark table, and the quick subset.
SIDES = [8, 16, 32, 64, 128]
QUICK_SIDES = [8, 16, 32]


@dataclass(frozen=True)
class Trolls:
    """A troll game on ``side`` x ``side`` cells (see the module's docstring)."""

    side: int
    goals: int = 2
    liveness: bool = True  # each troll comes home infinitely often

    @property
    def name(self) -> str:
        return f"{self.side}x{self.side} g{self.goals}" + ("" if self.liveness
                                                         else " no liveness")

    @property
    def height(self) -> int:
        """The rows of each troll's band."""
        return max(2, self.side // 8)

    def band_rows(self) -> list[int]:
        """The first row of each troll's band; the three free strips between and around them
        are at least one row high, the middle one at least two."""
        strip = (self.side - 2 * self.height) // 3
        return [strip, self.side - strip - self.height]

    def homes(self) -> list[tuple[int, int]]:
        """Each troll's home as (column, row within its band): troll 0 at the left end of its
        band's first row, troll 1 at the right end of its band's last row."""
        return [(0, 0), (self.side - 1, self.height - 1)]

    def goal_cells(self) -> list[tuple[int, int]]:
        """The top-left and bottom-right corners, then the middle of the middle strip."""
        n = self.side - 1
        return [(0, 0), (n, n), (self.side // 2, self.side // 2)][:self.goals]


def trolls_text(game: Trolls) -> str:
    """The structured-SLUGS text of ``game``."""
    if game.side < 8 or not 2 <= game.goals <= 3:
        raise ValueError("a troll game needs at least 8 cells a side and two or three goals")
    n, h = game.side, game.height
    inputs: list[str] = []
    env_init: list[str] = []
    env_trans: list[str] = []
    env_live: list[str] = []
    clash: list[str] = []
    for k, (top, home) in enumerate(zip(game.band_rows(), game.homes(), strict=True)):
        tx, ty = f"troll{k}x", f"troll{k}y"
        inputs += [f"{tx}:0...{n - 1}", f"{ty}:0...{h - 1}"]
        env_init.append(point(tx, ty, home, primed=False))
        env_trans += moves(tx, n) + moves(ty, h)
        env_trans.append(one_axis((tx, n), (ty, h)))
        if game.liveness:
            env_live.append(point(tx, ty, home, primed=False))
        # the robot's next cell is never the troll's next cell
        clash += [f"!({point('x', 'y', (i, top + j))} & {point(tx, ty, (i, j))})"
                  for j in range(h) for i in range(n)]
    out = [f"# troll game {game.name}", "", "[INPUT]", *inputs, ""]
    out += ["[OUTPUT]", f"x:0...{n - 1}", f"y:0...{n - 1}", ""]
    out += ["[ENV_INIT]", *env_init, "", "[SYS_INIT]", "x = 0", "y = 0", ""]
    out += ["[ENV_TRANS]", *env_trans, ""]
    out += ["[SYS_TRANS]", *moves("x", n), *moves("y", n), one_axis(("x", n), ("y", n))]
    out += [*clash, ""]
    if env_live:
        out += ["[ENV_LIVENESS]", *env_live, ""]
    out += ["[SYS_LIVENESS]"]
    out += [point("x", "y", goal, primed=False) for goal in game.goal_cells()]
    return "\n".join([*out, ""])
