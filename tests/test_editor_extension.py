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

ROOT = Path(__file__).resolve().parent.parent


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


def test_the_grammar_knows_every_keyword_of_the_language() -> None:
    """Each keyword of ltlcompiler/gait.lark is highlighted by some pattern of the grammar."""
    import re

    lark = (ROOT / "ltlcompiler" / "gait.lark").read_text()
    keywords = set(re.findall(r'"([a-z]+)"', lark))
    grammar = (ROOT / "editors" / "vscode" / "syntaxes" / "gait.tmLanguage.json").read_text()
    missing = sorted(k for k in keywords if not re.search(rf"\b{k}\b", grammar))
    assert missing == []
