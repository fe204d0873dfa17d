"""Fuzz slice of the language server and the terminal player (issue 48), CI size: seeded
mutants of the sessions of :mod:`fuzz_lsp` and the key sequences of :mod:`fuzz_player`,
judged as ``bench/fuzz.py`` judges them; the faults found and not yet mended
(:data:`fuzz_lsp.KNOWN`) are each shown by a session of their own, and those mended
(:data:`fuzz_lsp.MENDED`) each stay mended in theirs.
"""

from __future__ import annotations

import importlib.util
import random
from collections import Counter

import pytest
from fuzz_mutate import mutate

LSP_RUNS = 25  # mutant sessions of the language server (about a second each)
PLAYER_RUNS = 25  # mutant key sequences of the player (about a second each)
LSP_LIMIT = 10.0  # seconds a session may take (generous: the machine is shared)
PLAYER_LIMIT = 30.0
PLAYER_KEYS = 120  # keys of a mutant played here, at most (the long mode plays 200)

needs_lsp = pytest.mark.skipif(importlib.util.find_spec("pygls") is None,
                               reason="the language server needs pygls")
needs_textual = pytest.mark.skipif(importlib.util.find_spec("textual") is None,
                                   reason="the terminal player needs textual")


# ---------------------------------------------------------------------- the language server
def test_a_session_is_framed_as_the_base_protocol_reads_it() -> None:
    from fuzz_lsp import EXCHANGES, frames_of, read_frames

    for name, data in EXCHANGES:
        wire = frames_of(data)
        frames = list(read_frames(wire.stream))
        assert frames and all(f.in_step for f in frames), name
        assert frames[-1].end == len(wire.stream), name
        assert frames_of(data) == wire  # deterministic
    # a line that is no longer JSON goes as one body (this mutant's headers are kept)
    broken = b'[\n{"jsonrpc": "2.0", "id": 1, "method": "shutdown"},\n{"jsonrpc": "2.0",\n]\n'
    assert [(f.in_step, f.body) for f in read_frames(frames_of(broken).stream)] == [
        (True, b'{"jsonrpc": "2.0", "id": 1, "method": "shutdown"}'),
        (True, b'{"jsonrpc": "2.0"')]
    # a wrong Content-Length puts every later frame out of step
    stream = b"Content-Length: 1\r\n\r\n{}}Content-Length: 2\r\n\r\n{}"
    assert [f.in_step for f in read_frames(stream)] == [True, False]


@needs_lsp
def test_every_lsp_seed_is_answered_in_full() -> None:
    from fuzz_lsp import EXCHANGES, session

    for name, data in EXCHANGES:
        run = session(data, LSP_LIMIT)
        assert not run.verdict.problems, (name, run.verdict.problems)
        assert run.judged >= 4 and run.answered == run.judged, (name, run)
        assert run.verdict.code == 0, name


@pytest.mark.slow  # about 25 s
@needs_lsp
def test_mutant_sessions_of_the_language_server() -> None:
    """Every request answered once, no traceback but pygls's, an end at exit: in 25
    seeded mutants, no problem that a known fault does not explain."""
    from fuzz_lsp import EXCHANGES, session, unknown_problems

    donors = [d for _, d in EXCHANGES]
    counts: Counter[str] = Counter()
    failures = []
    for index in range(LSP_RUNS):
        rng = random.Random(f"ci:lsp:{index}")
        name, seed = EXCHANGES[rng.randint(0, len(EXCHANGES) - 1)]
        data = mutate(seed, rng, donors)
        run = session(data, LSP_LIMIT)
        counts.update(requests=run.requests, judged=run.judged, unanswered=run.unanswered,
                      frames=run.frames)
        counts[run.verdict.outcome] += 1
        if unknown_problems(run.verdict):
            failures.append((index, name, data[:300], unknown_problems(run.verdict)))
    print(f"\nlsp: {LSP_RUNS} sessions, {dict(counts)}")
    assert not failures, failures
    assert counts["requests"] >= 5 * LSP_RUNS


def _known() -> list[object]:
    from fuzz_lsp import KNOWN

    race = pytest.mark.skip(reason="a race: its session shows it only now and then")
    return [pytest.param(k, id=k.name, marks=() if k.always else race) for k in KNOWN]


@needs_lsp
@pytest.mark.parametrize("known", _known() if importlib.util.find_spec("pygls") else [])
def test_a_known_fault_of_the_server_still_shows(known: object) -> None:
    """Each fault of :data:`fuzz_lsp.KNOWN` shows in its session (an expected failure
    while gaitc has it); once mended, this test fails until its entry is moved to
    :data:`fuzz_lsp.MENDED`."""
    from fuzz_lsp import Known, session

    assert isinstance(known, Known)
    problems = session(known.session, LSP_LIMIT).verdict.problems
    assert problems == known.explains(problems), problems
    assert problems, f"{known.name} is mended: move it to fuzz_lsp.MENDED"
    pytest.xfail(f"{known.name}: {known.what}")


