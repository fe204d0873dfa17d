"""The documentation site (issue 41): it builds strictly, and what it shows is the code's.

- ``mkdocs build --strict``: every page in the navigation, every link and anchor resolves,
  every snippet the tutorial includes exists, the API pages render from the docstrings.
- The command-line reference is the parser's own help (``tools/cli_reference.py``).
- The tutorial's outputs and pictures are what the current code prints and draws
  (``tools/tutorial.py`` runs every command again).
- Every ``console`` block of the how-to guides and the home page runs, from a scratch copy
  of the repository's specs: each ``$`` line exits 0, or the code its ``# exit N`` says.
  ``python`` blocks with ``>>>`` run as doctests.
"""

from __future__ import annotations

import doctest
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
RUN_PAGES = [DOCS / "index.md", *sorted((DOCS / "how-to").glob("*.md"))]
_BLOCK = re.compile(r"^( *)```console\n(.*?)^\1```", re.M | re.S)


def console_commands(page: Path) -> list[tuple[str, int]]:
    """The ``$`` lines of a page's console blocks, with the exit code each must give."""
    found = []
    for match in _BLOCK.finditer(page.read_text(encoding="utf-8")):
        for line in match.group(2).splitlines():
            line = line.strip()
            if not line.startswith("$ "):
                continue
            command, _, comment = line[2:].partition("  # ")
            expected = re.fullmatch(r"exit (\d+)", comment.strip())
            found.append((command.strip(), int(expected.group(1)) if expected else 0))
    return found


def test_the_site_builds_strictly(tmp_path: Path) -> None:
    pytest.importorskip("mkdocs")
    pytest.importorskip("material")
    done = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-d",
                           str(tmp_path / "site")], cwd=ROOT, capture_output=True, text=True,
                          timeout=300, env=dict(os.environ, NO_MKDOCS_2_WARNING="1"))
    assert done.returncode == 0, done.stderr[-4000:]
    page = (tmp_path / "site" / "tutorial" / "index.html").read_text(encoding="utf-8")
    assert "draft.gait: unrealizable" in page and "--8<--" not in page
    assert (tmp_path / "site" / "tutorial" / "out" / "map.svg").exists()
    assert "gaitc.api.deciding.check" in (tmp_path / "site" / "reference" / "api" /
                                         "index.html").read_text(encoding="utf-8")


def test_the_cli_reference_is_the_parsers_help() -> None:
    done = subprocess.run([sys.executable, str(ROOT / "tools" / "cli_reference.py"),
                           "--check"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr


def test_the_tutorial_outputs_match_the_code() -> None:
    done = subprocess.run([sys.executable, str(ROOT / "tools" / "tutorial.py"), "--check"],
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr + "\nrun: python tools/tutorial.py"


def test_every_page_of_the_navigation_exists_and_every_doc_is_in_it() -> None:
    import yaml

    config = yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8").replace(
        "!!python/name:", ""))
    listed: list[str] = []

    def walk(items: object) -> None:
        if isinstance(items, str):
            listed.append(items)
        elif isinstance(items, list):
            for item in items:
                walk(item)
        elif isinstance(items, dict):
            for value in items.values():
                walk(value)

    walk(config["nav"])
    pages = {str(p.relative_to(DOCS)) for p in DOCS.rglob("*.md")}
    assert set(listed) == pages


@pytest.mark.parametrize("page", RUN_PAGES, ids=lambda p: str(p.relative_to(DOCS)))
def test_the_console_blocks_run(page: Path, tmp_path: Path) -> None:
    commands = console_commands(page)
    if not commands:
        pytest.skip("no console block")
    shutil.copytree(ROOT / "specs", tmp_path / "specs", symlinks=False)
    shutil.copytree(ROOT / "tests" / "data" / "slugs_examples",
                    tmp_path / "tests" / "data" / "slugs_examples")
    env = dict(os.environ, PYTHONPATH=str(ROOT), NO_COLOR="1")
    if any(c.startswith("gaitc ros ") or " --mcap " in c for c, _ in commands):
        from ros_graph import MISSING, ros_environment

        if MISSING is not None:
            pytest.skip(MISSING)
        env.update(ros_environment())  # ROS 2 traffic stays on this machine, in its domain
    for command, expected in commands:
        argv = shlex.split(command)
        assert argv[0] == "gaitc", command
        done = subprocess.run([sys.executable, "-m", "gaitc", *argv[1:]], cwd=tmp_path,
                              capture_output=True, text=True, timeout=600, env=env)
        assert done.returncode == expected, (command, done.stdout[-2000:], done.stderr[-2000:])


@pytest.mark.parametrize("page", [p for p in RUN_PAGES if ">>>" in p.read_text()],
                         ids=lambda p: str(p.relative_to(DOCS)))
def test_the_python_blocks_run(page: Path) -> None:
    old = Path.cwd()
    os.chdir(ROOT)
    try:
        result = doctest.testfile(str(page), module_relative=False,
                                  optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    finally:
        os.chdir(old)
    assert result.attempted > 0 and result.failed == 0


def test_the_tutorials_gait_blocks_are_its_robots_file() -> None:
    """Every ``gait`` block the tutorial shows is a part of the file it runs (the draft or
    the repaired robot), line for line."""
    page = (DOCS / "tutorial" / "index.md").read_text(encoding="utf-8")
    files = ((DOCS / "tutorial" / "lab8.gait").read_text(encoding="utf-8")
             + (DOCS / "tutorial" / "out" / "draft.gait").read_text(encoding="utf-8"))
    known = {" ".join(line.split()) for line in files.splitlines()}
    blocks = re.findall(r"```gait\n(.*?)```", page, re.S)
    assert len(blocks) >= 5
    for block in blocks:
        for line in block.splitlines():
            if line.strip() and not line.startswith("--8<--"):
                assert " ".join(line.split()) in known, line
