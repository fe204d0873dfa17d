"""Localisation from an external tracker: poses on a local stream, mapped to regions.

A motion-capture bridge streams poses as JSON (``{"x": 1.2, "y": 0.4}``, metres or any unit
the map uses), one per UDP datagram (``udp://127.0.0.1:PORT``: gaitc listens) or one per
line over TCP (``tcp://HOST:PORT``: gaitc connects).  The region is the one whose polygon
holds the latest pose: polygons from a map file, or the cells of the spec's grid at a given
cell size (origin at the grid's south-west corner, x east, y north).  :class:`Localised`
wraps any backend and replaces the region of its readings, so the driver's check that the
robot reached the region the controller expects (thesis section 3.3's region propositions)
rests on the tracker.  Messages are bounded in size; malformed ones are counted and skipped;
a pose older than ``max_age`` seconds, or none within ``timeout``, is an error.
:func:`deviation` tells how a gait missed the region expected: the wrong way, short of it,
past it, or drifted sideways into a neighbour.
"""

from __future__ import annotations

import json
import math
import select
import socket
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

import yaml

from gaitc.diagnostics.yamltext import finite_number, keyed_section, node_span
from gaitc.hw.backend import WRONG_WAY, Backend, Course, HardwareError, SensorReading, where
from gaitc.sim.environments import Move
from ltlcompiler.model import Model

MAX_MESSAGE = 4096  # bytes of one pose message
MAX_BATCH = 10_000  # messages read per look at the stream
Point = tuple[float, float]


@dataclass(frozen=True)
class Pose:
    x: float
    y: float
    received: float  # time.monotonic() of its arrival


class RegionMap:
    """Named polygons; :meth:`region_at` says which one holds a point."""

    def __init__(self, polygons: Mapping[str, Sequence[Point]]) -> None:
        self.polygons = {name: tuple(points) for name, points in polygons.items()}

    @classmethod
    def from_grid(cls, model: Model, cell: float) -> RegionMap:
        """The spec's grid cells as squares of side ``cell``."""
        if model.grid is None or cell <= 0:
            raise HardwareError("the spec declares no grid; give a map file (--map)",
                                where("localisation"))
        rows = model.grid[0]
        out = {}
        for r in model.regions:
            if r.row is None or r.col is None:
                continue
            x0, y0 = r.col * cell, (rows - 1 - r.row) * cell
            out[r.name] = ((x0, y0), (x0 + cell, y0), (x0 + cell, y0 + cell), (x0, y0 + cell))
        return cls(out)

    @classmethod
    def from_file(cls, path: str | Path, regions: Sequence[str]) -> RegionMap:
        """``regions: {name: [[x, y], ...], ...}`` in YAML; names must be the spec's.  Every
        error names the file and the position of the value at fault."""
        name, polygons = keyed_section(path, HardwareError, "map", "regions",
                                       "a map file maps 'regions' to polygons")
        out = {}
        for region, (key, value) in polygons.items():
            if region not in regions:
                raise HardwareError(f"the map names region {region!r}, which the spec has not",
                                    node_span(name, key))
            points = value.value if isinstance(value, yaml.SequenceNode) else []
            polygon = []
            for point in points:
                xy = point.value if isinstance(point, yaml.SequenceNode) else []
                numbers = [n for n in (finite_number(v) for v in xy) if n is not None]
                if len(xy) != 2 or len(numbers) != 2:
                    raise HardwareError(f"region {region}: a polygon point must be [x, y], two "
                                        "finite numbers", node_span(name, point))
                polygon.append((numbers[0], numbers[1]))
            if len(polygon) < 3:
                raise HardwareError(f"region {region}: a polygon needs at least 3 [x, y] points",
                                    node_span(name, value))
            out[region] = polygon
        return cls(out)

    def centre(self, name: str) -> Point:
        """The centre of a region's polygon (the mean of its corners)."""
        points = self.polygons[name]
        return (sum(p[0] for p in points) / len(points), sum(p[1] for p in points) / len(points))

    def region_at(self, x: float, y: float) -> str | None:
        """The first region (in map order) whose polygon holds (x, y); None outside all."""
        for name, polygon in self.polygons.items():
            if _inside(x, y, polygon):
                return name
        return None


