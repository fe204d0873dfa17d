"""A simulated run in domain terms: steps (region, gait, leg health, hazard), summary, files.

Written as JSON Lines (a header line, one line per step, a summary line) or CSV; the JSONL
form is read back by ``gaitc render map --run``.
"""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Final

from gaitc.diagnostics import GaitcError, ScenarioError, Span, UsageError, source_lines
from gaitc.diagnostics.files import decode_text, read_input, write_atomically
from gaitc.diagnostics.versions import RUN
from gaitc.sim.events import Surprise
from gaitc.sim.map_view import run_view

if TYPE_CHECKING:
    from ltlcompiler.model import Model


#: The most steps a run may have: a run is kept whole in memory and written whole (a step
#: takes about a kilobyte, with its line in the file), so a million steps is about a gigabyte.
MAX_STEPS: Final = 1_000_000


def checked_steps(steps: int, what: str = "the number of steps") -> int:
    """``steps`` when a run may have that many (0 to :data:`MAX_STEPS`); else a
    :class:`UsageError` naming ``what`` (``--steps``)."""
    if steps < 0:
        raise UsageError(f"{what} must not be negative")
    if steps > MAX_STEPS:
        raise UsageError(f"{what} is {steps}, more than the {MAX_STEPS:,} steps a run may have: "
                         "a run is kept whole in memory and written whole (about a kilobyte "
                         "a step); run fewer steps, or continue a saved run with "
                         "'gaitc play SPEC --from RUN.jsonl'")
    return steps


@dataclass(frozen=True)
class Step:
    """One state of a run.

    ``degraded``/``failed`` belong to the move into this state and its gait: the legs that
    this step's gait wears out (Mealy turn order: the environment lowers their level on the
    next step, eq. 3.5, or fails them there when this step entered an active hazard region,
    eq. 3.9, or lowers them by up to k levels for a hazard that ``wears k``; a leg that ends
    above level 1 counts as degraded), so the mark sits on the move that caused it.
    ``repaired`` lists the legs whose level went up on the step into this state (a cache,
    eq. 3.6).
    """

    index: int
    node: int
    region: str
    gait: str
    legs_used: tuple[str, ...]
    health: tuple[tuple[str, int], ...]  # (leg, level) in leg order; 1 = failed
    hazard: str | None
    goals: tuple[str, ...] = ()  # labels of the goals this state satisfies
    degraded: tuple[str, ...] = ()  # legs this step's gait makes lose a level (still working)
    failed: tuple[str, ...] = ()  # legs this step's gait makes fail (level 1 on the next step)
    repaired: tuple[str, ...] = ()  # legs whose level went up (cache)
    values: tuple[tuple[str, int], ...] = ()  # spec-level variable values, sorted by name

    def level(self, leg: str) -> int:
        return dict(self.health)[leg]

    def to_json(self) -> dict[str, Any]:
        return {
            "kind": "step", "step": self.index, "node": self.node, "region": self.region,
            "gait": self.gait, "legs_used": list(self.legs_used), "health": dict(self.health),
            "hazard": self.hazard, "goals": list(self.goals), "degraded": list(self.degraded),
            "failed": list(self.failed), "repaired": list(self.repaired),
            "values": dict(self.values),
        }


@dataclass(frozen=True)
class Summary:
    """What a run achieved and whether the spec held along it (checked by the monitor)."""

    steps: int
    goal_visits: tuple[tuple[str, int], ...]  # every goal, with the number of steps reaching it
    cache_visits: tuple[tuple[str, int], ...]
    legs_failed: tuple[tuple[int, str], ...]  # (step, leg)
    legs_degraded: tuple[tuple[int, str], ...]
    assumptions_held: bool
    guarantees_held: bool
    violations: tuple[str, ...] = ()
    env_liveness: tuple[tuple[str, int], ...] = ()  # □◇ assumption → times it held
    sys_liveness: tuple[tuple[str, int], ...] = ()  # □◇ guarantee → times it held
    stopped: str | None = None  # why the run ended early

    def to_json(self) -> dict[str, Any]:
        return {
            "kind": "summary", "steps": self.steps,
            "goal_visits": dict(self.goal_visits), "cache_visits": dict(self.cache_visits),
            "legs_failed": [list(x) for x in self.legs_failed],
            "legs_degraded": [list(x) for x in self.legs_degraded],
            "assumptions_held": self.assumptions_held, "guarantees_held": self.guarantees_held,
            "violations": list(self.violations), "env_liveness": dict(self.env_liveness),
            "sys_liveness": dict(self.sys_liveness), "stopped": self.stopped,
        }


