"""Compact controllers: a winning strategy as small decision diagrams over the robot's words.

Stages: :mod:`~gaitc.core.vocabulary` (the quantities a decision reads),
:mod:`~gaitc.compact.diagram` (the diagram builder that spends the strategy's freedom on size),
:mod:`~gaitc.compact.extraction` (from a solved game's relations to the smallest diagram),
:mod:`~gaitc.compact.controller` (the controller, its file and its run) and
:mod:`~gaitc.compact.rules` (the diagrams as tables of rules in domain words).
"""
