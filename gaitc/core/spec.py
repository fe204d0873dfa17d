"""The spec: a specification file or text of any supported kind becomes a :class:`Spec`.

A :class:`Spec` is the one object every later stage takes: the GR(1) IR, and for a
``.gait`` source the domain model, the encoding it was compiled with, the source text and
the vocabulary a compact controller decides in.

``.gait`` goes through the :mod:`ltlcompiler` front end and lowering (thesis eqs. 3.3-3.9);
``.slugsin``/``.txt``, ``.structuredslugs`` and ``.ltl`` (the LTL text ``gaitc compile``
writes) through the readers of :mod:`slugs_bridge`.
Each file is read once; its hash is taken from the same bytes the readers see.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

from gaitc.core.presentation import table
from gaitc.diagnostics import Diagnostic, SlugsFormatError, SpecSyntaxError, UsageError
from gaitc.diagnostics.files import decode_text, read_input
from gaitc.ir.spec import SECTIONS, GR1Spec
from ltlcompiler.encoding import EncodingName

if TYPE_CHECKING:
    from gaitc.core.vocabulary import Vocabulary
    from ltlcompiler.model import Model

GAIT_SUFFIXES = (".gait",)
PREFIX_SUFFIXES = (".slugsin", ".txt")
INFIX_SUFFIXES = (".structuredslugs", ".structureslugs")
LTL_SUFFIXES = (".ltl",)  # the readable LTL text gaitc compile writes
SUFFIXES = GAIT_SUFFIXES + PREFIX_SUFFIXES + INFIX_SUFFIXES + LTL_SUFFIXES


@dataclass(frozen=True)
class Spec:
    """A GR(1) spec ready for a solver, with the domain model when it came from ``.gait``.

    ``gr1`` is the specification IR; ``model`` (robot, map, task) and ``encoding`` are set
    for ``.gait`` sources, and every clause of ``gr1`` then carries its ``.gait`` origin.
    """

    path: str
    gr1: GR1Spec
    model: Model | None = field(default=None, repr=False)
    encoding: EncodingName | None = None
    diagnostics: tuple[Diagnostic, ...] = field(default=(), repr=False)
    sha256: str = field(default="", repr=False)
    text: str = field(default="", repr=False, compare=False)  # the source, for messages

    @property
    def is_gait(self) -> bool:
        """Whether the spec came from ``.gait`` (it then has a model and an encoding)."""
        return self.model is not None

    @property
    def robot(self) -> Model:
        """The domain model; a spec in a SLUGS format has none, which is a
        :class:`UsageError` naming ``self.path`` (commands that need what the variables
        mean ask for it here)."""
        if self.model is None:
            raise UsageError(f"'{self.path}': this needs a .gait spec, which says what the "
                             "variables mean (regions, gaits, legs); a spec in a SLUGS "
                             "format has only bits and integers")
        return self.model

    @property
    def robot_encoding(self) -> EncodingName:
        """The encoding the spec was compiled with (onehot for a SLUGS format, where no
        robot words are encoded)."""
        return self.encoding if self.encoding is not None else EncodingName.ONEHOT

    @cached_property
    def vocabulary(self) -> Vocabulary:
        """The fields a compact controller of this spec decides in
        (:func:`gaitc.core.vocabulary.expected_vocabulary`): the robot's words for a
        ``.gait`` spec, one field per declared variable otherwise."""
        # lazy: not on the lint and check paths (start-up)
        from gaitc.core.vocabulary import expected_vocabulary

        return expected_vocabulary(self.gr1, self.model, self.encoding)

    def source(self) -> dict[str, str]:
        """The ``source`` record written into controller files."""
        out = {"file": self.path, "sha256": self.sha256}
        if self.encoding is not None:
            out["encoding"] = self.encoding
        return out

    def clause_count(self) -> int:
        spec = self.gr1
        return sum(len(spec.section(name)) for name in SECTIONS)

    def source_map_size(self) -> int:
        """How many clauses the source map ties to a line of the source file."""
        spec = self.gr1
        return sum(1 for name in SECTIONS for clause in spec.section(name)
                   if clause.origin is not None and clause.origin.span is not None)

    def to_json(self) -> dict[str, Any]:
        """The spec's size for ``--json`` (docs/json.md): variables, clauses per section."""
        spec = self.gr1
        return {"file": self.path, "sha256": self.sha256, "encoding": self.encoding,
                "inputs": len(spec.inputs), "outputs": len(spec.outputs),
                "clauses": {name: len(spec.section(name)) for name in SECTIONS},
                "source_map": self.source_map_size()}

    def __repr__(self) -> str:
        kind = f".gait, {self.encoding} encoding" if self.model is not None else "SLUGS format"
        return (f"<gaitc.Spec {self.path!r} ({kind}): {len(self.gr1.inputs)} inputs, "
                f"{len(self.gr1.outputs)} outputs, {self.clause_count()} clauses>")

    def _repr_html_(self) -> str:
        rows = [("file", self.path), ("inputs", str(len(self.gr1.inputs))),
                ("outputs", str(len(self.gr1.outputs))), ("clauses", str(self.clause_count()))]
        if self.model is not None:
            rows[1:1] = [
                ("robot", self.model.name or "(unnamed)"), ("encoding", str(self.encoding)),
                ("legs", ", ".join(f"{leg.name}:{leg.health}" for leg in self.model.legs)),
                ("regions", str(len(self.model.regions))),
                ("gaits", ", ".join(g.name for g in self.model.gaits)),
            ]
        if self.diagnostics:
            rows.append(("warnings", str(len(self.diagnostics))))
        return table("GR(1) specification", rows)


