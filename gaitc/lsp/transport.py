"""The server's channel: JSON-RPC over standard input and output, and what ends it.

pygls reads standard input in a worker of its thread pool and, on a signal, waits for that
worker, that is for the client to close the input; a request whose params do not fit the
protocol (a position of -1, ``"params": null``) it only logs, so the client waits for ever.
Here a daemon thread reads and decodes the messages (a few at a time, so a flood of large
edits waits in the pipe, not in memory) and hands them to the request loop;
:class:`GaitProtocol` answers every request it cannot handle with a JSON-RPC error
(ParseError, InvalidRequest, InvalidParams), drops the notifications that come before
``initialize`` or name a document that is not open, as the LSP says, and cancels what is
pending at ``shutdown`` without tripping over pygls's own bookkeeping; and SIGTERM or SIGINT
ends the loop at once, then is delivered again to the handler it found, which for ``gaitc
lsp`` turns it into exit 143 or 130.
"""

from __future__ import annotations

import asyncio
import contextlib
import contextvars
import json
import logging
import os
import signal
import threading
from collections.abc import Callable, Generator, Iterator
from dataclasses import dataclass
from pathlib import Path
from types import FrameType
from typing import Any, cast
from urllib.parse import unquote

from lsprotocol import types
from pygls.exceptions import (
    JsonRpcInvalidParams,
    JsonRpcInvalidRequest,
    JsonRpcParseError,
)
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol, lsp_method
from pygls.protocol.json_rpc import JsonRPCResponseMessage, RPCRequest

logger = logging.getLogger(__name__)

MsgId = int | str
IN_FLIGHT = 4  # messages decoded but not yet handled, at most
_HEADERS_LIMIT = 1 << 16  # bytes of headers before a blank line, at most
_READ = 1 << 20  # bytes read at a time, at most
_LENGTH_DIGITS = 18  # digits of a Content-Length, at most (10**18 bytes: no real message)
#: Notifications about a document, which pygls's workspace must know (LSP: "the server
#: should drop notifications before initialize"; a change of a closed document is stale).
_DOCUMENT_NOTIFICATIONS = (types.TEXT_DOCUMENT_DID_OPEN, types.TEXT_DOCUMENT_DID_CHANGE,
                           types.TEXT_DOCUMENT_DID_CLOSE)

#: The work-done token of the request being handled (the client's progress bar), if any.
_TOKEN: contextvars.ContextVar[types.ProgressToken | None] = contextvars.ContextVar(
    "gaitc_lsp_work_done_token", default=None)


def work_done_token() -> types.ProgressToken | None:
    """The ``workDoneToken`` the client gave with the request being handled."""
    return _TOKEN.get()


@dataclass(frozen=True)
class Refused:
    """A message that is answered with an error without being handled (``id`` None: the
    id could not be read); a notification (``answer`` False) is only logged."""

    id: MsgId | None
    code: int
    message: str
    answer: bool = True


