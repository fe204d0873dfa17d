"""The example robots and specs that ship inside the package, copied out for a new user.

The examples are package data (``gaitc/examples``: the thesis robots A and B, the patrols,
the hazard corridor and the robot files of ``gaitc gaits``), so a user who installed the
wheel, with no checkout, can start from ``gaitc examples my-robots``.
"""

from __future__ import annotations

import stat
from dataclasses import dataclass
from importlib import resources
from importlib.abc import Traversable
from pathlib import Path

from gaitc.diagnostics import FileAccessError
from gaitc.diagnostics.files import check_writable, make_folder, reason, write_atomically

#: Where the examples live inside the package.
PACKAGE, FOLDER = "gaitc", "examples"
#: The kinds of file an example is.
SUFFIXES = (".gait", ".yaml")


@dataclass(frozen=True)
class Examples:
    """The files :func:`copy_examples` wrote, relative to ``folder``."""

    folder: Path
    files: tuple[str, ...]

    def __str__(self) -> str:
        lines = [f"{len(self.files)} example files in {self.folder}:"]
        lines += [f"  {name}" for name in self.files]
        first = next((n for n in self.files if n.endswith("thesis_robot_a.gait")), None)
        if first is not None:
            lines.append(f"try: gaitc synth {self.folder / first} -o robot_a.controller.json")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        items = "".join(f"<li><code>{name}</code></li>" for name in self.files)
        head = f"<p>{len(self.files)} example files in <code>{self.folder}</code></p>"
        return f"{head}<ul>{items}</ul>"

    def to_json(self) -> dict[str, object]:
        return {"folder": str(self.folder), "files": list(self.files)}


def _walk(node: Traversable, prefix: str) -> list[tuple[str, Traversable]]:
    found: list[tuple[str, Traversable]] = []
    for child in sorted(node.iterdir(), key=lambda c: c.name):
        name = f"{prefix}{child.name}"
        if child.is_dir():
            found += _walk(child, name + "/")
        elif child.name.endswith(SUFFIXES):
            found.append((name, child))
    return found


def example_files() -> list[tuple[str, Traversable]]:
    """Every example shipped with this gaitc, by its path inside the examples folder."""
    return _walk(resources.files(PACKAGE).joinpath(FOLDER), "")


def copy_examples(folder: str | Path, overwrite: bool = False) -> Examples:
    """Copy the shipped examples into ``folder`` (made if missing). An existing file is
    never replaced unless ``overwrite``: the copy stops before writing anything and names it.

    Nothing is written through a symbolic link found inside ``folder``: a link where an
    example goes counts as an existing file, and ``overwrite`` replaces the link itself; a
    link where a subfolder of examples goes is refused.
    """
    target = Path(folder)
    files = example_files()
    if _kind(target, target) not in (None, "folder"):
        raise FileAccessError(f"cannot copy the examples into '{target}': it is not a folder",
                              target)
    for sub in sorted({Path(name).parent for name, _ in files} - {Path(".")}):
        if _kind(target / sub, target) not in (None, "folder"):
            raise FileAccessError(
                f"cannot copy the examples into '{target / sub}': it is a symbolic link or "
                "a file, not a folder; remove it or choose another folder", target / sub)
    if not overwrite:
        clashes = [name for name, _ in files if _kind(target / name, target) is not None]
        if clashes:
            raise FileAccessError(
                f"'{target / clashes[0]}' exists; copy the examples into a new folder, or "
                f"replace {len(clashes)} existing file(s) with --force", target / clashes[0])
    for sub in sorted({(target / name).parent for name, _ in files}):
        make_folder(sub)
    for name, _ in files:
        check_writable(target / name, follow_links=False)
    for name, source in files:
        write_atomically(target / name, source.read_bytes(), follow_links=False)
    return Examples(target, tuple(name for name, _ in files))


def _kind(path: Path, folder: Path) -> str | None:
    """``"folder"``, ``"link"`` or ``"other"`` for what ``path`` is (a link not followed),
    None when there is nothing there; a name the system cannot look up (too long, a loop)
    is a :class:`FileAccessError` naming the examples' ``folder``."""
    try:
        mode = path.lstat().st_mode
    except (FileNotFoundError, NotADirectoryError):
        return None
    except OSError as err:
        raise FileAccessError(f"cannot copy the examples into '{folder}': {reason(err)}",
                              folder) from None
    except ValueError:  # a NUL in the name (only a caller in Python can pass one)
        raise FileAccessError(f"cannot copy the examples into {str(folder)!r}: a file name "
                              "cannot hold a NUL byte", folder) from None
    if stat.S_ISLNK(mode):
        return "folder" if path == folder and path.is_dir() else "link"
    return "folder" if stat.S_ISDIR(mode) else "other"
