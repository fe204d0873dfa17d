"""``Game.solve(within=...)``: νZ started from a set known to hold the winning region.

The preferences' hazard-avoiding game (gaitc/solver/preferences.py) has fewer system moves than
the full game, so it starts from the full game's winning region.  Started there or from
the care set, the fixpoint must give the same winning region and, since its last round is
at the same Z, the same strategy layers and rings: every test solves both and compares.
"""

from __future__ import annotations

from pathlib import Path

from games import tiny_specs
from hypothesis import HealthCheck, given, settings

from gaitc.ir.spec import GR1Spec
from gaitc.solver.game import Game
from gaitc.solver.preferences import fewer_moves
from gaitc.solver.symbolic import Options, SymbolicSpec
from slugs_bridge.formats import load_spec_file

CORPUS = sorted((Path(__file__).parents[1] / "data" / "gr1_corpus").glob("rand3_00[0-3]*.slugsin"))


def _both_ways(spec: GR1Spec) -> int:
    """Solve a restricted game of ``spec`` from the care set and from the full game's
    winning region, compare, and return how many rounds the second start saved."""
    sym = SymbolicSpec(spec, Options(reordering=False))
    winning = Game(sym).solve().winning
    out = sym.output_bits[0] + "'"
    strict = fewer_moves(sym, ~sym.bdd.var(out))  # the first output stays false
    plain_game, started_game = Game(strict), Game(strict)
    plain = plain_game.solve(keep_layers=True)
    started = started_game.solve(keep_layers=True, within=winning)
    assert started.winning == plain.winning
    assert started.winning <= winning
    assert started.layers == plain.layers
    assert started.rings == plain.rings
    return plain_game.stats.z_iterations - started_game.stats.z_iterations


def test_a_restricted_game_started_inside_the_winning_region() -> None:
    saved = [_both_ways(load_spec_file(str(path))) for path in CORPUS]
    assert min(saved) >= 0
    assert sum(saved) >= len(CORPUS) // 2  # most of these save a round (32 of 40 here)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(tiny_specs())
def test_a_restricted_game_started_inside_the_winning_region_on_tiny_specs(
        spec: GR1Spec) -> None:
    _both_ways(spec)
