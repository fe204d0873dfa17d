"""Scripted environments: YAML scenarios saying, step by step, which hazard is active and
which legs degrade (by one level, or by several under a graded hazard) or fail; names are
checked on loading (errors point at file:line:col), and each step's input is checked
against the spec's assumptions ρe while the run goes.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import yaml

from gaitc.diagnostics import ScenarioError, Span
from gaitc.diagnostics.files import decode_text, read_input
from gaitc.diagnostics.yamltext import compose
from gaitc.sim.domain import State
from gaitc.sim.environments import Environment, Move, Request, Situation
from ltlcompiler.model import Model

NONE_WORDS = ("none", "null", "~", "", "off")
STEP_KEYS = ("hazard", "degrade", "fail", "health", "note")
START_KEYS = ("hazard", "health", "note")
TOP_KEYS = ("start", "steps")


@dataclass(frozen=True)
class ScriptStep:
    """One scripted step; ``keep_hazard`` when the step does not mention the hazard.

    ``degrade`` holds (leg, levels lost): ``degrade: [L1]`` loses one level (eq. 3.5),
    ``degrade: {L1: 2}`` two, which only a graded hazard (``wears 2`` or more) allows."""

    span: Span
    keep_hazard: bool = True
    hazard: str | None = None
    degrade: tuple[tuple[str, int], ...] = ()
    fail: tuple[str, ...] = ()
    health: tuple[tuple[str, int], ...] = ()

    def describe(self) -> str:
        parts = []
        if not self.keep_hazard:
            parts.append(f"hazard {self.hazard or 'none'}")
        parts.extend(f"degrade {leg}" if lost == 1 else f"degrade {leg} by {lost} levels"
                     for leg, lost in self.degrade)
        parts.extend(f"fail {leg}" for leg in self.fail)
        parts.extend(f"{leg} at level {level}" for leg, level in self.health)
        return ", ".join(parts) or "no change"


@dataclass(frozen=True)
class Scenario:
    file: str
    start: ScriptStep | None
    steps: tuple[ScriptStep, ...]


def _span(file: str, node: yaml.Node) -> Span:
    start, end = node.start_mark, node.end_mark
    end_col = end.column if end.line == start.line else None
    return Span(file, start.line + 1, start.column + 1, end.line + 1 if end_col else None,
                end_col)


class _Reader:
    def __init__(self, file: str, model: Model) -> None:
        self.file = file
        self.model = model
        self.legs = {leg.name: leg.health for leg in model.legs}
        self.hazards = tuple(h.name for h in model.hazards)

    def fail(self, message: str, node: yaml.Node, hint: str | None = None) -> ScenarioError:
        return ScenarioError(message, _span(self.file, node), hint)

    def mapping(self, node: yaml.Node, what: str, keys: tuple[str, ...]) -> dict[str, yaml.Node]:
        if not isinstance(node, yaml.MappingNode):
            raise self.fail(f"{what} must be a mapping with keys {', '.join(keys)}", node)
        out: dict[str, yaml.Node] = {}
        for key, value in node.value:
            name = key.value if isinstance(key, yaml.ScalarNode) else None
            if name not in keys:
                raise self.fail(f"unknown key '{name}' in {what}; expected one of "
                                f"{', '.join(keys)}", key)
            if name in out:
                raise self.fail(f"key '{name}' appears twice in {what}", key)
            out[name] = value
        return out

    def leg(self, node: yaml.Node) -> str:
        if not isinstance(node, yaml.ScalarNode) or node.value not in self.legs:
            shown = node.value if isinstance(node, yaml.ScalarNode) else "(a list or mapping)"
            shown = shown if len(shown) <= 40 else shown[:37] + "..."
            raise self.fail(f"unknown leg '{shown}'; the robot's legs are "
                            f"{', '.join(self.legs)}", node)
        return str(node.value)

    def legs_of(self, node: yaml.Node, key: str) -> tuple[str, ...]:
        items = node.value if isinstance(node, yaml.SequenceNode) else [node]
        legs = tuple(self.leg(item) for item in items)
        for i, leg in enumerate(legs):
            if leg in legs[:i]:
                raise self.fail(f"leg '{leg}' is listed twice under '{key}'", items[i])
        return legs

    def hazard(self, node: yaml.Node) -> str | None:
        value = node.value if isinstance(node, yaml.ScalarNode) else None
        if isinstance(value, str) and value.lower() in NONE_WORDS:
            return None
        if value not in self.hazards:
            known = ", ".join(self.hazards) if self.hazards else "(the spec declares none)"
            raise self.fail(f"unknown hazard set '{value}'; use one of {known}, or none", node)
        return str(value)

    def degrade(self, node: yaml.Node) -> tuple[tuple[str, int], ...]:
        """``[L1, L3]`` or ``L1`` (one level each) or ``{L1: 2}`` (levels lost per leg)."""
        if not isinstance(node, yaml.MappingNode):
            return tuple((leg, 1) for leg in self.legs_of(node, "degrade"))
        out: list[tuple[str, int]] = []
        for key, value in node.value:
            leg = self.leg(key)
            if leg in (named for named, _ in out):
                raise self.fail(f"leg '{leg}' is listed twice under 'degrade'", key)
            text = value.value if isinstance(value, yaml.ScalarNode) else None
            if not isinstance(text, str) or not text.isdigit() or int(text) < 1:
                raise self.fail(f"leg '{leg}' must lose a whole number of levels, at least 1",
                                value)
            out.append((leg, int(text)))
        return tuple(out)

    def health(self, node: yaml.Node) -> tuple[tuple[str, int], ...]:
        if not isinstance(node, yaml.MappingNode):
            raise self.fail("'health' must map legs to levels, e.g. {L1: 2}", node)
        out = []
        for key, value in node.value:
            leg = self.leg(key)
            try:
                level = int(value.value)
            except (ValueError, TypeError, AttributeError):
                raise self.fail(f"the level of leg '{leg}' must be an integer", value) from None
            if not 1 <= level <= self.legs[leg]:
                raise self.fail(f"leg '{leg}' has levels 1..{self.legs[leg]}, not {level}", value)
            out.append((leg, level))
        return tuple(out)

    def step(self, node: yaml.Node, what: str, keys: tuple[str, ...]) -> ScriptStep:
        if isinstance(node, yaml.ScalarNode) and node.value.lower() in ("", "null", "~", "{}"):
            return ScriptStep(_span(self.file, node))
        fields = self.mapping(node, what, keys)
        degrade = self.degrade(fields["degrade"]) if "degrade" in fields else ()
        fail = self.legs_of(fields["fail"], "fail") if "fail" in fields else ()
        health = self.health(fields["health"]) if "health" in fields else ()
        named = [leg for leg, _ in degrade] + list(fail) + [leg for leg, _ in health]
        for i, leg in enumerate(named):
            if leg in named[:i]:
                raise self.fail(f"{what} says two things about leg '{leg}'", node)
        hazard = self.hazard(fields["hazard"]) if "hazard" in fields else None
        return ScriptStep(_span(self.file, node), "hazard" not in fields, hazard, degrade, fail,
                          health)


def parse_scenario(text: str, model: Model, file: str = "<scenario>") -> Scenario:
    """Check a scenario's YAML against ``model`` (leg and hazard names, levels, keys)."""
    root = compose(text, file, ScenarioError, "scenario")
    reader = _Reader(file, model)
    if root is None:
        raise ScenarioError("scenario is empty; it needs a 'steps' list", Span(file, 1, 1))
    top = reader.mapping(root, "a scenario", TOP_KEYS)
    start = reader.step(top["start"], "'start'", START_KEYS) if "start" in top else None
    if "steps" not in top:
        raise reader.fail("scenario needs a 'steps' list", root)
    seq = top["steps"]
    if not isinstance(seq, yaml.SequenceNode):
        raise reader.fail("'steps' must be a list, one item per step", seq)
    steps = tuple(reader.step(item, f"step {i}", STEP_KEYS)
                  for i, item in enumerate(seq.value, 1))
    return Scenario(file, start, steps)


