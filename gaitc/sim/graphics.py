"""Graphviz output shared by the views: format choice, running ``dot``, notebook display.

Views build a pydot graph; :class:`Picture` keeps its DOT text and renders it with
Graphviz's ``dot`` program (``--format dot`` needs no Graphviz at all).
"""

from __future__ import annotations

import re
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
    said = result.stderr.decode("utf-8", "replace")
    if result.returncode != 0:
        message = said.strip().splitlines()
        raise GaitcError("Graphviz failed: " + (message[0] if message else "no message"))
    shrunk = _SHRUNK.search(said)
    if shrunk is not None:
        # a bitmap has at most 32,767 pixels a side; Graphviz would scale the whole
        # picture down (text and all) and say so only on its standard error
        raise UsageError(
            f"the picture is too large for a {fmt.upper()} image (at most {BITMAP_SIDE:,} "
            f"pixels a side): Graphviz would shrink it to {float(shrunk.group(1)):.0%} and "
            "its text would be unreadable; write it as SVG or PDF (-o FILE.svg), which have "
            "no such limit")
    return result.stdout


#: The longest side of a bitmap Graphviz's cairo renderer writes, in pixels.
BITMAP_SIDE = 32767
_SHRUNK = re.compile(r"too large for cairo-renderer bitmaps\. Scaling by ([0-9.]+)")


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
