"""``gaitc lsp``: the Language Server Protocol server for ``.gait`` files, on pygls.

Each open document is analysed (:mod:`gaitc.lsp.analysis`) a short debounce after its last
edit, in a worker thread, one analysis at a time and only of its latest text
(:mod:`gaitc.lsp.scheduling`): typing never waits for the compiler, a burst of edits
costs one analysis more, and a superseded result is dropped. Diagnostics come in two
steps: the compiler's at once, then the valve primitives' (a gait search) when they are
ready. The features are thin views of the index and the model: hover
(:mod:`gaitc.lsp.hover`), definition and references, completion
(:mod:`gaitc.lsp.completion`), rename, code actions and the repair command
(:mod:`gaitc.lsp.actions`; it runs in a child process, :mod:`gaitc.lsp.jobs`, with
progress, and can be cancelled), semantic tokens and the outline. Requests wait for an
analysis without holding up the loop. :mod:`gaitc.lsp.transport` carries the messages,
answers with an error every request it cannot handle, and ends on SIGTERM and SIGINT.
"""

from __future__ import annotations

import asyncio
import threading
import uuid
from collections import deque
from collections.abc import Callable
from typing import Any

from lsprotocol import types
from pygls.exceptions import JsonRpcException, JsonRpcRequestCancelled
from pygls.lsp.server import LanguageServer

from gaitc.lsp.actions import (
    Fix,
    RepairEdit,
    find_repairs,
    preload_repairs,
    quick_fixes,
    suggestion,
)
from gaitc.lsp.analysis import Finding, analyse
from gaitc.lsp.completion import offers
from gaitc.lsp.hover import describe
from gaitc.lsp.index import Kind, Mention, Symbol
from gaitc.lsp.jobs import ChildJob, Outcome
from gaitc.lsp.positions import Lines
from gaitc.lsp.scheduling import Document, Scheduler
from gaitc.lsp.transport import GaitProtocol, MsgId, work_done_token

NAME = "gaitc"
REPAIR_TIMEOUT = 120.0  # seconds the repair command may solve for
REPAIR_GRACE = 5.0  # seconds more before its child is killed (explain keeps its timeout)
REPAIR_COMMAND = "gaitc.findRepairs"
PROGRESS_CREATE_WAIT = 5.0  # seconds to wait for the client to accept a progress token
CANCELS_KEPT = 256  # ids of $/cancelRequest remembered for commands not yet started

#: Semantic token types, in the legend's order, and the kind of name each colours.
TOKEN_TYPES = ("variable", "function", "enumMember", "event")
TOKEN_OF = {Kind.LEG: 0, Kind.GAIT: 1, Kind.REGION: 2, Kind.HAZARD: 3}
TOKEN_MODIFIERS = ("declaration",)
SYMBOL_KIND = {Kind.LEG: types.SymbolKind.Variable, Kind.GAIT: types.SymbolKind.Function,
               Kind.REGION: types.SymbolKind.EnumMember, Kind.HAZARD: types.SymbolKind.Event}
COMPLETION_KIND = {"keyword": types.CompletionItemKind.Keyword,
                   "value": types.CompletionItemKind.Value,
                   Kind.LEG.value: types.CompletionItemKind.Variable,
                   Kind.GAIT.value: types.CompletionItemKind.Function,
                   Kind.REGION.value: types.CompletionItemKind.EnumMember,
                   Kind.HAZARD.value: types.CompletionItemKind.Event}


class RequestFailed(JsonRpcException):
    """A request the server understood but cannot do (LSP's RequestFailed), with a message
    the editor shows the user."""

    CODE = -32803