def load_scenario(path: str | Path, model: Model) -> Scenario:
    """Read and check a scenario file."""
    file = str(path)
    data = read_input(path, "scenario")
    return parse_scenario(decode_text(data, file, ScenarioError), model, file)


class ScriptedEnvironment(Environment):
    """Plays a :class:`Scenario`; the run ends after its last step.

    A step fixes what it mentions (hazard, named legs' levels); other legs keep their level
    when the controller allows it, otherwise the closest input it accepts (for example the
    reset of every leg in a cache region) is taken.
    """

    def __init__(self, scenario: Scenario, inputs: tuple[str, ...]) -> None:
        self.scenario = scenario
        self.inputs = inputs
        self.name = f"scripted {scenario.file}"

    def _wanted(self, step: ScriptStep, here: State) -> tuple[str | None, dict[str, int]]:
        hazard = here.hazard if step.keep_hazard else step.hazard
        levels: dict[str, int] = {}
        for leg, lost in step.degrade:
            if here.level(leg) == 1:
                raise ScenarioError(f"leg '{leg}' has already failed (level 1) and cannot "
                                    "degrade further", step.span)
            if here.level(leg) - lost < 1:
                raise ScenarioError(f"leg '{leg}' is at level {here.level(leg)} and cannot lose "
                                    f"{lost} levels; its lowest level is 1 (write 'fail: "
                                    f"{leg}')", step.span)
            levels[leg] = here.level(leg) - lost
        levels.update({leg: 1 for leg in step.fail})
        levels.update(dict(step.health))
        return hazard, levels

    def choose(self, situation: Situation) -> Request | None:
        index = situation.step
        domain = situation.domain
        if index == 0:
            step = self.scenario.start or ScriptStep(Span(self.scenario.file, 1, 1), False)
            initial = {leg.name: leg.initial for leg in domain.model.legs}
            here = State("", "", tuple(initial.items()), None)
            hazard, levels = self._wanted(step, here)
            levels = initial | levels  # the first state is given in full
        elif index - 1 < len(self.scenario.steps):
            step = self.scenario.steps[index - 1]
            assert situation.state is not None
            here = situation.state
            hazard, levels = self._wanted(step, here)
        else:
            return None
        best: tuple[int, Move] | None = None
        for move in situation.moves:
            if move.state.hazard != hazard:
                continue
            if any(move.state.level(leg) != lv for leg, lv in levels.items()):
                continue
            changes = sum(1 for leg, lv in move.state.health if lv != here.level(leg))
            if best is None or changes < best[0]:
                best = (changes, move)
        what = step.describe()
        if best is not None:
            return Request(best[1].inputs, what, step.span)
        wanted = State(here.region or domain.regions[0], here.gait or "noGait",
                       tuple((leg, levels.get(leg, lv)) for leg, lv in here.health), hazard)
        values = domain.encode(wanted)
        return Request(tuple(values[name] for name in self.inputs), what, step.span)
