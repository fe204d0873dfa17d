"""Writing result files safely: a temporary file in the target folder, then a rename.

Every command that writes a file (specs, controllers, runs, pictures) goes through
:func:`write_atomically`, so an error or an interruption never leaves a half-written
or lost file behind.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import os
import stat
from pathlib import Path

from gaitc.diagnostics import FileAccessError, GaitcError, MissingFileError, Span, source_lines


def decode_text(data: bytes, file: str, error: type[GaitcError]) -> str:
    """``data`` as UTF-8 text; a positioned ``error`` at the first byte that is not."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        before = data[: err.start]
        line = before.count(b"\n") + 1
        # characters, not bytes, as the printer counts columns (the prefix is valid UTF-8);
        # line 1's columns start after a byte order mark, as every reader's do
        head = before[before.rfind(b"\n") + 1:]
        if line == 1:
            head = head.removeprefix("\ufeff".encode())
        column = len(head.decode("utf-8")) + 1
        raise error(f"'{file}' is not UTF-8 text (byte 0x{data[err.start]:02x} at offset "
                    f"{err.start}); save the file as UTF-8", Span(file, line, column)) from None


def _ordinary_mode(target: Path | None) -> int:
    """The mode ``open(target, "w")`` would leave: the old file's, else (or for no old file
    to go by) 0o666 minus umask.

    (``mkstemp`` creates its file with mode 0600, which a plain rename would keep.)
    """
    try:
        if target is not None:
            return stat.S_IMODE(target.stat().st_mode)
    except OSError:
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def _stream_in_place(target: Path) -> bool:
    """Whether ``target`` is a FIFO or a device, which is written to, never replaced."""
    try:
        mode = target.stat().st_mode
    except OSError:
        return False
    return stat.S_ISFIFO(mode) or stat.S_ISCHR(mode) or stat.S_ISBLK(mode)


def read_input(path: str | Path, what: str = "") -> bytes:
    """The bytes of the input file ``path`` (``what`` it is, for the message: "scenario",
    "robot file"); a file that is missing, a folder or unreadable is a usage error (exit 2,
    as for a missing spec), named with the file and the reason in words."""
    name = f"{what} '{path}'" if what else f"'{path}'"
    if "\0" in str(path):
        raise FileAccessError(f"cannot read {name}: the name holds a NUL character")
    try:
        return Path(path).read_bytes()
    except FileNotFoundError:
        raise MissingFileError(f"cannot read {name}: no such file", path) from None
    except IsADirectoryError:
        raise FileAccessError(f"cannot read {name}: it is a directory", path) from None
    except OSError as err:
        raise FileAccessError(f"cannot read {name}: {err.strerror or err}", path) from None


def _output_target(path: str | Path, follow_links: bool = True) -> Path:
    """The file an output ``path`` names (a symbolic link followed, unless not
    ``follow_links``: then the link itself is the file, to be replaced); a folder, socket
    or other kind that is neither a regular file nor a stream is refused, and so is a name
    the system cannot look up (a link that points to itself, a name too long)."""
    target = Path(path)
    try:
        if target.is_symlink():
            if not follow_links:
                return target
            # a loop is ELOOP here on every Python (3.13's resolve() follows it quietly); a
            # link to a file not made yet is written through
            with contextlib.suppress(FileNotFoundError):
                target.stat()
            target = target.resolve(strict=False)
        if target.exists() and not target.is_file() and not _stream_in_place(target):
            raise FileAccessError(f"cannot write '{path}': it is not a regular file")
    except RuntimeError:  # Path.resolve of a link loop (Python 3.11, 3.12)
        raise FileAccessError(f"cannot write '{path}': the symbolic link points to "
                              "itself") from None
    except OSError as err:
        if isinstance(err, FileAccessError):
            raise
        raise FileAccessError(f"cannot write '{path}': {reason(err)}") from None
    return target


def reason(err: OSError) -> str:
    """An operating system error in words, without Python's ``[Errno N]`` prefix."""
    if err.errno == errno.ELOOP:
        return "the symbolic link points to itself"
    if err.errno == errno.ENAMETOOLONG:
        return "the file name is too long for the file system"
    return str(err.strerror or err)


