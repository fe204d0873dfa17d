"""The recorder node: every topic of the controller and the robot, as received, into an
MCAP file (:class:`~gaitc.ros.recording.Recording`), as ``ros2 bag record`` would."""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from gaitc.ros.graph import wait_until
from gaitc.ros.recording import Recording
from gaitc.ros.topics import Topic, qos

if TYPE_CHECKING:
    from gaitc.ros.graph import Graph


class Recorder:
    """Subscribes to ``topics`` (serialized, not decoded) and writes each message to
    ``recording`` when it arrives."""

    def __init__(self, graph: Graph, topics: Sequence[Topic], recording: Recording,
                 name: str = "gaitc_recorder") -> None:
        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.node import Node

        self.recording = recording
        self.node = node = Node(name, context=graph.context)
        self.subscriptions = []
        for topic in topics:
            resolved = node.resolve_topic_name(topic.name)
            recording.channel(topic, resolved)
            self.subscriptions.append(node.create_subscription(
                topic.message_class, topic.name, self._writer(resolved), qos(topic),
                raw=True))
        graph.add(node)

    def _writer(self, topic: str) -> Any:
        def write(data: bytes) -> None:
            self.recording.write(topic, data, time.time_ns())
        return write

    def connected(self, publishers: dict[str, int]) -> bool:
        """Whether each subscription sees at least ``publishers[topic]`` publishers."""
        return all(s.get_publisher_count() >= publishers.get(s.topic_name, 1)
                   for s in self.subscriptions)

    def settle(self, expected: dict[str, int], timeout: float = 2.0) -> bool:
        """Wait until at least ``expected[topic]`` messages of each topic were written."""
        counts = self.recording.counts
        return wait_until(lambda: all(counts.get(t, 0) >= n for t, n in expected.items()),
                          timeout)
