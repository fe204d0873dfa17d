"""Playing a controller or a counter-strategy by hand (``gaitc play``).

:mod:`gaitc.play.player` is the model (legal moves, undo and redo, autopilots, the play as
a run); :mod:`gaitc.play.words` tells moves in the robot's words; :mod:`gaitc.play.mapgrid`
draws the map in text; :mod:`gaitc.play.terminal` is the terminal app (Textual) and
:mod:`gaitc.play.widget` the notebook widget (ipywidgets), both thin views of the model.
"""
