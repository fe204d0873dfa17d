"""``--timeout`` and ``--memory-limit`` hold on every kind of input the solver reads (issue 9).

Each case runs gaitc as a user does, in its own process, on a task far too big for the
limit: the thesis-style 30 x 30 grid of bench/bench_solver.py in both encodings and as a
.slugsin file, and robot A's synthesis (limited during extraction and verification). The
command must end with exit 4, one message and its JSON record, within one second of the
time limit (the record's own clock; the process as a whole also pays Python's start-up),
and below the memory limit (the largest resident size of any process it started).
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import pytest

import gaitc

ROOT = Path(__file__).resolve().parents[2]
GRID = ROOT / "tests" / "data" / "limits" / "grid30_h5.gait"
ROBOT_A = ROOT / "specs" / "thesis_robot_a.gait"
STARTUP = 1.5  # seconds a loaded CI machine may need to start Python and import gaitc


def gaitc_run(*argv: str, cwd: Path | None = None) -> tuple[int, str, str, float]:
    started = time.monotonic()
    proc = subprocess.run([sys.executable, "-m", "gaitc", *argv], capture_output=True,
                          text=True, cwd=cwd, timeout=120, check=False)
    return proc.returncode, proc.stdout, proc.stderr, time.monotonic() - started


@pytest.fixture(scope="module")
def amba10(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The AMBA AHB arbiter with 10 masters (bench/families/amba.py): 19 s or more here.

    Eight masters, used before, took only 4-7 s, and a fast CI machine decided it within
    the 2 s limit: the case must stay far above the limit for the test to mean anything."""
    sys.path.insert(0, str(ROOT))
    from bench.families.amba import amba_text

    path = tmp_path_factory.mktemp("limits") / "amba10.structuredslugs"
    path.write_text(amba_text(10), encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def grid_slugsin(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("limits") / "grid30_h5.slugsin"
    path.write_text(gaitc.emit(gaitc.load(GRID, "binary"), "slugsin"), encoding="utf-8")
    return path


def _inputs(grid_slugsin: Path) -> dict[str, list[str]]:
    return {"onehot": [str(GRID), "--encoding", "onehot"],
            "binary": [str(GRID), "--encoding", "binary"],
            "slugsin": [str(grid_slugsin)]}


@pytest.mark.parametrize("kind", ["onehot", "binary", "slugsin", "amba"])
def test_timeout_stops_check_within_a_second(kind: str, grid_slugsin: Path,
                                             amba10: Path) -> None:
    """The thesis grid and AMBA: the static order and (after its head start) the racing
    sifted order are both cut off (gaitc.solver.portfolio)."""
    argv = [str(amba10)] if kind == "amba" else _inputs(grid_slugsin)[kind]
    code, out, err, wall = gaitc_run("check", *argv, "--timeout", "2", "--json")
    assert code == 4, err
    record = json.loads(out)
    assert record["verdict"] == "error"
    assert record["error"]["message"] == "synthesis stopped after the time limit of 2 s"
    assert record["seconds"] <= 3.0
    assert wall <= 3.0 + STARTUP
    assert err.count("error:") == 1


def test_timeout_stops_synthesis_and_writes_nothing(
        tmp_path: Path, tmp_path_factory: pytest.TempPathFactory) -> None:
    """A 10 x 10 grid at health 4 (several minutes to synthesize; thesis robot A, used here
    before, now synthesizes within the limit on a fast machine)."""
    sys.path.insert(0, str(ROOT))
    from bench.families.thesis import gait_text

    spec = tmp_path_factory.mktemp("limits") / "grid10_h4.gait"
    spec.write_text(gait_text(10, 10, 4), encoding="utf-8")
    out_file = tmp_path / "a.json"
    code, _, err, wall = gaitc_run("synth", str(spec), "--timeout", "0.5", "-o",
                                   str(out_file))
    assert code == 4, err
    assert "time limit of 0.5 s" in err
    assert wall <= 1.5 + STARTUP
    assert list(tmp_path.iterdir()) == []


def test_timeout_stops_resilience_and_its_workers(tmp_path: Path) -> None:
    """resilience --timeout (issue 38): robot A with 100 health levels a leg takes minutes;
    the analysis and its two workers stop a second past the limit, with one JSON record."""
    spec = tmp_path / "robot_a_h100.gait"
    spec.write_text(ROBOT_A.read_text(encoding="utf-8").replace("health 3", "health 100"),
                    encoding="utf-8")
    code, out, err, wall = gaitc_run("resilience", str(spec), "--jobs", "2", "--timeout",
                                     "1", "--json")
    assert code == 4, err
    record = json.loads(out)
    assert record["error"]["message"] == (
        "the resilience analysis stopped after the time limit of 1 s")
    assert wall <= 2.0 + STARTUP
    assert err.count("error:") == 1


@pytest.mark.parametrize("kind", ["onehot", "binary"])
def test_memory_limit_is_exit_4_below_the_bound(kind: str, grid_slugsin: Path) -> None:
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    code, out, err, _ = gaitc_run("check", *_inputs(grid_slugsin)[kind], "--memory-limit",
                                  "100", "--timeout", "60", "--json")
    peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    assert code == 4, err
    record = json.loads(out)
    assert record["error"]["message"] == "synthesis ran out of memory"
    assert "hint: raise --memory-limit" in err
    if before / 1024 < 100:  # else an earlier child of this test process set the maximum
        assert peak_mb <= 100


def test_a_memory_limit_below_gaitc_itself_says_how_much_is_needed() -> None:
    code, out, err, _ = gaitc_run("check", str(ROBOT_A), "--memory-limit", "20", "--json")
    assert code == 4
    record = json.loads(out)
    assert record["error"]["message"].startswith("a memory limit of 20 MB is too small: "
                                                 "gaitc itself takes ")
    assert "hint: give --memory-limit at least" in err


def test_a_sufficient_memory_limit_changes_nothing(tmp_path: Path) -> None:
    code, out, err, _ = gaitc_run("synth", str(ROBOT_A), "--memory-limit", "2000",
                                  "--timeout", "100", "-o", str(tmp_path / "a.json"))
    assert code == 0, err
    assert "realizable" in out and "verified" in out
    assert json.loads((tmp_path / "a.json").read_text(encoding="utf-8"))["nodes"]


@pytest.mark.parametrize(("value", "message"), [
    ("0", "must be a positive number of megabytes, not 0"),
    ("-5", "must be a positive number of megabytes, not -5"),
    ("1.5", "'1.5' is not a whole number of megabytes"),
    ("lots", "'lots' is not a whole number of megabytes"),
])
def test_bad_memory_limits_are_usage_errors(value: str, message: str) -> None:
    code, _, err, _ = gaitc_run("check", str(ROBOT_A), f"--memory-limit={value}")
    assert code == 2
    assert message in err


def test_no_limit_runs_in_process() -> None:
    """Without limits nothing is forked (the library's answer is the command's)."""
    from gaitc.api.isolation import HardLimits, run_limited

    assert run_limited(os.getpid, HardLimits()) == os.getpid()
    assert run_limited(os.getpid, HardLimits(seconds=10)) != os.getpid()


@pytest.mark.parametrize(("value", "message"), [
    ("nan", "must be a positive, finite number of seconds, not nan"),
    ("inf", "must be a positive, finite number of seconds, not inf"),
    ("-1", "must be a positive, finite number of seconds, not -1"),
    ("0", "must be a positive, finite number of seconds, not 0"),
    ("soon", "'soon' is not a number of seconds"),
])
@pytest.mark.parametrize("command", ["check", "synth", "explain", "resilience"])
def test_bad_timeouts_are_usage_errors(value: str, message: str, command: str,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    """Reproducer 9 of issue 9: ``--timeout nan`` was ignored, ``--timeout -1`` accepted."""
    from gaitc.cli import main

    assert main([command, str(ROBOT_A), f"--timeout={value}"]) == 2
    assert message in capsys.readouterr().err


def test_a_solved_game_is_freed_without_the_garbage_collector() -> None:
    """No reference cycle keeps a BDD manager alive: the memory check the limits hold is a
    weak reference (a cycle left managers to the collector, which at shutdown freed one
    before its nodes: "Still 1636 nodes referenced upon shutdown" on centipede24)."""
    import gc
    import weakref

    from gaitc.solver.game import Limits
    from gaitc.solver.symbolic import Options
    from gaitc.solver.synthesis import _game

    spec = gaitc.load(ROOT / "specs" / "patrol_2x2.gait").gr1
    gc.disable()
    try:
        limits = Limits(10.0)
        sym, game = _game(spec, "default", Options(), limits)
        game.solve()
        limits.check()
        alive = weakref.ref(sym)
        del sym, game, limits
        assert alive() is None
    finally:
        gc.enable()


def test_timeout_stops_the_search_behind_a_primitive(tmp_path: Path) -> None:
    """lint --timeout (issue 38's campaign of 100,000 inputs): a mutated robot file whose
    primitive search takes 20 s (tests/data/limits/slow_primitive_robot.yaml) stops a
    second past the limit, with the hint that names the slow part."""
    robot = ROOT / "tests" / "data" / "limits" / "slow_primitive_robot.yaml"
    spec = tmp_path / "uses_it.gait"
    spec.write_text(f'legs L1..L8 health 2\ngait north_a uses L6, L8 moves north primitive '
                    f'"{robot}" direction +y\ngrid 2 x 1\nstart r0\n', encoding="utf-8")
    code, out, err, wall = gaitc_run("lint", str(spec), "--timeout", "1", "--json")
    assert code == 4, err
    assert json.loads(out)["error"]["message"] == "the lint stopped after the time limit of 1 s"
    assert "the search behind a gait's primitive" in err
    assert wall <= 2.0 + STARTUP
