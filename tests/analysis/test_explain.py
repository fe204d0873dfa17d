"""``gaitc explain``: every answer is checked here by solving again, not trusted.

Purpose-built specs in tests/data/explain/ cover each kind of failure and each sanity
warning; every core is re-solved with and without each of its units, every repair's edited
text is parsed and solved, the freedoms are re-checked, and the play is replayed.
"""

from __future__ import annotations

import difflib
import itertools
import json
import shutil
from collections.abc import Sequence
from pathlib import Path

import pytest

import gaitc
from gaitc.analysis.explanation import Explanation
from gaitc.analysis.freedoms import Freedom, freedoms
from gaitc.cli import main
from gaitc.core.changes import HazardSwitch, LegWears
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import Implies, Not, atoms, conj, disj
from gaitc.ir.spec import Clause, GR1Spec
from gaitc.solver import synthesis
from gaitc.verifier.counterstrategy import verify_counterstrategy
from ltlcompiler.encoding import make_encoding
from ltlcompiler.model import Model

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "explain"
UNREALIZABLE = {
    "initial.gait": "initial", "safety.gait": "safety", "corridor_guarantee.gait": "liveness",
    "hazard_cut.gait": "liveness", "few_levels.gait": "liveness",
    "failed_direction.gait": "liveness", "unrealizable_2x2.gait": "liveness",
    "thesis_robot_a_health2.gait": "liveness", "all_legs_short.gait": "liveness",
    "spill_pair.gait": "liveness", "spare_leg.gait": "liveness",
}
IN_SPECS = ("unrealizable_2x2.gait", "thesis_robot_a_health2.gait")  # the rest: DATA
SPECS = {name: (ROOT / "specs" if name in IN_SPECS else DATA) / name for name in UNREALIZABLE}


def _realizable(spec: GR1Spec) -> bool:
    return synthesis.check(spec).realizable


def _core_variant(spec: GR1Spec, keep: set[tuple[str, int]]) -> GR1Spec:
    """Assumptions whole; of the guarantees, the structural ones (no source, or the map)
    and the clauses in ``keep`` (built here, not with gaitc.analysis.units)."""
    changes = {}
    for section in ("sys_init", "sys_trans", "sys_liveness"):
        kept = []
        for index, clause in enumerate(spec.section(section)):
            origin = clause.origin
            structural = origin is None or origin.span is None or origin.rule.startswith(
                "eq. 3.3:")
            if structural or (section, index) in keep:
                kept.append(clause)
        changes[section] = tuple(kept)
    return spec.with_sections(**changes)


@pytest.mark.parametrize("encoding", ["onehot", "binary"])
@pytest.mark.parametrize("name", sorted(SPECS))
def test_unrealizable_specs_are_explained_and_every_answer_rechecked(
        name: str, encoding: str) -> None:
    spec = gaitc.load(SPECS[name], encoding)
    why = gaitc.explain(spec)
    assert not why.realizable and why.kind == UNREALIZABLE[name]
    # the core: unrealizable with all its units, realizable without any one of them
    clauses = {(u.section, i) for u in why.core for i in u.indices}
    assert not _realizable(_core_variant(spec.gr1, clauses))
    for unit in why.core:
        without = clauses - {(unit.section, i) for i in unit.indices}
        assert _realizable(_core_variant(spec.gr1, without)), unit.rule
    # every repair: its edited text is what its diff says, and it is realizable
    original = spec.text.splitlines()
    for repair in why.repairs:
        changed = [d for d in difflib.ndiff(original, repair.text.splitlines())
                   if d.startswith(("+ ", "- "))]
        assert sorted(d[0] + d[2:] for d in changed) == sorted(repair.diff)
        fixed = gaitc.parse(repair.text, name=str(SPECS[name]), encoding=encoding)
        assert gaitc.check(fixed).realizable, repair.change
    assert why.repairs or name == "safety.gait" or why.kind == "initial"
    if why.kind == "liveness" and why.goals:  # one story: the core holds the header's goal
        assert any(u.section == "sys_liveness" and u.rule.endswith(f": {why.goals[0]}")
                   for u in why.core)
    _check_freedoms(spec, why)
    _check_play(spec, why)


