"""Gait primitives for a robot file, behind one call: :func:`gaits` (``gaitc gaits``).

Three kinds of search answer it, picked by :class:`GaitOptions` and looked up in the one
registry of search methods (:mod:`gaitc.search.registry`, :class:`SearchMethod`):

- the chapter 2 gait graph (thesis 2.3-2.5, :mod:`gaitc.gaitgraph`): stable poses of the
  kinematic model, Kabsch transitions, and gait cycles ranked by their displacement toward
  a direction (``method`` chapter2, full, random or reset);
- the gait graph of a chapter 4 dynamic model (thesis 4.2.2, :mod:`gaitc.models`), whose
  transitions are simulated (``model``), optionally of some legs only (``legs``: the search
  the ``.gait`` ``primitive`` clause runs, :mod:`gaitc.search.primitives`);
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

from gaitc.core.modes import SearchMethod
from gaitc.diagnostics import SpecSemanticError, UsageError
from gaitc.diagnostics.files import make_folder, write_atomically
from gaitc.diagnostics.versions import GAITS
from gaitc.gaitgraph.cycles import MAX_HEADING_DEG, parse_direction
from gaitc.gaitgraph.drawing import write_drawings
from gaitc.gaitgraph.report import gait_table, gaits_json, search_document
from gaitc.gaitgraph.robot import load_robot
from gaitc.models.catalogue import MODEL_CHOICES, chosen_model, load_model
from gaitc.models.gait_graph import gait_rows
from gaitc.search.goals import numbers, parse_goal
from gaitc.search.planners import Settings
from gaitc.search.predictions import graph_transitions
from gaitc.search.registry import direction_search, entry, goal_search, legs_sentence, pressurised
from gaitc.search.transitions import TransitionModel

if TYPE_CHECKING:
    from gaitc.gaitgraph.displacement import Stillness
    from gaitc.gaitgraph.robot import Robot
    from gaitc.gaitgraph.search import SearchResult
    from gaitc.models.catalogue import ModelSearch
    from gaitc.search.goals import Goal
    from gaitc.search.planners import Settings
    from gaitc.search.plans import GaitPlan


#: Deprecated name of :class:`gaitc.core.modes.SearchMethod` (``gaitc.GaitMethod``).
GaitMethod = SearchMethod

#: The chapter 5 searches, by name.
GLOBAL_METHODS = tuple(m.value for m in SearchMethod if m.is_global)


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
        for name in ("budget", "iterations", "horizon"):
            if getattr(self, name) < 1:
                raise UsageError(f"--{name} must be at least 1")
        cell, angle = _pair(self.cell, "--cell", 2.0) if self.cell else (2.0, 2.0)
        if abs(360.0 / angle - round(360.0 / angle)) > 1e-9:
            raise UsageError(f"--cell: the angle {angle:g} deg must divide 360")
        return Settings(cell, angle, budget=self.budget, iterations=self.iterations,
                        horizon=self.horizon, seed=seed)

    def target(self, method: SearchMethod | str) -> Goal:
        """The goal, parsed with its tolerance."""
        if self.goal is None:
            raise UsageError(f"--method {method} needs --goal DX,DY[,DTHETA] (mm, degrees)")
        return parse_goal(self.goal, self.tolerance)


def _pair(text: str, option: str, default_angle: float) -> tuple[float, float]:
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
    ``max_states`` valve states, and the chapter 5 ``search``.  ``legs`` (a model's gait
    graph only) keeps the gaits that pressurise exactly those legs, started at the first
    one's pressurisation: the search a ``.gait`` ``primitive`` clause runs for a gait that
    ``uses`` them, in that order."""

    direction: str = "+x"
    method: SearchMethod | str | None = None
    model: str | None = None
    max_open: int = 1
    seed: int = 0
    max_states: int = 10_000
    search: GlobalSearch = field(default_factory=GlobalSearch)
    legs: tuple[str, ...] | None = None


def _direction(text: str) -> tuple[float, float]:
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
            why = (f"no cycle of the kinematic gait graph's {edges} transitions goes within "
                   f"{MAX_HEADING_DEG:g} degrees of {self.direction}")
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
        return gaits_json(self.robot, self.result, self.direction, self.seed)

    def save(self, path: str | Path) -> bool:
        """Write the gaits file; True (there is always one, if empty)."""
        write_atomically(path, self.gaits_file())
        return True

    def draw(self, folder: str | Path) -> list[str]:
        """The gait graph and a top view of every pose of every gait, as SVG files."""
        return write_drawings(self.robot, self.result.graph, self.result.gaits, str(folder))

    def to_json(self) -> dict[str, Any]:
        return search_document(self.robot, self.result, self.direction, self.seed)


