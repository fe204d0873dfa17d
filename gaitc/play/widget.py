"""The player in a notebook: an ipywidgets view of :class:`Player`.

The map is the SVG of :meth:`gaitc.play.mapgrid.MapGrid.svg`, the state a small table, each
legal move a button (its tooltip is the other side's answer, or why it loses), the moves
that break an assumption in a group of their own (:attr:`PlayerWidget.break_buttons`, their
tooltip the assumption broken), a log of the surprises met (each with its outcome:
recovered, degraded or stopped), and a row of controls: undo, redo, go to a step, the two
pilots and save. Every control calls the same
model as the terminal app, so a notebook and ``gaitc play`` play alike.
"""

from __future__ import annotations

from html import escape
from typing import Any

from gaitc.core.modes import Role
from gaitc.diagnostics import GaitcError, UsageError
from gaitc.play.mapgrid import MapGrid
from gaitc.play.player import Autopilot, Player

try:  # the notebook extra: pip install 'gaitc[notebook]'
    import ipywidgets as widgets
except ImportError:  # pragma: no cover - exercised without the extra
    widgets = None

DEFAULT_AUTO = 20


def _require() -> Any:
    if widgets is None:
        raise UsageError("the notebook player needs ipywidgets: pip install 'gaitc[notebook]' "
                         "(or pip install ipywidgets)")
    return widgets


class PlayerWidget:
    """A notebook widget over ``player``; :attr:`box` is what the notebook shows."""

    def __init__(self, player: Player, run_file: str = "play.run.jsonl") -> None:
        w = _require()
        self.player = player
        self.grid = MapGrid(player.session.model)
        self.map = w.HTML()
        self.status = w.HTML()
        self.turn = w.HTML()
        self.moves = w.VBox()
        self.breaks = w.VBox()
        self.log = w.HTML()
        self.message = w.HTML()
        self.buttons: list[Any] = []
        self.break_buttons: list[Any] = []
        self.undo_button = w.Button(description="undo", icon="undo")
        self.redo_button = w.Button(description="redo", icon="repeat")
        self.step_box = w.BoundedIntText(value=0, min=-1, max=0, description="step",
                                         layout=w.Layout(width="150px"))
        self.go_button = w.Button(description="go to step")
        self.count = w.BoundedIntText(value=DEFAULT_AUTO, min=1, max=10_000,
                                      description="steps", layout=w.Layout(width="150px"))
        self.strongest_button = w.Button(description="strongest pilot")
        self.random_button = w.Button(description="random pilot")
        self.file = w.Text(value=run_file, description="run file")
        self.save_button = w.Button(description="save")
        self.undo_button.on_click(lambda _b: self._do(self.player.undo))
        self.redo_button.on_click(lambda _b: self._do(self.player.redo))
        self.go_button.on_click(lambda _b: self._do(self.player.jump, self.step_box.value))
        self.strongest_button.on_click(lambda _b: self._auto(Autopilot.STRONGEST))
        self.random_button.on_click(lambda _b: self._auto(Autopilot.RANDOM))
        self.save_button.on_click(lambda _b: self._save())
        self.box = w.VBox([
            w.HBox([self.map, self.status]), self.turn, self.moves, self.breaks, self.log,
            w.HBox([self.undo_button, self.redo_button, self.step_box, self.go_button]),
            w.HBox([self.count, self.strongest_button, self.random_button]),
            w.HBox([self.file, self.save_button]), self.message])
        self.refresh()

    # ------------------------------------------------------------------ actions
    def play(self, number: int) -> None:
        """Play move ``number`` (as the buttons do): a legal move, or one numbered after
        them that breaks an assumption."""
        if number > len(self.player.choices()) and self.player.breaks():
            self._do(self.player.break_assumption, number)
        else:
            self._do(self.player.choose, number)

    def _do(self, action: Any, *args: Any) -> None:
        try:
            action(*args)
            self.message.value = ""
        except GaitcError as err:
            self.message.value = f"<b>{escape(err.message)}</b>"
        self.refresh()

    def _auto(self, pilot: Autopilot) -> None:
        self._do(self.player.autoplay, int(self.count.value), pilot)

    def _save(self) -> None:
        try:
            self.player.save(self.file.value)
            self.message.value = f"saved {self.player.step + 1} steps to {escape(self.file.value)}"
        except GaitcError as err:
            self.message.value = f"<b>{escape(err.message)}</b>"

    # ------------------------------------------------------------------ drawing
    def refresh(self) -> None:
        """Draw the map, the state and the moves of the player as it is now."""
        w = _require()
        player = self.player
        here = player.state
        goal = next((g.regions for g in player.domain.goals if g.label == player.goal), ())
        steps = player.steps
        self.map.value = self.grid.svg(here.region if here else None,
                                       here.hazard if here else None, goal,
                                       {s.region for s in steps}, [s.region for s in steps])
        self.status.value = self._status_html()
        over = player.over
        if over is not None:
            self.turn.value = f"<b>{escape(over)}</b>"
        elif player.role is Role.ROBOT:
            self.turn.value = (f"the environment: {escape(player.pending())}; "
                               "<b>your move as the robot</b>")
        else:
            self.turn.value = "<b>your move as the environment</b>"
        self.buttons = []
        for choice in player.choices():
            tip = choice.why if player.role is Role.ROBOT else \
                f"the controller answers: {choice.answer}"
            button = w.Button(description=f"{choice.number}. {choice.words}", tooltip=tip,
                              layout=w.Layout(width="auto"))
            button.on_click(lambda _b, n=choice.number: self.play(n))
            self.buttons.append(button)
        self.moves.children = tuple(self.buttons)
        self.break_buttons = []
        for choice in player.breaks():
            button = w.Button(description=f"{choice.number}. ! {choice.words}",
                              tooltip=f"breaks {choice.breaks}; {choice.answer}",
                              button_style="danger",
                              layout=w.Layout(width="auto"))
            button.on_click(lambda _b, n=choice.number: self.play(n))
            self.break_buttons.append(button)
        heading = w.HTML("<i>break an assumption (the controller recovers if it can):</i>")
        self.breaks.children = (heading, *self.break_buttons) if self.break_buttons else ()
        self.log.value = "<br>".join(f"surprise: {escape(s.words())}"
                                     for s in player.surprises)
        self.step_box.max = max(0, player.length - 1)
        self.step_box.value = max(-1, player.step)

    def _status_html(self) -> str:
        player = self.player
        here = player.state
        rows = [f"<b>step {player.step if player.step >= 0 else 'start'}</b> · you play the "
                f"{player.role}"]
        if here is not None:
            rows.append(f"in {escape(here.region)}, gait {escape(here.gait)}")
            rows.append(f"hazard: {escape(here.hazard or 'none')}")
        if player.goal is not None:
            rows.append(f"next goal: {escape(player.goal)}")
        full = player.session.full_health
        health = here.health if here else tuple((leg, full[leg]) for leg in player.domain.legs)
        legs = []
        for leg, level in health:
            colour = "#5b9bd5" if level >= full[leg] else ("#d64541" if level == 1 else
                                                           "#f2c94c")
            used = "*" if here is not None and leg in here.legs_used else ""
            legs.append(f'<span style="color:{colour}">{escape(leg)} {level}{used}</span>')
        rows.append(" ".join(legs))
        return "<div style='padding-left:1em'>" + "<br>".join(rows) + "</div>"

    def _repr_mimebundle_(self, **kwargs: Any) -> Any:
        return self.box._repr_mimebundle_(**kwargs)
