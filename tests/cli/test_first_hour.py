"""What a new user met in their first hour (a review of every command): outputs checked
before the work, missing inputs as usage errors, signed option values, negative counts,
CSV runs, control characters in quoted source lines, and the ``.txt`` round trip.  Each
test failed on the code before its fix."""

from __future__ import annotations

from pathlib import Path

import pytest

from gaitc.cli import main
from gaitc.cli.exitcodes import ExitCode

ROOT = Path(__file__).resolve().parents[2]
PATROL = str(ROOT / "specs" / "patrol_2x2.gait")
UNREALIZABLE = str(ROOT / "specs" / "unrealizable_2x2.gait")
RADIAL8 = str(ROOT / "specs" / "robots" / "radial8.yaml")
SYMMETRIC6 = str(ROOT / "specs" / "robots" / "symmetric6.yaml")


def _err(capsys: pytest.CaptureFixture[str]) -> str:
    captured = capsys.readouterr()
    return captured.err.strip()


@pytest.mark.parametrize(("words", "message"), [
    (["simulate", PATROL, "--steps", "3", "--out", "{tmp}/nodir/run.jsonl"],
     "argument --out: cannot write '{tmp}/nodir/run.jsonl': there is no folder '{tmp}/nodir'"),
    (["simulate", PATROL, "--steps", "3", "--out", "{tmp}/run.txt"],
     "argument --out: cannot tell the run format from '{tmp}/run.txt': use a .jsonl or .csv "
     "file"),
    (["drive", PATROL, "--steps", "3", "--out", "{tmp}/nodir/d.jsonl"],
     "argument --out: cannot write '{tmp}/nodir/d.jsonl': there is no folder '{tmp}/nodir'"),
    (["explain", UNREALIZABLE, "--out", "{tmp}/nodir/p.jsonl"],
     "argument --out: cannot write '{tmp}/nodir/p.jsonl': there is no folder '{tmp}/nodir'"),
    (["synth", PATROL, "-o", "{tmp}"],
     "argument -o/--output: cannot write '{tmp}': it is not a regular file"),
    (["compile", PATROL, "-o", "{tmp}/nodir/x.slugsin"],
     "argument -o/--output: cannot write '{tmp}/nodir/x.slugsin': there is no folder "
     "'{tmp}/nodir'"),
])
def test_outputs_are_checked_before_any_work(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                             words: list[str], message: str) -> None:
    filled = [w.format(tmp=tmp_path) for w in words]
    assert main(filled) == ExitCode.USAGE
    captured = capsys.readouterr()
    assert captured.out == ""  # nothing was run, so nothing printed and lost
    assert captured.err.strip() == f"gaitc: usage error: {message.format(tmp=tmp_path)}"


@pytest.mark.parametrize(("words", "message"), [
    (["simulate", PATROL, "--env", "scripted", "{tmp}/nosuch.yaml"],
     "cannot read scenario '{tmp}/nosuch.yaml': no such file"),
    (["gaits", "{tmp}/nosuch.yaml"], "cannot read robot file '{tmp}/nosuch.yaml': no such file"),
    (["calibrate", "{tmp}/nosuch.csv"], "cannot read recording '{tmp}/nosuch.csv': no such file"),
    (["render", "map", PATROL, "--run", "{tmp}", "-o", "{tmp}/m.svg"],
     "cannot read run file '{tmp}': it is a directory"),
    (["verify", PATROL, "{tmp}/nosuch.json"],
     "cannot read controller file '{tmp}/nosuch.json': no such file"),
])
def test_a_missing_input_is_a_usage_error_like_a_missing_spec(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], words: list[str],
        message: str) -> None:
    assert main([w.format(tmp=tmp_path) for w in words]) == ExitCode.USAGE
    assert _err(capsys) == f"gaitc: usage error: {message.format(tmp=tmp_path)}"