@dataclass(frozen=True)
class ModelGaits:
    """Gaits of a chapter 4 model's gait graph (thesis 4.2.2)."""

    found_search: ModelSearch
    model: str
    direction: str
    still: Stillness | None = None  # the graph's moving cycles, when no gait was found
    legs: tuple[str, ...] | None = None  # the legs the search was restricted to
    movers: tuple[str, ...] | None = None  # with legs and no gait: the legs that move so

    @property
    def found(self) -> bool:
        return bool(self.found_search.gaits)

    @property
    def hints(self) -> tuple[str, ...]:
        """Why a search found nothing and what to do (the command prints it on stderr)."""
        if self.found:
            return ()
        edges = len(self.found_search.graph.motion)
        if self.legs is not None:

            return (legs_sentence(self.legs, self.direction, f"the {self.model} model",
                                  self.movers or ()),)
        if self.still is not None and not self.still.moves:
            return (f"the {self.model} model's gait graph has no displacement: every cycle of "
                    f"its {edges} simulated transitions returns the chassis to where it "
                    "started; check the model's friction and limb parameters "
                    "(docs/models.md), or allow more open valves with --max-open",)
        return (f"no cycle of the {self.model} model's {edges} simulated transitions goes "
                f"within {MAX_HEADING_DEG:g} degrees of {self.direction}; more open valves "
                "(--max-open) give the search more valve states",)

    def __str__(self) -> str:
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
        raise UsageError(f"the gaits of the {self.model} model have no drawing yet: the "
                         "drawings are of the chapter 2 gait graph, which --model kinematic "
                         "searches")


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
        if not plan.reached and self.method == SearchMethod.MCTS:
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
        return {"robot": self.robot, "method": str(self.method), "model": self.model,
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


def model_choices() -> tuple[str, ...]:
    """The gait graphs ``model`` names (``kinematic`` and each chapter 4 model;
    :data:`gaitc.models.catalogue.MODEL_CHOICES`, imported here when asked for)."""
    return MODEL_CHOICES


def gaits(robot: str | Path, options: GaitOptions | None = None) -> GaitSearch:
    """Gait primitives of the robot file ``robot`` (see the module's docstring).

    The robot file decides the gait graph: its chapter 4 model when it declares one, else
    the kinematic graph of chapter 2; ``options.model`` overrides it.

        >>> import gaitc
        >>> found = gaitc.gaits("specs/robots/symmetric6.yaml", gaitc.GaitOptions("+x"))
        >>> found.found, found.to_json()["gaits"][0]["rank"]
        (True, 1)
    """
    opts = options or GaitOptions()
    method = entry(opts.method).method if opts.method is not None else None
    if opts.max_states < 1:
        raise UsageError("--max-states must be at least 1")
    loaded = load_robot(robot)
    model = chosen_model(loaded, opts.model)
    if opts.legs is not None and (model is None or (method is not None and method.is_global)):
        raise UsageError("--legs restricts a chapter 4 model's gait graph (the search of a "
                         "'.gait' primitive clause); the robot file declares no model, or "
                         "--model kinematic or a chapter 5 --method was asked for")
    if method is not None and method.is_global:
        return _global_gait(str(robot), loaded, opts, goal_search(method).method, model)
    if opts.search.goal is not None:
        raise UsageError(f"--goal is for --method astar, lpa, dstar or mcts; the chapter 2 "
                         f"search (--method {method or SearchMethod.CHAPTER2}) takes "
                         "--direction")
    if model is not None:
        return _model_gaits(str(robot), opts, method, model)
    search = direction_search(method)
    direction = _direction(opts.direction)
    chosen = search.graph_method(loaded, opts.max_states)
    if chosen == SearchMethod.FULL and opts.seed != 0:
        raise UsageError(f"--seed seeds the random and reset searches; the full search of "
                         f"robot {loaded.name} tries every valve state, without random numbers")
    result = search.kinematic(loaded, direction, opts.seed, opts.max_states)
    still = None
    if not result.gaits:

        still = TransitionModel.from_graph(result.graph).stillness()
    return KinematicGaits(loaded, result, chosen, opts.direction, opts.seed, opts.max_states,
                          still)


def _model_gaits(robot: str, opts: GaitOptions, method: SearchMethod | None,
                 model: str) -> ModelGaits:
    search = direction_search(method)
    if search.not_on_models is not None:
        raise UsageError(search.not_on_models)
    if opts.seed != 0 and not search.sampled:
        raise UsageError(f"--seed seeds the random searches; the {model} model's gait graph "
                         "is searched whole, without random numbers (--method random samples "
                         "--max-states valve states)")
    if opts.max_open < 1:
        raise UsageError("--max-open must be at least 1")
    direction = _direction(opts.direction)
    loaded = load_model(model, robot)
    legs = opts.legs
    if legs is not None:
        unknown = [leg for leg in legs if leg not in loaded.valve_legs]
        if unknown or not legs:
            raise UsageError(f"--legs: robot {loaded.robot} has no leg "
                             f"{', '.join(unknown) or '(none given)'} (its legs: "
                             f"{', '.join(dict.fromkeys(loaded.valve_legs))})")
    found = search.model(loaded, direction, max_open=opts.max_open, seed=opts.seed,
                         max_states=opts.max_states, legs=legs)
    still, movers = None, None
    if not found.gaits and legs is not None:
        anyone = search.model(loaded, direction, max_open=opts.max_open, seed=opts.seed,
                              max_states=opts.max_states)
        movers = pressurised(anyone.gaits[0], loaded.valve_legs) if anyone.gaits else ()
    elif not found.gaits:

        still = graph_transitions(found.graph, loaded.valve_legs).stillness()
    return ModelGaits(found, model, opts.direction, still, legs, movers)


def _global_gait(robot: str, loaded: Robot, opts: GaitOptions, method: SearchMethod,
                 model: str | None) -> GlobalGait:
    goal = opts.search.target(method)
    settings = opts.search.settings(opts.seed)
    search = goal_search(method)
    if model is None:
        first = search.kinematic(loaded, goal, settings, opts.max_states)
    else:
        first = search.model(robot, goal, settings, max_open=opts.max_open, model=model,
                             max_states=opts.max_states)[0]
    return GlobalGait(loaded.name, loaded.valve_count, method.value, goal, first.plan,
                      model or "kinematic", first.reason)
