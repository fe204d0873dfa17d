"""The SLUGS binary path (``--solver slugs``): run ``slugs`` on slugsin text, read its answers.

Facts from SLUGS's ``src/main.cpp`` (Ehlers & Raman, CAV 2016): the verdict is the
``RESULT: Specification is (un)realizable.`` line on stderr (exit code 0 for both); only fixed,
lexicographically sorted option combinations are accepted; ``--counterStrategy`` reads the
output file name *before* the input file, explicit strategies *after* it.  SLUGS answers in
the bit names gaitc's slugsin writer wrote; names it renamed (:mod:`slugs_bridge.names`) are
mapped back to the spec's before a controller is built.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass, replace
from pathlib import Path

from gaitc.diagnostics import SolverError, Span, source_lines, span_at
from gaitc.ir.bitblast import bitblast
from gaitc.ir.bits import spec_bits
from gaitc.ir.controller import (
    Controller,
    ControllerKind,
    ControllerNode,
    controller_from_dict,
    integers_of,
)
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import conj
from gaitc.ir.spec import GR1Spec, Semantics
from slugs_bridge.slugsin import slugsin_renaming

#: Options per task and semantics; every combination appears in SLUGS's ``optionCombinations``.
OPTIONS: dict[tuple[str, str], tuple[str, ...]] = {
    ("check", "default"): (),
    ("check", "robotics"): ("--sysInitRoboticsSemantics",),
    ("synth", "default"): ("--explicitStrategy", "--jsonOutput"),
    ("synth", "robotics"): ("--explicitStrategy", "--jsonOutput", "--sysInitRoboticsSemantics"),
    ("counter", "default"): ("--counterStrategy",),
    ("counter", "robotics"): ("--counterStrategy", "--sysInitRoboticsSemantics"),
}
_RESULT = re.compile(r"^RESULT: Specification is (realizable|unrealizable)\.\s*$", re.M)
_STATE = re.compile(r"^State (\d+) with rank \(?(\d+)(?:,(\d+))?\)? -> <([^>]*)>\s*$")
_SUCC = re.compile(r"^\s*With (?:successors : ?(.*)|no successors\.)\s*$")


@dataclass(frozen=True)
class SlugsResult:
    """What one SLUGS run said: the verdict, wall-clock time, its stderr and output file text."""

    realizable: bool
    seconds: float
    stderr: str
    output: str | None = None
    command: tuple[str, ...] = ()


def find_slugs(explicit: str | None = None) -> str | None:
    """The SLUGS binary: ``explicit`` (``--slugs PATH``), else ``$SLUGS``, else ``slugs`` on PATH.

    Returns ``None`` when none is found; raises :class:`SolverError` when an explicitly named
    binary (argument or ``$SLUGS``) does not exist or cannot be executed.
    """
    for origin, candidate in (("--slugs", explicit), ("$SLUGS", os.environ.get("SLUGS"))):
        if not candidate:
            continue
        found = shutil.which(candidate) or (candidate if os.access(candidate, os.X_OK) else None)
        if found is None or Path(found).is_dir():
            raise SolverError(
                f"the SLUGS binary given by {origin} ('{candidate}') does not exist or is not "
                "executable",
                hint="build slugs (https://github.com/VerifiableRobotics/slugs) or fix the path",
            )
        return os.path.abspath(found)
    return shutil.which("slugs")


def _binary(slugs: str | None) -> str:
    found = find_slugs(slugs)
    if found is None:
        raise SolverError(
            "no SLUGS binary found: give --slugs PATH, set $SLUGS, or put 'slugs' on PATH",
            hint="or use the embedded solver (--solver embedded)",
        )
    return found


def _run(
    mode: str, slugsin_text: str, semantics: Semantics, timeout: float | None, slugs: str | None
) -> SlugsResult:
    if (mode, semantics) not in OPTIONS:
        raise ValueError(f"unknown SLUGS task {mode!r} / semantics {semantics!r}")
    binary = _binary(slugs)
    with tempfile.TemporaryDirectory(prefix="gaitc-slugs-") as tmp:
        spec_file = Path(tmp, "spec.slugsin")
        spec_file.write_text(slugsin_text, encoding="utf-8")
        out_file = Path(tmp, "counter.txt" if mode == "counter" else "strategy.json")
        files = {"check": [str(spec_file)], "synth": [str(spec_file), str(out_file)],
                 "counter": [str(out_file), str(spec_file)]}[mode]
        command = (binary, *OPTIONS[(mode, semantics)], *files)
        start = time.perf_counter()
        try:
            proc = subprocess.Popen(
                command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                stderr=subprocess.PIPE, text=True, cwd=tmp,
            )
        except OSError as err:
            raise SolverError(f"cannot run SLUGS ('{binary}'): {err.strerror}") from None
        try:
            stdout, stderr = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            raise SolverError(
                f"SLUGS did not finish within {timeout:g} s",
                hint="raise --timeout or try the embedded solver",
            ) from None
        seconds = time.perf_counter() - start
        realizable = _verdict(stderr, proc.returncode)
        output = out_file.read_text(encoding="utf-8") if out_file.exists() else None
    if output is None and mode == "synth" and realizable and stdout.strip():
        output = stdout
    return SlugsResult(realizable, seconds, stderr, output, command)


def _verdict(stderr: str, returncode: int) -> bool:
    """The RESULT line of ``stderr``; SLUGS's ``Error: ...`` lines become a SolverError."""
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    errors = [line for line in lines if line.startswith("Error")]
    if errors or returncode != 0:
        text = "; ".join(errors or lines[-1:] or ["no message on stderr"])
        how = f"killed by signal {-returncode}" if returncode < 0 else f"exit code {returncode}"
        raise SolverError(f"SLUGS failed ({how}): {text}")
    found = _RESULT.findall(stderr)
    if len(found) != 1:
        raise SolverError(
            f"SLUGS printed {len(found)} RESULT lines instead of one; its stderr ends with: "
            + " | ".join(stderr.strip().splitlines()[-3:])
        )
    return bool(found[0] == "realizable")


