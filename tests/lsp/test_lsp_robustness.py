"""The language server cannot be starved (issue 48): each finding of the fuzz campaign
against ``gaitc lsp``, as the exact behaviour that replaced it.

Most tests start ``gaitc lsp`` as a process and speak to it message by message over its
pipes (:class:`Server`), so that they can send what no LSP client library would (a
position of -1, ``"params": null``, bytes that are not JSON), send signals while its input
is still open, and watch its child processes. The scheduler and the analysis are also
tested in this process, with a stand-in analysis whose timing the test decides.
"""

from __future__ import annotations

import asyncio
import json
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import psutil
import pytest

import gaitc
from gaitc.lsp import analysis as analysis_module
from gaitc.lsp import scheduling
from gaitc.lsp.analysis import Analysis, Finding, analyse
from gaitc.lsp.scheduling import Document, Scheduler

ROOT = Path(__file__).resolve().parents[2]
PATROL = (ROOT / "specs" / "patrol_2x2.gait").read_text()
ROBOT_A = (ROOT / "specs" / "thesis_robot_a.gait").read_text()
#: Robot A with two health levels and no cache: unrealizable, and its repair search takes
#: seconds (5.5 s on the machine the test was written on), long enough to cancel.
SLOW_REPAIRS = ROBOT_A.replace("cache r3, r14", "").replace("health 3", "health 2")
#: The patrol with many guarantees: its analysis takes a second or more.
GUARANTEE = "guarantee always ((sw & !se) -> next(!nw | ne))\n"
SLOW_ANALYSIS = PATROL + GUARANTEE * 1200
PROMPT = 1.0  # seconds: what "at once" means for an answer or an exit


