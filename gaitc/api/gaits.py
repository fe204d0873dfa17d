"""Gait primitives for a robot file, behind one call: :func:`gaits` (``gaitc gaits``).

Three searches answer it, picked by :class:`GaitOptions`:

- the chapter 2 gait graph (thesis 2.3-2.5, :mod:`gaitc.gaitgraph`): stable poses of the
  kinematic model, Kabsch transitions, and gait cycles ranked by their displacement toward
  a direction (``method`` chapter2, full, random or reset);
- the gait graph of a chapter 4 dynamic model (thesis 4.2.2, :mod:`gaitc.models`), whose
  transitions are simulated (``model``);
- the chapter 5 global-frame searches toward a displacement per cycle (A*, LPA*, D* Lite,
  MCTS; :mod:`gaitc.search`), with ``method`` astar, lpa, dstar or mcts and a goal.

Each returns a result that prints as the command prints it, shows itself in a notebook,
and has ``to_json``, ``save`` (the gaits file) and ``draw`` (SVG drawings).
"""

from __future__ import annotations

import html
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.diagnostics import SpecSemanticError, UsageError
from gaitc.diagnostics.choices import Choice
from gaitc.diagnostics.files import make_folder, write_atomically
from gaitc.diagnostics.versions import GAITS

if TYPE_CHECKING:
    from gaitc.gaitgraph.displacement import Stillness
    from gaitc.gaitgraph.robot import Robot
    from gaitc.gaitgraph.search import SearchResult
    from gaitc.models.catalogue import ModelSearch
    from gaitc.search.goals import Goal
    from gaitc.search.planners import Settings
    from gaitc.search.plans import GaitPlan


class GaitMethod(Choice):
    """How :func:`gaits` searches (``--method``)."""

    CHAPTER2 = "chapter2"  # full for a small robot, else random (thesis 2.5)
    FULL = "full"
    RANDOM = "random"
    RESET = "reset"
    ASTAR = "astar"  # thesis chapter 5, toward a goal
    LPA = "lpa"
    DSTAR = "dstar"
    MCTS = "mcts"

    @property
    def is_global(self) -> bool:
        """A chapter 5 search in the global frame, toward a goal displacement."""
        return self in (GaitMethod.ASTAR, GaitMethod.LPA, GaitMethod.DSTAR, GaitMethod.MCTS)


#: The chapter 5 searches, by name.
GLOBAL_METHODS = tuple(m.value for m in GaitMethod if m.is_global)


@dataclass(frozen=True)
class GlobalSearch:
    """The goal and settings of the chapter 5 searches (shared by :func:`gaits` and
    :func:`gaitc.learn`): goal ``"DX,DY[,DTHETA]"`` (mm, degrees per cycle), tolerance and
    lattice cell ``"MM[,DEG]"``, node expansions per A*/LPA* search, MCTS iterations and
    the longest MCTS cycle in transitions."""

    goal: str | None = None
    tolerance: str | None = None
    cell: str | None = None
    budget: int = 200_000
    iterations: int = 2000
    horizon: int = 12

    def settings(self, seed: int) -> Settings:
        """The planners' settings, checked (a :class:`UsageError` names the option)."""
        from gaitc.search.planners import Settings

        for name in ("budget", "iterations", "horizon"):
            if getattr(self, name) < 1:
                raise UsageError(f"--{name} must be at least 1")
        cell, angle = _pair(self.cell, "--cell", 2.0) if self.cell else (2.0, 2.0)
        if abs(360.0 / angle - round(360.0 / angle)) > 1e-9:
            raise UsageError(f"--cell: the angle {angle:g} deg must divide 360")
        return Settings(cell, angle, budget=self.budget, iterations=self.iterations,
                        horizon=self.horizon, seed=seed)

    def target(self, method: str) -> Goal:
        """The goal, parsed with its tolerance."""
        from gaitc.search.goals import parse_goal

        if self.goal is None:
            raise UsageError(f"--method {method} needs --goal DX,DY[,DTHETA] (mm, degrees)")
        return parse_goal(self.goal, self.tolerance)


def _pair(text: str, option: str, default_angle: float) -> tuple[float, float]:
    from gaitc.search.goals import numbers

    values = numbers(text, option, 1, 2)
    if any(v <= 0 for v in values):
        raise UsageError(f"{option}: must be positive, got {text!r}")
    return values[0], values[1] if len(values) == 2 else default_angle


