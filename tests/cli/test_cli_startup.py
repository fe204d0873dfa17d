"""The command line imports only what the command it runs needs (issue 37's start-up):
the parser registers the named command's module alone, and ``--version`` none."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from gaitc.cli import build_parser, main
from gaitc.cli.commands import COMMANDS, all_modules


def test_the_registry_names_every_command_a_module_registers() -> None:
    assert build_parser().commands == tuple(COMMANDS)
    assert len(all_modules()) == len(set(COMMANDS.values()))


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_named_command_gets_the_same_parser_as_with_every_command(command: str) -> None:
    alone, every = build_parser([command]), build_parser()
    assert alone.commands == every.commands
    sub_alone = alone._subparsers._group_actions[0].choices[command]  # type: ignore[union-attr]
    sub_every = every._subparsers._group_actions[0].choices[command]  # type: ignore[union-attr]
    assert sub_alone.format_help() == sub_every.format_help()


def _modules_after(*words: str) -> set[str]:
    code = ("import sys, json\nfrom gaitc.cli import main\n"
            f"try:\n    main({list(words)!r})\nexcept SystemExit:\n    pass\n"
            "print(json.dumps(sorted(sys.modules)))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    return set(json.loads(done.stdout.splitlines()[-1]))


def test_version_loads_no_command() -> None:
    loaded = _modules_after("--version")
    assert not {m for m in loaded if m.startswith("gaitc.cli.commands.")}
    assert not {"dd", "numpy", "networkx", "lark"} & loaded


def test_lint_loads_neither_the_solver_nor_numpy() -> None:
    """lint solves the environment's game for well-separation (issue 52: BDDs, so ``dd`` and
    the symbolic spec load), but not the system's game nor anything of synthesis."""
    loaded = _modules_after("lint", "gaitc/examples/patrol_2x2.gait")
    assert not {"numpy", "networkx", "gaitc.solver.game", "gaitc.solver.strategy"} & loaded
    assert "gaitc.cli.commands.compiling" in loaded
    assert "gaitc.cli.commands.solving" not in loaded


def test_a_misspelt_command_still_gets_its_suggestion(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sytnh"]) == 2
    assert "did you mean 'synth'?" in capsys.readouterr().err


def test_check_loads_neither_networkx_nor_numpy_nor_the_compact_controllers() -> None:
    loaded = _modules_after("check", "gaitc/examples/patrol_2x2.gait")
    assert "dd" in loaded
    assert not {"networkx", "numpy", "gaitc.compact", "gaitc.compact.controller"} & loaded


def _lint_with_cache_home(home: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "XDG_CACHE_HOME": home}
    return subprocess.run([sys.executable, "-m", "gaitc", "lint", "gaitc/examples/patrol_2x2.gait"],
                          capture_output=True, text=True, env=env, check=False)


def test_the_grammar_cache_is_written_and_a_broken_one_is_rebuilt(tmp_path: Path) -> None:
    first = _lint_with_cache_home(str(tmp_path))
    cached = tmp_path / "gaitc" / "gait-grammar.json"
    assert first.returncode == 0 and first.stderr == "" and cached.is_file()
    assert (tmp_path / "gaitc").stat().st_mode & 0o077 == 0  # the user's alone
    cached.write_bytes(b"not a cache\n" + b"\x80" * 50)
    again = _lint_with_cache_home(str(tmp_path))
    assert (again.returncode, again.stdout, again.stderr) == (0, first.stdout, "")
    assert not cached.read_bytes().startswith(b"not a cache")  # written anew


def test_without_a_cache_folder_the_grammar_is_built_each_time(tmp_path: Path) -> None:
    blocked = tmp_path / "a-file"
    blocked.write_text("", encoding="utf-8")
    done = _lint_with_cache_home(str(blocked))  # the cache folder cannot be made inside
    assert done.returncode == 0 and done.stderr == ""


def test_help_before_a_command_lists_every_command_with_its_summary(
        capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["-h", "synth"])
    out = capsys.readouterr().out
    assert "synthesize and verify a controller" in out
    assert "explain why a spec is unrealizable, and how to repair it" in out
