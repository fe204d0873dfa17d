"""Compact controllers for people and for boards: rule tables and generated C.

- :func:`compact_policy`: a compact controller as one table of rules per goal, in the
  robot's words, the rules a run never uses left out (``gaitc render policy --compact``);
  it displays itself in a notebook;
- :func:`generate`: C for a host or the valve board (``gaitc codegen``), after proving the
  controller against the spec, so a controller of another spec or a tampered file never
  reaches a robot.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from gaitc.api.solving import compact, read_controller, synthesize, verify
from gaitc.codegen.board import BoardTables, board_tables
from gaitc.codegen.build import FLASH_LIMIT, Built, Recovery, Target, build
from gaitc.codegen.recovery import FIRMWARE_BYTES, fit, none_fits, stops
from gaitc.codegen.tables import table_bytes
from gaitc.compact.controller import CompactController
from gaitc.compact.diagram import TooLarge
from gaitc.compact.recovery import RecoveryOptions, prove_recovery, recovering_controller
from gaitc.compact.rules import RuleTables, rule_tables
from gaitc.core.spec import Spec, SpecLike, as_gr1, resolve
from gaitc.diagnostics import ControllerError, Span, SpecSemanticError, UsageError
from gaitc.hw.driver import bind_primitives
from gaitc.ir.bddfile import SymbolicController
from gaitc.ir.controller import Controller
from gaitc.search.primitives import resolve_primitive
from gaitc.sim.domain import model_goals


def _goal_labels(spec: Spec | object) -> list[str]:
    if isinstance(spec, Spec) and spec.model is not None:

        return [g.label for g in model_goals(spec.model)]
    return []


def compact_of(spec: SpecLike, controller: CompactController | SymbolicController | Controller
               | str | Path | None = None, *, prefer: str | None = None
               ) -> CompactController | None:
    """The compact controller of ``spec``: ``controller`` in its compact form (a controller
    of any form is compacted, :meth:`gaitc.forms.base.ControllerForm.to_compact`), or
    (None) a new one synthesized; None when the spec is unrealizable."""
    resolved = resolve(spec)
    if controller is None:
        made = synthesize(resolved, form="compact", prefer=prefer)
        if made.controller is None:
            return None
        return compact(resolved, made.controller)
    found = (read_controller(controller, resolved) if isinstance(controller, (str, Path))
             else controller)
    return compact(resolved, found)


def compact_policy(spec: SpecLike, controller: CompactController | SymbolicController | str
                   | Path | None = None, *, all_rules: bool = False,
                   prefer: str | None = None) -> RuleTables | None:
    """The compact controller of ``spec`` (``controller`` compacted, or one synthesized) as
    one table of rules per goal, each rule checked against the states a run of it reaches
    under the spec's assumptions (:func:`gaitc.compact.rules.reach`): the never used ones
    are left out of the text and counted, or with ``all_rules`` listed and marked.  What
    ``gaitc render policy --compact`` prints (:func:`gaitc.api.drawing.compact_rules`);
    None when the spec is unrealizable."""
    resolved = resolve(spec)
    found = compact_of(resolved, controller, prefer=prefer)
    if found is None:
        return None
    return rule_tables(found, _goal_labels(resolved), table_bytes(found),
                       spec=as_gr1(resolved), all_rules=all_rules)


def generate(spec: SpecLike, controller: CompactController | SymbolicController | str | Path,
             target: Target | str, out_dir: str | Path, *, monitor: bool = True,
             recover: bool = False) -> Built:
    """C for ``target`` (``c`` or ``avr``) in ``out_dir``, from a compact (or symbolic)
    controller proved against ``spec`` first; a controller that fails the proof, or an AVR
    build that does not fit, writes nothing.  ``monitor=False`` leaves the assumption
    monitor out: the board then checks only that the levels it grades are in range, and
    says so (``monitor=0`` in its PING answer, ``GAITC_MONITOR 0`` in the header).

    ``recover`` adds the recovery and fallback tables of :mod:`gaitc.compact.recovery`
    (a surprise recovers, degrades to fewer goals or stops, instead of venting): the
    recovering controller is built from the spec's game, proved (its ordinary part and its
    surprise handling) and written instead of ``controller`` (so it is off by default: the
    moves written are then those of ``controller``).  On the board, fallbacks are dropped
    until the tables fit its flash; the surprises then stopped on are listed, in words, in
    ``Built.stops``.  Needs the monitor."""
    chosen = Target.parse(str(target), "--target")
    resolved = resolve(spec)
    file = str(controller) if isinstance(controller, (str, Path)) else ""
    found = compact_of(resolved, controller)
    assert found is not None
    report = verify(resolved, found)
    if not report.ok:
        name = resolved.path if isinstance(resolved, Spec) else "the spec"
        raise ControllerError(
            f"the controller does not realize {name}: {report.problems[0]}",
            Span(file or "<controller>", 1, 1),
            hint="it belongs to another spec or was changed; synthesize it again with "
            "'gaitc synth --compact'")
    if chosen == Target.AVR and any(len(f.labels) > 36 for f in found.vocabulary.inputs):
        raise UsageError("the board's C command reads one base-36 digit per input: an input "
                         "field with more than 36 values needs --target c")
    if not monitor:
        found = replace(found, assumed_root=None)
    recovery = None
    if recover:
        if not monitor:
            raise UsageError("recovery tables need the assumption monitor: drop --no-monitor "
                             "or --recover")
        recovery = _recovery(resolved, found, chosen, file)
        if recovery.controller is not None:
            found = recovery.controller.base
    return build(found, out_dir, chosen, file, _board(resolved, found, chosen), recovery)


def _recovery(spec: Spec | object, ctrl: CompactController, target: Target, file: str
              ) -> Recovery:
    """The recovering controller of ``spec``, proved, and trimmed to the board's flash."""
    gr1 = as_gr1(spec)  # type: ignore[arg-type]
    vocabulary = spec.vocabulary if isinstance(spec, Spec) else ctrl.vocabulary
    # on the board, building stops as soon as the diagrams pass its flash
    budget = FLASH_LIMIT - FIRMWARE_BYTES if target == Target.AVR else None
    try:
        rc = recovering_controller(gr1, vocabulary, ctrl.semantics,
                                   RecoveryOptions(budget=budget))
    except TooLarge as err:
        return Recovery(None, (none_fits(err.bytes, err.limit),))
    for report in (verify(spec, rc.base), prove_recovery(gr1, rc)):  # type: ignore[arg-type]
        if not report.ok:  # cannot happen; proved, not trusted
            raise ControllerError(f"the recovery tables failed their proof: "
                                  f"{report.problems[0]}", Span(file or "<controller>", 1, 1),
                                  hint="generate with --no-recover")
    if target != Target.AVR:
        return Recovery(rc, tuple(stops(rc)))
    trimmed, words = fit(rc, FLASH_LIMIT - FIRMWARE_BYTES)
    return Recovery(trimmed, tuple(words))


def _board(spec: Spec | object, ctrl: CompactController, target: Target) -> BoardTables | None:
    """The tables that let the board run the task alone: for the avr target, a robot spec
    whose every gait has a valve primitive (else the board only answers C commands)."""
    if target != Target.AVR or not isinstance(spec, Spec) or spec.model is None:
        return None
    if ctrl.vocabulary.domain != "robot":
        return None

    try:  # the valves drive binds: a primitive clause searches the robot file's model
        primitives = bind_primitives(spec.model, str(Path(spec.path).parent),
                                     resolve_primitive)
    except SpecSemanticError:
        return None
    return board_tables(ctrl, primitives)


__all__ = ["Target", "compact_of", "compact_policy", "generate"]
