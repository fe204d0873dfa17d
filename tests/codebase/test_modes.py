"""Modes are types: no module picks a mode by comparing a string with a mode's name.

Every choice a command makes is an enumeration (:mod:`gaitc.core.modes` and the few that
live where the lower layers need them); a comparison such as ``semantics == "robotics"``
works, since a member equals its value, but it hides the mode from mypy and from a rename.
This test reads every module with :mod:`ast` and lists the ``==``/``!=`` comparisons and
``in`` tests of a name against a mode's value written as a string.  Parsers and serialisers
(that turn text into members and back) may do so; elsewhere there is none
(:data:`BUDGET`).
"""

from __future__ import annotations

import ast
from pathlib import Path

from packages import ROOT

from gaitc.api.compiling import OutputFormat
from gaitc.codegen.build import Target
from gaitc.core.modes import (
    ControllerKind,
    EncodingName,
    EnvironmentKind,
    Form,
    Role,
    SearchMethod,
    Semantics,
)
from gaitc.solver.synthesis import Extraction

MODES = (ControllerKind, EncodingName, EnvironmentKind, Form, Role, SearchMethod, Semantics,
         Extraction, Target, OutputFormat)
#: Values that are also ordinary words of the data (a field named "region", a target "c"),
#: which a comparison may mean as data rather than as a mode.
AMBIGUOUS = {"c", "robot", "environment", "region", "gait", "leg"}
VALUES = {str(m.value) for mode in MODES for m in mode} - AMBIGUOUS
#: Modules whose job is to turn text into modes and back.
PARSERS = ("gaitc/diagnostics/choices.py", "gaitc/ir/controller.py", "gaitc/ir/bddfile.py",
           "gaitc/compact/controller.py", "gaitc/core/spec.py", "gaitc/api/compiling.py",
           "slugs_bridge/names.py")
#: The mode-picking string comparisons allowed outside parsers and serialisers.
BUDGET = 0


def _is_mode_text(node: ast.AST) -> bool:
    if isinstance(node, ast.Constant):
        return isinstance(node.value, str) and node.value in VALUES
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return bool(node.elts) and all(_is_mode_text(e) for e in node.elts)
    return False


def mode_comparisons() -> list[str]:
    found = []
    for package in ("gaitc", "ltlcompiler", "slugs_bridge"):
        for path in sorted((ROOT / package).rglob("*.py")):
            name = str(path.relative_to(ROOT))
            if name in PARSERS:
                continue
            tree = ast.parse(path.read_text(encoding="utf-8"))
            for node in ast.walk(tree):
                if not isinstance(node, ast.Compare) or len(node.ops) != 1:
                    continue
                op, right = node.ops[0], node.comparators[0]
                equal = isinstance(op, (ast.Eq, ast.NotEq)) and (
                    _is_mode_text(node.left) or _is_mode_text(right))
                member = isinstance(op, (ast.In, ast.NotIn)) and _is_mode_text(right)
                if equal or member:
                    found.append(f"{name}:{node.lineno}")
    return found


def test_modes_are_compared_as_members() -> None:
    found = mode_comparisons()
    assert len(found) <= BUDGET, (
        f"{len(found)} mode-picking string comparisons (budget {BUDGET}); compare enum "
        "members instead:\n" + "\n".join(found))


def test_the_scan_sees_a_string_comparison(tmp_path: Path) -> None:
    tree = ast.parse('if semantics == "robotics":\n    pass\nif form in ("explicit", '
                     '"symbolic"):\n    pass\n')
    compares = [n for n in ast.walk(tree) if isinstance(n, ast.Compare)]
    assert len(compares) == 2
    assert _is_mode_text(compares[0].comparators[0])
    assert _is_mode_text(compares[1].comparators[0])
