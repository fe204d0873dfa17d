"""Graphviz output shared by the views: format choice, running ``dot``, notebook display.

Views build a pydot graph; :class:`Picture` keeps its DOT text and renders it with
Graphviz's ``dot`` program (``--format dot`` needs no Graphviz at all).
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pydot

from gaitc.diagnostics import GaitcError, UsageError
from gaitc.diagnostics.files import write_atomically

FORMATS = ("dot", "svg", "png", "pdf")
_ALIASES = {"gv": "dot"}
INSTALL_HINT = ("install Graphviz (Debian/Ubuntu: apt-get install graphviz, macOS: brew install "
                "graphviz) or write DOT with --format dot")


def output_format(path: str | Path | None, fmt: str | None = None) -> str:
    """The output format: ``fmt`` if given, else the extension of ``path`` (default svg)."""
    if fmt is not None:
        name = fmt.lower().lstrip(".")
    elif path is not None and Path(path).suffix:
        name = Path(path).suffix.lower().lstrip(".")
    else:
        name = "svg"
    name = _ALIASES.get(name, name)
    if name not in FORMATS:
        raise UsageError(f"cannot write format '{name}'; choose one of {', '.join(FORMATS)} "
                         "(from the -o extension or --format)")
    return name


def have_dot() -> bool:
    """Whether Graphviz's ``dot`` is on PATH."""
    return shutil.which("dot") is not None


def run_dot(source: str, fmt: str) -> bytes:
    """Render DOT ``source`` to ``fmt`` bytes with Graphviz (``dot`` returns the source)."""
    if fmt == "dot":
        return source.encode("utf-8")
    exe = shutil.which("dot")
    if exe is None:
        raise UsageError(f"rendering to {fmt} needs Graphviz's 'dot', which is not on PATH: "
                         + INSTALL_HINT)
    result = subprocess.run([exe, f"-T{fmt}"], input=source.encode("utf-8"),
                            capture_output=True, check=False, timeout=300)
    if result.returncode != 0:
        message = result.stderr.decode("utf-8", "replace").strip().splitlines()
        raise GaitcError("Graphviz failed: " + (message[0] if message else "no message"))
    return result.stdout


class Picture:
    """A rendered view: DOT text that can be saved in any format or shown in a notebook."""

    def __init__(self, graph: pydot.Dot, notes: tuple[str, ...] = ()) -> None:
        self.graph = graph
        self.notes = notes  # what the view did, for the user (e.g. which nodes were merged)

    def dot(self) -> str:
        text: str = self.graph.to_string()
        return text

    def svg(self) -> str:
        return run_dot(self.dot(), "svg").decode("utf-8")

    def render(self, fmt: str) -> bytes:
        return run_dot(self.dot(), fmt)

    def save(self, path: str | Path, fmt: str | None = None) -> str:
        """Write the picture; returns the format used."""
        chosen = output_format(path, fmt)
        write_atomically(path, self.render(chosen))
        return chosen

    def _repr_svg_(self) -> str:
        return self.svg()


def quote(text: str) -> str:
    """A DOT string literal (pydot leaves attribute values as given)."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def html(text: str) -> str:
    """Escape text for a Graphviz HTML-like label."""
    return (text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;"))
