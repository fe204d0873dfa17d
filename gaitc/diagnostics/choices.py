"""Modes as types: the base of gaitc's enumerations of named choices.

A :class:`Choice` is a ``str`` enumeration: its members compare equal to, print as and
serialise to their values (``Semantics.ROBOTICS == "robotics"``, ``f"{m}"`` gives the value,
``json.dumps`` writes it), so a notebook may pass either the member or its name, and the
library converts at its edge with :meth:`Choice.parse`, which names the accepted values in
a :class:`~gaitc.diagnostics.UsageError`.  It is an ``enum.StrEnum`` with that parser (its
``__str__`` and ``__format__`` spelled out, as the members print everywhere).
"""

from __future__ import annotations

from enum import StrEnum
from typing import TypeVar

from gaitc.diagnostics import UsageError

C = TypeVar("C", bound="Choice")


class Choice(StrEnum):
    """A named choice among fixed values (see the module's docstring)."""

    def __str__(self) -> str:
        return str(self.value)

    def __format__(self, spec: str) -> str:
        return format(str(self.value), spec)

    @classmethod
    def parse(cls: type[C], value: object, what: str | None = None) -> C:
        """``value`` as a member (a member, or its value as text); an unknown value is a
        :class:`UsageError` naming ``what`` (default: the class's name in words) and the
        accepted values."""
        if isinstance(value, cls):
            return value
        for member in cls:
            if member.value == value:
                return member
        name = what or cls.__name__.lower()
        raise UsageError(f"unknown {name} {value!r}; use one of "
                         f"{', '.join(str(m.value) for m in cls)}")

    @classmethod
    def values(cls) -> tuple[str, ...]:
        """Every member's value, in declaration order (for argparse's ``choices``)."""
        return tuple(str(m.value) for m in cls)
