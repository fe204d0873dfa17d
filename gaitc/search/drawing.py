"""Pictures of the chapter 5 searches as standalone SVG: explored cells, trajectories, goal.

:func:`plan_svg` draws one plan (the cell centres the search explored, the predicted chassis
path, the goal's tolerance disc); :func:`learning_svg` draws an online run (the first and the
final predicted paths, what the robot really did each iteration, and the transitions whose
predictions changed).  x points right, y up, millimetres, equal scale.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from gaitc.search.plans import GaitPlan

Point = tuple[float, float]
_COLOURS = ("#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22")


class _Canvas:
    def __init__(self, points: Sequence[Point], width: float = 520.0, pad: float = 30.0) -> None:
        xs = [p[0] for p in points] or [0.0]
        ys = [p[1] for p in points] or [0.0]
        self.x0, self.x1 = min(xs), max(xs)
        self.y0, self.y1 = min(ys), max(ys)
        span = max(self.x1 - self.x0, self.y1 - self.y0, 1.0)
        self.scale = (width - 2 * pad) / span
        self.pad = pad
        self.width = width
        self.height = (self.y1 - self.y0) * self.scale + 2 * pad + 68
        self.parts: list[str] = []

    def pt(self, p: Point) -> tuple[float, float]:
        return (
            self.pad + (p[0] - self.x0) * self.scale,
            self.pad + (self.y1 - p[1]) * self.scale,
        )

    def dots(self, points: Sequence[Point], colour: str, r: float = 1.5) -> None:
        for p in points:
            x, y = self.pt(p)
            self.parts.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r}" fill="{colour}"/>')

    def line(self, points: Sequence[Point], colour: str, dash: str = "", w: float = 2) -> None:
        if len(points) < 2:
            return
        path = " ".join("{:.1f},{:.1f}".format(*self.pt(p)) for p in points)
        extra = f' stroke-dasharray="{dash}"' if dash else ""
        self.parts.append(
            f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="{w}"{extra}/>'
        )

    def disc(self, centre: Point, radius: float, colour: str) -> None:
        x, y = self.pt(centre)
        self.parts.append(
            f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{radius * self.scale:.1f}" fill="{colour}" '
            'fill-opacity="0.25" stroke="#333"/>'
        )

    def text(self, row: int, words: str) -> None:
        y = self.height - 34 + 14 * row
        self.parts.append(
            f'<text x="6" y="{y:.0f}" font-family="monospace" font-size="11">{_esc(words)}</text>'
        )

    def svg(self) -> str:
        head = (
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{self.width:.0f}" '
            f'height="{self.height:.0f}"><rect width="100%" height="100%" fill="white"/>'
        )
        return "\n".join([head, *self.parts, "</svg>"]) + "\n"


def _esc(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _frame(goal: Point, radius: float, *groups: Sequence[Point]) -> list[Point]:
    pts: list[Point] = [(0.0, 0.0), (goal[0] + radius, goal[1] + radius)]
    pts.append((goal[0] - radius, goal[1] - radius))
    for g in groups:
        pts.extend(g)
    return pts


def plan_svg(plan: GaitPlan) -> str:
    """Explored cells (grey), predicted path (blue, one dot per pose), goal (green disc)."""
    goal = (plan.goal.dx, plan.goal.dy)
    path = [(x, y) for x, y, _ in plan.trajectory()]
    canvas = _Canvas(_frame(goal, plan.goal.tolerance, path, plan.explored))
    canvas.dots(plan.explored, "#bbb", 1.2)
    canvas.disc(goal, plan.goal.tolerance, "#2ca02c")
    canvas.line(path, "#1f77b4")
    canvas.dots(path, "#1f77b4", 3)
    canvas.dots([(0.0, 0.0)], "black", 4)
    x, y, th = plan.displacement
    canvas.text(
        0,
        f"{plan.method} {plan.robot}: {len(plan.steps)} transitions, "
        f"{len(plan.explored)} explored cells",
    )
    canvas.text(1, f"predicted {x:.1f} mm, {y:.1f} mm, {th:.1f} deg; goal {plan.goal}")
    return canvas.svg()


def learning_svg(
    first: GaitPlan,
    final: GaitPlan,
    executed: Sequence[Sequence[Point]],
    changed: Sequence[tuple[Point, Point]],
) -> str:
    """An online run: first plan (dashed grey), final plan (blue), each executed cycle
    (coloured, measured), and for changed transitions the predicted (red) and measured
    (black) end of the step, joined."""
    goal = (final.goal.dx, final.goal.dy)
    first_path = [(x, y) for x, y, _ in first.trajectory()]
    final_path = [(x, y) for x, y, _ in final.trajectory()]
    flat = [p for run in executed for p in run] + [p for pair in changed for p in pair]
    canvas = _Canvas(_frame(goal, final.goal.tolerance, first_path, final_path, flat))
    canvas.dots(final.explored, "#ddd", 1.2)
    canvas.disc(goal, final.goal.tolerance, "#2ca02c")
    canvas.line(first_path, "#999", "5,4")
    for i, run in enumerate(executed):
        canvas.line(run, _COLOURS[i % len(_COLOURS)], "", 1)
    for predicted, measured in changed:
        canvas.line([predicted, measured], "#d62728", "2,2", 1)
        canvas.dots([measured], "black", 2)
    canvas.line(final_path, "#1f77b4", "", 2.5)
    canvas.dots(final_path, "#1f77b4", 3)
    canvas.dots([(0.0, 0.0)], "black", 4)
    canvas.text(-2, "grey dashed: first plan; blue: final plan; green: goal; thin: each")
    canvas.text(-1, "executed cycle; red dotted: predicted step end -> measured (black)")
    canvas.text(
        0,
        f"{final.method} {final.robot}: {len(executed)} executed cycles, "
        f"{len(changed)} changed predictions",
    )
    x, y, th = final.displacement
    canvas.text(1, f"final gait predicts {x:.1f} mm, {y:.1f} mm, {th:.1f} deg; goal {final.goal}")
    return canvas.svg()
