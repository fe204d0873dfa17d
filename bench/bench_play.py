"""How fast the player answers a move (issue 39): per step, with each kind of controller.

A step is what a user waits for after pressing a key: the move is played, the controller's
answer decoded and the next list of legal moves told in words. The model rows time that
alone (``Player.choose`` then ``Player.choices``), on thesis robot A with an explicit and a
symbolic controller, and on the 8-leg radial8 patrol robot (5,298 explicit nodes); the
robot role row plays the unrealizable 2 x 2 patrol against its counter-strategy. The app
rows time the same step through the terminal app under Textual's headless pilot, key press
to redrawn screen, in CPU time (see :func:`app_steps`). Every step of a row follows one
seeded random play, so a step is rarely served from the player's cache of moves. The
targets are 50 ms (explicit) and 200 ms (symbolic) a step.
Run: .venv/bin/python bench/bench_play.py [--quick] [--steps N]
"""

from __future__ import annotations

import argparse
import asyncio
import random
import statistics
import time
from pathlib import Path

import gaitc
from gaitc.play.player import Player

ROOT = Path(__file__).resolve().parent.parent
SPECS = ROOT / "specs"


def players() -> list[tuple[str, Player, float]]:
    """(row, a fresh player, target ms)."""
    robot_a = gaitc.load(SPECS / "thesis_robot_a.gait")
    symbolic = gaitc.synthesize(robot_a, form="symbolic")
    return [
        ("robot A, explicit (267 nodes)", gaitc.player(robot_a), 50.0),
        ("robot A, symbolic", gaitc.player(robot_a, symbolic), 200.0),
        ("radial8 patrol, explicit", gaitc.player(SPECS / "radial8_patrol.gait"), 50.0),
        ("unrealizable 2x2, robot role", gaitc.player(SPECS / "unrealizable_2x2.gait"), 50.0),
    ]


def model_steps(player: Player, steps: int, seed: int = 0) -> list[float]:
    """Milliseconds per step of a seeded random play (choose, then the next choices)."""
    rng = random.Random(seed)
    times = []
    for _ in range(steps):
        found = player.choices()
        if not found:
            break
        start = time.perf_counter()
        player.choose(rng.randrange(len(found)) + 1)
        player.choices()
        times.append((time.perf_counter() - start) * 1000)
    return times


def app_steps(player: Player, steps: int, seed: int = 0) -> list[float]:
    """CPU milliseconds per step through the terminal app, key press to redrawn screen.

    CPU time, not wall time: the headless pilot waits for Textual's frame timer and its
    own message round trips (about 60 ms of idle time a key), which a terminal does not;
    a real screen shows the new frame at most one frame (1/60 s) after this work ends."""
    from gaitc.play.terminal import PlayApp

    rng = random.Random(seed)
    app = PlayApp(player)
    times: list[float] = []

    async def script() -> None:
        async with app.run_test(size=(80, 24)) as pilot:
            await pilot.pause()
            for _ in range(steps):
                found = player.choices()
                if not found:
                    break
                number = rng.randrange(min(9, len(found))) + 1
                start = time.process_time()
                await pilot.press(str(number))
                await pilot.pause()
                times.append((time.process_time() - start) * 1000)

    asyncio.run(script())
    return times


def row(name: str, kind: str, times: list[float], target: float) -> str:
    ordered = sorted(times)
    p95 = ordered[min(len(ordered) - 1, int(0.95 * len(ordered)))]
    verdict = "yes" if p95 <= target else "NO"
    return (f"| {name} | {kind} | {len(times)} | {statistics.median(times):.2f} | {p95:.2f} | "
            f"{max(times):.2f} | {target:.0f} | {verdict} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="100 steps a row")
    parser.add_argument("--steps", type=int, default=500)
    args = parser.parse_args()
    steps = 100 if args.quick else args.steps
    print("| controller | through | steps | median ms | p95 ms | worst ms | target ms | "
          "p95 within |")
    print("|---|---|---|---|---|---|---|---|")
    for name, player, target in players():
        print(row(name, "model", model_steps(Player(player.session), steps), target),
              flush=True)
        print(row(name, "terminal app", app_steps(Player(player.session), min(steps, 100)),
                  target), flush=True)


if __name__ == "__main__":
    main()
