"""The one layout of gaitc's ROS 2 topics: names, message types, QoS, and the messages of a
step, used alike by the controller node, the simulated robot and the MCAP writer.

Standard messages only (no interface package to build): the robot's observation is a
``sensor_msgs/JointState`` of leg health levels by leg name, with a second one of hazard
sets (1 on, 0 off) stamped the same; the commands are ``std_msgs/String`` (gait, target
region, valve pattern); the node's state goes to ``/diagnostics`` as a
``diagnostic_msgs/DiagnosticArray``.  Names are relative, so a namespace or a remap moves
them as it moves any node's.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import Enum
from typing import TYPE_CHECKING, Any, Final

from gaitc.diagnostics import UsageError

if TYPE_CHECKING:
    from rclpy.qos import QoSProfile

    from gaitc.gaitgraph.pairing import ValveSequence

#: What to install when the ROS 2 wheels or mcap are missing.
EXTRA_HINT: Final = "pip install 'gaitc[ros]' (or run scripts/setup.sh)"


class Flow(Enum):
    """What a topic carries, seen from the controller node."""

    OBSERVATION = "observation"  # the robot's sensors to the controller
    COMMAND = "command"  # the controller to the robot
    DIAGNOSTICS = "diagnostics"  # the controller's state, for people and monitors

    @property
    def direction(self) -> str:
        """``subscribed`` or ``published``, by the controller node."""
        return "subscribed" if self is Flow.OBSERVATION else "published"


@dataclass(frozen=True)
class Topic:
    """One topic: its (relative) name, its message type, which way it flows, and what it
    carries."""

    name: str
    type: str  # package/msg/Type
    flow: Flow
    carries: str
    only: str = ""  # when it exists: every spec if empty

    @property
    def default_name(self) -> str:
        """The name in the root namespace without remaps (``/gait``), as recordings say it."""
        return self.name if self.name.startswith("/") else f"/{self.name}"

    @property
    def message_class(self) -> Any:
        """The rclpy message class of :attr:`type`."""
        package, _, kind = self.type.split("/")
        return getattr(importlib.import_module(f"{package}.msg"), kind)


LEG_HEALTH: Final = Topic("leg_health", "sensor_msgs/msg/JointState", Flow.OBSERVATION,
                          "each leg's health level: name = the spec's legs, position = "
                          "level (1..the leg's levels); header.stamp = when sensed")
HAZARDS: Final = Topic("hazards", "sensor_msgs/msg/JointState", Flow.OBSERVATION,
                       "each hazard set's state: name = the spec's hazard sets, position 1 "
                       "on, 0 off (at most one on); the stamp of the leg_health it goes with",
                       only="specs with hazards")
GAIT: Final = Topic("gait", "std_msgs/msg/String", Flow.COMMAND,
                    "the gait to run now (the spec's no-gait when stopped: vent)")
REGION: Final = Topic("target_region", "std_msgs/msg/String", Flow.COMMAND,
                      "the region the gait takes the robot to")
VALVES: Final = Topic("valves", "std_msgs/msg/String", Flow.COMMAND,
                      "the gait's valve states, one word per state ('0110 1001'); all "
                      "'0' when vented", only="specs whose gaits bind valve primitives")
DIAGNOSTICS: Final = Topic("/diagnostics", "diagnostic_msgs/msg/DiagnosticArray",
                           Flow.DIAGNOSTICS,
                           "the node's state: step, monitor verdict, surprises, goals kept "
                           "and lost, why it stopped")

#: Every topic, in the order the docs list them.
TOPICS: Final = (LEG_HEALTH, HAZARDS, GAIT, REGION, VALVES, DIAGNOSTICS)
#: The name of the controller node's one status in /diagnostics.
STATUS_NAME: Final = "gaitc: controller"
#: DiagnosticStatus levels.
OK, WARN, ERROR = 0, 1, 2


def require() -> None:
    """Raise a :class:`UsageError` naming the extra when rclpy, the messages or mcap are
    missing (or do not load)."""
    for module in ("rclpy", "std_msgs.msg", "sensor_msgs.msg", "diagnostic_msgs.msg", "mcap",
                   "mcap_ros2"):
        try:
            importlib.import_module(module)
        except ImportError as err:  # a missing wheel, or a ROS library that does not load
            raise UsageError(f"'gaitc ros' and 'simulate --mcap' need ROS 2 and MCAP "
                             f"({module} is missing: {err}); {EXTRA_HINT}") from None


def qos(topic: Topic) -> QoSProfile:
    """The QoS of ``topic``: reliable everywhere, so that no step is lost; commands are
    transient-local (a late subscriber gets the current gait, as a latched topic did)."""
    # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

    durable = topic.flow is Flow.COMMAND
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=10,
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=(DurabilityPolicy.TRANSIENT_LOCAL if durable
                                  else DurabilityPolicy.VOLATILE))


def qos_words(topic: Topic) -> str:
    """:func:`qos` in words, for the docs' table."""
    return ("reliable, transient local, keep last 10" if topic.flow is Flow.COMMAND
            else "reliable, volatile, keep last 10")


def stamp(nanoseconds: int) -> Any:
    """A ``builtin_interfaces/Time`` of ``nanoseconds`` since the epoch."""
    # lazy: the ros extra may be missing; gaitc ros then names the extra
    from builtin_interfaces.msg import Time

    return Time(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)


