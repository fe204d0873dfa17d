"""The fuzzed input kinds: their seed files and the gaitc commands that read each kind.

Shared by the fuzz tests and ``bench/fuzz.py``. :class:`Fixtures` prepares, once per
folder, what the commands need besides the mutant (specs, controllers, a run file);
:func:`commands_for` gives the argument lists that read one mutant file.
"""

from __future__ import annotations

import contextlib
import io
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from fuzz_oracle import Verdict, run_command, write_mutant

ROOT = Path(__file__).resolve().parent.parent
SPECS = ROOT / "specs"
GOLDEN = ROOT / "tests" / "golden"
SLUGS_EXAMPLES = ROOT / "tests" / "data" / "slugs_examples"
CHECK_TIMEOUT = "2"  # seconds, for every command that takes --timeout

SCENARIOS: tuple[tuple[str, str], ...] = (
    ("quiet.yaml", "steps:\n  - {}\n  - {}\n"),
    ("hazard.yaml", "start: {hazard: h, note: begin}\nsteps:\n  - hazard: none\n"
                    "  - {degrade: [L1], note: wear}\n  - {fail: L2}\n  - {}\n"),
    ("health.yaml", "start:\n  health: {L1: 2, L3: 1}\nsteps:\n  - health: {L2: 2}\n"
                    "  - hazard: h\n  - degrade: [L3]\n  - {hazard: off, note: \"done\"}\n"),
    ("flow.yaml", "# a comment\nsteps: [{}, {hazard: h}, {degrade: [L2, L3]}, {}]\n"),
)
HAZARD_SPEC = ROOT / "tests" / "data" / "hazard_patrol.gait"
SHUTTLE = ROOT / "tests" / "data" / "softmodels" / "radial8_shuttle.gait"
RADIAL8 = SPECS / "robots" / "radial8.yaml"
MAPS: tuple[tuple[str, str], ...] = (
    ("cells.yaml", "regions:\n  a: [[0, 0], [100, 0], [100, 100], [0, 100]]\n"
                   "  b: [[100, 0], [200, 0], [200, 100], [100, 100]]\n"),
    ("flow.yaml", "regions: {a: [[0, 0], [100, 0], [0, 100]], b: [[100, 0], [300, 0], "
                  "[300, 100], [100, 100]]}\n"),
)
SENSING: tuple[tuple[str, str], ...] = (
    ("legs.sensing.yaml", "# thresholds\nlegs:\n  L1: {thresholds: [0.4], hysteresis: 0.02}\n"
                          "  L2: {thresholds: [0.35]}\n"),
    ("block.sensing.yaml", "legs:\n  L3:\n    thresholds:\n      - 0.5\n    hysteresis: 0\n"),
)
ONE_LIMB = ROOT / "tests" / "data" / "softmodels" / "one_limb.yaml"
# a curvature step response (time s, curvature 1/mm) of about 12 rad/s, damping ratio 0.9
CURVATURE: tuple[tuple[str, str], ...] = (
    ("step.csv", "time,curvature\n" + "".join(
        f"{k * 0.05:.2f},{0.022 - 0.014 * (1.1 ** -k):.5f}\n" for k in range(40))),
)
CALIBRATION: tuple[tuple[str, str], ...] = (
    ("legs.csv", "leg,cycle,level,intensity\n" + "".join(
        f"L1,{c},{2 - c % 2},{v}\n" for c in range(4)
        for v in (900, 890, 600 if c % 2 == 0 else 850, 880, 900))),
)
PATROL = SPECS / "patrol_2x2.gait"
LTL_SOURCES = (PATROL, SPECS / "thesis_robot_a.gait", GOLDEN / "features.gait")
# One gait bound to a stored primitive of the robot file (a search when it has none).
ROBOT_USER = """legs L1..L8 health 2
gait north_a uses L6, L8 moves north primitive "{robot}" direction +y
grid 2 x 1
start r0
"""


def _quiet(argv: list[str]) -> int:
    from gaitc.cli import main

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        code: int = main(argv)
    return code