class GaitServer(LanguageServer):
    """The server: the open documents and their analyses, and the commands running."""

    def __init__(self) -> None:
        from gaitc import __version__

        super().__init__(NAME, __version__, protocol_cls=GaitProtocol)
        self.scheduler = Scheduler(self._publish, self.trace)
        self.jobs: dict[MsgId, ChildJob] = {}  # the commands running, by request id
        #: The latest ids the client cancelled: a command among them never starts its work.
        self.cancelled: deque[MsgId] = deque(maxlen=CANCELS_KEPT)
        self.stopped = False  # serving has ended, or the client has said shutdown
        protocol = self.protocol
        assert isinstance(protocol, GaitProtocol)
        protocol.on_cancel = self.request_cancelled

    @property
    def documents(self) -> dict[str, Document]:
        return self.scheduler.documents

    def trace(self, message: str) -> None:
        """Tell a client that asked for a trace (``$/setTrace``, ``trace`` of
        ``initialize``) what the server does: each analysis started, dropped, published."""
        if self.protocol.trace not in (None, types.TraceValue.Off):
            self.log_trace(types.LogTraceParams(message=message))

    def request_cancelled(self, msg_id: MsgId) -> None:
        """``$/cancelRequest``: a command running for request ``msg_id`` is killed, one
        not started yet will not start (pygls has answered it RequestCancelled)."""
        self.cancelled.append(msg_id)
        job = self.jobs.get(msg_id)
        if job is not None:
            job.cancel()

    def abandoned(self, msg_id: MsgId | None) -> bool:
        """Whether the request ``msg_id`` has been answered already by cancelling it (by
        the client, or by ``shutdown``): its work is not to start, nor its end to raise."""
        return self.stopped or (msg_id is not None and msg_id in self.cancelled)

    def stop(self) -> None:
        """Serving ends: no analysis is started or published any more, commands are
        killed."""
        self.stopped = True
        self.scheduler.stop()
        for job in list(self.jobs.values()):
            job.cancel()

    # ------------------------------------------------------------------ diagnostics
    def _publish(self, doc: Document, findings: list[Finding]) -> None:
        diagnostics = [self._diagnostic(doc, f) for f in findings]
        self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
            uri=doc.uri, diagnostics=diagnostics, version=doc.version))

    @staticmethod
    def _diagnostic(doc: Document, finding: Finding) -> types.Diagnostic:
        span = finding.span
        elsewhere = span is not None and span.file not in (doc.path, "<string>")
        message = finding.message if not elsewhere else f"{span}: {finding.message}"
        if finding.hint:
            message += f"\nhint: {finding.hint}"
        data = {"suggestion": suggestion(finding)} if suggestion(finding) else None
        return types.Diagnostic(
            range=doc.lines.span_range(None if elsewhere else span), message=message,
            severity=(types.DiagnosticSeverity.Error if finding.severity == "error"
                      else types.DiagnosticSeverity.Warning),
            source=NAME, data=data)

    # ------------------------------------------------------------------ queries
    async def document(self, uri: str, wait: float = 2.0) -> Document | None:
        """The document at ``uri`` with the analysis of its latest text (waiting up to
        ``wait`` seconds for it, without holding up other requests); None when it is not
        open."""
        return await self.scheduler.current(uri, wait)

    async def symbol_at(self, uri: str, position: types.Position
                        ) -> tuple[Document, Symbol, Mention] | None:
        doc = await self.document(uri)
        if doc is None or doc.analysis is None or doc.analysis.index is None:
            return None
        line, column, word = doc.lines.at(position)
        hit = doc.analysis.index.at(line, column, word)
        return None if hit is None else (doc, *hit)


server = GaitServer()


def _location(doc: Document, mention: Mention) -> types.Location:
    return types.Location(uri=doc.uri, range=doc.lines.span_range(mention.span))


def _feature(name: str, options: Any = None) -> Callable[[Any], Any]:
    return server.feature(name, options) if options is not None else server.feature(name)


@_feature(types.INITIALIZE)
def initialize(ls: GaitServer, params: types.InitializeParams) -> None:
    """Trace as the client asks from the start (``$/setTrace`` changes it later)."""
    ls.protocol.trace = params.trace or types.TraceValue.Off


@_feature(types.SHUTDOWN)
def shutdown(ls: GaitServer, params: None) -> None:
    """No analysis or command outlives ``shutdown``."""
    del params
    ls.stop()


@_feature(types.INITIALIZED)
def initialized(ls: GaitServer, params: types.InitializedParams) -> None:
    """Load the compiler in the background, so the first document opened is fast."""
    del params

    def warm() -> None:
        analyse("legs L1..L2 health 2\ngait g uses L1 moves north\ngrid 2 x 1\nstart r0\n"
                "visit r1 infinitely often\n", "<warm-up>.gait")

    threading.Thread(target=warm, name="gaitc-lsp-warm-up", daemon=True).start()
    del ls


