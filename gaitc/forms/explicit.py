"""The explicit form: an automaton whose every node is listed (``docs/controller-format.md``).

Two file layouts hold it.  The tables layout (names ending in ``.gz``) is gzip-compressed
JSON that stores each distinct state valuation once, nodes as columns of indices and
successor lists, and a SHA-256 digest of its contents; SLUGS's JSON (``slugs
--explicitStrategy --jsonOutput``, with gaitc's additions) is written for other names, for
interchange.  :func:`read_tables` reads the first back with messages that name the file and
what is wrong; the second is read by :mod:`gaitc.ir.controller`.

Its compact form is built through the symbolic one: per goal j, the relation of the moves
the automaton makes from its nodes of rank j (the goal each node pursues), the winning
region the states its nodes hold.  A runtime of those relations picks, as the explicit
extraction does, one move per state, input and goal, so an automaton that keeps one node
per state and goal (the embedded solver's and SLUGS's) keeps its moves; any other is
refused by the proof the caller runs on the result.
"""

from __future__ import annotations

import hashlib
import json
import struct
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Final, NoReturn

from gaitc.compact.extraction import compact_from_symbolic
from gaitc.core.modes import Form, Semantics
from gaitc.diagnostics import ControllerError, Span
from gaitc.diagnostics.choices import Choice
from gaitc.diagnostics.versions import FileFormat
from gaitc.forms.base import ControllerForm
from gaitc.ir.bddfile import SymbolicController, node_table
from gaitc.ir.controller import (
    KINDS,
    Controller,
    ControllerKind,
    ControllerNode,
    controller_from_dict,
    controller_to_json,
    integers_from_json,
    integers_to_json,
)
from gaitc.ir.spec import SEMANTICS
from gaitc.sim.strategy import strategy_from_controller
from gaitc.solver.canonical import spec_integers
from gaitc.solver.symbolic import SymbolicSpec
from gaitc.verifier.counterstrategy import verify_counterstrategy
from gaitc.verifier.strategy import verify as verify_strategy

if TYPE_CHECKING:
    from gaitc.compact.controller import CompactController
    from gaitc.core.spec import Spec
    from gaitc.ir.bddfile import SymbolicController
    from gaitc.sim.view import StrategyView
    from gaitc.verifier.strategy import VerificationReport


class Layout(Choice):
    """How an explicit controller is laid out on disk."""

    #: gzip-compressed JSON of shared tables, with a digest (for a name ending in .gz).
    TABLES = "tables"
    #: SLUGS's explicit-strategy JSON with gaitc's additions, for interchange.
    SLUGS_JSON = "slugs-json"


#: ``gaitc.format`` of the tables layout.
TABLES_FORMAT: Final = "explicit-tables"
#: The tables layout's version (``gaitc.version``).
TABLES: Final = FileFormat("explicit controller file (tables layout)", 1)
#: The first bytes of every gzip stream, by which a reader tells the tables layout.
GZIP_MAGIC: Final = b"\x1f\x8b"
#: The gzip header of a tables file (RFC 1952): deflate, no time stamp, and a comment
#: that ends the file's first line, so that ``head -1`` and an error's excerpt say what
#: the file is.
GZIP_HEADER: Final = (GZIP_MAGIC + b"\x08\x10" + b"\0\0\0\0" + b"\x00\xff"
                      + b"gaitc explicit controller, tables layout: gzip-compressed JSON "
                        b"('zcat FILE' shows it; docs/controller-format.md)\n\0")
#: The most text a tables file may unpack to (a hand-made file must not fill the memory).
MAX_TEXT: Final = 1 << 30
#: The most a tables file may unpack to per byte of the file. The tables gaitc writes
#: unpack to 7 to 11 times their size (radial8: 49 KB to 355 KB; a six-legged robot's
#: 9,266 nodes: 96 KB to 1.0 MB), where deflate can reach about 1,000 times: a file past
#: this ratio (beyond :data:`MIN_LIMIT`) was made to fill the memory, and reading stops
#: as soon as it passes it, not after unpacking it all.
MAX_RATIO: Final = 64
MIN_LIMIT: Final = 1 << 20
_CHUNK: Final = 1 << 16
_HINT: Final = "write it again with 'gaitc synth -o FILE'"


def layout_for(path: str | Path) -> Layout:
    """The layout a file name asks for: the tables layout for a name ending in ``.gz``
    (``robot.ctl.gz``), SLUGS's JSON for any other, as before the tables existed: every
    reader takes both (:func:`gaitc.forms.reader.read_document`), but a ``robot.json``
    that is gzip would surprise its user and any tool that reads SLUGS's JSON."""
    return Layout.TABLES if str(path).lower().endswith(".gz") else Layout.SLUGS_JSON