def run_slugs_check(
    slugsin_text: str, *, semantics: Semantics = Semantics.DEFAULT, timeout: float | None = None,
    slugs: str | None = None,
) -> SlugsResult:
    """Decide realizability with ``slugs [--sysInitRoboticsSemantics] spec.slugsin``."""
    return _run("check", slugsin_text, semantics, timeout, slugs)


def run_slugs_synth(
    slugsin_text: str, *, semantics: Semantics = Semantics.DEFAULT, timeout: float | None = None,
    slugs: str | None = None,
) -> SlugsResult:
    """``slugs --explicitStrategy --jsonOutput ... spec.slugsin out.json``; ``output`` holds the
    JSON strategy when realizable (read it with :func:`controller_from_slugs_json`)."""
    return _run("synth", slugsin_text, semantics, timeout, slugs)


def run_slugs_counter(
    slugsin_text: str, *, semantics: Semantics = Semantics.DEFAULT, timeout: float | None = None,
    slugs: str | None = None,
) -> SlugsResult:
    """``slugs --counterStrategy ... out.txt spec.slugsin``; ``output`` holds SLUGS's textual
    counter-strategy when unrealizable (read it with :func:`counterstrategy_from_slugs_text`)."""
    return _run("counter", slugsin_text, semantics, timeout, slugs)


# ---------------------------------------------------------------- reading SLUGS's answers
def _starts(spec: GR1Spec, variables: tuple[str, ...], node: ControllerNode) -> bool:
    """Whether ``node``'s state satisfies env_init ∧ sys_init (``spec`` is Boolean)."""
    valuation = dict(zip(variables, node.state, strict=True))
    return evaluate(conj(c.formula for c in spec.env_init + spec.sys_init), valuation)


