"""Controller forms and the one reader every command reads a controller file through.

A controller comes in three forms: an explicit automaton (:mod:`gaitc.ir.controller`), BDDs
(:mod:`gaitc.ir.bddfile`) and decision diagrams over the robot's words
(:mod:`gaitc.compact`).  :func:`~gaitc.forms.reader.read_controller` decides the form once
and checks the file against the spec it is used with, so a controller of another spec is
refused with the same message by verify, simulate, render, play, drive and codegen.
"""
