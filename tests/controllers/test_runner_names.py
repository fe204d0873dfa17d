"""``gaitc-run --names`` reads the spec's names as well as printing them (issue 51).

A run fed value indices without ``--names`` and the same run fed names (``FIELD=NAME``, a
bare name, or a bare index, which stays an index) with ``--names`` must make the same moves
step by step; an unknown name, a name of another field or a name without ``--names`` is
refused with one ``error`` line.  The build's hint names ``--names``.  Needs gcc.
"""

from __future__ import annotations

import random
import shutil
import subprocess
from pathlib import Path

import pytest
from packages import ROOT

import gaitc
from gaitc.codegen.build import Built, build
from gaitc.compact.controller import CompactController

CORRIDOR = ROOT / "specs" / "corridor_hazard.gait"
needs_gcc = pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc is not installed")
pytestmark = needs_gcc


@pytest.fixture(scope="module")
def corridor() -> CompactController:
    made = gaitc.synthesize(gaitc.load(CORRIDOR), form="compact")
    assert made.verified and isinstance(made.controller, CompactController)
    return made.controller


@pytest.fixture(scope="module")
def built(corridor: CompactController, tmp_path_factory: pytest.TempPathFactory) -> Built:
    done = build(corridor, tmp_path_factory.mktemp("runner") / "out", "c")
    assert done.program is not None
    return done


def _talk(program: Path, lines: list[str], *flags: str) -> list[str]:
    done = subprocess.run([str(program), *flags], input="\n".join(lines) + "\n", text=True,
                          capture_output=True, check=True, timeout=60)
    assert done.stderr == ""
    return done.stdout.splitlines()


def _spoken(ctrl: CompactController, rng: random.Random, values: list[int]) -> str:
    """Input ``values`` (indices) in one of the ways --names reads them."""
    words = []
    for f, v in zip(ctrl.vocabulary.inputs, values, strict=True):
        label = f.labels[v]
        way = rng.randrange(3)
        if way == 0 or label.isdigit():  # a bare number would be read as an index
            words.append(f"{f.name}={label}" if way != 2 else str(v))
        else:
            words.append(label if way == 1 else str(v))
    return " ".join(words)


def _assumed_inputs(ctrl: CompactController, rng: random.Random, count: int
                    ) -> list[list[int]]:
    """``count`` input rows that keep the corridor's assumptions on every step: the legs
    stay at full health (idle legs keep theirs, and none is worn by these steps' choice),
    the spill comes and goes at random (its only assumption is fairness)."""
    rows = []
    for _ in range(count):
        rows.append([rng.randrange(len(f.labels)) if not f.numeric else len(f.labels) - 1
                     for f in ctrl.vocabulary.inputs])
    return rows


def test_names_in_make_the_same_run_as_indices(corridor: CompactController,
                                               built: Built) -> None:
    assert built.program is not None
    rng = random.Random(51)
    runs = _assumed_inputs(corridor, rng, 400)
    plain = [("s " if k == 0 else "x ") + " ".join(map(str, v)) for k, v in enumerate(runs)]
    named = [("s " if k == 0 else "x ") + _spoken(corridor, rng, v)
             for k, v in enumerate(runs)]
    by_index = _talk(built.program, plain)
    by_name = _talk(built.program, named, "--names")
    assert len(by_index) == len(by_name) == len(runs)
    fields = corridor.vocabulary.fields
    moved = 0
    for k, (number, word) in enumerate(zip(by_index, by_name, strict=True)):
        values = number.split()
        words = word.split()
        if k > 0:  # a step's answer starts with its move
            assert words.pop(0) == f"move={values.pop(0)}"
            moved += 1
        assert words == [f"{f.name}={f.labels[int(v)]}" for f, v in
                         zip(fields, values[:-1], strict=True)] + [f"goal={values[-1]}"]
    assert moved == len(runs) - 1


def test_an_answer_can_be_read_back(corridor: CompactController, built: Built) -> None:
    """A state as --names prints it (without its goal) is a whole state for ``a``."""
    assert built.program is not None
    first = _talk(built.program, ["s " + " ".join("0" for _ in corridor.vocabulary.inputs)],
                  "--names")[0]
    state = " ".join(first.split()[:-1])
    assert _talk(built.program, [f"a {state}"], "--names")[0] in ("0", "1")


def test_wrong_names_are_refused(corridor: CompactController, built: Built) -> None:
    assert built.program is not None
    inputs = corridor.vocabulary.inputs
    n = len(inputs)
    good = [f"{f.name}={f.labels[0]}" for f in inputs]
    unknown = [*good[:-1], f"{inputs[-1].name}=nowhere"]
    swapped = [good[1], good[0], *good[2:]]
    lines = ["s " + " ".join(unknown), "s " + " ".join(swapped), "s " + " ".join(good)]
    answers = _talk(built.program, lines, "--names")
    refusal = f"error: {n} input values in range expected (indices, names or FIELD=NAME)"
    assert answers[:2] == [refusal, refusal]
    assert answers[2].startswith(f"{corridor.vocabulary.fields[0].name}=")
    # without --names, names are not values
    assert _talk(built.program, ["s " + " ".join(good)]) == [
        f"error: {n} input values in range expected"]


