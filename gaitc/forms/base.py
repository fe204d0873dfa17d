"""The controller-form interface: what every form of controller offers every command.

A controller is kept in one of several forms (:class:`~gaitc.core.modes.Form`): an
explicit automaton, BDDs of the strategy's relations, decision diagrams over the robot's
words.  Each form is one subclass of :class:`ControllerForm`, registered once in
:mod:`gaitc.forms.registry`; every command that takes a controller reaches its form
through that registry, so adding a form is one registered class and one enum member
(``docs/background/layout.md`` lists the steps).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, TypeAlias

from gaitc.core.modes import Form, Semantics
from gaitc.diagnostics import UsageError

if TYPE_CHECKING:
    from gaitc.compact.controller import CompactController
    from gaitc.core.spec import Spec
    from gaitc.core.vocabulary import Vocabulary
    from gaitc.ir.bddfile import SymbolicController
    from gaitc.ir.controller import Controller
    from gaitc.sim.view import StrategyView
    from gaitc.verifier.strategy import VerificationReport

#: A controller in any of its forms.
Automaton: TypeAlias = "Controller | SymbolicController | CompactController"


class ControllerForm(ABC):
    """One form of controller: how it is recognised, read, written, proved, run, measured
    and turned into the compact form the valve board runs."""

    #: The form's name, as files and ``--json`` output write it.
    form: ClassVar[Form]

    @abstractmethod
    def owns(self, automaton: object) -> bool:
        """Whether ``automaton`` is a controller of this form."""

    @abstractmethod
    def recognises(self, data: Any) -> bool:
        """Whether a parsed controller file is of this form (by its header alone)."""

    @abstractmethod
    def parse(self, data: Any, file: str, spec: Spec) -> Automaton:
        """The controller in a parsed file, its own structure checked (not yet that it
        belongs to ``spec``: :func:`gaitc.forms.registry.read_controller` does both)."""

    def vocabulary(self, automaton: Any) -> Vocabulary | None:
        """The fields the controller decides in, when its form has its own (they must be
        the spec's, :attr:`gaitc.core.spec.Spec.vocabulary`); None by default."""
        return None

    @abstractmethod
    def to_json(self, automaton: Any) -> str:
        """The controller file's text (``docs/controller-format.md``)."""

    def to_file(self, automaton: Any, path: str | Path, layout: str | None = None
                ) -> str | bytes:
        """The controller file's contents for the file ``path``: the form's JSON text
        (:meth:`to_json`) unless the form has other layouts (``layout``, or one the name
        asks for)."""
        if layout is not None:
            raise UsageError(f"a {self.form} controller has one file layout, JSON; "
                             f"'{layout}' is a layout of explicit controllers")
        return self.to_json(automaton)

    @abstractmethod
    def verify(self, spec: Spec, automaton: Any, semantics: Semantics) -> VerificationReport:
        """The independent proof (:mod:`gaitc.verifier`) that ``automaton`` realizes
        ``spec`` (or, for a counter-strategy, defeats it); the vocabulary was checked
        before."""

    @abstractmethod
    def runtime(self, spec: Spec, automaton: Any, file: str = "") -> StrategyView:
        """The controller as a run sees it: nodes, their values and successors
        (:class:`gaitc.sim.view.StrategyView`), for simulate, play, drive and the pictures."""

    @abstractmethod
    def size(self, automaton: Any) -> str:
        """The controller's size in words (``gaitc synth`` prints it)."""

    @abstractmethod
    def size_json(self, automaton: Any) -> dict[str, Any]:
        """The controller's size for ``--json``: ``nodes`` and the form's own figures."""

    @abstractmethod
    def to_compact(self, spec: Spec, automaton: Any) -> CompactController:
        """The same controller as decision diagrams over ``spec``'s fields
        (:mod:`gaitc.compact`), which code generation needs; the caller proves it."""
