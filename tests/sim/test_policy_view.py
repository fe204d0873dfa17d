"""Readable controller views (issue 13): the controller projected on the map agrees with
the controller move by move, names only the spec's regions and gaits and needs each of
its condition variables; the first-k-steps view holds exactly the nodes a breadth-first
search reaches; both are deterministic; the CLI options work, symbolic controllers too."""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path

import pytest

import gaitc
from gaitc.api.simulation import Session, session
from gaitc.cli import main
from gaitc.sim.condensation import Move
from gaitc.sim.domain import Domain
from gaitc.sim.policy import Policy, controller_policy, project
from gaitc.sim.policy_view import policy_view
from gaitc.sim.steps_view import steps_view
from gaitc.sim.strategy import Strategy

ROOT = Path(__file__).resolve().parents[2]
ROBOT_A = str(ROOT / "specs" / "thesis_robot_a.gait")
PATROL = str(ROOT / "tests" / "data" / "hazard_patrol.gait")
SPECS = {"robot_a": ROBOT_A, "hazard_patrol": PATROL}
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module", params=sorted(SPECS))
def loaded(request: pytest.FixtureRequest) -> Session:
    found = session(SPECS[request.param], None)
    assert found is not None and isinstance(found.strategy, Strategy)
    return found


def _explicit(s: Session) -> Strategy:
    assert isinstance(s.strategy, Strategy)
    return s.strategy


def _condition(domain: Domain, rank: int, values: Mapping[str, int]) -> dict[str, str]:
    """The condition of a move, worked out here from the spec's variables, not by the
    module under test: the goal pursued, the hazard and each leg's band after the move."""
    seen = domain.decode(values)
    out = {"goal": domain.goals[rank].label}
    if domain.model.hazards:
        out["hazard"] = seen.hazard or "none"
    for leg in domain.model.legs:
        level = seen.level(leg.name)
        out[leg.name] = "healthy" if level == leg.health else "failed" if level == 1 else "degraded"
    return out


def _moves(s: Session) -> list[tuple[str, dict[str, str], Move]]:
    """Every move of the controller: (region before, condition, (gait, region) after)."""
    strategy, domain = _explicit(s), s.domain
    out = []
    for node in range(len(strategy)):
        here = domain.decode(strategy.valuation(node))
        for succ in strategy.options(node).values():
            there = domain.decode(strategy.valuation(succ))
            out.append(
                (
                    here.region,
                    _condition(domain, strategy.ranks[node], strategy.valuation(succ)),
                    Move(there.gait, there.region),
                )
            )
    return out


def _matching(policy: Policy, region: str, cond: Mapping[str, str]) -> list[int]:
    return [
        i
        for i, rule in enumerate(policy.rules)
        if rule.region == region and all(cond[name] in values for name, values in rule.condition)
    ]


@pytest.mark.parametrize("max_rules", [None, 2])
def test_the_table_gives_the_move_the_controller_makes(
    loaded: Session, max_rules: int | None
) -> None:
    policy = project(loaded.strategy, loaded.domain, max_rules=max_rules)
    moves = _moves(loaded)
    covered: dict[int, dict[Move, int]] = {}
    for region, cond, move in moves:
        found = _matching(policy, region, cond)
        assert len(found) == 1, (region, cond, found)  # the rules of a region partition
        rule = policy.rules[found[0]]
        assert move in dict(rule.moves), (region, cond, move, rule)
        counted = covered.setdefault(found[0], {})
        counted[move] = counted.get(move, 0) + 1
    for i, rule in enumerate(policy.rules):  # the counts are the controller's moves
        assert dict(rule.moves) == covered.get(i), rule
    assert policy.decisions == len(moves)
    assert policy.nodes == len(_explicit(loaded))
    if max_rules is not None:
        for region in policy.regions:
            assert sum(1 for r in policy.rules if r.region == region) <= max_rules


