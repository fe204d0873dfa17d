"""The public API of ``import gaitc``: the examples of docs/api.md and module docstrings run
as doctests, and each answer the API gives is checked independently of the object it sits on.
"""

from __future__ import annotations

import doctest
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

import gaitc
from gaitc.diagnostics import UsageError
from gaitc.ir.controller import load_controller
from gaitc.verifier.strategy import verify as verify_strategy

ROOT = Path(__file__).resolve().parents[2]
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


@pytest.fixture
def at_root() -> Iterator[None]:
    old = Path.cwd()
    os.chdir(ROOT)
    yield
    os.chdir(old)


@pytest.mark.usefixtures("at_root")
def test_docs_api_examples_run() -> None:
    result = doctest.testfile(str(ROOT / "docs" / "api.md"), module_relative=False,
                              optionflags=FLAGS)
    assert result.attempted > 20
    assert result.failed == 0


@pytest.mark.usefixtures("at_root")
@pytest.mark.parametrize("module", ["gaitc.api.compiling", "gaitc.api.simulation",
                                    "gaitc.play.player"])
def test_module_examples_run(module: str) -> None:
    import importlib

    result = doctest.testmod(importlib.import_module(module), optionflags=FLAGS)
    assert result.attempted > 0 and result.failed == 0


def test_the_issue_one_liners_from_a_fresh_interpreter() -> None:
    script = (
        "import gaitc\n"
        "s = gaitc.load('specs/thesis_robot_a.gait')\n"
        "print(gaitc.check(s).realizable)\n"
        "found = gaitc.synthesize(s)\n"
        "print(found.verified)\n"
        "print(gaitc.verify(s, found).ok)\n"
        "print(gaitc.simulate(s, found, steps=5).summary.guarantees_held)\n"
    )
    out = subprocess.run([sys.executable, "-c", script], cwd=ROOT, capture_output=True,
                         text=True, check=True, timeout=600)
    assert out.stdout.split() == ["True"] * 4


def test_everything_exported_is_documented() -> None:
    text = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    for name in gaitc.__all__:
        assert name in text, name


def test_results_say_what_they_are() -> None:
    spec = gaitc.load(ROOT / "specs" / "patrol_2x2.gait")
    found = gaitc.synthesize(spec)
    assert found.controller is not None and found.report is not None
    for obj, word in ((spec, "gaitc.Spec"), (gaitc.check(spec), "realizable"),
                      (found, "verified"), (found.controller, "Controller strategy"),
                      (found.report, "strategy ok"),
                      (gaitc.simulate(spec, found, steps=3), "the spec held")):
        assert word in repr(obj)
        assert len(repr(obj)) < 300  # a summary, not a dump of every node
    for obj in (spec, gaitc.check(spec), found, found.controller, found.report):
        assert obj._repr_html_().startswith(("<table>", "<p>"))  # type: ignore[attr-defined]


def test_synthesized_controllers_are_proved_again_by_the_test(tmp_path: Path) -> None:
    for encoding in ("onehot", "binary"):
        spec = gaitc.load(ROOT / "specs" / "patrol_2x2.gait", encoding)
        found = gaitc.synthesize(spec)
        path = tmp_path / f"c.{encoding}.json"
        found.save(path)
        again = load_controller(str(path), spec.gr1)
        assert verify_strategy(spec.gr1, again, again.semantics).ok
        assert again.source is not None and again.source["encoding"] == encoding


def test_verify_reads_the_recorded_encoding(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    from gaitc.cli import main

    out = tmp_path / "binary.json"
    patrol = str(ROOT / "specs" / "patrol_2x2.gait")
    assert main(["synth", patrol, "-o", str(out), "--encoding", "binary"]) == 0
    capsys.readouterr()
    assert main(["verify", patrol, str(out)]) == 0
    assert "verified: strategy ok" in capsys.readouterr().out


def test_api_refuses_bad_arguments_with_usage_errors() -> None:
    spec = gaitc.load(ROOT / "specs" / "patrol_2x2.gait")
    with pytest.raises(UsageError, match="unknown semantics 'bogus'"):
        gaitc.check(spec, semantics="bogus")
    with pytest.raises(UsageError, match="unknown solver"):
        gaitc.check(spec, solver="z3")
    with pytest.raises(UsageError, match="unknown encoding"):
        gaitc.load(ROOT / "specs" / "patrol_2x2.gait", "gray")
    with pytest.raises(UsageError, match="unknown format"):
        gaitc.emit(spec, "dot")
    with pytest.raises(UsageError, match="unknown environment"):
        gaitc.simulate(spec, env="hostile")
    with pytest.raises(UsageError, match="no such file"):
        gaitc.load("specs/missing.gait")


def test_parse_and_load_agree() -> None:
    path = ROOT / "specs" / "thesis_robot_b.gait"
    loaded = gaitc.load(path, "binary")
    parsed = gaitc.parse(path.read_text(encoding="utf-8"), name=str(path), encoding="binary")
    assert loaded.gr1 == parsed.gr1 and loaded.sha256 == parsed.sha256
    assert gaitc.emit(loaded, "slugsin") == gaitc.emit(parsed, "slugsin")


def test_a_controller_with_unknown_semantics_is_refused_everywhere(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import json

    from gaitc.cli import main

    patrol = str(ROOT / "specs" / "patrol_2x2.gait")
    good = tmp_path / "good.json"
    assert main(["synth", patrol, "-o", str(good)]) == 0
    data = json.loads(good.read_text(encoding="utf-8"))
    data["gaitc"]["semantics"] = "bogus"
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data), encoding="utf-8")
    capsys.readouterr()
    for command in (["verify", patrol, str(bad)], ["simulate", patrol, str(bad)]):
        assert main(command) == 1
        assert "'gaitc.semantics' must be one of default, robotics" in capsys.readouterr().err


def test_load_reads_the_file_once(monkeypatch: pytest.MonkeyPatch) -> None:
    import pathlib

    reads: list[str] = []
    real_bytes, real_text = pathlib.Path.read_bytes, pathlib.Path.read_text

    def count_bytes(self: pathlib.Path) -> bytes:
        reads.append(str(self))
        return real_bytes(self)

    def count_text(self: pathlib.Path, *args: object, **kwargs: object) -> str:
        reads.append(str(self))
        return real_text(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(pathlib.Path, "read_bytes", count_bytes)
    monkeypatch.setattr(pathlib.Path, "read_text", count_text)
    for name in ("patrol_2x2.gait",):
        gaitc.load(ROOT / "specs" / name)
    gaitc.load(ROOT / "tests" / "data" / "slugs_examples" / "water_reservoir.structuredslugs")
    assert [Path(r).name for r in reads] == ["patrol_2x2.gait", "water_reservoir.structuredslugs"]


@pytest.mark.parametrize("fmt", ["structuredslugs", "slugsin", "ltl"])
def test_what_compile_writes_loads_back_with_the_same_verdict(fmt: str, tmp_path: Path) -> None:
    spec = gaitc.load(ROOT / "specs" / "thesis_robot_b.gait", "binary")
    path = tmp_path / f"robot_b.{fmt}"
    path.write_text(gaitc.emit(spec, fmt), encoding="utf-8")
    again = gaitc.load(path)
    assert again.model is None
    assert gaitc.check(again).realizable == gaitc.check(spec).realizable
