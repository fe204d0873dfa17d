"""Localisation from an external tracker (issue 14): region maps, pose streams over local UDP
and TCP, and the driver's region check resting on them (``gaitc drive --pose``)."""

from __future__ import annotations

import json
import socket
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from gaitc.api.simulation import Session, session
from gaitc.cli import main
from gaitc.hw.backend import HardwareError
from gaitc.hw.driver import Driver, bind_primitives
from gaitc.hw.localisation import Localised, PoseStream, RegionMap, parse_pose
from gaitc.hw.simulated import SimulatedRobot
from gaitc.sim.environments import RandomEnvironment

ROOT = Path(__file__).resolve().parents[2]
RADIAL8 = ROOT / "specs" / "radial8_patrol.gait"
TINY = (Path(__file__).resolve().parents[2] / "specs" / "shuttle_2leg.gait").read_text(
    encoding="utf-8")  # two legs, two valves: short runs on the simulated board


@pytest.fixture()
def tiny(tmp_path: Path) -> tuple[Path, Session]:
    spec = tmp_path / "tiny.gait"
    spec.write_text(TINY, encoding="utf-8")
    loaded = session(str(spec), None)
    assert loaded is not None
    return spec, loaded


@pytest.fixture()
def udp() -> Iterator[PoseStream]:
    stream = PoseStream("udp://127.0.0.1:0", timeout=0.3, max_age=0.5)
    yield stream
    stream.close()


def send(stream: PoseStream, *messages: bytes) -> None:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as out:
        for message in messages:
            out.sendto(message, stream.sock.getsockname())
    time.sleep(0.05)


def pose(x: float, y: float) -> bytes:
    return json.dumps({"x": x, "y": y}).encode()


def test_grid_cells_and_map_polygons(tmp_path: Path) -> None:
    loaded = session(str(RADIAL8), None)
    assert loaded is not None
    grid = RegionMap.from_grid(loaded.model, 0.5)  # 3 x 3 cells nw..se, 0.5 m each
    assert [grid.region_at(0.25, 1.25), grid.region_at(0.75, 0.75), grid.region_at(1.4, 0.1)] \
        == ["nw", "c", "se"]
    assert grid.region_at(0.5, 0.5) == "c" and grid.region_at(-0.1, 0.2) is None
    path = tmp_path / "map.yaml"
    path.write_text("regions:\n  c: [[0, 0], [2, 0], [1, 2]]\n  w: [[-1, 0], [0, 0], [0, 1]]\n",
                    encoding="utf-8")
    drawn = RegionMap.from_file(path, loaded.domain.regions)
    assert drawn.region_at(1, 1) == "c" and drawn.region_at(1.8, 1.5) is None
    for text, message in [("regions:\n  moon: [[0, 0], [1, 0], [0, 1]]\n", "region 'moon'"),
                          ("regions:\n  c: [[0, 0], [1, 0]]\n", "at least 3"),
                          ("regions:\n  c: [[0, 0], [1, x], [0, 1]]\n",
                           "a polygon point must be \\[x, y\\], two finite numbers"),
                          ("- 1\n", "maps 'regions'")]:
        path.write_text(text, encoding="utf-8")
        with pytest.raises(HardwareError, match=message):
            RegionMap.from_file(path, loaded.domain.regions)


def test_pose_messages_are_bounded_and_checked() -> None:
    assert parse_pose(b'{"x": 1.5, "y": -2}') == (1.5, -2.0)
    for bad in (b"", b"{", b'{"x": 1}', b'{"x": "a", "y": 1}', b'{"x": NaN, "y": 1}',
                b'{"x": 1, "y": 1, "pad": "' + b"p" * 5000 + b'"}', b"[" * 100_000):
        assert parse_pose(bad) is None


def test_udp_stream_keeps_the_latest_pose_and_skips_garbage(udp: PoseStream) -> None:
    with pytest.raises(HardwareError, match=r"no pose from the tracker .* within 0.3 s"):
        udp.pose()
    send(udp, pose(0.1, 0.2), b"\xff garbage", pose(1.0, 2.0))
    assert (udp.pose().x, udp.pose().y) == (1.0, 2.0) and udp.malformed == 1
    time.sleep(0.6)  # older than max_age
    with pytest.raises(HardwareError, match="no fresh pose"):
        udp.pose()


def test_tcp_stream_joins_lines_across_reads() -> None:
    server = socket.create_server(("127.0.0.1", 0))
    url = f"tcp://127.0.0.1:{server.getsockname()[1]}"

    def serve() -> None:
        conn, _ = server.accept()
        with conn:
            conn.sendall(b'{"x": 3, "y"')
            time.sleep(0.05)
            conn.sendall(b': 4}\nnot json\n{"x": 5, "y": 6}\n')
            time.sleep(0.5)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    stream = PoseStream(url, timeout=1.0)
    time.sleep(0.2)
    try:
        latest = stream.pose()
        assert (latest.x, latest.y) == (5.0, 6.0) and stream.malformed == 1
    finally:
        stream.close()
        server.close()
    with pytest.raises(HardwareError, match="is not udp://HOST:PORT"):
        PoseStream("http://x:1")


def test_the_driver_checks_the_region_against_the_tracker(tiny: tuple[Path, Session]
                                                          ) -> None:
    spec, loaded = tiny
    regions = RegionMap.from_grid(loaded.model, 1.0)  # a: x in [0, 1), b: x in [1, 2)

    def run_at(x: float) -> object:
        robot = SimulatedRobot(loaded.strategy, loaded.domain, loaded.monitor,
                               RandomEnvironment(1), 2)
        stream = PoseStream("udp://127.0.0.1:0", timeout=0.3)
        driver = Driver(loaded.strategy, loaded.domain, loaded.monitor,
                        bind_primitives(loaded.model, str(spec.parent)),
                        Localised(robot, stream, regions))  # closes the stream at the end
        send(stream, pose(x, 0.5))
        return driver.run(0)

    assert getattr(run_at(0.5), "error", "x") is None  # the start, a
    error = getattr(run_at(1.5), "error", None)
    assert isinstance(error, HardwareError)
    assert "localisation reports region b but the controller expects a" in error.message
    error = getattr(run_at(7.0), "error", None)
    assert isinstance(error, HardwareError)
    assert "the tracker puts the robot at (7, 0.5), outside every region" in error.message


def test_cli_drive_with_a_pose_stream(tiny: tuple[Path, Session],
                                      capsys: pytest.CaptureFixture[str]) -> None:
    spec, _ = tiny
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    stop = threading.Event()

    def stream_poses() -> None:
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as out:
            while not stop.is_set():
                out.sendto(pose(0.5, 0.5), ("127.0.0.1", port))
                time.sleep(0.02)

    threading.Thread(target=stream_poses, daemon=True).start()
    try:
        code = main(["drive", str(spec), "--steps", "0", "--pose", f"udp://127.0.0.1:{port}",
                     "--cell-size", "1"])
    finally:
        stop.set()
    assert code == 0, capsys.readouterr().err
    assert "poses udp://127.0.0.1:" in capsys.readouterr().out
    assert main(["drive", str(spec), "--map", "m.yaml"]) == 2