@_feature(types.TEXT_DOCUMENT_DID_OPEN)
def did_open(ls: GaitServer, params: types.DidOpenTextDocumentParams) -> None:
    ls.scheduler.edit(params.text_document.uri, params.text_document.text,
                      params.text_document.version)


@_feature(types.TEXT_DOCUMENT_DID_CHANGE)
def did_change(ls: GaitServer, params: types.DidChangeTextDocumentParams) -> None:
    document = ls.workspace.get_text_document(params.text_document.uri)
    ls.scheduler.edit(params.text_document.uri, document.source, params.text_document.version)


@_feature(types.TEXT_DOCUMENT_DID_CLOSE)
def did_close(ls: GaitServer, params: types.DidCloseTextDocumentParams) -> None:
    ls.scheduler.close(params.text_document.uri)
    ls.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
        uri=params.text_document.uri, diagnostics=[]))


@_feature(types.TEXT_DOCUMENT_HOVER)
async def hover(ls: GaitServer, params: types.HoverParams) -> types.Hover | None:
    hit = await ls.symbol_at(params.text_document.uri, params.position)
    if hit is None:
        return None
    doc, symbol, mention = hit
    assert doc.analysis is not None and doc.analysis.index is not None
    text = describe(symbol, doc.analysis.index, doc.analysis.model, mention.role)
    return types.Hover(contents=types.MarkupContent(kind=types.MarkupKind.Markdown, value=text),
                       range=doc.lines.span_range(mention.span) if not mention.ranged else None)


@_feature(types.TEXT_DOCUMENT_DEFINITION)
async def definition(ls: GaitServer, params: types.DefinitionParams
                     ) -> types.Location | None:
    hit = await ls.symbol_at(params.text_document.uri, params.position)
    if hit is None or hit[1].declaration is None:
        return None
    doc, symbol, _ = hit
    declared = symbol.declaration
    assert declared is not None
    return _location(doc, declared)


@_feature(types.TEXT_DOCUMENT_REFERENCES)
async def references(ls: GaitServer, params: types.ReferenceParams
                     ) -> list[types.Location]:
    hit = await ls.symbol_at(params.text_document.uri, params.position)
    if hit is None:
        return []
    doc, symbol, _ = hit
    return [_location(doc, m) for m in symbol.mentions
            if params.context.include_declaration or not m.declaration]


@_feature(types.TEXT_DOCUMENT_COMPLETION,
          types.CompletionOptions(trigger_characters=[",", ":", " ", "("]))
async def completion(ls: GaitServer, params: types.CompletionParams
                     ) -> types.CompletionList:
    doc = await ls.document(params.text_document.uri, wait=0.5)
    if doc is None:
        return types.CompletionList(is_incomplete=False, items=[])
    live = Lines(doc.text)
    line = params.position.line
    column = live.column(line, params.position.character)
    before = "\n".join([*live.lines[:line], live.line(line)[:column]])
    index = doc.analysis.index if doc.analysis is not None else None
    items = [types.CompletionItem(label=o.label, kind=COMPLETION_KIND[o.kind],
                                  detail=o.detail or None) for o in offers(before, index)]
    return types.CompletionList(is_incomplete=False, items=items)


@_feature(types.TEXT_DOCUMENT_PREPARE_RENAME)
async def prepare_rename(ls: GaitServer, params: types.PrepareRenameParams
                         ) -> types.Range | None:
    hit = await _renamable(ls, params.text_document.uri, params.position)
    return None if hit is None else hit[0].lines.span_range(hit[2].span)


async def _renamable(ls: GaitServer, uri: str, position: types.Position
                     ) -> tuple[Document, Symbol, Mention] | None:
    """The name at ``position`` when it can be renamed; a name from a range cannot."""
    hit = await ls.symbol_at(uri, position)
    if hit is None:
        return None
    symbol = hit[1]
    ranged = next((m for m in symbol.mentions if m.ranged), None)
    if ranged is not None:
        raise RequestFailed(f"'{symbol.name}' is one name of a range (line "
                            f"{ranged.span.line}); rename the range, or list the names one "
                            "by one")
    return hit


