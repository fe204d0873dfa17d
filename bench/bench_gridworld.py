"""Large integer maps (issue 37): gridworlds and position arithmetic, SLUGS side by side.

Rows are the gridworlds of :mod:`bench.families.gridworld` (2^bits cells a side, one or two
obstacles in 8 x 8 boxes, integer or one-hot obstacle, every move its own clause), the
evasion grids in the style of SLUGS's EvasionOnGrid example (arithmetic position updates,
an obstacle that moves by at most one cell) and the moving-obstacle games of SLUGS's
benchmark generator (:func:`bench.families.safety_games.obstacle_text`, positions updated by
arithmetic).  Each row runs ``gaitc check`` as a whole process (the embedded solver's
default: the race of two orders) and ``gaitc check --solver slugs`` when $SLUGS is set, each
with its wall time and peak memory (the largest resident set of the process and of the
children it waited for, from ``wait4``), and the ratio SLUGS / gaitc.  ``--quick`` takes the
rows up to 256 x 256, 32 x 32 and 32 x 32 (about 10 minutes with SLUGS on two cores).
Run: .venv/bin/python bench/bench_gridworld.py [--quick] [--timeout S]
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.families.gridworld import BITS, QUICK_BITS, evasion_text, gridworld_text  # noqa: E402
from bench.families.safety_games import Obstacle, obstacle_text  # noqa: E402

GAITC = [sys.executable, "-m", "gaitc"]
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


def measure(command: list[str], timeout: float) -> tuple[str, float, float]:
    """(verdict or 'timeout', wall seconds, peak MB) of one process run: its own peak
    resident set and that of every child it waited for (``wait4``'s ru_maxrss)."""
    began = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             start_new_session=True)
    deadline = began + timeout
    while True:
        pid, status, usage = os.wait4(child.pid, os.WNOHANG)
        if pid:
            break
        if time.perf_counter() > deadline:
            os.killpg(child.pid, signal.SIGKILL)
            os.wait4(child.pid, 0)
            return "timeout", timeout, 0.0
        time.sleep(0.02)
    seconds = time.perf_counter() - began
    code = os.waitstatus_to_exitcode(status)
    verdict = {0: "realizable", 3: "unrealizable"}.get(code, f"exit {code}")
    return verdict, seconds, usage.ru_maxrss / 1024.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--timeout", type=float, default=600.0)
    args = parser.parse_args()
    slugs = os.environ.get("SLUGS")
    print(f"{'instance':<24} {'gaitc s':>8} {'MB':>6} {'slugs s':>8} {'MB':>6} "
          f"{'ratio':>6}  verdict")
    with tempfile.TemporaryDirectory() as folder:
        for name, text in rows(args.quick):
            path = Path(folder) / (name.replace(" ", "_") + ".structuredslugs")
            path.write_text(text, encoding="utf-8")
            verdict, ours, our_mb = measure([*GAITC, "check", str(path)], args.timeout)
            theirs, their_mb, ratio = "-", "-", "-"
            if slugs:
                slugs_verdict, seconds, mb = measure(
                    [*GAITC, "check", "--solver", "slugs", "--slugs", slugs, str(path)],
                    args.timeout)
                theirs, their_mb = f"{seconds:8.2f}", f"{mb:6.0f}"
                ratio = f"{seconds / ours:6.2f}" if verdict != "timeout" else "-"
                if slugs_verdict != verdict and "timeout" not in (slugs_verdict, verdict):
                    verdict += f" (SLUGS: {slugs_verdict})"
            print(f"{name:<24} {ours:8.2f} {our_mb:6.0f} {theirs:>8} "
                  f"{their_mb:>6} {ratio:>6}  {verdict}", flush=True)
    print("ratio: SLUGS seconds / gaitc seconds (above 1: gaitc faster); MB: peak resident "
          "memory of the process and the children it waited for")


if __name__ == "__main__":
    main()