def nanoseconds(time: Any) -> int:
    """A ``builtin_interfaces/Time`` in nanoseconds."""
    return int(time.sec) * 1_000_000_000 + int(time.nanosec)


def health_message(health: Sequence[tuple[str, int]], at: int) -> Any:
    """The ``leg_health`` observation of ``health`` ((leg, level) pairs), stamped ``at`` ns."""
    message = LEG_HEALTH.message_class()
    message.header.stamp = stamp(at)
    message.name = [leg for leg, _ in health]
    message.position = [float(level) for _, level in health]
    return message


def hazards_message(hazards: Sequence[str], active: str | None, at: int) -> Any:
    """The ``hazards`` observation: every hazard set, ``active`` on (None: all off)."""
    message = HAZARDS.message_class()
    message.header.stamp = stamp(at)
    message.name = list(hazards)
    message.position = [1.0 if name == active else 0.0 for name in hazards]
    return message


def text_message(text: str) -> Any:
    """A ``std_msgs/String`` of ``text`` (gait, region, valves)."""
    message = GAIT.message_class()
    message.data = text
    return message


def valve_pattern(primitives: Mapping[str, ValveSequence] | None, gait: str, count: int
                  ) -> str:
    """What the ``valves`` topic carries for ``gait``: its primitive's valve states, one word
    each (``count`` zeros, vented, for a gait without one, such as the no-gait)."""
    seq = None if primitives is None else primitives.get(gait)
    return " ".join(seq.states) if seq is not None and seq.states else "0" * count


@dataclass(frozen=True)
class Status:
    """The controller's state as /diagnostics reports it: a level (OK, WARN, ERROR), a
    sentence, and key-value pairs (step, verdict, surprises, goals kept and lost)."""

    level: int
    message: str
    values: tuple[tuple[str, str], ...] = ()

    def value(self, key: str) -> str | None:
        return dict(self.values).get(key)


def step_status(index: int, region: str, gait: str, broken: Sequence[str],
                outcomes: Sequence[str], kept: Sequence[str], lost: Sequence[str]) -> Status:
    """The controller's status after step ``index``: the gait to ``region``; the run
    monitor's verdict (``broken``: the clauses broken so far, described); the surprises so
    far (``outcomes``: recovered, degraded, stopped); the goals kept and lost.  OK while
    nothing was broken or surprising, else WARN."""
    verdict = "held" if not broken else f"{len(broken)} clause(s) broken; first: {broken[0]}"
    level = OK if not broken and not outcomes else WARN
    return Status(level, f"step {index}: {gait} to {region}", (
        ("step", str(index)), ("region", region), ("gait", gait), ("monitor", verdict),
        ("surprises", str(len(outcomes))), ("last surprise", outcomes[-1] if outcomes
                                                else "none"),
        *goal_values(kept, lost)))


def stop_status(reason: str, kept: Sequence[str], lost: Sequence[str]) -> Status:
    """The controller's status once stopped (every valve vented) for ``reason``."""
    return Status(ERROR, reason, (*goal_values(kept, lost), ("stopped", reason)))


def goal_values(kept: Sequence[str], lost: Sequence[str]) -> tuple[tuple[str, str], ...]:
    """The goals kept and lost as /diagnostics values."""
    return (("goals kept", ", ".join(kept) or "none"), ("goals lost", ", ".join(lost) or "none"))


def diagnostics_message(status: Status, hardware_id: str, at: int) -> Any:
    """The ``/diagnostics`` array holding ``status``, stamped ``at`` ns."""
    # lazy: the ros extra may be missing; gaitc ros then names the extra
    from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

    entry = DiagnosticStatus(level=bytes([status.level]), name=STATUS_NAME,
                             message=status.message, hardware_id=hardware_id,
                             values=[KeyValue(key=k, value=v) for k, v in status.values])
    array = DiagnosticArray()
    array.header.stamp = stamp(at)
    array.status = [entry]
    return array


def status_of(message: Any) -> Status | None:
    """The controller's :class:`Status` in a /diagnostics array (a message object or the
    record mcap_ros2 decodes), or None when it holds none."""
    for entry in message.status:
        if entry.name == STATUS_NAME:
            level = entry.level
            number = level[0] if isinstance(level, (bytes, bytearray)) else int(level)
            return Status(number, entry.message,
                          tuple((kv.key, kv.value) for kv in entry.values))
    return None


def present(topics: Sequence[Topic], hazards: bool, valves: bool) -> tuple[Topic, ...]:
    """The topics of a spec: ``hazards`` only with hazard sets, ``valves`` only with valve
    primitives."""
    return tuple(t for t in topics if (t is not HAZARDS or hazards) and (t is not VALVES
                                                                         or valves))


def table() -> str:
    """The topic table in Markdown (docs/how-to/ros.md holds this text)."""
    lines = ["| topic | type | direction | QoS | carries |", "|---|---|---|---|---|"]
    for t in TOPICS:
        when = f" ({t.only})" if t.only else ""
        lines.append(f"| `{t.name}` | `{t.type}` | {t.flow.direction} | {qos_words(t)} | "
                     f"{t.carries}{when} |")
    return "\n".join(lines)
