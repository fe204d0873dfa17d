"""``--json`` on every reporting command: the keys docs/json.md lists, errors as objects.

The documented keys are read from the tables of docs/json.md, so the page cannot drift
from what the commands print (gaitc/cli/reporting.py).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import gaitc
from gaitc.cli import main
from gaitc.cli.reporting import SCHEMA
from gaitc.diagnostics import GaitcError

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "json.md"
PATROL = str(ROOT / "specs" / "patrol_2x2.gait")
SHUTTLE = str(ROOT / "specs" / "shuttle_2leg.gait")
UNREALIZABLE = str(ROOT / "specs" / "unrealizable_2x2.gait")
ROBOT = str(ROOT / "specs" / "robots" / "symmetric6.yaml")
COMMON = {"schema", "command"}
#: A .gait file with a syntax error on line 2, column 22 (a character no name has).
BROKEN = "leg L1 health 2\ngait g uses L1 moves @\nregion a, b\nstart a\n"
#: One leg failed from the start: the gait that uses it draws a warning on line 6, col 17.
WARNED = ('robot "w"\n\nleg L1 health 2\nleg L2 health 1\ngait go uses L1 moves a -> b, '
          'b -> a\ngait never uses L2 moves a -> b\n\nregion a, b\nstart a\n'
          'visit b infinitely often\n')


def documented() -> dict[str, set[str]]:
    """The keys of each table of docs/json.md, by the heading above it (lower case)."""
    tables: dict[str, set[str]] = {}
    heading = ""
    for line in DOC.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            heading = line.lstrip("#").strip().lower()
            continue
        found = re.match(r"\| `([a-z_0-9]+)` \|", line)
        if found and heading:
            tables.setdefault(heading, set()).add(found.group(1))
    return tables


DOCUMENTED = documented()


def keys(*sections: str) -> set[str]:
    out: set[str] = set()
    for name in sections:
        assert name in DOCUMENTED, f"docs/json.md has no table under '{name}'"
        out |= DOCUMENTED[name]
    return out


def run_json(argv: list[str], capsys: pytest.CaptureFixture[str]
             ) -> tuple[int, list[dict[str, Any]], str]:
    """Run gaitc in-process; every stdout line must be one sorted JSON object."""
    code = main(argv)
    captured = capsys.readouterr()
    lines = captured.out.splitlines()
    objects = [json.loads(line) for line in lines]
    for line, obj in zip(lines, objects, strict=True):
        assert line == json.dumps(obj, sort_keys=True, ensure_ascii=False), "keys unsorted"
        assert obj["schema"] == SCHEMA
    return code, objects, captured.err


def one(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, dict[str, Any]]:
    code, objects, _ = run_json(argv, capsys)
    assert len(objects) == 1, objects
    return code, objects[0]


@pytest.fixture(scope="module")
def controllers(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    folder = tmp_path_factory.mktemp("json")
    out = {}
    for name, spec in (("patrol", PATROL), ("shuttle", SHUTTLE)):
        path = folder / f"{name}.json"
        gaitc.synthesize(gaitc.load(spec)).save(path)
        out[name] = str(path)
    return out


def test_the_doc_has_a_table_for_every_command_and_shared_object() -> None:
    for name in ("the rules", "the error object", "lint", "the diagnostic object", "compile",
                 "check", "synth and counter", "verify", "the verification object",
                 "simulate", "drive", "the step object", "the summary object", "explain",
                 "resilience", "gaits", "gaits --method astar, lpa, dstar, mcts"):
        assert DOCUMENTED.get(name), name
    assert DOCUMENTED["the rules"] == COMMON
    assert DOCUMENTED["the error object"] == {"type", "file", "line", "column", "message",
                                              "hint"}


def test_lint_and_its_diagnostics(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "w.gait"
    spec.write_text(WARNED, encoding="utf-8")
    code, obj = one(["lint", str(spec), "--json"], capsys)
    assert code == 0 and obj["command"] == "lint"
    assert set(obj) == COMMON | keys("lint")
    assert (obj["errors"], obj["warnings"], obj["deep"]) == (0, 1, None)
    [diag] = obj["diagnostics"]
    assert set(diag) == keys("the diagnostic object")
    assert (diag["severity"], diag["file"], diag["line"], diag["column"]) == (
        "warning", str(spec), 6, 17)
    assert "permanently failed" in diag["message"]
    code, obj = one(["lint", PATROL, "--deep", "--json"], capsys)
    assert code == 0 and obj["deep"] == {"verdict": "realizable", "kind": None, "warnings": []}


def test_compile_to_stdout_holds_the_text_and_to_a_file_its_size(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code, obj = one(["compile", PATROL, "--json"], capsys)
    assert code == 0 and set(obj) == COMMON | keys("compile")
    assert main(["compile", PATROL]) == 0
    assert obj["text"] == capsys.readouterr().out
    assert obj["bytes"] == len(obj["text"].encode()) and obj["lines"] == obj["text"].count("\n")
    spec = gaitc.load(PATROL)
    assert (obj["inputs"], obj["outputs"]) == (len(spec.gr1.inputs), len(spec.gr1.outputs))
    assert sum(obj["clauses"].values()) == spec.clause_count() >= obj["source_map"] > 0
    out = tmp_path / "p.ltl"
    code, obj = one(["compile", PATROL, "-o", str(out), "--json"], capsys)
    assert code == 0 and obj["output"] == str(out) and obj["text"] is None
    assert obj["format"] == "ltl" and obj["bytes"] == len(out.read_bytes())


def test_check_prints_one_object_per_file(capsys: pytest.CaptureFixture[str]) -> None:
    code, objects, _ = run_json(["check", PATROL, UNREALIZABLE, "--json"], capsys)
    assert code == 3
    assert [o["verdict"] for o in objects] == ["realizable", "unrealizable"]
    assert all(set(o) == COMMON | keys("check") for o in objects)
    assert all(o["error"] is None for o in objects)


def test_synth_and_counter(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "c.json"
    code, obj = one(["synth", SHUTTLE, "-o", str(out), "--json"], capsys)
    assert code == 0 and set(obj) == COMMON | keys("synth and counter")
    assert obj["output"] == str(out) and out.exists()
    assert obj["verification"]["ok"] is True
    assert set(obj["verification"]) == keys("the verification object")
    assert obj["nodes"] == len(json.loads(out.read_text())["nodes"])
    code, obj = one(["synth", UNREALIZABLE, "-o", str(tmp_path / "u.json"), "--json"], capsys)
    assert code == 3 and obj["output"] is None and obj["verdict"] == "unrealizable"
    code, obj = one(["counter", UNREALIZABLE, "-o", str(tmp_path / "k.json"), "--json"],
                    capsys)
    assert code == 0 and obj["command"] == "counter" and obj["kind"] == "counterstrategy"
    assert set(obj) == COMMON | keys("synth and counter")
    code, obj = one(["counter", SHUTTLE, "-o", str(tmp_path / "n.json"), "--json"], capsys)
    assert code == 3 and obj["output"] is None and not (tmp_path / "n.json").exists()


def test_verify(controllers: dict[str, str], capsys: pytest.CaptureFixture[str]) -> None:
    code, obj = one(["verify", PATROL, controllers["patrol"], "--json"], capsys)
    assert code == 0 and set(obj) == COMMON | keys("verify", "the verification object")
    assert obj["ok"] is True and obj["controller"] == controllers["patrol"]
    code, obj = one(["verify", SHUTTLE, controllers["patrol"], "--json"], capsys)
    assert code == 1 and obj["ok"] is False and obj["problems"]  # another spec's controller


@pytest.mark.parametrize("command", ["simulate", "drive"])
def test_simulate_and_drive_print_the_run(command: str, tmp_path: Path,
                                          controllers: dict[str, str],
                                          capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run.jsonl"
    code, obj = one([command, SHUTTLE, controllers["shuttle"], "--steps", "5", "--out",
                     str(out), "--json"], capsys)
    expected = keys("simulate", "drive") if command == "drive" else keys("simulate")
    assert code == 0 and set(obj) == COMMON | expected
    assert len(obj["steps"]) == 6 and obj["error"] is None and obj["output"] == str(out)
    assert all(set(step) == keys("the step object") for step in obj["steps"])
    assert set(obj["summary"]) == keys("the summary object")
    saved = [json.loads(line) for line in out.read_text().splitlines()]
    assert saved[1:-1] == obj["steps"] and saved[-1] == obj["summary"]


def test_simulate_of_an_unrealizable_spec(capsys: pytest.CaptureFixture[str]) -> None:
    code, obj = one(["simulate", UNREALIZABLE, "--json"], capsys)
    assert code == 3 and set(obj) == COMMON | keys("simulate")
    assert obj["realizable"] is False and obj["steps"] == [] and obj["summary"] is None
    code, obj = one(["simulate", UNREALIZABLE, "--env", "adversarial", "--steps", "3",
                     "--json"], capsys)
    assert obj["realizable"] is False and obj["steps"]
    assert obj["environment"].startswith("counter-strategy")


def test_a_run_stopped_by_a_scenario_holds_the_error(
    tmp_path: Path, controllers: dict[str, str], capsys: pytest.CaptureFixture[str]
) -> None:
    scenario = tmp_path / "s.yaml"
    scenario.write_text("steps:\n  - degrade: [L1]\n", encoding="utf-8")
    argv = ["simulate", PATROL, controllers["patrol"], "--env", "scripted", str(scenario),
            "--on-surprise", "stop"]
    plain = main(argv)
    capsys.readouterr()
    code, obj, err = run_json([*argv, "--json"], capsys)
    assert code == plain == 1
    [run] = obj
    error = run["error"]
    assert (error["type"], error["file"], error["line"], error["column"]) == (
        "ScenarioError", str(scenario), 2, 5)
    assert error["message"].startswith("step 1 (degrade L1): L1 failed while not in use "
                                       "(eq. 3.5, L1 declared on line 12): the environment "
                                       "breaks the assumption 'eq. 3.5")
    assert f"{scenario}:2:5: error: step 1" in err  # stderr keeps the human text
    assert len(run["steps"]) == 1


def test_explain_and_resilience(capsys: pytest.CaptureFixture[str]) -> None:
    code, obj = one(["explain", UNREALIZABLE, "--no-repairs", "--json"], capsys)
    assert code == 3 and set(obj) == COMMON | keys("explain")
    assert obj["verdict"] == "unrealizable" and obj["core"]
    code, obj = one(["resilience", SHUTTLE, "--json"], capsys)
    assert code == 0 and set(obj) == COMMON | keys("resilience")
    assert obj["single_points_of_failure"] == ["L1", "L2"]


def test_gaits_both_searches(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "g.json"
    code, obj = one(["gaits", ROBOT, "-o", str(out), "--json"], capsys)
    assert code == 0 and set(obj) == COMMON | keys("gaits")
    assert obj["written"] == [str(out)] and obj["gaits"]
    saved = json.loads(out.read_text())
    assert {k: obj[k] for k in saved} == saved
    code, obj = one(["gaits", ROBOT, "--method", "astar", "--goal", "40,0", "--json"], capsys)
    assert code == 0 and set(obj) == COMMON | keys("gaits --method astar, lpa, dstar, mcts")
    assert obj["found"] and obj["reached"] and obj["plan"]["method"] == "astar"


def _expected(load: Callable[[], object]) -> dict[str, Any]:
    with pytest.raises(GaitcError) as info:
        load()
    err = info.value
    assert err.span is not None
    return {"type": type(err).__name__, "file": err.span.file, "line": err.span.line,
            "column": err.span.column, "message": err.message, "hint": err.hint}


@pytest.mark.parametrize("argv", [
    ["lint", "{spec}"], ["compile", "{spec}"], ["synth", "{spec}", "-o", "{out}"],
    ["counter", "{spec}", "-o", "{out}"], ["verify", "{spec}", "{controller}"],
    ["simulate", "{spec}"], ["drive", "{spec}"], ["explain", "{spec}"],
    ["resilience", "{spec}"],
])
def test_a_syntax_error_is_an_error_object(argv: list[str], tmp_path: Path,
                                           controllers: dict[str, str],
                                           capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "broken.gait"
    spec.write_text(BROKEN, encoding="utf-8")
    words = [w.format(spec=spec, out=tmp_path / "c.json", controller=controllers["patrol"])
             for w in argv]
    plain = main(words)
    capsys.readouterr()
    code, obj = one([*words, "--json"], capsys)
    assert code == plain == 1
    assert set(obj) == COMMON | {"error"} and obj["command"] == argv[0]
    assert set(obj["error"]) == keys("the error object")
    assert obj["error"] == _expected(lambda: gaitc.load(spec))
    assert (obj["error"]["type"], obj["error"]["line"], obj["error"]["column"]) == (
        "SpecSyntaxError", 2, 22)
    assert obj["error"]["message"].startswith("unexpected character '@'")


def test_check_puts_a_syntax_error_in_the_files_record(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    spec = tmp_path / "broken.gait"
    spec.write_text(BROKEN, encoding="utf-8")
    code, objects, err = run_json(["check", str(spec), PATROL, "--json"], capsys)
    assert code == 1
    assert [o["verdict"] for o in objects] == ["error", "realizable"]
    assert objects[0]["error"] == _expected(lambda: gaitc.load(spec))
    assert f"{spec}:2:22: error: unexpected character" in err


def test_a_missing_file_stops_check_with_an_error_object_last(
    capsys: pytest.CaptureFixture[str]
) -> None:
    code, objects, _ = run_json(["check", PATROL, "missing.gait", "--json"], capsys)
    assert code == 2 and objects[0]["verdict"] == "realizable"
    assert set(objects[1]) == COMMON | {"error"}
    assert objects[1]["error"]["message"] == "cannot read 'missing.gait': no such file"


def test_a_broken_robot_file_is_an_error_object(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    robot = tmp_path / "r.yaml"
    robot.write_text("name: x\nlegs: [\n", encoding="utf-8")
    code, obj = one(["gaits", str(robot), "--json"], capsys)
    assert code == 1 and obj["command"] == "gaits"
    assert (obj["error"]["type"], obj["error"]["file"], obj["error"]["line"]) == (
        "RobotFileError", str(robot), 2)


@pytest.mark.parametrize(("argv", "command", "kind"), [
    (["lint", "--json"], "lint", "UsageError"),  # SPEC missing
    (["simulate", PATROL, "--json", "--steps", "many"], "simulate", "UsageError"),
    (["render", "map", PATROL, "--json"], "render", "UsageError"),  # no --json of its own
    (["--json"], None, "UsageError"),
    (["check", "--json", "missing.gait"], "check", "MissingFileError"),  # after parsing
])
def test_usage_errors_are_error_objects(argv: list[str], command: str | None, kind: str,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    code, obj = one(argv, capsys)
    assert code == 2 and obj["command"] == command
    error = obj["error"]
    assert error["type"] == kind and error["message"]
    assert (error["file"], error["line"], error["column"]) == (None, None, None)


def test_without_json_nothing_changes_on_stdout_for_an_error(
    capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["lint", "--", "--json"]) == 2  # after --, the word is a file name
    captured = capsys.readouterr()
    assert captured.out == "" and "usage error" in captured.err


def test_an_internal_error_is_an_error_object(monkeypatch: pytest.MonkeyPatch,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    def broken(*args: object) -> None:
        raise RuntimeError("boom")

    monkeypatch.setattr(gaitc, "lint", broken)
    code, obj = one(["lint", PATROL, "--json"], capsys)
    assert code == 70
    assert obj["error"]["type"] == "InternalError" and "boom" in obj["error"]["message"]


def test_the_same_input_prints_the_same_bytes(capsys: pytest.CaptureFixture[str]) -> None:
    outputs = []
    for _ in range(2):
        assert main(["compile", PATROL, "--json"]) == 0
        assert main(["lint", PATROL, "--json"]) == 0
        outputs.append(capsys.readouterr().out)
    assert outputs[0] == outputs[1]