@dataclass(frozen=True)
class GaitOptions:
    """What :func:`gaits` searches: ``direction`` (``+x``, ``-y`` or an angle in degrees)
    for chapter 2 and the models, ``method`` (None: chapter 2), ``model`` (None: the chapter 4
    model the robot file declares, else the kinematic graph; ``"kinematic"``: the kinematic
    graph; or a model by name, :data:`gaitc.models.catalogue.MODEL_CHOICES`) with valve
    states of at most ``max_open`` open valves, the ``seed`` of the random searches, at most
    ``max_states`` valve states, and the chapter 5 ``search``."""

    direction: str = "+x"
    method: GaitMethod | str | None = None
    model: str | None = None
    max_open: int = 1
    seed: int = 0
    max_states: int = 10_000
    search: GlobalSearch = field(default_factory=GlobalSearch)


def _direction(text: str) -> tuple[float, float]:
    from gaitc.gaitgraph.cycles import parse_direction

    try:
        return parse_direction(text)
    except SpecSemanticError as err:  # no file to point at: a usage error
        raise UsageError(f"--direction: unknown direction {text!r}") from err


def _html_pre(title: str, text: str) -> str:
    return f"<b>{html.escape(title)}</b><pre>{html.escape(text)}</pre>"


@dataclass(frozen=True)
class KinematicGaits:
    """Gaits of the chapter 2 gait graph (thesis 2.3-2.5)."""

    robot: Robot
    result: SearchResult
    method: str
    direction: str
    seed: int
    max_states: int
    still: Stillness | None = None  # the graph's moving cycles, when no gait was found

    @property
    def found(self) -> bool:
        return bool(self.result.gaits)

    @property
    def hints(self) -> tuple[str, ...]:
        """Why a search found nothing and what to do (the command prints it on stderr)."""
        if self.found:
            return ()
        edges = len(self.result.graph.edges)
        if self.still is not None and not self.still.moves:
            why = (f"the kinematic gait graph has no displacement: every cycle of its {edges} "
                   "transitions returns the chassis to where it started (chapter 2's model "
                   "is frictionless, so feet that only push or slide move nothing)")
        else:
            why = (f"no cycle of the kinematic gait graph's {edges} transitions goes toward "
                   f"{self.direction}")
        if self.robot.models:
            fix = (f"drop --model kinematic to search the robot file's {self.robot.models[0]} "
                   "model, which models friction")
        else:
            fix = ("a robot that walks by friction needs a chapter 4 model: add a 'model:' "
                   "section to the robot file (docs/models.md)")
        if self.result.limit_reached:
            fix = f"raise --max-states (the search stopped at {self.max_states}); or {fix}"
        return (f"{why}; {fix}",)

    def __str__(self) -> str:
        from gaitc.gaitgraph.report import gait_table

        robot, result = self.robot, self.result
        lines = [f"robot {robot.name}: {robot.valve_count} chambers, method {self.method}, "
                 f"{result.states_added} valve states, {len(result.graph)} poses, "
                 f"{len(result.graph.edges)} transitions"]
        lines.append(gait_table(robot, result.gaits) if result.gaits
                     else f"no gait towards {self.direction} found")
        if result.limit_reached:
            lines.append(f"the search stopped at --max-states {self.max_states} of the "
                         f"{1 << robot.valve_count} valve states")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        return _html_pre(f"gaits of {self.robot.name}", str(self))

    def gaits_file(self) -> str:
        """The gaits file (JSON, format :data:`gaitc.diagnostics.versions.GAITS`)."""
        from gaitc.gaitgraph.report import gaits_json

        return gaits_json(self.robot, self.result, self.direction, self.seed)

    def save(self, path: str | Path) -> bool:
        """Write the gaits file; True (there is always one, if empty)."""
        write_atomically(path, self.gaits_file())
        return True

    def draw(self, folder: str | Path) -> list[str]:
        """The gait graph and a top view of every pose of every gait, as SVG files."""
        from gaitc.gaitgraph.drawing import write_drawings

        return write_drawings(self.robot, self.result.graph, self.result.gaits, str(folder))

    def to_json(self) -> dict[str, Any]:
        from gaitc.gaitgraph.report import search_document

        return search_document(self.robot, self.result, self.direction, self.seed)


