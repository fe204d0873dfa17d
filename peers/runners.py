"""Running the peers on a spec: gr1c on the ``.spc`` text, omega in a process of its own.

Facts from gr1c's ``src/main.c``: ``gr1c -r`` only decides realizability and exits 0 when
the spec is realizable, 3 when it is not (printing ``Realizable.`` or ``Not realizable.``),
2 for a syntax error; ``-n`` names the interpretation of the initial conditions, which
:func:`peers.spc.emit_spc` chooses.  omega runs as ``python -m peers.omega_game`` on the
spec written as structured SLUGS, which keeps its integers, with the same exit codes.
Each run is one process, killed with its process group at the time limit; every failure
is a :class:`~gaitc.diagnostics.SolverError` with a hint.
"""

from __future__ import annotations

import contextlib
import importlib.util
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Final

from gaitc.diagnostics import SolverError
from gaitc.ir.spec import GR1Spec, Semantics
from peers.spc import emit_spc
from slugs_bridge.structured import emit_structuredslugs

_GR1C_HINT: Final = ("build gr1c (https://github.com/tulip-control/gr1c) and set $GR1C or put "
                     "'gr1c' on PATH")
#: The folder holding the ``peers`` package, put on the omega child's import path.
_ROOT: Final = Path(__file__).resolve().parent.parent


@dataclass(frozen=True)
class PeerResult:
    """One run of a peer solver: which, its verdict, its wall-clock seconds (the whole
    process, start-up included) and the command that ran."""

    solver: str
    realizable: bool
    seconds: float
    command: tuple[str, ...] = ()

    @property
    def verdict(self) -> str:
        return "realizable" if self.realizable else "unrealizable"


def find_gr1c(explicit: str | None = None) -> str | None:
    """The gr1c binary: ``explicit``, else ``$GR1C``, else ``gr1c`` on PATH (gaitc never
    builds a peer, nor looks for one in a folder of its own choosing).  ``None`` when none
    is found; a
    :class:`~gaitc.diagnostics.SolverError` when a named binary (argument or ``$GR1C``) is
    missing or cannot be run."""
    for origin, candidate in (("the gr1c argument", explicit), ("$GR1C", os.environ.get("GR1C"))):
        if not candidate:
            continue
        found = shutil.which(candidate) or (candidate if os.access(candidate, os.X_OK) else None)
        if found is None or Path(found).is_dir():
            raise SolverError(f"the gr1c binary given by {origin} ('{candidate}') does not "
                              "exist or is not executable", hint=_GR1C_HINT)
        return os.path.abspath(found)
    return shutil.which("gr1c")


def omega_installed() -> bool:
    """Whether the ``omega`` package can be imported (the ``peers`` extra)."""
    return importlib.util.find_spec("omega") is not None


def run_gr1c(spec: GR1Spec, semantics: Semantics = Semantics.DEFAULT,
             timeout: float | None = None, gr1c: str | None = None) -> PeerResult:
    """Decide ``spec`` with ``gr1c -r`` under ``semantics`` (the ``.spc`` text and flags of
    :func:`peers.spc.emit_spc`)."""
    binary = find_gr1c(gr1c)
    if binary is None:
        raise SolverError("no gr1c binary found: set $GR1C or put 'gr1c' on PATH",
                          hint=_GR1C_HINT)
    program = emit_spc(spec, semantics, comments=False)
    with tempfile.TemporaryDirectory(prefix="gaitc-gr1c-") as tmp:
        path = Path(tmp, "spec.spc")
        path.write_text(program.text, encoding="utf-8")
        command = (binary, "-r", *program.flags, str(path))
        code, out, err, seconds = _run("gr1c", command, timeout, tmp)
    said = out.strip().splitlines()[-1:] if out.strip() else []
    if code == 0 and said == ["Realizable."]:
        return PeerResult("gr1c", True, seconds, command)
    if code == 3 and said == ["Not realizable."]:
        return PeerResult("gr1c", False, seconds, command)
    raise _failure("gr1c", code, out + err,
                   "gr1c rejected the text gaitc wrote: a bug in peers/spc.py" if code == 2
                   else "run the command by hand to see gr1c's own messages")


def run_omega(spec: GR1Spec, semantics: Semantics = Semantics.DEFAULT,
              timeout: float | None = None, python: str | None = None) -> PeerResult:
    """Decide ``spec`` with omega, as ``python -m peers.omega_game`` in a process of its own
    on the spec written as structured SLUGS (``python``: that interpreter, default this
    one)."""
    interpreter = python or sys.executable
    with tempfile.TemporaryDirectory(prefix="gaitc-omega-") as tmp:
        path = Path(tmp, "spec.structuredslugs")
        path.write_text(emit_structuredslugs(spec, comments=False), encoding="utf-8")
        command = (interpreter, "-m", "peers.omega_game", str(path), "--semantics",
                   str(semantics))
        code, out, err, seconds = _run("omega", command, timeout, tmp)
    said = out.strip().splitlines()[-1:] if out.strip() else []
    if code == 0 and said == ["realizable"]:
        return PeerResult("omega", True, seconds, command)
    if code == 3 and said == ["unrealizable"]:
        return PeerResult("omega", False, seconds, command)
    raise _failure("omega", code, err or out,
                   "install the peers extra (pip install 'gaitc[peers]')"
                   if "No module named 'omega" in err else
                   "run 'python -m peers.omega_game FILE' by hand to see the whole message")


def _run(name: str, command: tuple[str, ...], timeout: float | None,
         cwd: str) -> tuple[int, str, str, float]:
    """Exit code, stdout, stderr and wall-clock seconds of ``command``; its process group
    is killed at ``timeout``."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(_ROOT), env.get("PYTHONPATH")) if p)
    start = time.perf_counter()
    try:
        proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, cwd=cwd, env=env,
                                start_new_session=True)
    except OSError as err:
        raise SolverError(f"cannot run {name} ('{command[0]}'): {err.strerror}") from None
    try:
        out, err_text = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):  # it ended meanwhile
            os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise SolverError(f"{name} did not finish within {timeout:g} s",
                          hint="raise the time limit") from None
    return proc.returncode, out, err_text, time.perf_counter() - start


def _failure(name: str, code: int, text: str, hint: str) -> SolverError:
    how = f"killed by signal {-code}" if code < 0 else f"exit code {code}"
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    said = " | ".join(lines[-3:]) or "no message"
    return SolverError(f"{name} failed ({how}): {said}", hint=hint)
