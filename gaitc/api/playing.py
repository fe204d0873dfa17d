"""Playing by hand: a :class:`gaitc.play.player.Player` bound to a ``.gait`` spec.

:func:`player` is what ``gaitc play`` and the notebook widget start from: the spec's
controller (read from a file or synthesized) with the user as the environment, or, for an
unrealizable spec, the environment's counter-strategy with the user as the robot.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from gaitc.api.answers import explain
from gaitc.api.simulation import ControllerLike, counter_session, session
from gaitc.api.solving import read_once, recorded_encoding
from gaitc.core.modes import Role
from gaitc.core.spec import Spec, load
from gaitc.diagnostics import ScenarioError, UsageError
from gaitc.forms.reader import ControllerFile
from gaitc.ir.spec import Semantics
from gaitc.play.player import Autopilot, Choice, Player
from gaitc.play.widget import PlayerWidget
from gaitc.sim.run import Run, read_jsonl
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.play.widget import PlayerWidget
    from gaitc.solver.progress import Progress

__all__ = ["Autopilot", "Choice", "Player", "Role", "player", "player_widget"]


def player(spec: Spec | str | Path,
           controller: ControllerLike | None = None,
           *, against: bool | None = None, start: Run | str | Path | None = None,
           at: int | None = None, encoding: EncodingName | str | None = None,
           semantics: Semantics | str = Semantics.DEFAULT,
           progress: Progress | None = None) -> Player:
    """A play of ``spec`` to step by hand.

    With ``against`` unset, the user plays the environment against ``controller`` (a file,
    an automaton, or synthesized here) when the spec is realizable, and the robot against
    the environment's counter-strategy when it is not; ``against=True`` asks for the
    counter-strategy and is an error for a realizable spec. ``start`` (a run or a run file:
    a saved play, ``simulate --out`` or ``explain --out``) replays its steps up to ``at``
    (default: all) before the play goes on, its broken assumptions too. Playing the
    environment, :meth:`Player.breaks` lists the moves that break an assumption and
    :meth:`Player.break_assumption` performs one: the controller recovers as in
    ``simulate --violate`` (``semantics`` is also that of the games recovery solves).
    """
    if against and controller is not None:
        raise UsageError("--against plays the robot against the environment's counter-"
                         "strategy; a CONTROLLER is for playing the environment")
    controller = read_once(controller)
    if not isinstance(spec, Spec):
        if encoding is None and isinstance(controller, (str, Path, ControllerFile)):
            encoding = recorded_encoding(controller)
        spec = load(spec, encoding or EncodingName.ONEHOT)
    bound = None if against else session(spec, controller, None, semantics, progress=progress)
    if bound is None:
        bound = counter_session(spec, semantics, progress)
        if bound is None:
            raise UsageError(f"'{spec.path}' is realizable: the environment has no winning "
                             "strategy to play against; play the environment against the "
                             "controller (leave out --against)")
    played = Player(bound, semantics=semantics)
    if start is not None:
        run = start if isinstance(start, Run) else read_jsonl(start)
        try:
            played.resume(run, at)
        except ScenarioError:
            if played.role is not Role.ROBOT:
                raise
            played = _explains_player(spec, semantics, run, at)
    elif at is not None:
        raise UsageError("--at picks a step of the run given with --from")
    return played


def _explains_player(spec: Spec, semantics: Semantics | str, run: Run,
                     at: int | None) -> Player:
    """The robot's play against ``explain``'s counter-strategy, resumed from ``run``.

    ``explain`` plays the environment restricted to the freedoms it needs, so its play may
    leave the counter-strategy of the whole spec; the play is then resumed against the one
    it came from. When that cannot follow the run either, its error stands."""
    counter = explain(spec, semantics, repairs=False).counter
    if counter is None:
        raise ScenarioError("the run cannot be played against this spec's counter-strategy",
                            None)
    bound = session(spec, counter, None, semantics)
    assert bound is not None
    played = Player(bound, Role.ROBOT, semantics)
    played.resume(run, at)
    return played


def player_widget(spec: Spec | str | Path | Player,
                  controller: ControllerLike | None = None, *, against: bool | None = None,
                  start: Run | str | Path | None = None,
                  at: int | None = None, encoding: EncodingName | str | None = None,
                  semantics: Semantics | str = Semantics.DEFAULT) -> PlayerWidget:
    """The player as a notebook widget (ipywidgets): the map as SVG, the moves as buttons,
    undo, redo and the autopilots; the options are those of :func:`player`, or give a
    :class:`Player` itself."""
    bound = spec if isinstance(spec, Player) else player(
        spec, controller, against=against, start=start, at=at, encoding=encoding,
        semantics=semantics)
    return PlayerWidget(bound)
