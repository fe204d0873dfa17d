"""When each open document is analysed: one analysis at a time, of the latest text only.

An edit records the document's text and schedules its analysis after a short debounce.
Each document has at most one analysis running, in a thread of its own, and at most one
waiting: its latest text, which supersedes every edit before it, so a burst of edits costs
one analysis after the one under way and memory does not grow with the burst. The result
of a superseded analysis is dropped, never published; every other result (an internal
error included, see :func:`gaitc.lsp.analysis.analyse`) is stored and published, and the
requests waiting for it are answered. Everything but the analysis itself happens on the
request loop, so the documents need no lock.
"""

from __future__ import annotations

import asyncio
import contextlib
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from pygls.uris import to_fs_path

from gaitc.lsp.actions import RepairEdit
from gaitc.lsp.analysis import Analysis, Finding, analyse, internal_error, primitive_findings
from gaitc.lsp.positions import Lines

DEBOUNCE = 0.05  # seconds of quiet after an edit before the analysis starts


@dataclass
class Document:
    """An open document: its latest text and version, and the latest analysis stored."""

    uri: str
    path: str
    text: str = ""
    version: int = 0
    analysis: Analysis | None = None
    lines: Lines = field(default_factory=lambda: Lines(""))  # of the analysed text
    repairs: list[RepairEdit] = field(default_factory=list)
    repairs_for: str | None = None  # the text the repairs were found for
    ready: asyncio.Event = field(default_factory=asyncio.Event)  # the latest text analysed
    waiting: bool = False  # the latest text waits for an analysis
    timer: asyncio.TimerHandle | None = None  # the debounce under way


@dataclass
class Job:
    """One analysis: the text of one version, and whether a newer one has superseded it."""

    uri: str
    path: str
    version: int
    text: str
    previous: Analysis | None
    superseded: threading.Event = field(default_factory=threading.Event)


