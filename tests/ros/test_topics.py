"""The topic layout, the observation checks and the MCAP files, without a graph: every bad
observation is named in its message; a reading pairs leg_health and hazards by stamp; the
schemas are the installed definitions; ``simulate --mcap`` writes the topics and messages
the node publishes; the docs' topic table is the layout's; without the extra, ``gaitc ros``
and ``simulate --mcap`` say what to install."""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import pytest
from ros_graph import ROBOT_A, ros_domain

import gaitc
from gaitc.api.ros import record_run
from gaitc.cli import main
from gaitc.hw.backend import HardwareError
from gaitc.ros.observation import Intake
from gaitc.ros.recording import definition, read
from gaitc.ros.topics import TOPICS, hazards_message, health_message, status_of, table

ROOT = Path(__file__).resolve().parents[2]
__all__ = ["ros_domain"]

LEGS = {f"L{i}": 3 for i in range(1, 9)}
FULL = tuple((leg, 3) for leg in LEGS)
NOW = 1_700_000_000 * 10**9


def intake() -> Intake:
    return Intake(LEGS, ("blue", "red"), stale_after=1.0)


def health(pairs: object, at: int = NOW) -> object:
    message = health_message((), at)
    names, values = zip(*pairs, strict=True) if pairs else ((), ())  # type: ignore[call-overload]
    message.name, message.position = list(names), [float(v) for v in values]
    return message


BAD_HEALTH = [
    ([*FULL[:7], ("L9", 3)], "leg_health: unknown leg 'L9'; the spec has L1, L2, L3, L4, L5, "
                             "L6, L7, L8"),
    ([*FULL, ("L1", 3)], "leg_health: leg L1 is named twice"),
    (FULL[:7], "leg_health: no value for leg L8"),
    ([*FULL[:7], ("L8", 0)], "leg_health: leg L8 has health level 0, outside 1..3"),
    ([*FULL[:7], ("L8", 4)], "leg_health: leg L8 has health level 4, outside 1..3"),
    ([*FULL[:7], ("L8", 2.5)], "leg_health: leg L8 has health level 2.5, outside 1..3"),
    ([*FULL[:7], ("L8", math.nan)], "leg_health: leg L8 has health level nan, outside 1..3"),
    ([*FULL[:7], ("L8", -math.inf)], "leg_health: leg L8 has health level -inf, outside 1..3"),
]


@pytest.mark.parametrize(("pairs", "words"), BAD_HEALTH)
def test_a_bad_leg_health_message_is_named(pairs: list[tuple[str, float]], words: str) -> None:
    with pytest.raises(HardwareError) as bad:
        intake().health(health(pairs), NOW)
    assert bad.value.message == words


def test_stamps_are_checked() -> None:
    with pytest.raises(HardwareError, match=r"^leg_health: stale reading, stamped 2\.000 s "
                       r"ago \(more than 1 s\)$"):
        intake().health(health(FULL, NOW - 2 * 10**9), NOW)
    with pytest.raises(HardwareError, match=r"stamped 3\.000 s in the future"):
        intake().health(health(FULL, NOW + 3 * 10**9), NOW)
    with pytest.raises(HardwareError, match=r"has no stamp \(header.stamp is 0\)"):
        intake().health(health(FULL, 0), NOW)
    paired = intake()
    paired.hazards(hazards_message(("blue", "red"), None, NOW), NOW)
    assert paired.health(health(FULL, NOW), NOW) is not None
    with pytest.raises(HardwareError, match=r"not newer than the last one"):
        paired.health(health(FULL, NOW), NOW)
    message = health(FULL)
    message.position = message.position[:3]  # type: ignore[attr-defined]
    with pytest.raises(HardwareError, match="8 names but 3 positions"):
        intake().health(message, NOW)


def test_hazards_are_checked_and_paired_by_stamp() -> None:
    taken = intake()
    assert taken.health(health(FULL, NOW), NOW) is None  # waits for its hazards
    assert taken.hazards(hazards_message(("blue", "red"), "red", NOW + 5), NOW) is None
    reading = taken.hazards(hazards_message(("blue", "red"), "blue", NOW), NOW)
    assert reading is not None and (reading.stamp, reading.hazard) == (NOW, "blue")
    assert reading.health == FULL
    both = hazards_message(("blue", "red"), None, NOW)
    both.position = [1.0, 1.0]
    with pytest.raises(HardwareError, match="hazard sets blue, red are on at once"):
        intake().hazards(both, NOW)
    half = hazards_message(("blue", "red"), None, NOW)
    half.position = [0.5, 0.0]
    with pytest.raises(HardwareError, match=r"1 \(on\) or 0 \(off\), not blue 0.5"):
        intake().hazards(half, NOW)
    with pytest.raises(HardwareError, match="unknown hazard set 'spill'"):
        intake().hazards(hazards_message(("blue", "red", "spill"), None, NOW), NOW)
    with pytest.raises(HardwareError, match="the spec has no hazard sets"):
        Intake(LEGS, (), 1.0).hazards(hazards_message(("blue",), None, NOW), NOW)
    assert Intake(LEGS, (), 1.0).health(health(FULL), NOW) is not None  # no hazards: alone


