"""Controller forms: one registry of the forms a controller takes, and the one reader.

A controller comes in three forms: an explicit automaton (:mod:`gaitc.forms.explicit`),
BDDs of its relations (:mod:`gaitc.forms.symbolic`) and decision diagrams over the robot's
words (:mod:`gaitc.forms.compact`).  Each is one :class:`~gaitc.forms.base.ControllerForm`
registered in :mod:`gaitc.forms.registry`, which says how to read, write, prove, run,
measure and compact it; :func:`~gaitc.forms.reader.read_controller` decides a file's form
once and checks the file against the spec it is used with, so a controller of another spec
is refused with the same message by verify, simulate, render, play, drive and codegen.
"""