@pytest.mark.parametrize("max_rules", [None, 2])
def test_each_rule_is_as_exact_as_the_condition_allows(
    loaded: Session, max_rules: int | None
) -> None:
    """A rule lists exactly the moves the controller makes under the full condition of
    each decision it covers: it hides no distinction the condition variables make, and
    rules with several moves are where the controller's memory decides.  Under
    ``max_rules`` the rules marked not exact (~) are the ones that join such conditions."""
    policy = project(loaded.strategy, loaded.domain, max_rules=max_rules)
    moves = _moves(loaded)
    full: dict[tuple[str, tuple[tuple[str, str], ...]], set[Move]] = {}
    for region, cond, move in moves:
        full.setdefault((region, tuple(sorted(cond.items()))), set()).add(move)
    joined: set[int] = set()
    for region, cond, _ in moves:
        k = _matching(policy, region, cond)[0]
        rule = policy.rules[k]
        if {m for m, _ in rule.moves} != full[(region, tuple(sorted(cond.items())))]:
            joined.add(k)
    assert joined == {k for k, r in enumerate(policy.rules) if not r.exact}
    assert all(r.when().startswith("~ ") != r.exact for r in policy.rules)
    if max_rules is None:
        assert not joined
    assert len(policy.rules) <= len(full)
    for region, used in policy.variables.items():
        tested = {name for r in policy.rules if r.region == region for name, _ in r.condition}
        assert set(used) == tested


def test_rows_name_only_the_spec(loaded: Session) -> None:
    model = loaded.domain.model
    regions = {r.name for r in model.regions}
    gaits = {g.name for g in model.gaits} | {"noGait"}
    legs = {leg.name for leg in model.legs}
    goals = {g.label for g in loaded.domain.goals}
    hazards = {h.name for h in model.hazards} | {"none"}
    policy = project(loaded.strategy, loaded.domain)
    assert policy.rules
    for rule in policy.rules:
        assert rule.region in regions
        assert {m.gait for m, _ in rule.moves} <= gaits
        assert {m.target for m, _ in rule.moves} <= regions
        for name, values in rule.condition:
            allowed = (
                goals
                if name == "goal"
                else hazards
                if name == "hazard"
                else ({"healthy", "degraded", "failed"} if name in legs else set())
            )
            assert values and set(values) <= allowed, (name, values)


def _bfs(strategy: Strategy, k: int) -> dict[int, int]:
    dist = {n: 0 for n in strategy.initial}
    layer = sorted(dist)
    for step in range(1, k + 1):
        layer = sorted({s for n in layer for s in strategy.successors[n] if s not in dist})
        dist.update({n: step for n in layer})
    return dist


@pytest.mark.parametrize("k", [0, 1, 3, 5])
def test_the_k_step_view_has_exactly_the_nodes_within_k_moves(loaded: Session, k: int) -> None:
    strategy = _explicit(loaded)
    view = steps_view(strategy, loaded.domain, k, cap=10**6)
    dist = _bfs(strategy, k)
    assert view.depth == dist
    edges = {(n, s) for n in dist if dist[n] < k for s in strategy.successors[n]}
    assert set(view.edges) == edges
    drawn = {n.get_name() for n in view.graph.get_nodes()} - {"start", "node", "edge"}
    assert drawn == {f"n{n}" for n in dist}
    total = sum(len(set(s)) for s in strategy.successors)
    assert (
        f"cut {len(strategy) - len(dist)} of {len(strategy)} nodes and "
        f"{total - len(edges)} of {total} edges"
    ) in view.notes[0]


def test_the_k_step_view_stops_at_the_node_cap(loaded: Session) -> None:
    view = steps_view(loaded.strategy, loaded.domain, 10, cap=5)
    assert len(view.depth) == 5 and "node cap 5" in view.notes[0]
    dist = _bfs(_explicit(loaded), 10)
    assert all(dist[n] == d for n, d in view.depth.items())


def test_views_are_smaller_than_the_automaton(loaded: Session) -> None:
    strategy = _explicit(loaded)
    policy = project(strategy, loaded.domain)
    assert len(policy.rules) < len(strategy)
    assert len(steps_view(strategy, loaded.domain).depth) < len(strategy)


