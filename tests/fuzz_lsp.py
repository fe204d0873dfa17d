"""The language server under fuzzing: a mutant is a session of LSP messages for ``gaitc lsp``.

:func:`frames_of` turns the bytes into what is written to the server's input: a JSON list
of messages (one a line, so that a mutant whose JSON broke is read line by line, each line
that is not JSON going as one frame body), or, when the bytes start with a
``Content-Length`` header, the bytes themselves. :func:`session` runs one fresh server on
them, reads its answers with a deadline and judges the run like :mod:`fuzz_oracle` does:
every request is answered once, nothing inside the server fails (no traceback but
pygls's decode noise), it ends at ``exit``. :data:`MENDED` lists the faults found and
mended (each session a regression test), :data:`KNOWN` those found and not mended yet.
"""

from __future__ import annotations

import contextlib
import json
import os
import queue
import re
import select
import subprocess
import sys
import tempfile
import threading
import time
import zlib
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from fuzz_oracle import Verdict

ROOT = Path(__file__).resolve().parent.parent
EXIT_WAIT = 2.0  # seconds the server may take to end after ``exit`` (or its input closing)
START_WAIT = 60.0  # seconds the server's imports may take
MAX_EXPANDED = 4 << 20  # bytes a session's ``$repeat`` values may add up to, at most
MAX_HEADERS = 8 << 10  # bytes of one header block that the judge still reads as framing

# The server as ``gaitc lsp`` runs, its log records marked so that the judge can tell a
# traceback pygls logs (for a message it cannot decode) from one of gaitc's; it says when
# its imports are done (a byte on the pipe named by its argument), for a session's time
# is counted from there: on a busy machine starting Python takes seconds.
BOOT = """\
import logging, os, runpy, sys

class Marked(logging.Formatter):
    def format(self, record):
        return f"@@log {record.name} {record.levelname}\\n{super().format(record)}\\n@@end"

handler = logging.StreamHandler()
handler.setFormatter(Marked("%(message)s"))
logging.basicConfig(handlers=[handler], level=logging.WARNING)
import gaitc.lsp.server  # the imports take the time; then the judge's clock starts

ready = int(sys.argv[1])
os.write(ready, b"+")
os.close(ready)
sys.argv = ["gaitc", "lsp"]
runpy.run_module("gaitc", run_name="__main__", alter_sys=True)
"""


# ---------------------------------------------------------------------- the seeds
def _text(name: str) -> str:
    return (ROOT / "specs" / name).read_text()


PATROL = _text("patrol_2x2.gait")
UNREALIZABLE = _text("unrealizable_2x2.gait")
DEEP = {
    "negations": "!" * 1000 + "sw",
    "conjunctions": " & ".join(["(sw"] * 1000) + ")" * 1000,
    "parentheses": "(" * 1000 + "sw" + ")" * 1000,
}
URI = "file:///fuzz/patrol.gait"
OTHER = "file:///fuzz/unrealizable.gait"


def _at(text: str, needle: str, nth: int = 0) -> dict[str, int]:
    """The LSP position of the ``nth`` occurrence of ``needle`` in ``text``."""
    start = -1
    for _ in range(nth + 1):
        start = text.index(needle, start + 1)
    line = text.count("\n", 0, start)
    return {"line": line, "character": start - (text.rfind("\n", 0, start) + 1)}


def _request(msg_id: int | str, method: str, params: Any) -> dict[str, Any]:
    return {"jsonrpc": "2.0", "id": msg_id, "method": method, "params": params}


def _notify(method: str, params: Any) -> dict[str, Any]:
    return {"jsonrpc": "2.0", "method": method, "params": params}


def _doc(uri: str, position: dict[str, int] | None = None, **more: Any) -> dict[str, Any]:
    params: dict[str, Any] = {"textDocument": {"uri": uri}}
    if position is not None:
        params["position"] = position
    return {**params, **more}


def _open(uri: str, text: Any, version: int = 1) -> dict[str, Any]:
    return _notify("textDocument/didOpen", {"textDocument": {
        "uri": uri, "languageId": "gait", "version": version, "text": text}})


def _change(uri: str, version: int, *changes: dict[str, Any]) -> dict[str, Any]:
    return _notify("textDocument/didChange", {
        "textDocument": {"uri": uri, "version": version}, "contentChanges": list(changes)})


def _range(start: dict[str, int], end: dict[str, int]) -> dict[str, Any]:
    return {"start": start, "end": end}


def _start(capabilities: dict[str, Any] | None = None) -> list[Any]:
    return [_request(1, "initialize", {"processId": None, "rootUri": "file:///fuzz",
                                       "capabilities": capabilities or {}}),
            _notify("initialized", {})]


WAIT = {"$wait": True}  # the client waits for every answer owed so far
_END = [WAIT, _request("end", "shutdown", None), _notify("exit", None)]


def _session_bytes(messages: list[Any]) -> bytes:
    """A session as a seed: a JSON list, one message a line."""
    return ("[\n" + ",\n".join(json.dumps(m) for m in messages) + "\n]\n").encode()


def _wire_bytes(messages: list[Any]) -> bytes:
    """A session as the framed bytes themselves."""
    out = b""
    for message in messages:
        if message == WAIT:  # the bytes as they are: nothing but messages
            continue
        body = json.dumps(message).encode()
        out += b"Content-Length: %d\r\n\r\n" % len(body) + body
    return out


