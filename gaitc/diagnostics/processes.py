"""Work in forked child processes: the answer of the first child to succeed, within a deadline.

Used twice: :mod:`gaitc.api.isolation` runs one solver run in a child to make ``--timeout`` and
``--memory-limit`` hard limits, and :mod:`gaitc.solver.portfolio` races two solver configurations
and keeps the first answer. Each child sends back one outcome through a pipe:
``("ok", value)`` or ``("raise", exception, traceback text)``; a child that ends without
one is ``("died", exit status)``, and a deadline passed is ``("timeout",)``. A child may
claim the answer before it has it (:func:`claim`: a racer that has solved the game first),
and the others are killed then. Children die
with their parent (``PR_SET_PDEATHSIG`` on Linux), ignore Ctrl-C (the parent handles it and
kills them), and are killed once an answer is chosen.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import signal
import sys
import time
import traceback
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, Final

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

# multiprocessing (with socket and the rest) and ctypes load when a child is first started,
# in the parent: a run that forks none (``gaitc check`` of a small spec) does not wait for
# them, and a forked child imports nothing.

#: Seconds past a time limit before a worker process (a racer, a limited child) is killed.
#: A child checks the limit itself between BDD operations and usually stops first; the
#: parent's kill is for the one operation that runs on (AMBA with 10 masters: seconds), and
#: ``--timeout`` promises to end within a second of its limit, CLI start-up included.
GRACE: Final = 0.1

Outcome = tuple[Any, ...]
_PR_SET_PDEATHSIG: Final = 1
_POLL: Final = 0.2  # the longest wait between looks at the children


def can_fork() -> bool:
    """Whether this process may start children: it can fork, and it is not itself a
    daemonic multiprocessing worker (those may not have children).  Such a worker runs
    multiprocessing's code, so a process that has not imported it is none."""
    if not hasattr(os, "fork"):
        return False
    loaded = sys.modules.get("multiprocessing")
    return loaded is None or not loaded.current_process().daemon


def first_success(works: Sequence[Callable[[], Any]], deadline: float | None = None,
                  setup: Callable[[], None] | None = None,
                  delays: Sequence[float] = (),
                  relay: Callable[[Any], None] | None = None) -> tuple[int, Outcome]:
    """Run each of ``works`` in its own forked child (after ``setup`` there) and return the
    index and outcome of the first to answer ``ok``; when none does, the first other
    outcome. Work ``i`` starts ``delays[i]`` seconds after the first (default 0), or at once
    when an earlier work has failed, and only while no answer has come. ``deadline`` is a
    :func:`time.monotonic` time: past it, ``("timeout",)``. What a child passes to
    :func:`to_parent` is handed to ``relay`` here (progress messages), as it arrives: the
    first child's until a child calls :func:`claim`, then only the claimant's, whose outcome
    (success or not) is then the answer, the others killed."""
    # lazy: for die_with_parent in the children, imported before the fork
    import ctypes  # noqa: F401
    import multiprocessing  # lazy: forked solvers' machinery, not on check's path (start-up)
    from multiprocessing import connection  # lazy: as multiprocessing above

    context = multiprocessing.get_context("fork")
    started_at = time.monotonic()
    starts = [started_at + (delays[i] if i < len(delays) else 0.0) for i in range(len(works))]
    children: dict[int, tuple[Any, Connection]] = {}
    failures: dict[int, Outcome] = {}
    claimant: int | None = None  # the child that called claim(), once one has

    def start_due() -> None:
        for i, work in enumerate(works):
            if claimant is not None:
                return
            if i not in children and time.monotonic() >= starts[i]:
                receiver, sender = context.Pipe(duplex=False)
                # Not daemonic: a child may race children of its own (gaitc.solver.portfolio in
                # the child of gaitc.api.isolation); every child is killed and joined below.
                child = context.Process(target=_child, args=(work, setup, sender),
                                        daemon=False)
                with signals_held():
                    child.start()
                sender.close()
                children[i] = (child, receiver)

    try:
        while True:
            start_due()
            for i, (child, receiver) in list(children.items()):
                if i in failures or claimant not in (None, i):
                    continue
                speaker = min(children) if claimant is None else claimant
                outcome = _outcome(child, receiver, relay if i == speaker else None)
                if outcome is not None and outcome[0] == "claim":
                    claimant = i
                    _stop_others(children, i)
                    outcome = _outcome(child, receiver, relay)
                if outcome is not None and outcome[0] == "ok":
                    return i, outcome
                if outcome is not None:
                    failures[i] = outcome
                    starts = [min(t, time.monotonic()) for t in starts]
                    if claimant is not None:  # the others are gone: this is the answer
                        return i, outcome
            if len(failures) == len(works):
                first = min(failures)
                return first, failures[first]
            now = time.monotonic()
            if deadline is not None and now >= deadline:
                return 0, ("timeout",)
            # once claimed, no other child starts (or waits to): only the claimant's pipe
            wake = ([] if claimant is not None
                    else [t for i, t in enumerate(starts) if i not in children])
            if deadline is not None:
                wake.append(deadline)
            timeout = max(0.0, min(wake) - now) if wake else None
            connection.wait([r for i, (_, r) in children.items()
                             if i not in failures and claimant in (None, i)],
                            timeout if timeout is None else min(timeout, _POLL))
    finally:
        for child, receiver in children.values():
            if child.is_alive():
                child.kill()
            child.join()
            receiver.close()