class ExplicitForm(ControllerForm):
    """An explicit Mealy automaton (or an environment's counter-strategy)."""

    form: ClassVar[Form] = Form.EXPLICIT

    def owns(self, automaton: object) -> bool:
        return isinstance(automaton, Controller)

    def recognises(self, data: Any) -> bool:
        return True  # a file that names no other form (the registry asks the others first)

    def parse(self, data: Any, file: str, spec: Spec) -> Controller:
        if is_tables(data):
            return controller_from_tables(data, file)
        return controller_from_dict(data, file, spec.gr1)

    def to_json(self, automaton: Controller) -> str:
        return controller_to_json(automaton)

    def to_file(self, automaton: Controller, path: str | Path, layout: str | None = None
                ) -> str | bytes:
        chosen = layout_for(path) if layout is None else Layout.parse(layout, "file layout")
        if chosen == Layout.SLUGS_JSON:
            return controller_to_json(automaton)
        return tables_bytes(automaton)

    def verify(self, spec: Spec, automaton: Controller, semantics: Semantics
               ) -> VerificationReport:
        if automaton.kind == ControllerKind.COUNTERSTRATEGY:

            return verify_counterstrategy(spec.gr1, automaton, semantics)

        return verify_strategy(spec.gr1, automaton, semantics)

    def runtime(self, spec: Spec, automaton: Controller, file: str = "") -> StrategyView:
        return strategy_from_controller(automaton, spec.gr1, file)

    def size(self, automaton: Controller) -> str:
        return f"{len(automaton.nodes)} nodes"

    def size_json(self, automaton: Controller) -> dict[str, Any]:
        return {"nodes": len(automaton.nodes)}

    def to_compact(self, spec: Spec, automaton: Controller) -> CompactController:
        if automaton.kind == ControllerKind.COUNTERSTRATEGY:
            raise ControllerError(
                "a counter-strategy has no compact form: it is the environment's plan, not "
                "a controller a robot runs", Span("<controller>", 1, 1))
        return compact_from_symbolic(symbolic_of_explicit(spec, automaton), spec.vocabulary)


# ---------------------------------------------------------------- the tables layout
def tables_document(c: Controller) -> dict[str, Any]:
    """The JSON object of the tables layout of ``c``, without its digest: each distinct
    state once (in order of first use), and per node its state's index, rank and sorted
    successors, as three columns."""
    index: dict[tuple[int, ...], int] = {}
    states: list[str] = []
    column: list[int] = []
    for node in c.nodes:
        found = index.get(node.state)
        if found is None:
            found = index[node.state] = len(states)
            states.append("".join("1" if b else "0" for b in node.state))
        column.append(found)
    head: dict[str, Any] = {
        "format": TABLES_FORMAT, "version": TABLES.version, "solver": c.solver,
        "semantics": str(c.semantics), "kind": str(c.kind), "slugs": c.slugs_version,
        "inputs": list(c.inputs), "outputs": list(c.outputs),
        "integers": integers_to_json(c.integers)}
    if c.source is not None:
        head["source"] = dict(c.source)
    return {"gaitc": head, "variables": list(c.variables), "states": states,
            "nodes": {"state": column, "rank": [n.rank for n in c.nodes],
                      "trans": [list(n.trans) for n in c.nodes]},
            "initial": list(c.initial)}


def _canonical(document: dict[str, Any]) -> bytes:
    """The bytes the digest covers: ``document`` as JSON, keys sorted, no spaces."""
    return json.dumps(document, sort_keys=True, separators=(",", ":")).encode("ascii")


def tables_bytes(c: Controller) -> bytes:
    """The file of ``c`` in the tables layout: gzip of its canonical JSON text with a
    ``digest`` key added (the same controller gives the same bytes)."""
    document = tables_document(c)
    document["digest"] = "sha256:" + hashlib.sha256(_canonical(document)).hexdigest()
    text = _canonical(document) + b"\n"
    pack = zlib.compressobj(6, zlib.DEFLATED, -zlib.MAX_WBITS)
    return (GZIP_HEADER + pack.compress(text) + pack.flush()
            + struct.pack("<II", zlib.crc32(text), len(text) & 0xFFFFFFFF))