class Scheduler:
    """The open documents and their analyses. Its methods run on the request loop;
    ``publish`` is called there with a document and the findings of its latest version,
    ``trace`` with a sentence on each analysis started, dropped or finished."""

    def __init__(self, publish: Callable[[Document, list[Finding]], None],
                 trace: Callable[[str], None], debounce: float = DEBOUNCE) -> None:
        self.documents: dict[str, Document] = {}
        self.running: dict[str, Job] = {}  # by URI: a closed document's job runs to its end
        self._publish = publish
        self._trace = trace
        self._debounce = debounce
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stopped = False

    # ------------------------------------------------------------------ the editor's side
    def edit(self, uri: str, text: str, version: int) -> Document:
        """Record ``text`` as version ``version`` of ``uri`` (opening it if need be) and
        schedule its analysis; an analysis under way of an older version is superseded."""
        self._loop = asyncio.get_running_loop()
        doc = self.documents.get(uri)
        if doc is None:
            doc = self.documents[uri] = Document(uri, to_fs_path(uri) or uri)
        doc.text, doc.version, doc.waiting = text, version, True
        doc.ready.clear()
        job = self.running.get(uri)
        if job is not None and job.version != version:
            job.superseded.set()
        if doc.timer is not None:
            doc.timer.cancel()
        doc.timer = self._loop.call_later(self._debounce, self._due, doc)
        return doc

    def close(self, uri: str) -> None:
        """Forget ``uri``: its pending analysis is not started, its running one dropped."""
        doc = self.documents.pop(uri, None)
        if doc is not None and doc.timer is not None:
            doc.timer.cancel()
        job = self.running.get(uri)
        if job is not None:
            job.superseded.set()

    async def current(self, uri: str, wait: float) -> Document | None:
        """The document at ``uri`` once its latest text is analysed, waiting at most
        ``wait`` seconds (then with the latest analysis stored); None when it is not open
        or has never been analysed."""
        doc = self.documents.get(uri)
        if doc is None:
            return None
        if not doc.ready.is_set():
            with contextlib.suppress(asyncio.TimeoutError):
                await asyncio.wait_for(doc.ready.wait(), wait)
        doc = self.documents.get(uri)
        return doc if doc is not None and doc.analysis is not None else None

    def stop(self) -> None:
        """Start no more analyses, drop the results of those under way, and let go of
        every document now: the interpreter's own teardown of the syntax trees and models
        of a large document takes seconds where freeing them here takes a tenth."""
        self._stopped = True
        for doc in self.documents.values():
            if doc.timer is not None:
                doc.timer.cancel()
        for job in self.running.values():
            job.superseded.set()
        self.documents.clear()

    # ------------------------------------------------------------------ the analyses
    def _due(self, doc: Document) -> None:
        doc.timer = None
        if self.documents.get(doc.uri) is doc:
            self._start(doc)

    def _start(self, doc: Document) -> None:
        """Analyse ``doc``'s latest text, unless an analysis of its URI is running: that
        one starts the next when it ends."""
        if self._stopped or not doc.waiting or doc.uri in self.running:
            return
        job = Job(doc.uri, doc.path, doc.version, doc.text, doc.analysis)
        doc.waiting = False
        self.running[doc.uri] = job
        self._trace(f"analysis of {doc.uri} version {job.version} started")
        threading.Thread(target=self._work, args=(job,), name="gaitc-lsp-analysis",
                         daemon=True).start()

    def _work(self, job: Job) -> None:
        """In the job's thread: analyse, hand the result to the loop, then (unless
        superseded meanwhile) the valve primitives' findings, then the end."""
        found: Analysis | None = None
        try:
            found = analyse(job.text, job.path, job.previous)
            job.previous = None
            self._hand(self._analysed, job, found, Lines(job.text))
            if found.model is not None and not job.superseded.is_set():
                extra = primitive_findings(found)
                if extra:
                    self._hand(self._extended, job, found, extra)
        except BaseException as err:  # both say their own failures: this is a last resort
            said = internal_error(err, job.path, "analysing the file")
            if found is None:
                found = Analysis(job.text, job.path, findings=[said])
                self._hand(self._analysed, job, found, Lines(job.text))
            else:
                self._hand(self._extended, job, found, [said])
        finally:
            self._hand(self._finished, job)

    def _hand(self, callback: Callable[..., None], *args: Any) -> None:
        """Run ``callback(*args)`` on the loop (dropped once the loop has closed)."""
        loop = self._loop
        if loop is None:
            return
        with contextlib.suppress(RuntimeError):  # the loop has closed: the server is ending
            loop.call_soon_threadsafe(callback, *args)

    def _current(self, job: Job) -> Document | None:
        """The document ``job`` is still the latest analysis of, else None."""
        doc = self.documents.get(job.uri)
        if doc is None or self.running.get(job.uri) is not job or job.superseded.is_set() \
                or doc.version != job.version:
            return None
        return doc

    def _analysed(self, job: Job, found: Analysis, lines: Lines) -> None:
        doc = self._current(job)
        if doc is None:
            self._trace(f"analysis of {job.uri} version {job.version} dropped: superseded")
            return
        doc.analysis, doc.lines = found, lines
        doc.ready.set()
        self._trace(f"analysis of {job.uri} version {job.version} published")
        self._publish(doc, list(found.findings))

    def _extended(self, job: Job, found: Analysis, extra: list[Finding]) -> None:
        doc = self._current(job)
        if doc is None or doc.analysis is not found:
            return
        found.findings.extend(extra)
        self._publish(doc, list(found.findings))

    def _finished(self, job: Job) -> None:
        if self.running.get(job.uri) is job:
            del self.running[job.uri]
        self._trace(f"analysis of {job.uri} version {job.version} ended")
        doc = self.documents.get(job.uri)
        if doc is not None and doc.timer is None:
            self._start(doc)