class GaitProtocol(LanguageServerProtocol):
    """pygls's protocol, answering what it would drop: params that do not fit the method,
    messages that are not JSON-RPC 2.0 requests, requests after ``shutdown``; and telling
    :attr:`on_cancel` of each ``$/cancelRequest`` before pygls cancels what it can."""

    def __init__(self, server: LanguageServer, converter: Any) -> None:
        super().__init__(server, converter)
        self.on_cancel: Callable[[MsgId], None] = lambda msg_id: None

    def structure_message(self, data: dict[str, Any]) -> Any:
        if "jsonrpc" in data and data["jsonrpc"] != self.VERSION:
            request = "id" in data and "method" in data
            return Refused(_message_id(data) if request else None, JsonRpcInvalidRequest.CODE,
                           f"not a JSON-RPC 2.0 message: \"jsonrpc\" is {data['jsonrpc']!r}",
                           answer=request)
        if "jsonrpc" in data:
            refused = _malformed(data)
            if refused is not None:
                return refused
        try:
            return super().structure_message(data)
        except Exception as err:
            method = data.get("method")
            if isinstance(method, str):
                msg_id = _message_id(data)
                reason = "; ".join(_reasons(err.__cause__ or err)) or str(err)
                return Refused(msg_id, JsonRpcInvalidParams.CODE,
                               f"invalid params of {method}: {reason}", answer="id" in data)
            # a response of the client that does not fit: passed on as it is
            return JsonRPCResponseMessage(id=cast(MsgId, data.get("id")),
                                          jsonrpc=str(data.get("jsonrpc")),
                                          result=data.get("result"))

    def handle_message(self, message: Any) -> None:
        refused = message if isinstance(message, Refused) else self._refusal(message)
        if refused is not None:
            if refused.answer and refused.id is not None:
                self._send_response(refused.id, error=types.ResponseError(
                    code=refused.code, message=refused.message))
            elif refused.answer:  # with "id": null, which pygls's converter would leave out
                self._send_data({"jsonrpc": self.VERSION, "id": None, "error": {
                    "code": refused.code, "message": refused.message}})
            else:
                logger.warning("ignored a notification: %s", refused.message)
            return
        method = getattr(message, "method", None)
        if method in _DOCUMENT_NOTIFICATIONS and not isinstance(message, RPCRequest):
            uri = getattr(getattr(getattr(message, "params", None), "text_document", None),
                          "uri", None)
            dropped = self._not_for_workspace(method, uri)
            if dropped:
                logger.warning("ignored %s of %s: %s", method, uri, dropped)
                return
        if method == types.CANCEL_REQUEST:
            with contextlib.suppress(AttributeError):
                self.on_cancel(message.params.id)
        token = _TOKEN.set(getattr(getattr(message, "params", None), "work_done_token", None)
                           if isinstance(message, RPCRequest) else None)
        try:
            super().handle_message(message)
        finally:
            _TOKEN.reset(token)

    def _not_for_workspace(self, method: str, uri: object) -> str:
        """Why a notification about document ``uri`` is dropped ("" to handle it): before
        ``initialize`` there is no workspace; a change of a document not open has nothing
        to apply to."""
        workspace = self._workspace  # pygls's property raises before initialize
        if workspace is None:
            return "the server has not been initialized"
        if method == types.TEXT_DOCUMENT_DID_CHANGE and (
                not isinstance(uri, str) or unquote(uri) not in workspace.text_documents):
            return "the document is not open"
        return ""

    @lsp_method(types.SHUTDOWN)
    def lsp_shutdown(self, *args: Any) -> Generator[Any, Any, None]:
        """pygls's shutdown, cancelling the pending requests from a copy of its table: a
        cancelled request's callback removes it from the table at once."""
        if (user_handler := self.fm.features.get(types.SHUTDOWN)) is not None:
            yield user_handler, args, None
        current_id = self.msg_id
        for msg_id, future in list(self._request_futures.items()):
            if msg_id != current_id and not future.done():
                future.cancel()
        self._shutdown = True
        return None

    def _refusal(self, message: Any) -> Refused | None:
        """Why ``message`` is refused, or None to handle it."""
        if isinstance(message, dict):  # JSON without "jsonrpc"
            request = "id" in message
            return Refused(_message_id(message), JsonRpcInvalidRequest.CODE,
                           "not a JSON-RPC 2.0 message: \"jsonrpc\": \"2.0\" is missing",
                           answer=request or "method" not in message)
        if not hasattr(message, "jsonrpc"):  # a JSON array, string, number...
            return Refused(None, JsonRpcInvalidRequest.CODE,
                           "not a JSON-RPC 2.0 message: a message is a JSON object")
        if isinstance(message, RPCRequest) and self._shutdown and message.method != types.EXIT:
            return Refused(message.id, JsonRpcInvalidRequest.CODE,
                           f"{message.method}: the server has been shut down; only 'exit' "
                           "is accepted now")
        return None

    def refuse_unreadable(self, err: Exception) -> None:
        """Answer input that is not JSON (id null, as JSON-RPC says)."""
        self.handle_message(Refused(None, JsonRpcParseError.CODE,
                                    f"the message is not JSON: {type(err).__name__}: {err}"))


