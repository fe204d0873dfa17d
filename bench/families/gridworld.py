"""Gridworlds: a robot on a large grid of integer coordinates, dynamic obstacles, two goals.

Two shapes of the same task, both written in SLUGS's structured format:

- :func:`gridworld_text`, the shape a GR(1) tool's gridworld example uses: the robot's
  position is two integers of ``bits`` bits (a side of 2^bits cells), every allowed move is
  its own clause (``x = k -> x' = k - 1 | x' = k | x' = k + 1`` for every k), the robot
  moves along one axis at a time (4-connected), each obstacle stays in its own 8 x 8 box and
  moves one cell at a time too, and the robot must visit two opposite corners infinitely
  often without ever sharing a cell with an obstacle.  The obstacle's position is two small
  integers (``encoding="integer"``) or one Boolean per cell of its box (``"onehot"``, with
  the exactly-one constraint as an environment assumption).
- :func:`evasion_text`, the style of SLUGS's EvasionOnGrid example: the robot's moves are
  Boolean outputs and the position update is arithmetic (``x > 0 & left -> x' + 1 = x``),
  an obstacle moves by at most one cell per step (``mox' <= mox + 1``) within a band of
  three rows across the middle and returns to its home cell infinitely often, and the robot
  must shuttle between two corners, crossing the band.

Both are realizable: the boxes lie away from the corners and the grid is wide enough to go
around them.  The robot moves and the obstacle moves are those of the issue's gridworld
(issue 37); the numbers of bits and obstacles are the family's parameters.
"""

from __future__ import annotations

#: Sides (bits per coordinate) of the family in the benchmark table, and the quick subset.
BITS = [6, 7, 8, 9, 10]
QUICK_BITS = [6, 7, 8]
BOX = 8  # an obstacle's box is BOX x BOX cells


def _boxes(side: int, obstacles: int) -> list[tuple[int, int]]:
    """The lower-left corners of the obstacles' boxes: on the diagonal, away from the
    corners the robot must visit."""
    out = []
    for k in range(obstacles):
        at = (k + 1) * side // (obstacles + 1) - BOX // 2
        out.append((at, at))
    return out


def _moves(var: str, side: int) -> list[str]:
    """One clause per value: from k the next value is k - 1, k or k + 1 (within the grid)."""
    out = []
    for k in range(side):
        nxt = [f"{var}' = {v}" for v in (k - 1, k, k + 1) if 0 <= v < side]
        out.append(f"{var} = {k} -> ({' | '.join(nxt)})")
    return out


def gridworld_text(bits: int, obstacles: int = 1, encoding: str = "integer") -> str:
    """The structured-SLUGS text of the gridworld of 2^``bits`` cells a side with
    ``obstacles`` dynamic obstacles (see the module's docstring)."""
    if encoding not in ("integer", "onehot"):
        raise ValueError(f"unknown obstacle encoding {encoding!r}")
    side = 1 << bits
    if side < 4 * BOX or not 1 <= obstacles <= 2:
        raise ValueError("a gridworld needs at least 5 bits a side and one or two obstacles")
    boxes = _boxes(side, obstacles)
    inputs: list[str] = []
    env_init: list[str] = []
    env_trans: list[str] = []
    env_live: list[str] = []
    clash: list[str] = []
    for n, (bx, by) in enumerate(boxes):
        if encoding == "integer":
            inputs += [f"ox{n}:0...{BOX - 1}", f"oy{n}:0...{BOX - 1}"]
            env_init += [f"ox{n} = 0", f"oy{n} = 0"]
            env_trans += _moves(f"ox{n}", BOX) + _moves(f"oy{n}", BOX)
            env_trans.append(f"ox{n}' = ox{n} | oy{n}' = oy{n}")
            # the robot must not step onto the obstacle's cell, nor stay where it arrives
            for i in range(BOX):
                for j in range(BOX):
                    clash.append(f"!(x' = {bx + i} & y' = {by + j} & ox{n}' = {i} & "
                                 f"oy{n}' = {j})")
            env_live.append(f"ox{n} = 0 & oy{n} = 0")
        else:
            cells = [(i, j) for i in range(BOX) for j in range(BOX)]
            names = {c: f"o{n}_{c[0]}_{c[1]}" for c in cells}
            inputs += list(names.values())
            env_init.append(names[(0, 0)] + "".join(
                f" & !{names[c]}" for c in cells if c != (0, 0)))
            for c in cells:  # exactly one cell, and it moves to a neighbour or stays
                others = " & ".join(f"!{names[d]}'" for d in cells if d != c)
                env_trans.append(f"{names[c]}' -> ({others})")
                near = [names[d] + "'" for d in cells
                        if abs(d[0] - c[0]) + abs(d[1] - c[1]) <= 1]
                env_trans.append(f"{names[c]} -> ({' | '.join(near)})")
            env_trans.append("(" + " | ".join(f"{v}'" for v in names.values()) + ")")
            for (i, j), name in names.items():
                clash.append(f"!(x' = {bx + i} & y' = {by + j} & {name}')")
            env_live.append(names[(0, 0)])
    out = ["[INPUT]", *inputs, "", "[OUTPUT]", f"x:0...{side - 1}", f"y:0...{side - 1}", ""]
    out += ["[ENV_INIT]", *env_init, "", "[SYS_INIT]", "x = 0", "y = 0", ""]
    out += ["[ENV_TRANS]", *env_trans, "", "[SYS_TRANS]"]
    out += _moves("x", side) + _moves("y", side)
    out += ["x' = x | y' = y", *clash, ""]
    out += ["[ENV_LIVENESS]", *env_live, ""]
    out += ["[SYS_LIVENESS]", "x = 0 & y = 0", f"x = {side - 1} & y = {side - 1}", ""]
    return "\n".join(out)


