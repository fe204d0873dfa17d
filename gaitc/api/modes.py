"""The modes, as the facade names them: every choice a command offers, as a type.

The enumerations are :mod:`gaitc.core.modes`'s (each a ``str`` enumeration: a member equals
its value, and ``Enum.values()`` lists the values for a command line's ``choices=``); the
encodings of a ``.gait`` spec are :mod:`ltlcompiler.encoding`'s.
"""

from __future__ import annotations

from gaitc.core.modes import (
    FORM_CHOICES,
    BackendKind,
    ControllerKind,
    EncodingName,
    EnvironmentKind,
    Form,
    Role,
    SearchMethod,
    Semantics,
    form_choice,
)
from ltlcompiler.encoding import ENCODINGS

__all__ = ["ENCODINGS", "FORM_CHOICES", "BackendKind", "ControllerKind", "EncodingName",
           "EnvironmentKind", "Form", "Role", "SearchMethod", "Semantics", "form_choice"]
