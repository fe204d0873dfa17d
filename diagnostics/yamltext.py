"""YAML for the project's input files (robots, scenarios): safe loading, positioned errors.

Every YAML reader goes through :func:`compose`: PyYAML's safe loader only, any YAML
problem (bad syntax, a NUL or other character YAML forbids, nesting deeper than
:data:`MAX_DEPTH`) becomes the caller's error class with the file, line and column.
"""

from __future__ import annotations

import yaml

from diagnostics import GaitcError, Span

MAX_DEPTH = 200  # nested lists and mappings; the robot and scenario formats need five


def compose(text: str, file: str, error: type[GaitcError], what: str) -> yaml.Node | None:
    """The YAML node tree of ``text`` (None for an empty document)."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        span = Span(file, mark.line + 1, mark.column + 1) if mark else Span(file, 1, 1)
        raise error(f"{what} is not valid YAML: {err.problem}", span) from None
    except yaml.reader.ReaderError as err:
        line, column = _position(text, err.position)
        raise error(f"{what} contains the character {err.character!r}, which YAML does not "
                    "allow", Span(file, line, column)) from None
    except yaml.YAMLError as err:
        raise error(f"{what} is not valid YAML: {err}", Span(file, 1, 1)) from None
    except RecursionError:
        raise error(f"{what} nests too deeply (the limit is {MAX_DEPTH} levels)",
                    Span(file, 1, 1)) from None
    if root is not None:
        _check_depth(root, file, error, what)
    return root


def _position(text: str, offset: int) -> tuple[int, int]:
    before = text[:offset]
    return before.count("\n") + 1, offset - (before.rfind("\n") + 1) + 1


def _check_depth(root: yaml.Node, file: str, error: type[GaitcError], what: str) -> None:
    stack: list[tuple[yaml.Node, int]] = [(root, 1)]
    while stack:
        node, depth = stack.pop()
        if depth > MAX_DEPTH:
            mark = node.start_mark
            raise error(f"{what} nests deeper than {MAX_DEPTH} levels",
                        Span(file, mark.line + 1, mark.column + 1))
        if isinstance(node, yaml.SequenceNode):
            stack.extend((child, depth + 1) for child in node.value)
        elif isinstance(node, yaml.MappingNode):
            stack.extend((child, depth + 1) for pair in node.value for child in pair)
