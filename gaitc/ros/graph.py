"""The ROS 2 graph a command runs in: its own rclpy context (initialised with the command's
``--ros-args``), one executor spinning the callbacks of its nodes in a thread, and a
shutdown that ends every node and the thread.

Signals stay gaitc's (rclpy's handlers are not installed), so that SIGINT and SIGTERM
vent the robot before anything else happens (:mod:`gaitc.ros.node`).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from types import TracebackType
from typing import Any

from gaitc.diagnostics import UsageError


class Graph:
    """An rclpy context with an executor thread; a context manager that shuts both down."""

    def __init__(self, ros_args: Sequence[str] = ()) -> None:
        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        import rclpy

        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.context import Context

        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.executors import SingleThreadedExecutor

        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.signals import SignalHandlerOptions

        self.context = Context()
        args = ["gaitc", *(["--ros-args", *ros_args] if ros_args else [])]
        try:
            rclpy.init(args=args, context=self.context,
                       signal_handler_options=SignalHandlerOptions.NO)
        except Exception as err:  # rclpy's UnknownROSArgsError, RCLError for malformed ones
            unknown = type(err).__name__ == "UnknownROSArgsError"
            raise UsageError(f"--ros-args: {'unknown ROS arguments ' if unknown else ''}{err}",
                             hint="ROS arguments are remaps (-r FROM:=TO), parameters (-p "
                             "NAME:=VALUE) and --log-level LEVEL") from None
        self.executor = SingleThreadedExecutor(context=self.context)
        self.nodes: list[Any] = []
        self._thread = threading.Thread(target=self._spin, name="gaitc-ros-executor",
                                        daemon=True)
        self._started = False
        self._stop = threading.Event()

    def add(self, node: Any) -> Any:
        """Spin ``node``'s callbacks in this graph's executor; returns it."""
        self.nodes.append(node)
        self.executor.add_node(node)
        if not self._started:
            self._started = True
            self._thread.start()
        return node

    def _spin(self) -> None:
        # lazy: the ros extra (rclpy) may be missing; gaitc ros then names the extra
        from rclpy.executors import ExternalShutdownException

        try:
            while not self._stop.is_set() and self.context.ok():
                self.executor.spin_once(timeout_sec=0.05)
        except (ExternalShutdownException, KeyboardInterrupt):
            pass
        except Exception:  # the context was shut down while a wait set was being built
            if self.context.ok():
                raise

    def close(self) -> None:
        """Destroy every node, shut down the context and join the executor thread."""
        self._stop.set()
        if self._started:
            self._thread.join(timeout=2.0)
        for node in self.nodes:
            self.executor.remove_node(node)
            node.destroy_node()
        self.nodes.clear()
        self.executor.shutdown(timeout_sec=0.5)
        self.context.try_shutdown()

    def __enter__(self) -> Graph:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.close()


def wait_until(done: Callable[[], bool], timeout: float, every: float = 0.005) -> bool:
    """Poll ``done`` until it holds or ``timeout`` s pass; whether it held."""
    end = time.monotonic() + timeout
    while not done():
        if time.monotonic() > end:
            return False
        time.sleep(every)
    return True