def _restrict(spec: gaitc.Spec, taken: Sequence[Freedom]) -> GR1Spec:
    model, encoding = spec.model, spec.encoding
    assert model is not None and encoding is not None
    enc = make_encoding(model, encoding)
    hot = disj(conj((enc.hazard(h.name), disj(enc.region(r) for r in h.regions)))
               for h in model.hazards)
    extra_init, extra_trans = [], []
    for f in taken:
        if isinstance(f.change, LegWears):
            guard = conj([enc.gait(f.gait), *(Not(enc.region(c)) for c in model.caches),
                          *([Not(hot)] if model.hazards else [])])
            extra_trans.append(Clause(Implies(guard, enc.keep_health(f.change.leg))))
        else:
            assert isinstance(f.change, HazardSwitch) and f.change.on
            extra_init.append(Clause(Not(enc.hazard(f.change.hazard))))
            extra_trans.append(Clause(Not(enc.hazard(f.change.hazard, True))))
    gr1 = spec.gr1
    return gr1.with_sections(env_init=gr1.env_init + tuple(extra_init),
                             env_trans=gr1.env_trans + tuple(extra_trans))


def _check_freedoms(spec: gaitc.Spec, why: Explanation) -> None:
    """The freedoms are those the environment needs against the core (one story): it wins
    the core's game with just them, and so the whole spec, and each one is needed there."""
    assert spec.model is not None
    every = list(freedoms(spec.model))
    needed = list(why.freedoms)
    assert set(needed) <= set(every)
    others = [f for f in every if f not in needed]
    assert not _realizable(_restrict(spec, others))  # it still wins with just these
    clauses = {(u.section, i) for u in why.core for i in u.indices}
    restricted = _restrict(spec, others)
    core_game = _core_variant(restricted, clauses)
    assert not _realizable(core_game)
    for f in needed:  # and each one is needed against the core
        taken = _restrict(spec, [*others, f])
        assert _realizable(_core_variant(taken, clauses)), f.describe()


def _check_play(spec: gaitc.Spec, why: Explanation) -> None:
    counter = why.counter
    assert counter is not None
    report = verify_counterstrategy(spec.gr1, counter, "default")
    assert report.ok, report.problems
    play, run = why.play, why.run
    if why.kind == "initial":
        assert play is None and not counter.initial
        return
    assert play is not None and run is not None
    assert run.summary is not None and run.summary.assumptions_held
    assert run.summary.guarantees_held  # the robot's answers keep its rules
    assert play.path[0] in counter.initial
    for a, b in zip(play.path, play.path[1:], strict=False):
        assert b in counter.nodes[a].trans
    if play.deadlock:
        assert not counter.nodes[play.path[-1]].trans
        return
    loop = play.path[play.loop_start:]
    missed = [j for j, goal in enumerate(spec.gr1.sys_liveness) if not any(
        evaluate(goal.formula, {**counter.values(a),
                                **{f"{k}'": v for k, v in counter.values(b).items()}})
        for a, b in itertools.pairwise(loop))]
    assert missed and tuple(missed) == play.missed
    _check_summary(spec, why)


def _region_distance(model: Model, targets: set[str]) -> dict[str, int]:
    """Moves along the map's transitions from each region to ``targets`` (the test's own
    breadth-first search, not the explanation's)."""
    distance = dict.fromkeys(targets, 0)
    frontier = sorted(targets)
    while frontier:
        nxt = []
        for t in model.transitions:
            if t.target in frontier and t.source not in distance and t.gaits:
                distance[t.source] = distance[t.target] + 1
                nxt.append(t.source)
        frontier = nxt
    return distance


