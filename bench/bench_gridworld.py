"""Large integer maps (issue 37): gridworlds and position arithmetic, four solvers side by side.

Rows are the gridworlds of :mod:`bench.families.gridworld` (2^bits cells a side, one or two
obstacles in 8 x 8 boxes, integer or one-hot obstacle, every move its own clause), the
evasion grids in the style of SLUGS's EvasionOnGrid example (arithmetic position updates,
an obstacle that moves by at most one cell) and the moving-obstacle games of SLUGS's
benchmark generator (:func:`bench.families.safety_games.obstacle_text`, positions updated by
arithmetic).  Each row runs gaitc (``gaitc check``, the embedded solver's default: the race
of two orders), SLUGS on the slugsin gaitc writes, gr1c on the ``.spc`` text of
peers/spc.py and omega (``python -m peers.omega_game``), each as a whole process, with the
wall seconds, CPU seconds and peak MB of its process tree and its verdict, as in
bench/bench_families.py (whose table this is; ``-`` where a solver is missing or cannot
take the spec: gr1c lists the values of a comparison of several positions, up to
peers.comparisons.LIMIT combinations).  ``--quick`` takes the rows up to 256 x 256,
32 x 32 and 32 x 32.
Run: .venv/bin/python bench/bench_gridworld.py [--quick] [--timeout S] [--repeat N]
"""

from __future__ import annotations

import argparse
import signal
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.bench_families import Table, measure_row  # noqa: E402
from bench.families import solvers  # noqa: E402
from bench.families.catalogue import Instance  # noqa: E402
from bench.families.gridworld import BITS, QUICK_BITS, evasion_text, gridworld_text  # noqa: E402
from bench.families.safety_games import Obstacle, obstacle_text  # noqa: E402
from gaitc.ir.spec import Semantics  # noqa: E402

#: The moving-obstacle games beyond the families table's 48 x 48 (SLUGS's generator's
#: configurations: the most glitches that leave the game realizable, and one more).
OBSTACLE_GAMES = [Obstacle(32, 11), Obstacle(32, 12), Obstacle(48, 19), Obstacle(48, 20),
                  Obstacle(64, 27), Obstacle(64, 28)]
QUICK_GAMES = OBSTACLE_GAMES[:2]


def rows(quick: bool) -> list[tuple[str, str]]:
    """(name, structured-SLUGS text) of every row."""
    out = []
    for bits in QUICK_BITS if quick else BITS:
        side = 1 << bits
        out.append((f"grid {side}x{side} int", gridworld_text(bits)))
        if bits <= 7:
            out.append((f"grid {side}x{side} one-hot", gridworld_text(bits, encoding="onehot")))
            out.append((f"grid {side}x{side} 2 obst", gridworld_text(bits, 2)))
    for side in (16, 24, 32) if quick else (16, 24, 32, 48, 64):
        out.append((f"evasion {side}x{side}", evasion_text(side, side)))
    for game in QUICK_GAMES if quick else OBSTACLE_GAMES:
        out.append((f"obstacle {game.side}x{game.side} g{game.glitches}", obstacle_text(game)))
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--timeout", type=float, default=600.0,
                        help="each solver's limit per row (default 600 s)")
    parser.add_argument("--repeat", type=int, default=1, metavar="N",
                        help="run each solver N times per row (min/median/max wall)")
    parser.add_argument("--slugs", help="the SLUGS binary (else $SLUGS or PATH)")
    parser.add_argument("--gr1c", help="the gr1c binary (else $GR1C or PATH)")
    args = parser.parse_args(argv)
    if args.repeat < 1:
        parser.error("--repeat needs a positive count")
    # the settings bench_families.py's rows and table read
    args.semantics = Semantics.DEFAULT
    args.slugs_timeout = args.peer_timeout = args.timeout
    args.lag_limit = float("inf")  # no --timeout lag column worth a second run here
    found = solvers.Binaries.find(args.slugs, args.gr1c)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # ends the solver measured too
    with tempfile.TemporaryDirectory() as folder:
        table = Table("gridworld", args)
        for name, text in rows(args.quick):
            path = Path(folder) / (name.replace(" ", "_") + ".structuredslugs")
            path.write_text(text, encoding="utf-8")
            instance = Instance("gridworld", name, path)
            inputs = solvers.prepare(path, "onehot", args.semantics, Path(folder))
            table.row(measure_row(instance, inputs, args, found))
        table.close()
    print("\nR realizable, U unrealizable, T past the time limit, E failed, - not run; ! a "
          "verdict unlike the others'; MB: peak resident memory of the process tree")


if __name__ == "__main__":
    main()