def _malformed(data: dict[str, Any]) -> Refused | None:
    """A JSON-RPC 2.0 message whose method or id cannot be what the protocol says: a
    method that is not a string, an id that is neither an integer nor a string (JSON-RPC:
    InvalidRequest, with id null when the id is unusable). A notification, or a response
    of the client, so malformed is only logged."""
    method = data.get("method")
    if "method" in data and not isinstance(method, str):
        return Refused(_message_id(data), JsonRpcInvalidRequest.CODE,
                       f"invalid request: \"method\" is {_kind(method)}, not a string",
                       answer="id" in data)
    if data.get("id") is not None and _message_id(data) is None:
        what = "request" if "method" in data else "response"
        return Refused(None, JsonRpcInvalidRequest.CODE,
                       f"invalid {what}: \"id\" is {_kind(data['id'])}, not an integer or a "
                       "string", answer="method" in data)
    return None


def _kind(value: object) -> str:
    """What a JSON value is, in a few words (for an error message)."""
    names = {bool: "a Boolean", int: "a number", float: "a number", str: "a string",
             list: "a list", dict: "an object", type(None): "null"}
    return names.get(type(value), type(value).__name__)


def _message_id(data: dict[str, Any]) -> MsgId | None:
    msg_id = data.get("id")
    return msg_id if isinstance(msg_id, (int, str)) and not isinstance(msg_id, bool) else None


def _reasons(err: BaseException, path: str = "", expected: str = "") -> Iterator[str]:
    """Each failure of structuring a message, with the place in it (``params.position``)
    and the protocol type expected there, from cattrs's exception groups, whose notes name
    the field of each sub-exception."""
    group = getattr(err, "exceptions", None)  # an ExceptionGroup (the backport's too)
    if isinstance(group, tuple):
        for sub in group:
            notes = [note for note in getattr(sub, "__notes__", ())
                     if isinstance(getattr(note, "name", None), str)]
            name = _camel(notes[0].name) if notes else ""
            kind = getattr(notes[0].type, "__name__", "") if notes else ""
            if isinstance(sub, KeyError):
                yield f"{_at(path)}{name or sub} is missing"
            else:
                yield from _reasons(sub, f"{path}.{name}" if path and name else path or name,
                                    kind)
    elif isinstance(err, ValueError):
        yield f"{_at(path)}{err}"
    else:
        what = f"a valid {expected}" if expected else "valid"
        yield f"{_at(path)}not {what} ({type(err).__name__}: {err})"


def _at(path: str) -> str:
    return f"{path}: " if path else ""


def _camel(name: str) -> str:
    """The protocol's name of a field (``text_document`` is ``textDocument``)."""
    head, *rest = name.split("_")
    return head + "".join(word.title() for word in rest)


class Channel:
    """The protocol's output: whole messages written to a file descriptor, one at a time
    (whatever thread writes); once the client has gone, writes are dropped."""

    def __init__(self, fd: int, on_lost: Callable[[], None]) -> None:
        self._fd = fd
        self._on_lost = on_lost
        self._lock = threading.Lock()
        self.closed = False

    def write(self, data: bytes) -> None:
        with self._lock:
            if self.closed:
                return
            view = memoryview(data)
            try:
                while view:
                    view = view[os.write(self._fd, view):]
            except OSError:
                self.closed = True
                self._on_lost()

    def close(self) -> None:
        self.closed = True


def widen_pipe(fd: int) -> None:
    """Let a pipe at ``fd`` hold as much as the system allows an unprivileged process (1 MB
    on Linux, against 64 kB): a 10 MB edit then takes 10 reads, not 160, and each read
    waits for the interpreter lock behind an analysis. Anything else is left as it is."""
    try:
        import fcntl

        limit = int(Path("/proc/sys/fs/pipe-max-size").read_text())
        fcntl.fcntl(fd, fcntl.F_SETPIPE_SZ, min(limit, _READ))
    except (ImportError, AttributeError, OSError, ValueError):
        pass  # not Linux, or not a pipe