@dataclass(frozen=True)
class ModelGaits:
    """Gaits of a chapter 4 model's gait graph (thesis 4.2.2)."""

    found_search: ModelSearch
    model: str
    direction: str
    still: Stillness | None = None  # the graph's moving cycles, when no gait was found

    @property
    def found(self) -> bool:
        return bool(self.found_search.gaits)

    @property
    def hints(self) -> tuple[str, ...]:
        """Why a search found nothing and what to do (the command prints it on stderr)."""
        if self.found:
            return ()
        edges = len(self.found_search.graph.motion)
        if self.still is not None and not self.still.moves:
            return (f"the {self.model} model's gait graph has no displacement: every cycle of "
                    f"its {edges} simulated transitions returns the chassis to where it "
                    "started; check the model's friction and limb parameters "
                    "(docs/models.md), or allow more open valves with --max-open",)
        return (f"no cycle of the {self.model} model's {edges} simulated transitions goes "
                f"toward {self.direction}; more open valves (--max-open) give the search "
                "more valve states",)

    def __str__(self) -> str:
        from gaitc.models.gait_graph import gait_rows

        found, loaded = self.found_search, self.found_search.loaded
        lines = [f"robot {loaded.robot}: model {self.model}, {len(found.graph.states)} valve "
                 f"states, {len(found.graph.motion)} simulated transitions of "
                 f"{loaded.period:g} s"]
        if found.gaits:
            best = found.gaits[0]
            lines.append(gait_rows(found.gaits, loaded.valve_legs))
            lines.append(f"predicted displacement per cycle of gait 1: {best.net.x:.1f} mm, "
                         f"{best.net.y:.1f} mm, {math.degrees(best.net.theta):.2f} deg "
                         f"({len(best.states)} valve states)")
        else:
            lines.append(f"no gait towards {self.direction} found")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        return _html_pre(f"gaits of {self.found_search.loaded.robot} ({self.model})", str(self))

    def to_json(self) -> dict[str, Any]:
        found = self.found_search
        gaits = [
            {
                "rank": rank,
                "valves": list(g.valves),
                "transitions": [
                    {"dx": _r(p.x), "dy": _r(p.y), "rotation": _r(math.degrees(p.theta))}
                    for p in g.steps
                ],
                "displacement": [_r(g.net.x), _r(g.net.y)],
                "rotation": _r(math.degrees(g.net.theta)),
                "score": _r(g.score),
            }
            for rank, g in enumerate(found.gaits, 1)
        ]
        return {
            "format": GAITS.version,
            "robot": found.loaded.robot,
            "model": found.graph.model,
            "direction": self.direction,
            "period": found.graph.period,
            "valve_states": len(found.graph.states),
            "transitions": len(found.graph.motion),
            "valve_legs": list(found.loaded.valve_legs),
            "units": {"length": "mm", "angle": "deg"},
            "gaits": gaits,
        }

    def gaits_file(self) -> str:
        return json.dumps(self.to_json(), indent=2, sort_keys=True) + "\n"

    def save(self, path: str | Path) -> bool:
        """Write the gaits file; True (there is always one, if empty)."""
        write_atomically(path, self.gaits_file())
        return True

    def draw(self, folder: str | Path) -> list[str]:
        raise UsageError("--svg draws the chapter 2 gait graph; the model's graph has no "
                         "drawing yet")


def _r(x: float) -> float:
    value = round(x, 3)
    return 0.0 if value == 0 else value


@dataclass(frozen=True)
class GlobalGait:
    """One gait toward a goal displacement, from a chapter 5 search (None: none found)."""

    robot: str
    chambers: int
    method: str
    goal: Goal
    plan: GaitPlan | None
    model: str = "kinematic"  # the gait graph searched: kinematic or a chapter 4 model
    reason: str | None = None  # why there is no plan, when the graph says so at once

    @property
    def found(self) -> bool:
        return self.plan is not None and self.plan.reached

    hints: tuple[str, ...] = ()

    def __str__(self) -> str:
        plan, goal = self.plan, self.goal
        if plan is None:
            why = f": {self.reason}" if self.reason else ""
            return f"robot {self.robot}: no gait toward {goal} found ({self.model}){why}"
        states, poses, edges = plan.graph
        lines = [f"robot {self.robot}: {self.chambers} chambers, {self.model} gait graph, "
                 f"method {self.method}, {states} valve states, {poses} poses, {edges} "
                 "transitions", plan.table()]
        if not plan.reached and self.method == "mcts":
            lines.append(f"the best cycle found misses the goal's tolerance ({goal.tolerance:g}"
                         f" mm, {goal.angle_tolerance:g} deg); more --iterations or a longer "
                         "--horizon may help")
        elif not plan.reached:
            lines.append(f"no cycle within the search budget meets the tolerance "
                         f"({goal.tolerance:g} mm, {goal.angle_tolerance:g} deg); this is the "
                         "closest found, after re-planning toward tighter goal cells and on a "
                         "finer lattice; a larger --budget or --max-states may help")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        if self.plan is None:
            return _html_pre("no gait", str(self))
        return self.plan._repr_svg_() + _html_pre(f"{self.method} gait of {self.robot}",
                                                  str(self))

    def to_json(self) -> dict[str, Any]:
        plan = self.plan
        states, poses, edges = plan.graph if plan is not None else (None, None, None)
        return {"robot": self.robot, "method": self.method, "model": self.model,
                "reason": self.reason, "found": plan is not None,
                "reached": plan is not None and plan.reached, "valve_states": states,
                "poses": poses, "transitions": edges,
                "plan": None if plan is None else plan.to_dict()}

    def save(self, path: str | Path) -> bool:
        """Write the plan as JSON; False (nothing written) when no gait was found."""
        if self.plan is None:
            return False
        write_atomically(path, self.plan.to_json())
        return True

    def draw(self, folder: str | Path) -> list[str]:
        if self.plan is None:
            return []
        make_folder(folder)
        path = Path(folder) / "gait-search.svg"
        write_atomically(path, self.plan._repr_svg_())
        return [str(path)]


