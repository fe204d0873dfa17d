"""A compact controller's rule tables say only what a run can meet (issue 51).

Checked without the BDD reachability they are made with: on small specs every run of the
controller is enumerated state by state (its Python decisions, the environment's inputs
allowed by ρe evaluated on the formulas), and the rules those decisions take are exactly the
rules printed, each condition exactly the values the decisions have; no decision at a
reachable state picks a gait that uses a leg the environment just failed.  On the larger
shipped specs the same leg check runs over the printed rules with the BDD care set.  One
policy is pinned as golden text (``--update-golden`` rewrites it).
"""

from __future__ import annotations

import itertools
import json
import os
from collections import deque
from collections.abc import Iterator, Mapping
from pathlib import Path

import pytest

import gaitc
from gaitc.api.drawing import compact_rules
from gaitc.api.generating import compact_of
from gaitc.cli import main
from gaitc.compact.controller import CompactController
from gaitc.compact.diagram import paths
from gaitc.compact.rules import RuleTables, condition, reach, rule_tables
from gaitc.core.spec import Spec
from gaitc.ir.bitblast import bitblast
from gaitc.ir.evaluation import evaluate
from gaitc.ir.spec import GR1Spec, Semantics

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "gaitc" / "examples"
GOLDEN = ROOT / "tests" / "golden" / "policy"
SMALL = ["shuttle_2leg.gait", "patrol_2x2.gait", "corridor_hazard.gait",
         "correction_edges.gait"]
LARGER = ["thesis_robot_a.gait", "thesis_robot_b.gait", "radial8_patrol.gait"]
WIDE5 = """robot "wide five"
legs A1..A5 health 3
gait g1  uses A1, A2 moves east
gait g2  uses A2, A3 moves east
gait g3  uses A3, A4 moves east
gait g4  uses A4, A5 moves west
gait g5  uses A5, A1 moves west
gait g6  uses A1, A3 moves west
gait g7  uses A2, A4 moves north
gait g8  uses A3, A5 moves north
gait g9  uses A1, A4 moves south
gait g10 uses A2, A5 moves south
gait g11 uses A4, A1 moves east
gait g12 uses A1, A2 moves west
grid 2 x 8 cells a0, a1, a2, a3, a4, a5, a6, a7,
                 b0, b1, b2, b3, b4, b5, b6, b7
cache a0, b7, a4
start a0
visit b7, a0 infinitely often
"""

State = tuple[tuple[str, int], ...]


def _compact(spec: Spec) -> CompactController:
    found = compact_of(spec)
    assert found is not None
    return found


@pytest.fixture(scope="module")
def small() -> dict[str, tuple[Spec, CompactController]]:
    """The small examples' compact controllers, under the default semantics and (keys
    ending in ``+robotics``) the robotics one."""
    out = {}
    for name in SMALL:
        spec = gaitc.load(EXAMPLES / name)
        out[name] = (spec, _compact(spec))
        made = gaitc.synthesize(spec, Semantics.ROBOTICS, form="compact")
        assert isinstance(made.controller, CompactController)
        out[f"{name}+robotics"] = (spec, made.controller)
    return out


# ---------------------------------------------------------------------------- enumeration
def _bits(ctrl: CompactController, values: Mapping[str, int], primed: bool) -> dict[str, int]:
    out: dict[str, int] = {}
    for f in ctrl.vocabulary.fields:
        if f.name in values:
            out.update({b: int(on) for b, on in f.cube(values[f.name], primed).items()})
    return out


def _holds(clauses: GR1Spec, section: str, valuation: Mapping[str, int]) -> bool:
    return all(evaluate(c.formula, valuation) for c in clauses.section(section))


def _inputs(ctrl: CompactController) -> Iterator[dict[str, int]]:
    fields = ctrl.vocabulary.inputs
    for combo in itertools.product(*(range(len(f.labels)) for f in fields)):
        yield dict(zip((f.name for f in fields), combo, strict=True))


Decision = tuple[int, dict[str, int], dict[str, int], dict[str, int]]


