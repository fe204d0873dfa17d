"""Positioned access to the YAML nodes of a robot file's ``model:`` section.

Every reader error names the file, line and column of the node, as the rest of the robot
file's errors do (:mod:`gaitc.gaitgraph.robot`); the class raised is :class:`ModelFileError`.
"""

from __future__ import annotations

import math

import yaml

from gaitc.diagnostics import Span
from gaitc.gaitgraph.robot import FieldReader, RobotFileError


class ModelFileError(RobotFileError):
    """The ``model:`` section of a robot file is malformed or describes an impossible model."""


def span_of(path: str, node: yaml.Node) -> Span:
    """The span of a node's first character."""
    mark = node.start_mark
    return Span(path, mark.line + 1, mark.column + 1)


class Fields(FieldReader):
    """Typed, positioned readers over the YAML nodes of one file, failing with
    :class:`ModelFileError`; numbers may be asked to be positive."""

    error = ModelFileError

    def number(
        self, node: yaml.Node, what: str, low: float | None = None, positive: bool = False
    ) -> float:
        try:
            if not isinstance(node, yaml.ScalarNode):
                raise ValueError
            value = float(node.value)
        except ValueError:
            raise self.fail(node, f"{what} must be a number") from None
        if not math.isfinite(value):
            raise self.fail(node, f"{what} must be a finite number, not {node.value}")
        if positive and value <= 0:
            raise self.fail(node, f"{what} must be positive, not {node.value}")
        if low is not None and value < low:
            raise self.fail(node, f"{what} must be at least {low:g}, not {node.value}")
        return value

    def matrix3(self, node: yaml.Node, what: str) -> tuple[tuple[float, ...], ...]:
        rows = self.sequence(node, what)
        if len(rows) != 3:
            raise self.fail(node, f"{what} must be a 3x3 matrix (three rows), not {len(rows)} rows")
        return tuple(self.vector(row, f"a row of {what}", 3) for row in rows)