def test_a_schema_is_the_installed_definition_with_those_it_uses() -> None:
    text = definition("diagnostic_msgs/msg/DiagnosticArray")
    assert text.startswith("# This message is used to send diagnostic information") or \
        "DiagnosticStatus[] status" in text.splitlines()[0:40].__str__()
    used = [line.removeprefix("MSG: ") for line in text.splitlines() if line.startswith("MSG: ")]
    assert used == ["std_msgs/Header", "builtin_interfaces/Time",
                    "diagnostic_msgs/DiagnosticStatus", "diagnostic_msgs/KeyValue"]
    assert "MSG: builtin_interfaces/Time" in definition("sensor_msgs/msg/JointState")


def test_a_run_is_written_with_the_topics_of_the_node(tmp_path: Path) -> None:
    spec = gaitc.load(ROOT / "specs" / "shuttle_2leg.gait")  # two legs, two valves
    run = gaitc.simulate(spec, steps=10, violate=["3:fail L2"])
    mcap = tmp_path / "run.mcap"
    record_run(run, spec, mcap)
    messages = list(read(mcap))
    topics = {m.topic for m in messages}
    assert topics == {"/leg_health", "/gait", "/target_region", "/valves", "/diagnostics"}
    assert [m.message.data for m in messages if m.topic == "/gait"] == [
        *(s.gait for s in run.steps), "noGait"]
    valves = [m.message.data for m in messages if m.topic == "/valves"]
    assert set(valves) <= {"10 00", "01 00", "00"} and valves[-1] == "00"
    statuses = [status_of(m.message) for m in messages if m.topic == "/diagnostics"]
    third = next(s for s in statuses if s is not None and s.value("step") == "3")
    assert (third.value("surprises"), third.value("last surprise")) == ("1", "degraded")
    assert (third.value("goals kept"), third.value("goals lost")) == ("visit b", "visit a")
    assert third.value("monitor").startswith("1 clause(s) broken; first: step 3: assumption")
    assert statuses[-1] is not None and statuses[-1].value("stopped") == \
        f"{run.halted or 'finished 10 steps'}; every valve vented"
    again = tmp_path / "again.mcap"  # the same run written again: the same bytes
    record_run(run, spec, again)
    assert again.read_bytes() == mcap.read_bytes()


def test_simulate_mcap_writes_the_run(tmp_path: Path) -> None:
    spec = ROOT / "specs" / "patrol_2x2.gait"
    mcap = tmp_path / "run.mcap"
    assert main(["simulate", str(spec), "--steps", "6", "--mcap", str(mcap), "--quiet"]) == 0
    run = gaitc.simulate(spec, steps=6)
    messages = list(read(mcap))
    assert {m.topic for m in messages} == {"/leg_health", "/gait", "/target_region",
                                           "/diagnostics"}
    assert [m.message.data for m in messages if m.topic == "/gait"] == [
        *(s.gait for s in run.steps), "noGait"]
    health = next(m.message for m in messages if m.topic == "/leg_health")
    assert list(health.name) == ["L1", "L2", "L3", "L4"] and health.header.stamp.sec == 1


def test_the_docs_table_is_the_layout() -> None:
    page = (ROOT / "docs" / "how-to" / "ros.md").read_text(encoding="utf-8")
    assert table() in page
    assert len(TOPICS) == 6


def test_no_extra_names_what_to_install(monkeypatch: pytest.MonkeyPatch,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setitem(sys.modules, "rclpy", None)  # as if the ros extra were missing
    assert main(["ros", str(ROBOT_A)]) == 2
    err = capsys.readouterr().err
    assert "pip install 'gaitc[ros]'" in err and "Traceback" not in err
    assert main(["simulate", str(ROBOT_A), "--steps", "2", "--mcap",
                 str(Path(time.strftime("/tmp")) / "never.mcap")]) == 2
    assert "pip install 'gaitc[ros]'" in capsys.readouterr().err


def test_ros_arguments_are_checked(capsys: pytest.CaptureFixture[str],
                                   ros_domain: dict[str, str]) -> None:
    spec = str(ROOT / "specs" / "patrol_2x2.gait")
    assert main(["ros", spec, "--ros-args", "-p", "watchdog:=abc"]) == 2
    assert "usage error: parameter watchdog: Trying to set parameter 'watchdog' to 'abc'" in \
        capsys.readouterr().err
    assert main(["ros", spec, "--ros-args", "-p", "on_surprise:=maybe"]) == 2
    assert "unknown parameter on_surprise 'maybe'; use one of recover, stop" in \
        capsys.readouterr().err
    assert main(["ros", spec, "--ros-args", "--bogus"]) == 2
    assert "--ros-args: unknown ROS arguments ['--bogus']" in capsys.readouterr().err
    assert main(["ros", spec, "--seed", "3"]) == 2
    assert "--env, --seed and --violate are for the simulated robot: add --sim" in \
        capsys.readouterr().err


def test_a_robot_file_for_the_valves_is_checked(tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    radial8 = str(ROOT / "specs" / "radial8_patrol.gait")
    assert main(["ros", str(ROOT / "specs" / "patrol_2x2.gait"), "--robot", radial8]) == 2
    assert "no gait of" in capsys.readouterr().err
    assert main(["ros", radial8, "--robot", str(tmp_path / "none.yaml")]) == 2
    assert "none.yaml: no such robot file" in capsys.readouterr().err
    assert main(["ros", radial8, "--robot", str(ROOT / "specs" / "robots" / "silicone6.yaml")
                 ]) == 1
    assert "gait north_a uses L6, L8, which robot silicone6 does not have" in \
        capsys.readouterr().err