def test_negative_directions_and_goals_are_typed_as_the_help_shows(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["gaits", RADIAL8, "--model", "spring-damper", "--direction", "-y"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    dy = float(last.split(":")[1].split(",")[1].replace("mm", ""))
    assert dy < -10  # the gait found walks towards -y
    main(["gaits", SYMMETRIC6, "--method", "astar", "--goal", "-20,0", "--budget", "2000"])
    captured = capsys.readouterr()
    assert "goal (-20 mm, 0 mm, 0 deg)" in captured.out + captured.err


def test_a_negative_step_count_is_refused(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["render", "map", PATROL, "--max-steps", "-3", "-o",
                 str(tmp_path / "m.svg")]) == ExitCode.USAGE
    assert _err(capsys) == ("gaitc: usage error: argument --max-steps: must be a positive "
                            "whole number, not -3")
    assert not (tmp_path / "m.svg").exists()


def test_a_csv_run_says_it_cannot_be_drawn(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    run = tmp_path / "run.csv"
    assert main(["simulate", PATROL, "--steps", "3", "--quiet", "--out", str(run)]) == 0
    capsys.readouterr()
    assert main(["render", "map", PATROL, "--run", str(run), "-o",
                 str(tmp_path / "m.svg")]) == ExitCode.USAGE
    assert _err(capsys) == (f"gaitc: usage error: '{run}' is a CSV run, a table for "
                            "spreadsheets that cannot be read back; save the run with --out "
                            "FILE.jsonl to draw or replay it")


def test_control_characters_of_a_source_line_never_reach_the_terminal(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "esc.gait"
    spec.write_bytes(b'robot "x"\nlegs L1\x1b]0;pwned\x07 zz\n')
    assert main(["check", str(spec)]) == ExitCode.USER
    lines = _err(capsys).splitlines()
    assert lines[1] == "    legs L1?]0;pwned? zz"
    assert lines[2] == "           ^"  # under the ESC, at column 8
    assert not any(ord(c) < 32 for line in lines for c in line)


def test_a_txt_file_compiled_reads_back(tmp_path: Path,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    out, slugsin = tmp_path / "names.txt", tmp_path / "names.slugsin"
    assert main(["compile", PATROL, "-o", str(out)]) == 0
    assert main(["compile", PATROL, "-o", str(slugsin)]) == 0
    assert out.read_text() == slugsin.read_text()  # .txt is slugsin, as the readers take it
    assert main(["check", str(out)]) == 0
    assert "realizable" in capsys.readouterr().out



def test_cache_placement_answers_an_unrealizable_task_and_each_answer_re_solves(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import gaitc

    report = gaitc.resilience(UNREALIZABLE, place_caches=1)
    assert not report.realizable and report.cache_placements
    text = Path(UNREALIZABLE).read_text(encoding="utf-8")
    assert "cache ne\n" in text
    for (site,) in [("nw",), ("ne",), ("sw",), ("se",)]:
        moved = tmp_path / f"cache_{site}.gait"
        moved.write_text(text.replace("cache ne\n", f"cache {site}\n"), encoding="utf-8")
        realizable = gaitc.check(gaitc.load(moved)).realizable
        assert realizable == ((site,) in report.cache_placements), site
    assert main(["resilience", UNREALIZABLE, "--place-caches", "1"]) == ExitCode.UNREALIZABLE
    out = capsys.readouterr().out
    assert "caches at 1 region(s) that make it realizable" in out


@pytest.mark.parametrize(("count", "message"), [
    ("0", "argument --place-caches: must be a positive whole number, not 0"),
    ("9", "--place-caches 9: the map has only 4 regions no hazard covers"),
])
def test_cache_counts_out_of_range_are_usage_errors(
        capsys: pytest.CaptureFixture[str], count: str, message: str) -> None:
    assert main(["resilience", UNREALIZABLE, "--place-caches", count]) == ExitCode.USAGE
    assert _err(capsys) == f"gaitc: usage error: {message}"


def test_init_and_cache_clauses_point_at_their_own_statements(
        capsys: pytest.CaptureFixture[str]) -> None:
    lines = Path(PATROL).read_text(encoding="utf-8").splitlines()
    start = next(n for n, text in enumerate(lines, 1) if text.startswith("start "))
    cache = next(n for n, text in enumerate(lines, 1) if text.startswith("cache "))
    assert main(["compile", PATROL]) == 0
    out = capsys.readouterr().out
    assert f"# line {start}: init: start in nw" in out
    assert f"# line {cache}: eq. 3.6: cache ne resets every leg" in out


def test_unsatisfiable_assumptions_are_named_and_each_is_needed(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    base = (ROOT / "specs" / "corridor_hazard.gait").read_text(encoding="utf-8")
    clash = ["assume always eventually spill", "assume always !spill"]
    spec = tmp_path / "vacuous.gait"
    spec.write_text(base + "\n".join(clash) + "\n", encoding="utf-8")
    lines = spec.read_text(encoding="utf-8").splitlines()
    numbers = [lines.index(text) + 1 for text in clash]
    assert main(["lint", "--deep", str(spec)]) == ExitCode.WARNING
    err = capsys.readouterr().err
    assert "cannot satisfy its own assumptions" in err
    for number in numbers:
        assert f"({spec}:{number}:1)" in err
    for dropped in clash:  # each named assumption is needed: without it, no such warning
        alone = tmp_path / "alone.gait"
        alone.write_text(base + "\n".join(t for t in clash if t != dropped) + "\n",
                         encoding="utf-8")
        main(["lint", "--deep", str(alone)])
        assert "cannot satisfy its own assumptions" not in capsys.readouterr().err


def test_a_typo_is_shown_under_the_word_with_the_keyword_it_may_be(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = Path(PATROL).read_text(encoding="utf-8")
    spec = tmp_path / "typo.gait"
    spec.write_text(text.replace("moves west", "moves wset"), encoding="utf-8")
    line = next(n for n, t in enumerate(text.splitlines(), 1) if t.endswith("moves west"))
    assert main(["lint", str(spec)]) == ExitCode.USER
    lines = _err(capsys).splitlines()
    assert lines[0].startswith(f"{spec}:{line}:26: error: 'wset' after 'moves' is not a "
                               "direction")
    assert lines[1:] == ["    gait west  uses L4 moves wset",
                         "                             ^^^^",
                         "  hint: did you mean 'west'?"]


def test_a_byte_order_mark_is_accepted_and_columns_skip_it(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = Path(PATROL).read_text(encoding="utf-8")
    spec = tmp_path / "bom.gait"
    spec.write_bytes(b"\xef\xbb\xbf" + text.encode("utf-8"))
    assert main(["lint", str(spec)]) == 0
    assert _err(capsys) == ""
    spec.write_bytes(b"\xef\xbb\xbflegs L1 helth 2\n")
    assert main(["lint", str(spec)]) == ExitCode.USER
    assert _err(capsys).splitlines() == [
        f"{spec}:1:9: error: unexpected name 'helth'; expected ',', '..' or 'health'",
        "    legs L1 helth 2",
        "            ^^^^^",
        "  hint: did you mean 'health'?",
    ]


def test_a_byte_order_mark_is_accepted_in_slugs_formats_too(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from slugs_bridge.formats import load_spec_file

    for name, text in (("bom.slugsin", "[INPUT]\nx\n\n[OUTPUT]\ny\n\n[SYS_TRANS]\n"
                        "| ! x' y'\n"),
                       ("bom.structuredslugs", "[INPUT]\nx\n\n[OUTPUT]\ny\n\n"
                        "[SYS_TRANS]\nx' -> y'\n")):
        spec = tmp_path / name
        spec.write_bytes(b"\xef\xbb\xbf" + text.encode("utf-8"))
        gr1 = load_spec_file(str(spec))
        assert [v.name for v in gr1.inputs] == ["x"]
        assert len(gr1.sys_trans) == 1
        assert main(["check", str(spec)]) == 0
        assert "realizable" in capsys.readouterr().out


@pytest.fixture(scope="module")
def patrol_controller(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("ctrl") / "patrol.json"
    assert main(["synth", PATROL, "-o", str(path)]) == 0
    return str(path)


@pytest.mark.parametrize("order", [
    ["{c}", "--env", "random"],
    ["--env", "random", "{c}"],
    ["--env", "scripted", "{s}", "{c}"],
    ["--steps", "3", "{c}"],
])
def test_controller_may_follow_env_and_other_options(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], patrol_controller: str,
        order: list[str]) -> None:
    scenario = tmp_path / "s.yaml"
    scenario.write_text("steps:\n  - {}\n  - {}\n  - {}\n", encoding="utf-8")
    words = [w.format(c=patrol_controller, s=scenario) for w in order]
    capsys.readouterr()
    assert main(["simulate", PATROL, *words, "--steps", "3", "--quiet"]) == 0, _err(capsys)
    assert "summary: 3 steps" in capsys.readouterr().out


def test_env_before_the_spec_says_where_the_spec_goes(
        capsys: pytest.CaptureFixture[str], patrol_controller: str) -> None:
    assert main(["simulate", "--env", "random", PATROL, patrol_controller]) == ExitCode.USAGE
    assert _err(capsys) == ("gaitc: usage error: the following arguments are required: SPEC "
                            "(--env took the words after it as its own; write SPEC "
                            "[CONTROLLER] before --env)")


def test_drive_takes_its_controller_after_env(capsys: pytest.CaptureFixture[str],
                                              tmp_path: Path) -> None:
    shuttle, ctrl = str(ROOT / "specs" / "shuttle_2leg.gait"), str(tmp_path / "s.json")
    assert main(["synth", shuttle, "-o", ctrl]) == 0
    capsys.readouterr()
    assert main(["drive", shuttle, "--env", "random", ctrl, "--steps", "2", "--quiet"]) == 0
    assert "summary: 2 steps" in capsys.readouterr().out


@pytest.mark.parametrize(("words", "message"), [
    (["--env", "adversarial", "--seed", "3"],
     "--seed seeds the random environment; --env adversarial uses no random numbers (drop "
     "--seed, or use --env random)"),
    (["--env", "scripted", "{s}", "--seed", "3"],
     "--seed seeds the random environment; --env scripted uses no random numbers (drop "
     "--seed, or use --env random)"),
    (["--prefer", "goal"],
     "--prefer orders the moves of a controller synthesized here, but CONTROLLER was "
     "synthesized already; give --prefer to the 'gaitc synth' that writes it, or leave out "
     "CONTROLLER"),
])
def test_options_that_would_be_ignored_are_usage_errors(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], patrol_controller: str,
        words: list[str], message: str) -> None:
    scenario = tmp_path / "s.yaml"
    scenario.write_text("steps:\n  - {}\n", encoding="utf-8")
    filled = [w.format(s=scenario) for w in words]
    capsys.readouterr()
    assert main(["simulate", PATROL, patrol_controller, *filled]) == ExitCode.USAGE
    assert _err(capsys) == f"gaitc: usage error: {message}"


def test_prefer_with_a_controller_is_refused_by_render_and_drive_too(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], patrol_controller: str) -> None:
    shuttle, ctrl = str(ROOT / "specs" / "shuttle_2leg.gait"), str(tmp_path / "s.json")
    assert main(["synth", shuttle, "-o", ctrl]) == 0
    capsys.readouterr()
    for words in (["render", "automaton", PATROL, patrol_controller, "-o",
                   str(tmp_path / "a.dot")],
                  ["drive", shuttle, ctrl, "--steps", "1"]):
        assert main([*words, "--prefer", "none"]) == ExitCode.USAGE
        assert _err(capsys).startswith("gaitc: usage error: --prefer orders the moves")
    assert main(["drive", shuttle, ctrl, "--backend", "serial", "--port",
                 "loop://", "--seed", "1"]) == ExitCode.USAGE
    assert _err(capsys) == ("gaitc: usage error: --seed seeds the simulated random "
                            "environment; the serial backend reads real sensors")


@pytest.mark.parametrize(("words", "message"), [
    (["--model", "kinematic", "--method", "full", "--seed", "3"],
     "--seed seeds the random and reset searches; the full search of robot radial8 tries "
     "every valve state, without random numbers"),
    (["--model", "kinematic", "--seed", "3"],  # chapter 2's default for 8 chambers: full
     "--seed seeds the random and reset searches; the full search of robot radial8 tries "
     "every valve state, without random numbers"),
    (["--seed", "3"],  # the robot file's spring-damper model, searched whole
     "--seed seeds the random searches; the spring-damper model's gait graph is searched "
     "whole, without random numbers (--method random samples --max-states valve states)"),
])
def test_a_seed_the_gait_search_would_not_use_is_refused(
        capsys: pytest.CaptureFixture[str], words: list[str], message: str) -> None:
    assert main(["gaits", RADIAL8, *words]) == ExitCode.USAGE
    assert _err(capsys) == f"gaitc: usage error: {message}"


def test_the_preference_bench_table_names_robot_a_binary_controller() -> None:
    """docs/simulation.md's bench rows for robot A are its binary controller (231 nodes);
    the text says plain 'synth' (one-hot) writes 267: both counts as synthesized now."""
    import gaitc

    doc = (ROOT / "docs" / "simulation.md").read_text(encoding="utf-8")
    robot_a = str(ROOT / "specs" / "thesis_robot_a.gait")
    counts = {}
    for encoding in ("binary", "onehot"):
        found = gaitc.synthesize(gaitc.load(robot_a, encoding), verify=False)
        assert found.controller is not None
        counts[encoding] = len(found.controller.nodes)
    assert f"| thesis_robot_a | default | {counts['binary']} |" in doc
    assert f"writes {counts['onehot']} nodes" in doc
    assert "**binary** encoding" in doc


@pytest.mark.parametrize("symbolic", [False, True])
def test_verify_and_simulate_describe_a_foreign_controller_alike(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], symbolic: bool) -> None:
    shuttle, ctrl = str(ROOT / "specs" / "shuttle_2leg.gait"), str(tmp_path / "s.json")
    assert main(["synth", shuttle, "-o", ctrl, *(["--symbolic"] if symbolic else [])]) == 0
    capsys.readouterr()
    said = ("controller does not belong to this spec: it lacks the spec's variables 'L3_h2', "
            "'L3_h1', 'L4_h2', 'L4_h1', 'nw', 'ne' and 4 more (10 in all); it has variables "
            "'a', 'b', which the spec does not have")
    assert main(["verify", PATROL, ctrl]) == ExitCode.USER
    assert f"  - {said}" in capsys.readouterr().out.splitlines()
    assert main(["simulate", PATROL, ctrl, "--steps", "2"]) == ExitCode.USER
    assert _err(capsys).splitlines()[0] == f"{ctrl}:1:1: error: {said}"


def test_model_preferences_on_a_slugs_spec_are_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    slugsin = str(tmp_path / "p.slugsin")
    assert main(["compile", PATROL, "-o", slugsin]) == 0
    capsys.readouterr()
    out = str(tmp_path / "c.json")
    assert main(["synth", slugsin, "--prefer", "health,goal", "-o", out]) == ExitCode.USAGE
    assert _err(capsys) == ("gaitc: usage error: --prefer health weighs moves by the robot "
                            "model of a .gait spec, and this spec has none (SLUGS input); use "
                            "--prefer goal or none")
    assert main(["synth", slugsin, "--prefer", "goal", "-o", out]) == 0
