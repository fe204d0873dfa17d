"""Trust at the edges (issue 48): a verified controller file is the controller.

Each finding of the campaign is a case here with its exact message or behaviour: a value
label that would close a C comment, values listed in another order with the logic kept,
a changed assumption monitor, another spec's controller, a yes/no diagram that points into a
move diagram, a symbolic controller with a changed variable index, the generated runner's
field checks and names, and the generated C under the address and undefined-behaviour
sanitizers.  The reader, the verifier and the generated code are exercised through the
commands a user runs.
"""

from __future__ import annotations

import copy
import json
import random
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest

import gaitc
from gaitc.cli import main
from gaitc.codegen.build import build
from gaitc.codegen.emitter import SAFE, c_names, header, source
from gaitc.compact.controller import (
    CompactController,
    compact_from_dict,
    compact_to_dict,
    to_symbolic,
)
from gaitc.compact.diagram import leaf, reachable_nodes
from gaitc.core.spec import Spec
from gaitc.core.vocabulary import Field, Vocabulary
from gaitc.verifier.symbolic import verify_symbolic

ROOT = Path(__file__).resolve().parents[2]
CORRIDOR = ROOT / "specs" / "corridor_hazard.gait"
PATROL = ROOT / "specs" / "patrol_2x2.gait"
needs_gcc = pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc is not installed")
BELONGS = "controller does not belong to this spec: "


@pytest.fixture(scope="module")
def corridor() -> tuple[Spec, CompactController]:
    spec = gaitc.load(CORRIDOR)
    made = gaitc.synthesize(spec, form="compact")
    assert made.verified and isinstance(made.controller, CompactController)
    return spec, made.controller


def _write(tmp_path: Path, data: dict[str, Any], name: str = "c.json") -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


def _field_index(data: dict[str, Any], name: str) -> int:
    return next(k for k, f in enumerate(data["fields"]) if f["name"] == name)


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


