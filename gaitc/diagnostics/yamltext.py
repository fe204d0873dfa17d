"""YAML for the project's input files (robots, scenarios): safe loading, positioned errors.

Every YAML reader goes through :func:`compose`: PyYAML's safe loader only, any YAML
problem (bad syntax, a NUL or other character YAML forbids, nesting deeper than
:data:`MAX_DEPTH`) becomes the caller's error class with the file, line and column.
PyYAML also ends lines at \r, \x85 and U+2028/9; every position it reports (and every
node's marks) is recounted from its character offset by the rule of ``source_lines`` (a text
without those characters has PyYAML's positions already).

libyaml (PyYAML's C composer) is about five times faster, but it is a different parser: on
10,000 printable-ASCII mutants of the project's YAML seeds it accepted 7 texts that PyYAML
refuses (a tab inside a flow mapping, among others), refused 10 that PyYAML accepts, and
made 23 other trees differ (empty values one column apart, tags read differently).  The
Python composer is kept, linear at about 4-5 s per MB (bench/bench_readers.py).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import yaml

from gaitc.diagnostics import GaitcError, LineTable, Span, span_at
from gaitc.diagnostics.files import decode_text, read_input

MAX_DEPTH = 200  # nested lists and mappings; the robot and scenario formats need five
MAX_NODES = 200_000  # values that aliases add to the document (each use of an alias expands
# its anchor's values again): a few lines can otherwise stand for billions of values


#: The line breaks of PyYAML that ``source_lines`` does not count.
_OTHER_BREAKS = re.compile("[\r\x85\u2028\u2029]")


def compose(text: str, file: str, error: type[GaitcError], what: str) -> yaml.Node | None:
    """The YAML node tree of ``text`` (None for an empty document)."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        span = span_at(text, file, mark.index) if mark else Span(file, 1, 1)
        raise error(f"{what} is not valid YAML: {err.problem}", span) from None
    except yaml.reader.ReaderError as err:
        raise error(f"{what} contains the character {err.character!r}, which YAML does not "
                    "allow", span_at(text, file, err.position)) from None
    except yaml.YAMLError as err:
        raise error(f"{what} is not valid YAML: {err}", Span(file, 1, 1)) from None
    except RecursionError:
        raise error(f"{what} nests too deeply (the limit is {MAX_DEPTH} levels)",
                    Span(file, 1, 1)) from None
    if root is not None:
        _check_depth(root, text, file, error, what)
    return root


def _recount(mark: yaml.Mark, lines: LineTable) -> yaml.Mark:
    span = lines.span(mark.index)
    return yaml.Mark(mark.name, mark.index, span.line - 1, span.column - 1, "", 0)


def _check_depth(root: yaml.Node, text: str, file: str, error: type[GaitcError],
                 what: str) -> None:
    """Bound the nesting, and recount every node's marks (see the module docstring)."""
    stack: list[tuple[yaml.Node, int]] = [(root, 1)]
    lines = LineTable(text, file) if _OTHER_BREAKS.search(text) else None
    seen: set[int] = set()
    expanded = 0
    while stack:
        node, depth = stack.pop()
        if id(node) in seen:  # an alias shares its anchor's node: a value again
            expanded += 1
            if expanded > MAX_NODES:  # aliases can make a small file a huge tree
                raise error(f"{what} has more than {MAX_NODES} values once its aliases are "
                            "expanded", Span(file, 1, 1))
        else:  # recount each node once
            seen.add(id(node))
            if lines is not None:
                node.start_mark = _recount(node.start_mark, lines)
                node.end_mark = _recount(node.end_mark, lines)
        if depth > MAX_DEPTH:
            mark = node.start_mark
            raise error(f"{what} nests deeper than {MAX_DEPTH} levels",
                        Span(file, mark.line + 1, mark.column + 1))
        if isinstance(node, yaml.SequenceNode):
            stack.extend((child, depth + 1) for child in node.value)
        elif isinstance(node, yaml.MappingNode):
            stack.extend((child, depth + 1) for pair in node.value for child in pair)


def node_span(file: str, node: yaml.Node) -> Span:
    """Where a node of a :func:`compose` tree starts (its marks are recounted)."""
    return Span(file, node.start_mark.line + 1, node.start_mark.column + 1)


def mapping_of(node: yaml.Node | None) -> dict[str, tuple[yaml.Node, yaml.Node]] | None:
    """A mapping node's entries by key text, each with its key and value node (the first of
    a repeated key wins); None for any other node."""
    if not isinstance(node, yaml.MappingNode):
        return None
    out: dict[str, tuple[yaml.Node, yaml.Node]] = {}
    for key, value in node.value:
        out.setdefault(str(key.value), (key, value))
    return out


def finite_number(node: yaml.Node) -> float | None:
    """A plain scalar that is a finite number (not a Boolean, NaN or infinite); else None."""
    if not isinstance(node, yaml.ScalarNode) or node.style is not None:
        return None
    try:
        value = float(node.value)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def keyed_section(path: str | Path, error: type[GaitcError], what: str, key: str,
                  expected: str) -> tuple[str, dict[str, tuple[yaml.Node, yaml.Node]]]:
    """Read the YAML file ``path`` (``what``, as messages name it) and return its name and
    the mapping under its top-level ``key``; anything else is ``error(expected)`` where the
    file went wrong (the value of ``key``, else the document)."""
    name = str(path)
    text = decode_text(read_input(path, what), name, error)
    root = compose(text, name, error, f"the {what}")
    table = mapping_of(root)
    entry = None if table is None else table.get(key)
    section = mapping_of(None if entry is None else entry[1])
    if section is None:
        at = entry[1] if entry is not None else root
        raise error(expected, node_span(name, at) if at is not None else Span(name, 1, 1))
    return name, section
