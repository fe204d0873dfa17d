"""Reporting: the one JSON form of every command's result and of every error (docs/json.md).

Each ``--json`` command prints a single object (``check``: one per file) made by
:func:`document`: its ``schema`` version, the ``command`` name and the result's own
``to_json()``.  Errors become ``{"error": {...}}`` objects with ``file``, ``line``,
``column``, ``message`` and ``hint`` (null where unknown); the exit code is the same as
without ``--json`` (:func:`exit_code_of`), and stderr keeps the human text.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, Final, TextIO

from gaitc.cli.exitcodes import ExitCode
from gaitc.diagnostics import Diagnostic, GaitcError, SolverError, Span, UsageError

if TYPE_CHECKING:
    from gaitc.api.answers import Explanation
    from gaitc.api.loading import Spec

#: The version of the JSON objects documented in docs/json.md; raised when a key changes
#: meaning or disappears (adding a key does not change it).
SCHEMA: Final = 1


def _where(span: Span | None) -> dict[str, Any]:
    if span is None:
        return {"file": None, "line": None, "column": None}
    return {"file": span.file, "line": span.line, "column": span.column}


def error_json(err: GaitcError) -> dict[str, Any]:
    """``err`` as ``{type, file, line, column, message, hint}``; null where unknown."""
    return err.to_json()


def diagnostic_json(diag: Diagnostic) -> dict[str, Any]:
    """A warning (or primitive error) as ``{severity, file, line, column, message, hint}``."""
    return {"severity": diag.severity, **_where(diag.span), "message": diag.message,
            "hint": diag.hint}


def internal_error_json(err: Exception) -> dict[str, Any]:
    """A bug in gaitc, in the error object's shape (no position: it is not in the input)."""
    return {"type": "InternalError", **_where(None),
            "message": f"internal error: {type(err).__name__}: {err}",
            "hint": "this is a bug in gaitc, not in your input; GAITC_DEBUG=1 prints the "
            "traceback"}


def document(command: str | None, body: Mapping[str, Any]) -> dict[str, Any]:
    """The printed object: ``schema`` and ``command``, then the result's keys."""
    return {"schema": SCHEMA, "command": command, **body}


def error_document(command: str | None, err: GaitcError) -> dict[str, Any]:
    """The object a failed ``--json`` command prints instead of its result."""
    return document(command, {"error": error_json(err)})


def print_json(obj: Mapping[str, Any], stream: TextIO | None = None) -> None:
    """One object on one line, keys sorted (the same result prints the same bytes)."""
    out = sys.stdout if stream is None else stream
    text = json.dumps(obj, sort_keys=True, ensure_ascii=False)
    if any("\ud800" <= c <= "\udfff" for c in text):  # a path of bytes that are no UTF-8
        text = json.dumps(obj, sort_keys=True)  # escaped, so the line stays UTF-8 JSON
    out.write(text + "\n")
    out.flush()


def exit_code_of(err: GaitcError) -> ExitCode:
    """The exit code of an error, with or without ``--json``: 2 usage, 4 solver, else 1."""
    if isinstance(err, UsageError):
        return ExitCode.USAGE
    return ExitCode.SOLVER if isinstance(err, SolverError) else ExitCode.USER


def json_requested(argv: Sequence[str]) -> bool:
    """Whether the command line asks for ``--json`` (before any ``--``), for the errors
    that happen before its arguments are parsed (a usage error, an unknown option)."""
    for token in argv:
        if token == "--":
            return False
        if token == "--json":
            return True
    return False


def command_named(argv: Sequence[str], commands: Iterable[str]) -> str | None:
    """The subcommand of ``argv``: its first word that names one, else None."""
    known = set(commands)
    return next((token for token in argv if token in known), None)


def lint_json(file: str, diagnostics: Sequence[Diagnostic],
              deep: Explanation | None = None) -> dict[str, Any]:
    """The result of ``gaitc lint``: every finding, counted by severity; with ``--deep``
    the verdict and the sanity warnings of :func:`gaitc.explain`."""
    errors = sum(1 for d in diagnostics if d.severity == "error")
    found: dict[str, Any] | None = None
    if deep is not None:
        found = {"verdict": deep.verdict(), "kind": deep.kind if not deep.realizable else None,
                 "warnings": [w.to_json() for w in deep.warnings]}
    return {"file": file, "diagnostics": [diagnostic_json(d) for d in diagnostics],
            "errors": errors, "warnings": len(diagnostics) - errors, "deep": found}


def compilation_json(spec: Spec, fmt: str, text: str, output: str) -> dict[str, Any]:
    """The result of ``gaitc compile``: the spec's sizes (:meth:`Spec.to_json`), the
    format and where the text went; with ``-o -`` the text itself (else null)."""
    return {**spec.to_json(), "format": fmt, "output": output,
            "bytes": len(text.encode("utf-8")), "lines": text.count("\n"),
            "text": text if output == "-" else None,
            "warnings": [diagnostic_json(d) for d in spec.diagnostics]}
