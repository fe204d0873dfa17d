"""Evasion games in the shape of SLUGS's EvasionOnGrid example (``basicEvasion``), at any
width and height from 8 x 8 on.

The robot's position is an *input*: the environment moves it by arithmetic as the system's
``left``/``right``/``up``/``down`` flags of the step before say.  Two horizontal walls and a
block between them are cells the robot must not be on; a moving obstacle of 2 x 2 cells (its
upper-left corner ``mox6``, ``moy6``) moves by one cell along one axis a step, never overlaps
the walls or the block, and comes home (below the block, in the bottom lane) infinitely
often; the robot must never be under it.  Two request bits are the system's goals:
``requestPending1`` rises with the environment's ``deliveryrequest2`` and is cleared in the
pickup area left of the block; ``requestPending2`` is raised there and cleared in the drop
area right of the block, so each delivery takes the robot around a wall and through the
obstacle's reach.  ``door4``, ``pickup`` and ``drop`` are kept from the example (the example
leaves the door unused and forbids only picking up and dropping at once).

Scaling, as read off the example at 24 x 8: the walls lie on rows ``H // 4`` and
``H - 1 - H // 4`` and span columns ``W // 6`` to ``W - 1 - W // 6``; the block is
``max(1, W // 12)`` columns wide at the middle and fills the rows between the walls, the
pickup and drop areas are as wide as the block, beside it; the obstacle starts at
``(2W // 3, H - 2)`` and its home is ``(block's first column, H - 2)``.  At 24 x 8 the text
is the example's specification (same clauses in every section; the tests compare them).
Realizability is not argued by construction: the robot must commit to each move before it
sees the obstacle's, and whether it can always slip past depends on the lanes' widths; the
catalogue records the sizes the embedded solver and SLUGS both found realizable.
"""

from __future__ import annotations

from dataclasses import dataclass

#: (width, height) of the family in the benchmark table, and the quick subset.
SIZES = [(8, 8), (12, 8), (16, 8), (24, 8), (32, 8), (32, 16), (48, 16)]
QUICK_SIZES = [(8, 8), (12, 8)]


@dataclass(frozen=True)
class Evasion:
    """An evasion game on a ``width`` x ``height`` grid (see the module's docstring)."""

    width: int
    height: int
    liveness: bool = True  # the moving obstacle comes home infinitely often

    @property
    def name(self) -> str:
        return f"{self.width}x{self.height}" + ("" if self.liveness else " no liveness")

    @property
    def wall_rows(self) -> tuple[int, int]:
        return self.height // 4, self.height - 1 - self.height // 4

    @property
    def wall_columns(self) -> tuple[int, int]:
        """The first and last column of both walls."""
        return self.width // 6, self.width - 1 - self.width // 6

    @property
    def block_columns(self) -> tuple[int, int]:
        """The first and last column of the block between the walls."""
        wide = max(1, self.width // 12)
        first = self.width // 2 - wide // 2
        return first, first + wide - 1

    def areas(self) -> tuple[tuple[int, int], tuple[int, int]]:
        """The columns (first, last) of the pickup area and of the drop area; both span the
        rows between the walls."""
        first, last = self.block_columns
        wide = last - first + 1
        return (first - wide, first - 1), (last + 1, last + wide)

    @property
    def start(self) -> tuple[int, int]:
        """The moving obstacle's first position."""
        return 2 * self.width // 3, self.height - 2

    @property
    def home(self) -> tuple[int, int]:
        """The moving obstacle's home."""
        return self.block_columns[0], self.height - 2


def _in_area(columns: tuple[int, int], rows: tuple[int, int]) -> str:
    return f"(x >= {columns[0]} & x <= {columns[1]}) & (y >= {rows[0]} & y <= {rows[1]})"


def evasion_requests_text(game: Evasion) -> str:
    """The structured-SLUGS text of ``game``."""
    if game.width < 8 or game.height < 8:
        raise ValueError("an evasion game needs at least 8 x 8 cells (below, the obstacle's "
                         "home or the areas between the walls do not fit)")
    w, h = game.width - 1, game.height - 1
    top, bottom = game.wall_rows
    c0, c1 = game.wall_columns
    b0, b1 = game.block_columns
    inner = (top + 1, bottom - 1)  # the rows between the walls
    pickup, drop = (_in_area(cols, inner) for cols in game.areas())
    out = [f"# evasion game {game.name} in the shape of SLUGS's basicEvasion", ""]
    out += ["[INPUT]", f"x:0...{w}", f"y:0...{h}", f"mox6:0...{w}", f"moy6:0...{h}",
            "deliveryrequest2", "door4", ""]
    out += ["[OUTPUT]", "left", "right", "up", "down", "pickup", "drop", "requestPending1",
            "requestPending2", ""]
    out += ["[ENV_INIT]", "x = 0", "y = 0", f"mox6 = {game.start[0]}",
            f"moy6 = {game.start[1]}", "! deliveryrequest2", ""]
    out += ["[SYS_INIT]", "! left", "! right", "! up", "! down", "! pickup", "! drop", ""]
    out += ["[ENV_TRANS]", "# the robot moves as its flags of the step before say",
            "x > 0 & left -> x' + 1 = x", f"x < {w} & right -> x' = x + 1",
            "y > 0 & up -> y' + 1 = y", f"y < {h} & down -> y' = y + 1",
            "(! left & ! right) -> x' = x", "(! up & ! down) -> y' = y",
            "# the obstacle moves by at most one cell, along one axis",
            "mox6' <= mox6 + 1", "moy6' <= moy6 + 1", "mox6 <= mox6' + 1", "moy6 <= moy6' + 1",
            "mox6' = mox6 | moy6' = moy6",
            "# and never overlaps a wall or the block, nor leaves the grid at the bottom",
            f"mox6' < {c0 - 1} | mox6' > {c1} | (moy6' != {top} & moy6' != {top - 1})",
            f"mox6' < {c0 - 1} | mox6' > {c1} | (moy6' != {bottom} & moy6' != {bottom - 1})",
            f"mox6' < {b0 - 1} | mox6' > {b1} | moy6' < {top} | moy6' > {bottom - 1}",
            f"moy6' < {h}", ""]
    out += ["[SYS_TRANS]", "! left' | ! right'", "! up' | ! down'", "! pickup' | ! drop'",
            "# the robot is never on a wall or the block",
            f"x < {c0} | x > {c1} | y != {top}", f"x < {c0} | x > {c1} | y != {bottom}",
            f"x < {b0} | x > {b1} | y < {inner[0]} | y > {inner[1]}",
            "# requests: one raised by the environment, cleared in the pickup area, which"
            " raises the second, cleared in the drop area",
            f"{pickup} -> ! requestPending1'",
            f"!({pickup}) -> (requestPending1' <-> (requestPending1 | deliveryrequest2))",
            f"{drop} -> ! requestPending2'",
            f"!({drop}) -> (requestPending2' <-> ({pickup} & requestPending1 |"
            " requestPending2))",
            "# the robot is never under the obstacle",
            "x' < mox6' | y' < moy6' | x' > mox6' + 1 | y' > moy6' + 1", ""]
    if game.liveness:
        out += ["[ENV_LIVENESS]", f"mox6' = {game.home[0]} & moy6' = {game.home[1]}", ""]
    out += ["[SYS_LIVENESS]", "! requestPending1", "! requestPending2", ""]
    return "\n".join(out)
