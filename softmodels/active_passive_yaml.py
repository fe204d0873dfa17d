"""YAML node access for the ``active_passive`` section: typed values with positioned errors.

Every failure is a :class:`ModelFileError` at the line and column of the node at fault
(like :class:`softmodels.fields.Fields`, with the few readers this section needs besides).
"""

from __future__ import annotations

import contextlib
import math

import yaml

from diagnostics import Span
from softmodels.fields import ModelFileError


class Reader:
    def __init__(self, path: str) -> None:
        self.path = path

    def fail(self, node: yaml.Node, message: str, hint: str | None = None) -> ModelFileError:
        m = node.start_mark
        return ModelFileError(message, Span(self.path, m.line + 1, m.column + 1), hint)

    def mapping(self, node: yaml.Node, what: str, allowed: set[str]) -> dict[str, yaml.Node]:
        if not isinstance(node, yaml.MappingNode):
            raise self.fail(node, f"{what} must be a mapping of keys to values")
        out: dict[str, yaml.Node] = {}
        for key, value in node.value:
            name = str(key.value)
            if name not in allowed:
                raise self.fail(
                    key,
                    f"unknown key {name!r} in {what}",
                    "expected one of: " + ", ".join(sorted(allowed)),
                )
            if name in out:
                raise self.fail(key, f"key {name!r} appears twice in {what}")
            out[name] = value
        return out

    def sequence(self, node: yaml.Node, what: str) -> list[yaml.Node]:
        if not isinstance(node, yaml.SequenceNode):
            raise self.fail(node, f"{what} must be a list")
        return list(node.value)

    def text(self, node: yaml.Node, what: str) -> str:
        if not isinstance(node, yaml.ScalarNode) or node.value == "":
            raise self.fail(node, f"{what} must be a non-empty text value")
        return str(node.value)

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

    def vector(self, node: yaml.Node, what: str, size: int) -> tuple[float, ...]:
        items = self.sequence(node, what)
        if len(items) != size:
            raise self.fail(node, f"{what} must have {size} numbers, not {len(items)}")
        return tuple(self.number(item, what) for item in items)

    def count(self, node: yaml.Node, what: str, low: int) -> int:
        value = self.number(node, what, float(low))
        if not value.is_integer():
            raise self.fail(node, f"{what} must be a whole number, not {node.value}")
        return int(value)

    def span(self, node: yaml.Node) -> Span:
        return Span(self.path, node.start_mark.line + 1, node.start_mark.column + 1)