def _decisions(spec: Spec, ctrl: CompactController
               ) -> tuple[list[dict[str, int]], list[Decision]]:
    """Every first input θe allows (default semantics), and every decision (goal, state,
    inputs chosen, move) of every run: breadth first over (state, goal) from the first
    states (the controller's first outputs, or under the robotics semantics every state
    θe allows that it accepts), each input ρe allows, the controller's own move and
    counter (as :class:`gaitc.compact.controller.Runner` steps)."""
    clauses = bitblast(spec.gr1)
    firsts, starts = [], []
    if ctrl.semantics == Semantics.ROBOTICS:
        outs = ctrl.vocabulary.outputs
        for chosen in _inputs(ctrl):
            for combo in itertools.product(*(range(len(f.labels)) for f in outs)):
                state = chosen | dict(zip((f.name for f in outs), combo, strict=True))
                if ctrl.accepts(state) and _holds(clauses, "env_init",
                                                  _bits(ctrl, state, False)):
                    starts.append(state)
    else:
        for chosen in _inputs(ctrl):
            state = chosen | ctrl.first(chosen)
            if _holds(clauses, "env_init", _bits(ctrl, state, False)):
                firsts.append(chosen)
                starts.append(state)
    seen: set[tuple[State, int]] = set()
    queue: deque[tuple[dict[str, int], int]] = deque()
    for state in starts:
        key = (tuple(sorted(state.items())), 0)
        if key not in seen:
            seen.add(key)
            queue.append((state, 0))
    out: list[Decision] = []
    while queue:
        state, goal = queue.popleft()
        now = _bits(ctrl, state, False)
        after = ctrl.advance(goal, state)
        for chosen in _inputs(ctrl):
            move = ctrl.decide(goal, state, chosen)
            valuation = now | _bits(ctrl, chosen, True) | _bits(ctrl, move, True)
            if not _holds(clauses, "env_trans", valuation):
                continue
            out.append((goal, state, chosen, move))
            nxt = dict(state) | chosen | move
            key = (tuple(sorted(nxt.items())), after)
            if key not in seen:
                seen.add(key)
                queue.append((nxt, after))
    return firsts, out


def _expected(ctrl: CompactController, root: int, met: list[list[int]]
              ) -> list[tuple[str, ...] | None]:
    """Per path of ``root``, the conditions the decisions that take it have (None: no
    decision takes it), said as the tables say them."""
    robot = ctrl.vocabulary.domain == "robot"
    found = paths(ctrl.nodes, root, len(ctrl.slots))
    taken: list[list[list[int]]] = [[] for _ in found]
    for values in met:
        hits = [k for k, (cond, _) in enumerate(found)
                if all(c is None or v in c for c, v in zip(cond, values, strict=True))]
        assert len(hits) == 1, (values, hits)
        taken[hits[0]].append(values)
    everywhere = [{v[k] for v in met} for k in range(len(ctrl.slots))]
    out: list[tuple[str, ...] | None] = []
    for (cond, _), rows in zip(found, taken, strict=True):
        if not rows:
            out.append(None)
            continue
        words = []
        for k, slot in enumerate(ctrl.slots):
            here = frozenset(v[k] for v in rows)
            if cond[k] is not None or (not slot.next and not slot.field.is_input
                                       and len(here) == 1 and here < everywhere[k]):
                words.append(condition(slot, here, robot))
        out.append(tuple(words))
    return out


BOTH = [*SMALL, *(f"{name}+robotics" for name in SMALL)]


@pytest.mark.parametrize("name", BOTH)
def test_the_printed_rules_are_exactly_the_ones_runs_take(
        small: dict[str, tuple[Spec, CompactController]], name: str) -> None:
    spec, ctrl = small[name]
    firsts, decisions = _decisions(spec, ctrl)
    assert decisions and bool(firsts) == (ctrl.semantics == Semantics.DEFAULT)
    tables = rule_tables(ctrl, spec=spec.gr1)
    for j, (_, rules) in enumerate(tables.goals):
        met = [ctrl.slot_values(s, c) for g, s, c, _ in decisions if g == j]
        expected = _expected(ctrl, ctrl.move_roots[j], met)
        assert [r.conditions if r.used else None for r in rules] == expected, (name, j)
    if ctrl.semantics == Semantics.DEFAULT:  # the robotics start is a set, not rules
        start = _expected(ctrl, ctrl.start_root, [ctrl.slot_values({}, c) for c in firsts])
        assert [r.conditions if r.used else None for r in tables.start] == start
    else:
        assert tables.start == ()
    # the text lists the used rules and counts the others
    text = tables.text()
    printed = sum(len(tables.shown(rules)) for _, rules in tables.goals)
    assert printed == sum(r is not None for j, root in enumerate(ctrl.move_roots)
                          for r in _expected(ctrl, root, [ctrl.slot_values(s, c) for g, s, c, _
                                                         in decisions if g == j]))
    assert "(never used)" not in text
    assert (f"{tables.never_used} rule" in text) == (tables.never_used > 0)


