"""The code base stays ruff- and mypy-clean (the style guide's rule 6)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from packages import PACKAGES, ROOT


def _tool(name: str) -> list[str]:
    local = Path(sys.executable).parent / name
    if local.exists():
        return [str(local)]
    found = shutil.which(name)
    if found is None:
        pytest.skip(f"{name} is not installed")
    return [found]


def test_ruff_clean() -> None:
    result = subprocess.run(
        [*_tool("ruff"), "check", *PACKAGES, "tests", "bench", "tools"],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_mypy_clean() -> None:
    result = subprocess.run(
        [*_tool("mypy"), *[p for p in PACKAGES if (ROOT / p).is_dir()]],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_every_module_has_a_docstring() -> None:
    """Every module says its role (modules are sized by concept, so no line cap)."""
    problems = []
    for package in [*PACKAGES, "tests", "bench", "tools"]:
        for path in sorted((ROOT / package).rglob("*.py")):
            text = path.read_text(encoding="utf-8")
            body = text.split("\n", 1)[1] if text.startswith("#!") else text
            if not body.lstrip().startswith(('"""', "'''")):
                problems.append(f"{path.relative_to(ROOT)}: no module docstring")
    assert not problems, "\n".join(problems)


LARK_MODULES = ("ltlcompiler/parser.py", "ltlcompiler/parse_tree.py")


def test_the_package_list_is_complete() -> None:
    """Every Python package folder of the repository is one of the listed packages or below
    one (so none escapes these checks), and the list names exactly the four roots."""
    assert PACKAGES == ["gaitc", "ltlcompiler", "slugs_bridge", "peers"]
    outside = sorted(
        init.parent.name for init in ROOT.glob("*/__init__.py")
        if init.parent.name not in PACKAGES
    )
    assert outside == [], outside


def test_lark_stays_in_the_parser() -> None:
    offenders = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            if path.relative_to(ROOT).as_posix() in LARK_MODULES:
                continue
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if line.strip().startswith(("import lark", "from lark")):
                    offenders.append(f"{path.relative_to(ROOT)}:{number}")
    assert not offenders, "\n".join(offenders)


def test_no_eval_or_exec_anywhere() -> None:
    """Issue 9: no ``eval``, ``exec`` or ``compile`` of source text in the code base."""
    import ast

    found = []
    for package in [*PACKAGES, "bench", "tools"]:
        for path in sorted((ROOT / package).rglob("*.py")):
            tree = ast.parse(path.read_text(encoding="utf-8"))
            for node in ast.walk(tree):
                if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                        and node.func.id in ("eval", "exec", "compile")):
                    found.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.func.id}")
    assert found == []


#: The dispatches over formula nodes (issue 33): each is a ``match`` ending in
#: ``unreachable``, so that mypy reports a node kind one of them forgets.
DISPATCHES = ("gaitc/ir/evaluation.py", "gaitc/ir/bitblast.py", "gaitc/sim/monitor.py",
              "gaitc/solver/symbolic.py", "gaitc/verifier/logic.py", "ltlcompiler/lowering.py",
              "slugs_bridge/prefixform.py", "slugs_bridge/infixtext.py")


def test_formula_dispatches_are_checked_matches() -> None:
    for name in DISPATCHES:
        text = (ROOT / name).read_text(encoding="utf-8")
        assert "match " in text and "unreachable(" in text, name


def test_mypy_reports_a_forgotten_node_kind(tmp_path: Path) -> None:
    probe = tmp_path / "probe.py"
    probe.write_text(
        '"""A dispatch that forgets Add."""\n'
        "from gaitc.ir.formula import IntConst, IntVar, Node, term_kind, unreachable\n\n\n"
        "def width(node: Node) -> int:\n"
        "    kind = term_kind(node)\n"
        "    match kind:\n"
        "        case IntConst():\n"
        "            return 0\n"
        "        case IntVar():\n"
        "            return 1\n"
        "        case _:\n"
        "            unreachable(kind)\n", encoding="utf-8")
    result = subprocess.run([*_tool("mypy"), "--strict", str(probe)], cwd=ROOT,
                            capture_output=True, text=True, check=False)
    assert result.returncode == 1, result.stdout
    assert 'incompatible type "Add"; expected "Never"' in result.stdout


def test_no_long_positional_lists() -> None:
    """Issue 33: a call passes at most 7 arguments by position and a function takes at most
    7 positional parameters; longer lists are keywords or option dataclasses."""
    import ast

    found = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                where = f"{path.relative_to(ROOT)}:{getattr(node, 'lineno', 0)}"
                if isinstance(node, ast.Call) and len(node.args) >= 8:
                    found.append(f"{where}: a call with {len(node.args)} positional arguments")
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    positional = [a.arg for a in node.args.posonlyargs + node.args.args
                                  if a.arg not in ("self", "cls")]
                    if len(positional) >= 8:
                        found.append(f"{where}: {node.name} takes {len(positional)} "
                                     "positional parameters")
    assert found == [], "\n".join(found)