def test_output_is_deterministic() -> None:
    first, second = session(PATROL, None), session(PATROL, None)
    assert first is not None and second is not None
    a, b = (project(s.strategy, s.domain) for s in (first, second))
    assert a.text() == b.text() and a.markdown() == b.markdown() and a.html() == b.html()
    assert policy_view(a, first.domain).dot() == policy_view(b, second.domain).dot()
    assert (
        steps_view(first.strategy, first.domain).dot()
        == steps_view(second.strategy, second.domain).dot()
    )


def test_the_policy_shows_itself_in_a_notebook() -> None:
    s = session(PATROL, None)
    assert s is not None
    policy = project(s.strategy, s.domain)
    assert policy._repr_html_().startswith("<table>")
    assert policy._repr_markdown_().startswith("| region | when |")
    assert str(policy) == policy.text()
    # the hazard patrol walks east_b to ne and stays there until the goal changes; it never
    # waits for the hazard to go (its cell se is off the way, and each goal is forced
    # whatever the hazard does: the attractor's strategy, gaitc.solver.game)
    text = policy.text()
    assert "nw      heading for ne  east_b → ne (12)" in text
    assert "ne      heading for ne  noGait (stays) (8)" in text
    assert "hazard" not in text


@pytest.fixture(scope="module")
def symbolic(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("sym") / "patrol.json"
    spec = gaitc.load(PATROL)
    gaitc.synthesize(spec, form="symbolic", verify=False).save(str(path))
    return str(path)


def test_a_symbolic_controller_projects_as_its_explicit_twin(symbolic: str) -> None:
    sym, expl = session(PATROL, symbolic), session(PATROL, None)
    assert sym is not None and expl is not None
    assert not isinstance(sym.strategy, Strategy)
    bounded = controller_policy(sym.strategy, sym.domain)
    assert bounded.rows() == project(expl.strategy, expl.domain).rows()
    assert bounded.notes == (
        "the controller is symbolic: projected from all 22 nodes a run can reach",
    )
    near = controller_policy(sym.strategy, sym.domain, steps=1)
    assert near.nodes == 4 and "the 4 nodes within 1 move of the start" in near.notes[0]
    view = steps_view(sym.strategy, sym.domain, 3)
    twin = steps_view(expl.strategy, expl.domain, 3)
    assert len(view.depth) == len(twin.depth) and len(view.edges) == len(twin.edges)
    assert "symbolic" in view.notes[0]


def test_cli_render_policy(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], symbolic: str
) -> None:
    assert main(["render", "policy", PATROL]) == 0
    out = capsys.readouterr().out
    assert out.startswith("region  when") and "6 rules" in out
    for name in ("p.md", "q.md", "p.html", "p.dot"):
        assert main(["render", "policy", PATROL, "-o", str(tmp_path / name)]) == 0
    assert (tmp_path / "p.md").read_bytes() == (tmp_path / "q.md").read_bytes()
    assert (tmp_path / "p.md").read_text().startswith("| region |")
    assert (tmp_path / "p.html").read_text().startswith("<table>")
    assert "digraph" in (tmp_path / "p.dot").read_text()
    assert main(["render", "policy", PATROL, "--steps", "1"]) == 0
    assert "within 1 move of the start" in capsys.readouterr().out
    assert main(["render", "policy", PATROL, symbolic]) == 0
    assert "the controller is symbolic" in capsys.readouterr().out
    assert main(["render", "policy", PATROL, "--steps", "-2"]) == 2
    assert "--steps must be 0 or more" in capsys.readouterr().err
    assert main(["render", "policy", PATROL, "--format", "png"]) == 2
    assert "give -o FILE" in capsys.readouterr().err
    assert main(["render", "policy", PATROL, "--max-rules", "0"]) == 2
    assert "--max-rules must be at least 1" in capsys.readouterr().err
    assert main(["render", "policy", PATROL, "--max-rules", "1"]) == 0
    out = capsys.readouterr().out
    assert "3 rules" in out and "the rules marked ~ in nw, ne, sw" in out


