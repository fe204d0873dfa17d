"""Structured mutants of compact controllers and the differential oracle behind them.

Byte mutants (:mod:`fuzz_mutate`) mostly break a file's JSON; the mutants here keep it a
well-formed compact controller and change what it says: a child, a root, a move, the order
of a field's values (with or without the children that read it, so the logic is kept), a
label, a slot, the monitor.  :func:`judge` then holds each mutant to issue 48's promise:
the reader either refuses it with gaitc's own error, or the verifier refuses it, or it is
verified and then the Python runner, the symbolic runtime and the generated C make the
same moves on random and adversarial runs.  A verified mutant whose runtimes differ is a
hole in the proof.
"""

from __future__ import annotations

import copy
import json
import random
import subprocess
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import gaitc
from gaitc.compact.controller import CompactController, Runner
from gaitc.core.spec import Spec
from gaitc.diagnostics import GaitcError
from gaitc.forms.reader import runtime as view_of

Data = dict[str, Any]
PAYLOADS = ("none", "spill", "x*\\\n/ int evil; /*", "", "\u00e9", "r0 ", "0", "??/")


def _node_refs(data: Data) -> int:
    return len(data["nodes"])


def _some_ref(data: Data, rng: random.Random, below: int | None = None) -> int:
    """A node index below ``below`` or a leaf (moves and the two truth values)."""
    leaves = max(len(data["moves"]), 2) + 1  # one past: the reader must refuse it
    nodes = _node_refs(data) if below is None else below
    if nodes and rng.random() < 0.5:
        return rng.randrange(nodes)
    return -rng.randrange(leaves) - 1


def _kid(data: Data, rng: random.Random) -> str:
    if not data["nodes"]:
        return "no node"
    n = rng.randrange(len(data["nodes"]))
    kids = data["nodes"][n][1]
    kids[rng.randrange(len(kids))] = _some_ref(data, rng, n)
    return f"child of node {n}"


def _unused_kid(data: Data, rng: random.Random) -> str:
    """A child at a value no state has: the logic on reachable states is kept."""
    marked = [n for n, node in enumerate(data["nodes"]) if node[2]]
    if not marked:
        return _kid(data, rng)
    n = rng.choice(marked)
    value = rng.choice(data["nodes"][n][2])
    data["nodes"][n][1][value] = _some_ref(data, rng, n)
    return f"unused child of node {n}"


def _root(data: Data, rng: random.Random) -> str:
    roots = data["roots"]
    kind = rng.choice(["moves", "reached", "start", "assumed"])
    if kind in ("moves", "reached"):
        roots[kind][rng.randrange(len(roots[kind]))] = _some_ref(data, rng)
    elif kind == "assumed" and rng.random() < 0.3:
        roots[kind] = None
    else:
        roots[kind] = _some_ref(data, rng)
    return f"root {kind}"


def _move(data: Data, rng: random.Random) -> str:
    if not data["moves"] or not data["moves"][0]:
        return "no move"
    row = data["moves"][rng.randrange(len(data["moves"]))]
    row[rng.randrange(len(row))] = rng.randrange(4)
    return "move"


def _swap_values(data: Data, rng: random.Random, keep_logic: bool) -> str:
    k = rng.randrange(len(data["fields"]))
    values = data["fields"][k]["values"]
    if len(values) < 2:
        return "one value"
    a, b = rng.sample(range(len(values)), 2)
    values[a], values[b] = values[b], values[a]
    if keep_logic:
        name = data["fields"][k]["name"]
        reading = {s for s, (slot, _) in enumerate(data["slots"]) if slot == name}
        for node in data["nodes"]:
            if node[0] in reading and len(node[1]) > max(a, b):
                node[1][a], node[1][b] = node[1][b], node[1][a]
                node[2] = sorted({b if v == a else a if v == b else v for v in node[2]})
        if not data["fields"][k]["input"]:  # a move row holds an output's value index
            outs = [g["name"] for g in data["fields"] if not g["input"]]
            i = outs.index(name)
            for row in data["moves"]:
                row[i] = b if row[i] == a else a if row[i] == b else row[i]
    return f"values of field {k} swapped" + (" with the logic" if keep_logic else "")


