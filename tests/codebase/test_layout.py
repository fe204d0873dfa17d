"""The package layout: dependencies flow one way and no module imports itself in a loop.

Every import is read with :mod:`ast`, the ones inside functions too (a deferred import is
still a dependency); only imports under ``if TYPE_CHECKING:`` are left out.
"""

from __future__ import annotations

import ast
from pathlib import Path

from packages import PACKAGES, ROOT, subpackages

# The units of the layering: the packages below ``gaitc`` and the three top-level packages the
# design names. A unit may import the units of earlier layers and its own modules, nothing
# else. ``gaitc`` itself is the lazy facade over ``gaitc.api`` that the command line wraps.
LAYERS: list[tuple[str, ...]] = [
    ("gaitc.diagnostics",),
    ("gaitc.ir",),
    ("gaitc.solver", "gaitc.verifier", "slugs_bridge"),
    ("peers",),
    ("ltlcompiler",),
    ("gaitc.core",),
    ("gaitc.compact",),
    ("gaitc.gaitgraph",),
    ("gaitc.models", "gaitc.sim"),
    ("gaitc.analysis", "gaitc.hw", "gaitc.play"),
    ("gaitc.search", "gaitc.codegen"),
    ("gaitc.forms", "gaitc.ros"),
    ("gaitc.api",),
    ("gaitc",),
    ("gaitc.lsp",),
    ("gaitc.cli",),
    ("gaitc.__main__",),
]
UNITS = [name for layer in LAYERS for name in layer]
LEVEL = {name: level for level, layer in enumerate(LAYERS) for name in layer}


def _unit(module: str) -> str | None:
    """The layering unit a dotted module name belongs to (the longest unit that prefixes it)."""
    best = None
    for unit in UNITS:
        if (module == unit or module.startswith(unit + ".")) and (
                best is None or len(unit) > len(best)):
            best = unit
    return best


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _imports(tree: ast.AST, package: str) -> list[tuple[int, str]]:
    """Every import of a module of ``package`` (relative ones resolved against it)."""
    found: list[tuple[int, str]] = []
    stack: list[ast.AST] = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and _is_type_checking(node):
            stack.extend(node.orelse)
            continue
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join([package, *([base] if base else [])])
            found.append((node.lineno, base))
            # "from pkg import module" names a module too
            found.extend((node.lineno, f"{base}.{alias.name}") for alias in node.names)
        stack.extend(ast.iter_child_nodes(node))
    return found


def _modules() -> dict[str, Path]:
    return {
        _module_name(path): path
        for package in PACKAGES
        for path in (ROOT / package).rglob("*.py")
    }


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    graph: dict[str, set[str]] = {name: set() for name in modules}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        for _, target in _imports(tree, package):
            if target in modules and target != name:
                graph[name].add(target)
    return graph


def test_every_package_has_a_layer() -> None:
    """A package added to the project must be placed in :data:`LAYERS` (no silent drift)."""
    missing = [name for name in subpackages() if _unit(name) is None]
    assert not missing, f"packages without a layer: {missing}"
    assert set(PACKAGES) <= set(UNITS)


def test_packages_import_only_lower_layers() -> None:
    offenders = []
    for name, path in sorted(_modules().items()):
        unit = _unit(name)
        assert unit is not None, name
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for line, target in _imports(tree, package):
            other = _unit(target)
            if other is not None and other != unit and LEVEL[other] >= LEVEL[unit]:
                offenders.append(f"{path.relative_to(ROOT)}:{line}: imports {target}")
    assert not offenders, "\n".join(sorted(set(offenders)))


def test_no_import_loops() -> None:
    graph = _graph()
    loops: list[str] = []
    state: dict[str, int] = {}  # 1 on the stack, 2 done
    for root in sorted(graph):
        if root in state:
            continue
        path: list[str] = [root]
        todo: list[list[str]] = [sorted(graph[root])]
        state[root] = 1
        while todo:
            if not todo[-1]:
                state[path.pop()] = 2
                todo.pop()
                continue
            nxt = todo[-1].pop()
            if state.get(nxt) == 1:
                loops.append(" -> ".join([*path[path.index(nxt):], nxt]))
            elif nxt not in state:
                state[nxt] = 1
                path.append(nxt)
                todo.append(sorted(graph[nxt]))
    assert not loops, "\n".join(loops)


def test_the_slugs_package_never_imports_the_solver() -> None:
    graph = _graph()
    bad = sorted(
        f"{name} imports {target}"
        for name, targets in graph.items() if name.startswith("slugs_bridge")
        for target in targets if target.startswith(("gaitc.solver", "gaitc.verifier"))
    )
    assert not bad, "\n".join(bad)


def test_the_verifier_shares_no_code_with_the_solver() -> None:
    graph = _graph()
    bad = sorted(
        f"{name} imports {target}"
        for name, targets in graph.items() if name.startswith("gaitc.verifier")
        for target in targets if target.startswith("gaitc.solver")
    )
    assert not bad, "\n".join(bad)


def test_the_test_is_not_vacuous() -> None:
    graph = _graph()
    assert "gaitc.ir.formula" in graph["gaitc.ir.spec"]
    assert any(t.startswith("gaitc.ir") for t in graph["gaitc.solver.synthesis"])
    assert _unit("gaitc.solver.game") == "gaitc.solver" and _unit("gaitc") == "gaitc"