def _features() -> list[Any]:
    """Every request of the server on the patrol, a broken edit and a repaired one."""
    sw, west = _at(PATROL, "sw", 2), _at(PATROL, "west", 1)
    broken = PATROL.replace("start nw", "start nx")
    suggestion = {"range": _range(_at(broken, "nx"), {**_at(broken, "nx"), "character":
                                                      _at(broken, "nx")["character"] + 2}),
                  "message": "unknown region 'nx'", "data": {"suggestion": "nw"}}
    return [
        *_start(), _open(URI, PATROL),
        _request(2, "textDocument/hover", _doc(URI, sw)),
        _request(3, "textDocument/definition", _doc(URI, sw)),
        _request(4, "textDocument/references", _doc(URI, sw, context={
            "includeDeclaration": True})),
        _request(5, "textDocument/completion", _doc(URI, _at(PATROL, "visit"))),
        _request(6, "textDocument/documentSymbol", _doc(URI)),
        _request(7, "textDocument/semanticTokens/full", _doc(URI)),
        _request(8, "textDocument/prepareRename", _doc(URI, west)),
        _request(9, "textDocument/rename", _doc(URI, west, newName="w2")),
        WAIT, _change(URI, 2, {"text": broken}),
        _request(10, "textDocument/codeAction", _doc(URI, range=suggestion["range"], context={
            "diagnostics": [suggestion]})),
        _change(URI, 3, {"range": suggestion["range"], "text": "nw"}),
        _request(11, "textDocument/hover", _doc(URI, _at(PATROL, "nw", 1))),
        _request(12, "textDocument/completion", _doc(URI, {"line": 3, "character": 5})),
        _request(13, "textDocument/rename", _doc(URI, west, newName="1 bad")),
        WAIT, _notify("textDocument/didClose", _doc(URI)),
        _request(14, "textDocument/hover", _doc(URI, sw)),
        *_END,
    ]


def _repairs() -> list[Any]:
    """The repair command on an unrealizable spec, its code actions, a cancel."""
    whole = _range({"line": 0, "character": 0}, {"line": 30, "character": 0})
    command = {"command": "gaitc.findRepairs", "arguments": [OTHER]}
    return [
        *_start({"window": {"workDoneProgress": True}}), _open(OTHER, UNREALIZABLE),
        _request(2, "textDocument/codeAction", _doc(OTHER, range=whole, context={
            "diagnostics": []})),
        _request(3, "workspace/executeCommand", command),
        _request(4, "textDocument/hover", _doc(OTHER, _at(UNREALIZABLE, "L1", 1))),
        _request(5, "textDocument/codeAction", _doc(OTHER, range=whole, context={
            "diagnostics": []})),
        _request(6, "workspace/executeCommand", {**command, "workDoneToken": "t"}),
        _notify("$/cancelRequest", {"id": 6}),
        _request(7, "workspace/executeCommand", {"command": "gaitc.findRepairs",
                                                 "arguments": [[OTHER], 5]}),
        _request(8, "workspace/executeCommand", {"command": "gaitc.nothing"}),
        _notify("window/workDoneProgress/cancel", {"token": "t"}),
        *_END,
    ]


def _deep() -> list[Any]:
    """Formulas nested 1,000 deep, hovered and highlighted."""
    out = _start()
    for number, (name, formula) in enumerate(DEEP.items()):
        text = PATROL + f"guarantee always {formula}\n"
        uri = f"file:///fuzz/deep_{name}.gait"
        last = _at(text, "sw", text.count("sw") - 1)
        out += [_open(uri, text),
                _request(10 * number + 2, "textDocument/hover", _doc(uri, last)),
                _request(10 * number + 3, "textDocument/semanticTokens/full", _doc(uri)),
                _request(10 * number + 4, "textDocument/references", _doc(uri, last, context={
                    "includeDeclaration": False})),
                _request(10 * number + 5, "textDocument/documentSymbol", _doc(uri))]
    return [*out, *_END]


def _odd_params() -> list[Any]:
    """Positions of -1 and 2^31, null and missing params, ids and bodies of every shape."""
    hover = "textDocument/hover"
    return [
        *_start(), _open(URI, PATROL),
        _request(2, hover, _doc(URI, {"line": -1, "character": 0})),
        _request(3, hover, _doc(URI, {"line": 0, "character": 2**31})),
        _request(4, hover, _doc(URI, {"line": 2**31, "character": -1})),
        _request(5, hover, None),
        {"jsonrpc": "2.0", "id": 6, "method": "textDocument/completion"},
        _request(7, "textDocument/definition", {"textDocument": None, "position": []}),
        _request("eight", "textDocument/references", _doc(URI, {"line": 9, "character": 5})),
        _request(9, "gaitc/nothing", {}),
        {"jsonrpc": "1.0", "id": 10, "method": hover, "params": {}},
        {"id": 11, "method": "shutdown"},
        "{not json",
        "[" * 5000 + "]" * 5000,
        [1, 2],
        {"jsonrpc": "2.0", "id": 12, "result": None},
        _notify("$/cancelRequest", {"id": 99}),
        _notify("$/setTrace", {"value": "verbose"}),
        _request(13, "textDocument/semanticTokens/full", _doc("file:///fuzz/never.gait")),
        _request(14, "textDocument/rename", _doc(URI, {"line": 9, "character": 5},
                                                  newName="")),
        _request(15, "shutdown", None),
        _request(16, hover, _doc(URI, {"line": 0, "character": 0})),
        _notify("exit", None),
    ]