@_feature(types.TEXT_DOCUMENT_RENAME)
async def rename(ls: GaitServer, params: types.RenameParams) -> types.WorkspaceEdit | None:
    import re

    hit = await _renamable(ls, params.text_document.uri, params.position)
    if hit is None:
        return None
    doc, symbol, _ = hit
    new = params.new_name
    if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", new):
        raise RequestFailed(f"'{new}' is not a name: use letters, digits and _, not first a digit")
    assert doc.analysis is not None and doc.analysis.index is not None
    if new in doc.analysis.index.symbols and new != symbol.name:
        raise RequestFailed(f"'{new}' is already the name of a "
                         f"{doc.analysis.index.symbols[new].kind}")
    edits = [types.TextEdit(range=doc.lines.span_range(m.span), new_text=new)
             for m in symbol.mentions]
    return types.WorkspaceEdit(changes={doc.uri: edits})


@_feature(types.TEXT_DOCUMENT_CODE_ACTION)
async def code_action(ls: GaitServer, params: types.CodeActionParams
                      ) -> list[types.CodeAction | types.Command]:
    doc = await ls.document(params.text_document.uri)
    if doc is None:
        return []
    actions: list[types.CodeAction | types.Command] = []
    for diagnostic in params.context.diagnostics:
        fixes = _fixes(doc, diagnostic)
        for i, fix in enumerate(fixes):
            edits = [types.TextEdit(range=types.Range(
                start=doc.lines.position(e.line, e.column),
                end=doc.lines.position(e.line, e.end)), new_text=e.text) for e in fix.edits]
            actions.append(types.CodeAction(
                title=fix.title, kind=types.CodeActionKind.QuickFix, diagnostics=[diagnostic],
                is_preferred=i == 0, edit=types.WorkspaceEdit(changes={doc.uri: edits})))
        data = diagnostic.data if isinstance(diagnostic.data, dict) else {}
        name = data.get("suggestion")
        if isinstance(name, str) and not fixes:
            edit = types.TextEdit(range=diagnostic.range, new_text=name)
            actions.append(types.CodeAction(
                title=f"Change to '{name}'", kind=types.CodeActionKind.QuickFix,
                diagnostics=[diagnostic], is_preferred=True,
                edit=types.WorkspaceEdit(changes={doc.uri: [edit]})))
    if doc.repairs_for == doc.text:
        for repair in doc.repairs:
            edits = [types.TextEdit(range=types.Range(
                start=types.Position(line=e.start, character=0),
                end=types.Position(line=e.end, character=0)),
                new_text="".join(line + "\n" for line in e.lines)) for e in repair.edits]
            actions.append(types.CodeAction(title=repair.title,
                                            kind=types.CodeActionKind.QuickFix,
                                            edit=types.WorkspaceEdit(changes={doc.uri: edits})))
    elif doc.analysis is not None and doc.analysis.model is not None:
        actions.append(types.Command(
            title="Find verified repairs (solves the spec: takes seconds)",
            command=REPAIR_COMMAND, arguments=[doc.uri]))
    return actions


def _fixes(doc: Document, diagnostic: types.Diagnostic) -> list[Fix]:
    """The quick fixes of the finding ``diagnostic`` shows (:func:`quick_fixes`): found by
    its range and message in the document's analysis."""
    analysis = doc.analysis
    if analysis is None:
        return []
    for finding in analysis.findings:
        if finding.message == diagnostic.message.split("\nhint: ")[0] \
                and doc.lines.span_range(finding.span) == diagnostic.range:
            return quick_fixes(analysis, finding)
    return []


