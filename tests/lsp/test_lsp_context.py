"""The editor offers only what the checker accepts (issue 51).

Completion by context (:data:`gaitc.lsp.completion.CONTEXTS`): every name offered at a
place is put there and the file checked again, so an offer the checker refuses fails the
test; blocked cells, legs outside ``uses``, repeats that are errors are not offered. The
quick fixes of unknown legs, gaits and regions (:func:`gaitc.lsp.actions.quick_fixes`):
each fix is applied and the edited file linted again. The server itself is driven over LSP
(pytest-lsp, as in ``test_lsp.py``) for the completion after ``cache`` and ``uses`` and the
fixes of ``unknown leg 'A6'``, an unknown gait and an unknown region.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient

import gaitc
from gaitc.lsp.actions import apply, quick_fixes
from gaitc.lsp.analysis import Analysis, analyse
from gaitc.lsp.completion import CONTEXTS, offers, place_of

#: A 3 x 3 grid with two blocked cells (r4 by name, r2 as the cell (0, 2)), a cache, a
#: hazard set and legs of health 3.
MAP = """\
robot "walker"
legs L1..L4 health 3
gait fwd uses L1, L2 moves east
gait back uses L3, L4 moves west
gait up uses L1, L3 moves north
gait down uses L2, L4 moves south
grid 3 x 3
block r4, (0, 2)
hazard mud: r6
cache r0
start r0
visit r8 infinitely often
"""
BLOCKED = {"r2", "r4"}
FREE = ["r0", "r1", "r3", "r5", "r6", "r7", "r8"]


def _index(text: str = MAP) -> Analysis:
    found = analyse(text, "map.gait")
    assert found.model is not None and not found.errors, found.findings
    return found


def _labels(before: str, found: Analysis | None = None) -> list[str]:
    found = found or _index()
    return [o.label for o in offers(before, found.index)]


def _checks(text: str) -> bool:
    try:
        gaitc.lint(gaitc.parse(text, "edited.gait"))
    except gaitc.GaitcError:
        return False
    return True


# ---------------------------------------------------------------------- completion
def test_the_map_is_what_the_tests_say() -> None:
    found = _index()
    assert found.index is not None and found.index.blocked == BLOCKED
    assert found.index.free_regions() == FREE
    assert found.model is not None
    assert [r.name for r in found.model.regions] == FREE


def test_after_cache_no_blocked_cell_nor_a_cache_nor_a_hazard_region() -> None:
    offered = _labels(MAP + "cache ")
    assert offered == ["r1", "r3", "r5", "r7", "r8"]
    assert _labels(MAP + "caches r1, ") == ["r3", "r5", "r7", "r8"]
    assert _labels(MAP + "cache r1 ") == []  # a comma or the next statement comes next


def test_every_region_offered_after_cache_is_accepted_and_every_other_refused() -> None:
    """The offers are exactly the regions the checker accepts as a new cache."""
    offered = set(_labels(MAP + "cache "))
    for region in [*FREE, *BLOCKED]:
        assert _checks(MAP + f"cache {region}\n") == (region in offered), region


def test_after_uses_legs_only_and_not_twice() -> None:
    assert _labels(MAP + "gait g uses ") == ["L1", "L2", "L3", "L4"]
    assert _labels(MAP + "gait g uses L2, ") == ["L1", "L3", "L4"]
    assert _labels(MAP + "gait g uses L1..L3, ") == ["L4"]
    assert _labels(MAP + "gait g uses L2 ") == ["moves", "valves", "primitive"]
    assert "uses" not in _labels(MAP + "correction gait turn ")  # correction gaits use no legs
    assert _checks(MAP + "gait g uses L1, L3 moves east\n")
    assert not _checks(MAP + "gait g uses L1, L1 moves east\n")  # a leg listed twice


def test_each_region_list_offers_free_regions_and_no_repeat_that_is_an_error() -> None:
    assert _labels(MAP + "start ") == FREE
    assert _labels(MAP + "hazard ice: r1, ") == ["r3", "r5", "r6", "r7", "r8"]  # no cache
    assert _labels(MAP + "visit r1, ") == ["r0", "r3", "r5", "r6", "r7"]  # r8 is a goal
    assert _labels(MAP + "visit r1 ") == ["infinitely"]
    assert _labels(MAP + "gait hop uses L1 moves r1 -> ") == FREE
    assert _labels(MAP + "edge ") == FREE and _labels(MAP + "edge r0 <-> ") == FREE
    assert _labels(MAP + "block ") == ["r0", "r1", "r3", "r5", "r6", "r7", "r8"]
    for text in (MAP + "start r4\n", MAP + "visit r2 infinitely often\n",
                 MAP + "hazard ice: r0\n", MAP + "visit r8 infinitely often\n"):
        assert not _checks(text.replace("start r0\n", "") if "start r4" in text else text)


def test_after_moves_directions_and_regions_of_one_kind() -> None:
    directions = ["north", "south", "east", "west"]
    assert _labels(MAP + "gait hop uses L1 moves ") == directions + FREE
    assert _labels(MAP + "gait hop uses L1 moves north, ") == ["south", "east", "west"]
    assert _labels(MAP + "gait hop uses L1 moves r0 -> r1, ") == FREE
    assert _labels(MAP + "gait hop uses L1 moves north ") == ["valves", "primitive"]


def test_edges_take_moving_gaits_and_start_takes_legs_and_their_levels() -> None:
    gaits = ["fwd", "back", "up", "down"]
    assert _labels(MAP + "edge r0 -> r8 by ") == gaits  # never noGait
    assert _labels(MAP + "edge r0 -> r8 by fwd, ") == ["back", "up", "down"]
    assert _labels(MAP + "edge r0 -> r8 ") == ["by", "north", "south", "east", "west"]
    text = MAP.replace("start r0\n", "")
    assert _labels(text + "start r0 with ", _index()) == ["L1", "L2", "L3", "L4"]
    assert _labels(text + "start r0 with L2 = ", _index()) == ["1", "2", "3"]
    assert _labels(text + "start r0 with L2 = 1, ", _index()) == ["L1", "L3", "L4"]
    for level in ("1", "3"):
        assert _checks(text + f"start r0 with L2 = {level}\n")
    assert not _checks(text + "start r0 with L2 = 4\n")
    assert not _checks(MAP + "edge r0 -> r8 by noGait\n")


def test_formulas_offer_the_names_their_place_accepts() -> None:
    names = set(_labels(MAP + "guarantee always "))
    assert {"r0", "fwd", "noGait", "mud"} <= names
    assert not (BLOCKED | {"L1", "L2", "L3", "L4"}) & names  # a leg is no proposition
    for name in names - {"always", "eventually", "next", "not", "true", "false", "health",
                         "failed"}:
        assert _checks(MAP + f"guarantee always {name} -> up\n"), name
    for name in (*BLOCKED, "L1"):
        assert not _checks(MAP + f"guarantee always {name} -> up\n"), name
    # under next an assumption names only what the environment chooses
    under = _labels(MAP + "assume always next ")
    assert "mud" in under and "r0" not in under and "fwd" not in under
    assert _checks(MAP + "assume always next mud -> mud\n")
    assert not _checks(MAP + "assume always next r0 -> mud\n")
    assert _labels(MAP + "assume always health(") == ["L1", "L2", "L3", "L4"]
    assert _labels(MAP + "assume always health(L1) >= ") == ["1", "2", "3"]
    assert "next" not in _labels(MAP + "guarantee ")  # an initial condition cannot look ahead


def test_every_statement_place_has_one_entry_in_the_table() -> None:
    """Each place reached by the texts below is an entry of CONTEXTS (no fallback)."""
    texts = ["legs A1 ", "legs A1 health ", "gait g ", "gait g uses ", "gait g moves ",
             "gait g valves ", 'gait g primitive "r.yaml" ', 'gait g primitive "r" direction ',
             'gait g primitive "r" method ', "grid 2 ", "grid 2 x 2 ", "grid 2 x 2 cells ",
             "block ", "region ", "edge ", "edge a -> ", "edge a <-> ", "edge a -> b by ",
             "cache ", "hazard h ", "hazard h: ", "start ", "start a with ", "visit ",
             "visit a infinitely ", "assume ", "guarantee ", "robot ", "correction "]
    for text in texts:
        place = place_of(text, None)
        assert place is not None and (place.statement, place.clause) in CONTEXTS, text


# ---------------------------------------------------------------------- quick fixes
def _fixes(text: str) -> tuple[Analysis, list[tuple[str, str]]]:
    found = analyse(text, "typo.gait")
    [error] = found.errors
    return found, [(fix.title, apply(text, fix.edits)) for fix in quick_fixes(found, error)]


def test_an_unknown_leg_is_replaced_or_declared_and_each_fix_checks() -> None:
    text = MAP.replace("L1..L4", "L1..L6").replace("gait up uses L1, L3",
                                                   "gait up uses L1, A6")
    found, fixes = _fixes(text)
    assert found.errors[0].message.startswith("unknown leg 'A6' in gait up")
    titles = [title for title, _ in fixes]
    assert titles == ["Change to 'L6'", "Declare leg A6 health 3"]
    for title, edited in fixes:
        assert _checks(edited), title
    declared = dict(fixes)["Declare leg A6 health 3"]
    assert declared.splitlines()[2] == "leg A6 health 3"  # after the legs statement


def test_a_fix_that_the_checker_refuses_is_not_offered() -> None:
    """L1 is the closest leg to L11, but the gait uses L1 already: no "Change to 'L1'"."""
    for uses in ("L1, L11", "L11, L1"):  # the error is at the second L1 either way
        text = MAP.replace("gait up uses L1, L3", f"gait up uses {uses}")
        _, fixes = _fixes(text)
        titles = [title for title, _ in fixes]
        assert "Change to 'L1'" not in titles and "Declare leg L11 health 3" in titles
        assert all(_checks(edited) for _, edited in fixes)
    # a second goal is an error too: r8 is a goal already
    _, fixes = _fixes(MAP.replace("visit r8", "visit r8, r88"))
    assert "Change to 'r8'" not in [title for title, _ in fixes]


def test_an_unknown_gait_and_an_unknown_region_are_replaced_by_valid_names() -> None:
    _, fixes = _fixes(MAP + "edge r0 -> r8 by fwdd\n")
    assert [title for title, _ in fixes][:1] == ["Change to 'fwd'"]
    assert all(_checks(edited) for _, edited in fixes)
    _, fixes = _fixes(MAP.replace("visit r8", "visit r48"))
    titles = [title for title, _ in fixes]
    assert titles == ["Change to 'r8'"]  # as close, r4 is blocked
    assert all(_checks(edited) for _, edited in fixes)


def test_other_errors_have_no_name_fix() -> None:
    found = analyse(MAP + "cache r0\n", "twice.gait")
    [error] = found.errors
    assert "a cache twice" in error.message and quick_fixes(found, error) == []


# ---------------------------------------------------------------------- over LSP
@pytest_lsp.fixture(config=ClientServerConfig(server_command=[sys.executable, "-m", "gaitc",
                                                               "lsp"]))
async def client(lsp_client: LanguageClient):  # type: ignore[no-untyped-def]
    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=types.ClientCapabilities()))
    yield
    await lsp_client.shutdown_session()


async def _open(client: LanguageClient, path: Path, text: str) -> str:
    uri = path.as_uri()
    client.text_document_did_open(types.DidOpenTextDocumentParams(text_document=(
        types.TextDocumentItem(uri=uri, language_id="gait", version=1, text=text))))
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    return uri


async def _complete_at_end(client: LanguageClient, uri: str, text: str) -> list[str]:
    """Change the document to ``text`` and complete at its end."""
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))
    await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    lines = text.split("\n")
    found = await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(line=len(lines) - 1, character=len(lines[-1]))))
    items = found.items if isinstance(found, types.CompletionList) else found or []
    return [item.label for item in items]


@pytest.mark.asyncio
async def test_the_server_completes_cache_without_blocked_cells(
        client: LanguageClient, tmp_path: Path) -> None:
    uri = await _open(client, tmp_path / "map.gait", MAP)
    offered = await _complete_at_end(client, uri, MAP + "cache ")
    assert offered == ["r1", "r3", "r5", "r7", "r8"]


@pytest.mark.asyncio
async def test_the_server_completes_uses_with_legs_only(client: LanguageClient,
                                                        tmp_path: Path) -> None:
    uri = await _open(client, tmp_path / "map.gait", MAP)
    assert await _complete_at_end(client, uri, MAP + "gait g uses L3, ") == ["L1", "L2", "L4"]


@pytest.mark.asyncio
@pytest.mark.parametrize(("old", "new", "fixed"), [
    ("gait up uses L1, L3", "gait up uses L1, A6", "Declare leg A6 health 3"),
    ("visit r8", "visit r88", "Change to 'r8'"),
    ("cache r0\n", "cache r0\nedge r0 -> r8 by dwn\n", "Change to 'down'"),
])
async def test_the_server_offers_fixes_the_checker_accepts(
        client: LanguageClient, tmp_path: Path, old: str, new: str, fixed: str) -> None:
    text = MAP.replace(old, new)
    uri = await _open(client, tmp_path / "typo.gait", text)
    [diagnostic] = client.diagnostics[uri]
    assert diagnostic.message.startswith("unknown ")
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), range=diagnostic.range,
        context=types.CodeActionContext(diagnostics=[diagnostic])))
    fixes = [a for a in actions or [] if isinstance(a, types.CodeAction)]
    assert fixed in [a.title for a in fixes]
    assert fixes[0].is_preferred
    for action in fixes:
        assert action.edit is not None and action.edit.changes is not None
        assert _checks(_apply(text, action.edit.changes[uri])), action.title


def _apply(text: str, edits: list[types.TextEdit]) -> str:
    lines = text.split("\n")
    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character),
                       reverse=True):
        start, end = edit.range.start, edit.range.end
        head = lines[start.line][:start.character]
        tail = lines[end.line][end.character:]
        lines[start.line:end.line + 1] = (head + edit.new_text + tail).split("\n")
    return "\n".join(lines)