def encoding_named(encoding: EncodingName | str) -> EncodingName:
    """``encoding`` as an :class:`EncodingName`; an unknown one is a :class:`UsageError`."""
    return EncodingName.parse(encoding, "encoding")


def _kind(name: str) -> str:
    suffix = Path(name).suffix.lower()
    if suffix in SUFFIXES:
        return suffix
    raise UsageError(
        f"'{name}': unknown specification kind '{suffix or '(none)'}'; "
        "give a .gait, .slugsin, .structuredslugs or .ltl file"
    )


def reader_of(name: str) -> str | None:
    """The ``kind`` for :func:`load` in a command whose input is a ``.gait`` file unless its
    name says it is another spec format (``.slugsin`` or ``.txt``, ``.structuredslugs``,
    ``.ltl``, as every command reads them): None there (the suffix decides), ``".gait"``
    for every other name and standard input."""
    suffix = Path(name).suffix.lower()
    return None if suffix in SUFFIXES and suffix not in GAIT_SUFFIXES else ".gait"


def _decode(data: bytes, path: str, suffix: str) -> str:
    return decode_text(data, path, SpecSyntaxError if suffix in GAIT_SUFFIXES
                       else SlugsFormatError)


def load(path: str | Path, encoding: EncodingName | str = EncodingName.ONEHOT,
         kind: str | None = None) -> Spec:
    """Read ``path`` (.gait, .slugsin, .structuredslugs) into a :class:`Spec`.

    The suffix picks the reader unless ``kind`` (one of the suffixes, say ``".gait"``) does.

    Raises the project's :class:`~gaitc.diagnostics.GaitcError` subclasses with a span for every
    problem in the file, and :class:`~gaitc.diagnostics.UsageError` for an unknown file kind,
    encoding or an unreadable file.
    """
    name = str(path)
    chosen = encoding_named(encoding)
    suffix = _kind(name) if kind is None else _kind(f"spec{kind}")
    raw = read_input(name)
    return _build(_decode(raw, name, suffix), name, suffix, chosen,
                  hashlib.sha256(raw).hexdigest())


def parse(text: str, name: str = "<string>.gait",
          encoding: EncodingName | str = EncodingName.ONEHOT) -> Spec:
    """A :class:`Spec` from ``text``; the suffix of ``name`` picks the reader (``.gait``
    when ``name`` has none of the known suffixes), and spans name ``name``."""
    chosen = encoding_named(encoding)
    suffix = Path(name).suffix.lower()
    if suffix not in SUFFIXES:
        suffix = ".gait"
    digest = hashlib.sha256(text.encode("utf-8")).hexdigest()
    return _build(text, name, suffix, chosen, digest)


def _build(text: str, name: str, suffix: str, encoding: EncodingName, digest: str) -> Spec:
    if suffix in GAIT_SUFFIXES:
        # lazy: one input format's reader, loaded for its files only (start-up)
        from ltlcompiler.frontend import model_from_text
        from ltlcompiler.lowering import lower

        model, diagnostics = model_from_text(text, name)
        spec = lower(model, encoding)
        return Spec(name, spec, model, encoding, tuple(diagnostics), digest, text)
    if suffix in PREFIX_SUFFIXES:
        # lazy: one input format's reader, loaded for its files only (start-up)
        from slugs_bridge.slugsin import parse_slugsin

        return Spec(name, parse_slugsin(text, name), sha256=digest, text=text)
    if suffix in LTL_SUFFIXES:
        # lazy: one input format's reader, loaded for its files only (start-up)
        from slugs_bridge.ltltext import parse_ltl

        return Spec(name, parse_ltl(text, name), sha256=digest, text=text)
    # lazy: one input format's reader, loaded for its files only (start-up)
    from slugs_bridge.structured import parse_structuredslugs

    return Spec(name, parse_structuredslugs(text, name), sha256=digest, text=text)


#: What the facade's functions take as a spec: a loaded one, the GR(1) IR, or a file's path.
SpecLike = Spec | GR1Spec | str | Path


def resolve(spec: SpecLike) -> Spec | GR1Spec:
    """``spec`` itself, or the spec its path names, loaded with :func:`load`."""
    return load(spec) if isinstance(spec, (str, Path)) else spec


def as_spec(spec: SpecLike) -> Spec:
    """``spec`` as a :class:`Spec`: loaded when it is a path, wrapped when it is bare IR."""
    loaded = resolve(spec)
    return loaded if isinstance(loaded, Spec) else Spec(loaded.name or "<spec>", loaded)


def as_gr1(spec: SpecLike) -> GR1Spec:
    """The IR of a spec, loaded first when ``spec`` is a path."""
    loaded = resolve(spec)
    return loaded.gr1 if isinstance(loaded, Spec) else loaded
