"""Cross-check of the embedded solver against SLUGS's recorded verdicts (100% agreement).

Every spec of tests/data/gr1_corpus (both formats) and tests/data/slugs_examples, under both
initial-state semantics.  The fixpoint does not depend on the semantics, so each spec is
solved once and both initial conditions are read off its winning region.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gaitc.core.spec import load
from gaitc.solver.game import Game
from gaitc.solver.symbolic import SymbolicSpec

DATA = Path(__file__).parents[1] / "data"
CORPUS = DATA / "gr1_corpus"
EXAMPLES = DATA / "slugs_examples"


def _corpus_cases() -> list[tuple[Path, str, str]]:
    cases = []
    for record in json.loads((CORPUS / "verdicts.json").read_text(encoding="utf-8")):
        for suffix in (".slugsin", ".structuredslugs"):
            cases.append(
                (CORPUS / (record["name"] + suffix), record["default"], record["robotics"])
            )
    return cases


def _example_cases() -> list[tuple[Path, str, str]]:
    cases = []
    for line in (EXAMPLES / "verdicts.tsv").read_text(encoding="utf-8").splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        name, default, robotics = line.split("\t")[:3]
        cases.append((EXAMPLES / name, default, robotics))
    return cases


def _structured_reader_available() -> bool:
    try:
        import slugs_bridge.formats  # noqa: F401
    except ModuleNotFoundError:
        return False
    return True


def verdicts(path: Path) -> tuple[str, str]:
    if path.suffix != ".slugsin" and path.suffix != ".txt" and not _structured_reader_available():
        pytest.skip("the .structuredslugs reader (slugs_bridge.formats) is not available")
    sym = SymbolicSpec(load(str(path)).gr1)
    game = Game(sym)
    winning = game.solve().winning
    return tuple(  # type: ignore[return-value]
        "realizable" if game.initially_winning(winning, s) else "unrealizable"
        for s in ("default", "robotics")
    )


def test_the_recorded_data_is_complete() -> None:
    assert len(_corpus_cases()) == 300
    assert len(_example_cases()) >= 26
    kinds = {(d, r) for _, d, r in _corpus_cases()}
    assert ("realizable", "realizable") in kinds and ("unrealizable", "unrealizable") in kinds


@pytest.mark.parametrize(
    ("path", "default", "robotics"), _corpus_cases(), ids=lambda x: getattr(x, "name", "")
)
def test_corpus_verdicts_match_slugs(path: Path, default: str, robotics: str) -> None:
    assert verdicts(path) == (default, robotics)


@pytest.mark.parametrize(
    ("path", "default", "robotics"), _example_cases(), ids=lambda x: getattr(x, "name", "")
)
def test_slugs_example_verdicts_match_slugs(path: Path, default: str, robotics: str) -> None:
    assert verdicts(path) == (default, robotics)
