"""The player in a terminal (``gaitc play``): a Textual app over :class:`Player`.

The screen fits 80 x 24: the map (:mod:`gaitc.play.mapgrid`) and the robot's state side by
side, the legal moves below with the other side's answer to the highlighted one, and a
line for questions (how many steps, which file). The map takes the width the state leaves
(:data:`STATE_WIDTH`); a map wider than that labels its cells with short names, and one
wider or taller still scrolls (tab focuses it, the arrows scroll it) and keeps the robot in
view. A row of cells is never wrapped. Keyboard only; ``?`` lists the keys. Every mark
reads without colour (``NO_COLOR`` or ``--no-color``). Playing the environment, the moves
that break an assumption follow the legal ones in a group of their own, each marked ``!``
with the assumption it breaks; playing one shows the surprise (the assumption broken and
what became of the run: recovered, degraded or stopped) in the log below the moves.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, ClassVar

from rich.text import Text
from textual import events
from textual.app import App, ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal, ScrollableContainer
from textual.geometry import Region
from textual.screen import ModalScreen
from textual.widgets import Footer, Input, OptionList, Static
from textual.widgets.option_list import Option

from gaitc.core.modes import Role
from gaitc.diagnostics import GaitcError
from gaitc.play.mapgrid import MapGrid
from gaitc.play.player import Autopilot, Choice, Player

#: Rich styles of the text map's style names and the health levels.
COLOURS = {"robot": "bold reverse", "hazard_on": "bold white on red", "hazard": "yellow",
           "cache": "green", "goal": "magenta", "next_goal": "bold magenta underline",
           "visited": "cyan", "legend": "dim", "healthy": "blue", "degraded": "yellow",
           "failed": "bold red", "loses": "red", "holds": "yellow", "breaks": "bold red",
           "heading": "bold", "log": "italic"}
#: The heading of the group of moves that break an assumption.
BREAKS_HEADING = "break an assumption (! the controller recovers if it can):"
#: The surprises the log shows at most (the latest).
LOG_LINES = 2
DEFAULT_AUTO = 20
#: Steps a pilot may be asked for at once (each step is a move of the controller and of the
#: pilot; 10**7 of them kept the app busy for minutes): more is refused with this number.
MAX_AUTO = 10_000
STATE_WIDTH = 30  # columns the robot's state keeps beside the map (50 left of 80 for it)
DEFAULT_RUN_FILE = "play.run.jsonl"

KEYS = """\
 1-9   play move 1-9             enter   play the highlighted move
       (moves marked ! break an assumption; the controller recovers)
 ↑ ↓   highlight a move          u  r    undo, redo
 g     go to a step              s       save the play as a run file
 a     the strongest pilot plays N steps (you are asked for N)
 n     a random pilot plays N steps
 tab   the map: the arrows scroll it (a map too big to show whole)
 ?     this help                 q       quit (saving to --out first)