@server.command(REPAIR_COMMAND)
async def repair_command(ls: GaitServer, *args: Any) -> dict[str, Any]:
    """Solve the document and keep its verified repairs for the code actions.

    The search runs in a child process (:class:`gaitc.lsp.jobs.ChildJob`), so other
    requests are answered meanwhile; its stages show as work-done progress when the client
    supports it, and ``$/cancelRequest`` or cancelling the progress kills the child (the
    answer is then RequestCancelled)."""
    msg_id = ls.protocol.msg_id
    # A request cancelled before it started has been answered RequestCancelled by pygls,
    # which drops whatever this coroutine ends with: it returns at once, and never raises
    # (nobody would retrieve the exception).
    if ls.abandoned(msg_id):
        return _CANCELLED
    uri = args[0] if args and isinstance(args[0], str) else None
    if uri is None and args and isinstance(args[0], list) and args[0]:
        uri = str(args[0][0])
    doc = await ls.document(uri or "")
    if doc is None:
        return {"message": "the document is not open", "repairs": []}
    if ls.abandoned(msg_id):
        return _CANCELLED
    text, path = doc.text, doc.path
    progress = Progress(ls, "gaitc: finding verified repairs")
    job = ChildJob(lambda report: find_repairs(text, path, REPAIR_TIMEOUT, report),
                   REPAIR_TIMEOUT + REPAIR_GRACE, progress.report, prepare=preload_repairs)
    outcome = job.start()
    if msg_id is not None:
        ls.jobs[msg_id] = job
    final = "cancelled"
    try:
        await progress.begin(work_done_token(), job.cancel)
        message, found = _repairs_of(await outcome)
        final = message
    except JsonRpcException as err:
        final = err.message
        if ls.abandoned(msg_id):
            return _CANCELLED  # already answered: cancelled by the client or by shutdown
        raise
    finally:
        if msg_id is not None:
            ls.jobs.pop(msg_id, None)
        if not outcome.done():  # this request was cancelled, or the server is ending
            job.cancel()
        progress.end(final)
    if ls.documents.get(doc.uri) is doc:
        doc.repairs, doc.repairs_for = found, text
    ls.window_show_message(types.ShowMessageParams(type=types.MessageType.Info,
                                                   message=message))
    return {"message": message, "repairs": [r.title for r in found]}


_CANCELLED: dict[str, Any] = {"message": "cancelled", "repairs": []}


def _repairs_of(outcome: Outcome) -> tuple[str, list[RepairEdit]]:
    """The repair search's sentence and repairs, or the error that answers the request."""
    kind = outcome[0]
    if kind == "ok":
        message, found = outcome[1]
        return str(message), list(found)
    if kind == "cancelled":
        raise JsonRpcRequestCancelled("the search for repairs was cancelled")
    if kind == "timeout":
        raise RequestFailed(f"the search for repairs took more than "
                            f"{REPAIR_TIMEOUT + REPAIR_GRACE:.0f} s and was stopped")
    if kind == "died":
        raise RequestFailed(f"the search for repairs ended without an answer (exit status "
                            f"{outcome[1]})")
    err = outcome[1]
    raise RequestFailed(f"the search for repairs failed: internal error: "
                        f"{type(err).__name__}: {err} (a bug in gaitc; please report it)")


class Progress:
    """A work-done progress in the client, when it supports one (``window.workDoneProgress``):
    begun with a title, told each stage, ended with the outcome; cancelling it in the
    client calls the ``cancel`` given to :meth:`begin`."""

    def __init__(self, ls: GaitServer, title: str) -> None:
        self.ls = ls
        self.title = title
        self.token: types.ProgressToken | None = None
        self.stage: str | None = None  # the latest stage, shown when the progress begins
        self.ended = False

    async def begin(self, given: types.ProgressToken | None, cancel: Callable[[], None]
                    ) -> None:
        """Begin, with the client's token ``given`` with the request, else with one the
        server creates (``window/workDoneProgress/create``)."""
        window = self.ls.client_capabilities.window
        if window is None or not window.work_done_progress:
            return
        token = given
        if token is None:
            token = f"gaitc-{uuid.uuid4()}"
            try:
                await asyncio.wait_for(self.ls.work_done_progress.create_async(token),
                                       PROGRESS_CREATE_WAIT)
            except (TimeoutError, JsonRpcException):
                return  # the client refused or did not answer: no progress then
        if self.ended:
            return
        self.token = token
        self.ls.work_done_progress.begin(token, types.WorkDoneProgressBegin(
            title=self.title, cancellable=True, message=self.stage))
        asked = self.ls.work_done_progress.tokens.get(token)
        if asked is not None:
            asked.add_done_callback(lambda future: cancel() if future.cancelled() else None)

    def report(self, stage: str) -> None:
        self.stage = stage
        if self.token is not None and not self.ended:
            self.ls.work_done_progress.report(self.token, types.WorkDoneProgressReport(
                message=stage, cancellable=True))

    def end(self, message: str) -> None:
        if self.ended:
            return
        self.ended = True
        if self.token is not None:
            self.ls.work_done_progress.end(self.token, types.WorkDoneProgressEnd(message=message))
            self.ls.work_done_progress.tokens.pop(self.token, None)