def evasion_text(width: int, height: int, obstacles: int = 1) -> str:
    """The structured-SLUGS text of a robot moved by arithmetic on a ``width`` x ``height``
    grid, dodging ``obstacles`` obstacles that move by at most one cell a step (the style of
    SLUGS's EvasionOnGrid example)."""
    if width < 8 or height < 8 or not 1 <= obstacles <= 2:
        raise ValueError("an evasion grid needs at least 8 x 8 cells and one or two obstacles")
    w, h = width - 1, height - 1
    inputs = [f"x:0...{w}", f"y:0...{h}"]
    env_init = ["x = 0", "y = 0"]
    env_trans = [
        "x>0 & left -> x'+1=x", f"x<{w} & right -> x'=x+1",
        "y>0 & up -> y'+1=y", f"y<{h} & down -> y'=y+1",
        "(!left & !right) -> x'=x", "(!up & !down) -> y'=y",
        "(x=0 & left) -> x'=x", f"(x={w} & right) -> x'=x",
        "(y=0 & up) -> y'=y", f"(y={h} & down) -> y'=y",
    ]
    sys_trans = ["! left' | ! right'", "! up' | ! down'"]
    env_live = []
    for n in range(obstacles):
        ox, oy = f"mox{n}", f"moy{n}"
        inputs += [f"{ox}:0...{w}", f"{oy}:0...{h}"]
        env_init += [f"{ox} = {w // 2 + n}", f"{oy} = {h // 2}"]
        env_trans += [f"{ox}' <= {ox}+1", f"{oy}' <= {oy}+1", f"{ox} <= {ox}'+1",
                      f"{oy} <= {oy}'+1", f"{ox}'={ox} | {oy}'={oy}",
                      # it patrols a band of three rows across the middle
                      f"{oy}' >= {h // 2 - 1}", f"{oy}' <= {h // 2 + 1}"]
        # the robot never shares a cell with the obstacle (after the robot's and its move)
        sys_trans.append(f"!(x'={ox}' & y'={oy}')")
        sys_trans.append(f"!(x={ox}' & y={oy}')")
        env_live.append(f"{ox} = {w // 2 + n} & {oy} = {h // 2}")
    out = ["[INPUT]", *inputs, "", "[OUTPUT]", "left", "right", "up", "down", ""]
    out += ["[ENV_INIT]", *env_init, "", "[SYS_INIT]", "! left", "! right", "! up", "! down",
            ""]
    out += ["[ENV_TRANS]", *env_trans, "", "[SYS_TRANS]", *sys_trans, ""]
    out += ["[ENV_LIVENESS]", *env_live, ""]
    out += ["[SYS_LIVENESS]", "x = 0 & y = 0", f"x = {w} & y = {h}", ""]
    return "\n".join(out)
