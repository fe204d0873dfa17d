"""Long fuzz mode (issue 9): N mutants of every input kind through every command reading it.

Usage: python bench/fuzz.py --per-kind N [--hours H] [--kinds a,b] [--jobs J] [--seed S]
       [--limit SECONDS] [--reproducers DIR]

Besides the file kinds of ``tests/fuzz_cases.py``: ``serial`` (the board's replies),
``runner`` (scripts for a compiled ``gaitc-run``, skipped without gcc), ``target`` (odd
output paths; its first inputs are the fixed special targets), ``codegen`` (codegen's
option words), ``lsp`` (sessions of LSP messages for a fresh ``gaitc lsp``, skipped
without pygls) and ``player`` (screen sizes and keys for the terminal player, skipped
without textual) and ``ros`` (malformed and out-of-range observations for the controller
node's callbacks, each bad one vented, skipped without rclpy), from ``tests/fuzz_serial.py``,
``fuzz_runner.py``, ``fuzz_targets.py``, ``fuzz_lsp.py``, ``fuzz_player.py`` and
``fuzz_ros.py``. A session of ``lsp`` may take ``--limit`` seconds
(its server's start-up not counted); a key sequence of ``player`` at least
:data:`PLAYER_LIMIT`.

Each worker process runs commands in-process (``gaitc.cli.main``) on mutants made from
``(seed, kind, index)`` alone, so a run is deterministic given ``--seed``. A run past its
wall-clock limit is counted, and a worker stuck at three times the limit is killed and
replaced. With ``--hours``, each kind gets an equal share of the time still left (and
at most N mutants). Reproducers of every failure (the mutant and a README line with the command)
go to ``--reproducers``. The table goes to stdout; docs/reliability.md shows a run.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib.util
import multiprocessing
import multiprocessing.connection
import random
import shutil
import sys
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from fuzz_cases import KIND_NAMES, Fixtures, kinds, run_case
from fuzz_mutate import mutate
from fuzz_oracle import OUTCOMES, Verdict
from fuzz_runner import SCRIPTS, build_program
from fuzz_runner import exchange as run_script
from fuzz_serial import EXCHANGES, exchange
from fuzz_targets import NAMES, OPTIONS, SPECIAL, SPECIALS, run_codegen, run_target

# the file kinds, the board's serial replies, gaitc-run's scripts, output targets and
# codegen's options, the language server's sessions and the player's keys
ALL_KINDS = (*KIND_NAMES, "serial", "runner", "target", "codegen", "lsp", "player", "ros")
#: What each front-end kind needs installed (the kind is skipped without it).
NEEDS = {"lsp": "pygls", "player": "textual", "ros": "rclpy"}
PLAYER_LIMIT = 30.0  # seconds a key sequence may take, at least (Textual's pilot is slow)
SERIAL_COMMANDS = ("board",)


def mutant_of(seeds: tuple[tuple[str, bytes], ...], seed: int, kind: str,
              index: int) -> tuple[str, bytes]:
    """The ``index``-th mutant of ``kind``: (seed file name, bytes)."""
    rng = random.Random(f"{seed}:{kind}:{index}")
    name, data = seeds[rng.randint(0, len(seeds) - 1)]
    return name, mutate(data, rng, [d for _, d in seeds])


def play_of(seed: int, index: int) -> tuple[str, bytes]:
    """The ``index``-th mutant of the ``player`` kind: a key sequence, on another screen
    one time in two (:func:`fuzz_player.mutate_play`)."""
    from fuzz_player import EXCHANGES as PLAYS
    from fuzz_player import mutate_play

    rng = random.Random(f"{seed}:player:{index}")
    name, data = PLAYS[rng.randint(0, len(PLAYS) - 1)]
    return name, mutate_play(data, rng, [d for _, d in PLAYS])


def target_of(seed: int, index: int) -> tuple[str, bytes]:
    """The ``index``-th input of the ``target`` kind: the special targets first (their
    name, no bytes), then mutants of the names."""
    if index < len(SPECIALS):
        return SPECIAL + SPECIALS[index][0], b""
    return mutant_of(NAMES, seed, "target", index)


def _ros_node(fx: Fixtures) -> Any:
    """The ros kind's controller node: thesis robot A (the seeds' legs and hazard sets) in a
    graph of this worker's own, its ROS traffic kept on this machine, in the bench's domain."""
    import os

    os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    os.environ.setdefault("ROS_DOMAIN_ID", "57")
    import gaitc
    from gaitc.api.simulation import session
    from gaitc.ros.graph import Graph
    from gaitc.ros.node import ControllerNode, NodeOptions

    bound = session(gaitc.load(Path(__file__).resolve().parent.parent / "specs"
                               / "thesis_robot_a.gait"), None)
    assert bound is not None
    graph = Graph()  # lives as long as the worker
    return ControllerNode(graph, bound.strategy, bound.domain, bound.monitor, None,
                          NodeOptions(rate=0.0), spec_file="thesis_robot_a.gait")


def _worker(conn: multiprocessing.connection.Connection, folder: str, limit: float) -> None:
    fx = Fixtures(Path(folder))
    table = kinds(fx)
    program: Path | None = None  # gaitc-run, built for the first runner job
    ros_node: Any = None  # the controller node of the ros kind, made for its first job
    while True:
        job = conn.recv()
        if job is None:
            return
        kind, seed, index = job
        current = Path(folder) / "current.bin"  # the parent's copy if this run never ends
        if kind == "serial":
            name, data = mutant_of(EXCHANGES, seed, kind, index)
            current.write_bytes(data)
            verdicts = [exchange(data, limit)]
        elif kind == "runner":
            if program is None:
                program = build_program(fx.hazard_compact, Path(folder) / "runner")
                assert program is not None, "main drops the runner kind without gcc"
            name, data = mutant_of(SCRIPTS, seed, kind, index)
            current.write_bytes(data)
            verdicts = run_script(data, limit, program)
        elif kind == "target":
            name, data = target_of(seed, index)
            current.write_bytes(data)
            verdicts = run_target(name, data, fx, limit)
        elif kind == "codegen":
            name, data = mutant_of(OPTIONS, seed, kind, index)
            current.write_bytes(data)
            verdicts = run_codegen(data, fx, limit)
        elif kind == "lsp":
            from fuzz_lsp import EXCHANGES as SESSIONS
            from fuzz_lsp import exchange as run_session

            name, data = mutant_of(SESSIONS, seed, kind, index)
            current.write_bytes(data)
            verdicts = [run_session(data, limit)]
        elif kind == "ros":
            from fuzz_ros import EXCHANGES as OBSERVATIONS
            from fuzz_ros import exchange as observe

            if ros_node is None:
                ros_node = _ros_node(fx)
            name, data = mutant_of(OBSERVATIONS, seed, kind, index)
            current.write_bytes(data)
            verdicts = [observe(data, ros_node, limit=limit)]
        elif kind == "player":
            from fuzz_player import exchange as play

            name, data = play_of(seed, index)
            current.write_bytes(data)
            verdicts = [play(data, max(limit, PLAYER_LIMIT))]
        else:
            name, data = mutant_of(table[kind].seeds, seed, kind, index)
            current.write_bytes(data)
            verdicts = run_case(table[kind], fx, name, data, limit)
        conn.send((kind, index, name, data, [(v.command, v.code, v.seconds, v.problems)
                                             for v in verdicts]))


@dataclass
class Tally:
    """Counts for one input kind."""

    inputs: int = 0
    outcomes: Counter[str] = field(default_factory=Counter)
    seconds: float = 0.0


class Pool:
    """``jobs`` worker processes, each with its own fixtures folder."""

    def __init__(self, jobs: int, root: Path, limit: float) -> None:
        self.root, self.limit = root, limit
        self.workers: list[tuple[multiprocessing.Process,
                                 multiprocessing.connection.Connection]] = []
        self.busy: dict[int, tuple[tuple[str, int, int], float]] = {}
        for slot in range(jobs):
            self.workers.append(self._start(slot))

    def _start(self, slot: int) -> tuple[multiprocessing.Process,
                                         multiprocessing.connection.Connection]:
        parent, child = multiprocessing.Pipe()
        # Not daemonic: a daemonic process may not fork, so a command's --timeout would run
        # unlimited in it; with a child of its own it is bounded as a user's command is.
        proc = multiprocessing.Process(target=_worker, daemon=False,
                                       args=(child, str(self.root / f"w{slot}"), self.limit))
        proc.start()
        return proc, parent

    def send(self, slot: int, job: tuple[str, int, int]) -> None:
        self.workers[slot][1].send(job)
        self.busy[slot] = (job, time.monotonic())

    def idle(self) -> list[int]:
        return [s for s in range(len(self.workers)) if s not in self.busy]

    def collect(self) -> list[tuple[object, ...]]:
        """Results that arrived (waiting a little); a stuck worker is killed, its job failed."""
        results: list[tuple[object, ...]] = []
        conns = {self.workers[s][1]: s for s in self.busy}
        for ready in multiprocessing.connection.wait(list(conns), timeout=0.5):
            conn = next(c for c in conns if c is ready)
            slot = conns[conn]
            try:
                results.append(conn.recv())
            except EOFError:  # the worker died (killed by the OS, or a C library exited)
                results.append(self._lost(slot, "the worker process died"))
            self.busy.pop(slot, None)
        now = time.monotonic()
        for slot, (_job, started) in list(self.busy.items()):
            if now - started > 10 * self.limit + 10:
                results.append(self._lost(slot, f"killed after {now - started:.0f} s"))
                self.busy.pop(slot)
        return results

    def _lost(self, slot: int, why: str) -> tuple[object, ...]:
        (kind, _seed, index), started = self.busy[slot]
        proc, _conn = self.workers[slot]
        proc.kill()
        proc.join()
        self.workers[slot] = self._start(slot)
        seconds = time.monotonic() - started
        current = self.root / f"w{slot}" / "current.bin"
        data = current.read_bytes() if current.exists() else b""
        return (kind, index, "?", data, [("(worker)", -1, seconds, [f"past limit: {why}"])])

    def close(self) -> None:
        """End every worker: asked to stop, killed when it does not within 5 s."""
        for proc, conn in self.workers:
            with contextlib.suppress(OSError):  # a worker that died closed its pipe
                conn.send(None)
            proc.join(timeout=5)
            if proc.is_alive():
                proc.kill()
                proc.join()


def table(tallies: dict[str, Tally]) -> str:
    """The per-kind table: inputs, runs, and the runs of each outcome."""
    head = ["kind", "inputs", "runs", *OUTCOMES, "seconds"]
    rows = [head]
    for kind, t in tallies.items():
        rows.append([kind, str(t.inputs), str(sum(t.outcomes.values())),
                     *[str(t.outcomes[o]) for o in OUTCOMES], f"{t.seconds:.0f}"])
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    lines = ["| " + " | ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)) + " |"
             for r in rows]
    lines.insert(1, "|" + "|".join("-" * (w + 2) for w in widths) + "|")
    return "\n".join(lines)


def save_reproducer(folder: Path, kind: str, index: int, seed_name: str, data: bytes,
                    verdicts: list[Verdict]) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    stem = f"{kind}-{index:06d}"
    (folder / f"{stem}.bin").write_bytes(data)
    with open(folder / "README.txt", "a", encoding="utf-8") as out:
        for v in verdicts:
            for problem in v.problems:
                out.write(f"{stem}.bin (from {seed_name}) {v.command}: {problem}\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per-kind", type=int, default=100_000, help="mutants per kind")
    parser.add_argument("--hours", type=float, default=None, help="stop after this long")
    parser.add_argument("--kinds", default=",".join(ALL_KINDS))
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--limit", type=float, default=6.0, help="seconds per run")
    parser.add_argument("--reproducers", type=Path, default=Path("fuzz-reproducers"))
    args = parser.parse_args(argv)
    chosen = [k for k in args.kinds.split(",") if k]
    unknown = sorted(set(chosen) - set(ALL_KINDS))
    if unknown or args.per_kind < 1 or args.jobs < 1:
        parser.error(f"unknown kinds {unknown}" if unknown else "--per-kind/--jobs must be ≥ 1")
    if "runner" in chosen and shutil.which("gcc") is None:
        print("runner: skipped, gcc is missing (gaitc-run cannot be built)", file=sys.stderr)
        chosen.remove("runner")
    for kind, module in NEEDS.items():
        if kind in chosen and importlib.util.find_spec(module) is None:
            print(f"{kind}: skipped, {module} is not installed", file=sys.stderr)
            chosen.remove(kind)
    tallies = {kind: Tally() for kind in chosen}
    deadline = None if args.hours is None else time.monotonic() + args.hours * 3600
    with tempfile.TemporaryDirectory(prefix="gaitc-fuzz-") as tmp:
        pool = Pool(args.jobs, Path(tmp), args.limit)
        try:
            run_kinds(pool, chosen, tallies, args, deadline)
        finally:
            pool.close()
    print(f"seed {args.seed}, per-run limit {args.limit:g} s, {args.jobs} job(s)")
    print(table(tallies))
    bad = sum(t.outcomes[o] for t in tallies.values() for o in OUTCOMES[3:])
    return 1 if bad else 0


def run_kinds(pool: Pool, chosen: list[str], tallies: dict[str, Tally],
              args: argparse.Namespace, deadline: float | None) -> None:
    """Every chosen kind in turn, each with an equal share of the time left."""
    for number, kind in enumerate(chosen):
        start, sent, done = time.monotonic(), 0, 0
        # an equal share of the time left, so a kind that finishes early gives time back
        share = None if deadline is None else (deadline - start) / (len(chosen) - number)
        while done < sent or sent < args.per_kind:
            out_of_time = share is not None and time.monotonic() - start > share
            for slot in pool.idle():
                if sent < args.per_kind and not out_of_time:
                    pool.send(slot, (kind, args.seed, sent))
                    sent += 1
            if out_of_time and done == sent:
                break
            for result in pool.collect():
                done += 1
                _record(tallies, args.reproducers, result)
        tallies[kind].seconds = time.monotonic() - start
        print(f"{kind}: {tallies[kind].inputs} inputs in {tallies[kind].seconds:.0f} s",
              file=sys.stderr, flush=True)


def _record(tallies: dict[str, Tally], folder: Path, result: tuple[object, ...]) -> None:
    kind, index, seed_name, data, raw = result
    assert isinstance(kind, str) and isinstance(index, int) and isinstance(data, bytes)
    verdicts = [Verdict(c, code, s, list(p)) for c, code, s, p in raw]  # type: ignore[attr-defined]
    tally = tallies[kind]
    tally.inputs += 1
    tally.outcomes.update(v.outcome for v in verdicts)
    if any(v.problems for v in verdicts):
        save_reproducer(folder, kind, index, str(seed_name), data, verdicts)


if __name__ == "__main__":
    sys.exit(main())
