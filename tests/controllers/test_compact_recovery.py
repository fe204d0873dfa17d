"""Recovery in the compact form and the generated C (issue 52).

On shipped specs: the recovering compact controller is proved (its ordinary part by the
compact form's verifier, its surprise handling by :mod:`gaitc.verifier.recovery`, which
refuses a broken recovery move); the generated C (host gcc, -Wall -Wextra -Werror) and the
Python runtime make the same moves, outcomes and goal masks on 10,000 steps with seeded
violations injected (legs failing or losing a level, hazard switches); on every surprise
the outcome and the goals kept agree with :meth:`gaitc.sim.recovery.Fallback.enter`, which
re-solves the games itself, and the spec's own clauses (:class:`gaitc.sim.monitor.Monitor`)
find ρs kept on every move.  On the valve board (simavr, marker ``firmware``): the shuttle's
firmware built with ``codegen --recover`` answers ``C r`` as the runtime steps, and running
alone reports a leg failing in use on an ``R`` line and goes on instead of venting.
"""

from __future__ import annotations

import random
import shutil
import subprocess
from dataclasses import replace
from pathlib import Path

import pytest

import gaitc
from gaitc.codegen.build import write_sources
from gaitc.codegen.recovery import fit, recovery_sizes
from gaitc.compact.controller import CompactController
from gaitc.compact.diagram import Builder, TooLarge, leaf
from gaitc.compact.extraction import FieldOrder, slot_order
from gaitc.compact.recovery import (
    RecoveringController,
    RecoveringRunner,
    RecoveryOptions,
    prove_recovery,
    recovering_controller,
)
from gaitc.core.modes import Outcome
from gaitc.core.vocabulary import Field
from gaitc.sim.domain import Domain
from gaitc.sim.monitor import Monitor
from gaitc.sim.recovery import Fallback
from gaitc.solver.game import Game, goal_strategies
from gaitc.solver.symbolic import Options, SymbolicSpec

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "gaitc" / "examples"
SPECS = ("patrol_2x2.gait", "shuttle_2leg.gait", "corridor_hazard.gait")
HARNESS = r"""
#include <stdio.h>
#include <stdlib.h>
#include "gaitc_controller.h"
int main(void)
{
    char line[512];
    gaitc_state s;
    uint8_t in[GAITC_INPUTS + 1];
    while (fgets(line, sizeof line, stdin)) {
        char *p = line + 2;
        int k;
        uint16_t move = 0;
        uint8_t outcome = 0;
        for (k = 0; k < GAITC_INPUTS; k++) in[k] = (uint8_t)strtol(p, &p, 10);
        if (line[0] == 's') gaitc_start(&s, in);
        else outcome = gaitc_step_surprise(&s, in, &move);
        printf("%u %u %u %u", outcome, outcome == GAITC_STOPPED ? 0u : move,
               gaitc_kept(&s), s.goal);
        for (k = 0; k < GAITC_FIELDS; k++) printf(" %u", s.value[k]);
        printf("\n");
        fflush(stdout);
    }
    return 0;
}
"""
C_OUTCOME = {0: Outcome.ALLOWED, 1: Outcome.RECOVERED, 2: Outcome.DEGRADED, 3: Outcome.STOPPED}


@pytest.fixture(scope="module")
def made() -> dict[str, tuple[gaitc.Spec, RecoveringController]]:
    out = {}
    for name in SPECS:
        spec = gaitc.load(EXAMPLES / name) if (EXAMPLES / name).exists() \
            else gaitc.load(ROOT / "specs" / name)
        out[name] = spec, recovering_controller(spec.gr1, spec.vocabulary)
    return out


@pytest.mark.parametrize("name", SPECS)
def test_the_recovering_controller_is_proved(
        made: dict[str, tuple[gaitc.Spec, RecoveringController]], name: str) -> None:
    spec, rc = made[name]
    report = gaitc.verify(spec, rc.base)
    assert report.ok, report.problems
    proof = prove_recovery(spec.gr1, rc)
    assert proof.ok, proof.problems
    assert rc.fallbacks, "every shipped example has a surprise that only degrades"


