"""Section layout shared by SLUGS's two formats: headers, declarations and who may use what.

Follows ``GR1Context::init`` in SLUGS (src/synthesisContextBasics.cpp): ``#`` comment
lines, eight section headers in any order, and the variable kinds each section admits.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from diagnostics import SlugsFormatError, Span
from gr1.formula import IntVar, Var, walk
from gr1.spec import SECTIONS, Clause, GR1Spec

# Section headers in the order the writers use; values are GR1Spec field names.
HEADERS: dict[str, str] = {
    "[INPUT]": "inputs",
    "[OUTPUT]": "outputs",
    "[ENV_INIT]": "env_init",
    "[SYS_INIT]": "sys_init",
    "[ENV_TRANS]": "env_trans",
    "[SYS_TRANS]": "sys_trans",
    "[ENV_LIVENESS]": "env_liveness",
    "[SYS_LIVENESS]": "sys_liveness",
}
FIELD_HEADERS = {field: header for header, field in HEADERS.items()}
OPERATORS = frozenset({"!", "&", "|", "^", "$", "?", "0", "1"})
TOKEN = re.compile(r"\S+")


@dataclass(frozen=True)
class SourceLine:
    """One meaningful (non-blank, non-comment) line of a SLUGS file, inside a section."""

    field: str  # GR1Spec field name, e.g. "sys_trans"
    header: str  # e.g. "[SYS_TRANS]"
    text: str  # the raw line, untrimmed
    line: int
    span: Span  # covers the trimmed text


def read_sections(text: str, filename: str) -> Iterator[SourceLine]:
    """Yield the content lines of a SLUGS file with their section; shared by both readers.

    Blank lines and lines starting with ``#`` are skipped (as in SLUGS); a line starting
    with ``[`` must be a known section header.  Sections may repeat and come in any order.
    """
    header: str | None = None
    for number, raw in enumerate(text.splitlines(), start=1):
        stripped = raw.strip()
        if not stripped or stripped.startswith("#"):
            continue
        start = len(raw) - len(raw.lstrip()) + 1
        span = Span(filename, number, start, number, start + len(stripped) - 1)
        if stripped.startswith("["):
            if stripped not in HEADERS:
                known = ", ".join(HEADERS)
                raise SlugsFormatError(
                    f"unknown section header '{stripped}'; the known sections are {known}",
                    span,
                )
            header = stripped
            continue
        if header is None:
            raise SlugsFormatError(
                "this line comes before any section header; start the file with a section "
                "such as [INPUT]",
                span,
            )
        yield SourceLine(HEADERS[header], header, raw, number, span)


def check_name(name: str, span: Span) -> None:
    """Reject variable names SLUGS cannot read back (whitespace, primes, operator tokens)."""
    if TOKEN.fullmatch(name) is None:
        raise SlugsFormatError(
            f"variable name '{name}' contains white space; a name must be a single word", span
        )
    if "'" in name:
        raise SlugsFormatError(
            f"variable name '{name}' contains a prime (\"'\"); primes mark next-state copies, "
            "which SLUGS creates automatically",
            span,
        )
    if name in OPERATORS:
        raise SlugsFormatError(
            f"'{name}' cannot be a variable name: it is an operator or constant of the "
            "slugsin format",
            span,
        )


def check_atoms(spec: GR1Spec) -> None:
    """Check every clause uses declared variables the way SLUGS allows in its section.

    As in SLUGS: [ENV_INIT] may mention only unprimed inputs, [SYS_INIT] only unprimed
    variables, [ENV_TRANS] no primed outputs; the other sections anything declared.
    """
    inputs = {v.name for v in spec.inputs}
    outputs = {v.name for v in spec.outputs}
    for field in SECTIONS:
        header = FIELD_HEADERS[field]
        for clause in spec.section(field):
            for node in walk(clause.formula):
                if isinstance(node, (Var, IntVar)):
                    _check_atom(node, field, header, inputs, outputs, clause)


def _check_atom(
    node: Var | IntVar,
    field: str,
    header: str,
    inputs: set[str],
    outputs: set[str],
    clause: Clause,
) -> None:
    span = node.span or (clause.origin.span if clause.origin else None)
    shown = node.name + ("'" if node.primed else "")
    if node.name not in inputs and node.name not in outputs:
        raise SlugsFormatError(
            f"unknown variable '{node.name}'; declare it under [INPUT] or [OUTPUT]", span
        )
    if node.primed and field in ("env_init", "sys_init"):
        raise SlugsFormatError(
            f"next-state variable '{shown}' cannot appear in {header}: initial conditions "
            "constrain the first state only",
            span,
        )
    if field == "env_init" and node.name in outputs:
        raise SlugsFormatError(
            f"output '{node.name}' cannot appear in [ENV_INIT]: SLUGS allows only inputs "
            "there; move the clause to [SYS_INIT]",
            span,
        )
    if field == "env_trans" and node.primed and node.name in outputs:
        raise SlugsFormatError(
            f"next-state output '{shown}' cannot appear in [ENV_TRANS]: the environment "
            "moves before the system and cannot see its next move",
            span,
        )