def _stop_others(children: dict[int, tuple[Any, Connection]], keep: int) -> None:
    """Kill and forget every child but ``keep`` (which has claimed the answer)."""
    for i in [i for i in children if i != keep]:
        child, receiver = children.pop(i)
        if child.is_alive():
            child.kill()
        child.join()
        receiver.close()


def _outcome(child: Any, receiver: Connection, relay: Callable[[Any], None] | None
             ) -> Outcome | None:
    """The child's answer, ``("died", status)`` when it ended without one, ``("claim",)``
    when it has called :func:`claim`, else None; messages for :func:`to_parent` on the way
    are relayed."""
    while True:
        try:
            if not receiver.poll(0):
                break
            item: Outcome = receiver.recv()
        except EOFError:
            break
        if item[0] != "message":
            return item
        if relay is not None:
            relay(item[1])
    if child.is_alive():
        return None
    try:
        if receiver.poll(0):
            late: Outcome = receiver.recv()
            if late[0] != "message":
                return late
    except EOFError:
        pass
    return ("died", child.exitcode)


_parent: Connection | None = None  # in a child: the pipe to the parent


def to_parent(message: Any) -> None:
    """In a child of :func:`first_success`: pass ``message`` to the parent's ``relay``."""
    if _parent is not None:
        with contextlib.suppress(OSError, ValueError):
            _parent.send(("message", message))


def claim() -> None:
    """In a child of :func:`first_success`: the answer will be this child's, so the parent
    kills the others, starts no more, and relays this child's messages from now on (a racer
    that has solved the game first extracts the controller alone).  Elsewhere a no-op."""
    if _parent is not None:
        with contextlib.suppress(OSError, ValueError):
            _parent.send(("claim",))


def _child(work: Callable[[], Any], setup: Callable[[], None] | None,
           sender: Connection) -> None:
    global _parent
    as_worker()
    _parent = sender
    try:
        if setup is not None:
            setup()
        outcome: Outcome = ("ok", work())
    except BaseException as err:  # every exception goes back to the parent
        outcome = ("raise", err, traceback.format_exc())
    try:
        sender.send(outcome)
    except Exception as err:  # an answer that cannot be pickled
        _send_portable(sender, outcome, err)
    finally:
        sender.close()


def _send_portable(sender: Connection, outcome: Outcome, err: Exception) -> None:
    """Send an error that did not pickle as a copy that does, else say why nothing came."""
    if outcome[0] == "raise":  # the error itself, without what cannot travel
        try:
            sender.send(("raise", _portable(outcome[1]), outcome[2]))
        except Exception:  # the message below says the answer was lost
            pass
        else:
            return
    with contextlib.suppress(Exception):
        sender.send(("raise", RuntimeError(
            f"the answer could not be passed back: {type(err).__name__}: {err}"), ""))


def _portable(err: BaseException) -> BaseException:
    """A copy of ``err`` that pickles: its arguments and attributes that do not travel
    between processes (a module, a lock, a parser's state) are left out or given as text,
    so the parent still reports the user's error (file, line, message), not an internal
    one."""
    def travels(value: object) -> bool:
        try:
            pickle.dumps(value)
        except Exception:
            return False
        return True

    clone = err.__class__.__new__(err.__class__)
    clone.args = tuple(a if travels(a) else str(a) for a in err.args)
    clone.__dict__.update({k: v for k, v in vars(err).items() if travels(v)})
    pickle.dumps(clone)  # raises when even the copy cannot travel
    return clone


#: The signals a run turns into exceptions (gaitc.cli), held back while a child is forked.
HELD: Final = frozenset({signal.SIGINT, signal.SIGTERM})


def mask_held(blocked: bool) -> None:
    """Block (or unblock) :data:`HELD` in the calling thread, where the platform has thread
    signal masks."""
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_BLOCK if blocked else signal.SIG_UNBLOCK, HELD)


@contextlib.contextmanager
def signals_held() -> Iterator[None]:
    """SIGINT and SIGTERM held back (blocked, then delivered) for the duration: around a
    fork, whose interpreter hooks (logging's lock release) print and drop an exception
    that a signal handler raises inside them, so that a Ctrl-C pressed just then was lost
    and the run went on to its end."""
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    before = signal.pthread_sigmask(signal.SIG_BLOCK, HELD)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, before)


def as_worker() -> None:
    """Set up a worker process of this run (a racer, a limited child, a pool's worker): it
    dies with its parent, even one killed by SIGKILL; Ctrl-C is the parent's to handle (it
    stops the workers); SIGTERM, the parent stopping it, ends it quietly; and the signals
    the parent held back around the fork are unblocked."""
    die_with_parent()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    mask_held(False)


def die_with_parent() -> None:
    """Ask the kernel to kill this process when its parent ends (Linux; elsewhere a no-op)."""
    # lazy: first_success imports it before it forks; other workers load it here
    import ctypes

    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        pass
