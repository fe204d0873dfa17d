"""tests/slow_tests.txt, the functions the quick run leaves out, names real tests.

tools/slow_tests.py writes the list from measured times, and tests/conftest.py marks every
case of each function in it ``slow``; a name that no longer matches a test (a renamed or
removed function) would silently put that test back in the quick run, or name nothing.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

from packages import ROOT
from slow_marks import SLOW_LIST
from slow_marks import listed_slow as listed

sys.path.insert(0, str(ROOT / "tools"))

from slow_tests import HEADER, function_of, slow_functions


def _defined(path: Path) -> set[str]:
    """``function`` and ``Class::function`` for every test function of a module."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = set()
    for node in tree.body:
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            names.add(node.name)
        elif isinstance(node, ast.ClassDef):
            names.update(f"{node.name}::{item.name}" for item in node.body
                         if isinstance(item, ast.FunctionDef | ast.AsyncFunctionDef))
    return names


def test_every_listed_function_is_a_test_of_the_suite() -> None:
    names = listed()
    assert names, "tests/slow_tests.txt lists nothing"
    missing = []
    for name in sorted(names):
        module, _, function = name.partition("::")
        path = ROOT / module
        if not path.is_file() or not function.startswith(("test_", "Test")) \
                or function not in _defined(path):
            missing.append(name)
    assert not missing, ("tests/slow_tests.txt names tests that do not exist (renamed or "
                         "removed: mend the line, or run tools/slow_tests.py again):\n"
                         + "\n".join(missing))


def test_the_list_is_sorted_once_each_under_its_header() -> None:
    lines = SLOW_LIST.read_text(encoding="utf-8").splitlines()
    body = [line for line in lines if line and not line.startswith("#")]
    assert body == sorted(set(body))
    assert lines[0] == HEADER.splitlines()[0]


def test_the_tool_chooses_by_the_slowest_case_and_by_the_total() -> None:
    report = "\n".join([
        "2.50s call     tests/a/test_x.py::test_one[first]",
        "0.10s call     tests/a/test_x.py::test_one[second]",
        "0.90s call     tests/a/test_x.py::test_two",
        "9.00s setup    tests/a/test_x.py::test_two",
        *(f"0.50s call     tests/a/test_y.py::TestMany::test_case[{k}]" for k in range(17)),
        "0.20s call     tests/a/test_y.py::test_cheap[1]",
    ])
    assert slow_functions(report, 1.0) == ["tests/a/test_x.py::test_one",
                                           "tests/a/test_y.py::TestMany::test_case"]
    assert function_of("tests/a/test_x.py::test_one[a-b[c]]") == "tests/a/test_x.py::test_one"