@_feature(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
          types.SemanticTokensLegend(token_types=list(TOKEN_TYPES),
                                     token_modifiers=list(TOKEN_MODIFIERS)))
async def semantic_tokens(ls: GaitServer, params: types.SemanticTokensParams
                          ) -> types.SemanticTokens:
    doc = await ls.document(params.text_document.uri)
    if doc is None or doc.analysis is None or doc.analysis.index is None \
            or doc.analysis.stale_tree:
        return types.SemanticTokens(data=[])
    tokens = []
    for symbol in doc.analysis.index.symbols.values():
        for mention in symbol.mentions:
            if mention.ranged:
                continue
            place = doc.lines.span_range(mention.span)
            if place.start.line != place.end.line:
                continue
            tokens.append((place.start.line, place.start.character,
                           place.end.character - place.start.character,
                           TOKEN_OF[symbol.kind], int(mention.declaration)))
    data: list[int] = []
    last_line = last_char = 0
    for line, char, length, kind, modifiers in sorted(set(tokens)):
        data += [line - last_line, char - last_char if line == last_line else char, length,
                 kind, modifiers]
        last_line, last_char = line, char
    return types.SemanticTokens(data=data)


@_feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
async def document_symbols(ls: GaitServer, params: types.DocumentSymbolParams
                           ) -> list[types.DocumentSymbol]:
    doc = await ls.document(params.text_document.uri)
    if doc is None or doc.analysis is None or doc.analysis.index is None:
        return []
    groups: dict[Kind, list[types.DocumentSymbol]] = {kind: [] for kind in Kind}
    for symbol in doc.analysis.index.symbols.values():
        declared = symbol.declaration
        if declared is None:
            continue
        place = doc.lines.span_range(declared.span)
        groups[symbol.kind].append(types.DocumentSymbol(
            name=symbol.name, kind=SYMBOL_KIND[symbol.kind], range=place,
            selection_range=place, detail=", ".join(sorted(r for r in symbol.roles() if r))
            or None))
    titles = {Kind.LEG: "legs", Kind.GAIT: "gaits", Kind.REGION: "map",
              Kind.HAZARD: "hazard sets"}
    out = []
    for kind, children in groups.items():
        if children:
            whole = types.Range(start=children[0].range.start, end=children[-1].range.end)
            out.append(types.DocumentSymbol(name=titles[kind], kind=types.SymbolKind.Namespace,
                                            range=whole, selection_range=children[0].range,
                                            children=children))
    goals = [m for s in doc.analysis.index.symbols.values() for m in s.mentions
             if m.role == "goal"]
    if goals:
        place = doc.lines.span_range(goals[0].span)
        names = [s.name for s in doc.analysis.index.symbols.values() if "goal" in s.roles()]
        out.append(types.DocumentSymbol(name="goals", kind=types.SymbolKind.Event, range=place,
                                        selection_range=place, detail=", ".join(names)))
    return out


def serve() -> None:
    """Serve over standard input and output until the client says exit or closes the
    input, or SIGTERM or SIGINT arrives (:func:`gaitc.lsp.transport.run`).

    Standard output is the protocol's channel: anything else the process (or a child
    process of the repair search) would print goes to standard error instead."""
    import os
    import sys

    from gaitc.lsp.transport import run

    channel = os.dup(sys.stdout.fileno())
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())
    try:
        run(server, sys.stdin.fileno(), channel, server.stop)
    finally:
        os.close(channel)