def _large() -> list[Any]:
    """A 1 MB document, edited at its end and asked about."""
    line = "# a comment line of a large file, with names: nw ne sw se L1 north\n"
    times = (1 << 20) // len(line) + 1
    big = {"$join": [PATROL, {"$repeat": line, "times": times}]}
    end = {"line": PATROL.count("\n") + times, "character": 0}
    return [
        *_start(), _open(URI, big),
        _request(2, "textDocument/hover", _doc(URI, _at(PATROL, "sw"))),
        _change(URI, 2, {"range": _range(end, end), "text": "guarantee always !sw | se\n"}),
        _request(3, "textDocument/semanticTokens/full", _doc(URI)),
        _request(4, "textDocument/completion", _doc(URI, end)),
        _change(URI, 3, {"text": big}),
        _request(5, "textDocument/documentSymbol", _doc(URI)),
        *_END,
    ]


def _typing() -> list[Any]:
    """The patrol typed a few characters at a time, with edits out of range."""
    out = [*_start(), _open(URI, "")]
    version, line, column = 1, 0, 0
    for start in range(0, len(PATROL), 23):
        piece = PATROL[start:start + 23]
        version += 1
        here = {"line": line, "character": column}
        out.append(_change(URI, version, {"range": _range(here, here), "text": piece}))
        line += piece.count("\n")
        column = len(piece) - piece.rfind("\n") - 1 if "\n" in piece else column + len(piece)
        if version % 5 == 0:
            out.append(_request(version, "textDocument/completion", _doc(URI, here)))
    far = {"line": 500, "character": 3}
    out += [
        _change(URI, version + 1, {"range": _range(far, far), "text": "start ne\n"}),
        _change(URI, version + 2, {"range": _range({"line": 4, "character": 9},
                                                   {"line": 2, "character": 0}), "text": ""}),
        _request("h", "textDocument/hover", _doc(URI, {"line": 4, "character": 2})),
        _open(URI, PATROL, version + 3),
        _request("s", "textDocument/semanticTokens/full", _doc(URI)),
        *_END,
    ]
    return out


EXCHANGES: tuple[tuple[str, bytes], ...] = (
    ("features.json", _session_bytes(_features())),
    ("repairs.json", _session_bytes(_repairs())),
    ("deep.json", _session_bytes(_deep())),
    ("odd_params.json", _session_bytes(_odd_params())),
    ("large.json", _session_bytes(_large())),
    ("typing.json", _session_bytes(_typing())),
    ("wire.txt", _wire_bytes([*_start(), _open(URI, PATROL),
                              _request(2, "textDocument/hover", _doc(URI, _at(PATROL, "se"))),
                              _request(3, "textDocument/completion",
                                       _doc(URI, {"line": 13, "character": 0})),
                              *_END])),
)


EXACT: set[bytes] = {data for _, data in EXCHANGES}  # sessions framed as they are (and MENDED's)


# ---------------------------------------------------------------------- bytes to frames
class _Budget:
    """How many bytes ``$repeat`` may still add to a session."""

    def __init__(self) -> None:
        self.left = MAX_EXPANDED


