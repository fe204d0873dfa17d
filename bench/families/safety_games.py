"""Two SYNTCOMP safety-game families as ``.structuredslugs``: Cinderella-Stepmother and a
robot evading a moving obstacle.

Written from the published descriptions of the families (R. Ehlers, "Cinderella-Stepmother
Game Benchmarks" and "Robot-on-a-grid Moving Obstacle Evasion Benchmarks", SYNTCOMP 2014,
shipped with SLUGS's benchmark generators) and their tables of realizable and unrealizable
configurations, which the tests reproduce.  Neither family has a liveness part: both are
pure safety games, whose solutions are long chains of Z rounds of one CPre step each and
whose difficulty lies in the integer arithmetic of their transition relations.

Own choices: the buckets Cinderella empties are named by the values of ``empty`` that
cover each bucket (not by modular arithmetic), and the robot's move is written case by case.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Cinderella:
    """``buckets`` buckets in a circle, ``adjacent`` of them emptied a step, each holding
    ``capacity`` units of 1/``units`` litre; the stepmother pours one litre a step."""

    buckets: int
    adjacent: int
    capacity: int
    units: int

    @property
    def name(self) -> str:
        return f"n{self.buckets}c{self.adjacent} b={self.capacity}/{self.units}"


#: The published configurations with their verdicts (realizable or not).
CINDERELLA: tuple[tuple[Cinderella, bool], ...] = (
    (Cinderella(5, 2, 6, 4), False), (Cinderella(5, 2, 7, 4), True),
    (Cinderella(5, 3, 12, 9), False), (Cinderella(5, 3, 13, 9), True),
    (Cinderella(6, 1, 14, 5), False), (Cinderella(6, 1, 15, 5), True),
    (Cinderella(6, 2, 13, 6), False), (Cinderella(6, 2, 14, 6), True),
    (Cinderella(6, 3, 10, 6), False), (Cinderella(6, 3, 11, 6), True),
)


def cinderella_text(game: Cinderella) -> str:
    """The Cinderella-Stepmother game ``game``: the system is Cinderella, who must keep every
    bucket's level within its capacity; the environment pours up to ``units`` units."""
    n, c = game.buckets, game.adjacent
    if not 1 <= c <= n or game.capacity < 1 or game.units < 1:
        raise ValueError(f"no Cinderella game with {n} buckets, {c} emptied, "
                         f"capacity {game.capacity}/{game.units}")
    buckets = range(n)
    pours = [f"pour{i}" for i in buckets]
    out = [f"# Cinderella-Stepmother, {game.name}", "", "[INPUT]"]
    out += [f"{p}:0...{game.units}" for p in pours]
    out += ["", "[OUTPUT]"]
    out += [f"level{i}:0...{game.capacity}" for i in buckets]
    out += [f"empty:0...{n - 1}", "", "[ENV_INIT]"]
    out += [f"{p} = 0" for p in pours]
    out += ["", "[ENV_TRANS]", " + ".join(f"{p}'" for p in pours) + f" <= {game.units}"]
    out += ["", "[SYS_INIT]"]
    out += [f"level{i} = 0" for i in buckets]
    out += ["", "[SYS_TRANS]"]
    for i in buckets:
        # empty = e clears buckets e, e+1, ..., e+c-1 (around the circle)
        covering = " | ".join(f"empty = {(i - d) % n}" for d in range(c))
        out.append(f"({covering}) -> level{i}' = pour{i}'")
        out.append(f"!({covering}) -> level{i}' = level{i} + pour{i}'")
    return "\n".join(out) + "\n"


@dataclass(frozen=True)
class Obstacle:
    """A robot on a ``side`` x ``side`` grid evading a 2 x 2 obstacle that moves every
    second step, except for at most ``glitches`` extra moves."""

    side: int
    glitches: int

    @property
    def name(self) -> str:
        return f"{self.side}x{self.side} glitches={self.glitches}"


#: The published configurations the tests and the benchmark use, with their verdicts.
OBSTACLES: tuple[tuple[Obstacle, bool], ...] = (
    (Obstacle(8, 0), True), (Obstacle(8, 1), False),
    (Obstacle(16, 3), True), (Obstacle(16, 4), False),
    (Obstacle(24, 7), True), (Obstacle(24, 8), False),
    (Obstacle(32, 11), True), (Obstacle(32, 12), False),
    (Obstacle(48, 19), True), (Obstacle(48, 20), False),
)


def _axis(robot: str, move: str, last: int) -> list[str]:
    """The environment moves the robot along one axis as ``move`` says (0 back, 1 stay,
    2 forward), stopping at the walls 0 and ``last``."""
    return [
        f"{move} = 1 -> {robot}' = {robot}",
        f"{move} = 0 & {robot} = 0 -> {robot}' = 0",
        f"{move} = 0 & {robot} != 0 -> {robot}' + 1 = {robot}",
        f"{move} = 2 & {robot} = {last} -> {robot}' = {last}",
        f"{move} = 2 & {robot} != {last} -> {robot}' = {robot} + 1",
    ]


def obstacle_text(game: Obstacle) -> str:
    """The moving-obstacle game ``game``: the environment reports the robot's and the
    obstacle's positions, the system chooses the robot's moves and must never share a
    cell with the obstacle, whose upper left corner is (obsx, obsy)."""
    m, c = game.side, game.glitches
    if m < 3 or c < 0:
        raise ValueError(f"no obstacle game on a {m} x {m} grid with {c} glitches")
    stays = "obsx' = obsx & obsy' = obsy"
    out = [f"# Moving obstacle evasion, {game.name}", "", "[INPUT]",
           f"robx:0...{m - 1}", f"roby:0...{m - 1}", f"obsx:0...{m - 2}", f"obsy:0...{m - 2}",
           f"glitches:0...{c}", "", "[OUTPUT]", "movx:0...2", "movy:0...2", "obsmove", "",
           "[ENV_INIT]", "robx = 0", "roby = 0", f"obsx = {m - 2}", f"obsy = {m - 2}",
           "glitches = 0", "", "[ENV_TRANS]",
           *_axis("robx", "movx", m - 1), *_axis("roby", "movy", m - 1),
           "obsx' <= obsx + 1 & obsx <= obsx' + 1",
           "obsy' <= obsy + 1 & obsy <= obsy' + 1",
           "glitches' >= glitches",
           f"!obsmove & !({stays}) -> glitches' > glitches",
           "", "[SYS_INIT]", "!obsmove", "", "[SYS_TRANS]",
           "robx < obsx | robx > obsx + 1 | roby < obsy | roby > obsy + 1",
           f"obsmove' <-> ({stays})"]
    return "\n".join(out) + "\n"
