"""Reading a controller file of any form and checking that it belongs to a spec.

The proof (:mod:`gaitc.verifier`) covers the logic of a controller; what the runtimes and
generated code use besides the logic is the file's vocabulary: its bits and their split
between the players, the layout of its integers and, for a compact controller, its fields
(order, owners, value order, labels and the bits that encode each value).  Generated C
addresses an input by its field's position and a value by its index, so two files with the
same logic but another value order drive a robot differently.  :func:`check_belongs`
therefore demands the spec's own vocabulary, computed from the spec alone, and names the
first difference.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeAlias

from gaitc.compact.controller import CompactController, compact_from_dict, is_compact
from gaitc.compact.fields import Vocabulary, expected_vocabulary, vocabulary_difference
from gaitc.diagnostics import ControllerError, Span
from gaitc.diagnostics.choices import Choice
from gaitc.ir.bddfile import SymbolicController, is_symbolic, symbolic_from_dict
from gaitc.ir.bits import bits_mismatch, spec_bits
from gaitc.ir.controller import (
    Controller,
    IntegerVar,
    controller_from_dict,
    read_controller_json,
    spec_integers,
)
from gaitc.ir.spec import GR1Spec

if TYPE_CHECKING:
    from collections.abc import Mapping

    from ltlcompiler.encoding import EncodingName
    from ltlcompiler.model import Model

#: A controller in any of its forms.
Automaton: TypeAlias = "Controller | SymbolicController | CompactController"

HINT_RESYNTHESIZE = "synthesize it again from this spec with 'gaitc synth'"


class Form(Choice):
    """The form of a controller file."""

    EXPLICIT = "explicit"
    SYMBOLIC = "symbolic"
    COMPACT = "compact"


def form_of(data: Any) -> Form:
    """The form of a parsed controller file (explicit unless it says otherwise)."""
    if is_symbolic(data):
        return Form.SYMBOLIC
    if is_compact(data):
        return Form.COMPACT
    return Form.EXPLICIT


def parse_controller(data: Any, file: str, spec: GR1Spec | None = None) -> Automaton:
    """The controller in a parsed file, its own structure checked (not yet its spec)."""
    form = form_of(data)
    if form == Form.SYMBOLIC:
        return symbolic_from_dict(data, file)
    if form == Form.COMPACT:
        return compact_from_dict(data, file)
    return controller_from_dict(data, file, spec)


def parse_file(path: str | Path, spec: GR1Spec | None = None) -> Automaton:
    """The controller in the file ``path``, its own structure checked (not yet its spec:
    :func:`read_controller` does both)."""
    return parse_controller(read_controller_json(str(path)), str(path), spec)


def read_controller(path: str | Path, spec: GR1Spec, model: Model | None = None,
                    encoding: EncodingName | None = None) -> Automaton:
    """Read the controller file ``path`` and check that it belongs to ``spec`` (compiled
    from ``model`` with ``encoding`` when it is a ``.gait`` spec); raises
    :class:`~gaitc.diagnostics.ControllerError` naming the file and the first difference."""
    file = str(path)
    automaton = parse_file(file, spec)
    vocabulary = (expected_vocabulary(spec, model, encoding)
                  if isinstance(automaton, CompactController) else None)
    check_belongs(automaton, spec, vocabulary, file)
    return automaton


def belongs(automaton: Automaton, spec: GR1Spec, vocabulary: Vocabulary | None = None
            ) -> str | None:
    """Why ``automaton`` does not belong to ``spec`` (its bits in order, their owners, its
    integers, a compact controller's fields against ``vocabulary``, by default the spec's
    own variables); None when it does."""
    ins, outs = spec_bits(spec)
    variables = (automaton.variables if isinstance(automaton, Controller)
                 else (*automaton.inputs, *automaton.outputs))
    mismatch = bits_mismatch(variables, ins + outs)
    if mismatch is not None:
        return mismatch.removeprefix("controller does not belong to this spec: ")
    if tuple(automaton.inputs) != ins:
        return (f"it makes {_first_moved(automaton.inputs, ins, outs)} an input, which the "
                "spec's system sets")
    if tuple(automaton.outputs) != outs:
        return (f"it makes {_first_moved(automaton.outputs, outs, ins)} an output, which "
                "the spec's environment sets")
    integers = _integers_difference(automaton.integers, spec_integers(spec))
    if integers is not None:
        return integers
    if isinstance(automaton, CompactController):
        wanted = vocabulary if vocabulary is not None else expected_vocabulary(spec)
        return vocabulary_difference(automaton.vocabulary, wanted)
    return None


def check_belongs(automaton: Automaton, spec: GR1Spec, vocabulary: Vocabulary | None = None,
                  file: str = "") -> None:
    """Raise :class:`~gaitc.diagnostics.ControllerError` when :func:`belongs` finds a
    difference."""
    why = belongs(automaton, spec, vocabulary)
    if why is not None:
        raise ControllerError(f"controller does not belong to this spec: {why}",
                              Span(file or "<controller>", 1, 1), hint=HINT_RESYNTHESIZE)


def _first_moved(have: tuple[str, ...], want: tuple[str, ...], other: tuple[str, ...]) -> str:
    for bit in have:
        if bit in other:
            return repr(bit)
    return next((repr(b) for b, w in zip(have, want, strict=False) if b != w), "a bit")


def _integers_difference(found: Mapping[str, IntegerVar], wanted: Mapping[str, IntegerVar]
                         ) -> str | None:
    for name in sorted(set(found) | set(wanted)):
        have, want = found.get(name), wanted.get(name)
        if have is None:
            return f"it does not lay out the spec's integer {name!r}"
        if want is None:
            return f"it has an integer {name!r}, which the spec does not have"
        if have != want:
            return (f"it lays out integer {name!r} as {have.low}..{have.high} on "
                    f"{list(have.bits)} ({have.owner}); the spec's is {want.low}..{want.high} "
                    f"on {list(want.bits)} ({want.owner})")
    return None