def _label(data: Data, rng: random.Random) -> str:
    f = rng.choice(data["fields"])
    value = rng.choice(f["values"])
    value["label"] = rng.choice(PAYLOADS)
    return "label"


def _field_name(data: Data, rng: random.Random) -> str:
    f = rng.choice(data["fields"])
    old, f["name"] = f["name"], rng.choice(["hazard", "region", "L1", "gait", "x y"])
    for slot in data["slots"]:
        if slot[0] == old:
            slot[0] = f["name"]
    return "field name"


def _field_order(data: Data, rng: random.Random) -> str:
    if len(data["fields"]) > 1:
        a, b = rng.sample(range(len(data["fields"])), 2)
        data["fields"][a], data["fields"][b] = data["fields"][b], data["fields"][a]
    return "field order"


def _slot(data: Data, rng: random.Random) -> str:
    slot = rng.choice(data["slots"])
    slot[1] = 1 - slot[1]
    return "slot"


def _monitor(data: Data, rng: random.Random) -> str:
    data["roots"]["assumed"] = rng.choice([-1, -2, None, _some_ref(data, rng)])
    return "monitor"


def _semantics(data: Data, rng: random.Random) -> str:
    data["gaitc"]["semantics"] = rng.choice(["default", "robotics"])
    return "semantics"


MUTATIONS: tuple[tuple[str, Callable[[Data, random.Random], str]], ...] = (
    ("kid", _kid), ("unused kid", _unused_kid), ("root", _root), ("move", _move),
    ("swap", lambda d, r: _swap_values(d, r, False)),
    ("swap keeping logic", lambda d, r: _swap_values(d, r, True)),
    ("label", _label), ("field name", _field_name), ("field order", _field_order),
    ("slot", _slot), ("monitor", _monitor), ("semantics", _semantics),
)


def mutant(seed: Data, rng: random.Random) -> tuple[Data, list[str]]:
    """One to three structural mutations of the compact controller file ``seed``."""
    data = copy.deepcopy(seed)
    done = []
    for _ in range(rng.choice((1, 1, 2, 3))):
        name, change = rng.choice(MUTATIONS)
        done.append(f"{name}: {change(data, rng)}")
    return data, done


# ------------------------------------------------------------------------- the oracle
@dataclass
class Judgement:
    """What happened to one mutant: ``outcome`` is ``refused by the reader``, ``refused
    by the verifier``, ``verified, same moves`` or a failure (``internal``, ``differs``)."""

    outcome: str
    detail: str = ""
    steps: int = 0
    mutations: list[str] = field(default_factory=list)

    @property
    def failed(self) -> bool:
        return self.outcome in ("internal", "differs")


def _values(ctrl: CompactController, valuation: dict[str, int], inputs: bool
            ) -> dict[str, int] | None:
    out = {}
    for f in ctrl.vocabulary.fields:
        if f.is_input == inputs:
            value = f.value_of(valuation)
            if value is None:
                return None
            out[f.name] = value
    return out


def walks(spec: Spec, ctrl: CompactController, steps: int, seed: int, adversarial: bool
          ) -> Iterator[tuple[dict[str, int], dict[str, int]]]:
    """(inputs chosen, outputs made) along a run of the symbolic runtime over the
    controller's relations, the environment random or adversarial (lowest levels and a
    hazard whenever it may)."""
    view = view_of(ctrl, spec)
    rng = random.Random(seed)
    node = view.initial[0]
    first = view.valuation(node)
    ins, outs = _values(ctrl, first, True), _values(ctrl, first, False)
    if ins is None or outs is None:
        raise AssertionError("the symbolic runtime reached a state that names no value")
    yield ins, outs
    for _ in range(steps):
        options = list(view.options(node).values())
        if adversarial:
            node = min(options, key=lambda n: (sum((_values(
                ctrl, view.valuation(n), True) or {}).values()), rng.random()))
        else:
            node = rng.choice(options)
        values = view.valuation(node)
        ins, outs = _values(ctrl, values, True), _values(ctrl, values, False)
        if ins is None or outs is None:
            raise AssertionError("the symbolic runtime reached a state that names no value")
        yield ins, outs


