"""The language server (issue 40): ``gaitc lsp`` started as a process, spoken to over LSP.

pytest-lsp starts the server and drives it with pygls's client: initialize, open a spec,
the diagnostics it publishes, hover, definition, references, completion, rename, the
quick fix and the verified repairs (re-solved here, not trusted), shutdown and exit.
"""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient

import gaitc

ROOT = Path(__file__).resolve().parents[2]
ROBOT_A = ROOT / "specs" / "thesis_robot_a.gait"
UNREALIZABLE = ROOT / "specs" / "unrealizable_2x2.gait"


@pytest_lsp.fixture(config=ClientServerConfig(server_command=[sys.executable, "-m", "gaitc",
                                                               "lsp"]))
async def client(lsp_client: LanguageClient):  # type: ignore[no-untyped-def]
    kinds = types.ClientCodeActionKindOptions(
        value_set=[types.CodeActionKind.QuickFix, types.CodeActionKind.Source])
    literal = types.ClientCodeActionLiteralOptions(code_action_kind=kinds)
    capabilities = types.ClientCapabilities(text_document=types.TextDocumentClientCapabilities(
        code_action=types.CodeActionClientCapabilities(code_action_literal_support=literal)))
    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=capabilities, root_uri=ROOT.as_uri()))
    yield
    await lsp_client.shutdown_session()


async def _open(client: LanguageClient, path: Path, text: str | None = None) -> str:
    uri = path.as_uri()
    client.text_document_did_open(types.DidOpenTextDocumentParams(text_document=(
        types.TextDocumentItem(uri=uri, language_id="gait", version=1,
                               text=path.read_text() if text is None else text))))
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    return uri


def _at(line: int, character: int) -> types.Position:
    return types.Position(line=line, character=character)


def _find(text: str, needle: str, nth: int = 0) -> types.Position:
    """The position of the ``nth`` occurrence of ``needle`` in the code of ``text`` (its
    comments left out)."""
    import re

    text = re.sub(r"#[^\n]*", lambda m: " " * len(m.group()), text)
    start = -1
    for _ in range(nth + 1):
        start = text.index(needle, start + 1)
    line = text.count("\n", 0, start)
    return _at(line, start - (text.rfind("\n", 0, start) + 1))


@pytest.mark.asyncio
async def test_a_clean_spec_has_no_diagnostics(client: LanguageClient) -> None:
    uri = await _open(client, ROBOT_A)
    assert list(client.diagnostics[uri]) == []


@pytest.mark.asyncio
async def test_an_unknown_leg_is_reported_with_the_cli_message_and_fixed(
        client: LanguageClient, tmp_path: Path) -> None:
    text = ROBOT_A.read_text().replace("gait north_a uses L4, L6", "gait north_a uses L4, L66")
    path = tmp_path / "typo.gait"
    path.write_text(text)
    uri = await _open(client, path, text)
    [diagnostic] = client.diagnostics[uri]
    with pytest.raises(gaitc.GaitcError) as cli:
        gaitc.parse(text, str(path))
    assert diagnostic.message.splitlines()[0] == cli.value.message
    assert diagnostic.severity == types.DiagnosticSeverity.Error
    where = _find(text, "L66")
    assert diagnostic.range.start == where
    assert diagnostic.range.end == _at(where.line, where.character + 3)
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), range=diagnostic.range,
        context=types.CodeActionContext(diagnostics=[diagnostic])))
    fix = next(a for a in actions if isinstance(a, types.CodeAction) and a.edit is not None)
    assert fix.title == "Change to 'L6'"
    [edit] = fix.edit.changes[uri]
    assert edit.new_text == "L6" and edit.range == diagnostic.range