def is_tables(data: Any) -> bool:
    """Whether a parsed controller file is in the tables layout."""
    extras = data.get("gaitc") if isinstance(data, dict) else None
    return isinstance(extras, dict) and extras.get("format") == TABLES_FORMAT


def _fail(file: str, message: str, hint: str = _HINT) -> NoReturn:
    raise ControllerError(message, Span(file, 1, 1), hint=hint)


def unpacked_limit(packed: int) -> int:
    """The most text a tables file of ``packed`` bytes may unpack to."""
    return min(MAX_TEXT, max(MIN_LIMIT, MAX_RATIO * packed))


def read_tables(raw: bytes, file: str) -> Any:
    """The parsed JSON of a tables file's bytes ``raw``; a file cut short, damaged,
    followed by other bytes or not JSON inside is a :class:`ControllerError` that says
    where (a byte offset of the file, or a line and column of the text inside)."""
    unpack = zlib.decompressobj(zlib.MAX_WBITS | 16)  # gzip, its CRC and length checked
    parts: list[bytes] = []
    size = 0
    limit = unpacked_limit(len(raw))
    for start in range(0, len(raw), _CHUNK):
        try:
            part = unpack.decompress(raw[start:start + _CHUNK], limit + 1 - size)
        except zlib.error as err:
            if "check" in str(err):  # the CRC-32 or the length of the gzip trailer
                _fail(file, "the unpacked data does not match the checksum at the end of "
                      "the file: some of its bytes were changed after it was written")
            _fail(file, f"the compressed data is damaged in bytes {start} to "
                  f"{min(start + _CHUNK, len(raw)) - 1} of {len(raw)} ({err}); the file "
                  "was changed or not copied whole")
        size += len(part)
        if size > limit or unpack.unconsumed_tail:
            _fail(file, f"it unpacks to more than {limit} bytes ({MAX_RATIO} times its "
                  f"{len(raw)} bytes, at most {MAX_TEXT}), more than any controller gaitc "
                  "writes: it was not written by gaitc")
        parts.append(part)
        if unpack.eof:
            break
    if not unpack.eof:
        _fail(file, f"the file ends after {len(raw)} bytes, inside its compressed data: it "
              "was cut short (a copy or a write that did not finish)")
    if unpack.unused_data:
        extra = len(unpack.unused_data)
        _fail(file, f"{extra} bytes follow the end of the compressed data at byte "
              f"{len(raw) - extra}; a tables file is one gzip stream")
    try:
        text = b"".join(parts).decode("utf-8")
        return json.loads(text)
    except UnicodeDecodeError as err:
        _fail(file, f"the unpacked text is not UTF-8 (byte {err.start})")
    except json.JSONDecodeError as err:
        _fail(file, f"the unpacked text is not valid JSON at line {err.lineno}, column "
              f"{err.colno}: {err.msg}")
    except (RecursionError, ValueError) as err:
        _fail(file, f"the unpacked text is not a controller: {err}")


def _is_index(value: Any, count: int) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and 0 <= value < count


def _list_of(value: Any, test: Callable[[Any], bool]) -> bool:
    return isinstance(value, list) and all(test(v) for v in value)