def test_cli_render_automaton_steps(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], symbolic: str
) -> None:
    out = tmp_path / "a.dot"
    assert main(["render", "automaton", PATROL, "--steps", "2", "-o", str(out)]) == 0
    assert "the first 2 steps from 2 initial nodes" in capsys.readouterr().err
    text = out.read_text()
    assert "step 2" in text and "step 3" not in text
    assert (
        main(
            ["render", "automaton", PATROL, symbolic, "--steps", "2", "-o", str(tmp_path / "s.dot")]
        )
        == 0
    )
    assert "symbolic" in capsys.readouterr().err
    assert main(["render", "automaton", PATROL, "--steps", "-1", "-o", str(out)]) == 2
    assert "--steps must be 0 or more" in capsys.readouterr().err
    assert main(["render", "automaton", PATROL, "--steps", "three", "-o", str(out)]) == 2
    assert "invalid int value: 'three'" in capsys.readouterr().err
    assert (
        main(
            ["render", "automaton", PATROL, "--steps", "2", "--quotient", "region", "-o", str(out)]
        )
        == 2
    )
    assert main(["render", "automaton", PATROL, "-o", str(out)]) == 0  # the full view stays


@pytest.mark.graphviz
@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' is not installed")
def test_the_policy_picture_has_a_table_per_region(tmp_path: Path) -> None:
    s = session(PATROL, None)
    assert s is not None
    policy = project(s.strategy, s.domain)
    root = ET.fromstring(policy_view(policy, s.domain).svg())
    titles = {
        t.text
        for g in root.iter(f"{SVG}g")
        if g.get("class") == "node"
        for t in g.iter(f"{SVG}title")
    }
    assert titles == set(policy.regions)
    assert main(["render", "policy", PATROL, "-o", str(tmp_path / "p.png")]) == 0
    assert (tmp_path / "p.png").read_bytes()[:4] == b"\x89PNG"


def test_the_policy_picture_puts_each_table_where_the_map_puts_its_region() -> None:
    s = session(PATROL, None)
    assert s is not None
    picture = policy_view(project(s.strategy, s.domain), s.domain)
    pos = {
        n.get_name().strip('"'): tuple(float(v) for v in n.get("pos").strip('"!').split(","))
        for n in picture.graph.get_nodes()
        if n.get("pos")
    }
    assert set(pos) == {"nw", "ne", "sw"}  # the robot never enters the hazard cell se
    assert pos["nw"][0] < pos["ne"][0] and pos["nw"][1] == pos["ne"][1]  # ne east of nw
    assert pos["sw"][1] < pos["nw"][1] and pos["sw"][0] == pos["nw"][0]  # sw south of nw


@pytest.mark.skipif(shutil.which("dot") is None, reason="needs Graphviz")
def test_a_picture_too_tall_for_a_bitmap_is_refused_not_shrunk(tmp_path: Path) -> None:
    """Issue 60: Graphviz scaled a 32,767 px strip down to unreadable text, saying so only
    on its standard error; the PNG is refused with the remedy, and no file is written,
    while SVG keeps the picture at its natural size."""
    import pydot

    from gaitc.sim.graphics import Picture

    graph = pydot.Dot("tall", graph_type="digraph")
    graph.set_node_defaults(shape="box", height="3")  # 150 of them: 42,000 px at 96 dpi
    for k in range(150):
        graph.add_edge(pydot.Edge(f"n{k}", f"n{k + 1}"))
    picture = Picture(graph)
    out = tmp_path / "tall.png"
    with pytest.raises(gaitc.UsageError) as caught:
        picture.save(out)
    assert str(caught.value).startswith(
        "the picture is too large for a PNG image (at most 32,767 pixels a side): Graphviz "
        "would shrink it to ")
    assert str(caught.value).endswith(" and its text would be unreadable; write it as SVG "
                                      "or PDF (-o FILE.svg), which have no such limit")
    assert not out.exists()
    assert picture.save(tmp_path / "tall.svg") == "svg"
    height = ET.parse(tmp_path / "tall.svg").getroot().get("height")
    assert height is not None and float(height.removesuffix("pt")) > 32767 * 0.75
