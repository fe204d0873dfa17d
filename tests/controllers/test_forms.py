"""Every registered controller form through every command that takes a controller.

For robot A of the thesis and an 8-leg radial robot, each form of :data:`FORMS` is
synthesized, written, read back, proved, simulated, drawn as a policy, played headless,
driven on the simulated board and compiled to C (codegen compacts the explicit and symbolic
forms itself); every answer is checked here (the run against the spec's guarantees, the
file against its own text), not taken from the tool.  Adding a form is one registered class
(docs/background/layout.md), and this test then covers it.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from packages import ROOT

import gaitc
from gaitc.api.generating import compact_of
from gaitc.api.solving import controller_form, read_controller
from gaitc.core.modes import Form
from gaitc.forms.base import ControllerForm
from gaitc.forms.registry import FORMS, entry, register

SPECS = {"robot_a": ROOT / "specs" / "thesis_robot_a.gait",
         "radial8": ROOT / "specs" / "radial8_patrol.gait"}
GAIT = re.compile(r"^(gait \S+\s+uses L(\d), L(\d) moves \w+)$", re.MULTILINE)


def with_valves(text: str) -> str:
    """Robot A with each two-leg gait bound to a valve sequence (its first leg, then its
    second), so a board can drive it; the spec's logic is unchanged."""
    def bind(match: re.Match[str]) -> str:
        first, second = (["0"] * 8 for _ in range(2))
        first[int(match[2]) - 1], second[int(match[3]) - 1] = "1", "1"
        return f"{match[1]} valves {''.join(first)}, {''.join(second)}"

    bound, count = GAIT.subn(bind, text)
    assert count == 12
    return bound


def test_every_form_has_one_entry() -> None:
    assert set(FORMS) == set(Form)
    assert all(found.form == form for form, found in FORMS.items())

    class Again(type(FORMS[Form.SYMBOLIC])):  # type: ignore[misc]
        pass

    with pytest.raises(ValueError, match="registered twice"):
        register(Again)


@pytest.fixture(scope="module", params=sorted(SPECS))
def spec(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
         ) -> gaitc.Spec:
    path = SPECS[request.param]
    if request.param == "robot_a":
        copy = tmp_path_factory.mktemp("robot_a") / path.name
        copy.write_text(with_valves(path.read_text(encoding="utf-8")), encoding="utf-8")
        path = copy
    return gaitc.load(path)


@pytest.mark.parametrize("form", list(Form), ids=str)
def test_a_form_through_every_command(spec: gaitc.Spec, form: Form, tmp_path: Path) -> None:
    made = gaitc.synthesize(spec, form=form.value)
    assert made.controller is not None and made.verified, made.report
    found: ControllerForm = entry(made.controller)
    assert found.form == form

    # write, read back: the same file text, the same form, the spec's vocabulary
    path = tmp_path / f"{form}.json"
    made.save(path)
    assert controller_form(path) == form
    again = read_controller(path, spec)
    assert found.to_json(again) == path.read_text(encoding="utf-8")

    # prove the file
    report = gaitc.verify(spec, path)
    assert report.ok, report.problems

    # simulate: the run keeps every guarantee, checked by the run monitor
    run = gaitc.simulate(spec, path, env="random", steps=25, seed=3)
    assert run.summary is not None and run.summary.guarantees_held
    assert len(run.steps) == 26

    # render policy: the rules per region of a run view, and the compact rule tables
    policy = gaitc.controller_policy(spec, path, steps=30)
    assert policy is not None and policy[0].text()
    tables = gaitc.compact_policy(spec, path)
    assert tables is not None and tables.text()

    # play headless: the user plays the environment, the controller answers
    player = gaitc.player(spec, path)
    for _ in range(6):
        if player.over is not None:
            break
        player.choose(len(player.choices()))  # the last of the moves offered
    played = player.run()
    assert played.summary is not None and played.summary.guarantees_held

    # drive on the simulated board
    driven = gaitc.drive(spec, path, gaitc.SimulatedBoard("random", seed=5),
                         gaitc.DriveOptions(steps=5))
    assert driven.run is not None and driven.run.summary is not None
    assert driven.run.summary.guarantees_held

    # codegen: every form is compacted, proved, and built for the host
    compacted = compact_of(spec, path)
    assert compacted is not None and gaitc.verify(spec, compacted).ok
    if shutil.which("cc") is None and shutil.which("gcc") is None:
        pytest.skip("no C compiler")
    built = gaitc.generate(spec, path, "c", tmp_path / "c")
    assert (tmp_path / "c" / "gaitc_controller.c").is_file() and built is not None