def test_a_rule_no_run_takes_is_left_out_and_counted(
        small: dict[str, tuple[Spec, CompactController]]) -> None:
    """The shuttle decides at b with the goal counter it had on arriving, so goal a's rule
    for b is never used (the enumeration above agrees)."""
    spec, ctrl = small["shuttle_2leg.gait"]
    tables = rule_tables(ctrl, ["a", "b"], spec=spec.gr1)
    assert tables.never_used == 1
    assert "in b  ->  west to a" not in tables.text().split("pursuing b")[0]
    marked = rule_tables(ctrl, ["a", "b"], spec=spec.gr1, all_rules=True).text()
    assert "in b  ->  west to a  (never used)" in marked
    data = json.loads(tables.json())
    assert data["never_used"] == 1
    assert [r["used"] for g in data["goals"] for r in g["rules"]] == [True, False, True, True]
    # without the spec nothing is known, so nothing is left out; a controller alone shows
    # its sizes in a notebook, not rules it cannot tell apart
    assert rule_tables(ctrl).never_used == 0 and rule_tables(ctrl).reach_line() is None
    assert "compact_rules(spec, controller)" in ctrl._repr_html_()


def _leg_problems(spec: Spec, ctrl: CompactController, tables: RuleTables) -> list[str]:
    """Used rules that, at a state a run reaches, pick a gait using a leg the environment
    has just failed (level 1)."""
    model = spec.model
    assert model is not None
    found = reach(ctrl, spec.gr1)
    bdd = found.bdd
    gait = ctrl.vocabulary.named("gait")
    legs = {leg.name: ctrl.vocabulary.named(leg.name) for leg in model.legs if leg.health > 1}
    chosen = {s.field.name: s for s in ctrl.slots if s.next}
    problems = []
    for j, root in enumerate(ctrl.move_roots):
        rules = tables.goals[j][1]
        for (cond, move), rule in zip(paths(ctrl.nodes, root, len(ctrl.slots)), rules,
                                      strict=True):
            if not rule.used:
                continue
            outs = dict(zip((f.name for f in ctrl.vocabulary.outputs), ctrl.moves[move],
                            strict=True))
            walked = gait.labels[outs["gait"]]
            on_path = found.moves[j] & found.path(ctrl, cond)
            for leg, f in legs.items():
                if walked in model.gaits_using(leg) and on_path & bdd.cube(
                        f.cube(f.labels.index("1"), chosen[leg].next)) != bdd.false:
                    problems.append(f"{rule.when} -> {rule.move}: {leg} failed")
    return problems


@pytest.mark.parametrize("name", BOTH)
def test_the_care_set_is_the_verifiers_reachable_set(
        small: dict[str, tuple[Spec, CompactController]], name: str) -> None:
    """Per goal, the states of the care set are the (state, goal) pairs the independent
    verifier's closed loop reaches (:mod:`gaitc.verifier.symbolic`), as many as it counts,
    and as many as the enumeration finds."""
    spec, ctrl = small[name]
    found = reach(ctrl, spec.gr1)
    post_in = {b + "'" for b in ctrl.inputs}
    bits = len(ctrl.inputs) + len(ctrl.outputs)
    counted = sum(int(found.bdd.count(found.bdd.exist(post_in, here), nvars=bits))
                  for here in found.moves)
    report = gaitc.verify(spec, ctrl)
    assert report.ok and counted == report.nodes
    _, decisions = _decisions(spec, ctrl)
    assert counted == len({(g, tuple(sorted(s.items()))) for g, s, _, _ in decisions})