# ---------------------------------------------------------------------- the process
class Server:
    """``gaitc lsp`` as a process: messages written to its input, every message it writes
    kept with the time it arrived. Requests from the server (progress creation) are
    answered with null at once."""

    def __init__(self, stderr: Path) -> None:
        self._stderr = stderr.open("wb")
        # Ctrl-C as an editor's child has it: the server respects an ignored SIGINT, and a
        # pytest worker may have left SIGINT ignored for the children it starts
        self.proc = subprocess.Popen([sys.executable, "-m", "gaitc", "lsp"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=self._stderr,
                                     preexec_fn=lambda: signal.signal(signal.SIGINT,
                                                                      signal.SIG_DFL))
        self.received: list[tuple[float, dict[str, Any]]] = []
        self._arrived = threading.Condition()
        self._lock = threading.Lock()
        self._next_id = 0
        self._closed = False  # the server's output has ended
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        try:
            self._messages()
        finally:
            with self._arrived:
                self._closed = True
                self._arrived.notify_all()

    def _messages(self) -> None:
        out = self.proc.stdout
        assert out is not None
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    return
                if line == b"\r\n":
                    break
                if line.lower().startswith(b"content-length:"):
                    length = int(line.split(b":")[1])
            assert length is not None
            message = json.loads(out.read(length))
            if "method" in message and "id" in message:  # a request of the server
                self.send({"jsonrpc": "2.0", "id": message["id"], "result": None})
            with self._arrived:
                self.received.append((time.monotonic(), message))
                self._arrived.notify_all()

    def send_bytes(self, body: bytes) -> None:
        stdin = self.proc.stdin
        assert stdin is not None
        with self._lock:
            stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            stdin.flush()

    def send(self, message: dict[str, Any]) -> None:
        self.send_bytes(json.dumps(message).encode())

    def request(self, method: str, params: Any, msg_id: int | str | None = None) -> int | str:
        if msg_id is None:
            self._next_id += 1
            msg_id = self._next_id
        self.send({"jsonrpc": "2.0", "id": msg_id, "method": method, "params": params})
        return msg_id

    def notify(self, method: str, params: Any) -> None:
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def wait_for(self, found: Callable[[dict[str, Any]], bool], timeout: float = 60.0
                 ) -> tuple[float, dict[str, Any]]:
        """The first message (and its arrival time) for which ``found`` holds."""
        deadline = time.monotonic() + timeout
        with self._arrived:
            while True:
                for arrived, message in self.received:
                    if found(message):
                        return arrived, message
                left = deadline - time.monotonic()
                if left <= 0 or self._closed:
                    raise AssertionError(f"no such message within {timeout} s")
                self._arrived.wait(min(left, 0.1))

    def response(self, msg_id: int | str, timeout: float = 60.0) -> dict[str, Any]:
        return self.wait_for(lambda m: m.get("id") == msg_id and "method" not in m,
                             timeout)[1]

    def call(self, method: str, params: Any, timeout: float = 60.0) -> dict[str, Any]:
        return self.response(self.request(method, params), timeout)

    def notifications(self, method: str) -> list[dict[str, Any]]:
        with self._arrived:
            return [m for _, m in self.received if m.get("method") == method and "id" not in m]

    def initialize(self, capabilities: dict[str, Any] | None = None,
                   trace: str = "off") -> None:
        self.call("initialize", {"processId": os.getpid(), "rootUri": ROOT.as_uri(),
                                 "capabilities": capabilities or {}, "trace": trace})
        self.notify("initialized", {})

    def open(self, uri: str, text: str, version: int = 1) -> None:
        self.notify("textDocument/didOpen", {"textDocument": {
            "uri": uri, "languageId": "gait", "version": version, "text": text}})

    def change(self, uri: str, text: str, version: int) -> None:
        self.notify("textDocument/didChange", {
            "textDocument": {"uri": uri, "version": version},
            "contentChanges": [{"text": text}]})

    def diagnostics(self, uri: str, version: int, timeout: float = 120.0
                    ) -> list[dict[str, Any]]:
        _, message = self.wait_for(
            lambda m: m.get("method") == "textDocument/publishDiagnostics"
            and m["params"]["uri"] == uri and m["params"].get("version") == version, timeout)
        diagnostics: list[dict[str, Any]] = message["params"]["diagnostics"]
        return diagnostics

    def end(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        self._stderr.close()


@pytest.fixture()
def lsp(tmp_path: Path) -> Iterator[Server]:
    server = Server(tmp_path / "stderr.txt")
    try:
        yield server
    finally:
        server.end()


def _position(text: str, needle: str, nth: int = 0) -> dict[str, int]:
    start = -1
    for _ in range(nth + 1):
        start = text.index(needle, start + 1)
    line = text.count("\n", 0, start)
    return {"line": line, "character": start - (text.rfind("\n", 0, start) + 1)}


def _hover(uri: str, position: dict[str, int]) -> dict[str, Any]:
    return {"textDocument": {"uri": uri}, "position": position}


# ---------------------------------------------------------------------- 1. edit bursts
def test_an_edit_burst_runs_one_analysis_at_a_time_and_publishes_the_last(
        lsp: Server, tmp_path: Path) -> None:
    """10 edits 150 ms apart while an analysis of a second or more runs: analyses never
    overlap, each one superseded is dropped unpublished, and the only diagnostics published
    are those of the last version."""
    lsp.initialize(trace="verbose")
    uri = (tmp_path / "burst.gait").as_uri()
    lsp.open(uri, SLOW_ANALYSIS)
    for version in range(2, 12):
        time.sleep(0.15)
        body = SLOW_ANALYSIS.replace("start nw", f"start v{version}")
        lsp.change(uri, body, version)
    [diagnostic] = lsp.diagnostics(uri, 11)
    assert diagnostic["message"].startswith("unknown region 'v11'")
    lsp.call("shutdown", None)
    published = [m["params"]["version"] for m in lsp.notifications(
        "textDocument/publishDiagnostics") if m["params"]["uri"] == uri]
    assert published == [11]
    traces = [m["params"]["message"] for m in lsp.notifications("$/logTrace")
              if uri in m["params"]["message"]]
    running = 0
    for line in traces:  # started and ended alternate: never two at once
        if line.endswith("started"):
            running += 1
            assert running == 1, traces
        elif line.endswith("ended"):
            running -= 1
    started = [line for line in traces if line.endswith("started")]
    dropped = [line for line in traces if line.endswith("dropped: superseded")]
    assert 1 <= len(started) <= 4, traces  # the first, one or two under the burst, the last
    assert len(dropped) == len(started) - 1
    assert started[-1].endswith("version 11 started")


def test_the_scheduler_keeps_one_running_and_the_latest_pending(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """With an analysis of 0.5 s and 10 edits 10 ms apart: at most one analysis at a time,
    the versions analysed are the first and the latest, only the latest is published, and
    no document text but the latest is kept waiting."""
    active: list[int] = []
    most = [0]
    analysed: list[str] = []
    lock = threading.Lock()

    def slow(text: str, path: str, previous: Analysis | None = None) -> Analysis:
        with lock:
            active.append(1)
            most[0] = max(most[0], len(active))
        time.sleep(0.5)
        with lock:
            active.pop()
            analysed.append(text)
        return Analysis(text, path, findings=[Finding(text, None, "warning")])

    monkeypatch.setattr(scheduling, "analyse", slow)
    published: list[tuple[int, str]] = []

    def publish(doc: Document, findings: list[Finding]) -> None:
        published.append((doc.version, findings[0].message))

    held: list[list[str]] = []

    async def burst() -> Document | None:
        scheduler = Scheduler(publish, lambda line: None)
        scheduler.edit("file:///burst.gait", "text 1", 1)
        await asyncio.sleep(0.1)  # the first analysis is under way
        for version in range(2, 12):
            scheduler.edit("file:///burst.gait", f"text {version}", version)
            await asyncio.sleep(0.01)
        # the texts held now: the one being analysed and the latest, nothing between
        held.append([job.text for job in scheduler.running.values()]
                    + [doc.text for doc in scheduler.documents.values()])
        return await scheduler.current("file:///burst.gait", wait=5.0)

    doc = asyncio.run(burst())
    assert held == [["text 1", "text 11"]]
    assert most[0] == 1
    assert analysed == ["text 1", "text 11"]
    assert published == [(11, "text 11")]
    assert doc is not None and doc.analysis is not None and doc.analysis.text == "text 11"


# ---------------------------------------------------------------------- 2. deep formulas
DEEP = {
    "negations": "!" * 1000 + "sw",
    "conjunctions": " & ".join(["(sw"] * 1000) + ")" * 1000,
    "parentheses": "(" * 1000 + "sw" + ")" * 1000,
    "20,000 negations": "!" * 20_000 + "sw",
}


@pytest.mark.parametrize("formula", DEEP.values(), ids=DEEP.keys())
def test_a_deeply_nested_formula_is_indexed_without_recursion(formula: str) -> None:
    """The index walks formulas iteratively: every name of a formula nested thousands of
    levels deep is found (the recursive walk raised RecursionError at 1,000)."""
    text = PATROL + f"guarantee always {formula}\n"
    found = analyse(text, "deep.gait")
    assert found.findings == [] and found.model is not None and found.index is not None
    spec = gaitc.parse(text, "deep.gait")  # what `gaitc lint` says: no diagnostic either
    assert list(spec.diagnostics) == []
    line = text.count("\n")
    in_formula = [m for m in found.index.symbols["sw"].mentions if m.span.line == line]
    assert len(in_formula) == formula.count("sw")


def test_a_deep_formula_gets_diagnostics_hover_and_tokens_at_once(lsp: Server,
                                                                  tmp_path: Path) -> None:
    lsp.initialize()
    uri = (tmp_path / "deep.gait").as_uri()
    text = PATROL + f"guarantee always {DEEP['conjunctions']}\n"
    lsp.open(uri, text)
    assert lsp.diagnostics(uri, 1) == []
    where = _position(text, "sw", text.count("sw") - 1)  # the formula's last name
    started = time.monotonic()
    hover = lsp.call("textDocument/hover", _hover(uri, where))
    assert time.monotonic() - started < PROMPT
    assert hover["result"]["contents"]["value"].startswith("**region** `sw`")
    tokens = lsp.call("textDocument/semanticTokens/full", {"textDocument": {"uri": uri}})
    data = tokens["result"]["data"]
    line = char = 0
    places = set()
    for i in range(0, len(data), 5):
        line += data[i]
        char = data[i + 1] if data[i] else char + data[i + 1]
        places.add((line, char))
    assert (where["line"], where["character"]) in places


def test_an_analysis_that_fails_inside_gaitc_is_a_diagnostic(
        monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(tree: object) -> None:
        raise RuntimeError("index broken")

    monkeypatch.setattr(analysis_module, "Index", broken)
    found = analyse(PATROL, "patrol.gait")
    assert [(f.message, f.severity, f.hint) for f in found.findings] == [(
        "gaitc failed while analysing the file: internal error: RuntimeError: index broken",
        "error", "this is a bug in gaitc, not in your file; please report it")]


def test_a_failing_analysis_still_answers_the_requests_waiting_for_it(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Whatever escapes the analysis ends as a published diagnostic, and a request waiting
    for the document is answered as soon as it is, not after its 2 s wait."""
    def escapes(text: str, path: str, previous: Analysis | None = None) -> Analysis:
        raise RecursionError("maximum recursion depth exceeded")

    monkeypatch.setattr(scheduling, "analyse", escapes)
    published: list[list[Finding]] = []

    async def wait() -> tuple[Document | None, float]:
        scheduler = Scheduler(lambda doc, findings: published.append(findings),
                              lambda line: None)
        scheduler.edit("file:///broken.gait", PATROL, 1)
        started = time.monotonic()
        doc = await scheduler.current("file:///broken.gait", wait=2.0)
        return doc, time.monotonic() - started

    doc, waited = asyncio.run(wait())
    assert waited < 0.5
    assert doc is not None
    assert [[f.message for f in findings] for findings in published] == [[
        "gaitc failed while analysing the file: internal error: RecursionError: maximum "
        "recursion depth exceeded"]]


# ---------------------------------------------------------------------- 3. bad params
BAD_PARAMS = {
    "line -1": ({"textDocument": {"uri": "file:///x.gait"},
                 "position": {"line": -1, "character": 0}},
                "invalid params of textDocument/hover: params.position: Position.line should "
                "be in range [0:2147483647], but was -1."),
    "character 2^31": ({"textDocument": {"uri": "file:///x.gait"},
                        "position": {"line": 0, "character": 2**31}},
                       "invalid params of textDocument/hover: params.position: "
                       "Position.character should be in range [0:2147483647], but was "
                       "2147483648."),
    "params null": (None, "invalid params of textDocument/hover: params: not a valid "
                          "HoverParams (TypeError: argument of type 'NoneType' is not "
                          "iterable)"),
}


def test_every_request_is_answered_even_when_it_cannot_be_handled(lsp: Server) -> None:
    lsp.initialize()
    for params, message in BAD_PARAMS.values():
        answer = lsp.call("textDocument/hover", params, timeout=PROMPT)
        assert answer["error"] == {"code": -32602, "message": message}
    missing = lsp.response(_without_params(lsp, "textDocument/hover"), PROMPT)
    assert missing["error"] == {"code": -32602, "message": "invalid params of "
                                "textDocument/hover: params is missing"}
    unknown = lsp.call("gaitc/nothing", {}, timeout=PROMPT)
    assert unknown["error"]["code"] == -32601
    lsp.send_bytes(b"{not json")
    _, garbage = lsp.wait_for(lambda m: m.get("id", 0) is None, PROMPT)
    assert garbage["error"]["code"] == -32700
    assert garbage["error"]["message"].startswith("the message is not JSON: JSONDecodeError")
    lsp.send({"jsonrpc": "1.0", "id": "old", "method": "textDocument/hover", "params": {}})
    assert lsp.response("old", PROMPT)["error"] == {
        "code": -32600, "message": "not a JSON-RPC 2.0 message: \"jsonrpc\" is '1.0'"}
    lsp.send({"id": "bare", "method": "shutdown"})
    assert lsp.response("bare", PROMPT)["error"]["code"] == -32600
    lsp.send_bytes(b"[" * 100_000 + b"]" * 100_000)  # too deep for Python's decoder
    _, deep = lsp.wait_for(lambda m: m.get("id", 0) is None and m is not garbage, PROMPT)
    assert deep["error"]["code"] == -32700
    # the server goes on: a good request after all these is answered
    assert lsp.call("textDocument/hover", _hover("file:///x.gait", {"line": 0, "character": 0}),
                    timeout=PROMPT) == {"jsonrpc": "2.0", "id": lsp._next_id, "result": None}
    assert lsp.call("shutdown", None, timeout=PROMPT)["result"] is None
    late = lsp.call("textDocument/hover", _hover("file:///x.gait", {"line": 0, "character": 0}),
                    timeout=PROMPT)
    assert late["error"] == {"code": -32600, "message": "textDocument/hover: the server has "
                             "been shut down; only 'exit' is accepted now"}
    lsp.notify("exit", None)
    assert lsp.proc.wait(timeout=PROMPT) == 0


def _without_params(lsp: Server, method: str) -> int:
    lsp._next_id += 1
    lsp.send({"jsonrpc": "2.0", "id": lsp._next_id, "method": method})
    return lsp._next_id


# ---------------------------------------------------------------------- 4. signals and exit
@pytest.mark.parametrize(("signum", "code"), [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_a_signal_ends_the_server_at_once_while_its_input_is_open(
        lsp: Server, tmp_path: Path, signum: int, code: int) -> None:
    lsp.initialize()
    uri = (tmp_path / "busy.gait").as_uri()
    lsp.open(uri, SLOW_ANALYSIS)
    time.sleep(0.3)  # its analysis (a second or more) is under way
    sent = time.monotonic()
    lsp.proc.send_signal(signum)
    assert lsp.proc.wait(timeout=10) == code
    assert time.monotonic() - sent < PROMPT
    assert lsp.proc.stdin is not None and not lsp.proc.stdin.closed


def test_exit_during_an_analysis_ends_the_server_at_once(lsp: Server, tmp_path: Path) -> None:
    lsp.initialize()
    uri = (tmp_path / "busy.gait").as_uri()
    lsp.open(uri, SLOW_ANALYSIS)
    time.sleep(0.3)  # its analysis (a second or more) is under way
    assert lsp.call("shutdown", None, timeout=PROMPT)["result"] is None
    sent = time.monotonic()
    lsp.notify("exit", None)
    assert lsp.proc.wait(timeout=10) == 0
    assert time.monotonic() - sent < PROMPT


# ---------------------------------------------------------------------- 5. long commands
WITH_PROGRESS = {"window": {"workDoneProgress": True}}


def _progress(lsp: Server) -> list[dict[str, Any]]:
    return [m["params"]["value"] for m in lsp.notifications("$/progress")]


def test_hover_is_answered_while_repairs_are_searched_with_progress(
        lsp: Server, tmp_path: Path) -> None:
    lsp.initialize(WITH_PROGRESS)
    uri = (tmp_path / "slow.gait").as_uri()
    lsp.open(uri, SLOW_REPAIRS)
    lsp.diagnostics(uri, 1)
    repair = lsp.request("workspace/executeCommand",
                         {"command": "gaitc.findRepairs", "arguments": [uri]})
    lsp.wait_for(lambda m: m.get("method") == "$/progress")  # the search is under way
    asked = time.monotonic()
    hover = lsp.call("textDocument/hover", _hover(uri, _position(SLOW_REPAIRS, "north_a")))
    answered = time.monotonic()
    assert hover["result"]["contents"]["value"].startswith("**gait** `north_a`")
    assert answered - asked < PROMPT
    done_at, done = lsp.wait_for(lambda m: m.get("id") == repair and "method" not in m, 120)
    assert done_at > answered
    result = done["result"]
    assert result["repairs"] and result["message"].startswith(
        f"{len(result['repairs'])} verified repairs found")
    [create] = [m for _, m in lsp.received if m.get("method") == "window/workDoneProgress/create"]
    steps = _progress(lsp)
    assert {m["params"]["token"] for m in lsp.notifications("$/progress")} == {
        create["params"]["token"]}
    assert steps[0]["kind"] == "begin" and steps[0]["title"] == "gaitc: finding verified repairs"
    assert steps[0]["cancellable"] is True
    stages = [s.get("message") for s in steps[:-1]]
    assert "solving the spec, then verifying each candidate repair" in stages
    assert steps[-1] == {"kind": "end", "message": result["message"]}


def _children(lsp: Server) -> list[psutil.Process]:
    try:
        return list(psutil.Process(lsp.proc.pid).children(recursive=True))
    except psutil.NoSuchProcess:
        return []


def _alive(child: psutil.Process) -> bool:
    """Whether a child still runs; one that exits between listing and asking is gone."""
    try:
        return child.status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def _gone(lsp: Server, within: float) -> bool:
    deadline = time.monotonic() + within
    while time.monotonic() < deadline:
        if not [c for c in _children(lsp) if _alive(c)]:
            return True
        time.sleep(0.02)
    return False


def _solving(message: dict[str, Any]) -> bool:
    value = message.get("params", {}).get("value", {}) \
        if message.get("method") == "$/progress" else {}
    return str(value.get("message", "")).startswith("solving the spec")


@pytest.mark.parametrize("how", ["$/cancelRequest", "window/workDoneProgress/cancel"])
def test_cancelling_the_repair_search_kills_it_at_once(lsp: Server, tmp_path: Path,
                                                       how: str) -> None:
    lsp.initialize(WITH_PROGRESS)
    uri = (tmp_path / "slow.gait").as_uri()
    lsp.open(uri, SLOW_REPAIRS)
    lsp.diagnostics(uri, 1)
    params: dict[str, Any] = {"command": "gaitc.findRepairs", "arguments": [uri]}
    if how == "window/workDoneProgress/cancel":  # the client names the progress itself
        params["workDoneToken"] = "the client's token"
    lsp.request("workspace/executeCommand", params, msg_id="repairs")
    _, solving = lsp.wait_for(_solving)
    assert _children(lsp), "the search runs in a child process"
    created = [m for _, m in lsp.received if m.get("method") == "window/workDoneProgress/create"]
    if how == "window/workDoneProgress/cancel":
        assert solving["params"]["token"] == "the client's token" and created == []
    else:
        assert [m["params"]["token"] for m in created] == [solving["params"]["token"]]
    sent = time.monotonic()
    if how == "$/cancelRequest":
        lsp.notify("$/cancelRequest", {"id": "repairs"})
    else:
        lsp.notify("window/workDoneProgress/cancel", {"token": solving["params"]["token"]})
    answer = lsp.response("repairs", timeout=PROMPT)
    assert time.monotonic() - sent < PROMPT
    assert answer["error"]["code"] == -32800
    if how == "window/workDoneProgress/cancel":
        assert answer["error"]["message"] == "the search for repairs was cancelled"
    assert _gone(lsp, PROMPT), _children(lsp)
    lsp.wait_for(lambda m: m.get("method") == "$/progress"
                 and m["params"]["value"]["kind"] == "end", PROMPT)
    assert _progress(lsp)[-1] == {"kind": "end",
                                  "message": "the search for repairs was cancelled"}
    hover = lsp.call("textDocument/hover", _hover(uri, _position(SLOW_REPAIRS, "north_a")),
                     timeout=PROMPT)
    assert hover["result"] is not None


# ---------------------------------------------------------------------- issue 48's fuzz finds
def test_a_content_length_of_thousands_of_digits_is_skipped_not_fatal() -> None:
    """int() refuses more than 4,300 digits: such a length is no length (the block is
    skipped, as one without a length is), and a sane one after it is still read."""
    from gaitc.lsp.transport import _content_length, frames

    assert _content_length(b"Content-Length: " + b"1" * 5000) is None
    assert _content_length(b"Content-Length: " + b"9" * 19) is None
    assert _content_length(b"Content-Length: 0000000000000000000042") == 42
    read, write = os.pipe()
    os.write(write, b"Content-Length: " + b"7" * 5000 + b"\r\n\r\n"
             + b"Content-Length: 2\r\n\r\n{}")
    os.close(write)
    try:
        assert list(frames(read)) == [b"{}"]
    finally:
        os.close(read)


def test_the_repair_child_imports_nothing_the_server_did_not() -> None:
    """The repair command's child is forked from a server whose other threads may be
    importing (an analysis, the warm-up): after :func:`preload_repairs`, which the job
    runs before it forks, finding the repairs imports no module at all (else the child
    may wait for ever on an import lock copied from the server)."""
    probe = (
        "import sys\n"
        "import gaitc.lsp.server\n"
        "from gaitc.lsp.actions import find_repairs, preload_repairs\n"
        "preload_repairs()\n"
        "before = set(sys.modules)\n"
        f"find_repairs({(ROOT / 'specs' / 'unrealizable_2x2.gait').read_text()!r}, "
        "'u.gait', 60)\n"
        "print(sorted(set(sys.modules) - before))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                          timeout=300, cwd=ROOT)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "[]", ("add these to gaitc.lsp.actions.REPAIR_IMPORTS: "
                                         + done.stdout)