def test_the_build_says_how_to_get_names(built: Built) -> None:
    assert built.hint is not None and "--names" in built.hint
    assert f"hint: '{built.program} --names' answers in the spec's names" in built.summary()
    assert built.to_json()["hint"] == built.hint


def test_a_runner_built_without_the_input_order_reads_indices(
        corridor: CompactController, built: Built, tmp_path: Path) -> None:
    """driver.c compiled by hand, without GAITC_INPUT_FIELDS: names out, indices in."""
    assert built.program is not None
    folder = built.program.parent
    program = tmp_path / "gaitc-run-plain"
    subprocess.run(["gcc", "-O1", "-Wall", "-Wextra", "-Werror", "-DGAITC_DUMP",
                    "-DGAITC_NAMES", f"-I{folder}", "-o", str(program),
                    str(folder / "gaitc_controller.c"),
                    str(ROOT / "gaitc" / "codegen" / "host" / "driver.c")],
                   check=True, capture_output=True)
    inputs = corridor.vocabulary.inputs
    answers = _talk(program, ["s " + " ".join(f"{f.name}={f.labels[0]}" for f in inputs),
                              "s " + " ".join("0" for _ in inputs)], "--names")
    assert answers[0] == f"error: {len(inputs)} input values in range expected"
    assert "=" in answers[1]


def test_names_in_are_clean_under_the_sanitizers(
        corridor: CompactController, built: Built, tmp_path: Path) -> None:
    """The name reader under -fsanitize=address,undefined, fed good, bad and cut names."""
    assert built.program is not None
    folder = built.program.parent
    program = tmp_path / "gaitc-run-asan"
    inputs = corridor.vocabulary.inputs
    order = "{" + ",".join(str(k) for k, f in enumerate(corridor.vocabulary.fields)
                           if f.is_input) + "}"
    subprocess.run(["gcc", "-O1", "-g", "-fsanitize=address,undefined",
                    "-fno-sanitize-recover=all", "-fno-omit-frame-pointer", "-Wall",
                    "-Wextra", "-Werror", "-DGAITC_DUMP", "-DGAITC_NAMES",
                    f"-DGAITC_INPUT_FIELDS={order}", f"-I{folder}", "-o", str(program),
                    str(folder / "gaitc_controller.c"),
                    str(ROOT / "gaitc" / "codegen" / "host" / "driver.c")],
                   check=True, capture_output=True)
    rng = random.Random(7)
    words = [w for f in corridor.vocabulary.fields for w in (f.name, *f.labels)]
    lines = []
    for _ in range(2000):
        tokens = []
        for f in inputs:
            pick = rng.random()
            label = rng.choice(f.labels)
            if pick < 0.5:
                tokens.append(f"{f.name}={label}")
            elif pick < 0.7:
                tokens.append(label)
            else:
                word = rng.choice(words)
                tokens.append(rng.choice([word, word[: rng.randrange(len(word) + 1)] + "=",
                                          "=" + word, "=", "999", "00", word + "=" + word]))
        lines.append(rng.choice("sxa") + " " + " ".join(tokens))
    done = subprocess.run([str(program), "--names"], input="\n".join(lines) + "\n",
                          text=True, capture_output=True, timeout=120,
                          env={"ASAN_OPTIONS": "detect_leaks=0", "PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stderr == ""
    assert len(done.stdout.splitlines()) == len(lines)


def test_tables_past_16_bit_offsets_compile_and_run_alike(
        corridor: CompactController, built: Built, tmp_path: Path) -> None:
    """Issue 60: a host controller whose ``kids`` table passed 65,536 entries was written
    with 16-bit offsets that gcc refused (``-Werror=overflow``: 112748 became 47212). The
    host target has no size limit: the offsets widen to 32 bits. The controller here is
    the corridor's with a chain of 23,000 nodes above its first move diagram, each with
    every child the same, so it must make the very moves of the corridor's own."""
    from dataclasses import replace

    from gaitc.codegen.tables import flatten
    from gaitc.compact.diagram import Branch

    slot = next(k for k, s in enumerate(corridor.slots) if len(s.field.labels) >= 3)
    width = len(corridor.slots[slot].field.labels)
    nodes = list(corridor.nodes)
    top = corridor.move_roots[0]
    for _ in range(70_000 // width):
        nodes.append(Branch(slot, (top,) * width))
        top = len(nodes) - 1
    wide = replace(corridor, nodes=tuple(nodes), move_roots=(top, *corridor.move_roots[1:]))
    tables = flatten(wide)
    assert tables.first_bytes == 4 and len(tables.kids) > 65_536
    done = build(wide, tmp_path / "wide", "c")
    assert done.program is not None and built.program is not None
    rng = random.Random(60)
    lines = [("s " if k == 0 else "x ") + " ".join(map(str, row))
             for k, row in enumerate(_assumed_inputs(corridor, rng, 300))]
    assert _talk(done.program, lines) == _talk(built.program, lines)
