"""The command line goes through the facade, and the facade lists its public names once.

- Every import in :mod:`gaitc.cli` (read with :mod:`ast`: the ones inside functions and
  under ``if TYPE_CHECKING:`` too) names ``gaitc``, ``gaitc.api``, ``gaitc.cli``,
  ``gaitc.diagnostics`` or one of the two front ends, ``gaitc.play.terminal`` and
  ``gaitc.lsp.server``: a command parses its arguments, makes one public call and prints.
- ``gaitc._MODULES`` is the one list of the public names: ``__all__`` is derived from it, and
  the ``TYPE_CHECKING`` block of ``gaitc/__init__.py`` (which a type checker needs spelt
  out) imports exactly those names from exactly those modules, each ``as`` itself.  Every
  public name loads and is documented in docs/api.md or docs/reference/api.md.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import gaitc

ROOT = Path(__file__).resolve().parents[2]
CLI = ROOT / "gaitc" / "cli"
#: What the command line may import of the project: the facade, its own modules, the
#: errors, and the two front ends it starts.
ALLOWED_PACKAGES = ("gaitc.api", "gaitc.cli", "gaitc.diagnostics")
ALLOWED_MODULES = ("gaitc", "gaitc.play.terminal", "gaitc.lsp.server")
PROJECT = ("gaitc", "ltlcompiler", "slugs_bridge")


def _allowed(module: str) -> bool:
    return module in ALLOWED_MODULES or any(
        module == package or module.startswith(package + ".") for package in ALLOWED_PACKAGES)


def _project_imports(text: str, package: str) -> list[tuple[int, str]]:
    """Every import of a project module in ``text`` (a module of ``package``), wherever it
    stands: inside functions and under ``TYPE_CHECKING`` too; relative imports resolved."""
    found = []
    for node in ast.walk(ast.parse(text)):
        names: list[str] = []
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                parts = parts[:len(parts) - node.level + 1]
                base = ".".join([*parts, *([base] if base else [])])
            names = [base]
        found += [(node.lineno, name) for name in names if name.split(".")[0] in PROJECT]
    return found


def _package(path: Path) -> str:
    return ".".join(path.relative_to(ROOT).with_suffix("").parts[:-1])


def test_the_command_line_imports_only_the_facade_and_the_front_ends() -> None:
    offenders = [f"{path.relative_to(ROOT)}:{line}: imports {module}"
                 for path in sorted(CLI.rglob("*.py"))
                 for line, module in _project_imports(path.read_text(encoding="utf-8"),
                                                      _package(path))
                 if not _allowed(module)]
    assert not offenders, "\n".join(offenders)


def test_the_rule_sees_deferred_typing_and_relative_imports() -> None:
    text = ("from typing import TYPE_CHECKING\n"
            "if TYPE_CHECKING:\n    from gaitc.sim.run import Run\n"
            "def run() -> None:\n    from ltlcompiler.encoding import ENCODINGS\n"
            "    from ..reporting import document\n    from ...sim import session\n"
            "    import gaitc\n    import gaitc.solver.game\n")
    found = [module for _, module in _project_imports(text, "gaitc.cli.commands")]
    assert sorted(m for m in found if not _allowed(m)) == [
        "gaitc.sim", "gaitc.sim.run", "gaitc.solver.game", "ltlcompiler.encoding"]
    assert "gaitc.cli.reporting" in found  # .. is gaitc.cli


# ---------------------------------------------------------------- the public names
def _init_tree() -> ast.Module:
    return ast.parse((ROOT / "gaitc" / "__init__.py").read_text(encoding="utf-8"))


def _typed_names() -> dict[str, str]:
    """The names the ``TYPE_CHECKING`` block of ``gaitc/__init__.py`` imports, and from where
    (an import that does not re-export its name, ``as`` itself, is recorded as ``None``)."""
    typed: dict[str, str] = {}
    for node in _init_tree().body:
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and (
                node.test.id == "TYPE_CHECKING"):
            for statement in node.body:
                assert isinstance(statement, ast.ImportFrom), ast.dump(statement)
                for alias in statement.names:
                    exported = alias.asname == alias.name
                    typed[alias.name] = statement.module if exported else "not re-exported"
    return typed


def test_all_is_derived_from_the_one_list() -> None:
    assert gaitc.__all__ == sorted(gaitc._HOMES)
    assert len(gaitc._HOMES) == sum(len(names) for names in gaitc._MODULES.values())
    assigned = [node for node in _init_tree().body if isinstance(node, ast.Assign)
                and any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets)]
    assert len(assigned) == 1 and not isinstance(assigned[0].value, ast.List), (
        "__all__ is derived from _MODULES, not listed again")


def test_every_public_name_is_typed_from_its_home() -> None:
    """The type checker sees each public name, from the module the lazy map loads it from;
    a name missing here would be ``Any`` to mypy (the module ``__getattr__``)."""
    typed = _typed_names()
    expected = {name: home for name, home in gaitc._HOMES.items()}
    missing = sorted(set(expected) - set(typed))
    extra = sorted(set(typed) - set(expected))
    moved = sorted(name for name in set(expected) & set(typed) if typed[name] != expected[name])
    block = "\n".join(f"    from {home} import {name} as {name}"
                      for name, home in sorted(expected.items(), key=lambda kv: kv[::-1]))
    assert not (missing or extra or moved), (
        f"missing {missing}, extra {extra}, from elsewhere {moved}; the block should read\n"
        f"{block}")


def test_every_public_name_loads() -> None:
    for name in gaitc.__all__:
        assert getattr(gaitc, name) is not None, name
        assert name in dir(gaitc)


def test_every_public_name_is_documented() -> None:
    """Named in code in the guide (docs/api.md) or the reference (docs/reference/api.md):
    ``gaitc.NAME``, a code span starting with ``NAME``, or a ``::: module.NAME`` entry."""
    text = "\n".join((ROOT / "docs" / name).read_text(encoding="utf-8")
                     for name in ("api.md", "reference/api.md"))
    undocumented = [name for name in gaitc.__all__
                    if not re.search(rf"gaitc\.{name}\b|`{name}\b|^::: [\w.]+\.{name}$", text,
                                     re.MULTILINE)]
    assert not undocumented, f"public names the API docs do not mention: {undocumented}"