def _expand(item: Any, budget: _Budget) -> Any:
    """``item`` with each ``{"$repeat": text, "times": n}`` replaced by the text repeated
    and each ``{"$join": [...]}`` by its parts joined (within the budget)."""
    if isinstance(item, list):
        return [_expand(x, budget) for x in item]
    if not isinstance(item, dict):
        return item
    if isinstance(item.get("$repeat"), str) and isinstance(item.get("times"), int):
        text: str = item["$repeat"]
        times = max(0, min(item["times"], budget.left // max(len(text), 1)))
        budget.left -= times * len(text)
        return text * times
    if isinstance(item.get("$join"), list):
        return "".join(str(_expand(x, budget)) for x in item["$join"])
    return {k: _expand(v, budget) for k, v in item.items()}


def _latin(text: str) -> bytes:
    return text.encode("latin-1") if max(text, default=" ") <= "\xff" else text.encode(
        "utf-8", "surrogatepass")


def _encode(item: Any, raw_utf8: bool) -> bytes:
    if isinstance(item, str):
        return item.encode("utf-8", "surrogatepass")
    return json.dumps(item, ensure_ascii=not raw_utf8).encode("utf-8", "surrogatepass")


def _frame(item: Any, budget: _Budget, raw_utf8: bool) -> bytes:
    """One item of a session as the bytes written: a message (or any JSON) framed, a
    string as a body, ``{"$raw": s}`` as the bytes of ``s`` (latin-1), ``{"$body": b,
    "length": n}`` as ``b`` framed with a Content-Length of ``n``."""
    try:
        item = _expand(item, budget)
        if isinstance(item, dict) and isinstance(item.get("$raw"), str):
            return _latin(item["$raw"])
        if isinstance(item, dict) and "$body" in item and isinstance(item.get("length"), int):
            return b"Content-Length: %d\r\n\r\n" % item["length"] + _encode(item["$body"],
                                                                            raw_utf8)
        body = _encode(item, raw_utf8)
    except (RecursionError, ValueError, TypeError):
        body = json.dumps(str(item)[:1000]).encode()
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


def _items(data: bytes) -> list[Any | bytes]:
    """The items of a session: its JSON list; else the pieces of the list that its
    brackets delimit (:func:`_pieces`), each parsed if it is JSON, else split into its
    lines, each parsed if it is JSON, else kept as bytes: one frame body."""
    try:
        whole = json.loads(data)
    except (ValueError, RecursionError):
        pass
    else:
        return list(whole) if isinstance(whole, list) else [whole]
    items: list[Any | bytes] = []
    for piece in _pieces(data):
        try:
            items.append(json.loads(piece))
            continue
        except (ValueError, RecursionError):
            pass
        for part in piece.split(b"\n"):
            part = part.strip().rstrip(b",")
            if part in (b"", b"[", b"]"):
                continue
            try:
                items.append(json.loads(part))
            except (ValueError, RecursionError):
                items.append(part)
    return items


def _pieces(data: bytes) -> list[bytes]:
    """The top-level items of a JSON list that may be broken, as the brackets delimit
    them (outside strings; a string ends at its line's end, as in JSON it must): a seed
    one message a line and one re-indented by a mutation both split into messages."""
    pieces: list[bytes] = []
    current = bytearray()
    depth = 0 if data.lstrip()[:1] == b"[" else 1  # 1: between the items of the list
    for line in data.split(b"\n"):
        in_string = escaped = False
        for byte in line:
            char = bytes([byte])
            if in_string:
                escaped, in_string = (False, True) if escaped else (
                    char == b"\\", char != b'"')
            elif char == b'"':
                in_string = True
            elif char in b"[{":
                depth += 1
                if depth == 1:  # the list's own bracket
                    continue
            elif char in b"]}":
                depth = max(depth - 1, 0)
                if depth == 0:  # the list's end, or a bracket too many
                    pieces.append(bytes(current))
                    current.clear()
                    continue
            elif char == b"," and depth == 1:
                pieces.append(bytes(current))
                current.clear()
                continue
            current.append(byte)
        current += b"\n"
    pieces.append(bytes(current))
    return [p for p in pieces if p.strip()]


@dataclass(frozen=True)
class Wire:
    """What is written to the server: the bytes, and the offsets at which the client
    waits for every answer owed so far (``{"$wait": ...}`` items) before going on."""

    stream: bytes
    waits: tuple[int, ...] = ()


def frames_of(data: bytes) -> Wire:
    """What is written to the server for the mutant ``data`` (deterministic).

    Bytes starting with ``Content-Length`` are written as they are. Otherwise each item
    of the session is framed (:func:`_frame`; bytes that are not JSON as one body), and one
    mutant in five (chosen by the CRC of ``data``; never one of :data:`EXACT`) gets one
    frame's header
    changed: its length one more or one less, no length, lines ended by ``\\n`` alone, or
    a lower-case name with a ``Content-Type`` (which is still good framing)."""
    if data.lstrip()[:15].lower() == b"content-length:":
        return Wire(data)
    crc = zlib.crc32(data)
    budget = _Budget()
    out: list[bytes] = []
    waits: list[int] = []
    for item in _items(data):
        if isinstance(item, dict) and "$wait" in item:
            waits.append(len(out))
        elif isinstance(item, bytes):
            out.append(b"Content-Length: %d\r\n\r\n" % len(item) + item)
        else:
            out.append(_frame(item, budget, bool(crc & 32)))
    variant, where = crc % 25, (crc >> 8) % max(len(out), 1)
    if variant < 5 and out and data not in EXACT:
        head, _, body = out[where].partition(b"\r\n\r\n")
        length = int(head.split(b":")[1]) if head.startswith(b"Content-Length: ") else len(body)
        out[where] = [
            b"Content-Length: %d\r\n\r\n" % (length + 1),
            b"Content-Length: %d\r\n\r\n" % max(length - 1, 0),
            b"Content-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n",
            b"Content-Length: %d\n\n" % length,
            b"content-length:%d\r\nContent-Type: application/vscode-jsonrpc; "
            b"charset=utf-8\r\n\r\n" % length,
        ][variant] + body
    offsets = [0]
    for frame in out:
        offsets.append(offsets[-1] + len(frame))
    return Wire(b"".join(out), tuple(offsets[i] for i in waits))


# ---------------------------------------------------------------------- what the server reads
@dataclass(frozen=True)
class Sent:
    """One frame as a server following the LSP base protocol reads it: where it ends in
    the bytes written, its body, and whether the framing before it (and its own) was
    good, so that the server must have read exactly this body."""

    start: int
    end: int
    body: bytes
    in_step: bool


HEADER = re.compile(rb"([!#$%&'*+.^_`|~0-9A-Za-z-]+):[ \t]*(.*?)[ \t]*")


def read_frames(stream: bytes) -> Iterator[Sent]:
    """The frames of ``stream`` by the base protocol: header lines ``Name: value`` ended by
    CRLF, a blank line, a body of ``Content-Length`` bytes. After the first header block
    that breaks these rules every frame is out of step (the judge stops counting there)."""
    position, in_step = 0, True
    while True:
        start, end = position, stream.find(b"\r\n\r\n", position)
        if end < 0:
            return
        block = stream[position:end]
        fields = [HEADER.fullmatch(line) for line in block.split(b"\r\n")]
        lengths = [m.group(2) for m in fields if m and m.group(1).lower() == b"content-length"]
        good = (len(block) <= MAX_HEADERS and all(fields) and len(lengths) == 1
                and lengths[0].isdigit() and len(lengths[0]) < 10)
        if not good:
            in_step = False
            length = 0
            for value in lengths[:1]:
                length = int(value) if value.isdigit() and len(value) < 10 else 0
        else:
            length = int(lengths[0])
        body = stream[end + 4:end + 4 + length]
        position = end + 4 + length
        if len(body) < length:
            in_step = False
        yield Sent(start, min(position, len(stream)), body, in_step)


# ---------------------------------------------------------------------- running a session
@dataclass
class Request:
    """A request the server must answer once (``method`` a string, ``id`` one)."""

    id: int | str
    method: str
    after: int  # the frame's end in the bytes written


@dataclass
class LspRun:
    """One session: its verdict and what was sent and answered."""

    verdict: Verdict
    frames: int = 0
    requests: int = 0  # messages with a method and an id, judged or not
    judged: int = 0  # requests that must be answered (before exit, framing in step)
    answered: int = 0
    unanswered: int = 0
    messages: list[dict[str, Any]] = field(default_factory=list)
    times: list[float] = field(default_factory=list)  # seconds from the start to each
    stderr: str = ""


def _plan(stream: bytes) -> tuple[list[Sent], list[Request], tuple[int, int] | None,
                                 Counter[str]]:
    """The frames, the requests to judge, where a good ``exit`` starts and ends, and the
    ids of every request sent (JSON text), judged or not."""
    sent = list(read_frames(stream))
    judged: list[Request] = []
    exit_at: tuple[int, int] | None = None
    ids: Counter[str] = Counter()
    judging = True
    for frame in sent:
        try:
            message = json.loads(frame.body)
        except (ValueError, RecursionError):
            continue
        if not isinstance(message, dict) or "method" not in message:
            continue
        msg_id = message.get("id")
        if "id" in message:
            with contextlib.suppress(ValueError, RecursionError):  # "id": NaN, too deep
                ids[json.dumps(msg_id)] += 1
        method = message["method"]
        if not isinstance(method, str):
            continue
        judging = judging and frame.in_step
        if method == "exit":
            if judging and "id" not in message and message.get("params") is None \
                    and message.get("jsonrpc") == "2.0":
                exit_at = (frame.start, frame.end)
            judging = False  # after any exit, whether the server is still there is unsure
        elif judging and isinstance(msg_id, (int, str)) and not isinstance(msg_id, bool):
            judged.append(Request(msg_id, method, frame.end))
    return sent, judged, exit_at, ids


class Server:
    """A fresh ``gaitc lsp``: bytes written without blocking for ever, every message it
    writes kept; its requests (progress creation) answered with null."""

    def __init__(self, stderr: Any) -> None:
        env = {**os.environ, "PYTHONPATH": os.pathsep.join(
            p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)}
        ready, told = os.pipe()
        try:
            self.proc = subprocess.Popen([sys.executable, "-c", BOOT, str(told)],
                                         stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                         stderr=stderr, cwd=ROOT, env=env, pass_fds=(told,))
        finally:
            os.close(told)
        try:  # the server is up when it says so (or when it has died: the pipe's end)
            readable = select.select([ready], [], [], START_WAIT)[0]
            self.started = bool(readable) and os.read(ready, 1) == b"+"
        finally:
            os.close(ready)
        self.start_status = None if self.started else self.proc.poll()
        assert self.proc.stdin is not None
        self.fd = self.proc.stdin.fileno()
        os.set_blocking(self.fd, False)
        self.messages: list[dict[str, Any]] = []
        self.times: list[float] = []  # when each message arrived (time.monotonic())
        self.malformed: list[str] = []
        self.replies: queue.Queue[bytes] = queue.Queue()
        self.arrived = threading.Condition()
        self.closed = False  # the server's output has ended
        self.broken = False  # its input cannot be written any more
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        out = self.proc.stdout
        assert out is not None
        try:
            while True:
                length = None
                while True:
                    line = out.readline()
                    if not line:
                        return
                    if line == b"\r\n":
                        break
                    name, _, value = line.partition(b":")
                    if name.lower() == b"content-length":
                        length = int(value)
                if length is None:
                    self.malformed.append("a header block without Content-Length")
                    continue
                message = json.loads(out.read(length))
                if isinstance(message, dict) and "method" in message and "id" in message:
                    body = json.dumps({"jsonrpc": "2.0", "id": message["id"], "result": None})
                    self.replies.put(b"Content-Length: %d\r\n\r\n" % len(body) + body.encode())
                with self.arrived:
                    self.messages.append(message)
                    self.times.append(time.monotonic())
                    self.arrived.notify_all()
        except (ValueError, OSError) as err:
            self.malformed.append(f"{type(err).__name__}: {err}")
        finally:
            with self.arrived:
                self.closed = True
                self.arrived.notify_all()

    def write(self, data: bytes, deadline: float) -> bool:
        """Write ``data`` (and any replies due) by ``deadline``; False if it could not."""
        view = memoryview(data)
        while not self.broken:
            while not self.replies.empty() and not view:
                view = memoryview(self.replies.get())
            if not view:
                return True
            left = deadline - time.monotonic()
            if left <= 0:
                return False
            _, ready, _ = select.select([], [self.fd], [], min(left, 0.05))
            if ready:
                try:
                    view = view[os.write(self.fd, view):]
                except BlockingIOError:
                    continue
                except OSError:
                    self.broken = True
        return False

    def wait_for(self, done: Callable[[], bool], deadline: float) -> bool:
        """Wait until ``done()`` holds (True), the output ends or ``deadline`` passes,
        answering the server's requests meanwhile."""
        while True:
            with self.arrived:
                if done():
                    return True
                if self.closed or time.monotonic() >= deadline:
                    return False
                self.arrived.wait(0.05)
            if not self.replies.empty():
                self.write(b"", deadline)

    def close_input(self) -> None:
        stdin = self.proc.stdin
        with contextlib.suppress(OSError):  # nothing is buffered: all went by os.write
            if stdin is not None:
                stdin.close()

    def end(self, since: float, most: float) -> bool:
        """Whether the process ended at most :data:`EXIT_WAIT` seconds after ``since``
        (when it was told to end) or after the last message it wrote, whichever is
        later (it may be still answering what came before), and within ``most`` seconds
        in all; it is killed if not."""
        ended = True
        while self.proc.poll() is None:
            now = time.monotonic()
            with self.arrived:
                last = max([since, *self.times[-1:]])
            if now - last > EXIT_WAIT or now - since > most:
                self.proc.kill()
                ended = False
                break
            time.sleep(0.02)
        self.proc.wait()
        self._reader.join(5)
        if self.proc.stdout is not None:
            self.proc.stdout.close()
        return ended


def _answers(messages: list[dict[str, Any]]) -> Counter[Any]:
    return Counter(json.dumps(m.get("id")) for m in messages
                   if "method" not in m and ("result" in m or "error" in m))


def _before_exit(stream: bytes, exit_at: tuple[int, int] | None) -> int:
    """Where the client stops to wait for every answer owed before it lets the server
    end: before the good ``exit``, or before the header of the first ``"exit"`` in the
    bytes (which the server may read as one where the judge has lost the framing);
    requests after it are not judged."""
    found = stream.find(b'"exit"')
    if found < 0:
        return exit_at[0] if exit_at else len(stream)
    header = max(stream.lower().rfind(b"content-length", 0, found), 0)
    return min(header, exit_at[0]) if exit_at else header


def _all_answered(server: Server, owed: Counter[str]) -> Callable[[], bool]:
    return lambda: not owed - _answers(server.messages)


def session(data: bytes, limit: float = 10.0) -> LspRun:
    """Run the session of ``data`` on a fresh ``gaitc lsp`` and judge it."""
    wire = frames_of(data)
    stream = wire.stream
    sent, judged, exit_at, ids = _plan(stream)
    hold = _before_exit(stream, exit_at)
    judged = [r for r in judged if r.after <= hold]
    stops = sorted({*wire.waits, hold, len(stream)})
    exit_sent: float | None = None
    died = False  # the server's output ended while answers were owed, before exit
    cutoff = len(stream)  # past the limit at this stop: requests after it are not judged
    with tempfile.TemporaryFile() as err:
        server = Server(err)
        start = time.monotonic()
        deadline = start + limit
        written = 0
        for stop in stops:  # the client waits for every answer owed at each $wait, before
            late = cutoff < len(stream)  # exit and at the input's end (until the limit)
            server.write(stream[written:stop], time.monotonic() + EXIT_WAIT if late
                         else deadline)
            written = stop
            owed = Counter(json.dumps(r.id) for r in judged if r.after <= stop)
            if not late and not server.wait_for(_all_answered(server, owed), deadline):
                if not server.closed:
                    cutoff = stop
                elif exit_sent is None:
                    died = True
            if stop == hold < len(stream):
                exit_sent = time.monotonic()
        server.close_input()
        ended = server.end(time.monotonic(), limit + EXIT_WAIT)
        seconds = time.monotonic() - start
        code = server.proc.returncode
        err.seek(0)
        stderr = err.read().decode("utf-8", "replace")
    messages = list(server.messages)
    times = [t - start for t in server.times[:len(messages)]]
    judged = [r for r in judged if r.after <= cutoff]
    expected = Counter(json.dumps(r.id) for r in judged)
    answered = _answers(messages)
    first: dict[str, float] = {}
    for when, message in zip(times, messages, strict=True):
        if "method" not in message and ("result" in message or "error" in message):
            first.setdefault(json.dumps(message.get("id")), when)
    missing = expected - answered
    problems: list[str] = []
    for key, count in answered.items():
        if key in expected and count > ids[key]:
            problems.append(f"internal: {count} answers to request {key}, sent {ids[key]} "
                            "times")
    for request in judged:
        key = json.dumps(request.id)
        if missing[key] > 0:
            missing[key] -= 1
            problems.append(
                f"internal: request {key} ({request.method}) was not answered: the server "
                f"ended (status {code})" if died else
                f"past limit: request {key} ({request.method}) was not answered within "
                f"{limit:g} s")
        elif first.get(key, 0.0) > limit:
            problems.append(f"past limit: request {key} ({request.method}) was answered "
                            f"after {first[key]:.1f} s, the limit is {limit:g} s")
    problems += _message_problems(messages)
    problems += [f"internal: the server wrote {m}" for m in server.malformed]
    problems += log_problems(stderr)
    if not server.started:
        problems.append(f"past limit: the server did not start within {START_WAIT:g} s"
                        if server.start_status is None else
                        f"internal: the server ended as it started (status "
                        f"{server.start_status})")
    if not ended:
        problems.append(f"past limit: the server was still running {EXIT_WAIT:g} s after "
                        f"{'exit' if exit_at is not None else 'its input closed'} and "
                        "its last message")
    elif code not in (0, 1):
        problems.append(f"internal: the server ended with exit status {code}")
    if seconds > limit + EXIT_WAIT:
        problems.append(f"past limit: {seconds:.1f} s, the limit is {limit:g} s")
    unanswered = sum((expected - answered).values())
    return LspRun(Verdict("lsp", code if code is not None else -1, seconds, problems),
                  frames=len(sent), requests=sum(ids.values()), judged=len(judged),
                  answered=len(judged) - unanswered, unanswered=unanswered,
                  messages=messages, times=times, stderr=stderr)


def _message_problems(messages: list[dict[str, Any]]) -> list[str]:
    """What the server said that shows an error inside it: an InternalError answer, a
    message or diagnostic naming an internal error, pygls's "Error in server"."""
    problems = []
    for message in messages:
        error = message.get("error")
        if isinstance(error, dict) and (error.get("code") == -32603
                                        or "internal error" in str(error.get("message"))):
            problems.append(f"internal: answer {message.get('id')!r}: {error}"[:400])
        params = message.get("params")
        method = message.get("method")
        if method == "window/showMessage" and isinstance(params, dict) and (
                params.get("type") == 1 or "internal error" in str(params.get("message"))):
            problems.append(f"internal: the server showed {params.get('message')!r}"[:400])
        if method == "textDocument/publishDiagnostics" and isinstance(params, dict):
            for diagnostic in params.get("diagnostics") or []:
                if "internal error" in str(diagnostic.get("message")):
                    problems.append(f"internal: diagnostic {diagnostic['message']!r}"[:400])
    return problems


# pygls logs each message it cannot decode with its traceback, and each error answer it
# sends (a JSON-RPC error raised by a feature: RequestFailed, a cancelled request);
# neither is a fault of the server.
NOISE = ("Unable to deserialize message", "Exception occurred for message",
         "Failed to handle request")
EXPECTED_ERRORS = re.compile(
    r"^(?:[\w.]+\.)?(?:JsonRpc(?!InternalError)\w+|RequestFailed)\b")
RECORD = re.compile(r"^@@log (\S+) (\S+)\n(.*?)\n@@end$", re.S | re.M)


def log_problems(stderr: str) -> list[str]:
    """Every traceback on the server's standard error but pygls's decode noise, every
    internal error and every text that is not a log record."""
    problems = []
    for record in RECORD.finditer(stderr):
        name, text = record.group(1), record.group(3)
        if "Traceback" not in text and "internal error" not in text:
            continue
        head = text.split("\n", 1)[0]
        last = [line for line in text.split("\n") if re.match(r"^[A-Za-z_][\w.]*(:|$)", line)]
        noise = name.startswith("pygls") and head.startswith(NOISE) and (
            head.startswith(NOISE[0]) or bool(last and EXPECTED_ERRORS.match(last[-1])))
        if not noise:
            problems.append(f"internal: logged by {name}: {head[:120]} ... "
                            f"{last[-1][:200] if last else ''}")
    rest = RECORD.sub("", stderr).strip()
    if rest:
        lines = rest.splitlines()
        last = [line for line in lines if re.match(r"^[A-Za-z_][\w.]*(:|$)", line)]
        problems.append(f"internal: the server printed {lines[0][:120]!r}"
                        + (f" ... {last[-1][:200]!r}" if last and last[-1] != lines[0] else ""))
    return problems


def exchange(data: bytes, limit: float = 10.0) -> Verdict:
    """Run the session of ``data`` on a fresh ``gaitc lsp``: every request answered once,
    no traceback but pygls's decode noise, no internal error, an end at ``exit``."""
    return session(data, limit).verdict


# ---------------------------------------------------------------------- faults found
@dataclass(frozen=True)
class Known:
    """A fault of the server that this fuzzer found and that is not mended yet: the
    problems it shows (``signature``, and ``follows``: what it brings with it, a problem
    only where the signature is there too) and a session that shows it."""

    name: str
    what: str
    signature: str
    session: bytes
    follows: tuple[str, ...] = ()
    always: bool = True  # False: a race, which its session shows only now and then

    def explains(self, problems: list[str]) -> list[str]:
        """Which of ``problems`` this fault explains."""
        if not any(re.search(self.signature, p) for p in problems):
            return []
        return [p for p in problems if re.search(self.signature, p)
                or any(re.search(f, p) for f in self.follows)]


_CONTENT_LENGTH = _wire_bytes(_start()) + b"Content-Length: %s\r\n\r\n{}" % (b"1" * 5000)
#: The faults this fuzzer found that are mended (issue 48's follow-up): each session is now
#: a regression test, which must show no problem at all (tests/robustness/test_fuzz_lsp_player.py).
MENDED: tuple[Known, ...] = (
    Known("change-unopened",
          "didChange of a document that is not open: pygls's workspace raises KeyError and "
          "the server shows the user \"Error in server: KeyError: '<uri>'\"",
          r"^internal: the server showed .Error in server: KeyError: ",
          _session_bytes([*_start(), _change(URI, 2, {"text": PATROL}), *_END])),
    Known("before-initialize",
          "a notification that needs the workspace (didOpen, didChange, didClose) before "
          "initialize: the server shows \"Error in server: RuntimeError: The workspace is "
          "not available - has the server been initialized?\" (LSP: drop it)",
          r"^internal: the server showed .Error in server: RuntimeError: The workspace is "
          r"not available",
          _session_bytes([_open(URI, PATROL), *_start(), *_END])),
    Known("shutdown-during-command",
          "shutdown while a workspace/executeCommand request is pending: pygls's "
          "lsp_shutdown cancels the pending futures while iterating over them, a "
          "concurrent Future runs its callback (which pops the dict) at once, so shutdown "
          "is answered with InternalError 'dictionary changed size during iteration', the "
          "server is not shut down and exit ends it with status 1",
          r"dictionary changed size during iteration",
          _session_bytes([*_start(), _open(OTHER, UNREALIZABLE),
                          _request(2, "workspace/executeCommand", {
                              "command": "gaitc.findRepairs", "arguments": [OTHER]}),
                          *_END[1:]])),
    Known("content-length-digits",
          "a Content-Length of more than 4,300 digits: int() raises ValueError in "
          "gaitc.lsp.transport._content_length, the reader thread dies with a traceback and "
          "the server never ends, not even when its input closes",
          r"Exceeds the limit \(4300 digits\) for integer string conversion",
          _CONTENT_LENGTH, follows=(r"^past limit: the server was still running",)),
    Known("method-not-a-string",
          "a request whose method is not a string (\"method\": 5): GaitProtocol passes it "
          "on, pygls's _get_handler builds 'Method Not Found: ' + 5 and raises TypeError, "
          "and the answer is InternalError -32603 with a traceback in its data (JSON-RPC: "
          "InvalidRequest -32600); a notification so (no id) shows the user \"Error in "
          "server: can only concatenate str (not \"int\") to str\"",
          r"^internal: .*can only concatenate str \(not \"\w+\"\) to str",
          _session_bytes([*_start(), {"jsonrpc": "2.0", "id": 2, "method": 5, "params": {}},
                          *_END])),
    Known("id-not-int-or-string",
          "a request whose id is a list or an object (\"id\": [1]): pygls keys its futures "
          "by the id, raises TypeError (unhashable type) and answers InternalError -32603 "
          "with a traceback in its data (LSP: an id is an integer or a string; JSON-RPC: "
          "InvalidRequest)",
          r"^internal: .*TypeError: unhashable type",
          _session_bytes([*_start(), {"jsonrpc": "2.0", "id": [1], "method": "shutdown"},
                          *_END])),
    Known("fork-during-import",
          "the repair command forks its child (gaitc.lsp.jobs.ChildJob, "
          "gaitc.diagnostics.processes.first_success) while another thread of the server "
          "(the warm-up of 'initialized', an analysis) holds an import lock; the child "
          "deadlocks in importlib at 'from ltlcompiler.frontend import model_from_text' "
          "(gaitc/api/loading.py, _build) and the request is answered only when the search "
          "times out (125 s) or is cancelled. Shows now and then, more often on a busy "
          "machine: open a spec and ask for repairs at once after initialized",
          r"^past limit: request \S+ \(workspace/executeCommand\)",
          _session_bytes([*_start({"window": {"workDoneProgress": True}}),
                          _open(OTHER, UNREALIZABLE.replace("cache ne", "cache ne,")),
                          *(_request(n, "workspace/executeCommand", {
                              "command": "gaitc.findRepairs", "arguments": [OTHER]})
                            for n in (2, 3, 4)), *_END]),
          follows=(r"^past limit: request \S+ \(shutdown\)",), always=False),
    Known("orphan-command-task",
          "$/cancelRequest of a workspace/executeCommand that has not started answers "
          "RequestCancelled at once (pygls cancels its own future), but gaitc's handler "
          "still runs: the repair search starts, shows its progress and message; when its "
          "progress is then cancelled (window/workDoneProgress/cancel), the handler's task "
          "raises JsonRpcRequestCancelled that nobody retrieves, and asyncio logs \"Task "
          "exception was never retrieved\" (or, at exit, \"unhandled exception during "
          "asyncio.run() shutdown\") with the traceback; shutdown cancelling a pending "
          "command does the same. Shows now and then",
          r"^internal: logged by asyncio: (Task exception was never retrieved|unhandled "
          r"exception during asyncio.run\(\) shutdown) .*JsonRpcRequestCancelled",
          _session_bytes([*_start({"window": {"workDoneProgress": True}}),
                          _open(OTHER, UNREALIZABLE),
                          _request(6, "workspace/executeCommand", {
                              "command": "gaitc.findRepairs", "arguments": [OTHER],
                              "workDoneToken": "t"}),
                          _notify("$/cancelRequest", {"id": 6}),
                          _request(9, "textDocument/hover",
                                   _doc(OTHER, _at(UNREALIZABLE, "L1", 1))), WAIT,
                          _notify("window/workDoneProgress/cancel", {"token": "t"}), *_END]),
          always=False),
)
#: The faults found and not mended yet (none at present): a mutant's problem that one of
#: them explains is not counted against the server.
KNOWN: tuple[Known, ...] = ()


EXACT.update(known.session for known in (*MENDED, *KNOWN))


def unknown_problems(verdict: Verdict) -> list[str]:
    """The problems of ``verdict`` that no fault of :data:`KNOWN` explains."""
    explained = {p for known in KNOWN for p in known.explains(verdict.problems)}
    return [p for p in verdict.problems if p not in explained]