GaitSearch = KinematicGaits | ModelGaits | GlobalGait


def gaits(robot: str | Path, options: GaitOptions | None = None) -> GaitSearch:
    """Gait primitives of the robot file ``robot`` (see the module's docstring).

    The robot file decides the gait graph: its chapter 4 model when it declares one, else
    the kinematic graph of chapter 2; ``options.model`` overrides it.

        >>> import gaitc
        >>> found = gaitc.gaits("specs/robots/symmetric6.yaml", gaitc.GaitOptions("+x"))
        >>> found.found, found.to_json()["gaits"][0]["rank"]
        (True, 1)
    """
    from gaitc.gaitgraph.robot import load_robot
    from gaitc.models.catalogue import chosen_model

    opts = options or GaitOptions()
    method = GaitMethod.parse(opts.method, "search method") if opts.method is not None else None
    if opts.max_states < 1:
        raise UsageError("--max-states must be at least 1")
    loaded = load_robot(robot)
    model = chosen_model(loaded, opts.model)
    if method is not None and method.is_global:
        return _global_gait(str(robot), loaded, opts, method, model)
    if opts.search.goal is not None:
        raise UsageError(f"--goal is for --method astar, lpa, dstar or mcts; the chapter 2 "
                         f"search (--method {(method or GaitMethod.CHAPTER2).value}) takes "
                         "--direction")
    if model is not None:
        return _model_gaits(str(robot), opts, method, model)
    from gaitc.gaitgraph.search import search

    direction = _direction(opts.direction)
    full = loaded.valve_count <= 12 and 1 << loaded.valve_count <= opts.max_states
    chosen = (method.value if method not in (None, GaitMethod.CHAPTER2) and method is not None
              else ("full" if full else "random"))
    if chosen == "full" and opts.seed != 0:
        raise UsageError(f"--seed seeds the random and reset searches; the full search of "
                         f"robot {loaded.name} tries every valve state, without random numbers")
    result = search(loaded, direction, chosen, opts.seed, opts.max_states)
    still = None
    if not result.gaits:
        from gaitc.search.transitions import TransitionModel

        still = TransitionModel.from_graph(result.graph).stillness()
    return KinematicGaits(loaded, result, chosen, opts.direction, opts.seed, opts.max_states,
                          still)


def _model_gaits(robot: str, opts: GaitOptions, method: GaitMethod | None,
                 model: str) -> ModelGaits:
    from gaitc.models.catalogue import load_model, sampled_states, search_gaits

    if method is GaitMethod.RESET:
        raise UsageError(f"--method reset searches the kinematic graph's reset edges (thesis "
                         f"2.5.2); the robot file's {model} model has none: add --model "
                         "kinematic, or use --method full or random")
    if opts.seed != 0 and method is not GaitMethod.RANDOM:
        raise UsageError(f"--seed seeds the random searches; the {model} model's gait graph "
                         "is searched whole, without random numbers (--method random samples "
                         "--max-states valve states)")
    if opts.max_open < 1:
        raise UsageError("--max-open must be at least 1")
    direction = _direction(opts.direction)
    loaded = load_model(model, robot)
    count = len(loaded.valve_legs)
    limit = opts.max_states if method is GaitMethod.RANDOM else 1 << count
    states = sampled_states(count, opts.max_open, limit, opts.seed)
    found = search_gaits(loaded, direction, opts.max_open, states)
    still = None
    if not found.gaits:
        from gaitc.search.predictions import graph_transitions

        still = graph_transitions(found.graph, loaded.valve_legs).stillness()
    return ModelGaits(found, model, opts.direction, still)


def _global_gait(robot: str, loaded: Robot, opts: GaitOptions, method: GaitMethod,
                 model: str | None) -> GlobalGait:
    from gaitc.search.api import first_planner, model_planner

    goal = opts.search.target(method.value)
    settings = opts.search.settings(opts.seed)
    if model is None:
        first = first_planner(loaded, goal, method.value, settings, opts.max_states)
    else:
        first = model_planner(robot, goal, method.value, settings, max_open=opts.max_open,
                              model=model, max_states=opts.max_states)[0]
    return GlobalGait(loaded.name, loaded.valve_count, method.value, goal, first.plan,
                      model or "kinematic", first.reason)
