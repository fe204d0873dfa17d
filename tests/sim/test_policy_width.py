"""Policy pictures stay readable (issue 51): a compact controller's rules and a projected
controller's region tables are drawn at their natural font size, no wider than a screen, on
the shipped thesis robots and a wide 5-leg robot, and every rule a run uses is in them.

Widths are measured on what Graphviz writes: the PNG header (pixels, at its default 96 dpi)
and the SVG's width (points).
"""

from __future__ import annotations

import html
import re
import struct
from pathlib import Path

import pytest

import gaitc
from gaitc.api.drawing import compact_rules, controller_policy, draw_policy, draw_rules
from gaitc.compact.rules import RuleTables
from gaitc.sim.graphics import Picture, have_dot
from gaitc.sim.policy_view import (
    MAX_WIDTH,
    MOVE_WRAP,
    RULE_WRAP,
    WHAT_WRAP,
    WHEN_WRAP,
    wrap,
)

pytestmark = pytest.mark.skipif(not have_dot(), reason="Graphviz's dot is not installed")

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "gaitc" / "examples"
MAX_PX = 1600  # a screen's width at the default 96 dpi
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
SPECS = ["thesis_robot_a", "thesis_robot_b", "corridor_hazard", "wide5"]


@pytest.fixture(scope="module")
def paths(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    out = {name: EXAMPLES / f"{name}.gait" for name in SPECS if name != "wide5"}
    wide = tmp_path_factory.mktemp("wide") / "wide5.gait"
    wide.write_text(WIDE5, encoding="utf-8")
    out["wide5"] = wide
    return out


def _png_width(picture: Picture) -> int:
    data = picture.render("png")
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    width: int = struct.unpack(">II", data[16:24])[0]
    return width


def _svg(picture: Picture) -> tuple[float, list[str], list[float]]:
    """The SVG's width in points, its text lines and its font sizes."""
    text = picture.svg()
    found = re.search(r'<svg width="([0-9.]+)pt"', text)
    assert found is not None
    found_text = re.findall(r"<text[^>]*>([^<]*)</text>", text)
    lines = [html.unescape(t).replace("\xa0", " ") for t in found_text]
    sizes = [float(s) for s in re.findall(r'font-size="([0-9.]+)"', text)]
    return float(found.group(1)), lines, sizes


def _bounded(picture: Picture) -> list[str]:
    """The picture's text lines, after checking its width and fonts."""
    assert "size=" not in picture.dot().replace("fontsize=", "")  # never scaled to fit
    assert _png_width(picture) <= MAX_PX
    width, lines, sizes = _svg(picture)
    assert width <= MAX_PX * 72 / 96
    assert sizes and min(sizes) >= 9.0
    return lines


@pytest.mark.parametrize("name", SPECS)
def test_the_compact_policy_picture_is_bounded_and_lists_every_used_rule(
        paths: dict[str, Path], name: str) -> None:
    tables = compact_rules(paths[name])
    assert isinstance(tables, RuleTables)
    lines = _bounded(draw_rules(tables))
    for label, rules in tables.goals:
        assert any(label in line for line in lines)
        for rule in tables.shown(rules):
            assert rule.used
            for line in [*wrap(rule.when, RULE_WRAP), *wrap(rule.said, MOVE_WRAP)]:
                assert line in lines, line


def test_the_compact_picture_marks_never_used_rules_only_when_asked() -> None:
    shuttle = EXAMPLES / "shuttle_2leg.gait"
    tables = compact_rules(shuttle)
    marked = compact_rules(shuttle, all_rules=True)
    assert tables is not None and marked is not None and tables.never_used == 1
    _, lines, _ = _svg(draw_rules(tables))
    _, all_lines, _ = _svg(draw_rules(marked))
    assert not any("never used" in line for line in lines)
    assert "west to a  (never used)" in all_lines


@pytest.mark.parametrize("name", SPECS)
def test_the_projected_policy_picture_is_bounded_and_lists_every_rule(
        paths: dict[str, Path], name: str, tmp_path: Path) -> None:
    spec = gaitc.load(paths[name])
    made = gaitc.synthesize(spec, form="symbolic")
    assert made.controller is not None
    found = controller_policy(spec, made.controller)
    assert found is not None
    policy, bound = found
    picture = draw_policy(policy, bound)
    lines = _bounded(picture)
    for rule in policy.rules:
        for line in [*wrap(rule.when(), WHEN_WRAP), *wrap(rule.what(), WHAT_WRAP)]:
            assert line in lines, line
    rowed = any("drawn in rows" in note for note in picture.notes)
    if name == "corridor_hazard":  # five tables side by side would be about 25 inches wide
        assert rowed


def test_wrapping_keeps_the_text_and_the_width() -> None:
    text = "heading for r12, L1 degraded, L2 healthy, L4 healthy, L5 healthy, L8 healthy"
    lines = wrap(text, 30)
    assert " ".join(lines) == text
    assert all(len(line) <= 30 for line in lines) and len(lines) == 3
    assert wrap("a-single-part-longer-than-the-width", 10) == [
        "a-single-part-longer-than-the-width"]
    assert MAX_WIDTH * 96 <= MAX_PX