@pytest.mark.asyncio
async def test_hover_tells_a_leg_a_gait_a_region_and_a_goal(client: LanguageClient) -> None:
    text = ROBOT_A.read_text()
    uri = await _open(client, ROBOT_A)
    doc = types.TextDocumentIdentifier(uri=uri)

    async def hover(needle: str, nth: int = 0) -> str:
        found = await client.text_document_hover_async(types.HoverParams(
            text_document=doc, position=_find(text, needle, nth)))
        assert found is not None
        assert isinstance(found.contents, types.MarkupContent)
        return found.contents.value

    leg = await hover("L4,", 0)
    assert "3 health levels" in leg and "north_a, north_b, east_a, east_c" in leg
    gait = await hover("north_a")
    assert "legs (firing order): L4, L6" in gait and "moves north" in gait
    cache = await hover("r14", 1)
    assert "a **cache**" in cache and "neighbours:" in cache and "- north `r12` by" in cache
    goal = await hover("r11,", 1)  # in 'visit r11, r12 infinitely often'
    assert "goal reachable from the start r12 in" in goal
    hazard = await hover("blue:")
    assert "regions: r7, r9, r10" in hazard


@pytest.mark.asyncio
async def test_definition_references_and_rename(client: LanguageClient) -> None:
    text = ROBOT_A.read_text()
    uri = await _open(client, ROBOT_A)
    doc = types.TextDocumentIdentifier(uri=uri)
    use = _find(text, "r14", 1)  # in 'cache r3, r14'
    declared = await client.text_document_definition_async(types.DefinitionParams(
        text_document=doc, position=use))
    assert isinstance(declared, types.Location)
    assert declared.range.start == _find(text, "r14", 0)  # the grid's cells
    found = await client.text_document_references_async(types.ReferenceParams(
        text_document=doc, position=use,
        context=types.ReferenceContext(include_declaration=True)))
    assert found is not None
    code_lines = [i for i, line in enumerate(text.splitlines())
                  if "r14" in line.split("#")[0]]
    assert sorted({loc.range.start.line for loc in found}) == code_lines
    edit = await client.text_document_rename_async(types.RenameParams(
        text_document=doc, position=use, new_name="depot"))
    assert edit is not None and edit.changes is not None
    renamed = _apply(text, edit.changes[uri])
    spec = gaitc.parse(renamed, "renamed.gait")
    assert spec.model is not None and "depot" in spec.model.caches
    with pytest.raises(Exception, match="already the name of a gait"):
        await client.text_document_rename_async(types.RenameParams(
            text_document=doc, position=use, new_name="north_a"))
    with pytest.raises(Exception, match=r"'L4' is one name of a range \(line 14\)"):
        await client.text_document_rename_async(types.RenameParams(
            text_document=doc, position=_find(text, "L4,"), new_name="front"))
    ready = await client.text_document_prepare_rename_async(types.PrepareRenameParams(
        text_document=doc, position=use))
    assert ready is not None


def _apply(text: str, edits: list[types.TextEdit]) -> str:
    lines = text.split("\n")
    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character),
                       reverse=True):
        start, end = edit.range.start, edit.range.end
        head = lines[start.line][:start.character]
        tail = lines[end.line][end.character:] if end.line < len(lines) else ""
        lines[start.line:end.line + 1] = (head + edit.new_text + tail).split("\n")
    return "\n".join(lines)


@pytest.mark.asyncio
async def test_completion_offers_names_of_the_right_kind(client: LanguageClient,
                                                         tmp_path: Path) -> None:
    text = ROBOT_A.read_text() + "\ngait extra uses \ncache \n"
    path = tmp_path / "more.gait"
    uri = await _open(client, path, text)
    doc = types.TextDocumentIdentifier(uri=uri)
    lines = text.split("\n")
    uses = await client.text_document_completion_async(types.CompletionParams(
        text_document=doc, position=_at(len(lines) - 3, len(lines[-3]))))
    labels = [item.label for item in (uses.items if isinstance(uses, types.CompletionList)
                                      else uses or [])]
    assert labels[:8] == [f"L{i}" for i in range(1, 9)] and "r12" not in labels
    cache = await client.text_document_completion_async(types.CompletionParams(
        text_document=doc, position=_at(len(lines) - 2, len(lines[-2]))))
    labels = [item.label for item in (cache.items if isinstance(cache, types.CompletionList)
                                      else cache or [])]
    assert "r12" in labels and "L1" not in labels