def _mended() -> list[object]:
    from fuzz_lsp import MENDED

    return [pytest.param(k, id=k.name) for k in MENDED]


RACE_RUNS = 3  # sessions of a mended race (it showed about 1 in 10 before the mend)


@needs_lsp
@pytest.mark.parametrize("mended", _mended() if importlib.util.find_spec("pygls") else [])
def test_a_mended_fault_of_the_server_stays_mended(mended: object) -> None:
    """The session of each fault found by fuzzing and mended shows no problem at all:
    every request answered once (a malformed one with InvalidRequest), no traceback, an
    end at exit. A race's session is run a few times."""
    from fuzz_lsp import Known, session

    assert isinstance(mended, Known)
    for _ in range(1 if mended.always else RACE_RUNS):
        run = session(mended.session, LSP_LIMIT)
        assert not run.verdict.problems, (mended.name, run.verdict.problems)
        assert run.verdict.code == 0, (mended.name, run.stderr[-2000:])


@needs_lsp
def test_malformed_requests_are_answered_invalid_request() -> None:
    """A method that is not a string, an id that is a list: InvalidRequest (-32600), the
    second with id null (its id cannot be read), and no traceback in either answer."""
    from fuzz_lsp import MENDED, session

    sessions = {k.name: k.session for k in MENDED}
    for name, want_id in (("method-not-a-string", 2), ("id-not-int-or-string", None)):
        errors = [m for m in session(sessions[name], LSP_LIMIT).messages if "error" in m]
        assert [(m["id"], m["error"]["code"]) for m in errors] == [(want_id, -32600)], name
        assert "data" not in errors[0]["error"], errors


@needs_lsp
def test_a_command_cancelled_before_it_starts_does_no_work() -> None:
    """``$/cancelRequest`` of a repair command not yet started: answered RequestCancelled
    and the search never starts (no progress begun, no message shown)."""
    from fuzz_lsp import MENDED, session

    orphan = next(k.session for k in MENDED if k.name == "orphan-command-task")
    run = session(orphan, LSP_LIMIT)
    assert not run.verdict.problems, run.verdict.problems
    methods = {m.get("method") for m in run.messages}
    assert not methods & {"$/progress", "window/showMessage"}, methods
    cancelled = [m for m in run.messages if m.get("id") == 6]
    assert [m["error"]["code"] for m in cancelled] == [-32800]


# ---------------------------------------------------------------------- the player
def test_key_bytes_read_back_as_the_keys_of_the_seeds() -> None:
    pytest.importorskip("textual")
    from fuzz_player import EXCHANGES, bytes_of, keys_of, size_of

    for _, data in EXCHANGES:
        keys = keys_of(data)
        assert bytes_of(*size_of(data), keys) == data
    assert size_of(b"") == (80, 24) and size_of(b"\xff\xff") == (56, 16)
    assert keys_of(b"\0\0a123456\n/") == ["a", "1", "2", "3", "enter", "minus"]


@needs_textual
def test_every_player_seed_is_played_and_saved() -> None:
    from fuzz_player import EXCHANGES, drive

    for name, data in EXCHANGES:
        run = drive(data, PLAYER_LIMIT)
        assert not run.verdict.problems, (name, run.verdict.problems, run.output[-2000:])
        assert run.steps >= 1 and run.saved is not None, (name, run)


@pytest.mark.slow  # about 14 s
@needs_textual
def test_mutant_key_sequences_of_the_player() -> None:
    """No exception escapes the app, it ends on escape, escape, q, q, and the play is
    saved with every step: in 25 seeded mutants (half of them on a random screen)."""
    from fuzz_player import EXCHANGES, drive, mutate_play

    donors = [d for _, d in EXCHANGES]
    keys: Counter[str] = Counter()
    sizes = set()
    failures = []
    for index in range(PLAYER_RUNS):
        rng = random.Random(f"ci:player:{index}")
        name, seed = EXCHANGES[rng.randint(0, len(EXCHANGES) - 1)]
        data = mutate_play(seed, rng, donors)
        run = drive(data, PLAYER_LIMIT, PLAYER_KEYS)
        keys.update(run.keys)
        sizes.add(run.size)
        if run.verdict.problems:
            failures.append((index, name, data[:300], run.verdict.problems,
                             run.output[-1500:]))
    print(f"\nplayer: {PLAYER_RUNS} sessions, {sum(keys.values())} keys ({len(keys)} kinds), "
          f"{len(sizes)} sizes: {sorted(sizes)}")
    assert not failures, failures
    assert len(sizes) >= 8