def _inside(x: float, y: float, polygon: Sequence[Point]) -> bool:
    """Even-odd rule; points on the lower or left edge count as inside."""
    inside = False
    for (x1, y1), (x2, y2) in zip(polygon, (*polygon[1:], polygon[0]), strict=True):
        if (y1 <= y < y2 or y2 <= y < y1) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


COMPASS = ("east", "north-east", "north", "north-west", "west", "south-west", "south",
           "south-east")


def compass(x: float, y: float) -> str:
    """The compass word (of eight) nearest the direction of (x, y), x east and y north."""
    return COMPASS[round(math.degrees(math.atan2(y, x)) / 45.0) % 8]


#: A gait whose motion is shorter than this (mm) did not move the robot (its direction
#: means nothing).
STILL = 0.5


class Miss(Enum):
    """How a gait missed the region it was to reach."""

    STILL = "did not move"  # its motion is under STILL mm
    WRONG_WAY = "went the wrong way"  # its motion is WRONG_WAY degrees or more off the move
    SHORT = "fell short"  # it stopped behind the region, toward where it set out
    FAR = "went too far"  # it passed the region
    DRIFTED = "drifted"  # far enough along the move, but beside the region


@dataclass(frozen=True)
class Deviation:
    """A gait's motion split along and across its move, and how it missed the region."""

    miss: Miss
    along: float  # mm of motion along the move (negative: backwards)
    across: float  # mm of motion across the move, to its left (negative: to its right)
    side: str  # the compass word of the motion across the move ("" when there is none)
    length: float  # mm of the move, centre to centre
    error: float  # degrees between the motion and the move
    beside: str  # the compass word of where the robot ended, seen from the region expected


def deviation(course: Course, reached: Point) -> Deviation:
    """How the motion of ``course`` missed its region; ``reached`` is where the region the
    robot ended in lies from the region expected (their centres, mm).  A motion shorter than
    :data:`STILL` did not move the robot; one :data:`WRONG_WAY` degrees or more off the move
    went the wrong way, whatever it reached;
    else the robot ended beside the region (``reached`` more across the move than along
    it): drifted; else behind it: fell short; else past it: went too far."""
    (mx, my), (wx, wy) = course.moved, course.wanted
    length = math.hypot(wx, wy)
    ux, uy = (wx / length, wy / length) if length > 1e-9 else (1.0, 0.0)
    along = mx * ux + my * uy
    across = -mx * uy + my * ux  # along the move's left normal (-uy, ux)
    side = compass(-uy * across, ux * across) if abs(across) >= 0.05 else ""
    rx, ry = reached
    ahead, aside = rx * ux + ry * uy, -rx * uy + ry * ux
    if math.hypot(mx, my) < STILL:
        miss = Miss.STILL
    elif course.error >= WRONG_WAY:
        miss = Miss.WRONG_WAY
    elif abs(ahead) < abs(aside):
        miss = Miss.DRIFTED
    else:
        miss = Miss.SHORT if ahead < 0 else Miss.FAR
    beside = compass(rx, ry) if math.hypot(rx, ry) > 1e-9 else ""
    return Deviation(miss, along, across, side, length, course.error, beside)


def parse_pose(message: bytes) -> tuple[float, float] | None:
    """``{"x": .., "y": ..}`` → (x, y); None for anything else (bounded, finite numbers)."""
    if len(message) > MAX_MESSAGE:
        return None
    try:
        data = json.loads(message)
        x, y = float(data["x"]), float(data["y"])
    except (ValueError, TypeError, KeyError, RecursionError):
        return None
    return (x, y) if math.isfinite(x) and math.isfinite(y) else None