def controller_from_slugs_json(text: str, spec: GR1Spec, semantics: Semantics = Semantics.DEFAULT,
                               filename: str = "<slugs output>") -> Controller:
    """SLUGS's JSON strategy as a :class:`Controller`, with the gaitc extras filled in.

    SLUGS does not mark initial nodes: it numbers the states of W ∧ θe ∧ θs first, with
    rank 0, so the initial nodes are exactly the rank-0 nodes whose state satisfies θe ∧ θs.
    """
    try:
        data = json.loads(text)
    except json.JSONDecodeError as err:
        raise SolverError(
            f"SLUGS wrote a strategy that is not valid JSON: {err.msg}",
            span_at(text, filename, err.pos),
        ) from None
    boolean = bitblast(spec)
    if isinstance(data, dict) and "gaitc" not in data and isinstance(data.get("variables"), list):
        back = _spec_names(boolean)
        data = {**data, "variables": [back.get(v, v) if isinstance(v, str) else v
                                      for v in data["variables"]]}
    raw = controller_from_dict(data, filename, spec)
    initial = tuple(
        k for k, node in enumerate(raw.nodes)
        if node.rank == 0 and _starts(boolean, raw.variables, node)
    )
    return replace(raw, initial=initial, semantics=semantics, solver="slugs")


def counterstrategy_from_slugs_text(text: str, spec: GR1Spec,
                                    semantics: Semantics = Semantics.DEFAULT,
                                    filename: str = "<slugs output>") -> Controller:
    """SLUGS's textual counter-strategy (``State N with rank (i,j) -> <v:0, ...>`` lines).

    Dead-end states (the system has no move) list only input bits; their output bits become 0.
    The initial nodes are the leading run of non-dead-end nodes whose state satisfies θe ∧ θs
    (SLUGS numbers the states of W ∧ θe ∧ θs first).
    """
    ins, outs = spec_bits(spec)
    variables = ins + outs
    back = _spec_names(bitblast(spec))
    states: dict[int, tuple[int, tuple[int, ...]]] = {}
    trans: dict[int, tuple[int, ...]] = {}
    dead: set[int] = set()
    current: int | None = None
    for number, line in enumerate(source_lines(text), 1):
        span = Span(filename, number, 1)
        stripped = line.rstrip()
        if not stripped:
            continue
        state = _STATE.match(stripped.strip())
        succ = _SUCC.match(stripped)
        if state is not None:
            current = int(state.group(1))
            values = _bits(state.group(4), variables, back, span)
            states[current] = (int(state.group(2)), values)
        elif succ is not None and current is not None:
            if succ.group(1) is None:
                dead.add(current)
            trans[current] = trans.get(current, ()) + _ids(succ.group(1) or "", span)
        else:
            raise SolverError(f"cannot read SLUGS's counter-strategy here: {stripped!r}", span)
    count = len(states)
    if sorted(states) != list(range(count)):
        raise SolverError("SLUGS's counter-strategy does not number its states 0..N-1",
                          Span(filename, 1, 1))
    nodes = tuple(
        ControllerNode(states[k][0], states[k][1], tuple(sorted(set(trans.get(k, ())))))
        for k in range(count)
    )
    boolean = bitblast(spec)
    initial: list[int] = []
    for k, node in enumerate(nodes):
        if k in dead or not _starts(boolean, variables, node):
            break
        initial.append(k)
    return Controller(
        variables=variables, inputs=ins, outputs=outs, nodes=nodes, initial=tuple(initial),
        integers=integers_of(variables, frozenset(ins)), kind=ControllerKind.COUNTERSTRATEGY,
        solver="slugs", semantics=semantics,
    )


def _ids(text: str, span: Span) -> tuple[int, ...]:
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if not all(p.isdigit() for p in parts):
        raise SolverError(f"bad successor list in SLUGS's counter-strategy: {text!r}", span)
    return tuple(int(p) for p in parts)


def _spec_names(boolean: GR1Spec) -> dict[str, str]:
    """SLUGS's bit names (as gaitc's slugsin writer renamed them) -> the spec's bit names."""
    return {written: name for name, written in slugsin_renaming(boolean).items()}


def _bits(
    text: str, variables: tuple[str, ...], back: dict[str, str], span: Span
) -> tuple[int, ...]:
    found: dict[str, int] = {}
    for item in text.split(","):
        written, _, value = item.strip().rpartition(":")
        name = back.get(written, written)
        if name not in variables or value not in ("0", "1"):
            raise SolverError(f"unknown variable or value '{item.strip()}' in SLUGS's output",
                              span)
        found[name] = int(value)
    return tuple(found.get(v, 0) for v in variables)