def differences(spec: Spec, ctrl: CompactController, program: Path | None, steps: int,
                seeds: tuple[int, ...] = (1, 2)) -> tuple[list[str], int]:
    """Where the Python runner, the symbolic runtime and the compiled ``program``
    (``gaitc-run`` of the same controller; None: left out) disagree, on one random and one
    adversarial run per seed; and the steps compared."""
    found: list[str] = []
    fields = ctrl.vocabulary.fields
    lines: list[str] = []
    expected: list[str] = []
    compared = 0
    for k, seed in enumerate(seeds):
        walk = walks(spec, ctrl, steps, seed, adversarial=k % 2 == 1)
        first_in, first_out = next(walk)
        run = Runner(ctrl, first_in)
        if {f: run.state[f] for f in first_out} != first_out:
            found.append(f"run {k}: the first outputs differ from the symbolic runtime's")
        lines.append("s " + " ".join(str(first_in[f.name]) for f in ctrl.vocabulary.inputs))
        expected.append(" ".join(str(run.state[f.name]) for f in fields) + " 0")
        for step, (chosen, made) in enumerate(walk, 1):
            if run.step(chosen) != made:
                found.append(f"run {k} step {step}: Python and the symbolic runtime differ")
                break
            compared += 1
            lines.append("x " + " ".join(str(chosen[f.name]) for f in ctrl.vocabulary.inputs))
            expected.append(" ".join(str(run.state[f.name]) for f in fields) + f" {run.goal}")
    if program is not None and not found:
        done = subprocess.run([str(program)], input="\n".join(lines) + "\n", text=True,
                              capture_output=True, timeout=60, check=False)
        answers = done.stdout.splitlines()
        got = [a if line.startswith("s") else a.split(" ", 1)[-1]
               for line, a in zip(lines, answers, strict=False)]
        if done.returncode != 0 or got != expected:
            at = next((i for i, (g, e) in enumerate(zip(got, expected, strict=False))
                       if g != e), min(len(got), len(expected)))
            found.append(f"the generated C differs at line {at}: "
                         f"{got[at] if at < len(got) else 'no answer'!r} where Python "
                         f"says {expected[at] if at < len(expected) else 'nothing'!r} "
                         f"(exit {done.returncode})")
    return found, compared


def judge(spec: Spec, data: Data, folder: Path, steps: int = 60,
          compile_c: bool = True) -> Judgement:
    """The mutant ``data`` through the reader, the verifier and, when verified, the three
    runtimes (see the module text)."""
    from gaitc.codegen.build import build

    path = folder / "mutant.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    try:
        automaton = gaitc.api.solving.read_controller(path, spec)
    except GaitcError as err:
        return Judgement("refused by the reader", err.message)
    except Exception as err:
        return Judgement("internal", f"reader: {type(err).__name__}: {err}")
    if not isinstance(automaton, CompactController):
        return Judgement("internal", "the reader made another form of a compact file")
    try:
        report = gaitc.verify(spec, automaton)
    except GaitcError as err:
        return Judgement("refused by the verifier", err.message)
    except Exception as err:
        return Judgement("internal", f"verify: {type(err).__name__}: {err}")
    if not report.ok:
        return Judgement("refused by the verifier", report.problems[0])
    try:
        program = build(automaton, folder / "c", "c").program if compile_c else None
        found, compared = differences(spec, automaton, program, steps)
    except Exception as err:
        return Judgement("internal", f"runtimes: {type(err).__name__}: {err}")
    if found:
        return Judgement("differs", found[0], compared)
    return Judgement("verified, same moves", "", compared)
