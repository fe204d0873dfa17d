"""How soon the language server shows diagnostics (issue 40), and what an edit burst on a
large document costs it (issue 48).

``gaitc lsp`` runs as a process, as an editor starts it, and pygls's client speaks LSP to
it. For every shipped spec the table gives the time from ``didOpen`` to the first
``publishDiagnostics``, then from ``didChange`` to the diagnostics of that version, over
edits that alternately break the file (a misspelt name at the end) and mend it; the
server's 50 ms debounce is included. The promise is 200 ms.

``--burst`` opens one large document instead (``--size-mb``, 10 by default: the patrol
spec padded with comment lines, or with guarantee statements for ``--shape
statements``), sends ``--edits`` whole-document edits ``--gap`` seconds apart, and waits
for the diagnostics of the last one; the table gives the server's peak resident memory
(with its children, sampled every 20 ms), the analyses it started, the time to the last
diagnostics, and how long the process took to end after ``exit``.
Run: .venv/bin/python bench/bench_lsp.py [--quick] [--edits N]
     .venv/bin/python bench/bench_lsp.py --burst [--size-mb 10] [--shape comments]
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import sys
import time
from pathlib import Path

from lsprotocol import types
from pygls.lsp.client import LanguageClient

ROOT = Path(__file__).resolve().parent.parent
TARGET_MS = 200.0


async def measure(edits: int) -> list[tuple[str, float, list[float], int]]:
    client = LanguageClient("bench", "1")
    arrived: dict[tuple[str, int | None], float] = {}
    event = asyncio.Event()

    @client.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def published(params: types.PublishDiagnosticsParams) -> None:
        arrived.setdefault((params.uri, params.version), time.perf_counter())
        event.set()

    async def wait_for(uri: str, version: int) -> float:
        while (uri, version) not in arrived:
            event.clear()
            await asyncio.wait_for(event.wait(), timeout=30)
        return arrived[(uri, version)]

    await client.start_io(sys.executable, "-m", "gaitc", "lsp")
    await client.initialize_async(types.InitializeParams(capabilities=types.ClientCapabilities()))
    client.initialized(types.InitializedParams())
    rows = []
    for spec in sorted((ROOT / "specs").glob("*.gait")):
        text = spec.read_text(encoding="utf-8")
        uri = spec.as_uri()
        start = time.perf_counter()
        client.text_document_did_open(types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(uri=uri, language_id="gait", version=1,
                                                 text=text)))
        opened = (await wait_for(uri, 1) - start) * 1000
        times = []
        errors = 0
        for version in range(2, edits + 2):
            body = text + ("\nvisit r_missing infinitely often\n" if version % 2 else "")
            start = time.perf_counter()
            client.text_document_did_change(types.DidChangeTextDocumentParams(
                text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
                content_changes=[types.TextDocumentContentChangeWholeDocument(text=body)]))
            times.append((await wait_for(uri, version) - start) * 1000)
            errors += version % 2
            await asyncio.sleep(0.01)
        client.text_document_did_close(types.DidCloseTextDocumentParams(
            text_document=types.TextDocumentIdentifier(uri=uri)))
        rows.append((spec.name, opened, times, errors))
    await client.shutdown_async(None)
    client.exit(None)
    await client.stop()
    return rows


def document(size: int, shape: str) -> str:
    """A valid spec of about ``size`` characters: the patrol padded with comment lines
    (cheap to analyse) or with guarantee statements (each one parsed, checked, lowered)."""
    base = (ROOT / "specs" / "patrol_2x2.gait").read_text(encoding="utf-8")
    line = ("# a long comment line that pads the document to its size, as big files have\n"
            if shape == "comments" else "guarantee always ((sw & !se) -> next(!nw | ne))\n")
    return base + line * max(0, (size - len(base)) // len(line))


async def burst(size: int, shape: str, edits: int, gap: float) -> dict[str, float]:
    import threading

    import psutil

    client = LanguageClient("bench", "1")
    last = edits + 1
    arrived: dict[int | None, float] = {}
    started: list[str] = []
    event = asyncio.Event()

    @client.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    def published(params: types.PublishDiagnosticsParams) -> None:
        arrived.setdefault(params.version, time.perf_counter())
        event.set()

    @client.feature(types.LOG_TRACE)
    def traced(params: types.LogTraceParams) -> None:
        if params.message.endswith("started"):
            started.append(params.message)

    await client.start_io(sys.executable, "-m", "gaitc", "lsp")
    assert client._server is not None
    process = psutil.Process(client._server.pid)
    peak = [0]
    sampling = threading.Event()

    def sample() -> None:
        while not sampling.is_set():
            try:
                rss = process.memory_info().rss + sum(
                    c.memory_info().rss for c in process.children(recursive=True))
            except psutil.Error:
                return
            peak[0] = max(peak[0], rss)
            time.sleep(0.02)

    await client.initialize_async(types.InitializeParams(
        capabilities=types.ClientCapabilities(), trace=types.TraceValue.Verbose))
    client.initialized(types.InitializedParams())
    await asyncio.sleep(1.0)  # the server's warm-up analysis
    before = process.memory_info().rss
    threading.Thread(target=sample, daemon=True).start()
    text = document(size, shape)
    uri = (ROOT / "burst.gait").as_uri()
    start = time.perf_counter()
    client.text_document_did_open(types.DidOpenTextDocumentParams(
        text_document=types.TextDocumentItem(uri=uri, language_id="gait", version=1,
                                             text=text)))
    for version in range(2, last + 1):
        await asyncio.sleep(max(0.0, start + (version - 1) * gap - time.perf_counter()))
        body = text.replace("start nw", f"start nw  # edit {version}")
        client.text_document_did_change(types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=body)]))
    while last not in arrived:
        event.clear()
        await asyncio.wait_for(event.wait(), timeout=3600)
    settled = arrived[last] - start
    await client.shutdown_async(None)
    exiting = time.perf_counter()
    client.exit(None)
    while process.is_running() and process.status() != psutil.STATUS_ZOMBIE:
        await asyncio.sleep(0.01)
    ended = time.perf_counter() - exiting
    sampling.set()
    await client.stop()
    return {"size MB": len(text) / 1e6, "RSS before MB": before / 1e6,
            "peak RSS MB": peak[0] / 1e6, "analyses started": len(started),
            "last diagnostics s": settled, "exit s": ended}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10 edits a spec")
    parser.add_argument("--edits", type=int, default=None,
                        help="edits a spec (40), or edits of the burst (10)")
    parser.add_argument("--burst", action="store_true",
                        help="one large document, edited in a burst (issue 48)")
    parser.add_argument("--size-mb", type=float, default=10.0)
    parser.add_argument("--shape", choices=("comments", "statements"), default="comments")
    parser.add_argument("--gap", type=float, default=0.15, help="seconds between edits")
    args = parser.parse_args()
    if args.burst:
        figures = asyncio.run(burst(int(args.size_mb * 1e6), args.shape,
                                    args.edits or 10, args.gap))
        print(f"| shape | {' | '.join(figures)} |")
        print("|---" * (len(figures) + 1) + "|")
        print(f"| {args.shape} | " + " | ".join(
            f"{v:.0f}" if k == "analyses started" else f"{v:.2f}" if k.endswith(" s")
            else f"{v:.1f}" for k, v in figures.items()) + " |")
        return
    rows = asyncio.run(measure(10 if args.quick else args.edits or 40))
    print("| spec | open → diagnostics ms | edits | edit → diagnostics median ms | worst ms "
          f"| within {TARGET_MS:.0f} ms |")
    print("|---|---|---|---|---|---|")
    for name, opened, times, _errors in rows:
        worst = max(times)
        ok = "yes" if max(worst, opened) <= TARGET_MS else "NO"
        print(f"| {name} | {opened:.1f} | {len(times)} | {statistics.median(times):.1f} | "
              f"{worst:.1f} | {ok} |")


if __name__ == "__main__":
    main()
