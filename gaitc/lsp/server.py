"""``gaitc lsp``: the Language Server Protocol server for ``.gait`` files, on pygls.

Each open document is analysed (:mod:`gaitc.lsp.analysis`) a short debounce after its last
edit, in a worker thread, so typing never waits for the compiler; a result for a version
that has been edited since is dropped. Diagnostics come in two steps: the compiler's at
once, then the valve primitives' (a gait search) when they are ready. The features are
thin views of the index and the model: hover (:mod:`gaitc.lsp.hover`), definition and
references, completion (:mod:`gaitc.lsp.completion`), rename, code actions and the
repair command (:mod:`gaitc.lsp.actions`), semantic tokens and the outline.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from lsprotocol import types
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer
from pygls.uris import to_fs_path

from gaitc.lsp.actions import RepairEdit, find_repairs, suggestion
from gaitc.lsp.analysis import Analysis, Finding, analyse, primitive_findings
from gaitc.lsp.completion import offers
from gaitc.lsp.hover import describe
from gaitc.lsp.index import Kind, Mention, Symbol
from gaitc.lsp.positions import Lines

NAME = "gaitc"
DEBOUNCE = 0.05  # seconds of quiet after an edit before the analysis starts
REPAIR_TIMEOUT = 120.0  # seconds the repair command may solve for
REPAIR_COMMAND = "gaitc.findRepairs"

#: Semantic token types, in the legend's order, and the kind of name each colours.
TOKEN_TYPES = ("variable", "function", "enumMember", "event")
TOKEN_OF = {Kind.LEG: 0, Kind.GAIT: 1, Kind.REGION: 2, Kind.HAZARD: 3}
TOKEN_MODIFIERS = ("declaration",)
SYMBOL_KIND = {Kind.LEG: types.SymbolKind.Variable, Kind.GAIT: types.SymbolKind.Function,
               Kind.REGION: types.SymbolKind.EnumMember, Kind.HAZARD: types.SymbolKind.Event}
COMPLETION_KIND = {"keyword": types.CompletionItemKind.Keyword,
                   Kind.LEG.value: types.CompletionItemKind.Variable,
                   Kind.GAIT.value: types.CompletionItemKind.Function,
                   Kind.REGION.value: types.CompletionItemKind.EnumMember,
                   Kind.HAZARD.value: types.CompletionItemKind.Event}


class RequestFailed(JsonRpcException):
    """A request the server understood but cannot do (LSP's RequestFailed), with a message
    the editor shows the user."""

    CODE = -32803


@dataclass
class Document:
    """An open document: its text and version, and the latest analysis of it."""

    uri: str
    path: str
    text: str = ""
    version: int = 0
    analysis: Analysis | None = None
    lines: Lines = field(default_factory=lambda: Lines(""))
    repairs: list[RepairEdit] = field(default_factory=list)
    repairs_for: str | None = None  # the text the repairs were found for
    timer: threading.Timer | None = None
    ready: threading.Event = field(default_factory=threading.Event)


class GaitServer(LanguageServer):
    """The server, with the open documents it analyses."""

    def __init__(self) -> None:
        from gaitc import __version__

        super().__init__(NAME, __version__)
        self.documents: dict[str, Document] = {}
        self.lock = threading.Lock()

    # ------------------------------------------------------------------ analysis
    def changed(self, uri: str, text: str, version: int) -> None:
        """Record an edit and schedule its analysis after the debounce."""
        with self.lock:
            doc = self.documents.get(uri)
            if doc is None:
                doc = Document(uri, to_fs_path(uri) or uri)
                self.documents[uri] = doc
            doc.text, doc.version = text, version
            doc.ready.clear()
            if doc.timer is not None:
                doc.timer.cancel()
            doc.timer = threading.Timer(DEBOUNCE, self._analyse, (uri, version))
            doc.timer.daemon = True
            doc.timer.start()

    def _analyse(self, uri: str, version: int) -> None:
        with self.lock:
            doc = self.documents.get(uri)
            if doc is None or doc.version != version:
                return
            text, previous = doc.text, doc.analysis
        found = analyse(text, doc.path, previous)
        with self.lock:
            if doc.version != version:
                return
            doc.analysis, doc.lines = found, Lines(text)
            doc.ready.set()
        self._publish(doc, found.findings, version)
        if found.model is not None:
            extra = primitive_findings(found)
            if extra:
                with self.lock:
                    if doc.version != version:
                        return
                    found.findings.extend(extra)
                self._publish(doc, found.findings, version)

    def _publish(self, doc: Document, findings: list[Finding], version: int) -> None:
        diagnostics = [self._diagnostic(doc, f) for f in findings]
        self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
            uri=doc.uri, diagnostics=diagnostics, version=version))

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

    def document(self, uri: str, wait: float = 2.0) -> Document | None:
        """The document at ``uri`` with the analysis of its latest text (waiting up to
        ``wait`` seconds for it); None when it is not open."""
        doc = self.documents.get(uri)
        if doc is None:
            return None
        doc.ready.wait(wait)
        return doc if doc.analysis is not None else None

    def symbol_at(self, uri: str, position: types.Position
                  ) -> tuple[Document, Symbol, Mention] | None:
        doc = self.document(uri)
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


@_feature(types.INITIALIZED)
def initialized(ls: GaitServer, params: types.InitializedParams) -> None:
    """Load the compiler in the background, so the first document opened is fast."""
    del params

    def warm() -> None:
        analyse("legs L1..L2 health 2\ngait g uses L1 moves north\ngrid 2 x 1\nstart r0\n"
                "visit r1 infinitely often\n", "<warm-up>.gait")

    threading.Thread(target=warm, daemon=True).start()
    del ls


@_feature(types.TEXT_DOCUMENT_DID_OPEN)
def did_open(ls: GaitServer, params: types.DidOpenTextDocumentParams) -> None:
    ls.changed(params.text_document.uri, params.text_document.text, params.text_document.version)


@_feature(types.TEXT_DOCUMENT_DID_CHANGE)
def did_change(ls: GaitServer, params: types.DidChangeTextDocumentParams) -> None:
    document = ls.workspace.get_text_document(params.text_document.uri)
    ls.changed(params.text_document.uri, document.source, params.text_document.version)


@_feature(types.TEXT_DOCUMENT_DID_CLOSE)
def did_close(ls: GaitServer, params: types.DidCloseTextDocumentParams) -> None:
    with ls.lock:
        doc = ls.documents.pop(params.text_document.uri, None)
        if doc is not None and doc.timer is not None:
            doc.timer.cancel()
    ls.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
        uri=params.text_document.uri, diagnostics=[]))


@_feature(types.TEXT_DOCUMENT_HOVER)
def hover(ls: GaitServer, params: types.HoverParams) -> types.Hover | None:
    hit = ls.symbol_at(params.text_document.uri, params.position)
    if hit is None:
        return None
    doc, symbol, mention = hit
    assert doc.analysis is not None and doc.analysis.index is not None
    text = describe(symbol, doc.analysis.index, doc.analysis.model, mention.role)
    return types.Hover(contents=types.MarkupContent(kind=types.MarkupKind.Markdown, value=text),
                       range=doc.lines.span_range(mention.span) if not mention.ranged else None)


@_feature(types.TEXT_DOCUMENT_DEFINITION)
def definition(ls: GaitServer, params: types.DefinitionParams) -> types.Location | None:
    hit = ls.symbol_at(params.text_document.uri, params.position)
    if hit is None or hit[1].declaration is None:
        return None
    doc, symbol, _ = hit
    declared = symbol.declaration
    assert declared is not None
    return _location(doc, declared)


@_feature(types.TEXT_DOCUMENT_REFERENCES)
def references(ls: GaitServer, params: types.ReferenceParams) -> list[types.Location]:
    hit = ls.symbol_at(params.text_document.uri, params.position)
    if hit is None:
        return []
    doc, symbol, _ = hit
    return [_location(doc, m) for m in symbol.mentions
            if params.context.include_declaration or not m.declaration]


@_feature(types.TEXT_DOCUMENT_COMPLETION,
          types.CompletionOptions(trigger_characters=[",", ":", " ", "("]))
def completion(ls: GaitServer, params: types.CompletionParams) -> types.CompletionList:
    doc = ls.document(params.text_document.uri, wait=0.5)
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
def prepare_rename(ls: GaitServer, params: types.PrepareRenameParams) -> types.Range | None:
    hit = _renamable(ls, params.text_document.uri, params.position)
    return None if hit is None else hit[0].lines.span_range(hit[2].span)


def _renamable(ls: GaitServer, uri: str, position: types.Position
               ) -> tuple[Document, Symbol, Mention] | None:
    """The name at ``position`` when it can be renamed; a name from a range cannot."""
    hit = ls.symbol_at(uri, position)
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
def rename(ls: GaitServer, params: types.RenameParams) -> types.WorkspaceEdit | None:
    import re

    hit = _renamable(ls, params.text_document.uri, params.position)
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
def code_action(ls: GaitServer, params: types.CodeActionParams
                ) -> list[types.CodeAction | types.Command]:
    doc = ls.document(params.text_document.uri)
    if doc is None:
        return []
    actions: list[types.CodeAction | types.Command] = []
    for diagnostic in params.context.diagnostics:
        data = diagnostic.data if isinstance(diagnostic.data, dict) else {}
        name = data.get("suggestion")
        if isinstance(name, str):
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


@server.command(REPAIR_COMMAND)
def repair_command(ls: GaitServer, *args: Any) -> dict[str, Any]:
    """Solve the document and keep its verified repairs for the code actions."""
    uri = args[0] if args and isinstance(args[0], str) else None
    if uri is None and args and isinstance(args[0], list) and args[0]:
        uri = str(args[0][0])
    doc = ls.document(uri or "")
    if doc is None:
        return {"message": "the document is not open", "repairs": []}
    text = doc.text
    message, found = find_repairs(text, doc.path, REPAIR_TIMEOUT)
    with ls.lock:
        doc.repairs, doc.repairs_for = found, text
    ls.window_show_message(types.ShowMessageParams(type=types.MessageType.Info,
                                                   message=message))
    return {"message": message, "repairs": [r.title for r in found]}


@_feature(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
          types.SemanticTokensLegend(token_types=list(TOKEN_TYPES),
                                     token_modifiers=list(TOKEN_MODIFIERS)))
def semantic_tokens(ls: GaitServer, params: types.SemanticTokensParams) -> types.SemanticTokens:
    doc = ls.document(params.text_document.uri)
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
def document_symbols(ls: GaitServer, params: types.DocumentSymbolParams
                     ) -> list[types.DocumentSymbol]:
    doc = ls.document(params.text_document.uri)
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
    """Serve over standard input and output until the client says exit.

    Standard output is the protocol's channel: anything else the process (or a child
    process of the repair search) would print goes to standard error instead."""
    import os
    import sys

    channel = os.fdopen(os.dup(sys.stdout.fileno()), "wb", buffering=0)
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())
    server.start_io(sys.stdin.buffer, channel)
