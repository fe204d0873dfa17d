"""Writing fitted values into the ``model: spring_damper:`` section of a robot file.

The file is edited as text, so its comments and layout stay: a value that is there is
replaced where it stands, a missing key is added to the limb's mapping (inside the braces
of a flow mapping, on a new line of a block one).  The result is read back with
:func:`~gaitc.models.spring_damper.description.parse_spring_damper` before it replaces the file.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import yaml

from gaitc.diagnostics.files import decode_text, read_input, write_atomically
from gaitc.models.fields import Fields, ModelFileError
from gaitc.models.spring_damper.description import parse_spring_damper, section_node


def number(value: float) -> str:
    """A number as the robot file writes it: six significant digits."""
    text = f"{value:.6g}"
    return "0" if text == "-0" else text


def matrix(rows: tuple[tuple[float, ...], ...]) -> str:
    return "[" + ", ".join("[" + ", ".join(number(v) for v in row) + "]" for row in rows) + "]"


def _limb_node(text: str, path: str, limb: str) -> yaml.MappingNode:
    f = Fields(path)
    section = section_node(text, path, "spring_damper")
    if not isinstance(section, yaml.MappingNode):
        raise f.fail(section, "model spring_damper must be a mapping of keys to values")
    limbs = next((v for k, v in section.value if k.value == "limbs"), None)
    if limbs is None:
        raise f.fail(section, "model spring_damper needs 'limbs', one per leg")
    for item in f.sequence(limbs, "limbs"):
        if isinstance(item, yaml.MappingNode):
            for key, value in item.value:
                if key.value == "name" and value.value == limb:
                    return item
    raise f.fail(limbs, f"model spring_damper has no limb {limb}")


def _end(node: yaml.Node) -> int:
    """Where a value ends: a block collection's own end mark lies past the lines after it."""
    while isinstance(node, yaml.MappingNode | yaml.SequenceNode) and not node.flow_style:
        if not node.value:
            break
        last = node.value[-1]
        node = last[1] if isinstance(last, tuple) else last
    return int(node.end_mark.index)


def set_field(text: str, path: str, limb: str, key: str, value: str) -> str:
    """``text`` with ``key: value`` (flow YAML) set in the entry of ``limb``."""
    node = _limb_node(text, path, limb)
    for k, v in node.value:
        if k.value == key:
            start = v.start_mark.index
            if isinstance(v, yaml.MappingNode | yaml.SequenceNode) and not v.flow_style:
                start = text.index(":", k.end_mark.index) + 1  # a block value: after "key:"
                value = " " + value
            return text[:start] + value + text[_end(v) :]
    if node.flow_style:
        close = text.rindex("}", 0, node.end_mark.index)
        return text[:close] + f", {key}: {value}" + text[close:]
    indent = " " * node.value[0][0].start_mark.column
    at = _end(node)
    return text[:at] + f"\n{indent}{key}: {value}" + text[at:]


def write_fields(
    robot: str | Path, limb: str, fields: Mapping[str, str], out: str | Path | None = None
) -> str:
    """Set ``fields`` of ``limb`` in the robot file, check it, write it atomically; the text."""
    name = str(robot)
    data = read_input(robot, "robot file")
    text = decode_text(data, name, ModelFileError)
    for key, value in fields.items():
        text = set_field(text, name, limb, key, value)
    parse_spring_damper(text, name)
    write_atomically(out or robot, text)
    return text