def make_folder(path: str | Path) -> Path:
    """The output folder ``path``, made with its parents if missing; a file in the way, a
    folder that cannot be made, or one that takes no new file (``/proc/self``, a read-only
    mount) is a :class:`FileAccessError` naming the path, before anything is written."""
    folder = Path(path)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise FileAccessError(f"cannot write into '{path}': it is a file, not a folder",
                              path) from None
    except OSError as err:
        raise FileAccessError(f"cannot make the folder '{path}': {reason(err)}",
                              path) from None
    except ValueError:  # a NUL in the name (only a caller in Python can pass one)
        raise FileAccessError(f"cannot make the folder {str(path)!r}: a file name cannot "
                              "hold a NUL byte", path) from None
    _check_new_file(folder, path)
    return folder


def _check_new_file(folder: Path, path: str | Path) -> None:
    """Make and remove a file in ``folder``, as :func:`write_atomically` will: a folder the
    system lets no one add a file to is refused now, not halfway through the outputs."""
    # lazy: tempfile, with random, by the commands that write, not those that read
    import tempfile

    try:
        fd, probe = tempfile.mkstemp(prefix=".gaitc-probe.", suffix=".tmp", dir=folder)
    except OSError as err:
        why = ("no file can be made in it" if err.errno in (errno.ENOENT, errno.ENOTDIR)
               else reason(err))
        raise FileAccessError(f"cannot write into '{path}': {why}", path) from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)


def check_writable(path: str | Path, follow_links: bool = True) -> None:
    """Refuse, before any work, an output ``path`` that :func:`write_atomically` could not
    write: its folder is missing or not writable, or it is a folder or other non-file."""
    try:
        _check_writable(path, follow_links)
    except FileAccessError:
        raise
    except OSError as err:
        raise FileAccessError(f"cannot write '{path}': {reason(err)}") from None


def _check_writable(path: str | Path, follow_links: bool) -> None:
    target = _output_target(path, follow_links)
    link = target.is_symlink()  # only when not following links: replaced, never written
    if not link and _stream_in_place(target):
        return
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise FileAccessError(f"cannot write '{path}': there is no folder '{folder}'")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise FileAccessError(f"cannot write '{path}': the folder '{folder}' is not writable")
    if not link and target.exists() and not os.access(target, os.W_OK):
        raise FileAccessError(f"cannot write '{path}': the file is read-only")


def write_atomically(path: str | Path, data: str | bytes, follow_links: bool = True) -> None:
    """Replace ``path`` by ``data`` (text is written as UTF-8 with ``\\n`` line ends).

    A symbolic link is followed (its target is replaced, the link stays), or, when not
    ``follow_links``, replaced itself by the new file (its target never opened); a FIFO or
    a device is written to in place, as a user who names ``/dev/stdout`` expects; any other
    kind of file that is not a regular one (a directory, a socket) is refused.
    """
    target = _output_target(path, follow_links)
    link = target.is_symlink()  # only when not following links
    payload = data.encode("utf-8") if isinstance(data, str) else data
    if not link and _stream_in_place(target):
        try:
            with open(target, "wb") as out:
                out.write(payload)
        except OSError as err:
            raise FileAccessError(f"cannot write '{path}': {reason(err)}") from None
        return
    import tempfile  # lazy: only commands that write load tempfile (start-up of check)

    tmp: str | None = None
    try:
        folder = target.parent if str(target.parent) else Path(".")
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=folder)
        os.fchmod(fd, _ordinary_mode(None if link else target))
        with os.fdopen(fd, "wb") as out:
            out.write(payload)
            out.flush()
            os.fsync(out.fileno())
        os.replace(tmp, target)
        tmp = None
    except OSError as err:
        raise FileAccessError(f"cannot write '{path}': {reason(err)}") from None
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)


def csv_rows(text: str, name: str, error: type[GaitcError]) -> list[list[str]]:
    """The rows of a CSV ``text`` split at the project's line ends (``\\n``, a ``\\r`` before it
    dropped: :func:`gaitc.diagnostics.source_lines`, as everywhere else); a row the csv
    module cannot read (a field over its size limit, a quote left open, a lone ``\\r``) is
    ``error`` at that line."""
    rows: list[list[str]] = []
    for number, line in enumerate(source_lines(text), 1):
        try:
            rows.extend(csv.reader([line]))
        except csv.Error as err:
            reason = ("a carriage return (\\r) inside the line" if "new-line" in str(err)
                      else str(err))
            raise error(f"line {number} is not a CSV row: {reason}", Span(name, number, 1)
                        ) from None
    return rows
