"""The terminal view of a run: a step table (leg health coloured when stdout is a terminal)
and the summary of goals, caches, failed legs and whether the spec held.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TextIO

from gaitc.sim.events import Surprise
from gaitc.sim.run import Run, Step, Summary

_RESET = "\033[0m"
_COLOURS = {"healthy": "\033[34m", "degraded": "\033[33m", "failed": "\033[31m",
            "bold": "\033[1m", "green": "\033[32m", "dim": "\033[2m"}


def use_colour(stream: TextIO) -> bool:
    """Colour only on a terminal, and never when NO_COLOR is set or TERM is dumb."""
    if os.environ.get("NO_COLOR") or os.environ.get("TERM") == "dumb":
        return False
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty())


class _Style:
    def __init__(self, colour: bool) -> None:
        self.colour = colour

    def __call__(self, text: str, *names: str) -> str:
        if not self.colour or not names:
            return text
        return "".join(_COLOURS[n] for n in names) + text + _RESET


def _health_cell(step: Step, leg: str, full: int, style: _Style) -> str:
    level = step.level(leg)
    kind = "healthy" if level >= full else ("failed" if level == 1 else "degraded")
    used = leg in step.legs_used
    text = f"{level}{'*' if used else ' '}"
    if leg in step.failed:
        text = f"{level}!"
    elif leg in step.degraded:
        text = f"{level}↓"
    return style(text, kind, *(("bold",) if used else ()))


def step_table(run: Run, full: dict[str, int] | None = None, colour: bool = False,
               steps: Sequence[Step] | None = None) -> str:
    """The steps of ``run`` as an aligned table; ``*`` marks legs in use, ``!`` (``↓``) a leg
    that this step's gait fails (degrades): its level drops on the next row."""
    style = _Style(colour)
    rows = list(run.steps if steps is None else steps)
    legs = list(run.legs)
    if full is None:
        full = {leg: max((s.level(leg) for s in rows), default=1) for leg in legs}
    table = [["step", "region", "gait", "legs used", *legs, "hazard", "goal"]]
    for s in rows:
        table.append([str(s.index), s.region, s.gait, ",".join(s.legs_used) or "-",
                      *[str(s.level(leg)) for leg in legs], s.hazard or "-",
                      ",".join(s.goals) or ""])
    widths = [max(len(r[i]) for r in table) for i in range(len(table[0]))]
    for i in range(4, 4 + len(legs)):
        widths[i] = max(widths[i], 2)
    lines = []
    header = "  ".join(cell.ljust(w) for cell, w in zip(table[0], widths, strict=True))
    lines.append(style(header.rstrip(), "bold"))
    for s, row in zip(rows, table[1:], strict=True):
        cells = []
        for i, (cell, w) in enumerate(zip(row, widths, strict=True)):
            if 4 <= i < 4 + len(legs):
                leg = legs[i - 4]
                cells.append(_health_cell(s, leg, full[leg], style)
                             + " " * max(0, w - 2))
            elif i == len(row) - 1 and cell:
                cells.append(style(cell.ljust(w), "green"))
            else:
                cells.append(cell.ljust(w))
        lines.append("  ".join(cells).rstrip())
    return "\n".join(lines)


def _counts(items: Sequence[tuple[str, int]]) -> str:
    return ", ".join(f"{name} ×{count}" for name, count in items) or "(none)"


def _when(leg: str, steps: list[int], shown: int = 4) -> str:
    more = ", ..." if len(steps) > shown else ""
    listed = ", ".join(map(str, steps[:shown])) + more
    times = f" ×{len(steps)}" if len(steps) > 1 else ""
    return f"{leg}{times} (step{'s' if len(steps) > 1 else ''} {listed})"


def summary_text(summary: Summary, environment: str = "", colour: bool = False) -> str:
    """The summary of a run, as a few indented lines."""
    style = _Style(colour)
    ok, bad = style("held at every step", "green"), style("VIOLATED", "failed", "bold")
    by_leg: dict[str, list[int]] = {}
    for index, leg in summary.legs_failed:
        by_leg.setdefault(leg, []).append(index)
    failed = ", ".join(_when(leg, idx) for leg, idx in by_leg.items())
    plural = "s" * (summary.steps != 1)
    lines = [f"summary: {summary.steps} step{plural}" + (f", environment {environment}"
                                                        if environment else ""),
             f"  goals visited:   {_counts(summary.goal_visits)}",
             f"  caches visited:  {_counts(summary.cache_visits)}",
             f"  legs failed:     {failed or '(none)'}",
             f"  degradations:    {len(summary.legs_degraded)}",
             f"  assumptions:     {ok if summary.assumptions_held else bad}",
             f"  guarantees:      {ok if summary.guarantees_held else bad}"]
    lines.extend(f"    {v}" for v in summary.violations)
    for what, items in (("assumed", summary.env_liveness), ("guaranteed", summary.sys_liveness)):
        for rule, count in items:
            lines.append(f"  □◇ {what}: {rule}: held on {count} step{'s' * (count != 1)}")
    if summary.stopped:
        lines.append(f"  stopped early: {summary.stopped}")
    return "\n".join(lines)


def surprises_text(surprises: Sequence[Surprise]) -> str:
    """The events the environment performed along a run, one line each with its outcome."""
    lines = ["surprises:"]
    for s in surprises:
        lines.append(f"  {s.words()}")
        if s.line:
            lines.append(f"    broken: {s.clause} ({s.line})")
    return "\n".join(lines)