class Fixtures:
    """The files the commands read besides the mutant, made once in ``folder``."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        folder.mkdir(parents=True, exist_ok=True)
        self.patrol_controller = folder / "patrol.json"
        self.hazard_controller = folder / "hazard.json"
        self.run_file = folder / "patrol.run.jsonl"
        self.shuttle_controller = folder / "shuttle.json"
        # compact controllers (synth --compact), the seeds of the 'compact' kind; the
        # hazard one is also what gaitc-run is built from (fuzz_runner)
        self.patrol_compact = folder / "patrol.compact.json"
        self.hazard_compact = folder / "hazard.compact.json"
        made = [
            _quiet(["synth", str(SHUTTLE), "-o", str(self.shuttle_controller)]),
            _quiet(["synth", str(PATROL), "-o", str(self.patrol_controller)]),
            _quiet(["synth", str(HAZARD_SPEC), "-o", str(self.hazard_controller)]),
            _quiet(["simulate", str(PATROL), str(self.patrol_controller), "--env", "random",
                    "--seed", "3", "--steps", "12", "--out", str(self.run_file), "--quiet"]),
            _quiet(["synth", str(PATROL), "--compact", "-o", str(self.patrol_compact)]),
            _quiet(["synth", str(HAZARD_SPEC), "--compact", "-o", str(self.hazard_compact)]),
        ]
        if made != [0] * len(made):
            raise RuntimeError(f"could not prepare the fuzz fixtures in {folder}: {made}")
        self.ltl: list[Path] = []  # the readable LTL text 'compile --format ltl' writes
        for spec in LTL_SOURCES:
            self.ltl.append(folder / f"{spec.stem}.ltl")
            made.append(_quiet(["compile", str(spec), "--format", "ltl",
                                "-o", str(self.ltl[-1])]))
        if made != [0] * len(made):
            raise RuntimeError(f"could not prepare the .ltl fuzz seeds in {folder}: {made}")
        self.out = folder / "out"
        self.out.mkdir(exist_ok=True)

    def spec_of_controller(self, seed: str) -> Path:
        return HAZARD_SPEC if seed.startswith("hazard") else PATROL


@dataclass(frozen=True)
class Kind:
    """One input kind: a file suffix, its seeds (name, bytes) and the commands reading it."""

    name: str
    suffix: str
    seeds: tuple[tuple[str, bytes], ...]
    commands: Callable[[Path, str, Fixtures], list[tuple[str, list[str]]]]
    slowness: float = 1.0  # times the per-run limit (lint's gait search on a robot file)


def _files(*patterns: tuple[Path, str]) -> tuple[tuple[str, bytes], ...]:
    found = sorted({p for folder, pattern in patterns for p in folder.glob(pattern)})
    return tuple((p.name, p.read_bytes()) for p in found)


def _gait_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    return [
        ("lint", ["lint", str(path)]),
        ("compile", ["compile", str(path), "-o", str(fx.out / "spec.structuredslugs")]),
        ("check", ["check", str(path), "--timeout", CHECK_TIMEOUT]),
        ("render spec", ["render", "spec", str(path), "-o", str(fx.out / "spec.dot")]),
    ]


def _check_commands(path: Path, _seed: str, _fx: Fixtures) -> list[tuple[str, list[str]]]:
    return [("check", ["check", str(path), "--timeout", CHECK_TIMEOUT])]


def _robot_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    # lint reads the robot file through the primitives of a spec beside it that names it
    spec = path.parent / "robot_user.gait"
    spec.write_text(ROBOT_USER.format(robot=path.name), encoding="utf-8")
    return [
        ("gaits random", ["gaits", str(path), "--method", "random", "--max-states", "30",
                          "--direction", "+y"]),
        ("gaits full", ["gaits", str(path), "--method", "full", "--max-states", "64"]),
        ("gaits lpa", ["gaits", str(path), "--method", "lpa", "--goal", "20,0",
                       "--max-states", "30", "--budget", "3000"]),
        ("gaits mcts", ["gaits", str(path), "--method", "mcts", "--goal", "20,0",
                        "--max-states", "30", "--iterations", "100"]),
        # a mutated robot file can make the primitive search take 20 s: bounded, as a user
        # bounds it, well inside the kind's limit (exit 4 is an answer, not a hang)
        ("lint", ["lint", str(spec), "--timeout", "10"]),
    ]


def _scenario_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    return [("simulate", ["simulate", str(HAZARD_SPEC), str(fx.hazard_controller),
                          "--env", "scripted", str(path), "--steps", "20", "--quiet"])]


def _controller_commands(path: Path, seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    spec = str(fx.spec_of_controller(seed))
    return [
        ("verify", ["verify", spec, str(path)]),
        ("simulate", ["simulate", spec, str(path), "--env", "random", "--seed", "1",
                      "--steps", "10", "--quiet"]),
        ("render automaton", ["render", "automaton", spec, str(path),
                              "-o", str(fx.out / "automaton.dot")]),
    ]


def _compact_commands(path: Path, seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    """The commands that take a compact controller (the 'controller' kind's, with the
    policy tables in place of the automaton's drawing, and codegen)."""
    spec = str(fx.spec_of_controller(seed))
    return [
        ("verify", ["verify", spec, str(path)]),
        ("simulate", ["simulate", spec, str(path), "--env", "random", "--seed", "1",
                      "--steps", "10", "--quiet"]),
        ("render policy", ["render", "policy", spec, str(path),
                           "-o", str(fx.out / "policy.txt")]),
        ("codegen c", ["codegen", spec, str(path), "--target", "c",
                       "-o", str(fx.out / "gen")]),
    ]


def _run_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    return [("render map", ["render", "map", str(PATROL), "--run", str(path),
                            "-o", str(fx.out / "map.dot")])]


def _map_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    return [("drive physics --map", ["drive", str(SHUTTLE), str(fx.shuttle_controller),
                                     "--backend", "physics", "--robot", str(RADIAL8),
                                     "--map", str(path), "--steps", "2", "--cycles", "1"])]


def _sensing_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    # the sensing file is read and checked against the spec before the port is opened;
    # loop:// is pyserial's loopback, which answers no handshake (exit 1 when it is good)
    return [("drive serial --sensing", ["drive", str(SHUTTLE), str(fx.shuttle_controller),
                                        "--backend", "serial", "--port", "loop://",
                                        "--sensing", str(path), "--steps", "1"])]


def _calibration_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    return [("calibrate", ["calibrate", str(path), "-o", str(fx.out / "legs.sensing.yaml")])]


def _curvature_commands(path: Path, _seed: str, fx: Fixtures) -> list[tuple[str, list[str]]]:
    return [("characterize --curvature", ["characterize", str(ONE_LIMB), "L1", "--curvature",
                                          str(path), "-o", str(fx.out / "limb.yaml")])]


def controller_seeds(fx: Fixtures) -> tuple[tuple[str, bytes], ...]:
    return (("patrol.json", fx.patrol_controller.read_bytes()),
            ("hazard.json", fx.hazard_controller.read_bytes()))


def compact_seeds(fx: Fixtures) -> tuple[tuple[str, bytes], ...]:
    return (("patrol.compact.json", fx.patrol_compact.read_bytes()),
            ("hazard.compact.json", fx.hazard_compact.read_bytes()))


#: Every fuzzed kind by name, in the order of :func:`kinds` (``bench/fuzz.py --kinds``).
KIND_NAMES = ("gait", "slugsin", "structuredslugs", "ltl", "robot", "scenario", "controller",
              "compact", "run", "map", "sensing", "calibration", "curvature")


def kinds(fx: Fixtures) -> dict[str, Kind]:
    """Every fuzzed input kind that a gaitc command reads, by name."""
    found = [
        Kind("gait", ".gait", _files((SPECS, "*.gait"), (GOLDEN, "*.gait")), _gait_commands),
        Kind("slugsin", ".slugsin",
             _files((GOLDEN, "*.slugsin"), (SLUGS_EXAMPLES, "*.slugsin")), _check_commands),
        Kind("structuredslugs", ".structuredslugs",
             _files((GOLDEN, "*.structuredslugs"), (SLUGS_EXAMPLES, "*.structuredslugs")),
             _check_commands),
        Kind("ltl", ".ltl", tuple((p.name, p.read_bytes()) for p in fx.ltl), _check_commands),
        Kind("robot", ".yaml", _files((SPECS / "robots", "*.yaml")), _robot_commands, 3.0),
        Kind("scenario", ".yaml", tuple((n, t.encode()) for n, t in SCENARIOS),
             _scenario_commands),
        Kind("controller", ".json", controller_seeds(fx), _controller_commands),
        Kind("compact", ".json", compact_seeds(fx), _compact_commands),
        Kind("run", ".jsonl", (("patrol.run.jsonl", fx.run_file.read_bytes()),), _run_commands),
        Kind("map", ".yaml", tuple((n, t.encode()) for n, t in MAPS), _map_commands, 3.0),
        Kind("sensing", ".yaml", tuple((n, t.encode()) for n, t in SENSING), _sensing_commands),
        Kind("calibration", ".csv", tuple((n, t.encode()) for n, t in CALIBRATION),
             _calibration_commands),
        Kind("curvature", ".csv", tuple((n, t.encode()) for n, t in CURVATURE),
             _curvature_commands),
    ]
    assert tuple(kind.name for kind in found) == KIND_NAMES
    return {kind.name: kind for kind in found}


def run_case(kind: Kind, fx: Fixtures, seed: str, data: bytes, limit: float) -> list[Verdict]:
    """Write the mutant, run every command of its kind on it, judge each run."""
    path = write_mutant(fx.out, kind.suffix, data)
    verdicts = []
    for name, argv in kind.commands(path, seed, fx):
        files = {str(path): data}
        if kind.name == "robot":
            user = path.parent / "robot_user.gait"
            files[str(user)] = user.read_bytes()
        verdicts.append(run_command(name, argv, files, limit * kind.slowness))
    return verdicts
