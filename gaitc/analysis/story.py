"""``explain``'s play told: the run of a play the environment wins, in the robot's terms.

The play itself (:class:`gaitc.sim.play.Play`, chosen by
:func:`gaitc.sim.counterplay.choose_play`) is a path of the counter-strategy to a deadlock
or into a loop on which some goal never holds; for a ``.gait`` spec its run
(:func:`gaitc.sim.replay.replay`) is told here a sentence a step, after a summary of the
environment's decisive moves, and its last move at a deadlock is found by the solver.
"""

from __future__ import annotations

from gaitc.ir.controller import Controller
from gaitc.ir.spec import GR1Spec
from gaitc.sim.play import Play
from gaitc.sim.run import Run, Step
from gaitc.solver.canonical import fix, primed, smallest
from gaitc.solver.symbolic import SymbolicSpec


def narrate(run: Run, play: Play, goal_names: list[str], final: str | None = None
            ) -> list[str]:
    """The play in robot terms, a sentence a step, and how the environment wins
    (``final``: its last move at a deadlock)."""
    lines: list[str] = []
    previous: Step | None = None
    for k, step in enumerate(run.steps):
        after = run.steps[k + 1] if k + 1 < len(run.steps) else None
        lines.append(f"step {step.index}: {_sentence(step, previous, after)}")
        previous = step
    last = run.steps[-1] if run.steps else None
    if play.deadlock and last is not None:
        move = f"the environment answers: {final}; " if final else ""
        lines.append(f"after step {last.index} {move}the robot has no legal move out of "
                     f"{last.region}: every move breaks one of its guarantees (see the core)")
    elif play.loop_start is not None:
        goals = ", ".join(goal_names[j] for j in play.missed) or "a goal"
        lines.append(f"from step {len(play.path) - 1} the play repeats steps "
                     f"{play.loop_start}..{len(play.path) - 2} for ever: {goals} never "
                     "holds again")
    return lines


def summarise(run: Run, play: Play, goal_names: list[str], about: tuple[int, ...] = ()
              ) -> list[str]:
    """The play in a few sentences before its steps: the goal the robot is kept from (the
    explanation's goal ``about`` first, the others it misses with it after), the
    environment's decisive moves (where, under which gait, what they do to the legs and
    hazards), and the pattern that repeats or the state the robot is left in."""
    if not run.steps:
        return []
    first = [j for j in about if j in play.missed]
    rest = [j for j in play.missed if j not in first]
    lost = ", ".join(goal_names[j] for j in first or rest) if play.missed else None
    also = (f" (and with it {', '.join(goal_names[j] for j in rest)})"
            if first and rest else "")
    lines = [f"the robot is kept from {lost}{also}" if lost else
             "the robot is driven to a state with no legal move"]
    moves: list[tuple[int, str]] = []
    previous: Step | None = None
    for k, step in enumerate(run.steps):
        after = run.steps[k + 1] if k + 1 < len(run.steps) else None
        done = _environment_move(step, previous, after)
        if done:
            where = f"in {step.region}" + (
                f" under gait {step.gait}" if step.gait and step.gait != "noGait" else "")
            moves.append((step.index, f"{where}: {done}"))
        previous = step
    if moves:
        shown = "; ".join(f"step {i} {text}" for i, text in moves[:4])
        more = f" (and {len(moves) - 4} more)" if len(moves) > 4 else ""
        lines.append(f"the environment's decisive moves: {shown}{more}")
    target = lost or "its goal"
    last = run.steps[-1]
    if not moves:
        lines.append(f"the environment never has to act in this play: every move the robot "
                     f"could make toward {target} leads to a state from which the environment "
                     "wins, so it stays where it can")
    elif play.loop_start is not None:
        looped = [text for i, text in moves if i > play.loop_start]
        if looped:
            lines.append(f"this repeats for ever: each time the robot is {looped[0]}")
        else:
            lines.append(f"after that the robot can only stay in {last.region}: the moves "
                         f"toward {target} need legs that have failed, or lead where the "
                         "environment wins")
    return lines


def _lost(step: Step, after: Step | None, leg: str) -> int:
    """The levels ``leg`` loses on the move after ``step`` (one where the run ends there; a
    graded hazard may take several at once)."""
    return step.level(leg) - after.level(leg) if after is not None else 1