def _check_summary(spec: gaitc.Spec, why: Explanation) -> None:
    """The summary before the steps names the lost goal and the environment's decisive
    moves, each of which happens in the replayed run where it says; and the robot tries:
    somewhere in the play it gets closer on the map to the goal it loses than it started."""
    model, play, run = spec.model, why.play, why.run
    if model is None or play is None or run is None or play.deadlock:
        return
    labels = [c.origin.rule.split(": ", 1)[1] for c in spec.gr1.sys_liveness
              if c.origin is not None and c.origin.rule.startswith("goal")]
    lost = [labels[j] for j in play.missed if j < len(labels)]
    first = [g for g in why.goals[:1] if g in lost]  # the header's goal leads the story
    rest = [g for g in lost if g not in first]
    also = f" (and with it {', '.join(rest)})" if first and rest else ""
    assert why.story[0] == f"the robot is kept from {', '.join(first or rest)}{also}"
    moves = why.story[1]
    if moves.startswith("the environment's decisive moves: "):
        for item in moves.removeprefix("the environment's decisive moves: ").split("; "):
            index, region = item.split(" ")[1], item.split(" ")[3].rstrip(":")
            step = run.steps[int(index)]
            assert step.region == region, item
            assert step.failed or step.degraded or step.hazard is not None, item
    else:
        assert moves.startswith("the environment never has to act in this play")
    regions = {r.name for r in model.regions}
    targets = {name for j in play.missed for name, _ in atoms(spec.gr1.sys_liveness[j].formula)
               if name in regions}
    if targets and spec.encoding == "onehot" and len({s.region for s in run.steps}) > 1:
        distance = _region_distance(model, targets)
        far = len(regions)
        start = distance.get(run.steps[0].region, far)
        closest = min(distance.get(s.region, far) for s in run.steps)
        assert closest < start or start == 0 or why.story[1].startswith(
            "the environment never"), (start, closest)


def test_the_robot_needs_the_corridor_the_guarantee_closes() -> None:
    why = gaitc.explain(DATA / "corridor_guarantee.gait")
    assert any(u.rule == "guarantee (line 9): !b" for u in why.core)
    assert why.goals == ("visit c",)
    assert "drop the guarantee on line 9" in [r.change for r in why.repairs]


def test_hazard_repairs_and_the_story() -> None:
    why = gaitc.explain(DATA / "hazard_cut.gait")
    changes = [r.change for r in why.repairs]
    assert changes[:2] == ["take b out of hazard set fire",
                           "assume hazard set fire is off infinitely often"]
    assert [f.describe() for f in why.freedoms] == ["switch hazard set fire on"]
    assert any("hazard fire on" in line for line in why.story)


def test_raising_every_legs_health_is_the_first_repair() -> None:
    """No single leg's raise and no cache helps; the one line ``health 2`` -> ``4`` does."""
    why = gaitc.explain(DATA / "all_legs_short.gait")
    first = why.repairs[0]
    assert first.change == "raise every leg's health to 4"
    assert first.diff == ("-legs L1..L4 health 2", "+legs L1..L4 health 4")
    assert why.repairs[-1].change == "drop the goal visit b2"  # dropping a goal comes last
    # re-solved here: one level less is not enough
    short = gaitc.parse(first.text.replace("health 4", "health 3"), name="short.gait")
    assert not gaitc.check(short).realizable and gaitc.check(
        gaitc.parse(first.text, name="fixed.gait")).realizable


def test_a_gait_on_the_spare_leg_is_a_repair() -> None:
    why = gaitc.explain(DATA / "spare_leg.gait")
    added = [r for r in why.repairs if r.change.startswith("add gait")]
    assert [r.change for r in added] == ["add gait east_2 on L3, moving as east does"]
    assert added[0].diff == ("+gait east_2 uses L3 moves east",)
    assert gaitc.check(gaitc.parse(added[0].text, name="spare.gait")).realizable


def test_an_added_gait_does_not_copy_the_comment_of_its_model() -> None:
    """Issue 60: the new gait's line took the old gait's comment along."""
    text = (DATA / "spare_leg.gait").read_text(encoding="utf-8").replace(
        "gait east uses L1 moves east", "gait east uses L1 moves east  # the front leg")
    why = gaitc.explain(gaitc.parse(text, name="commented.gait"))
    added = [r for r in why.repairs if r.change.startswith("add gait")]
    assert added[0].diff == ("+gait east_2 uses L3 moves east",)
    assert "gait east uses L1 moves east  # the front leg\n" in added[0].text