def dropped_at(step: Step, leg: str) -> int:
    """The step a run's summary names for ``leg``'s drop marked on ``step``: the step itself
    when its gait used the leg (the move that wore it), else the next one, where the leg
    dropped while not in use (a surprise, named at that step in the surprise list too)."""
    return step.index if leg in step.legs_used else step.index + 1


def wear(before: Step, after: Step) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The legs whose level drops from ``before`` to ``after``: (degraded, failed)."""
    now = dict(after.health)
    degraded: list[str] = []
    failed: list[str] = []
    for leg, level in before.health:
        new = now.get(leg, level)
        if new < level:
            (failed if new == 1 else degraded).append(leg)
    return tuple(degraded), tuple(failed)


@dataclass
class Run:
    """The steps of a simulation, its summary, and the error that stopped it (if any)."""

    legs: tuple[str, ...]
    steps: list[Step] = field(default_factory=list)
    summary: Summary | None = None
    error: GaitcError | None = None
    environment: str = ""
    spec_file: str = ""
    model: Model | None = field(default=None, repr=False)
    file: str = ""  # the run file it was read from
    lines: list[int] = field(default_factory=list, repr=False)  # the file's line of each step
    #: the events the environment performed that may break assumptions (``--violate``, or
    #: observed inputs outside ρe), each with what became of the run
    surprises: list[Surprise] = field(default_factory=list)
    halted: str | None = None  # why the run ended on purpose (a stopped robot), if it did

    def __repr__(self) -> str:
        if self.summary is None:
            held = "not checked"
        elif self.summary.assumptions_held and self.summary.guarantees_held:
            held = "the spec held"
        else:
            held = "the spec was broken"
        stopped = f"; stopped: {self.error.message}" if self.error is not None else ""
        return (f"<Run of {self.spec_file or 'a spec'!r}: {len(self.steps)} states against "
                f"{self.environment or 'an environment'}, {held}{stopped}>")

    def _repr_svg_(self) -> str:
        return run_view(self).svg()

    def add(self, step: Step) -> None:
        """Append ``step``; the level drops it shows are put on the step before it (the
        move whose gait caused them)."""
        if self.steps:
            degraded, failed = wear(self.steps[-1], step)
            self.steps[-1] = replace(self.steps[-1], degraded=degraded, failed=failed)
        self.steps.append(step)

    def patrols(self) -> int:
        """Patrols completed: rounds that visit the goals in their order, from the first
        state on (as ``gaitc chances`` counts them, and a GR(1) controller's rank moves)."""
        if self.summary is None or not self.summary.goal_visits:
            return 0
        order = [goal for goal, _ in self.summary.goal_visits]
        done, goal = 0, 0
        for step in self.steps:
            goal = 0 if goal == len(order) else goal
            while goal < len(order) and order[goal] in step.goals:
                goal += 1
            done += goal == len(order)
        return done

    def to_json(self) -> dict[str, Any]:
        """The whole run as one object (``simulate --json``, docs/json.md): the header's
        legs, environment and spec, every step, the summary (null when not checked)."""
        return {"legs": list(self.legs), "environment": self.environment,
                "spec": self.spec_file, "steps": [step.to_json() for step in self.steps],
                "violations": [s.to_json() for s in self.surprises],
                "summary": None if self.summary is None else self.summary.to_json()}

    def header(self) -> dict[str, Any]:
        return {"kind": "run", "format": RUN.version, "legs": list(self.legs),
                "environment": self.environment, "spec": self.spec_file}


def write_jsonl(run: Run) -> str:
    """The run as JSON Lines: a ``run`` header, one ``step`` per state, a ``summary``."""
    lines = [json.dumps(run.header(), sort_keys=True)]
    lines.extend(json.dumps(step.to_json(), sort_keys=True) for step in run.steps)
    lines.extend(json.dumps({"kind": "violation", **s.to_json()}, sort_keys=True)
                 for s in run.surprises)
    if run.summary is not None:
        lines.append(json.dumps(run.summary.to_json(), sort_keys=True))
    return "\n".join(lines) + "\n"


def write_csv(run: Run) -> str:
    """The steps as CSV, one column per leg's health level."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["step", "node", "region", "gait", "legs_used",
                     *[f"health_{leg}" for leg in run.legs],
                     "hazard", "goals", "degraded", "failed", "repaired"])
    for s in run.steps:
        writer.writerow([s.index, s.node, s.region, s.gait, " ".join(s.legs_used),
                         *[s.level(leg) for leg in run.legs], s.hazard or "",
                         " ".join(s.goals), " ".join(s.degraded), " ".join(s.failed),
                         " ".join(s.repaired)])
    return out.getvalue()


def run_format(path: str | Path) -> str:
    """The run format ``path``'s extension names: ``jsonl`` (``.jsonl``, ``.json``) or
    ``csv``; any other is a usage error."""
    suffix = Path(path).suffix.lower()
    if suffix in (".jsonl", ".json"):
        return "jsonl"
    if suffix == ".csv":
        return "csv"
    raise UsageError(f"cannot tell the run format from '{path}': use a .jsonl or .csv file")


def save_run(run: Run, path: str | Path) -> None:
    """Write ``run`` to ``path``; the extension (``.jsonl`` or ``.csv``) picks the format."""
    text = write_jsonl(run) if run_format(path) == "jsonl" else write_csv(run)
    write_atomically(path, text)


def _strs(value: Any) -> tuple[str, ...]:
    return tuple(str(v) for v in value) if isinstance(value, Sequence) else ()


def read_jsonl(path: str | Path) -> Run:
    """Read a run written by :func:`write_jsonl` (the summary line is kept as is)."""
    file = str(path)
    if Path(path).suffix.lower() == ".csv":
        raise UsageError(f"'{path}' is a CSV run, a table for spreadsheets that cannot be read "
                         "back; save the run with --out FILE.jsonl to draw or replay it")
    raw = read_input(path, "run file")  # bytes: universal newlines would split at a lone \r
    text = decode_text(raw, file, ScenarioError)
    run = Run(legs=(), file=file)
    numbers = run.lines  # the line of each step
    for number, line in enumerate(source_lines(text), 1):
        if not line.strip():
            continue
        try:
            data = json.loads(line)
            kind = data.get("kind")
            if kind == "run":
                if "format" in data:
                    RUN.check(data["format"], Span(file, number, 1), ScenarioError)
                run.legs = _strs(data["legs"])
                run.environment = str(data.get("environment", ""))
                run.spec_file = str(data.get("spec", ""))
            elif kind == "step":
                health = tuple((str(k), int(v)) for k, v in dict(data["health"]).items())
                run.steps.append(Step(

                    index=int(data["step"]),
                    node=int(data["node"]),
                    region=str(data["region"]),
                    gait=str(data["gait"]),
                    legs_used=_strs(data["legs_used"]),
                    health=health,
                    hazard=None if data.get("hazard") is None else str(data["hazard"]),
                    goals=_strs(data.get("goals", [])),
                    degraded=_strs(data.get("degraded", [])),
                    failed=_strs(data.get("failed", [])),
                    repaired=_strs(data.get("repaired", [])),
                    values=tuple((str(k), int(v)) for k, v in dict(data.get("values", {})).items()),
                ))
                numbers.append(number)
            elif kind == "violation":
                run.surprises.append(Surprise.from_json(data))
        except GaitcError:  # the format version's own message
            raise
        except (json.JSONDecodeError, KeyError, TypeError, ValueError, AttributeError,
                RecursionError, OverflowError):  # an integer of 5,000 digits, int(1e400)
            raise ScenarioError(
                "not a run written by 'gaitc simulate --out FILE.jsonl'",
                Span(file, number, 1),
            ) from None
    if not run.legs and run.steps:
        run.legs = tuple(leg for leg, _ in run.steps[0].health)
    for step, number in zip(run.steps, numbers, strict=True):
        if sorted(leg for leg, _ in step.health) != sorted(run.legs):
            raise ScenarioError(
                f"step {step.index} gives the health of {', '.join(k for k, _ in step.health)}"
                f" but the run's legs are {', '.join(run.legs)}", Span(file, number, 1),
                "a run file is written by 'gaitc simulate --out FILE.jsonl'")
    return run
