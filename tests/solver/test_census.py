"""The census of an explicit extraction (gaitc/solver/census.py) against the extraction itself.

The count must be exact: every test extracts the controller node by node and compares,
and extracts it again reading every node's moves off the census's move functions, which
must give the same automaton.
With a node limit, a long extraction gives up once the census passes it, after fewer
expansions than the limit, and ``auto`` turns symbolic then.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import gaitc
from bench.families.genbuf import genbuf_text
from gaitc.forms.synthesis import _costs
from gaitc.ir.bddfile import SymbolicController
from gaitc.ir.spec import GR1Spec
from gaitc.solver import strategy, synthesis
from gaitc.solver.census import Census, node_count
from gaitc.solver.game import ControllerTooLarge, GameResult, Limits, goal_strategies
from gaitc.solver.preferences import MovePreferences, preference_order
from gaitc.solver.strategy import extract_strategy
from gaitc.solver.symbolic import Options, SymbolicSpec
from gaitc.verifier.symbolic import verify_symbolic
from slugs_bridge.formats import load_spec_file

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).parents[1] / "data"
CORPUS = sorted((DATA / "gr1_corpus").glob("rand3_00[0-4]*.slugsin"))


def _solved(spec: GR1Spec, semantics: str) -> tuple[SymbolicSpec, GameResult] | None:
    sym, game = synthesis._game(spec, semantics, Options(), Limits())
    result = game.solve(keep_layers=True)
    if not game.initially_winning(result.winning, semantics):
        return None
    return sym, result


def _compare(spec: GR1Spec, semantics: str, prefer: MovePreferences | None,
             sym: SymbolicSpec, result: GameResult) -> int:
    strategies = goal_strategies(sym, result)
    relations = [prefer.relation(j, s) for j, s in enumerate(strategies)] if prefer \
        else strategies
    counted = node_count(sym, relations, result.winning, semantics)
    made = extract_strategy(sym, result, semantics, prefer=prefer)
    assert counted == len(made.nodes)
    with pytest.MonkeyPatch.context() as patch:  # every node read off the move functions
        patch.setattr(strategy, "CENSUS_AFTER", 0.0)
        patch.setattr(strategy, "Census", _Eager)
        _Eager.read_off = 0
        fast = extract_strategy(sym, result, semantics, prefer=prefer)
    assert _Eager.read_off == (1 if made.nodes else 0)  # no nodes: the loop never ran
    assert (fast.nodes, fast.initial) == (made.nodes, made.initial)
    return counted


class _Eager(Census):
    """A census that computes its move functions in its first slice."""

    read_off = 0  # how many censuses had their functions after their first slice

    def advance(self) -> int | None:
        if self.moves is not None:
            return super().advance()
        while self.moves is None and not self.done:
            super().advance()
        _Eager.read_off += self.moves is not None
        return self.count


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: p.name)
@pytest.mark.parametrize("semantics", ["default", "robotics"])
def test_the_census_counts_the_nodes_of_random_specs(path: Path, semantics: str) -> None:
    spec = load_spec_file(str(path))
    solved = _solved(spec, semantics)
    if solved is None:
        pytest.skip("unrealizable")
    sym, result = solved
    _compare(spec, semantics, None, sym, result)
    _compare(spec, semantics, MovePreferences(sym, result, (), ("goal",)), sym, result)


@pytest.mark.parametrize("senders", [2, 3])
def test_the_census_counts_a_generalized_buffer(tmp_path: Path, senders: int) -> None:
    path = tmp_path / f"genbuf{senders}.structuredslugs"
    path.write_text(genbuf_text(senders), encoding="utf-8")
    spec = load_spec_file(str(path))
    solved = _solved(spec, "default")
    assert solved is not None
    sym, result = solved
    assert _compare(spec, "default", MovePreferences(sym, result, (), ("goal",)),
                    sym, result) > 100


@pytest.mark.parametrize("name,encoding,order", [
    ("thesis_robot_b.gait", "onehot", None),
    ("thesis_robot_b.gait", "binary", None),
    ("thesis_robot_b.gait", "binary", "switches,goal"),
    ("corridor_hazard.gait", "onehot", None),
])
def test_the_census_counts_gait_controllers_under_the_robot_model(
        name: str, encoding: str, order: str | None) -> None:
    """The preferences weigh moves by the model's costs (and avoid hazards)."""
    spec = gaitc.load(ROOT / "specs" / name, encoding)
    solved = _solved(spec.gr1, "default")
    assert solved is not None
    sym, result = solved
    chosen = preference_order(order)
    prefer = MovePreferences(sym, result, _costs(spec, chosen), chosen)
    _compare(spec.gr1, "default", prefer, sym, result)


class _Expansions(Limits):
    """Limits that count the extraction's expansions (one check per node)."""

    def __init__(self) -> None:
        super().__init__()
        self.checks = 0

    def check(self) -> None:
        self.checks += 1
        super().check()


def _genbuf(tmp_path: Path, senders: int) -> GR1Spec:
    path = tmp_path / f"genbuf{senders}.structuredslugs"
    path.write_text(genbuf_text(senders), encoding="utf-8")
    return load_spec_file(str(path))


def _limited(spec: GR1Spec, max_nodes: int) -> tuple[int, bool]:
    solved = _solved(spec, "default")
    assert solved is not None
    sym, result = solved
    limits = _Expansions()
    try:
        extract_strategy(sym, result, "default", limits, max_nodes,
                         MovePreferences(sym, result, (), ("goal",)))
    except ControllerTooLarge:
        return limits.checks, True
    return limits.checks, False


def test_a_census_over_the_limit_stops_the_extraction_early(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """One node too many: without the census the extraction would find them all.  GenBuf
    with 4 senders: its 1,831 nodes take the census fewer slices than the extraction (with
    3 senders, 707 nodes, the extraction reaches its limit first)."""
    spec = _genbuf(tmp_path, 4)
    full, too_large = _limited(spec, 10**6)
    assert not too_large
    monkeypatch.setattr(strategy, "CENSUS_AFTER", float("inf"))
    without, too_large = _limited(spec, full - 1)  # stops at the full-th node found
    assert too_large
    monkeypatch.setattr(strategy, "CENSUS_AFTER", 0.0)
    # A census slice at every expansion, so the race is counted in steps, not in seconds
    # that a loaded machine would change.
    monkeypatch.setattr(strategy, "CENSUS_SHARE", 0.0)
    taken: list[Census] = []

    class Spy(Census):
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            taken.append(self)

    monkeypatch.setattr(strategy, "Census", Spy)
    checks, too_large = _limited(spec, full - 1)
    # The census, a slice per expansion, ends before the extraction would have found the
    # node too many.
    assert too_large and taken[0].count == full and checks < without
    checks, too_large = _limited(spec, full)  # exactly at the limit: it still fits
    assert not too_large and checks == full


def test_auto_turns_symbolic_once_the_census_passes_the_limit(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(strategy, "CENSUS_AFTER", 0.0)
    spec = _genbuf(tmp_path, 3)
    found = synthesis.synthesize_controller(spec, max_nodes=50, form="auto",
                                            prefer=("goal",))
    assert isinstance(found, SymbolicController)
    assert verify_symbolic(spec, found).ok
    with pytest.raises(ControllerTooLarge, match="more than 50 nodes"):
        synthesis.synthesize_controller(spec, max_nodes=50, form="explicit")
