"""The user's cache (``$XDG_CACHE_HOME/gaitc``): plain data that cannot run code when loaded,
kept only in a folder the user alone owns and may enter, never written through a link.

A cache file is one header line (the format, a key naming what the data was made from and
a seal of the key and the data) followed by the data as JSON, in which tuples and dictionaries with
keys other than strings are tagged so that they come back as they were.  Reading refuses a
folder that is not the user's own with mode ``0700``, a file that is a symbolic link, is not
a regular file, is another user's or may be written by others; anything refused, corrupt or
made from something else reads as missing, and the caller builds the data again.  The seal
is an HMAC-SHA-256 of the key and the data under a random secret kept in the same folder
(file ``secret``, made on the first store): a plain digest of the data could be computed
again by whoever edited it, so an edited file (the grammar's ``assume`` and ``guarantee``
swapped, issue 60), or one copied from another machine or key, would be read as genuine.
Now it reads as missing, unless whoever edits it reads the secret too (someone who can
write the user's files can change gaitc's own code as well).  Writing
goes to a new file in the same folder, renamed over the old name (a link there is replaced,
its target never touched).  No failure of the cache is ever an error.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import hmac
import json
import os
import secrets
import stat
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Final

#: The first word of every cache file, with the version of this format.
FORMAT: Final = "gaitc-cache 2"
#: The file of the folder's secret (the HMAC key of every seal) and its length in bytes.
SECRET: Final = "secret"
_SECRET_BYTES: Final = 32
#: A cache file larger than this is not read (a stray file, not one of ours).
MAX_BYTES: Final = 16 * 1024 * 1024
_TUPLE: Final = "\0tuple"
_DICT: Final = "\0dict"
# a file another user may write (or that is not a regular file) is not ours to read
_FOREIGN_FILE_BITS: Final = stat.S_IWGRP | stat.S_IWOTH


def cache_folder() -> Path:
    """``$XDG_CACHE_HOME/gaitc``, else ``~/.cache/gaitc`` (neither made nor checked here)."""
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "gaitc"


def load(name: str, key: str) -> Any | None:
    """The data stored as ``name`` in the cache folder if it was stored under ``key`` (one
    word, such as a digest of what the data is made from); None when there is none, or it
    cannot be trusted, read or decoded."""
    try:
        with _private_folder(create=False) as folder:
            raw = _read_own_file(folder, name)
            secret = _read_own_file(folder, SECRET)
    except (OSError, RuntimeError, ValueError):  # no home, a folder not ours, ...
        return None
    if raw is None or secret is None or len(secret) != _SECRET_BYTES:
        return None
    header, newline, payload = raw.partition(b"\n")
    if not newline or not hmac.compare_digest(header, _header(key, payload, secret)):
        return None
    try:
        return json.loads(payload, object_hook=_untag)
    except (ValueError, TypeError, RecursionError):
        return None


def store(name: str, key: str, data: Any) -> None:
    """Keep ``data`` (None, booleans, numbers, strings, lists, tuples and dictionaries of
    them) as ``name`` under ``key``; data JSON cannot give back exactly, or a folder that
    cannot be made or is not the user's alone, is quietly not stored."""
    try:
        payload = json.dumps(_tag(data), separators=(",", ":"), ensure_ascii=True,
                             allow_nan=False).encode("ascii")
        if json.loads(payload, object_hook=_untag) != data:
            return
    except (TypeError, ValueError, RecursionError):  # not plain data
        return
    with contextlib.suppress(OSError, RuntimeError, ValueError), \
            _private_folder(create=True) as folder:
        secret = _read_own_file(folder, SECRET)
        if secret is None or len(secret) != _SECRET_BYTES:
            secret = secrets.token_bytes(_SECRET_BYTES)
            _replace_file(folder, SECRET, secret)
        _replace_file(folder, name, _header(key, payload, secret) + b"\n" + payload)


def _header(key: str, payload: bytes, secret: bytes) -> bytes:
    """The header line: the format, the key and the seal of both and the data."""
    seal = hmac.new(secret, key.encode("utf-8", "replace") + b"\0" + payload,
                    hashlib.sha256).hexdigest()
    return f"{FORMAT} {key} {seal}".encode("ascii", "replace")


# ---------------------------------------------------------------- the folder and its files
@contextlib.contextmanager
def _private_folder(*, create: bool) -> Iterator[int]:
    """A descriptor of the cache folder, open without following a link, once it is known
    to be a folder owned by the user with no permission for anyone else (``OSError``
    otherwise); ``create`` makes it (mode ``0700``) when it is missing."""
    if not hasattr(os, "getuid") or not hasattr(os, "O_NOFOLLOW"):
        raise OSError(errno.ENOTSUP, "no private cache on this system")
    path = cache_folder()
    if create:
        path.mkdir(mode=0o700, parents=True, exist_ok=True)
    fd = os.open(path, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC)
    try:
        info = os.fstat(fd)
        if (not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid()
                or stat.S_IMODE(info.st_mode) != 0o700):
            raise OSError(errno.EPERM, "the cache folder is not the user's alone", str(path))
        yield fd
    finally:
        os.close(fd)


def _read_own_file(folder: int, name: str) -> bytes | None:
    """The bytes of the regular file ``name`` in ``folder`` if the user owns it and no one
    else may write it; None if it is missing, a link, or anything else."""
    try:
        fd = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC,
                     dir_fd=folder)
    except OSError:  # missing, a symbolic link (ELOOP), ...
        return None
    with os.fdopen(fd, "rb") as file:
        info = os.fstat(fd)
        if (not stat.S_ISREG(info.st_mode) or info.st_uid != os.getuid()
                or info.st_mode & _FOREIGN_FILE_BITS or info.st_size > MAX_BYTES):
            return None
        data = file.read(MAX_BYTES + 1)
    return data if len(data) <= MAX_BYTES else None


def _replace_file(folder: int, name: str, data: bytes) -> None:
    """Write ``data`` to a new file (mode ``0600``) in ``folder``, then rename it to
    ``name``: whatever ``name`` was (a link included) is replaced, never written through."""
    temporary = f".{name}.{secrets.token_hex(8)}.tmp"
    fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW
                 | os.O_CLOEXEC, 0o600, dir_fd=folder)
    try:
        with os.fdopen(fd, "wb") as file:
            file.write(data)
        os.replace(temporary, name, src_dir_fd=folder, dst_dir_fd=folder)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary, dir_fd=folder)
        raise


# ---------------------------------------------------------------- tuples and keys in JSON
def _tag(value: Any) -> Any:
    """``value`` with tuples and dictionaries whose keys are not all strings tagged, as JSON
    has neither; anything but plain data is a ``TypeError``."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, list):
        return [_tag(item) for item in value]
    if isinstance(value, tuple):
        return {_TUPLE: [_tag(item) for item in value]}
    if isinstance(value, dict):
        if all(isinstance(k, str) and not k.startswith("\0") for k in value):
            return {k: _tag(v) for k, v in value.items()}
        return {_DICT: [[_tag(k), _tag(v)] for k, v in value.items()]}
    raise TypeError(f"{type(value).__name__} is not plain data")


def _untag(obj: dict[str, Any]) -> Any:
    if len(obj) == 1:
        if _TUPLE in obj:
            return tuple(obj[_TUPLE])
        if _DICT in obj:
            return {k: v for k, v in obj[_DICT]}  # a list as a key: TypeError
    return obj
