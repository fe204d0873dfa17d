"""The package layout: dependencies flow one way and no module imports itself in a loop.

Every import is read with :mod:`ast`, the ones inside functions too (a deferred import is
still a dependency); only imports under ``if TYPE_CHECKING:`` are left out.
"""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# Each package may import the packages of earlier layers and its own modules, nothing else.
LAYERS: list[tuple[str, ...]] = [
    ("diagnostics",),
    ("gr1",),
    ("solver", "verifier", "slugs_bridge"),
    ("ltlcompiler",),
    ("gaitgraph",),
    ("gaitsim",),
    ("analysis", "gaithw"),
    ("gaitsearch",),
    ("gaitc",),
]
PACKAGES = [name for layer in LAYERS for name in layer]
LEVEL = {name: level for level, layer in enumerate(LAYERS) for name in layer}


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


def _graph() -> dict[str, set[str]]:
    modules = {
        _module_name(path): path
        for package in PACKAGES
        for path in (ROOT / package).rglob("*.py")
    }
    graph: dict[str, set[str]] = {name: set() for name in modules}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for _, target in _imports(tree, name.split(".")[0]):
            if target in modules and target != name:
                graph[name].add(target)
    return graph


def test_packages_import_only_lower_layers() -> None:
    offenders = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            tree = ast.parse(path.read_text(encoding="utf-8"))
            for line, target in _imports(tree, package):
                top = target.split(".")[0]
                if top in LEVEL and top != package and LEVEL[top] >= LEVEL[package]:
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
        for target in targets if target.split(".")[0] in ("solver", "verifier")
    )
    assert not bad, "\n".join(bad)


def test_the_verifier_shares_no_code_with_the_solver() -> None:
    graph = _graph()
    bad = sorted(
        f"{name} imports {target}"
        for name, targets in graph.items() if name.startswith("verifier")
        for target in targets if target.startswith("solver")
    )
    assert not bad, "\n".join(bad)


def test_the_test_is_not_vacuous() -> None:
    graph = _graph()
    assert "gr1.formula" in graph["gr1.spec"]
    assert any(t.startswith("gr1") for t in graph["solver.synthesis"])
