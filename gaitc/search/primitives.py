"""A ``.gait`` gait's ``primitive`` clause as a valve sequence, searched as ``gaitc gaits`` does.

A clause naming a robot file and a direction is resolved by the search
:func:`gaitc.gaits` runs for that robot file (:mod:`gaitc.search.registry`): the gait graph
of the chapter 4 model the file's ``model:`` section declares, restricted to the legs the
gait uses (only their valves open, each of them pressurised, the first one named first), so
``gaitc gaits ROBOT.yaml --direction D --legs L1,L2`` prints the same valve sequence first.
A gait the robot file stores for those legs and that direction still comes first, as it
does for robots without a model, and ``method reset`` asks for the kinematic graph's reset
edges, which a model has not.  Everything else (inline valves, robot files without a model)
is :func:`gaitc.gaitgraph.pairing.resolve_primitive`'s.

When the gait's legs cannot move that way in the model, the error says which legs do.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from gaitc.core.modes import SearchMethod
from gaitc.diagnostics import Diagnostic, SpecSemanticError
from gaitc.gaitgraph import pairing
from gaitc.gaitgraph.cycles import parse_direction
from gaitc.gaitgraph.pairing import ValveSequence
from gaitc.gaitgraph.robot import load_robot
from gaitc.models.catalogue import load_model
from gaitc.search.registry import direction_search, legs_sentence, pressurised
from ltlcompiler.model import Gait

__all__ = ["check_gaits", "resolve_primitive"]


def resolve_primitive(
    gait: Gait, spec_dir: str, legs: Sequence[str] | None = None, seed: int = 0
) -> ValveSequence:
    """The valve sequence bound to ``gait`` (see the module's docstring); ``legs`` is the
    spec's leg order, for inline valves without a robot file."""
    prim = gait.primitive
    if prim is None or prim.valves or prim.direction is None:
        return pairing.resolve_primitive(gait, spec_dir, legs, seed)
    path = pairing.robot_path(gait, spec_dir)
    if path is None:
        return pairing.resolve_primitive(gait, spec_dir, legs, seed)
    robot = load_robot(path)
    method = SearchMethod.parse(prim.method) if prim.method is not None else None
    if not robot.models or method is SearchMethod.RESET:
        return pairing.resolve_primitive(gait, spec_dir, legs, seed)
    kept = pairing.stored_gait(robot, gait, any_legs=False)
    if kept is not None:
        return kept
    return model_primitive(gait, path, robot.models[0], method, seed)


def model_primitive(gait: Gait, path: Path, model: str, method: SearchMethod | None = None,
                    seed: int = 0) -> ValveSequence:
    """The best gait of ``gait``'s legs toward its primitive's direction in the chapter 4
    ``model`` of the robot file ``path``, as :func:`gaitc.gaits` with those legs finds it."""
    prim = gait.primitive
    assert prim is not None and prim.direction is not None and prim.robot is not None
    span = prim.span or gait.span
    direction = parse_direction(prim.direction, span)
    loaded = load_model(model, path)
    fired = gait.firing_order
    unknown = [leg for leg in fired if leg not in loaded.valve_legs]
    if unknown:
        raise SpecSemanticError(
            f"gait {gait.name} uses {', '.join(unknown)}, which robot {loaded.robot} does not "
            f"have (its legs: {', '.join(dict.fromkeys(loaded.valve_legs))})",
            span, "robot legs are matched to spec legs by name")
    search = direction_search(method)
    found = search.model(loaded, direction, seed=seed, legs=fired)
    if found.gaits:
        label = f"{model} model, {prim.direction}"
        return ValveSequence(found.gaits[0].valves, loaded.valve_legs,
                             f"synthesised ({label})")
    anyone = search.model(loaded, direction, seed=seed)
    movers = pressurised(anyone.gaits[0], loaded.valve_legs) if anyone.gaits else ()
    if movers:
        hint = (f"let the gait use legs {', '.join(movers)}, pick another direction, or give "
                "the valve sequence inline")
    else:
        hint = ("the model moves no gait that way: 'gaitc gaits' with --max-open 2 searches "
                "more valve states, or give the valve sequence inline")
    where = f"{prim.robot}'s {model} model"
    raise SpecSemanticError(
        f"gait {gait.name}: {legs_sentence(fired, prim.direction, where, movers)}", span, hint)


def check_gaits(
    gaits: Sequence[Gait], spec_dir: str, legs: Sequence[str] | None = None,
    moves: Mapping[str, frozenset[tuple[str, str]]] | None = None,
) -> list[Diagnostic]:
    """``gaitc lint``'s check of the gaits' primitives
    (:func:`gaitc.gaitgraph.pairing.check_gaits`), each resolved by :func:`resolve_primitive`."""
    return pairing.check_gaits(gaits, spec_dir, legs, moves, resolve=resolve_primitive)
