"""Test modules have unique file names: the test folders are not packages, so pytest
imports each module by its base name, and a second ``test_cli.py`` in another folder is an
'import file mismatch' that stops the whole run (tests/chances/test_cli.py beside
tests/cli/test_cli.py did)."""

from __future__ import annotations

from collections import defaultdict

from packages import ROOT


def test_every_test_module_has_a_name_of_its_own() -> None:
    by_name: dict[str, list[str]] = defaultdict(list)
    for path in sorted((ROOT / "tests").rglob("*.py")):
        if path.name != "conftest.py" and "__pycache__" not in path.parts:
            by_name[path.name].append(str(path.relative_to(ROOT)))
    twice = {name: paths for name, paths in by_name.items() if len(paths) > 1}
    assert not twice, twice
