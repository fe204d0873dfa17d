"""The modes as types: every choice a command makes, defined once.

Each mode is a :class:`~gaitc.diagnostics.choices.Choice` (a ``str`` enumeration), so a
notebook may pass the member or its value and every layer compares members, never text.
Three of them are defined where the lower layers need them and re-exported here:
:class:`Semantics` (the initial-state semantics, :mod:`gaitc.ir.spec`),
:class:`ControllerKind` (a strategy or a counter-strategy, :mod:`gaitc.ir.spec` too) and
:class:`EncodingName` (the leg-health encoding, :mod:`ltlcompiler.encoding`).
"""

from __future__ import annotations

from typing import Final

from gaitc.diagnostics import UsageError
from gaitc.diagnostics.choices import Choice
from gaitc.ir.spec import ControllerKind, Semantics
from ltlcompiler.encoding import EncodingName

__all__ = ["AUTO_FORM", "FORM_CHOICES", "BackendKind", "ControllerKind", "EncodingName",
           "EnvironmentKind", "Form", "Outcome", "Role", "SearchMethod", "Semantics",
           "SurprisePolicy", "ViolationPolicy", "form_choice"]


class Form(Choice):
    """The form of a controller (one entry each in :mod:`gaitc.forms.registry`)."""

    EXPLICIT = "explicit"  # every node listed (docs/controller-format.md)
    SYMBOLIC = "symbolic"  # BDDs of the winning region and the strategy's relations
    COMPACT = "compact"  # decision diagrams over the spec's fields, for the valve board


#: ``synth --form``'s choice besides the forms themselves: explicit, unless the automaton
#: would pass the node limit, then symbolic.
AUTO_FORM: Final = "auto"
#: What ``synth --form`` and :func:`gaitc.synthesize`'s ``form`` take.
FORM_CHOICES: Final = (AUTO_FORM, *Form.values())


def form_choice(value: Form | str | None) -> Form | None:
    """The form ``value`` names (a member or its value), None for ``auto`` (or None); any
    other value is a :class:`UsageError` listing :data:`FORM_CHOICES`."""
    if value is None or value == AUTO_FORM:
        return None
    if isinstance(value, Form) or value in Form.values():
        return Form(value)
    raise UsageError(f"unknown controller form {value!r}; use one of {', '.join(FORM_CHOICES)}")


class EnvironmentKind(Choice):
    """Who plays the environment in a simulation or a drive."""

    SCRIPTED = "scripted"  # a scenario file (or a run file) says each input
    RANDOM = "random"  # uniform among the inputs the assumptions allow (seeded)
    ADVERSARIAL = "adversarial"  # the inputs that keep the robot from its goals longest
    STOCHASTIC = "stochastic"  # drawn from the rates of a rates file or --wear (gaitc chances)


class BackendKind(Choice):
    """What runs a controller's valve sequences, for ``drive`` and ``learn``."""

    SIM = "sim"  # the simulated robot: valves apply at once, readings from an environment
    PHYSICS = "physics"  # the robot file's spring-damper model moves the chassis (chapter 4)
    SERIAL = "serial"  # a valve board on a serial port: real valves, real sensors


class Role(Choice):
    """The side a user plays in the interactive player."""

    ENVIRONMENT = "environment"  # against a controller: the user picks the inputs
    ROBOT = "robot"  # against a counter-strategy: the user picks the robot's answers


class SearchMethod(Choice):
    """How a gait search explores (thesis chapters 2 and 5); one planner each in
    :mod:`gaitc.search.registry`."""

    CHAPTER2 = "chapter2"  # full for a small robot, else random (thesis 2.5)
    FULL = "full"
    RANDOM = "random"
    RESET = "reset"
    ASTAR = "astar"  # thesis chapter 5, toward a goal
    LPA = "lpa"
    DSTAR = "dstar"
    MCTS = "mcts"

    @property
    def is_global(self) -> bool:
        """A chapter 5 search in the global frame, toward a goal displacement."""
        return self in (SearchMethod.ASTAR, SearchMethod.LPA, SearchMethod.DSTAR,
                        SearchMethod.MCTS)


class Outcome(Choice):
    """What became of a run after an event the environment performed or an input that broke
    an assumption (decided by :mod:`gaitc.sim.recovery` on a host and by the recovery tables
    of :mod:`gaitc.compact.recovery` on the board; after Ehlers and Topcu, HSCC 2014)."""

    RECOVERED = "recovered"  # still winning: every goal, with the game's strategy
    DEGRADED = "degraded"  # only some goals are still achievable; those are pursued
    STOPPED = "stopped"  # no goal is achievable: to a cache if one is sure, then stop
    ALLOWED = "allowed"  # the event broke no assumption; the controller answered it


class SurprisePolicy(Choice):
    """What a run does when an observed input breaks an assumption (``--on-surprise``)."""

    RECOVER = "recover"  # go on from the state reached, degraded if need be (recovery.py)
    STOP = "stop"  # end the run with an error naming the assumption


class ViolationPolicy(Choice):
    """What the driver does with a reading that breaks the spec's assumptions
    (``drive --on-violation``)."""

    STOP = "stop"  # end the run with the broken assumption; every valve vented
    HOLD = "hold"  # take the allowed input closest to the levels the controller had
    WORST = "worst"  # take the allowed input with the lowest levels
    RECOVER = "recover"  # go on from the state sensed, as simulate recovers (recovery.py)