def test_a_recovery_move_that_breaks_the_guarantees_is_refused(
        made: dict[str, tuple[gaitc.Spec, RecoveringController]]) -> None:
    spec, rc = made["patrol_2x2.gait"]
    refused = [k for k in range(len(rc.base.moves))
               if not prove_recovery(spec.gr1, replace(rc, recover_root=leaf(k))).ok]
    assert refused, "some constant recovery move must break sys_trans or the goals"
    flag_everywhere = prove_recovery(spec.gr1, replace(rc, recoverable_root=leaf(1)))
    assert not flag_everywhere.ok
    fb = rc.fallbacks[0]
    bad_entries = [k for k in range(len(rc.base.moves))
                   if not prove_recovery(spec.gr1, replace(rc, fallbacks=(
                       replace(fb, entry_root=leaf(k)), *rc.fallbacks[1:]))).ok]
    assert bad_entries, "some constant entry move must break sys_trans or the goals kept"
    assert any("fallback to goals" in p for k in bad_entries[:1]
               for p in prove_recovery(spec.gr1, replace(rc, fallbacks=(
                   replace(fb, entry_root=leaf(k)), *rc.fallbacks[1:]))).problems)


def test_sizes_and_the_budget_name_the_surprises_that_stop(
        made: dict[str, tuple[gaitc.Spec, RecoveringController]]) -> None:
    spec, rc = made["patrol_2x2.gait"]
    sizes = recovery_sizes(rc)
    assert len(sizes.parts) == 2 + len(rc.fallbacks) and sizes.total > sizes.parts[0].bytes
    full, words = fit(rc, sizes.total)
    assert full is not None and len(full.fallbacks) == len(rc.fallbacks)
    small, words = fit(rc, sizes.parts[0].bytes + sizes.parts[1].bytes)
    assert small is not None and small.fallbacks == ()
    assert prove_recovery(spec.gr1, small).ok
    dropped = [w for w in words if "case(s) (its fallback tables do not fit)" in w]
    assert dropped and all(" fails where the assumptions forbid it: " in w
                           or " loses a level where the assumptions forbid it: " in w
                           for w in dropped)
    none, words = fit(rc, sizes.parts[0].bytes)
    assert none is None and words


