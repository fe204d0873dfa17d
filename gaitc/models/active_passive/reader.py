"""YAML node access for the ``active_passive`` section: typed values with positioned errors.

Every failure is a :class:`ModelFileError` at the line and column of the node at fault
(like :class:`gaitc.models.fields.Fields`, with the few readers this section needs besides).
"""

from __future__ import annotations

import contextlib
import math

import yaml

from gaitc.diagnostics import Span
from gaitc.gaitgraph.robot import FieldReader
from gaitc.models.fields import ModelFileError


class Reader(FieldReader):
    """The robot file's :class:`~gaitc.gaitgraph.robot.FieldReader`, failing with
    :class:`~gaitc.models.fields.ModelFileError`, with this section's number rules, counts
    and spans."""

    error = ModelFileError

    def number(self, node: yaml.Node, what: str, low: float | None = None) -> float:
        value = math.nan
        if isinstance(node, yaml.ScalarNode):
            with contextlib.suppress(ValueError):
                value = float(node.value)
        if not math.isfinite(value):
            raise self.fail(node, f"{what} must be a finite number")
        if low is not None and value < low:
            raise self.fail(node, f"{what} must be at least {low:g}, not {node.value}")
        return value

    def count(self, node: yaml.Node, what: str, low: int) -> int:
        value = self.number(node, what, float(low))
        if not value.is_integer():
            raise self.fail(node, f"{what} must be a whole number, not {node.value}")
        return int(value)

    def span(self, node: yaml.Node) -> Span:
        return Span(self.path, node.start_mark.line + 1, node.start_mark.column + 1)
