"""Computations in steps: generators whose every ``next`` runs a few BDD operations.

A long symbolic computation written this way (the preference relations of
:mod:`gaitc.solver.preferences`, the census of :mod:`gaitc.solver.census`) can run at once, or a
slice at a time beside other work that gives it a share of its own time.
"""

from __future__ import annotations

from collections.abc import Generator
from typing import TypeVar

T = TypeVar("T")
#: A computation in steps: each ``next`` runs a few BDD operations, the last returns.
Steps = Generator[None, None, T]


def run_through(steps: Steps[T]) -> T:
    """The value of ``steps``, run to the end at once."""
    while True:
        try:
            next(steps)
        except StopIteration as done:
            value: T = done.value
            return value


def given(value: T) -> Steps[T]:
    """A computation of no steps that returns ``value``."""
    return value
    yield  # a generator