def _environment_move(step: Step, previous: Step | None, after: Step | None = None) -> str:
    """What the environment does on the move into ``step``: a hazard switched on, legs the
    step's gait makes fail or lose levels (in a hazard's cell, naming the hazard)."""
    parts = []
    if step.hazard is not None and (previous is None or previous.hazard != step.hazard):
        parts.append(f"hazard {step.hazard} turns on")
    if step.failed:
        parts.append(f"{_legs(step.failed)} fail{'s' if len(step.failed) == 1 else ''}")
    by: dict[int, list[str]] = {}
    for leg in step.degraded:
        by.setdefault(_lost(step, after, leg), []).append(leg)
    for lost, legs in sorted(by.items()):
        levels = "a level" if lost == 1 else f"{lost} levels"
        cause = f" (hazard {step.hazard})" if lost > 1 and step.hazard else ""
        parts.append(f"{_legs(tuple(legs))} lose{'s' if len(legs) == 1 else ''} {levels}"
                     f"{cause}")
    return " and ".join(parts)


def _sentence(step: Step, previous: Step | None, after: Step | None = None) -> str:
    parts = [f"in {step.region}"]
    if step.gait and step.gait != "noGait":
        used = f" (uses {', '.join(step.legs_used)})" if step.legs_used else ""
        parts.append(f"gait {step.gait}{used}")
    elif previous is not None:
        parts.append("stays put")
    if step.hazard is not None and (previous is None or previous.hazard != step.hazard):
        parts.append(f"hazard {step.hazard} on")
    elif step.hazard is None and previous is not None and previous.hazard is not None:
        parts.append(f"hazard {previous.hazard} off")
    if step.failed:
        parts.append(f"{_legs(step.failed)} fail{'s' if len(step.failed) == 1 else ''}")
    for leg in step.degraded:  # marked on the move that wears it; the drop shows next step
        parts.append(f"{leg} drops to level {step.level(leg) - _lost(step, after, leg)}")
    if step.repaired:
        parts.append(f"{_legs(step.repaired)} repaired")
    if step.goals:
        parts.append(f"goal {', '.join(step.goals)} reached")
    return "; ".join(parts)


def _legs(legs: tuple[str, ...]) -> str:
    return legs[0] if len(legs) == 1 else ", ".join(legs[:-1]) + " and " + legs[-1]


def narrate_values(counter: Controller, play: Play) -> list[str]:
    """The play as variable values, for specs without a robot model."""
    lines = []
    previous: dict[str, int] | None = None
    for index, node in enumerate(play.path):
        values = counter.values(node)
        shown = values if previous is None else {
            k: v for k, v in values.items() if previous.get(k) != v}
        text = ", ".join(f"{k}={v}" for k, v in sorted(shown.items())) or "no change"
        lines.append(f"step {index}: {text}")
        previous = values
    if play.deadlock:
        lines.append(f"from step {len(play.path) - 1} the system has no legal move")
    elif play.loop_start is not None:
        lines.append(f"the play repeats steps {play.loop_start}..{len(play.path) - 2} "
                     "for ever")
    return lines


def deadlock_move(spec: GR1Spec, counter: Controller, node: int) -> dict[str, int] | None:
    """The environment's winning last input at the deadlock ``node``: one its assumptions
    allow and after which no robot answer keeps the guarantees (bits by name)."""
    sym = SymbolicSpec(spec)
    ins, outs = list(sym.input_bits), list(sym.output_bits)
    here = fix(sym, sym.env_trans & sym.sys_trans, ins + outs, counter.nodes[node].state)
    allowed = fix(sym, sym.env_trans, ins + outs, counter.nodes[node].state)
    answered = sym.bdd.exist(sym.post_outputs, here)
    stuck = sym.bdd.exist(sym.post_outputs, allowed) & ~answered
    x = smallest(sym, sym.bdd.exist(sym.post_outputs, stuck), primed(ins))
    if x is None:
        return None
    bits = dict(zip(ins, x, strict=True))
    values = dict(counter.values(node))
    plain = {b: v for b, v in bits.items() if not any(b in iv.bits for iv in
                                                       counter.integers.values())}
    values.update(plain)
    for name, iv in counter.integers.items():
        if iv.owner == "env":
            values[name] = iv.low + sum(bits[b] << k for k, b in enumerate(iv.bits))
    return values


def last_move(before: Step, after_health: tuple[tuple[str, int], ...],
              hazard: str | None) -> str:
    """The environment's final move in robot terms (legs that degrade or fail, hazards)."""
    old = dict(before.health)
    parts = []
    for leg, level in after_health:
        if level < old[leg]:
            parts.append(f"{leg} fails" if level == 1 else f"{leg} drops to level {level}")
    if hazard != before.hazard:
        parts.append(f"hazard {hazard} on" if hazard else f"hazard {before.hazard} off")
    return "; ".join(parts) or "no change"