@pytest.mark.parametrize("name", BOTH)
def test_no_reachable_decision_walks_on_a_failed_leg(
        small: dict[str, tuple[Spec, CompactController]], name: str) -> None:
    spec, ctrl = small[name]
    model = spec.model
    assert model is not None
    _, decisions = _decisions(spec, ctrl)
    gait = ctrl.vocabulary.named("gait")
    for _, _, chosen, move in decisions:
        walked = gait.labels[move["gait"]]
        for leg in model.legs:
            f = ctrl.vocabulary.named(leg.name) if leg.health > 1 else None
            if f is not None and f.labels[chosen[leg.name]] == "1":
                assert walked not in model.gaits_using(leg.name), (chosen, walked)
    assert _leg_problems(spec, ctrl, rule_tables(ctrl, spec=spec.gr1)) == []


def test_the_leg_check_sees_a_rule_that_walks_on_a_failed_leg(
        small: dict[str, tuple[Spec, CompactController]]) -> None:
    """The check above is not vacuous: send every leaf of corridor's first goal to a move
    by west_2 (which uses L4) and the rules where L4 may be failed are caught."""
    spec, ctrl = small["corridor_hazard.gait"]
    gait = ctrl.vocabulary.named("gait")
    index = next(k for k, m in enumerate(ctrl.moves)
                 if gait.labels[m[[f.name for f in ctrl.vocabulary.outputs].index("gait")]]
                 == "west_2")
    from dataclasses import replace

    from gaitc.compact.diagram import Branch

    nodes = tuple(Branch(b.field, tuple(-index - 1 if k < 0 else k for k in b.kids), b.unused)
                  for b in ctrl.nodes)
    changed = replace(ctrl, nodes=nodes)
    problems = _leg_problems(spec, changed, rule_tables(changed, spec=spec.gr1))
    assert problems and all("L4 failed" in p for p in problems)


@pytest.mark.parametrize("name", [*LARGER, "wide5"])
def test_no_printed_rule_walks_on_a_failed_leg(tmp_path: Path, name: str) -> None:
    if name == "wide5":
        path = tmp_path / "wide5.gait"
        path.write_text(WIDE5, encoding="utf-8")
    else:
        path = EXAMPLES / name
    spec = gaitc.load(path)
    ctrl = _compact(spec)
    tables = rule_tables(ctrl, spec=spec.gr1)
    assert tables.rules - tables.never_used > 0
    assert _leg_problems(spec, ctrl, tables) == []


# ---------------------------------------------------------------------------- golden
def _updating(request: pytest.FixtureRequest) -> bool:
    flag = request.config.getoption("--update-golden", default=False)
    return bool(flag) or os.environ.get("GAITC_UPDATE_GOLDEN") == "1"


@pytest.mark.parametrize(("name", "options"), [("corridor_hazard", []),
                                               ("shuttle_2leg", []),
                                               ("shuttle_2leg", ["--all-rules"])])
def test_golden_compact_policy(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                               request: pytest.FixtureRequest, name: str,
                               options: list[str]) -> None:
    controller = tmp_path / "c.json"
    spec = str(EXAMPLES / f"{name}.gait")
    assert main(["synth", spec, "--compact", "-o", str(controller)]) == 0
    capsys.readouterr()
    assert main(["render", "policy", spec, str(controller), *options]) == 0
    text = capsys.readouterr().out
    expected = GOLDEN / f"{name}{''.join(options).replace('--', '.')}.compact.txt"
    if _updating(request):
        expected.parent.mkdir(exist_ok=True)
        expected.write_text(text, encoding="utf-8")
        return
    assert expected.exists(), f"{expected.name} is missing: run with --update-golden"
    assert text == expected.read_text(encoding="utf-8")


def test_compact_rules_from_the_api_match_the_cli_json(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = str(EXAMPLES / "shuttle_2leg.gait")
    out = tmp_path / "rules.json"
    assert main(["render", "policy", spec, "--compact", "-o", str(out)]) == 0
    tables = compact_rules(spec)
    assert tables is not None
    assert json.loads(out.read_text(encoding="utf-8")) == tables.to_dict()
    # a projected (not compact) policy has no JSON and no never used rules
    assert main(["render", "policy", spec, "--format", "json"]) == 2
    assert main(["render", "policy", spec, "--all-rules"]) == 2
    assert "--all-rules lists a compact controller's rules" in capsys.readouterr().err