def test_raising_every_legs_health_edits_every_line_that_declares_legs() -> None:
    """Legs declared on two lines: the label says every leg, so both lines change."""
    text = (DATA / "all_legs_short.gait").read_text(encoding="utf-8").replace(
        "legs L1..L4 health 2", "legs L1..L2 health 2  # left\nlegs L3..L4 health 2  # right")
    why = gaitc.explain(gaitc.parse(text, name="two_sides.gait"))
    first = why.repairs[0]
    assert first.change == "raise every leg's health to 4"
    assert first.diff == ("-legs L1..L2 health 2  # left", "+legs L1..L2 health 4  # left",
                          "-legs L3..L4 health 2  # right", "+legs L3..L4 health 4  # right")
    fixed = gaitc.parse(first.text, name="fixed.gait")
    assert fixed.model is not None and {leg.health for leg in fixed.model.legs} == {4}
    assert gaitc.check(fixed).realizable


def test_a_raise_of_the_legs_below_a_level_names_them() -> None:
    """Issue 60: with one side at the level already, 'raise every leg's health to 4' edited
    one line; the label now names the legs it raises."""
    text = (DATA / "all_legs_short.gait").read_text(encoding="utf-8").replace(
        "legs L1..L4 health 2", "legs L1..L2 health 4\nlegs L3..L4 health 2")
    why = gaitc.explain(gaitc.parse(text, name="one_side.gait"))
    raises = [r for r in why.repairs if r.change.startswith("raise legs")]
    assert raises, [r.change for r in why.repairs]
    assert raises[0].change.startswith("raise legs L3, L4 to health ")
    assert raises[0].change.endswith(" (the other working legs have "
                                     f"{raises[0].change.split()[6]} or more)")
    fixed = gaitc.parse(raises[0].text, name="fixed.gait")
    assert fixed.model is not None and gaitc.check(fixed).realizable
    level = int(raises[0].change.split()[6])
    assert {leg.health for leg in fixed.model.legs} == {4, level} - {0}


def test_an_unblocked_cell_is_a_repair() -> None:
    """The goal lies past a blocked cell: unblocking it is the first repair."""
    text = ("legs L1..L2 health 3\ngait east uses L1 moves east\ngait west uses L2 moves west\n"
            "grid 1 x 3 cells a, b, c\nblock b\ncache a, c\nstart a\n"
            "visit c infinitely often\n")
    why = gaitc.explain(gaitc.parse(text, name="blocked.gait"))
    first = why.repairs[0]
    assert (first.change, first.diff) == ("unblock the cell b", ("-block b",))
    assert gaitc.check(gaitc.parse(first.text, name="open.gait")).realizable
    assert not gaitc.check(gaitc.parse(text, name="blocked.gait")).realizable


def test_a_cache_is_the_first_repair() -> None:
    why = gaitc.explain(DATA / "few_levels.gait")
    assert why.repairs[0].change.startswith("add a cache at ")
    assert not any(r.change.startswith("raise") for r in why.repairs)


def test_two_edits_where_no_single_one_works() -> None:
    why = gaitc.explain(DATA / "spill_pair.gait")
    pair = why.repairs[0]
    assert " and " in pair.change and pair.change.startswith("raise every leg's health")
    assert "two of these edits together" in why.repairs_tried
    # each half alone leaves the spec unrealizable (the test solves both)
    source = (DATA / "spill_pair.gait").read_text(encoding="utf-8")
    health_only = source.replace("health 2", "health 4")
    hazard_only = source.replace("hazard spill: b\n", "")
    for text in (health_only, hazard_only):
        assert not gaitc.check(gaitc.parse(text, name="half.gait")).realizable
    assert gaitc.check(gaitc.parse(pair.text, name="pair.gait")).realizable


