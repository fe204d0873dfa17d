"""Runs as MCAP files with ROS 2 encoding (``cdr`` messages, ``ros2msg`` schemas), the log
format Foxglove and rosbag2 read: the writer the recorder node and ``simulate --mcap`` share,
a run written as the nodes would have published it, and a reader of the messages back.

A schema is the message's definition as ROS 2 installed it (``share/PKG/msg/TYPE.msg``),
followed by the definitions it uses, as rosbag2 writes them.
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any, BinaryIO

from gaitc.diagnostics import UsageError
from gaitc.ros.topics import (
    DIAGNOSTICS,
    GAIT,
    HAZARDS,
    LEG_HEALTH,
    REGION,
    TOPICS,
    VALVES,
    Topic,
    diagnostics_message,
    hazards_message,
    health_message,
    present,
    step_status,
    stop_status,
    text_message,
    valve_pattern,
)
from gaitc.sim.events import ALLOWED_NOTE
from gaitc.solver.progress import goal_titles
from ltlcompiler.model import GaitKind

if TYPE_CHECKING:
    from gaitc.gaitgraph.pairing import ValveSequence
    from gaitc.sim.monitor import Monitor, Violation
    from gaitc.sim.run import Run
    from ltlcompiler.model import Model

#: The field types a definition names that are not messages.
PRIMITIVES = frozenset({"bool", "byte", "char", "float32", "float64", "int8", "uint8",
                        "int16", "uint16", "int32", "uint32", "int64", "uint64", "string",
                        "wstring"})
_SEPARATOR = "=" * 80


def _share_dirs() -> list[Path]:
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    return [Path(p) / "share" for p in [*prefixes, sys.prefix]]


def _definition_file(type_name: str) -> Path:
    package, kind = _split(type_name)
    for share in _share_dirs():
        found = share / package / "msg" / f"{kind}.msg"
        if found.is_file():
            return found
    raise UsageError(f"the definition of {type_name} is not installed (looked in "
                     f"{', '.join(str(s) for s in _share_dirs())}); reinstall the ros extra")


def _split(type_name: str) -> tuple[str, str]:
    parts = type_name.split("/")
    return parts[0], parts[-1]


def _used(text: str, package: str) -> list[str]:
    """The message types the fields of a definition use (``pkg/Type``), in order."""
    found: list[str] = []
    for line in text.splitlines():
        words = line.split("#", 1)[0].split()
        if len(words) < 2 or "=" in words[1] or "=" in words[0]:
            continue  # a comment, a blank line or a constant
        base = re.sub(r"\[.*\]$", "", words[0])
        base = re.sub(r"<=\d+$", "", base)
        if base in PRIMITIVES:
            continue
        name = ("std_msgs/Header" if base == "Header"
                else base if "/" in base else f"{package}/{base}")
        if name not in found:
            found.append(name)
    return found


def definition(type_name: str) -> str:
    """The ``ros2msg`` schema of ``type_name`` (``pkg/msg/Type``): its definition, then
    each definition it uses (once, depth first) after a separator line and ``MSG: pkg/Type``."""
    top = _definition_file(type_name).read_text(encoding="utf-8")
    parts = [top]
    seen: set[str] = set()
    stack = list(reversed(_used(top, _split(type_name)[0])))
    while stack:
        name = stack.pop()
        if name in seen:
            continue
        seen.add(name)
        text = _definition_file(name).read_text(encoding="utf-8")
        parts.append(f"{_SEPARATOR}\nMSG: {name}\n{text}")
        stack.extend(reversed(_used(text, _split(name)[0])))
    return "\n".join(part.rstrip("\n") for part in parts) + "\n"


def plain(message: Any) -> Any:
    """An rclpy message as plain data (dicts, lists, numbers, text), field by field."""
    if hasattr(message, "get_fields_and_field_types"):
        return {name: plain(getattr(message, name))
                for name in message.get_fields_and_field_types()}
    if isinstance(message, (bytes, bytearray)) and len(message) == 1:
        return message[0]  # a 'byte' field
    if isinstance(message, (list, tuple)) or type(message).__name__ == "array":
        return [plain(item) for item in message]
    return message


class Recording:
    """An MCAP file being written: one channel per topic (ROS 2 profile, CDR messages)."""

    def __init__(self, path: str | Path) -> None:
        # lazy: the ros extra (mcap) may be missing; gaitc ros then names the extra
        from mcap.writer import Writer

        self.path = Path(path)
        try:
            self._file: BinaryIO = self.path.open("wb")
        except OSError as err:
            raise UsageError(f"cannot write the recording '{path}': {err.strerror}") from None
        self._writer = Writer(self._file)
        self._writer.start(profile="ros2", library="gaitc")
        self._schemas: dict[str, int] = {}
        self._encoders: dict[str, Any] = {}
        self._channels: dict[str, int] = {}
        self._sequence: dict[str, int] = {}
        self._types: dict[str, str] = {}
        self.counts: dict[str, int] = {}
        self._closed = False

    def channel(self, topic: Topic, name: str | None = None) -> None:
        """Add ``topic`` (as ``name``, its resolved name, when given)."""
        shown = name or topic.name
        if shown in self._channels:
            return
        schema = self._schemas.get(topic.type)
        if schema is None:
            package, kind = _split(topic.type)
            schema = self._writer.register_schema(f"{package}/msg/{kind}", "ros2msg",
                                                  definition(topic.type).encode("utf-8"))
            self._schemas[topic.type] = schema
        self._channels[shown] = self._writer.register_channel(shown, "cdr", schema)
        self._types[shown] = topic.type
        self._sequence[shown] = 0
        self.counts[shown] = 0

    def write(self, topic: str, data: bytes, log_time: int, publish_time: int | None = None
              ) -> None:
        """Add the CDR message ``data`` on ``topic`` (a channel added before), received at
        ``log_time`` ns."""
        self._sequence[topic] += 1
        self.counts[topic] += 1
        self._writer.add_message(self._channels[topic], log_time, data,
                                 log_time if publish_time is None else publish_time,
                                 self._sequence[topic])

    def encoded(self, topic: str, message: Any) -> bytes:
        """``message`` (an rclpy message) in CDR by the schema of ``topic``'s channel, with
        mcap-ros2-support's encoder: the same message gives the same bytes (rclpy's
        serializer leaves its alignment padding unset)."""
        # lazy: the ros extra (mcap) may be missing; gaitc ros then names the extra
        from mcap_ros2._dynamic import serialize_dynamic  # the encoder of mcap_ros2.writer

        kind = self._types[topic]
        encoder = self._encoders.get(kind)
        if encoder is None:
            package, name = _split(kind)
            schema = f"{package}/msg/{name}"
            encoder = serialize_dynamic(schema, definition(kind))[schema]
            self._encoders[kind] = encoder
        data: bytes = encoder(plain(message))
        return data

    def close(self) -> None:
        if not self._closed:
            self._closed = True
            self._writer.finish()  # type: ignore[no-untyped-call]
            self._file.close()

    def __enter__(self) -> Recording:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.close()


@dataclass(frozen=True)
class Recorded:
    """One message read back: its topic, the time it was logged (ns) and its fields."""

    topic: str
    log_time: int
    message: Any


def read(path: str | Path) -> Iterator[Recorded]:
    """The messages of an MCAP recording in log-time order, decoded."""
    # lazy: the ros extra (mcap) may be missing; gaitc ros then names the extra
    from mcap.reader import make_reader

    # lazy: the ros extra (mcap) may be missing; gaitc ros then names the extra
    from mcap_ros2.decoder import DecoderFactory

    with Path(path).open("rb") as handle:
        reader = make_reader(handle, decoder_factories=[DecoderFactory()])
        for _schema, channel, message, decoded in reader.iter_decoded_messages(
                log_time_order=True):
            yield Recorded(channel.topic, message.log_time, decoded)


def end_reason(run: Run) -> str:
    """Why a run's robot was vented at its end, as the controller node says it."""
    if run.error is not None:
        return f"stopped: {run.error.message}; every valve vented"
    return f"{run.halted or f'finished {max(0, len(run.steps) - 1)} steps'}; every valve vented"


