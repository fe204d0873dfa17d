"""The front-end facade: .gait text or file -> checked :class:`~ltlcompiler.model.Model`.

Stops after any stage: :func:`parse_text` gives the syntax tree, :func:`model_from_text`
and :func:`load_model` the checked model plus its warnings.
"""

from __future__ import annotations

from pathlib import Path

from gaitc.diagnostics import Diagnostic, SpecSyntaxError
from ltlcompiler.checker import check
from ltlcompiler.model import Model
from ltlcompiler.parser import parse
from ltlcompiler.syntax import SpecFile


def parse_text(text: str, filename: str = "<string>") -> SpecFile:
    """The syntax tree of ``text``; raises :class:`SpecSyntaxError` or ``FormulaError``."""
    return parse(text, filename)


def model_from_text(text: str, filename: str = "<string>") -> tuple[Model, list[Diagnostic]]:
    """Parse and check ``text``; errors raise a GaitcError, warnings are returned."""
    return check(parse(text, filename))


def load_model(path: str) -> tuple[Model, list[Diagnostic]]:
    """Read the .gait file at ``path`` and check it (spans name ``path`` as given)."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SpecSyntaxError(f"cannot read '{path}': no such file") from None
    except UnicodeDecodeError as err:
        raise SpecSyntaxError(f"cannot read '{path}': not UTF-8 text ({err.reason})") from None
    except OSError as err:
        raise SpecSyntaxError(f"cannot read '{path}': {err.strerror}") from None
    return model_from_text(text, path)