def test_no_repair_says_what_was_tried(capsys: pytest.CaptureFixture[str]) -> None:
    """Two goals behind the robot, which can only walk east: no edit of the kinds searched
    (and no pair of them) helps, and dropping either goal leaves the other; the
    explanation says so and names every kind it tried."""
    text = ("legs L1..L2 health 2\ngait east uses L1 moves east\n"
            "grid 1 x 3 cells a, b, c\nstart c\nvisit a, b infinitely often\n")
    why = gaitc.explain(gaitc.parse(text, name="behind.gait"))
    assert not why.realizable and why.repairs == ()
    assert why.repairs_tried == ("raise a leg's health", "raise every leg's health",
                                 "add a cache", "two of these edits together",
                                 "another edit with the least health it needs", "drop a goal")
    lines = why.lines()
    at = lines.index("no repair found; searched:")
    assert lines[at + 1:at + 7] == [
        "  - raise a leg's health: each of the 2 legs alone, every level up to 100 (exact: "
        "doubling, then a parametric game)",
        "  - raise every leg's health: every working leg to one common level up to 100 "
        "(exact: doubling, then bisection)",
        "  - add a cache: each of the 3 regions with no cache or hazard; every pair of the "
        "first 3 (3 pairs)",
        "  - two of these edits together: 3 pairs of one kind and the 21 cheapest pairs of "
        "two kinds",
        "  - another edit with the least health it needs: the 3 cheapest other edits, each "
        "with the least health it needs up to level 4 (exact)",
        "  - drop a goal: each goal alone"]
    assert why.to_json()["repairs_searched"][0] == {
        "kind": "raise a leg's health",
        "searched": "each of the 2 legs alone, every level up to 100 (exact: doubling, then "
                    "a parametric game)"}
    # checked independently: no health of either leg up to the limit helps
    for legs in ("leg L1 health 100\nleg L2 health 2", "leg L1 health 2\nleg L2 health 100",
                 "legs L1..L2 health 100"):
        raised = text.replace("legs L1..L2 health 2", legs)
        assert not gaitc.check(gaitc.parse(raised, name="raised.gait")).realizable
    # checked independently: dropping either goal still leaves the spec unrealizable
    for kept in ("a", "b"):
        alone = text.replace("visit a, b", f"visit {kept}")
        assert not gaitc.check(gaitc.parse(alone, name="one.gait")).realizable


def test_a_permanently_failed_leg_is_repaired_by_health() -> None:
    why = gaitc.explain(DATA / "failed_direction.gait")
    assert why.goals == ("visit sw",)
    assert "raise leg L2's health to 2" in [r.change for r in why.repairs]


@pytest.mark.parametrize(("name", "code"), [("bad_assumption.gait", "assumptions-unsatisfiable"),
                                            ("not_separated.gait", "not-well-separated")])
def test_realizable_for_the_wrong_reason(name: str, code: str) -> None:
    why = gaitc.explain(DATA / name)
    assert why.realizable and [w.code for w in why.warnings][:1] == [code]
    if code == "not-well-separated":
        assert [u.rule for u in why.warnings[0].units] == ["assumption (line 9): b"]


#: The shipped examples that are unrealizable on purpose (each with its explanation in
#: docs); every other one is realizable.  A new example must be placed here or not.
UNREALIZABLE_EXAMPLES = frozenset({"unrealizable_2x2.gait", "thesis_robot_a_health2.gait"})


def test_every_example_spec_is_explained() -> None:
    """Each example's explanation gives its known verdict (pinned here, not asked of the
    solver a second time: radial12's explanation alone takes half a minute)."""
    explained = {}
    for path in sorted((ROOT / "specs").glob("*.gait")):
        explained[path.name] = why = gaitc.explain(path, repairs=False)
        assert why.realizable is (path.name not in UNREALIZABLE_EXAMPLES), path
    assert set(explained) >= UNREALIZABLE_EXAMPLES
    robot_b = explained["thesis_robot_b.gait"]
    assert [w.code for w in robot_b.warnings] == ["unused-gaits"]
    assert "north_b, east_b, south_c, west_c" in robot_b.warnings[0].message