def frames(fd: int) -> Iterator[bytes]:
    """The bodies of the ``Content-Length`` framed messages read from ``fd``, until the
    end of the input. A header block without a length is skipped."""
    buffer = bytearray()
    while True:
        end = buffer.find(b"\r\n\r\n")
        while end < 0:
            if len(buffer) > _HEADERS_LIMIT:  # no header block ends: not LSP framing
                del buffer[:-3]
            chunk = os.read(fd, _READ)
            if not chunk:
                return
            buffer += chunk
            end = buffer.find(b"\r\n\r\n")
        length = _content_length(bytes(buffer[:end]))
        del buffer[:end + 4]
        if length is None:
            continue
        while len(buffer) < length:
            chunk = os.read(fd, min(_READ, max(length - len(buffer), 1 << 16)))
            if not chunk:
                return
            buffer += chunk
        body = bytes(buffer[:length])
        del buffer[:length]
        yield body


def _content_length(headers: bytes) -> int | None:
    """The Content-Length of a header block; None without one, or with one of more digits
    than any message has (which ``int`` would refuse past 4,300 digits): the block is then
    skipped like a block without a length."""
    for line in headers.split(b"\r\n"):
        name, _, value = line.partition(b":")
        digits = value.strip()
        if name.strip().lower() == b"content-length" and digits.isdigit():
            if len(digits.lstrip(b"0")) > _LENGTH_DIGITS:
                logger.warning("ignored a header block: a Content-Length of %d digits",
                               len(digits))
                return None
            return int(digits)
    return None


@dataclass
class Ending:
    """How serving ended: a signal to deliver again, or the exit code of ``exit``."""

    signal: int | None = None
    exit_code: int | None = None


def run(server: LanguageServer, stdin: int, stdout: int, stop: Callable[[], None]) -> None:
    """Serve ``server`` on the file descriptors ``stdin`` and ``stdout`` until the client
    says ``exit`` (SystemExit with its code), closes the input (return), or SIGTERM or
    SIGINT arrives (the signal is delivered again once serving has ended, to the handler
    that was there before). ``stop`` is called on the loop as serving ends."""
    ending = Ending()
    asyncio.run(_serve(server, stdin, stdout, stop, ending))
    if ending.signal is not None:
        signal.raise_signal(ending.signal)
    if ending.exit_code is not None:
        raise SystemExit(ending.exit_code)


async def _serve(server: LanguageServer, stdin: int, stdout: int, stop: Callable[[], None],
                 ending: Ending) -> None:
    loop = asyncio.get_running_loop()
    done: asyncio.Future[None] = loop.create_future()
    protocol = server.protocol
    assert isinstance(protocol, GaitProtocol)

    def end() -> None:
        if not done.done():
            done.set_result(None)

    def hand(callback: Callable[..., None], *args: Any) -> None:
        with contextlib.suppress(RuntimeError):  # the loop has closed
            loop.call_soon_threadsafe(callback, *args)

    def on_signal(signum: int, frame: FrameType | None) -> None:
        del frame
        if ending.signal is None:
            ending.signal = signum
        hand(end)

    slots = threading.Semaphore(IN_FLIGHT)

    def deliver(message: Any, error: Exception | None) -> None:
        try:
            if error is not None:
                protocol.refuse_unreadable(error)
            else:
                protocol.handle_message(message)
        except SystemExit as exit_:  # pygls's answer to the client's "exit"
            ending.exit_code = exit_.code if isinstance(exit_.code, int) else 0
            end()
        except Exception:
            logger.exception("a message could not be handled")
        finally:
            slots.release()

    def read() -> None:
        try:
            for body in frames(stdin):
                slots.acquire()
                try:
                    message, error = json.loads(body, object_hook=protocol.structure_message), None
                except Exception as err:  # not JSON, or nested too deep to decode
                    message, error = None, err
                hand(deliver, message, error)
        except OSError:
            pass
        hand(end)

    widen_pipe(stdin)
    protocol.set_writer(Channel(stdout, lambda: hand(end)))
    previous = {}
    in_main = threading.current_thread() is threading.main_thread()  # where signals go
    for signum in (signal.SIGTERM, signal.SIGINT) if in_main else ():
        if signal.getsignal(signum) not in (signal.SIG_IGN, None):
            previous[signum] = signal.signal(signum, on_signal)
    try:
        threading.Thread(target=read, name="gaitc-lsp-reader", daemon=True).start()
        await done
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
        stop()