@pytest.mark.asyncio
async def test_verified_repairs_are_offered_as_edits(client: LanguageClient) -> None:
    text = UNREALIZABLE.read_text()
    uri = await _open(client, UNREALIZABLE)
    doc = types.TextDocumentIdentifier(uri=uri)
    whole = types.Range(start=_at(0, 0), end=_at(0, 0))
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=doc, range=whole, context=types.CodeActionContext(diagnostics=[])))
    [ask] = [a for a in actions if isinstance(a, types.Command)]
    assert ask.title.startswith("Find verified repairs")
    result = await client.workspace_execute_command_async(types.ExecuteCommandParams(
        command=ask.command, arguments=ask.arguments))
    assert result["repairs"], result
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=doc, range=whole, context=types.CodeActionContext(diagnostics=[])))
    repairs = [a for a in actions if isinstance(a, types.CodeAction) and a.edit is not None]
    assert [a.title for a in repairs] == result["repairs"]
    for action in repairs:
        assert action.edit is not None and action.edit.changes is not None
        repaired = _apply(text, action.edit.changes[uri])
        assert gaitc.check(gaitc.parse(repaired, "repaired.gait")).realizable, action.title


@pytest.mark.asyncio
async def test_the_outline_and_semantic_tokens(client: LanguageClient) -> None:
    uri = await _open(client, ROBOT_A)
    doc = types.TextDocumentIdentifier(uri=uri)
    outline = await client.text_document_document_symbol_async(
        types.DocumentSymbolParams(text_document=doc))
    assert outline is not None
    names = [s.name for s in outline if isinstance(s, types.DocumentSymbol)]
    assert names == ["legs", "gaits", "map", "hazard sets", "goals"]
    tokens = await client.text_document_semantic_tokens_full_async(
        types.SemanticTokensParams(text_document=doc))
    assert tokens is not None and len(tokens.data) % 5 == 0 and len(tokens.data) > 100


@pytest.mark.asyncio
async def test_edits_are_analysed_and_stale_results_dropped(client: LanguageClient,
                                                            tmp_path: Path) -> None:
    text = ROBOT_A.read_text()
    path = tmp_path / "edited.gait"
    uri = await _open(client, path, text)
    broken = text.replace("start r12", "start r99")
    for version, body in enumerate([text + "gait", text + "gait z uses", broken], 2):
        client.text_document_did_change(types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=body)]))
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    await asyncio.sleep(0.3)
    [diagnostic] = client.diagnostics[uri]
    assert "r99" in diagnostic.message


def test_every_prefix_of_every_shipped_spec_is_handled() -> None:
    """Each keystroke state of each shipped spec: analysed, completed and hovered at the
    cursor without an exception, errors positioned inside the document."""
    from gaitc.lsp.analysis import analyse
    from gaitc.lsp.completion import offers
    from gaitc.lsp.hover import describe
    from gaitc.lsp.positions import Lines

    specs = sorted((ROOT / "specs").glob("*.gait"))
    assert len(specs) >= 10
    for spec in specs:
        text = spec.read_text()
        previous = None
        for end in range(len(text) + 1):
            prefix = text[:end]
            found = analyse(prefix, str(spec), previous)
            previous = found
            lines = Lines(prefix)
            for finding in found.findings:
                place = lines.span_range(finding.span)
                assert place.start.line <= max(0, len(lines.lines) - 1), (spec, end, finding)
            offers(prefix, found.index)
            if found.index is not None:
                line = prefix.count("\n") + 1
                column = end - (prefix.rfind("\n") + 1)
                hit = found.index.at(line, max(1, column))
                if hit is not None:
                    describe(hit[0], found.index, found.model, hit[1].role)
        assert found.model is not None and not found.errors, spec