def test_cli_exit_codes_json_and_saved_play(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["explain", "specs/patrol_2x2.gait"]) == 0
    assert main(["explain", str(DATA / "not_separated.gait")]) == 5
    assert main(["lint", "--deep", str(DATA / "not_separated.gait")]) == 5
    assert main(["lint", "--deep", str(DATA / "safety.gait")]) == 3
    capsys.readouterr()
    out = tmp_path / "play.jsonl"
    assert main(["explain", str(DATA / "hazard_cut.gait"), "--json", "--out", str(out)]) == 3
    data = json.loads(capsys.readouterr().out)
    assert {"file", "verdict", "kind", "goals", "core", "environment", "play", "repairs",
            "warnings"} <= set(data)
    assert data["kind"] == "liveness" and data["core"][0]["line"] >= 1
    assert data["repairs"][0]["diff"].startswith("-hazard fire: b")
    from gaitc.sim.run import read_jsonl

    replayed = read_jsonl(str(out))
    assert len(replayed.steps) == len(data["play"]["steps"])


def test_a_counter_strategy_can_be_simulated(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    counter = tmp_path / "counter.json"
    spec = str(DATA / "safety.gait")
    assert main(["counter", spec, "-o", str(counter)]) == 0
    capsys.readouterr()
    assert main(["simulate", spec, str(counter), "--env", "adversarial", "--quiet"]) == 0
    assert "counter-strategy, robot careful" in capsys.readouterr().out
    assert main(["simulate", spec, str(counter), "--env", "scripted", "x.yaml"]) == 2


@pytest.mark.graphviz
@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' is not installed")
def test_the_saved_play_draws_as_a_map(tmp_path: Path) -> None:
    play, picture = tmp_path / "play.jsonl", tmp_path / "play.svg"
    spec = str(DATA / "hazard_cut.gait")
    assert main(["explain", spec, "--no-repairs", "--out", str(play)]) == 3
    assert main(["render", "map", spec, "--run", str(play), "-o", str(picture)]) == 0
    assert "<svg" in picture.read_text(encoding="utf-8")


def test_a_timeout_stops_the_analysis_with_exit_4(capsys: pytest.CaptureFixture[str]) -> None:
    spec = str(ROOT / "specs" / "thesis_robot_a_health2.gait")
    assert main(["explain", spec, "--timeout", "0.05"]) == 4
    assert "ran out of time" in capsys.readouterr().err


def test_the_notebook_view_highlights_the_core_and_draws_the_play() -> None:
    why = gaitc.explain(DATA / "hazard_cut.gait", repairs=False)
    page = why._repr_html_()
    core_lines = {u.span.line for u in why.core if u.span is not None}
    assert page.count("background:#fde0dd") == len(core_lines)
    if shutil.which("dot") is not None:
        assert "<svg" in page
    assert "Explanation" in repr(why) and "liveness failure" in repr(why)


def test_a_spec_without_a_robot_is_explained_in_terms_of_the_system(tmp_path: Path) -> None:
    """The first GR(1) paper's arbiter without its clients' fairness: one client keeps its
    grant and starves another.  The words name the system, not a robot, and the core is
    solved again here: with only its guarantees the arbiter is lost, without any one won."""
    import sys

    sys.path.insert(0, str(ROOT))
    from bench.families.vmcai import arbiter_text

    path = tmp_path / "arbiter.structuredslugs"
    path.write_text(arbiter_text(4, fair=False), encoding="utf-8")
    why = gaitc.explain(path)
    text = "\n".join(why.lines()).replace(str(tmp_path), "")  # its name has "robot"
    assert not why.realizable and why.kind == "liveness"
    assert "the system can always move" in text and "robot" not in text
    spec = gaitc.load(path).gr1
    core = {(u.section, i) for u in why.core for i in u.indices}
    assert len(why.core) >= 2
    assert not _realizable(_core_variant(spec, core))
    for unit in why.core:
        assert _realizable(_core_variant(spec, core - {(unit.section, i) for i in unit.indices}))
    fair = tmp_path / "fair.structuredslugs"
    fair.write_text(arbiter_text(3), encoding="utf-8")
    sane = gaitc.explain(fair)
    assert sane.realizable
    assert all("robot" not in line.replace(str(tmp_path), "") for line in sane.lines())
