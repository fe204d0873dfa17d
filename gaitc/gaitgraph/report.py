"""Gait reports: the text table printed by ``gaitc gaits`` and its JSON file (sorted keys,
rounded numbers, so the same robot, method and seed give the same bytes)."""

from __future__ import annotations

import json
from typing import Any

from gaitc.diagnostics.versions import GAITS
from gaitc.gaitgraph.cycles import GaitCycle
from gaitc.gaitgraph.kinematics import body_length
from gaitc.gaitgraph.robot import Robot
from gaitc.gaitgraph.search import SearchResult


def _grouped(robot: Robot, valves: str) -> str:
    parts = []
    for leg in robot.legs:
        parts.append(valves[leg.first_valve : leg.first_valve + len(leg.chambers)])
    return " ".join(parts)


def gait_table(robot: Robot, gaits: list[GaitCycle], limit: int = 10) -> str:
    """Rank, valve sequence (chambers grouped by leg), displacement, rotation, slip."""
    lines = [
        f"{'rank':>4}  {'dx mm':>8} {'dy mm':>8} {'rot deg':>8} {'slip mm':>8}  valve sequence"
    ]
    for rank, g in enumerate(gaits[:limit], 1):
        seq = " | ".join(_grouped(robot, v) for v in g.valves)
        lines.append(
            f"{rank:>4}  {g.displacement[0]:8.1f} {g.displacement[1]:8.1f} {g.rotation:8.2f} "
            f"{g.slip:8.2f}  {seq}"
        )
    return "\n".join(lines)


def _r(x: float) -> float:
    value = round(x, 3)
    return 0.0 if value == 0 else value


def gaits_json(robot: Robot, result: SearchResult, direction: str, seed: int) -> str:
    """JSON document of a search: robot, method, and per gait its poses and motions."""
    return json.dumps(gaits_document(robot, result, direction, seed), indent=2,
                      sort_keys=True) + "\n"


def gaits_document(robot: Robot, result: SearchResult, direction: str, seed: int
                   ) -> dict[str, Any]:
    """The search as a JSON object (the gaits file, and ``gaitc gaits --json``)."""
    gaits: list[dict[str, Any]] = []
    for rank, g in enumerate(result.gaits, 1):
        gaits.append(
            {
                "rank": rank,
                "valves": list(g.valves),
                "poses": [{"valves": v, "contacts": list(c)} for v, c in g.keys],
                "transitions": [
                    {
                        "dx": _r(m.dx),
                        "dy": _r(m.dy),
                        "rotation": _r(m.rotation),
                        "slip": _r(m.slip),
                        "condition": m.condition,
                    }
                    for m in g.motions
                ],
                "displacement": [_r(g.displacement[0]), _r(g.displacement[1])],
                "rotation": _r(g.rotation),
                "slip": _r(g.slip),
                "score": _r(g.score),
            }
        )
    doc = {
        "format": GAITS.version,
        "robot": robot.name,
        "valve_legs": list(robot.leg_of_valve),
        "body_length": _r(body_length(robot)),
        "method": str(result.method),
        "direction": direction,
        "seed": seed,
        "valve_states_evaluated": result.states_added,
        "units": {"length": "mm", "angle": "deg"},
        "gaits": gaits,
    }
    return doc


def search_document(robot: Robot, result: SearchResult, direction: str, seed: int
                    ) -> dict[str, Any]:
    """``gaitc gaits --json``: the gaits file's object plus the size of the search."""
    return {**gaits_document(robot, result, direction, seed),
            "chambers": robot.valve_count, "poses": len(result.graph),
            "transitions": len(result.graph.edges), "limit_reached": result.limit_reached}
