"""``gaitc.compact_policy`` prints what ``gaitc render policy --compact`` prints: the rules
restricted to the states a run reaches (gaitc.api.drawing.compact_rules), never used ones
counted, or listed and marked with ``all_rules``."""

from __future__ import annotations

from pathlib import Path

import pytest

import gaitc
from gaitc.cli import main

SHUTTLE = Path(gaitc.__file__).resolve().parent / "examples" / "shuttle_2leg.gait"


@pytest.fixture(scope="module")
def controller(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("compact") / "shuttle.json"
    assert main(["synth", str(SHUTTLE), "--compact", "-o", str(path)]) == 0
    return path


@pytest.mark.parametrize("all_rules", [False, True])
def test_the_api_prints_what_the_cli_prints(controller: Path, all_rules: bool,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    capsys.readouterr()
    options = ["--all-rules"] if all_rules else []
    assert main(["render", "policy", str(SHUTTLE), str(controller), *options]) == 0
    printed = capsys.readouterr().out
    tables = gaitc.compact_policy(str(SHUTTLE), controller, all_rules=all_rules)
    assert tables is not None
    assert tables.text() == printed
    assert tables.reached and tables.never_used > 0  # restricted: some rules never used
    assert ("never used" in printed.split("\n\n", 1)[1]) == all_rules
