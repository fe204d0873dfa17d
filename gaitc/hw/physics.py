"""The physics backend: valve states run through a chapter 4 model, the region from the pose.

Health levels and hazards come from the simulated robot (:mod:`gaitc.hw.simulated`, within the
spec's assumptions); the chassis moves as the model predicts (thesis 4.1.1, via
:mod:`gaitc.models`), each valve state held for the robot file's control period in simulated
time, and a leg at health level 1 (inoperable) stays vented whatever its valve says.  The
regions get a size and a position on the map (grid cells, or the layout of
:mod:`gaitc.sim.placement`, as squares of ``cell`` mm), and the reading's region is the one
under the chassis: a gait that does not carry the robot into the region the controller
expects shows up as a run that breaks the spec, as it would on hardware.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from gaitc.hw.backend import Backend, Course, HardwareError, SensorReading, where
from gaitc.hw.localisation import RegionMap
from gaitc.hw.simulated import SimulatedRobot
from gaitc.models.motion import Pose2D
from gaitc.models.spring_damper.model import SpringDamperModel, State
from gaitc.sim.environments import Move
from gaitc.sim.placement import positions
from ltlcompiler.model import Model


def region_map(model: Model, cell: float) -> RegionMap:
    """Squares of side ``cell`` (mm) for the spec's regions: its grid, else the map layout."""
    if model.grid is not None:
        return RegionMap.from_grid(model, cell)

    half = cell / 2.0
    squares = {
        name: (
            (x - half, y - half),
            (x + half, y - half),
            (x + half, y + half),
            (x - half, y + half),
        )
        for name, (x, y) in positions(model, cell).items()
    }
    return RegionMap(squares)


def centre(regions: RegionMap, name: str) -> Pose2D:
    """The centre of a region's polygon (:meth:`RegionMap.centre`), heading 0 (east)."""
    x, y = regions.centre(name)
    return Pose2D(x, y, 0.0)


@dataclass(frozen=True)
class Placed:
    """The chassis pose when the sensors were read, and the region under it."""

    reading: int
    pose: Pose2D
    region: str | None


class PhysicsRobot(Backend):
    """A simulated robot whose chassis moves by the spring-damper model."""

    def __init__(
        self,
        inner: SimulatedRobot,
        model: SpringDamperModel,
        regions: RegionMap,
        start: Pose2D,
        period: float,
    ) -> None:
        super().__init__(inner.valve_count)
        self.inner, self.model, self.regions, self.start = inner, model, regions, start
        self.period = period
        self.name = f"physics model ({model.name}), {inner.environment.name}"
        self.placed: list[Placed] = []
        self.state: State | None = None
        self.failed: frozenset[str] = frozenset()  # legs the last reading put at level 1
        self.gait: str | None = None  # the gait the controller runs next (accepted)
        self._leg_of_valve = ["?"] * inner.valve_count
        for limb in model.robot.limbs:
            for valve in limb.valves:
                self._leg_of_valve[valve] = limb.name

    def open(self) -> None:
        self.inner.open()
        rest = self.model.steady_state((False,) * self.valve_count)
        offset = np.array([self.start.x / 1000.0, self.start.y / 1000.0, 0.0])
        offset[:2] -= rest.position[0, :2]
        self.state = replace(rest, position=rest.position + offset, feet=rest.feet + offset)

    def close(self) -> None:
        self.inner.close()

    def apply(self, valves: str) -> None:
        self.inner.apply(valves)  # checks the shape and records it
        if self.state is None:
            raise HardwareError("the physics model is not open", where(self.name))
        # an inoperable actuator (health level 1) no longer moves when its valve opens
        pressurised = tuple(
            c == "1" and leg not in self.failed
            for c, leg in zip(valves, self._leg_of_valve, strict=True)
        )
        self.state = self.model.run(self.state, [pressurised], self.period)

    def wait(self, seconds: float) -> None:
        del seconds  # simulated time: each valve state is held for one control period

    def accepted(self, move: Move) -> None:
        self.inner.accepted(move)
        self.gait = move.state.gait

    @property
    def pose(self) -> Pose2D:
        if self.state is None:
            return self.start
        return self.state.pose()

    def course(self, source: str, target: str) -> Course | None:
        """The chassis motion between the last two readings against the move from the
        centre of ``source`` to the centre of ``target``."""
        if len(self.placed) < 2 or source not in self.regions.polygons \
                or target not in self.regions.polygons:
            return None
        before, after = self.placed[-2].pose, self.placed[-1].pose
        a, b = centre(self.regions, source), centre(self.regions, target)
        return Course((after.x - before.x, after.y - before.y), (b.x - a.x, b.y - a.y))

    def read_sensors(self) -> SensorReading:
        reading = self.inner.read_sensors()
        self.failed = frozenset(leg for leg, level in reading.health if level == 1)
        pose = self.pose
        region = self.regions.region_at(pose.x, pose.y)
        self.placed.append(Placed(len(self.placed), pose, region))
        if region is None:
            raise self._off_map(pose)
        return SensorReading(reading.health, reading.hazard, region)

    def _off_map(self, pose: Pose2D) -> HardwareError:
        """The error for a pose outside the map, located as the driver locates a gait that
        missed its region: at the gait just run in the .gait file, named with its step (the
        driver's numbering: the gait of step k is read after it, by reading k + 1), or at the
        spec's ``start`` before the first gait."""
        model = self.inner.domain.model
        at = f"({pose.x:.1f}, {pose.y:.1f}) mm, outside every region of the map"
        gait = None if len(self.placed) < 2 else next(
            (g for g in model.gaits if g.name == self.gait), None)
        if gait is None:
            return HardwareError(f"at the start, the model puts the robot at {at}",
                                 model.start_span or where(self.name),
                                 "check that the map holds the start region's centre")
        return HardwareError(
            f"step {len(self.placed) - 2}: after gait {gait.name} the model puts the robot at "
            f"{at}; stopped with all valves vented", gait.span or where(self.name),
            "the gait carried the robot off the map: run fewer cycles (--cycles), grow the "
            "cells (--cell-size) or choose a primitive closer to the move")
