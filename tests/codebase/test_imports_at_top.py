"""Imports go at the top of modules below the facade (issue 61).

Start-up laziness belongs in the command line's table of commands and the facade's lazy
names (the units from ``gaitc`` up in :data:`test_layout.LAYERS`).  Below them an import
inside a function is an exception, and says why on its line or in the comment just above
it (a run of imports shares one): ``# lazy: <reason>`` (an optional extra that may be
missing, the start-up of ``gaitc check`` or ``lint``, code that runs before a solver
forks).  Imports under ``if TYPE_CHECKING:`` only name types and are not counted.
"""

from __future__ import annotations

import ast
from pathlib import Path

from packages import PACKAGES, ROOT
from test_layout import LEVEL, _is_type_checking, _module_name, _unit

#: The imports inside functions below the facade when issue 61 moved the rest to the top
#: (364 in all before, 58 after), and 20 of the ros and chances extras (rclpy and its
#: messages, mcap, stormpy, matplotlib) that came with gaitc ros and gaitc chances, each
#: marked; 81 in all.  Deciding split from synthesis (gaitc.forms.decision,
#: gaitc.api.deciding, the check command's own module) brought 30 of the imports that
#: waited only to keep ``gaitc check``'s start-up light to the top, leaving the two that
#: only ``--solver slugs`` needs (bit-blasting and the slugsin writer) and the drawing of a
#: synthesis (pydot): 54.  The count may fall, never rise.
MAX_LAZY = 54
MARK = "# lazy:"


def _below_the_facade(path: Path) -> bool:
    unit = _unit(_module_name(path))
    return unit is not None and LEVEL[unit] < LEVEL["gaitc"]


def _function_imports(tree: ast.Module) -> list[tuple[ast.Import | ast.ImportFrom, list[ast.stmt]]]:
    """Every import inside a function (not under ``if TYPE_CHECKING:``), with the list of
    statements it stands in."""
    found: list[tuple[ast.Import | ast.ImportFrom, list[ast.stmt]]] = []

    def visit(node: ast.AST, in_function: bool) -> None:
        for _, value in ast.iter_fields(node):
            children = value if isinstance(value, list) else [value]
            for child in children:
                if not isinstance(child, ast.AST):
                    continue
                if isinstance(child, ast.If) and _is_type_checking(child):
                    continue
                if in_function and isinstance(child, ast.Import | ast.ImportFrom):
                    assert isinstance(value, list)
                    found.append((child, value))
                visit(child, in_function or isinstance(
                    child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda))

    visit(tree, False)
    return found


def _marked(lines: list[str], node: ast.stmt, siblings: list[ast.stmt]) -> bool:
    """Whether ``node`` says why it is lazy: on its own lines, in the comment lines just
    above it, or as the next of a run of imports whose first says so."""
    assert node.end_lineno is not None
    if any(MARK in line for line in lines[node.lineno - 1:node.end_lineno]):
        return True
    index = siblings.index(node)
    before = siblings[index - 1] if index else None
    if (isinstance(before, ast.Import | ast.ImportFrom) and before.end_lineno is not None
            and before.end_lineno == node.lineno - 1):
        return _marked(lines, before, siblings)
    row = node.lineno - 2
    while row >= 0 and lines[row].strip().startswith("#"):
        if MARK in lines[row]:
            return True
        row -= 1
    return False


def _lazy_imports() -> tuple[list[str], list[str]]:
    """(every import inside a function below the facade, those that do not say why)."""
    every, unmarked = [], []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            if not _below_the_facade(path):
                continue
            text = path.read_text(encoding="utf-8")
            lines = text.splitlines()
            for node, siblings in _function_imports(ast.parse(text)):
                where = f"{path.relative_to(ROOT)}:{node.lineno}: {lines[node.lineno - 1].strip()}"
                every.append(where)
                if not _marked(lines, node, siblings):
                    unmarked.append(where)
    return every, unmarked


def test_imports_inside_functions_below_the_facade_say_why() -> None:
    _, unmarked = _lazy_imports()
    assert not unmarked, (
        "move these imports to the top of their modules, or say on the line why one must "
        "wait ('# lazy: <reason>'):\n" + "\n".join(unmarked))


def test_imports_inside_functions_do_not_grow() -> None:
    every, _ = _lazy_imports()
    assert len(every) <= MAX_LAZY, (
        f"{len(every)} imports inside functions below the facade, at most {MAX_LAZY}:\n"
        + "\n".join(every))


def test_the_scan_sees_a_lazy_import() -> None:
    """Not vacuous: the format readers of gaitc.core.spec wait for their files."""
    every, _ = _lazy_imports()
    assert any(w.startswith("gaitc/core/spec.py:") and "parse_slugsin" in w for w in every)
    assert not _below_the_facade(ROOT / "gaitc" / "cli" / "__init__.py")
    assert _below_the_facade(ROOT / "gaitc" / "api" / "solving.py")
