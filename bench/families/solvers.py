"""The four GR(1) solvers of the benchmark tables, each run as a whole process on its own input.

gaitc (``python -m gaitc check FILE``, the instance's encoding for a .gait file), SLUGS on the
slugsin text gaitc writes, gr1c on the ``.spc`` text :mod:`peers.spc` writes (with its
flags), and omega as ``python -m peers.omega_game`` on a SLUGS file (the instance's own, or
the structured SLUGS gaitc writes for a .gait file).  :func:`prepare` writes the inputs
once per instance; :func:`run` measures one tool on them with :mod:`bench.families.measure`
and reads the verdict from the exit code and the output.
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Final

import gaitc
from bench.families.measure import Measurement, measure
from gaitc.diagnostics import GaitcError
from gaitc.ir.spec import Semantics
from peers.game import peer_game
from peers.runners import find_gr1c, omega_installed
from peers.spc import emit_spc
from slugs_bridge.runner import OPTIONS, find_slugs

ROOT: Final = Path(__file__).resolve().parent.parent.parent
TOOLS: Final = ("gaitc", "slugs", "gr1c", "omega")
#: A verdict, or why there is none: ``timeout``, ``error`` (the tool failed), ``n/a`` (the
#: tool cannot take the spec, or is not installed).
VERDICTS: Final = ("realizable", "unrealizable", "timeout", "error", "n/a")
_SLUGS_RESULT = re.compile(r"^RESULT: Specification is (realizable|unrealizable)\.\s*$", re.M)
_SLUGS_FORMATS = (".slugsin", ".structuredslugs", ".structureslugs", ".txt")


@dataclass(frozen=True)
class Binaries:
    """The solvers found on this machine (None: not found, its column says n/a)."""

    slugs: str | None
    gr1c: str | None
    omega: bool

    @staticmethod
    def find(slugs: str | None = None, gr1c: str | None = None) -> Binaries:
        slugs = find_slugs(slugs)  # $SLUGS or PATH: a peer is found, never built
        return Binaries(slugs, find_gr1c(gr1c), omega_installed())


@dataclass(frozen=True)
class Inputs:
    """One instance's files for each tool; ``gr1c_flags`` go before the ``.spc`` file;
    ``peers_missing`` says why neither gr1c nor omega can take the spec (its liveness, see
    :mod:`peers.game`), ``gr1c_missing`` why gr1c cannot (a comparison too large to list)."""

    spec: Path
    encoding: str
    slugsin: Path
    spc: Path | None
    gr1c_flags: tuple[str, ...]
    omega: Path
    peers_missing: str = ""
    gr1c_missing: str = ""


@dataclass(frozen=True)
class Run:
    """One tool on one instance: the verdict (one of :data:`VERDICTS`) and the figures of
    its process tree (wall and CPU seconds, peak MB; the command's own ``ru_maxrss``)."""

    tool: str
    verdict: str
    wall: float = 0.0
    cpu: float = 0.0
    peak_mb: float = 0.0
    maxrss_mb: float = 0.0
    note: str = ""

    @property
    def decided(self) -> bool:
        return self.verdict in ("realizable", "unrealizable")


def prepare(spec: Path, encoding: str, semantics: Semantics, folder: Path) -> Inputs:
    """Write ``spec``'s inputs for the four tools into ``folder`` (a name per spec)."""
    gr1 = gaitc.load(str(spec), encoding).gr1
    stem = f"{spec.stem}_{encoding}" if spec.suffix == ".gait" else spec.stem
    slugsin = folder / f"{stem}.slugsin"
    slugsin.write_text(gaitc.emit(gr1, "slugsin"), encoding="utf-8")
    if spec.suffix.lower() in _SLUGS_FORMATS:
        omega = spec
    else:
        omega = folder / f"{stem}.structuredslugs"
        omega.write_text(gaitc.emit(gr1, "structuredslugs"), encoding="utf-8")
    try:
        peer_game(gr1)
    except GaitcError as err:
        return Inputs(spec, encoding, slugsin, None, (), omega, peers_missing=err.message)
    try:
        program = emit_spc(gr1, semantics)
    except GaitcError as err:
        return Inputs(spec, encoding, slugsin, None, (), omega, gr1c_missing=err.message)
    spc = folder / f"{stem}.{semantics}.spc"
    spc.write_text(program.text, encoding="utf-8")
    return Inputs(spec, encoding, slugsin, spc, program.flags, omega)


def command(tool: str, inputs: Inputs, semantics: Semantics, found: Binaries
            ) -> list[str] | str:
    """The command line of ``tool`` on ``inputs``, or why it cannot run."""
    robotics = semantics == Semantics.ROBOTICS
    if tool == "gaitc":
        line = [sys.executable, "-m", "gaitc", "check", str(inputs.spec)]
        if inputs.spec.suffix == ".gait":
            line += ["--encoding", inputs.encoding]
        return line + (["--robotics-semantics"] if robotics else [])
    if tool == "slugs":
        if found.slugs is None:
            return "no slugs binary ($SLUGS)"
        return [found.slugs, *OPTIONS[("check", str(semantics))], str(inputs.slugsin)]
    if tool == "gr1c":
        if found.gr1c is None:
            return "no gr1c binary ($GR1C)"
        if inputs.spc is None:
            return inputs.peers_missing or inputs.gr1c_missing
        return [found.gr1c, "-r", *inputs.gr1c_flags, str(inputs.spc)]
    if tool == "omega":
        if not found.omega:
            return "omega is not installed (the peers extra)"
        if inputs.peers_missing:
            return inputs.peers_missing
        return [sys.executable, "-m", "peers.omega_game", str(inputs.omega), "--semantics",
                str(semantics)]
    raise ValueError(f"unknown tool {tool!r}; the tools are {', '.join(TOOLS)}")


def run(tool: str, inputs: Inputs, semantics: Semantics, found: Binaries,
        timeout: float) -> Run:
    """``tool`` on ``inputs`` as a whole process, killed past ``timeout`` seconds."""
    line = command(tool, inputs, semantics, found)
    if isinstance(line, str):
        return Run(tool, "n/a", note=line)
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), env.get("PYTHONPATH")) if p)
    done = measure(line, timeout, cwd=ROOT, env=env)
    verdict = "timeout" if done.timed_out else _verdict(tool, done)
    note = "" if verdict in ("realizable", "unrealizable", "timeout") else _last_words(done)
    return Run(tool, verdict, done.wall, done.cpu, done.peak_mb, done.maxrss_mb, note)


def _verdict(tool: str, done: Measurement) -> str:
    if tool == "slugs":
        found = _SLUGS_RESULT.findall(done.stderr)
        return found[0] if done.returncode == 0 and len(found) == 1 else "error"
    if tool == "gaitc" and done.returncode == 4 and "time" in done.stderr:
        return "timeout"
    code = -1 if done.returncode is None else done.returncode
    return {0: "realizable", 3: "unrealizable"}.get(code, "error")


def _last_words(done: Measurement) -> str:
    """The error a failed run printed: its first ``error:`` line, else its last line."""
    lines = [line.strip() for line in (done.stderr + done.stdout).splitlines() if line.strip()]
    errors = [line for line in lines if "error:" in line.lower()]
    return (errors or lines[-1:] or [f"exit code {done.returncode}"])[0]
