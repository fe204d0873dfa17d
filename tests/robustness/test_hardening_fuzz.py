"""Regressions for the defects the fuzz suite found (issue 9): each input gives a positioned
error that shows its own line, within its limit, never an internal error."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from fuzz_serial import ReplayPort, board_over

from gaitc.cli import main
from gaitc.diagnostics import ScenarioError, span_at
from gaitc.diagnostics.files import decode_text
from gaitc.hw.backend import HardwareError
from gaitc.hw.serial_board import MAX_REPLY, parse_pong, parse_sensors

ROOT = Path(__file__).resolve().parents[2]
PATROL = str(ROOT / "specs" / "patrol_2x2.gait")
HAZARD = str(ROOT / "tests" / "data" / "hazard_patrol.gait")
RADIAL8 = str(ROOT / "specs" / "robots" / "radial8.yaml")


def _run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, list[str]]:
    code = main(list(argv))
    return code, capsys.readouterr().err.split("\n")


def test_span_at_counts_lines_as_source_lines_does() -> None:
    assert str(span_at("ab\ncd\n", "f", 6)) == "f:2:3"  # at the end: the last line's end
    assert str(span_at("ab\r\ncd\r\n", "f", 8)) == "f:2:3"
    assert str(span_at("a\x85b\u2028c\rd\n", "f", 6)) == "f:1:7"
    assert str(span_at("", "f", 0)) == "f:1:1"


def test_decode_error_column_counts_characters() -> None:
    with pytest.raises(ScenarioError) as info:
        decode_text("ééé".encode() + b"\xff\n", "x.yaml", ScenarioError)
    assert str(info.value.span) == "x.yaml:1:4"


@pytest.mark.parametrize(("raw", "where", "shown"), [
    (b'{"gaitc": 1,\n', ":1:13:", '{"gaitc": 1,'),  # truncated: not line 2 of 1
    (b'{"a": 1,\r"b": \n', ":1:15:", '{"a": 1,?"b": '),  # a lone \r ends no line; shown as ?
])
def test_controller_json_errors_point_at_existing_lines(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], raw: bytes, where: str,
        shown: str) -> None:
    path = tmp_path / "c.json"
    path.write_bytes(raw)
    code, err = _run(capsys, "verify", PATROL, str(path))
    assert code == 1 and err[0].startswith(f"{path}{where}"), err
    assert err[1] == f"    {shown}"


def test_run_files_not_utf8_and_lone_cr(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                        ) -> None:
    path = tmp_path / "run.jsonl"
    path.write_bytes(b'{"kind": "run", "legs": ["L1"]}\n{"kind": "st\xc4p"}\n')
    code, err = _run(capsys, "render", "map", PATROL, "--run", str(path),
                     "-o", str(tmp_path / "m.dot"))
    assert code == 1 and err[0].startswith(f"{path}:2:13: error: '{path}' is not UTF-8")
    path.write_bytes(b'{"kind": "run",\r "legs": ["L1"]}\n{"kind": "step"}\n')
    code, err = _run(capsys, "render", "map", PATROL, "--run", str(path),
                     "-o", str(tmp_path / "m.dot"))
    assert code == 1 and err[0].startswith(f"{path}:2:1: error: not a run")
    assert err[1] == '    {"kind": "step"}'  # a lone \r ends no line, here as in the reader
    path.write_bytes(b"[" * 100_000 + b"\n")
    code, err = _run(capsys, "render", "map", PATROL, "--run", str(path),
                     "-o", str(tmp_path / "m.dot"))
    assert code == 1 and err[0].startswith(f"{path}:1:1: error: not a run")


@pytest.mark.parametrize("odd", ["\r", "\x85", "\u2028", "\u2029"])
def test_yaml_positions_use_the_one_line_rule(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str],
                                              odd: str) -> None:
    path = tmp_path / "s.yaml"
    path.write_text(f'# a scenario\nsteps:\n  - {{note: "a{odd}b"}}\n  - degrade: [L9]\n',
                    encoding="utf-8")
    code, err = _run(capsys, "simulate", HAZARD, "--env", "scripted", str(path))
    assert code == 1 and err[0].startswith(f"{path}:4:15: error: unknown leg 'L9'"), err
    assert err[1] == "      - degrade: [L9]"


def test_yaml_error_at_the_end_points_at_the_last_line(tmp_path: Path,
                                                       capsys: pytest.CaptureFixture[str]
                                                       ) -> None:
    path = tmp_path / "s.yaml"
    path.write_text("steps:\n  - {}\n  - [\n", encoding="utf-8")
    code, err = _run(capsys, "simulate", HAZARD, "--env", "scripted", str(path))
    assert code == 1 and err[0].startswith(f"{path}:3:6: error: scenario is not valid YAML")
    assert err[1] == "      - ["


@pytest.mark.parametrize(("text", "message"), [
    ("a: &a [x, x, x, x, x, x, x, x, x, x]\n"
     + "".join(f"{n}: &{n} [{', '.join([f'*{p}'] * 10)}]\n"
       for p, n in zip("abcde", "bcdef", strict=True))
     + "steps: [*f]\n", "more than 200000 values once its aliases are expanded"),
    ("steps: &a [*a]\n", "nests deeper than 200 levels"),
])
def test_yaml_aliases_are_bounded(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                  text: str, message: str) -> None:
    path = tmp_path / "s.yaml"
    path.write_text(text, encoding="utf-8")
    start = time.perf_counter()
    code, err = _run(capsys, "simulate", HAZARD, "--env", "scripted", str(path))
    assert code == 1 and message in err[0], err
    assert time.perf_counter() - start < 10


@pytest.mark.parametrize("line", ["PONG fw valves=²", "PONG fw valves=" + "9" * 5000,
                                  "PONG fw valves=٣"])
def test_pong_needs_short_ascii_digits(line: str) -> None:
    from gaitc.hw.serial_board import Garbled

    with pytest.raises(Garbled):
        parse_pong(line)


@pytest.mark.parametrize("levels", ["3,²", "3," + "1" * 5000, "3,-1"])
def test_sensor_levels_need_short_ascii_digits(levels: str) -> None:
    from gaitc.hw.serial_board import Garbled

    with pytest.raises(Garbled):
        parse_sensors(f"S h={levels}", ("L1", "L2"))


def test_a_babbling_board_is_a_bounded_garbled_answer() -> None:
    port = ReplayPort((b"PONG fw valves=8 " + b"x" * 100_000 + b"\n") * 3)
    board = board_over(port)
    with pytest.raises(HardwareError, match=f"longer than {MAX_REPLY} bytes"):
        board._ask("PING", parse_pong)


def test_full_gait_search_honours_max_states(capsys: pytest.CaptureFixture[str]) -> None:
    start = time.perf_counter()
    code, err = _run(capsys, "gaits", RADIAL8, "--model", "kinematic", "--method", "full",
                     "--max-states", "50")
    assert code == 2 and "enumerates all 2^8 = 256 valve states" in err[0]
    assert "more than --max-states 50" in err[0]
    assert time.perf_counter() - start < 3


@pytest.mark.parametrize("method", ["random", "reset", None])
def test_other_searches_stop_at_max_states_and_say_so(
        capsys: pytest.CaptureFixture[str], method: str | None) -> None:
    chosen = [] if method is None else ["--method", method]
    assert main(["gaits", RADIAL8, "--model", "kinematic", "--max-states", "40", *chosen]) == 1
    out = capsys.readouterr().out
    assert f"method {method or 'random'}, 40 valve states" in out
    assert "the search stopped at --max-states 40 of the 256 valve states" in out


@pytest.mark.parametrize(("step", "health", "message"), [
    ("1e400", "2", "not a run written by 'gaitc simulate"),  # int(inf): OverflowError
    ("1", None, "step 1 gives the health of L1 but the run's legs are L1, L2, L3, L4"),
])
def test_run_file_steps_are_checked(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                    step: str, health: str | None, message: str) -> None:
    def line(number: str, levels: dict[str, str]) -> str:
        shown = ", ".join(f'"{k}": {v}' for k, v in levels.items())
        return (f'{{"kind": "step", "step": {number}, "node": 0, "region": "nw", '
                f'"gait": "noGait", "legs_used": [], "health": {{{shown}}}}}')

    every = {leg: health or "2" for leg in ("L1", "L2", "L3", "L4")}
    path = tmp_path / "run.jsonl"
    path.write_text('{"kind": "run", "legs": ["L1", "L2", "L3", "L4"]}\n'
                    f"{line('0', every)}\n{line(step, every if health else {'L1': '2'})}\n",
                    encoding="utf-8")
    code, err = _run(capsys, "render", "map", PATROL, "--run", str(path),
                     "-o", str(tmp_path / "m.dot"))
    assert code == 1 and err[0].startswith(f"{path}:3:1: error: {message}"), err


@pytest.mark.parametrize(("robot", "message"), [
    ("a" * 300 + ".yaml", "not found"),  # OSError: File name too long was an internal error
    ("a\x00b.yaml", "not found"),
    (".", "is a folder"),  # was an error without a position
])
def test_primitive_robot_names_the_system_refuses(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str],
                                                  robot: str, message: str) -> None:
    path = tmp_path / "p.gait"
    path.write_text(f'legs L1 health 2\ngait g uses L1 moves north primitive "{robot}" '
                    "direction +y\ngrid 2 x 1\nstart r0\n", encoding="utf-8")
    code, err = _run(capsys, "lint", str(path))
    located = [line for line in err if line.startswith(f"{path}:2:28: error: gait g: robot")]
    assert code == 1 and located and message in located[0], err


BIG = "1" * 5000


@pytest.mark.parametrize(("legs", "gait_leg", "message"), [
    (f"L{BIG}..L4", "L1", "1:6: error: range L1111111111111111111..L4: a number of 5000 "
                          "digits; the names of a range end in numbers of at most 9 digits"),
    (f"L1, L{BIG}", "L9", "2:13: error: unknown leg 'L9' in gait g; declared legs are L1, "
                          "L111"),  # the list of names said int() of 5000 digits
])
def test_names_with_huge_numbers(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                 legs: str, gait_leg: str, message: str) -> None:
    path = tmp_path / "n.gait"
    path.write_text(f"legs {legs} health 2\ngait g uses {gait_leg} moves north\n"
                    "grid 2 x 1\nstart r0\n", encoding="utf-8")
    code, err = _run(capsys, "lint", str(path))
    assert code == 1 and err[0].startswith(f"{path}:{message}"), err[0][:300]


def test_a_value_with_a_line_break_keeps_the_message_on_one_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "s.yaml"
    path.write_text("steps:\n  - {fail: L2 | L2\n\n     | L2}\n", encoding="utf-8")
    code, err = _run(capsys, "simulate", HAZARD, "--env", "scripted", str(path))
    assert code == 1 and err[0].startswith(f"{path}:2:12: error: unknown leg 'L2 | L2\\n| L2'")
    assert err[1] == "      - {fail: L2 | L2"  # the source line comes right after the message
