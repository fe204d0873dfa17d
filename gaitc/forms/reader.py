"""Reading a controller file of any form and checking that it belongs to a spec.

The proof (:mod:`gaitc.verifier`) covers the logic of a controller; what the runtimes and
generated code use besides the logic is the file's vocabulary: its bits and their split
between the players, the layout of its integers and, for a compact controller, its fields
(order, owners, value order, labels and the bits that encode each value).  Generated C
addresses an input by its field's position and a value by its index, so two files with the
same logic but another value order drive a robot differently.  :func:`check_belongs`
therefore demands the spec's own vocabulary, computed from the spec alone, and names the
first difference.  Every function takes the loaded :class:`~gaitc.core.spec.Spec`: the
facade loads a spec once per command and hands the same object to each.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.core.spec import Spec
from gaitc.core.vocabulary import vocabulary_difference
from gaitc.diagnostics import ControllerError, Span
from gaitc.diagnostics.files import read_input
from gaitc.forms.base import Automaton
from gaitc.forms.explicit import GZIP_MAGIC, read_tables
from gaitc.forms.registry import detect, entry
from gaitc.ir.bits import bits_mismatch, spec_bits
from gaitc.ir.controller import IntegerVar, parse_controller_json, spec_integers
from ltlcompiler.encoding import ENCODINGS, EncodingName

if TYPE_CHECKING:
    from collections.abc import Mapping

    from gaitc.sim.view import StrategyView

__all__ = ["HINT_RESYNTHESIZE", "Automaton", "ControllerFile", "ControllerSource", "belongs",
           "check_belongs", "load_runtime", "opened", "parse_controller", "parse_file",
           "read_controller", "read_document", "runtime"]

HINT_RESYNTHESIZE = "synthesize it again from this spec with 'gaitc synth'"


def parse_controller(data: Any, file: str, spec: Spec) -> Automaton:
    """The controller in a parsed file, its own structure checked (not yet its spec)."""
    return detect(data).parse(data, file, spec)


def read_document(path: str | Path) -> Any:
    """The parsed contents of the controller file ``path``, in any form and layout: JSON
    text, or an explicit controller's tables layout (gzip, :func:`gaitc.forms.explicit.
    read_tables`); a file that is neither is a :class:`~gaitc.diagnostics.ControllerError`
    saying where it goes wrong."""
    file = str(path)
    raw = read_input(file, "controller file")
    if raw.startswith(GZIP_MAGIC):
        return read_tables(raw, file)
    return parse_controller_json(raw, file)


@dataclass(frozen=True, eq=False)
class ControllerFile:
    """A controller file read once: its path and its parsed document (any form, any
    layout).  A command reads the file once, asks it the encoding its spec was compiled
    with, and parses the controller from the same document."""

    path: str
    document: Any

    @classmethod
    def read(cls, path: str | Path) -> ControllerFile:
        """Read ``path`` (a :class:`~gaitc.diagnostics.ControllerError` when it is neither
        JSON nor the tables layout)."""
        return cls(str(path), read_document(path))

    @property
    def encoding(self) -> EncodingName | None:
        """The encoding the file says its spec was compiled with, if it says one."""
        try:
            encoding = self.document["gaitc"]["source"]["encoding"]
        except (KeyError, TypeError):
            return None
        return EncodingName(encoding) if encoding in ENCODINGS else None


#: A controller file as the readers take it: a path, or the file read already.
ControllerSource = str | Path | ControllerFile


def opened(source: ControllerSource) -> ControllerFile:
    """``source`` read (a path) or as it is (a file read already)."""
    return source if isinstance(source, ControllerFile) else ControllerFile.read(source)


def parse_file(path: ControllerSource, spec: Spec) -> Automaton:
    """The controller in the file ``path``, its own structure checked (not yet its spec:
    :func:`read_controller` does both)."""
    file = opened(path)
    return parse_controller(file.document, file.path, spec)


def read_controller(path: ControllerSource, spec: Spec) -> Automaton:
    """Read the controller file ``path`` and check that it belongs to ``spec``; raises
    :class:`~gaitc.diagnostics.ControllerError` naming the file and the first difference."""
    file = opened(path)
    automaton = parse_controller(file.document, file.path, spec)
    check_belongs(automaton, spec, file.path)
    return automaton


def belongs(automaton: Automaton, spec: Spec) -> str | None:
    """Why ``automaton`` does not belong to ``spec`` (its bits in order, their owners, its
    integers, a compact controller's fields against the spec's vocabulary); None when it
    does."""
    ins, outs = spec_bits(spec.gr1)
    mismatch = bits_mismatch(automaton.variables, ins + outs)
    if mismatch is not None:
        return mismatch.removeprefix("controller does not belong to this spec: ")
    if tuple(automaton.inputs) != ins:
        return (f"it makes {_first_moved(automaton.inputs, ins, outs)} an input, which the "
                "spec's system sets")
    if tuple(automaton.outputs) != outs:
        return (f"it makes {_first_moved(automaton.outputs, outs, ins)} an output, which "
                "the spec's environment sets")
    integers = _integers_difference(automaton.integers, spec_integers(spec.gr1))
    if integers is not None:
        return integers
    fields = entry(automaton).vocabulary(automaton)
    return None if fields is None else vocabulary_difference(fields, spec.vocabulary)


def check_belongs(automaton: Automaton, spec: Spec, file: str = "") -> None:
    """Raise :class:`~gaitc.diagnostics.ControllerError` when :func:`belongs` finds a
    difference."""
    why = belongs(automaton, spec)
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


def runtime(automaton: Automaton, spec: Spec, file: str = "") -> StrategyView:
    """The run view of a controller of any form (:meth:`ControllerForm.runtime`)."""
    return entry(automaton).runtime(spec, automaton, file)


def load_runtime(path: ControllerSource, spec: Spec) -> StrategyView:
    """Read a controller file through :func:`read_controller` and give its run view."""
    file = opened(path)
    return runtime(read_controller(file, spec), spec, file.path)