def write_run(run: Run, model: Model, monitor: Monitor,
              primitives: Mapping[str, ValveSequence] | None, hardware_id: str,
              path: str | Path, period: float = 1.0) -> dict[str, int]:
    """Write ``run`` to ``path`` as the controller node and the robot would have published
    it, step k at (k + 1) * ``period`` s: the observation (``hazards``, ``leg_health``),
    the command (``target_region``, ``gait``, ``valves``) and ``/diagnostics`` (the monitor's
    verdict checked again with ``monitor``, the run's surprises and the goals kept), then
    the vent at the end.  Returns the messages written by topic."""

    hazards = tuple(h.name for h in model.hazards)
    no_gait = next(g.name for g in model.gaits if g.kind is GaitKind.NONE)
    count = 0 if not primitives else next(
        (len(s.states[0]) for s in primitives.values() if s.states), 0)
    titles = goal_titles(monitor.spec)
    step_ns = max(1, int(period * 1e9))
    broken: list[str] = []
    previous: tuple[int, ...] | None = None
    with Recording(path) as out:
        for topic in present(TOPICS, bool(hazards), primitives is not None):
            out.channel(topic, topic.default_name)

        def put(topic: Topic, message: Any, at: int) -> None:
            out.write(topic.default_name, out.encoded(topic.default_name, message), at)

        at = 0
        kept, lost = list(titles), []
        for step in run.steps:
            at = (step.index + 1) * step_ns
            if hazards:
                put(HAZARDS, hazards_message(hazards, step.hazard, at), at)
            put(LEG_HEALTH, health_message(step.health, at), at)
            put(REGION, text_message(step.region), at + 1000)
            put(GAIT, text_message(step.gait), at + 1000)
            if primitives is not None:
                put(VALVES, text_message(valve_pattern(primitives, step.gait, count)),
                    at + 1000)
            values = monitor.values(dict(step.values))
            broken.extend(v.describe() for v in _broken(monitor, step.index, previous, values))
            previous = values
            surprising = [s for s in run.surprises if s.step <= step.index
                          and s.note != ALLOWED_NOTE]
            if surprising:
                kept, lost = list(surprising[-1].kept), list(surprising[-1].lost)
            status = step_status(step.index, step.region, step.gait, broken,
                                 [s.outcome.value for s in surprising], kept, lost)
            put(DIAGNOSTICS, diagnostics_message(status, hardware_id, at + 2000),
                at + 2000)
        at += step_ns // 2
        put(GAIT, text_message(no_gait), at)
        if primitives is not None:
            put(VALVES, text_message("0" * count), at)
        put(DIAGNOSTICS, diagnostics_message(stop_status(end_reason(run), kept, lost),
                                                  hardware_id, at), at)
        return dict(out.counts)


def _broken(monitor: Monitor, index: int, before: tuple[int, ...] | None,
            values: tuple[int, ...]) -> list[Violation]:
    """The clauses the step into ``values`` breaks (as the simulator's monitor finds)."""
    if before is None:
        return monitor.check_initial(values)
    found = monitor.check_step(before, values)
    return ([monitor.violation(index, "env_trans", i) for i in found.env_failed]
            + [monitor.violation(index, "sys_trans", i) for i in found.sys_failed])
