"""The VS Code extension (issue 40): it builds to a .vsix, and its grammar highlights specs.

``scripts/build-vscode.sh`` installs the extension's npm packages from its lock file,
type-checks and bundles it, runs vscode-tmgrammar-test on the annotated specs in
``editors/vscode/test`` (every scope each token must get), and packages it. The package is
then opened here: it must hold the bundled client, the grammar and a manifest that starts
``gaitc lsp`` for ``.gait`` files.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(shutil.which("npm") is None, reason="npm is not installed")
def test_the_extension_builds_to_a_vsix_and_its_grammar_passes() -> None:
    done = subprocess.run([str(ROOT / "scripts" / "build-vscode.sh")], capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "test/robot.gait run successfuly" in done.stderr
    assert "test/formulas.gait run successfuly" in done.stderr
    vsix = Path(done.stdout.strip().splitlines()[-1])
    with zipfile.ZipFile(vsix) as package:
        names = set(package.namelist())
        manifest = json.loads(package.read("extension/package.json"))
    assert {"extension/out/extension.js", "extension/syntaxes/gait.tmLanguage.json"} <= names
    assert manifest["contributes"]["languages"][0]["extensions"] == [".gait"]
    default = manifest["contributes"]["configuration"]["properties"]["gaitc.server.command"]
    assert default["default"] == ["gaitc", "lsp"]


def _highlighted_words() -> dict[str, set[str]]:
    """The words each pattern of the editor grammar highlights by name: the words of its
    groups made of letters only (``\\b(robot|legs|...)\\b``, ``(correction)``), by the
    scope that colours them."""
    import re

    grammar = json.loads((ROOT / "editors" / "vscode" / "syntaxes" / "gait.tmLanguage.json")
                         .read_text())
    found: dict[str, set[str]] = {}
    stack: list[object] = [grammar]
    while stack:
        item = stack.pop()
        if isinstance(item, dict):
            match = item.get("match")
            if isinstance(match, str):
                scope = str(item.get("name") or sorted(
                    str(c.get("name")) for c in item.get("captures", {}).values()))
                for group in re.findall(r"\((?:\?:)?([a-z]+(?:\|[a-z]+)*)\)", match):
                    found.setdefault(scope, set()).update(group.split("|"))
            stack.extend(item.values())
        elif isinstance(item, list):
            stack.extend(item)
    return found


def test_the_grammar_highlights_exactly_the_keywords_of_the_language() -> None:
    """Each keyword of ltlcompiler/gait.lark (read from the analysed grammar, as the
    language server's completion reads it) is highlighted by some pattern of the editor
    grammar, and every word a pattern highlights by name is a keyword of gait.lark."""
    from ltlcompiler.parser import keywords

    highlighted = _highlighted_words()
    words = set().union(*highlighted.values())
    assert sorted(set(keywords()) - words) == [], "keywords the editor does not highlight"
    assert sorted(words - set(keywords())) == [], "highlighted words that are no keyword"
    assert all(scope.startswith(("keyword.", "storage.", "support.", "constant.language", "["))
               for scope in highlighted), sorted(highlighted)