def controller_from_tables(data: Any, file: str = "<controller>") -> Controller:
    """The controller of a parsed tables file, every table checked against the others and
    the digest against the contents; the first problem is a :class:`ControllerError`
    naming the key (and the node or state) where it is."""
    def need(ok: bool, message: str) -> None:
        if not ok:
            _fail(file, message)

    need(isinstance(data, dict), "a controller file must hold one JSON object")
    head = data.get("gaitc")
    need(isinstance(head, dict), "'gaitc' must be an object")
    TABLES.check(head.get("version"), Span(file, 1, 1), ControllerError)
    digest = data.get("digest")
    need(isinstance(digest, str) and digest.startswith("sha256:"),
         "'digest' must be 'sha256:' and the SHA-256 of the contents")
    body = {k: v for k, v in data.items() if k != "digest"}
    if "sha256:" + hashlib.sha256(_canonical(body)).hexdigest() != digest:
        _fail(file, "the digest does not match the contents: the file was changed after "
              "gaitc wrote it (by hand, or by a program that kept the old digest)",
              hint="write it again with 'gaitc synth -o FILE'; to edit a controller by "
                   "hand, write it as SLUGS JSON (a name ending in .json)")
    variables = data.get("variables")
    need(_list_of(variables, lambda v: isinstance(v, str)) and len(set(variables)) ==
         len(variables), "'variables' must list distinct bit names")
    names = tuple(variables)
    raw_in, raw_out = head.get("inputs"), head.get("outputs")
    for key, value in (("inputs", raw_in), ("outputs", raw_out)):
        need(_list_of(value, lambda v: isinstance(v, str)),
             f"'gaitc.{key}' must be a list of bit names")
    need(set(raw_in) | set(raw_out) == set(names) and not set(raw_in) & set(raw_out),
         "'gaitc.inputs' and 'gaitc.outputs' must split 'variables' between the players")
    kind, semantics = head.get("kind"), head.get("semantics")
    need(kind in KINDS, f"'gaitc.kind' must be one of {', '.join(KINDS)}")
    need(semantics in SEMANTICS, f"'gaitc.semantics' must be one of {', '.join(SEMANTICS)}")
    source = head.get("source")
    need(source is None or isinstance(source, dict), "'gaitc.source' must be an object")
    integers = integers_from_json(head.get("integers", {}), set(names), need)
    width = len(names)
    states = data.get("states")
    need(isinstance(states, list), "'states' must list the state valuations")
    table: list[tuple[int, ...]] = []
    for k, bits in enumerate(states):
        need(isinstance(bits, str) and len(bits) == width and not bits.strip("01"),
             f"state {k} must be a string of {width} characters 0 or 1, one per variable")
        table.append(tuple(1 if b == "1" else 0 for b in bits))
    nodes = data.get("nodes")
    need(isinstance(nodes, dict), "'nodes' must be an object of three columns: 'state', "
         "'rank' and 'trans'")
    column, ranks, trans = nodes.get("state"), nodes.get("rank"), nodes.get("trans")
    need(isinstance(column, list), "'nodes.state' must list each node's state index")
    count = len(column)
    for key, value in (("rank", ranks), ("trans", trans)):
        need(isinstance(value, list) and len(value) == count,
             f"'nodes.{key}' must have one entry per node ({count}, as 'nodes.state')")
    built: list[ControllerNode] = []
    for k in range(count):
        state, rank, succ = column[k], ranks[k], trans[k]
        need(_is_index(state, len(table)),
             f"node {k}: its state index must be one of 0..{len(table) - 1}, not {state!r}")
        need(isinstance(rank, int) and not isinstance(rank, bool),
             f"node {k}: its rank must be an integer, not {rank!r}")
        need(_list_of(succ, lambda t: _is_index(t, count)),
             f"node {k}: its successors must be node indices 0..{count - 1}")
        built.append(ControllerNode(rank, table[state], tuple(sorted(set(succ)))))
    initial = data.get("initial")
    need(_list_of(initial, lambda t: _is_index(t, count)),
         f"'initial' must list node indices 0..{count - 1}")
    return Controller(
        variables=names, inputs=tuple(raw_in), outputs=tuple(raw_out), nodes=tuple(built),
        initial=tuple(initial), integers=integers, kind=ControllerKind(kind),
        solver=str(head.get("solver", "embedded")), semantics=Semantics(semantics),
        source=None if source is None else dict(source),
        slugs_version=str(head.get("slugs", "0.0.1")))


# ---------------------------------------------------------------- as BDD relations
def symbolic_of_explicit(spec: Spec, automaton: Controller) -> SymbolicController:
    """The explicit automaton as BDD relations, one per goal (see the module's text)."""
    sym = SymbolicSpec(spec.gr1)
    bdd = sym.bdd
    names = automaton.variables

    def cube(node: int, primed: bool) -> Any:
        bits = automaton.bit_values(node)
        return bdd.cube({(n + "'" if primed else n): bool(bits[n]) for n in names})

    goals = len(sym.sys_live)
    strategies = [bdd.false] * goals
    winning = bdd.false
    for k, node in enumerate(automaton.nodes):
        here = cube(k, primed=False)
        winning |= here
        moves = bdd.false
        for succ in node.trans:
            moves |= cube(succ, primed=True)
        rank = node.rank % goals
        strategies[rank] |= here & moves
    roots = {"winning": winning, "env_init": sym.env_init, "sys_init": sym.sys_init,
             "env_trans": sym.env_trans, "goals": list(sym.sys_live),
             "strategies": strategies}
    order, nodes, refs = node_table(bdd, roots)
    return SymbolicController(
        inputs=tuple(sym.input_bits), outputs=tuple(sym.output_bits), order=order,
        nodes=nodes, roots=refs, integers=spec_integers(sym), semantics=automaton.semantics,
        solver=automaton.solver, source=automaton.source,
        choice=tuple(sorted(sym.input_bits + sym.output_bits,
                            key=sym.choice_rank.__getitem__)))