# ---------------------------------------------------------------- labels never become code
def test_a_label_that_would_close_a_c_comment_is_refused_before_codegen(
        corridor: tuple[Spec, CompactController], tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    _, ctrl = corridor
    data = compact_to_dict(ctrl)
    hazard = data["fields"][_field_index(data, "hazard")]
    hazard["values"][1]["label"] = "spill*\\\n/ int gaitc_injected(void) { return 1; } /*"
    path = _write(tmp_path, data)
    code, out, _ = _run(["verify", str(CORRIDOR), str(path)], capsys)
    assert code == 1
    assert out.splitlines()[1] == (
        "  - " + BELONGS + "field 'hazard' has 2 value(s): 'none', "
        "'spill*\\\\\\n/ int gaitc_injected(void) { return 1; } /*'; the spec's has 2 "
        "value(s): 'none', 'spill'")
    code, _, err = _run(["codegen", str(CORRIDOR), str(path), "--target", "c", "-o",
                         str(tmp_path / "out")], capsys)
    assert code == 1 and err.startswith(f"{path}:1:1: error: {BELONGS}field 'hazard' has ")
    assert not (tmp_path / "out").exists()


@needs_gcc
def test_generated_code_takes_no_name_verbatim(corridor: tuple[Spec, CompactController],
                                               tmp_path: Path) -> None:
    """Even a controller built in a notebook with hostile names (never read from a file)
    compiles with -Wall -Wextra -Werror to code that holds none of them as code."""
    _, ctrl = corridor
    payload = "x*\\\n/ int gaitc_injected(void) { return 1; } /* \u00e9\"'??/"
    fields = tuple(Field(payload if f.name == "hazard" else f.name, f.is_input,
                         tuple(payload if k else label for k, label in enumerate(f.labels)),
                         f.cubes, f.numeric) for f in ctrl.vocabulary.fields)
    hostile = Vocabulary(fields, ctrl.vocabulary.domain)
    slots = tuple(type(s)(fields[[f.name for f in ctrl.vocabulary.fields].index(s.field.name)],
                          s.next) for s in ctrl.slots)
    bad = CompactController(**{**ctrl.__dict__, "vocabulary": hostile, "slots": slots})
    text = header(bad) + source(bad)
    for line in text.splitlines():  # every comment naming fields is of the safe alphabet
        if line.startswith("#define GAITC_FIELD_"):
            body = line[line.index("/*") + 2:line.rindex("*/")]
            assert set(body) <= SAFE | {"*"} and "*/" not in body, line
    assert "\\\n" not in text and "gaitc_injected(void) {" not in text
    built = build(bad, tmp_path / "out", "c")
    assert built.program is not None
    symbols = subprocess.run(["nm", str(built.program)], capture_output=True, text=True,
                             check=True).stdout
    assert "gaitc_injected" not in symbols
    names = subprocess.run([str(built.program), "--names"], input="s 1 1 1 1 1\n",
                           capture_output=True, text=True, check=True).stdout
    assert payload in names  # the name itself survives, as a string


def test_c_names_are_distinct_ascii_identifiers() -> None:
    assert c_names(["L1", "l1", "a-b", "a_b", "9x", "\u00e9t\u00e9", ""]) == [
        "L1", "L1_2", "A_B", "A_B_2", "_9X", "_T_", "_"]


# ---------------------------------------------------------------- the vocabulary is proved
def _reordered(ctrl: CompactController) -> dict[str, Any]:
    """The file with the hazard's two values swapped and the children of every node that
    reads the hazard swapped too: the same logic, another value order."""
    data = compact_to_dict(ctrl)
    k = _field_index(data, "hazard")
    data["fields"][k]["values"].reverse()
    reading = {s for s, (name, _) in enumerate(data["slots"]) if name == "hazard"}
    for node in data["nodes"]:
        if node[0] in reading:
            node[1].reverse()
            node[2] = [1 - v for v in node[2]]
    moves_of = [f["name"] for f in data["fields"] if not f["input"]]
    assert "hazard" not in moves_of  # an input: no move row names it
    return data


def test_reordered_values_keep_the_logic_and_are_refused_by_every_command(
        corridor: tuple[Spec, CompactController], tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    spec, ctrl = corridor
    data = _reordered(ctrl)
    tampered = compact_from_dict(data, "t.json")
    # the logic is the same: the relations alone still verify
    assert verify_symbolic(spec.gr1, to_symbolic(tampered)).ok
    path = _write(tmp_path, data)
    why = (BELONGS + "field 'hazard' lists its values as 'spill', 'none'; the spec's order "
           "is 'none', 'spill'")
    code, out, _ = _run(["verify", str(CORRIDOR), str(path)], capsys)
    assert code == 1 and out.splitlines()[1] == f"  - {why}"
    for argv in (["simulate", str(CORRIDOR), str(path), "--steps", "5"],
                 ["render", "policy", str(CORRIDOR), str(path)],
                 ["codegen", str(CORRIDOR), str(path), "--target", "c", "-o",
                  str(tmp_path / "out")]):
        code, _, err = _run(argv, capsys)
        assert code == 1, argv
        assert err.startswith(f"{path}:1:1: error: {why}\n"), argv
    assert not (tmp_path / "out").exists()
    with pytest.raises(gaitc.ControllerError, match="lists its values as 'spill', 'none'"):
        gaitc.session(spec, path)
    report = gaitc.verify(spec, tampered)  # an object, not a file: the same answer
    assert not report.ok and report.problems == (why,)


def test_another_specs_compact_controller_is_refused_by_every_command(
        corridor: tuple[Spec, CompactController], tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    _, ctrl = corridor
    path = _write(tmp_path, compact_to_dict(ctrl))
    for argv in (["simulate", str(PATROL), str(path), "--steps", "5"],
                 ["render", "policy", str(PATROL), str(path)],
                 ["codegen", str(PATROL), str(path), "--target", "c", "-o",
                  str(tmp_path / "out")]):
        code, _, err = _run(argv, capsys)
        assert code == 1, argv
        assert err.startswith(f"{path}:1:1: error: {BELONGS}it lacks the spec's "), argv
    code, out, _ = _run(["verify", str(PATROL), str(path)], capsys)
    assert code == 1 and out.splitlines()[1].startswith(f"  - {BELONGS}it lacks the spec's ")


# ---------------------------------------------------------------- the monitor is proved
@pytest.mark.parametrize(("root", "word"), [(leaf(1), "allows"), (leaf(0), "forbids")])
def test_a_constant_monitor_fails_verify_with_the_state_where_it_differs(
        corridor: tuple[Spec, CompactController], tmp_path: Path,
        capsys: pytest.CaptureFixture[str], root: int, word: str) -> None:
    _, ctrl = corridor
    data = compact_to_dict(ctrl)
    data["roots"]["assumed"] = root
    path = _write(tmp_path, data)
    code, out, _ = _run(["verify", str(CORRIDOR), str(path)], capsys)
    assert code == 1
    other = "forbid" if word == "allows" else "allow"
    assert out.splitlines()[1].startswith(
        f"  - the assumption monitor {word} what the spec's assumptions (env_trans) "
        f"{other}: from the reachable state region=")
    code, _, err = _run(["codegen", str(CORRIDOR), str(path), "--target", "c", "-o",
                         str(tmp_path / "out")], capsys)
    assert code == 1 and "the assumption monitor" in err
    assert not (tmp_path / "out").exists()


def test_every_changed_monitor_leaf_fails_verify(
        corridor: tuple[Spec, CompactController]) -> None:
    """Flip each leaf of the nodes only the monitor uses, one at a time: every change the
    reachable states can see fails the proof, and every one is seen (the monitor was built
    on those states or on more)."""
    spec, ctrl = corridor
    assert ctrl.assumed_root is not None
    own = set(reachable_nodes(ctrl.nodes, ctrl.roots)) - set(
        reachable_nodes(ctrl.nodes, ctrl.roots[:-1]))
    flips = 0
    for n in sorted(own):
        for k, kid in enumerate(ctrl.nodes[n].kids):
            if kid >= 0:
                continue
            kids = list(ctrl.nodes[n].kids)
            kids[k] = leaf(1 - (-kid - 1))
            nodes = list(ctrl.nodes)
            nodes[n] = type(nodes[n])(nodes[n].field, tuple(kids), nodes[n].unused)
            changed = CompactController(**{**ctrl.__dict__, "nodes": tuple(nodes)})
            report = gaitc.verify(spec, changed)
            if k in ctrl.nodes[n].unused:
                continue  # a value no state has there
            flips += 1
            assert not report.ok and "the assumption monitor" in report.problems[-1]
    assert flips >= 10


def test_a_controller_without_a_monitor_says_so(
        corridor: tuple[Spec, CompactController], tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    _, ctrl = corridor
    data = compact_to_dict(ctrl)
    data["roots"]["assumed"] = None
    path = _write(tmp_path, data)
    code, out, _ = _run(["verify", str(CORRIDOR), str(path)], capsys)
    assert code == 0
    assert ("  note: the controller carries no assumption monitor: a board running it alone "
            "cannot tell when the assumptions break") in out.splitlines()
    ok = compact_to_dict(ctrl)
    code, out, _ = _run(["verify", str(CORRIDOR), str(_write(tmp_path, ok, "ok.json"))],
                        capsys)
    assert code == 0 and ("  note: the assumption monitor equals env_trans on every state a "
                          "run reaches") in out.splitlines()


# ---------------------------------------------------------------- structure of the diagrams
def test_a_yes_no_diagram_pointing_into_a_move_diagram_is_refused(
        corridor: tuple[Spec, CompactController], tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    _, ctrl = corridor
    data = compact_to_dict(ctrl)
    data["roots"]["reached"][0] = data["roots"]["moves"][0]
    path = _write(tmp_path, data)
    ends = sorted({-k - 1 for n in reachable_nodes(ctrl.nodes, [ctrl.move_roots[0]])
                   for k in ctrl.nodes[n].kids if k < 0})
    assert max(ends) >= 2
    for argv in (["verify", str(CORRIDOR), str(path)],
                 ["simulate", str(CORRIDOR), str(path), "--steps", "5"],
                 ["codegen", str(CORRIDOR), str(path), "--target", "c", "-o",
                  str(tmp_path / "out")],
                 ["render", "policy", str(CORRIDOR), str(path)]):
        code, _, err = _run(argv, capsys)
        assert code == 1, argv
        assert err.startswith(f"{path}:1:1: error: malformed compact controller: the diagram "
                              "of goal 1 "), (argv, err)
        assert ", where it may only return 0 or 1\n" in err or "reads the inputs" in err


def test_a_next_value_of_an_output_is_refused(
        corridor: tuple[Spec, CompactController]) -> None:
    _, ctrl = corridor
    data = compact_to_dict(ctrl)
    data["slots"][0] = [data["slots"][0][0], 1]
    with pytest.raises(gaitc.ControllerError) as caught:
        compact_from_dict(data, "x.json")
    assert caught.value.message == (
        f"malformed compact controller: slot ['{data['slots'][0][0]}', 1] reads the next "
        f"value of output field '{data['slots'][0][0]}'; only the environment's inputs have a "
        "value chosen before the controller moves")


def test_a_symbolic_controller_with_a_changed_variable_is_a_clean_error(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    sym = tmp_path / "sym.json"
    assert main(["synth", str(CORRIDOR), "--symbolic", "-o", str(sym)]) == 0
    capsys.readouterr()
    data = json.loads(sym.read_text(encoding="utf-8"))
    codes = []
    for k in range(0, len(data["nodes"]), 5):
        for delta in (-1, 1):
            changed = copy.deepcopy(data)
            changed["nodes"][k][0] += delta
            path = _write(tmp_path, changed, "m.json")
            code, _, err = _run(["simulate", str(CORRIDOR), str(path), "--steps", "20"],
                                capsys)
            assert code in (0, 1), err
            assert "internal error" not in err
            codes.append(code)
    assert codes.count(1) >= len(codes) // 2


# ---------------------------------------------------------------- the generated runner
@needs_gcc
def test_the_runner_checks_every_field_value_and_prints_names(
        corridor: tuple[Spec, CompactController], tmp_path: Path) -> None:
    _, ctrl = corridor
    built = build(ctrl, tmp_path / "out", "c")
    assert built.program is not None
    fields = ctrl.vocabulary.fields
    n_in = len(ctrl.vocabulary.inputs)
    bad = "a " + " ".join(["255"] * len(fields))
    lines = [bad, "x " + " ".join(["0"] * n_in), "a " + " ".join(["0"] * len(fields)),
             "s " + " ".join(["1"] * n_in), "d junk", "q"]
    done = subprocess.run([str(built.program)], input="\n".join(lines) + "\n", text=True,
                          capture_output=True, check=True)
    answers = done.stdout.splitlines()
    assert answers[0] == f"error: {len(fields)} field values in range expected"
    assert answers[1] == "error: start first"
    assert answers[2] in ("0", "1")
    assert answers[4:] == ["error: unknown command", "error: unknown command"]
    named = subprocess.run([str(built.program), "--names"],
                           input="s " + " ".join(["1"] * n_in) + "\n", text=True,
                           capture_output=True, check=True).stdout.split()
    assert [w.split("=")[0] for w in named] == [f.name for f in fields] + ["goal"]
    for word, f in zip(named, fields, strict=False):
        assert word.split("=", 1)[1] in f.labels
    refused = subprocess.run([str(built.program), "--bogus"], input="", text=True,
                             capture_output=True)
    assert refused.returncode == 2 and "usage: gaitc-run [--names]" in refused.stderr


@needs_gcc
def test_the_runner_is_clean_under_the_sanitizers(
        corridor: tuple[Spec, CompactController], tmp_path: Path) -> None:
    """gcc -fsanitize=address,undefined on the generated sources and the runner, fed
    random, garbage and out-of-range commands: no report, every line answered."""
    _, ctrl = corridor
    built = build(ctrl, tmp_path / "out", "c")
    assert built.program is not None
    folder = built.program.parent
    program = tmp_path / "gaitc-run-asan"
    flags = ["-O1", "-g", "-fsanitize=address,undefined", "-fno-sanitize-recover=all",
             "-fno-omit-frame-pointer", "-Wall", "-Wextra", "-Werror", "-DGAITC_DUMP",
             "-DGAITC_NAMES"]
    host = ROOT / "gaitc" / "codegen" / "host" / "driver.c"
    subprocess.run(["gcc", *flags, f"-I{folder}", "-o", str(program),
                    str(folder / "gaitc_controller.c"), str(host)], check=True,
                   capture_output=True)
    rng = random.Random(48)
    n_in, n_all = len(ctrl.vocabulary.inputs), len(ctrl.vocabulary.fields)
    sizes = [len(f.labels) for f in ctrl.vocabulary.inputs]
    lines = ["s " + " ".join(str(rng.randrange(n)) for n in sizes)]
    for _ in range(3000):
        kind = rng.random()
        if kind < 0.7:
            lines.append("x " + " ".join(str(rng.randrange(n)) for n in sizes))
        elif kind < 0.8:
            lines.append(rng.choice("sxa") + " " + " ".join(
                str(rng.randrange(300)) for _ in range(rng.choice((n_in, n_all, 1, 40)))))
        elif kind < 0.9:
            lines.append("".join(chr(rng.randrange(1, 256)) for _ in range(rng.randrange(60)))
                         .replace("\n", " "))
        else:
            lines.append(rng.choice(["d", "a", "x", "s", "", "x -1 " * n_in, "a 9999999999"]))
    text = "\n".join(lines) + "\n"
    done = subprocess.run([str(program), "--names"], input=text.encode("latin-1"),
                          capture_output=True, timeout=120,
                          env={"ASAN_OPTIONS": "detect_leaks=0", "PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr.decode("utf-8", "replace")[-2000:]
    assert done.stderr == b""
    assert len(done.stdout.decode("utf-8", "replace").splitlines()) >= len(lines) - 1
