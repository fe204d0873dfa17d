"""``gaitc chances`` and ``simulate --env stochastic`` on the command line: the JSON the issue
names, the files written, the errors at their place, and the message without Storm."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from gaitc.cli import main

#: The corridor of tests/data/chances/corridor.gait (see test_chances.py).
CORRIDOR = (Path(__file__).resolve().parents[1] / "data" / "chances"
            / "corridor.gait").read_text(encoding="utf-8")


@pytest.fixture
def corridor(tmp_path: Path) -> Path:
    spec = tmp_path / "corridor.gait"
    spec.write_text(CORRIDOR)
    return spec


def test_chances_json_out_and_plot(corridor: Path, tmp_path: Path,
                                   capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("stormpy", reason="needs the chances extra (stormpy)")
    out, plot = tmp_path / "best.json", tmp_path / "patrols.svg"
    code = main(["chances", str(corridor), "--wear", "10%", "--steps", "6", "--patrols", "2",
                 "--json", "--out", str(out), "--plot", str(plot)])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert [p["k"] for p in data["patrols"]] == [1, 2]
    assert data["patrols"][0]["probability"] == pytest.approx(0.9 * 0.9 * 1.1, abs=1e-6)
    assert set(data["goals"]) == {"c", "a"}
    assert data["rates"]["every"] == pytest.approx(0.1)
    assert data["written"]["patrols"][0]["probability"] == pytest.approx(0.891, abs=1e-6)
    assert out.exists() and "<svg" in plot.read_text()
    assert main(["verify", str(corridor), str(out)]) in (0, 1)  # liveness may fail; it runs


def test_simulate_stochastic_counts_patrols(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    spec = tmp_path / "corridor3.gait"
    spec.write_text(CORRIDOR.replace("health 2", "health 3"))  # realizable
    code = main(["simulate", str(spec), "--env", "stochastic", "--wear", "0.2", "--steps",
                 "40", "--json"])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert data["environment"] == "stochastic --seed 0"
    visits = data["summary"]["goal_visits"]
    # c then a, counted from the first state: no more patrols than visits of a or of c
    assert 1 <= data["patrols"] <= min(visits["a"], visits["c"])
    goals = [step["goals"] for step in data["steps"]]
    count, nxt = 0, "c"
    for reached in goals:
        if nxt in reached:
            count, nxt = (count + 1, "c") if nxt == "a" else (count, "a")
            if nxt == "a" and "a" in reached:
                count, nxt = count + 1, "c"
    assert data["patrols"] == count


def test_rates_need_the_stochastic_environment(corridor: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["simulate", str(corridor), "--env", "random", "--wear", "0.1"]) == 2
    assert "use --env stochastic" in capsys.readouterr().err


def test_a_bad_rates_file_is_shown_at_its_place(corridor: Path, tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    rates = tmp_path / "rates.yaml"
    rates.write_text("wear:\n  every: 2\n")
    assert main(["chances", str(corridor), "--rates", str(rates)]) == 1
    err = capsys.readouterr().err
    assert f"{rates}:2:10:" in err and "outside [0, 1]" in err


def test_without_storm_the_extra_is_named(corridor: Path, monkeypatch: pytest.MonkeyPatch,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setitem(sys.modules, "stormpy", None)  # import stormpy raises ImportError
    assert main(["chances", str(corridor), "--wear", "0.1"]) == 2
    assert "pip install 'gaitc[chances]'" in capsys.readouterr().err


def test_a_model_too_big_says_what_it_needs(corridor: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("stormpy", reason="needs the chances extra (stormpy)")
    assert main(["chances", str(corridor), "--wear", "0.1", "--max-states", "5"]) == 2
    err = capsys.readouterr().err
    assert "passed 5 states" in err and "symbolic engine" in err


def test_the_json_keys_are_the_documented_ones(corridor: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    """Every key of ``chances --json`` is in docs/json.md's table, and every row is a key."""
    import re

    pytest.importorskip("stormpy", reason="needs the chances extra (stormpy)")
    page = (Path(__file__).resolve().parents[2] / "docs" / "json.md").read_text()
    table = page.split("### chances", 1)[1].split("\n### ", 1)[0]
    rows = set(re.findall(r"^\| `([a-z_0-9]+)` \|", table, re.M))
    assert main(["chances", str(corridor), "--wear", "0.1", "--steps", "4", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) - {"command", "schema"} == rows
