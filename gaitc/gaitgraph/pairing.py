"""Pairing a spec's gaits with valve sequences, and the lint checks that they agree.

A gait's primitive is an inline valve sequence or a robot file plus a direction (and
method).  Inline valves without a robot file are read as one valve per leg, in the order
the legs are declared in the spec.  The legs a primitive pressurises must be exactly the
legs the spec says the gait uses, since the health reasoning (eq. 3.5) relies on that map.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from gaitc.diagnostics import Diagnostic, GaitcError, SpecSemanticError
from gaitc.gaitgraph.cycles import parse_direction
from gaitc.gaitgraph.robot import Robot, load_robot, parse_valves
from gaitc.gaitgraph.search import search
from ltlcompiler.model import Gait, GaitKind


@dataclass(frozen=True)
class ValveSequence:
    """A repeating sequence of valve states and the leg owning each valve position."""

    states: tuple[str, ...]
    leg_of_valve: tuple[str, ...]
    source: str  # "inline", "robot file gait <name>" or "synthesised (<method>, <direction>)"

    def pressurised_legs(self) -> tuple[str, ...]:
        """Legs with a chamber open in some state, in valve order."""
        out: list[str] = []
        for i, leg in enumerate(self.leg_of_valve):
            if leg not in out and any(s[i] == "1" for s in self.states):
                out.append(leg)
        return tuple(out)


def _leg_order(gaits: Sequence[Gait], legs: Sequence[str] | None) -> tuple[str, ...]:
    if legs is not None:
        return tuple(legs)
    order: list[str] = []
    for g in gaits:
        for leg in g.legs:
            if leg not in order:
                order.append(leg)
    return tuple(order)


def robot_path(gait: Gait, spec_dir: str) -> Path | None:
    """The robot file ``gait``'s primitive names (relative to ``spec_dir``), None when it
    names none; a missing file or a folder is a :class:`SpecSemanticError` at the clause."""
    prim = gait.primitive
    if prim is None or prim.robot is None:
        return None
    path = Path(prim.robot)
    if not path.is_absolute():
        path = Path(spec_dir) / path
    try:
        folder = path.is_dir()
        found = path.is_file()
    except (OSError, ValueError):  # a name too long for the system, or holding a NUL
        folder = found = False
    if folder:
        raise SpecSemanticError(f"gait {gait.name}: robot file {prim.robot!r} is a folder",
                                prim.span or gait.span)
    if not found:
        raise SpecSemanticError(
            f"gait {gait.name}: robot file {prim.robot!r} not found (looked for {str(path)!r})",
            prim.span or gait.span,
            "robot paths are relative to the .gait file",
        )
    return path


def _robot(gait: Gait, spec_dir: str) -> Robot | None:
    path = robot_path(gait, spec_dir)
    return None if path is None else load_robot(path)


def stored_gait(robot: Robot, gait: Gait, any_legs: bool = True) -> ValveSequence | None:
    """The robot file's stored gait for ``gait``'s primitive (one without a method): the
    first towards its direction with the gait's legs, else (``any_legs``) the first towards
    its direction at all; None when there is none."""
    prim = gait.primitive
    if prim is None or prim.method is not None or prim.direction is None:
        return None
    stored = [g for g in robot.gaits if g.direction == prim.direction]
    same = [g for g in stored if set(g.legs) == set(gait.legs)]
    chosen = same or (stored if any_legs else [])
    if not chosen:
        return None
    return ValveSequence(chosen[0].valves, robot.leg_of_valve, f"robot file gait {chosen[0].name}")


def resolve_primitive(
    gait: Gait, spec_dir: str, legs: Sequence[str] | None = None, seed: int = 0
) -> ValveSequence:
    """The valve sequence bound to ``gait`` over the chapter 2 kinematic graph; synthesises
    one when only a direction is given.  (:func:`gaitc.search.primitives.resolve_primitive`
    searches a robot file's declared chapter 4 model first, and comes here otherwise.)

    ``legs`` is the spec's leg declaration order (needed for inline valves without a robot
    file; by default the order in which the gait's legs appear).
    """
    prim = gait.primitive
    span = (prim.span if prim is not None else None) or gait.span
    if prim is None:
        raise SpecSemanticError(f"gait {gait.name} has no primitive", span)
    robot = _robot(gait, spec_dir)
    if prim.valves:
        order = robot.leg_of_valve if robot is not None else _leg_order([gait], legs)
        states = tuple(parse_valves(v, len(order), span) for v in prim.valves)
        return ValveSequence(states, order, "inline")
    if robot is None or prim.direction is None:
        raise SpecSemanticError(
            f"gait {gait.name}: a primitive needs inline valves, or a robot file and a direction",
            span,
        )

    direction = parse_direction(prim.direction, span)
    kept = stored_gait(robot, gait)
    if kept is not None:
        return kept
    method = prim.method or "reset"
    result = search(robot, direction, method, seed, max_states=PAIRING_STATES)
    if not result.gaits:
        within = (f" within {PAIRING_STATES} valve states" if result.limit_reached else "")
        raise SpecSemanticError(
            f"gait {gait.name}: no {method} gait towards {prim.direction} found for robot "
            f"{robot.name}{within}",
            span,
            "try another method, store the gait in the robot file ('gaitc gaits' searches "
            "further with --max-states), or give the valve sequence inline",
        )
    return ValveSequence(
        result.gaits[0].valves, robot.leg_of_valve, f"synthesised ({method}, {prim.direction})"
    )


#: How a primitive becomes a valve sequence: (gait, spec folder, the spec's leg order).
Resolver = Callable[[Gait, str, Sequence[str]], ValveSequence]

#: Valve states a gait search for a primitive may add (``compile``, ``lint``): the search
#: runs on every compile, so it is bounded; ``gaitc gaits --max-states`` searches further.
PAIRING_STATES = 500


def _primitive_hint(gait: Gait, order: Sequence[str]) -> str:
    """A primitive that would pass :func:`check_gaits` for ``gait``: inline valves that
    pressurise its legs one after the other (thesis 3.4.1: the two actuators of a gait are
    pressurised in succession; one leg is pressurised, then vented), or a robot file."""
    robot_file = 'primitive "ROBOT.yaml" direction D (D one of +x, -x, +y, -y; north is +y)'
    if not gait.legs:
        return f"add {robot_file}"
    fired = gait.firing_order
    states = ["".join("1" if leg == used else "0" for leg in order) for used in fired]
    if len(states) == 1:
        states.append("0" * len(order))
    steps = ", then ".join(fired) + (" pressurised" if len(fired) > 1 else
                                     " pressurised, then vented")
    return (f"add valves {', '.join(states)} ({steps}; one digit per leg, in the order "
            f"{', '.join(order)}) or {robot_file}")


def leg_mismatch(gait: Gait, seq: ValveSequence) -> tuple[str, str] | None:
    """Why ``seq`` cannot run ``gait`` as the spec's health reasoning has it, and the
    remedy, or None (:meth:`ltlcompiler.model.Gait.valve_mismatch`: a move gait's valves
    pressurise exactly its legs, a correction gait's none)."""
    return gait.valve_mismatch(seq.pressurised_legs(), seq.source)


def idle_fired(gait: Gait, seq: ValveSequence) -> tuple[str, str] | None:
    """Why running ``seq`` for ``gait`` would wear a leg the health reasoning takes as idle,
    with the remedy, or None (:meth:`ltlcompiler.model.Gait.idle_fired`)."""
    return gait.idle_fired(seq.pressurised_legs(), seq.source)


def check_gaits(
    gaits: Sequence[Gait], spec_dir: str, legs: Sequence[str] | None = None,
    moves: Mapping[str, frozenset[tuple[str, str]]] | None = None,
    resolve: Resolver | None = None,
) -> list[Diagnostic]:
    """Lint the gait-primitive bindings of a spec, each resolved by ``resolve`` (by default
    :func:`resolve_primitive`, the kinematic graph's).

    Warnings for gaits without a primitive; errors for primitives that cannot be resolved
    or whose pressurised legs differ from the legs the gait uses; and, given ``moves`` (the
    region transitions each gait makes), a warning for two gaits that move differently but
    run the same valve sequence, which the robot cannot tell apart.
    """
    out: list[Diagnostic] = []
    order = _leg_order(gaits, legs)
    resolved: dict[str, ValveSequence] = {}
    for gait in gaits:
        if gait.kind is GaitKind.NONE:
            continue
        if gait.primitive is None:
            out.append(
                Diagnostic(
                    f"gait {gait.name} has no primitive: nothing tells the valve board "
                    "how to run it",
                    gait.span,
                    "warning",
                    _primitive_hint(gait, order),
                )
            )
            continue
        span = gait.primitive.span or gait.span
        try:
            seq = (resolve or resolve_primitive)(gait, spec_dir, order)
        except GaitcError as err:
            out.append(Diagnostic(err.message, err.span or span, "error", err.hint))
            continue
        if gait.kind is not GaitKind.MOVE:
            wrong = leg_mismatch(gait, seq)
            if wrong is not None:
                out.append(Diagnostic(wrong[0], span, "error", wrong[1]))
            continue
        resolved[gait.name] = seq
        known = set(seq.leg_of_valve)
        unknown = [leg for leg in gait.legs if leg not in known]
        if unknown:
            out.append(
                Diagnostic(
                    f"gait {gait.name} uses {', '.join(unknown)}, which the primitive's robot "
                    f"does not have (its legs: {', '.join(dict.fromkeys(seq.leg_of_valve))})",
                    span,
                    "error",
                    "robot legs are matched to spec legs by name",
                )
            )
            continue
        wrong = leg_mismatch(gait, seq)
        if wrong is not None:
            out.append(Diagnostic(wrong[0], span, "error", wrong[1]))
    if moves is not None:
        out += _same_sequences(gaits, resolved, moves)
    return out


def _same_sequences(gaits: Sequence[Gait], resolved: Mapping[str, ValveSequence],
                    moves: Mapping[str, frozenset[tuple[str, str]]]) -> list[Diagnostic]:
    """Gaits that move differently but whose primitives run identical valve states."""
    out: list[Diagnostic] = []
    first: dict[tuple[tuple[str, ...], tuple[str, ...]], str] = {}
    spans = {g.name: g.span for g in gaits}
    for name, seq in resolved.items():
        key = (seq.states, seq.leg_of_valve)
        other = first.setdefault(key, name)
        if other != name and moves.get(other, frozenset()) != moves.get(name, frozenset()):
            out.append(Diagnostic(
                f"gaits {other} and {name} move the robot differently but run the same valve "
                f"sequence ({', '.join(seq.states)}): the robot cannot do both",
                spans.get(name), "warning",
                "fire the legs of one of them in another order (the order 'uses' names "
                "them), or give it its own primitive"))
    return out
