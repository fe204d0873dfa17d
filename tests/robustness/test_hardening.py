"""Regressions for the hostile inputs of issue 9 that are fixed: each is a positioned error
(exit 1), never an internal error (exit 70)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gaitc.cli import main

ROOT = Path(__file__).resolve().parents[2]
PATROL = str(ROOT / "specs" / "patrol_2x2.gait")
BIG = "1" * 5000


def _run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str]:
    code = main(list(argv))
    return code, capsys.readouterr().err


@pytest.mark.parametrize(("line", "message"), [
    ("$ ² b b", "found '²'"),
    (f"$ {BIG} a", "found a number of 5000 digits; the limit is 9 digits"),
])
def test_slugsin_counts(tmp_path: Path, capsys: pytest.CaptureFixture[str], line: str,
                        message: str) -> None:
    path = tmp_path / "bad.slugsin"
    path.write_text(f"[INPUT]\na\nb\n[OUTPUT]\nc\n[SYS_TRANS]\n{line}\n", encoding="utf-8")
    code, err = _run(capsys, "check", str(path))
    assert code == 1 and f"{path}:7:3: error:" in err and message in err


@pytest.mark.parametrize(("text", "where", "message"), [
    (f"[INPUT]\nx:0...3\n[OUTPUT]\nc\n[SYS_TRANS]\nx = {BIG}\n", ":6:5:",
     "the number has 5000 digits; the limit is 18"),
    (f"[INPUT]\nx:0...{BIG}\n[OUTPUT]\nc\n", ":2:1:", "bad integer range"),
])
def test_structuredslugs_huge_numbers(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                      text: str, where: str, message: str) -> None:
    path = tmp_path / "bad.structuredslugs"
    path.write_text(text, encoding="utf-8")
    code, err = _run(capsys, "check", str(path))
    assert code == 1 and where in err and message in err


@pytest.fixture(scope="module")
def controller(tmp_path_factory: pytest.TempPathFactory) -> dict[str, object]:
    out = tmp_path_factory.mktemp("c") / "c.json"
    assert main(["synth", PATROL, "-o", str(out)]) == 0
    data: dict[str, object] = json.loads(out.read_text(encoding="utf-8"))
    return data


def _mutated(controller: dict[str, object], key: str, value: object) -> bytes:
    data = json.loads(json.dumps(controller))
    data["gaitc"][key] = value
    return json.dumps(data).encode("utf-8")


@pytest.mark.parametrize("case", ["inputs-nested", "inputs-number", "not-utf8", "deep",
                                  "huge-rank", "bool-initial", "bogus-semantics"])
def test_controller_files(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                          controller: dict[str, object], case: str) -> None:
    raw = {
        "inputs-nested": lambda: _mutated(controller, "inputs", [[1]]),
        "inputs-number": lambda: _mutated(controller, "inputs", 5),
        "not-utf8": lambda: b'{"a": "\xff\xfe"}',
        "deep": lambda: b"[" * 100_000 + b"]" * 100_000,
        "huge-rank": lambda: json.dumps(controller).replace(
            '"rank": 0', '"rank": ' + BIG, 1).encode("utf-8"),
        "bool-initial": lambda: _mutated(controller, "initial", [True]),
        "bogus-semantics": lambda: _mutated(controller, "semantics", "bogus"),
    }[case]()
    path = tmp_path / "bad.json"
    path.write_bytes(raw)
    for command in ("verify", "simulate"):
        code, err = _run(capsys, command, PATROL, str(path))
        assert code == 1, (command, err)
        assert f"{path}:1:" in err and "internal error" not in err


SCENARIO_HEAD = "steps:\n"


@pytest.mark.parametrize(("raw", "where", "message"), [
    (b"s\xc3tart: {}\n", ":1:2:", "is not UTF-8 text (byte 0xc3 at offset 1)"),
    (b"steps:\n  - {note: a\x00}\n", ":2:", "which YAML does not allow"),
    (b"steps: " + b"[" * 1000 + b"]" * 1000 + b"\n", ":1:", "nests"),
    (b"steps: !!python/object:os.system {}\n", ":1:8:", "'steps' must be a list"),
])
def test_scenario_files(tmp_path: Path, capsys: pytest.CaptureFixture[str], raw: bytes,
                        where: str, message: str) -> None:
    path = tmp_path / "bad.yaml"
    path.write_bytes(raw)
    code, err = _run(capsys, "simulate", PATROL, "--env", "scripted", str(path))
    assert code == 1, err
    assert f"{path}{where}" in err and message in err


def test_robot_files_use_the_safe_loader(tmp_path: Path) -> None:
    from gaitc.diagnostics import GaitcError
    from gaitc.gaitgraph.robot import load_robot

    path = tmp_path / "evil.yaml"
    path.write_text("robot: !!python/object/apply:os.system ['true']\n", encoding="utf-8")
    with pytest.raises(GaitcError, match="robot file has no 'chassis' section"):
        load_robot(str(path))  # composed as plain nodes, never constructed: nothing runs
    path.write_bytes(b"robot: \xff\n")
    with pytest.raises(GaitcError, match="not UTF-8"):
        load_robot(str(path))


@pytest.mark.parametrize("odd", ["\x0c", "\x0b", "\x1c", "\x1d", "\x1e", "\x85", "\u2028",
                                 "\u2029"])
def test_odd_line_separators_do_not_shift_the_caret(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str],
                                                     odd: str) -> None:
    text = (f"# a comment with {odd} inside\nlegs L1 health 2\n"
            "gait g uses L9 moves north\ngrid 2 x 1\nstart r0\n")
    path = tmp_path / "odd.gait"
    path.write_text(text, encoding="utf-8")
    code, err = _run(capsys, "lint", str(path))
    assert code == 1
    assert f"{path}:3:13: error: unknown leg 'L9'" in err
    assert err.splitlines()[1].strip() == "gait g uses L9 moves north"


def test_a_robot_name_with_a_line_separator_round_trips(tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]
                                                        ) -> None:
    spec = tmp_path / "named.gait"
    spec.write_text('robot "a\u2028b"\nlegs L1 health 2\ngait g uses L1 moves north\n'
                    "grid 2 x 1\nstart r0\n", encoding="utf-8")
    for fmt in ("structuredslugs", "slugsin", "ltl"):
        out = tmp_path / f"named.{fmt}"
        assert main(["compile", str(spec), "-o", str(out), "--format", fmt]) == 0
        assert main(["check", str(out)]) == 0, capsys.readouterr().err


@pytest.mark.parametrize(("health", "message"), [
    ("100000", "health 100000 is more than the 100 levels gaitc supports"),
    ("1000000000", "the number has 10 digits; numbers in a .gait file have at most 9"),
    (BIG, "the number has 5000 digits"),
])
def test_huge_health_is_refused_before_any_bdd(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str],
                                               health: str, message: str) -> None:
    path = tmp_path / "huge.gait"
    path.write_text(f"legs L1 health {health}\ngait g uses L1 moves north\ngrid 2 x 1\n"
                    "start r0\n", encoding="utf-8")
    code, err = _run(capsys, "check", str(path), "--timeout", "2")
    assert code == 1 and f"{path}:1:16: error: {message}" in err


@pytest.mark.parametrize("delay", [0.5, 1.0, 2.0])  # once the interpreter has started
def test_ctrl_c_at_any_moment_is_one_line_and_exit_130(delay: float) -> None:
    import signal
    import subprocess
    import sys
    import time

    # A shell without job control starts background jobs with SIGINT ignored, and a child
    # inherits that; a user's Ctrl-C comes from a terminal, where it is not ignored.
    proc = subprocess.Popen([sys.executable, "-m", "gaitc", "explain",
                             "specs/thesis_robot_a_health2.gait"], cwd=ROOT,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert err.strip() == "gaitc: interrupted"