Playing the environment, the strongest pilot is the adversarial
environment of 'gaitc simulate'; playing the robot, it is the robot
that holds out longest. 'gaitc render map SPEC --run FILE' draws a
saved play; 'gaitc simulate SPEC --env scripted FILE' replays it."""


class HelpScreen(ModalScreen[None]):
    """The keys, over the play; any key closes it."""

    def compose(self) -> ComposeResult:
        yield Static(Text(KEYS), id="help")

    def on_key(self) -> None:
        self.dismiss()


class MoveList(OptionList):
    """The legal moves: Textual's option list, whose page keys also work when the list has
    no room on a tiny screen (Textual's own look up a line the list never laid out, and
    fail with KeyError); with no room, a page is one move."""

    def action_page_up(self) -> None:
        if self.scrollable_content_region or self.highlighted is None:
            super().action_page_up()  # type: ignore[no-untyped-call]
        elif self.highlighted > 0:
            self.action_cursor_up()

    def action_page_down(self) -> None:
        if self.scrollable_content_region or self.highlighted is None:
            super().action_page_down()  # type: ignore[no-untyped-call]
        elif self.highlighted < self.option_count - 1:
            self.action_cursor_down()


class PlayCrash(RuntimeError):
    """The terminal app stopped on an error of its own (a bug, shown above by Textual)."""


class PlayApp(App[int]):
    """The terminal player; :attr:`saved` is the file the play was last saved to."""

    CSS = """
    #top { height: auto; max-height: 14; }
    #map { width: 40; height: auto; max-height: 14; scrollbar-size: 1 1; }
    #mapview { width: auto; height: auto; text-wrap: nowrap; }
    #state { width: 1fr; height: auto; padding: 0 1; }
    #turn { height: 1; }
    #moves { height: 1fr; min-height: 3; }
    #answer { height: 1; }
    #log { height: auto; max-height: 3; display: none; }
    #ask { dock: bottom; display: none; }
    #help { width: 80; height: auto; border: round $accent; padding: 0 1; }
    HelpScreen { align: center middle; }
    """
    # Textual's command palette (ctrl+p) offers nothing the keys do not, and its list has
    # the page keys' KeyError on a tiny screen, which MoveList mends for the moves
    ENABLE_COMMAND_PALETTE = False
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("question_mark", "help", "help", key_display="?"),
        Binding("u", "undo", "undo"),
        Binding("r", "redo", "redo"),
        Binding("g", "ask('go')", "go to"),
        Binding("a", "ask('strongest')", "pilot"),
        Binding("n", "ask('random')", "random"),
        Binding("s", "ask('save')", "save"),
        Binding("q", "quit_play", "quit"),
        *[Binding(str(k), f"play({k})", show=False) for k in range(1, 10)],
    ]

    def __init__(self, player: Player, out: str | Path | None = None, seed: int = 0) -> None:
        super().__init__()
        self.player = player
        self.out = str(out) if out is not None else None
        self.saved: str | None = None
        self.seed = seed
        self.mapgrid = MapGrid(player.session.model)
        self._asking: str | None = None
        self._saved_path: tuple[object, ...] | None = None
        self.message = ""

    # ------------------------------------------------------------------ layout
    def compose(self) -> ComposeResult:
        with Horizontal(id="top"):
            with ScrollableContainer(id="map"):
                yield Static(id="mapview")
            yield Static(id="state")
        yield Static(id="turn")
        yield MoveList(id="moves")
        yield Static(id="answer")
        yield Static(id="log")
        yield Input(id="ask")
        yield Footer()

    def on_mount(self) -> None:
        self.title = f"gaitc play {self.player.session.spec.path}"
        self._fit_map(self.size.width)
        self.refresh_play()
        self.query_one("#moves", OptionList).focus()

    def on_resize(self, event: events.Resize) -> None:
        self._fit_map(event.size.width)  # the app's own size may not have followed yet
        self.refresh_play()

    def _fit_map(self, screen: int) -> None:
        """Give the map the columns that the state leaves of a screen ``screen`` columns
        wide, and its cells the labels that fit in them less one (the vertical scroll bar's)."""
        grid = self.mapgrid
        room = max(1, screen - STATE_WIDTH)
        grid.fit(room - 1)
        drawn = max(grid.cols * grid.width, *(len(line) for line in grid.legend()))
        self.query_one("#map").styles.width = min(drawn + 1, room)

    # ------------------------------------------------------------------ drawing
    def refresh_play(self) -> None:
        player = self.player
        here = player.state
        goal = player.goal
        goal_regions = next((g.regions for g in player.domain.goals if g.label == goal), ())
        visited = {s.region for s in player.steps}
        lines = self.mapgrid.lines(here.region if here else None, here.hazard if here else None,
                                   goal_regions, visited)
        picture = Text(no_wrap=True)
        for line in lines:
            for text, style in line:
                picture.append(text, COLOURS.get(style, ""))
            picture.append("\n")
        picture.append("\n".join(self.mapgrid.legend()), COLOURS["legend"])
        self.query_one("#mapview", Static).update(picture)
        self.query_one("#state", Static).update(self._state_text())
        self._fill_moves()
        self._fill_log()
        self.call_after_refresh(self._show_robot)

    def _show_robot(self) -> None:
        """Scroll the map (when it scrolls) so that the robot's cell is in view."""
        here = self.player.state
        grid = self.mapgrid
        if here is None or here.region not in grid.cells:
            return
        row, col = grid.cells[here.region]
        self.query_one("#map", ScrollableContainer).scroll_to_region(
            Region(col * grid.width, row, grid.width, 1), animate=False, immediate=True)

    def _state_text(self) -> Text:
        player = self.player
        here = player.state
        out = Text()
        out.append(f"step {player.step}" if player.step >= 0 else "start", "bold")
        if player.length > player.step + 1:
            out.append(f" of {player.length - 1}")
        out.append(f" · you play the {player.role}\n")
        if here is None:
            out.append("no state yet: choose how the play starts\n")
        else:
            gait = f"{here.gait} ({', '.join(here.legs_used)})" if here.legs_used else here.gait
            out.append(f"in {here.region}, gait {gait}\n")
            out.append(f"hazard: {here.hazard or 'none'}\n")
        if player.goal is not None:
            out.append(f"next goal: {player.goal}\n", COLOURS["goal"])
        full = player.session.full_health
        for i, (leg, level) in enumerate(here.health if here else
                                         tuple((leg, full[leg]) for leg in player.domain.legs)):
            kind = "healthy" if level >= full[leg] else ("failed" if level == 1 else "degraded")
            used = here is not None and leg in here.legs_used
            out.append(f"{leg} {level}{'*' if used else ' '}", COLOURS[kind])
            out.append("\n" if i % 4 == 3 else "  ")
        if self.message:
            out.append(f"\n{self.message}", "italic")
        return out

    def _fill_moves(self) -> None:
        player = self.player
        moves = self.query_one("#moves", OptionList)
        moves.clear_options()
        choices = player.choices()
        turn = self.query_one("#turn", Static)
        over = player.over
        if over is not None:
            turn.update(Text(over, COLOURS["failed"]))
        elif player.role is Role.ROBOT:
            turn.update(Text(f"the environment: {player.pending()}; your move as the robot:"))
        else:
            turn.update(Text("your move as the environment:"))
        for choice in choices:
            label = Text(f"{choice.number:>2} {choice.words}")
            if player.role is Role.ROBOT:
                mark = "x" if choice.loses_in is not None else "~"
                label.append(f"  {mark} {choice.why}",
                             COLOURS["loses" if choice.loses_in is not None else "holds"])
            moves.add_option(Option(label, id=str(choice.number)))
        breaks = player.breaks()
        if breaks:
            moves.add_option(Option(Text(BREAKS_HEADING, COLOURS["heading"]), disabled=True))
        for choice in breaks:
            label = Text(f"{choice.number:>2} {choice.words}")
            label.append(f"  ! {choice.breaks}", COLOURS["breaks"])
            moves.add_option(Option(label, id=str(choice.number)))
        if choices or breaks:
            moves.highlighted = 0 if choices else 1  # 1: the first break, after its heading
        self._show_answer()

    def _fill_log(self) -> None:
        """The latest surprises of the play, each with the assumption broken and what
        became of the run (hidden while there is none)."""
        log = self.query_one("#log", Static)
        surprises = self.player.surprises[-LOG_LINES:]
        log.display = bool(surprises)
        log.update(Text("\n".join(f"surprise: {s.words()}" for s in surprises),
                        COLOURS["log"]))

    def _highlighted(self) -> Choice | None:
        """The move the list highlights (a legal one or one that breaks an assumption)."""
        moves = self.query_one("#moves", OptionList)
        index = moves.highlighted
        if index is None or not 0 <= index < moves.option_count:
            return None
        number = moves.get_option_at_index(index).id
        return self._numbered(int(number)) if number else None

    def _numbered(self, number: int) -> Choice | None:
        player = self.player
        return next((c for c in (*player.choices(), *player.breaks()) if c.number == number),
                    None)

    def _show_answer(self) -> None:
        answer = self.query_one("#answer", Static)
        choice = self._highlighted()
        if choice is None:
            answer.update("")
        elif choice.event is not None:
            answer.update(Text(f"→ {choice.answer}", "dim"))
        elif self.player.role is Role.ENVIRONMENT:
            answer.update(Text(f"→ the controller answers: {choice.answer}", "dim"))
        else:
            answer.update(Text(f"→ {choice.why}", "dim"))

    def on_option_list_option_highlighted(self, _event: OptionList.OptionHighlighted) -> None:
        self._show_answer()

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        self.action_play(int(event.option.id or "0"))

    # ------------------------------------------------------------------ actions
    def _say(self, message: str) -> None:
        self.message = message
        self.refresh_play()

    def action_play(self, number: int) -> None:
        choice = self._numbered(number)
        if choice is None:
            self.bell()
            return
        if choice.event is None:
            step = self.player.choose(number)
            self._say(f"played move {number}; now in {step.region}")
            return
        step = self.player.break_assumption(number)
        outcome = self.player.surprises[-1].outcome
        self._say(f"broke an assumption with move {number} ({choice.words}): {outcome}; "
                  f"now in {step.region}")

    def action_undo(self) -> None:
        self._say("undone" if self.player.undo() else "nothing to undo")

    def action_redo(self) -> None:
        self._say("redone" if self.player.redo() else "nothing to redo")

    def action_help(self) -> None:
        self.push_screen(HelpScreen())

    def action_ask(self, what: str) -> None:
        questions = {
            "go": f"go to step (-1..{self.player.length - 1}):",
            "strongest": f"steps for the strongest pilot (up to {MAX_AUTO}) [{DEFAULT_AUTO}]:",
            "random": f"steps for a random pilot (up to {MAX_AUTO}) [{DEFAULT_AUTO}]:",
            "save": f"save the play to [{self.out or DEFAULT_RUN_FILE}]:",
        }
        self._asking = what
        ask = self.query_one("#ask", Input)
        ask.placeholder = questions[what]
        ask.value = ""
        ask.display = True
        ask.focus()

    def on_input_submitted(self, event: Input.Submitted) -> None:
        what, self._asking = self._asking, None
        ask = self.query_one("#ask", Input)
        ask.display = False
        self.query_one("#moves", OptionList).focus()
        answer = event.value.strip()
        try:
            if what == "go":
                self.player.jump(int(answer))
                self._say(f"at step {self.player.step}")
            elif what in ("strongest", "random"):
                count = int(answer) if answer else DEFAULT_AUTO
                if count > MAX_AUTO:
                    self._say(f"too many steps: a pilot plays at most {MAX_AUTO} steps at a "
                              "time (ask again to play on)")
                    return
                played = self.player.autoplay(count, Autopilot(what), self.seed)
                self._say(f"the {what} pilot played {played} steps")
            elif what == "save":
                self._save(answer or self.out or DEFAULT_RUN_FILE)
        except ValueError as err:
            message = err.message if isinstance(err, GaitcError) else f"not a number: {answer}"
            self._say(message)
        except GaitcError as err:
            self._say(err.message)

    def on_key(self, event: object) -> None:
        key = getattr(event, "key", "")
        if key == "escape" and self._asking is not None:
            self._asking = None
            self.query_one("#ask", Input).display = False
            self.query_one("#moves", OptionList).focus()

    def _save(self, path: str) -> None:
        self.player.save(path)
        self.saved = path
        self._saved_path = self._played()
        self._say(f"saved {self.player.step + 1} steps to {path}")

    def _unsaved(self) -> bool:
        """Whether the play has moves not yet saved, and a file they are to be saved to."""
        return (self.player.step >= 0 and self.out is not None
                and self._saved_path != self._played())

    def _played(self) -> tuple[object, ...]:
        """What a save keeps of the play: its states and its surprises."""
        return (*self.player.steps, *self.player.surprises)

    def action_quit_play(self) -> None:
        """Quit; a play with unsaved moves is saved to ``out`` first (every play is kept)."""
        if self._unsaved():
            try:
                self._save(self.out or DEFAULT_RUN_FILE)
            except GaitcError as err:
                self._say(f"{err.message}; save elsewhere with s, or quit again to drop it")
                self.out = None
                return
        self.exit(0)

    def play(self, **run: Any) -> str | None:
        """Run the app (``run``: Textual's options of :meth:`App.run`) until it ends; the
        file the play was last saved to.  However it ends (quitting with ``q`` or Textual's
        ctrl+q, an interruption, an error inside the app), unsaved moves are then saved to
        ``out``; an error inside the app is a :class:`PlayCrash` that says where the play
        went (Textual has shown its traceback)."""
        try:
            self.run(**run)
        finally:
            if self._unsaved():
                self.player.save(self.out or DEFAULT_RUN_FILE)
                self.saved, self._saved_path = self.out, self._played()
        if self.return_code:
            played = self.player.played_words()
            kept = (f"{played} is saved in {self.saved}" if self.saved
                    else "no move had been played" if self.player.moves == 0
                    else f"{played} is not saved (no file to save it to)")
            raise PlayCrash(f"the player stopped on an error of its own; {kept}")
        return self.saved


def play_in_terminal(player: Player, out: str | Path | None = None, seed: int = 0) -> str | None:
    """Run the terminal player until the user quits; the file the play was saved to."""
    return PlayApp(player, out, seed).play()