class PoseStream:
    """The tracker's stream: ``udp://HOST:PORT`` (listen) or ``tcp://HOST:PORT`` (connect)."""

    def __init__(self, url: str, timeout: float = 1.0, max_age: float = 1.0) -> None:
        self.url = url
        self.timeout = timeout
        self.max_age = max_age
        self.latest: Pose | None = None
        self.malformed = 0
        scheme, _, rest = url.partition("://")
        host, _, port = rest.rpartition(":")
        if scheme not in ("udp", "tcp") or not host or not port.isdigit():
            raise HardwareError(f"pose source {url!r} is not udp://HOST:PORT or tcp://HOST:PORT",
                                where("--pose"))
        self._pending = b""
        try:
            if scheme == "udp":
                self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                self.sock.bind((host, int(port)))
            else:
                self.sock = socket.create_connection((host, int(port)), timeout=timeout)
        except OSError as err:
            raise HardwareError(f"cannot open the pose source {url}: {err}",
                                where("--pose")) from None
        self.sock.setblocking(False)
        self.datagrams = scheme == "udp"

    def _messages(self) -> list[bytes]:
        out: list[bytes] = []
        while len(out) < MAX_BATCH and select.select([self.sock], [], [], 0)[0]:
            try:
                data = self.sock.recv(MAX_MESSAGE + 1)
            except OSError:
                break
            if self.datagrams:
                out.append(data)
                continue
            if not data:
                raise HardwareError(f"the pose source {self.url} closed the stream",
                                    where("--pose"))
            self._pending += data
            *lines, self._pending = self._pending.split(b"\n")
            out += lines
            if len(self._pending) > MAX_MESSAGE:  # a line without an end: drop it
                self._pending, self.malformed = b"", self.malformed + 1
        return out

    def pose(self) -> Pose:
        """The latest pose, waiting up to ``timeout`` for a first one; raise when stale."""
        deadline = time.monotonic() + self.timeout
        while True:
            for message in self._messages():
                point = parse_pose(message)
                if point is None:
                    self.malformed += 1
                else:
                    self.latest = Pose(point[0], point[1], time.monotonic())
            now = time.monotonic()
            if self.latest is not None and now - self.latest.received <= self.max_age:
                return self.latest
            if now >= deadline:
                what = "no pose" if self.latest is None else "no fresh pose"
                raise HardwareError(f"{what} from the tracker at {self.url} within "
                                    f"{self.timeout:g} s", where("--pose"),
                                    "check that the motion-capture bridge is streaming")
            select.select([self.sock], [], [], min(0.05, deadline - now))

    def close(self) -> None:
        self.sock.close()


class Localised(Backend):
    """A backend whose readings take their region from a pose stream and a region map."""

    def __init__(self, inner: Backend, stream: PoseStream, regions: RegionMap) -> None:
        super().__init__(inner.valve_count)
        self.inner, self.stream, self.regions = inner, stream, regions
        self.name = f"{inner.name}, poses {stream.url}"

    def open(self) -> None:
        self.inner.open()

    def close(self) -> None:
        try:
            self.inner.close()
        finally:
            self.stream.close()

    def apply(self, valves: str) -> None:
        self.inner.apply(valves)

    def wait(self, seconds: float) -> None:
        self.inner.wait(seconds)

    def step_context(self, in_use: tuple[str, ...], in_cache: bool) -> None:
        self.inner.step_context(in_use, in_cache)

    def accepted(self, move: Move) -> None:
        self.inner.accepted(move)

    def safety_note(self) -> str:
        return self.inner.safety_note()

    def course(self, source: str, target: str) -> Course | None:
        return self.inner.course(source, target)

    def read_sensors(self) -> SensorReading:
        reading = self.inner.read_sensors()
        pose = self.stream.pose()
        region = self.regions.region_at(pose.x, pose.y)
        if region is None:
            raise HardwareError(f"the tracker puts the robot at ({pose.x:g}, {pose.y:g}), "
                                "outside every region of the map", where(self.name))
        return SensorReading(reading.health, reading.hazard, region)