@pytest.mark.parametrize("name", ["patrol_2x2.gait", "corridor_hazard.gait"])  # 2 fallbacks
def test_a_budget_stops_building_and_keeps_what_fits(
        made: dict[str, tuple[gaitc.Spec, RecoveringController]], name: str) -> None:
    spec, rc = made[name]
    sizes = recovery_sizes(rc)
    first_two = sizes.parts[0].bytes + sizes.parts[1].bytes
    # too small for the controller and its recovery diagrams: building stops, nothing fits
    with pytest.raises(TooLarge) as stopped:
        recovering_controller(spec.gr1, spec.vocabulary,
                              options=RecoveryOptions(budget=first_two // 4))
    assert stopped.value.bytes > first_two // 4 == stopped.value.limit
    # room for the recovery diagrams but not every fallback: a prefix of them, proved, and
    # at least what trimming the whole build keeps
    budget = first_two
    kept = recovering_controller(spec.gr1, spec.vocabulary,
                                 options=RecoveryOptions(budget=budget))
    assert len(kept.fallbacks) < len(rc.fallbacks)
    assert [fb.kept for fb in kept.fallbacks] == [fb.kept for fb in
                                                  rc.fallbacks[:len(kept.fallbacks)]]
    trimmed, _ = fit(rc, budget)
    assert trimmed is not None and len(kept.fallbacks) >= len(trimmed.fallbacks)
    assert all(c.included == all(k < len(kept.fallbacks) for k in c.degraded)
               for c in kept.classes)
    assert gaitc.verify(spec, kept.base).ok
    assert prove_recovery(spec.gr1, kept).ok
    # what a budgeted build stops on bounds the tables from below: with the budget of the
    # whole tables exactly, nothing is stopped or left out
    whole = recovering_controller(spec.gr1, spec.vocabulary,
                                  options=RecoveryOptions(budget=sizes.total))
    assert whole == rc


def test_rolling_back_a_build_forgets_it() -> None:
    """A fallback that did not fit leaves nothing behind: the table after a rollback and a
    further build is the table of a builder that never tried it."""
    spec = gaitc.load(ROOT / "specs" / "patrol_2x2.gait")
    sym = SymbolicSpec(spec.gr1, Options(care=False))
    result = Game(sym).solve()
    slots = slot_order(spec.vocabulary, FieldOrder.GREEDY)
    strategies = goal_strategies(sym, result)
    care = result.winning & sym.env_trans
    tried, fresh = (Builder(sym.bdd, slots, spec.vocabulary.outputs, greedy=True)
                    for _ in range(2))
    first = tried.build_moves(care & sym.bdd.exist(set(b + "'" for b in sym.output_bits),
                                                   strategies[0]), strategies[0])
    mark = tried.mark()
    tried.build_boolean(result.winning, sym.sys_live[-1])
    tried.build_moves(care & sym.bdd.exist(set(b + "'" for b in sym.output_bits),
                                           strategies[-1]), strategies[-1])
    assert len(tried.nodes) > mark.nodes
    tried.rollback(mark)
    assert (len(tried.nodes), len(tried.moves), tried.bytes) == \
        (mark.nodes, mark.moves, mark.bytes)
    again = tried.build_boolean(result.winning, sym.sys_live[0])
    assert fresh.build_moves(care & sym.bdd.exist(set(b + "'" for b in sym.output_bits),
                                                  strategies[0]), strategies[0]) == first
    assert fresh.build_boolean(result.winning, sym.sys_live[0]) == again
    assert tried.nodes == fresh.nodes and tried.moves == fresh.moves
    assert tried.bytes == fresh.bytes


# ------------------------------------------------------------------ the 10,000 steps
def _spec_values(spec: gaitc.Spec, rc: RecoveringController, fields: dict[str, int]
                 ) -> tuple[int, ...]:
    """Spec-level values of field values (bits by the fields' cubes, integers decoded)."""
    bits: dict[str, bool] = {}
    for f in rc.base.vocabulary.fields:
        bits.update({b: False for b in f.bits})
        bits.update(f.cube(fields[f.name]))
    out = []
    for v in spec.gr1.variables():
        iv = rc.base.integers.get(v.name)
        if iv is not None:
            out.append(iv.low + sum(int(bits[b]) << k for k, b in enumerate(iv.bits)))
        else:
            out.append(int(bits[v.name]))
    return tuple(out)


def _surprise(rng: random.Random, inputs: tuple[Field, ...], now: dict[str, int]
              ) -> dict[str, int]:
    """A leg fails or loses a level, or the hazard switches (one field changes)."""
    f = rng.choice(inputs)
    out = {g.name: now[g.name] for g in inputs}
    if f.numeric:
        if now[f.name] > 0:
            out[f.name] = 0 if rng.random() < 0.5 else now[f.name] - 1
    else:
        out[f.name] = rng.choice([v for v in range(len(f.labels)) if v != now[f.name]] or [0])
    return out


@pytest.mark.skipif(shutil.which("gcc") is None, reason="no host C compiler")
@pytest.mark.parametrize("name", [
    "patrol_2x2.gait", "shuttle_2leg.gait",
    pytest.param("corridor_hazard.gait", marks=pytest.mark.slow)])  # about 10 s
def test_c_and_python_recover_alike_for_10000_steps(
        made: dict[str, tuple[gaitc.Spec, RecoveringController]], name: str,
        tmp_path: Path) -> None:
    spec, rc = made[name]
    seen = _lockstep(spec, rc, tmp_path, 10_000, name)
    assert seen[Outcome.RECOVERED] > 10 and seen[Outcome.ALLOWED] > 5000, seen
    assert seen[Outcome.DEGRADED] + seen[Outcome.STOPPED] > 0, seen


@pytest.mark.skipif(shutil.which("gcc") is None, reason="no host C compiler")
def test_without_fallbacks_the_c_stops_where_python_does(
        made: dict[str, tuple[gaitc.Spec, RecoveringController]], tmp_path: Path) -> None:
    spec, rc = made["patrol_2x2.gait"]
    seen = _lockstep(spec, rc.without_fallbacks(0), tmp_path, 1000, "no fallbacks")
    assert seen[Outcome.DEGRADED] == 0 and seen[Outcome.STOPPED] > 0, seen


def _lockstep(spec: gaitc.Spec, rc: RecoveringController, tmp_path: Path, steps: int,
              name: str) -> dict[Outcome, int]:
    """The generated C and the Python runtime side by side for ``steps`` steps with
    surprises injected (seeded by ``name``); each surprise's outcome checked against
    Fallback.enter (which the fallbacks dropped from ``rc`` turn into stops).  The count
    of each outcome."""
    ctrl = rc.base
    write_sources(ctrl, tmp_path, recovery=rc)
    (tmp_path / "harness.c").write_text(HARNESS)
    program = tmp_path / "harness"
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O1", "-o",
                    str(program), str(tmp_path / "gaitc_controller.c"),
                    str(tmp_path / "harness.c"), f"-I{tmp_path}"], check=True)
    fallback = Fallback(spec.gr1, Domain(spec.robot, spec.robot_encoding))
    monitor = Monitor(spec.gr1)
    inputs = ctrl.vocabulary.inputs
    fields = ctrl.vocabulary.fields
    rng = random.Random(f"52:{name}")
    seen = {o: 0 for o in Outcome}
    proc = subprocess.Popen([str(program)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            text=True)
    assert proc.stdin is not None and proc.stdout is not None

    def ask(line: str) -> list[int]:
        assert proc.stdin is not None and proc.stdout is not None
        proc.stdin.write(line + "\n")
        proc.stdin.flush()
        return [int(v) for v in proc.stdout.readline().split()]

    def start() -> RecoveringRunner:
        first = {f.name: len(f.labels) - 1 if f.numeric else 0 for f in inputs}
        run = RecoveringRunner(rc, first)
        answer = ask("s " + " ".join(str(first[f.name]) for f in inputs))
        assert answer[4:] == [run.state[f.name] for f in fields]
        return run

    run = start()
    try:
        for _ in range(steps):
            before = _spec_values(spec, rc, run.state)
            was_normal = run.mode == RecoveringRunner.NORMAL
            allowed = [c for c in _candidates(inputs)
                       if not monitor.check_step(before, _spec_values(
                           spec, rc, run.state | c)).env_failed]
            chosen = _surprise(rng, inputs, run.state) if rng.random() < 0.08 or not allowed \
                else rng.choice(allowed)
            step = run.step(chosen)
            answer = ask("x " + " ".join(str(chosen[f.name]) for f in inputs))
            assert C_OUTCOME[answer[0]] == step.outcome
            assert answer[1] == (0 if step.move is None else step.move)
            assert answer[2] == step.kept_mask and answer[3] == run.goal
            assert answer[4:] == [run.state[f.name] for f in fields]
            seen[step.outcome] += 1
            after = _spec_values(spec, rc, run.state)
            if step.outcome != Outcome.STOPPED:
                assert monitor.check_step(before, after).sys_failed == ()
            if step.outcome != Outcome.ALLOWED and was_normal:
                entry = fallback.enter(before, _named(spec, rc, chosen))
                expected = entry.outcome
                if expected == Outcome.DEGRADED and not any(
                        fb.kept == entry.kept for fb in rc.fallbacks):
                    expected = Outcome.STOPPED  # its tables were left out
                assert step.outcome == expected, (before, chosen)
                if step.outcome == Outcome.DEGRADED:
                    assert step.kept_mask == sum(1 << j for j in entry.kept)
            if step.outcome == Outcome.STOPPED:
                run = start()
    finally:
        proc.stdin.close()
        proc.wait()
    return seen


def _candidates(inputs: tuple[Field, ...]) -> list[dict[str, int]]:
    out: list[dict[str, int]] = [{}]
    for f in inputs:
        out = [c | {f.name: v} for c in out for v in range(len(f.labels))]
    return out


def _named(spec: gaitc.Spec, rc: RecoveringController, chosen: dict[str, int]
           ) -> dict[str, int]:
    """The inputs of ``chosen`` as spec-level values by name (what Fallback.enter reads)."""
    names = [v.name for v in spec.gr1.variables()]
    whole = {f.name: chosen.get(f.name, 0) for f in rc.base.vocabulary.fields}
    after = dict(zip(names, _spec_values(spec, rc, whole), strict=True))
    return {v.name: after[v.name] for v in spec.gr1.inputs}


# ------------------------------------------------------------------ the valve board
DIGITS = "0123456789abcdefghijklmnopqrstuvwxyz"


def _board_tools_missing() -> bool:
    from gaitc.hw.firmware import missing_tools

    return bool(missing_tools())


@pytest.mark.firmware  # builds two firmware images and runs one in simavr, about 5 s
@pytest.mark.skipif(_board_tools_missing(), reason="the AVR toolchain or libsimavr is missing")
def test_the_board_recovers_as_the_python_runtime(tmp_path: Path) -> None:
    """``codegen --target avr --recover`` on the shuttle: the board's ``C r`` answers (the
    ``R`` line, parsed by :func:`gaitc.hw.serial_board.parse_outcome`) are the Python
    runtime's outcome, goal mask, move, goal and fields on 600 steps with surprises; a
    stop vents."""
    import serial

    from gaitc.hw.firmware import Image, SimulatedBoard
    from gaitc.hw.firmware import build as build_firmware
    from gaitc.hw.serial_board import parse_outcome

    spec = gaitc.load(EXAMPLES / "shuttle_2leg.gait")
    made = gaitc.synthesize(spec, form="compact")
    assert isinstance(made.controller, CompactController)
    built = gaitc.generate(spec, made.controller, "avr", tmp_path / "board", recover=True)
    assert built.program is not None and built.recovering
    assert any(line.startswith("total:") for line in built.recovery)
    rc = recovering_controller(spec.gr1, spec.vocabulary)
    assert (tmp_path / "board" / "gaitc_controller.c").read_text() == _source(rc, tmp_path)
    plain = build_firmware(tmp_path / "plain")
    image = Image(built.program, built.program.with_suffix(".hex"), plain.simulator)
    inputs, fields = rc.base.vocabulary.inputs, rc.base.vocabulary.fields
    rng = random.Random("52:board")
    seen = {o: 0 for o in Outcome}
    with SimulatedBoard(image, tmp_path / "pins.jsonl") as sim:
        port = serial.Serial(sim.port, 115200, timeout=2.0)

        def ask(line: str) -> str:
            port.write(line.encode("ascii") + b"\n")
            return str(port.readline().decode("ascii")).strip()

        assert ask("PING").startswith("PONG gaitboard/2.0")
        first = {f.name: len(f.labels) - 1 for f in inputs}
        run = RecoveringRunner(rc, first)
        assert ask("C s " + "".join(DIGITS[first[f.name]] for f in inputs)).startswith("M 0")
        for _ in range(600):
            chosen = {f.name: rng.randrange(len(f.labels)) for f in inputs}
            step = run.step(chosen)
            answer = parse_outcome(ask("C r " + "".join(DIGITS[chosen[f.name]]
                                                        for f in inputs)))
            assert step.outcome == answer.outcome
            assert answer.kept == step.kept_mask and answer.goal == run.goal
            assert answer.move == (0 if step.move is None else step.move)
            assert answer.values == "".join(DIGITS[run.state[f.name]] for f in fields)
            seen[step.outcome] += 1
            if step.outcome == Outcome.STOPPED:
                assert sim.record()[-1][1].strip("0") == ""
                run = RecoveringRunner(rc, first)
                ask("C s " + "".join(DIGITS[first[f.name]] for f in inputs))
        port.close()
    assert all(seen[o] > 0 for o in Outcome), seen


def _source(rc: RecoveringController, folder: Path) -> str:
    write_sources(rc.base, folder / "again", recovery=rc)
    return (folder / "again" / "gaitc_controller.c").read_text()


def test_r_lines_parse_and_garbled_ones_are_refused() -> None:
    from gaitc.hw.serial_board import Garbled, parse_outcome

    line = parse_outcome("R degraded k=2 m=4 g=0 o=0a12")
    assert (line.outcome, line.kept, line.move, line.goal, line.values, line.step) == (
        Outcome.DEGRADED, 2, 4, 0, "0a12", None)
    assert parse_outcome("R recovered k=3 s=12").step == 12
    for bad in ("R", "R maybe k=1", "R stopped", "R stopped k=x", "R stopped k=1 k=1",
                "R stopped k=1 z=2", "R allowed k=1 o=a/b", "M 0 g=0 o=00"):
        with pytest.raises(Garbled):
            parse_outcome(bad)


def test_codegen_recover_reports_the_tables_on_the_command_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from gaitc.cli import main

    spec = str(EXAMPLES / "patrol_2x2.gait")
    controller = tmp_path / "p.compact.json"
    assert main(["synth", spec, "--compact", "-o", str(controller)]) == 0
    assert main(["codegen", spec, str(controller), "--target", "c", "-o",
                 str(tmp_path / "gen"), "--recover"]) == 0
    out = capsys.readouterr().out
    assert "recovery tables: controller and assumption monitor: " in out
    assert ("surprise: L3 fails where the assumptions forbid it: stop in 8 case(s) (no goal is "
            "achievable)") in out
    header = (tmp_path / "gen" / "gaitc_controller.h").read_text()
    assert "#define GAITC_RECOVER 1" in header and "gaitc_step_surprise" in header
    assert main(["codegen", spec, str(controller), "--target", "c", "-o",
                 str(tmp_path / "plain")]) == 0
    assert "GAITC_RECOVER" not in (tmp_path / "plain" / "gaitc_controller.h").read_text()
    assert main(["codegen", spec, str(controller), "--target", "c", "-o",
                 str(tmp_path / "x"), "--recover", "--no-monitor"]) == 2


SHUTTLE_3 = """robot "shuttle, three levels"
legs L1..L2 health 3
gait east uses L1 moves east valves 10, 00
gait west uses L2 moves west valves 01, 00
grid 1 x 2 cells a, b
cache a
start a
visit a, b infinitely often
"""


@pytest.mark.firmware  # builds two firmware images and runs the task in simavr, about 5 s
@pytest.mark.skipif(_board_tools_missing(), reason="the AVR toolchain or libsimavr is missing")
def test_the_board_running_alone_reports_a_surprise_and_goes_on(tmp_path: Path) -> None:
    """A leg in use reads failed at once (two levels lost in one step, which the
    assumptions forbid): the board running alone sends an ``R`` line with the Python
    runtime's outcome and goals kept before that step's ``A`` line, instead of venting."""
    import serial

    from gaitc.hw.firmware import Image, SimulatedBoard
    from gaitc.hw.firmware import build as build_firmware
    from gaitc.hw.serial_board import parse_outcome

    path = tmp_path / "shuttle3.gait"
    path.write_text(SHUTTLE_3)
    spec = gaitc.load(path)
    made = gaitc.synthesize(spec, form="compact")
    assert isinstance(made.controller, CompactController)
    built = gaitc.generate(spec, made.controller, "avr", tmp_path / "board", recover=True)
    assert built.program is not None and built.recovering
    rc = recovering_controller(spec.gr1, spec.vocabulary)
    plain = build_firmware(tmp_path / "plain")
    image = Image(built.program, built.program.with_suffix(".hex"), plain.simulator)
    inputs, fields = rc.base.vocabulary.inputs, rc.base.vocabulary.fields
    first = {f.name: len(f.labels) - 1 for f in inputs}
    run = RecoveringRunner(rc, first)
    surprises = []
    with SimulatedBoard(image, tmp_path / "pins.jsonl") as sim:
        port = serial.Serial(sim.port, 115200, timeout=3.0)
        port.write(f"A 40 {''.join(DIGITS[first[f.name]] for f in inputs)}\n".encode("ascii"))
        pending = None
        for count in range(40):
            line = str(port.readline().decode("ascii")).strip()
            assert line, "the board fell silent"
            if line.startswith("R "):
                pending = parse_outcome(line)
                continue
            if line.startswith("ERR"):
                assert pending is not None and str(pending.outcome) == "stopped"
                break
            assert line.startswith("A "), line
            step, move, goal, values = line.split(" ")[1:]
            state = {f.name: DIGITS.index(c) for f, c in zip(fields, values[2:], strict=True)}
            if step != "0":
                made_step = run.step({f.name: state[f.name] for f in inputs})
                assert move == f"m={made_step.move}" and goal == f"g={run.goal}"
                if pending is not None:
                    assert made_step.outcome == pending.outcome
                    assert made_step.kept_mask == pending.kept
                    assert pending.step == int(step)
                    surprises.append(pending.outcome)
                else:
                    assert made_step.outcome == Outcome.ALLOWED
            assert state == run.state
            pending = None
            if count == 3:
                sim.set_depth(0, 0.02)  # L1 reads failed from its next use on
        port.close()
    assert surprises, "the failing leg was never reported as a surprise"


@pytest.mark.skipif(shutil.which("gcc") is None, reason="no host C compiler")
def test_gaitc_run_of_a_recovering_controller_steps_as_the_runtime(
        made: dict[str, tuple[gaitc.Spec, RecoveringController]], tmp_path: Path) -> None:
    """Issue 60: the compiled gaitc-run ignored the --recover tables (its ``x`` always
    called gaitc_step, so after a surprise it made a move with a failed leg). It steps
    gaitc_step_surprise now and says the outcome, as RecoveringRunner does, on random
    inputs (most of them surprises)."""
    spec, rc = made["patrol_2x2.gait"]
    compact = gaitc.synthesize(spec, form="compact").controller
    assert isinstance(compact, CompactController)
    built = gaitc.generate(spec, compact, "c", tmp_path / "out", recover=True)
    assert built.program is not None
    inputs = rc.base.vocabulary.inputs
    fields = rc.base.vocabulary.fields
    rng = random.Random(60)
    first = {f.name: len(f.labels) - 1 if f.numeric else 0 for f in inputs}
    # episodes from the start: mostly steps that keep the legs (the hazard at random),
    # now and then any inputs at all (a surprise, more often than not); the expected
    # answers come from the runtime, stepped alongside
    lines, expected, seen = [], [], set()
    for _ in range(30):
        runner = RecoveringRunner(rc, first)
        lines.append("s " + " ".join(str(first[f.name]) for f in inputs))
        expected.append(" ".join([*(str(runner.state[f.name]) for f in fields), "0"]))
        for _ in range(15):
            if rng.random() < 0.25:
                row = {f.name: rng.randrange(len(f.labels)) for f in inputs}
            else:
                row = {f.name: runner.state[f.name] if f.numeric
                       else rng.randrange(len(f.labels)) for f in inputs}
            lines.append("x " + " ".join(str(row[f.name]) for f in inputs))
            step = runner.step(row)
            seen.add(step.outcome)
            if step.outcome == Outcome.STOPPED:
                expected.append("stopped")
                break
            head = {Outcome.RECOVERED: ["recovered"], Outcome.ALLOWED: []}.get(
                step.outcome, ["degraded", str(step.kept_mask)])
            expected.append(" ".join([*head, str(step.move),
                                      *(str(runner.state[f.name]) for f in fields),
                                      str(runner.goal)]))
    answers = subprocess.run([str(built.program)], input="\n".join(lines) + "\n", text=True,
                             capture_output=True, check=True, timeout=60).stdout.splitlines()
    assert answers == expected
    assert {Outcome.ALLOWED, Outcome.RECOVERED, Outcome.STOPPED} <= seen, seen
