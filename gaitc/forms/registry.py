"""The registry of controller forms: one entry per :class:`~gaitc.core.modes.Form`.

Every command that takes a controller asks here which form it is
(:func:`entry`, :func:`detect`) and then calls the entry's methods
(:class:`~gaitc.forms.base.ControllerForm`); nothing else tests a controller's class.
A new form is a subclass of :class:`~gaitc.forms.base.ControllerForm` decorated with
:func:`register`, plus its member of :class:`~gaitc.core.modes.Form`.
"""

from __future__ import annotations

from typing import Any, TypeVar

from gaitc.core.modes import Form
from gaitc.diagnostics import UsageError
from gaitc.forms.base import ControllerForm
from gaitc.forms.compact import CompactForm
from gaitc.forms.explicit import ExplicitForm
from gaitc.forms.symbolic import SymbolicForm

F = TypeVar("F", bound=type[ControllerForm])

#: Every registered form, by name; the fallback for a file that names no form comes last.
FORMS: dict[Form, ControllerForm] = {}
#: The form of a file that names none (the oldest format, SLUGS's automaton).
FALLBACK = Form.EXPLICIT


def register(cls: F) -> F:
    """Add the form ``cls`` implements to :data:`FORMS` (a class decorator)."""
    if cls.form in FORMS:
        raise ValueError(f"controller form {cls.form} is registered twice")
    FORMS[cls.form] = cls()
    return cls


for _cls in (SymbolicForm, CompactForm, ExplicitForm):
    register(_cls)


def entry(automaton: object) -> ControllerForm:
    """The form of a controller object."""
    for form in FORMS.values():
        if form.owns(automaton):
            return form
    raise UsageError(f"not a controller: {type(automaton).__name__}")


def entry_of(form: Form | str) -> ControllerForm:
    """The registered entry of ``form`` (a member or its name)."""
    return FORMS[Form.parse(form, "controller form")]


def detect(data: Any) -> ControllerForm:
    """The form of a parsed controller file, from its header alone."""
    for form, found in FORMS.items():
        if form != FALLBACK and found.recognises(data):
            return found
    return FORMS[FALLBACK]


def form_of(data: Any) -> Form:
    """The form of a parsed controller file (explicit unless it says otherwise)."""
    return detect(data).form
