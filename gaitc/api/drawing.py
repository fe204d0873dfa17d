"""Pictures of a spec and its controller (``gaitc render``), each a
:class:`~gaitc.sim.graphics.Picture` that saves in any Graphviz format and shows itself in a
notebook as SVG.

- :func:`draw_automaton`: the controller as an automaton over domain words, merged by
  region and gait when it is large, or the nodes within some steps of the start;
- :func:`controller_policy`: the controller projected to rules per region ("in region r,
  pursuing goal g, with these legs usable: use gait x"), as text, Markdown, HTML or a picture;
- :func:`compact_rules`: a compact controller's rules per goal, said only of the states a run
  reaches, and :func:`draw_rules`, the same as a picture (one table per goal);
- :func:`draw_map`: the region map, with a run's path and leg timeline;
- :func:`draw_spec`: the region graph with the gaits of each move.

A picture's format is one of :data:`FORMATS`, or the one :func:`output_format` reads from a
file name.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from gaitc.api.generating import compact_policy
from gaitc.api.simulation import session
from gaitc.core.spec import Spec, SpecLike, load
from gaitc.diagnostics import ScenarioError, Span, UsageError
from gaitc.sim.automaton_view import automaton_view
from gaitc.sim.graphics import FORMATS, Picture, output_format
from gaitc.sim.map_view import map_view, spec_view
from gaitc.sim.policy import controller_policy as project
from gaitc.sim.policy_view import policy_view, rules_view
from gaitc.sim.run import read_jsonl
from gaitc.sim.session import Session
from gaitc.sim.steps_view import steps_view
from gaitc.sim.strategy import explicit

if TYPE_CHECKING:
    from collections.abc import Sequence

    from gaitc.compact.controller import CompactController
    from gaitc.compact.rules import RuleTables
    from gaitc.ir.bddfile import SymbolicController
    from gaitc.ir.controller import Controller
    from gaitc.sim.policy import Policy
    from gaitc.sim.run import Run
    from gaitc.solver.progress import Progress
    from ltlcompiler.encoding import EncodingName
    from ltlcompiler.model import Model

__all__ = ["FORMATS", "Picture", "compact_rules", "controller_policy", "draw_automaton",
           "draw_map", "draw_policy", "draw_rules", "draw_spec", "output_format"]

def _check_steps(steps: int | None) -> None:
    if steps is not None and steps < 0:
        raise UsageError(f"--steps must be 0 or more (the moves from the start), not {steps}")


def draw_automaton(spec: Spec | str | Path, controller: Controller | str | Path | None = None,
                   *, quotient: str | None = None, steps: int | None = None,
                   max_nodes: int = 40, encoding: EncodingName | str | None = None,
                   prefer: str | Sequence[str] | None = None,
                   progress: Progress | None = None) -> Picture | None:
    """The controller of ``spec`` (synthesized when None) as an automaton; None when the spec
    is unrealizable. ``quotient`` merges nodes (``none``, ``region-gait``, ``region``; None
    picks one above ``max_nodes``); ``steps`` draws single nodes within that many moves of
    the start instead."""
    if max_nodes < 1:
        raise UsageError("--max-nodes must be at least 1")
    _check_steps(steps)
    if steps is not None and quotient is not None:
        raise UsageError("--steps draws single nodes; leave out --quotient")
    bound = session(spec, controller, encoding, prefer=prefer, progress=progress)
    if bound is None:
        return None
    if steps is not None:

        return steps_view(bound.strategy, bound.domain, steps, max_nodes)
    view = automaton_view(explicit(bound.strategy, "drawing the automaton"), bound.domain,
                          quotient, max_nodes)
    if quotient == "none" and len(bound.strategy) > max_nodes:
        view.notes = (*view.notes, f"the automaton has {len(bound.strategy)} nodes; "
                      "--quotient region-gait or --quotient region draws a smaller picture")
    return view


def controller_policy(spec: Spec | str | Path,
                      controller: Controller | str | Path | None = None, *,
                      steps: int | None = None, max_nodes: int = 2000,
                      max_rules: int | None = None, encoding: EncodingName | str | None = None,
                      prefer: str | Sequence[str] | None = None,
                      progress: Progress | None = None) -> tuple[Policy, Session] | None:
    """The controller's rules per region (and its session, for drawing them with
    :func:`draw_policy`); None when the spec is unrealizable."""
    if max_nodes < 1:
        raise UsageError("--max-nodes must be at least 1")
    _check_steps(steps)
    if max_rules is not None and max_rules < 1:
        raise UsageError("--max-rules must be at least 1")
    bound = session(spec, controller, encoding, prefer=prefer, progress=progress)
    if bound is None:
        return None
    return project(bound.strategy, bound.domain, steps, max_nodes, max_rules), bound


def draw_policy(policy: Policy, bound: Session) -> Picture:
    """``policy`` (of :func:`controller_policy`) drawn: one table per region of ``bound``'s
    spec, with arrows for its moves."""
    return policy_view(policy, bound.domain)


def compact_rules(spec: SpecLike, controller: CompactController | SymbolicController | str
                  | Path | None = None, *, all_rules: bool = False,
                  prefer: str | None = None) -> RuleTables | None:
    """The compact controller of ``spec`` (``controller`` compacted, or one synthesized) as
    one table of rules per goal, each rule checked against the states a run of it reaches
    under the spec's assumptions (:func:`gaitc.compact.rules.reach`): the never used ones
    are left out of the text and counted, or with ``all_rules`` listed and marked; its JSON
    lists them all.  None when the spec is unrealizable; the same tables as
    :func:`gaitc.api.generating.compact_policy`."""
    return compact_policy(spec, controller, all_rules=all_rules, prefer=prefer)


def draw_rules(tables: RuleTables) -> Picture:
    """``tables`` (of :func:`compact_rules`) drawn: one table per goal, stacked, each long
    condition wrapped, so the picture's width stays bounded however many rules it has."""
    return rules_view(tables)


def _model(spec: Spec | str | Path) -> Model:
    loaded = spec if isinstance(spec, Spec) else load(spec)
    if loaded.model is None:
        raise UsageError(f"'{loaded.path}': maps need a .gait spec")
    return loaded.model


def draw_map(spec: Spec | str | Path, run: Run | str | Path | None = None,
             max_steps: int = 30) -> Picture:
    """The region map of ``spec``; with ``run`` (or a run file), its path and leg timeline
    over the first ``max_steps`` steps. A run of another spec is refused."""
    model = _model(spec)
    path = None
    if isinstance(run, (str, Path)):
        path, run = str(run), read_jsonl(run)
    if run is not None:
        regions = {r.name for r in model.regions}
        legs = {leg.name for leg in model.legs}
        for step in run.steps:
            if step.region not in regions or not {leg for leg, _ in step.health} <= legs:
                raise ScenarioError(
                    f"this run does not belong to '{model.file or 'the spec'}': step "
                    f"{step.index} is in region '{step.region}'",
                    Span(path or run.spec_file or "<run>", 1, 1))
    return map_view(model, run, max_steps)


def draw_spec(spec: Spec | str | Path) -> Picture:
    """The region graph τ with the gaits of each move, and which legs each gait uses."""
    return spec_view(_model(spec))
