"""Explicit controllers (Mealy strategies and counter-strategies) and their JSON file format.

The layout is a superset of ``slugs --explicitStrategy --jsonOutput`` (see
``docs/controller-format.md``); :func:`load_controller` reads either, :func:`controller_to_json`
writes it deterministically.
"""

from __future__ import annotations

import html
import json
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Final

from gaitc.diagnostics import ControllerError, Span, span_at
from gaitc.diagnostics.files import decode_text, read_input
from gaitc.diagnostics.versions import CONTROLLER
from gaitc.ir.bits import cut_integers, integer_bits, spec_bits
from gaitc.ir.spec import SEMANTICS, GR1Spec, Semantics
from gaitc.ir.spec import ControllerKind as ControllerKind

KINDS: Final = ControllerKind.values()
#: ``gaitc.format`` of a symbolic controller file (:mod:`gaitc.ir.bddfile`).
SYMBOLIC_FORMAT = "symbolic-strategy"


@dataclass(frozen=True)
class IntegerVar:
    """An integer variable stored little-endian in ``bits`` (value = ``low`` + unsigned bits)."""

    low: int
    high: int
    bits: tuple[str, ...]
    owner: str  # "env" or "sys"


@dataclass(frozen=True)
class ControllerNode:
    """One automaton node: the goal index it pursues, its bit vector, its successors."""

    rank: int
    state: tuple[int, ...]
    trans: tuple[int, ...]


@dataclass(frozen=True)
class Controller:
    """An explicit automaton over the bits in ``variables``; node ``k`` is ``nodes[k]``."""

    variables: tuple[str, ...]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    nodes: tuple[ControllerNode, ...]
    initial: tuple[int, ...]
    integers: Mapping[str, IntegerVar] = field(default_factory=dict)
    kind: ControllerKind = ControllerKind.STRATEGY
    solver: str = "embedded"
    semantics: Semantics = Semantics.DEFAULT
    source: Mapping[str, str] | None = None
    slugs_version: str = "0.0.1"

    def __repr__(self) -> str:
        source = f" for {self.source['file']!r}" if self.source and "file" in self.source else ""
        return (f"<Controller {self.kind}{source}: {len(self.nodes)} nodes, "
                f"{len(self.initial)} initial, {len(self.inputs)} input and "
                f"{len(self.outputs)} output bits, {self.semantics} semantics, "
                f"{self.solver} solver>")

    def _repr_html_(self) -> str:
        rows = [("kind", self.kind), ("nodes", str(len(self.nodes))),
                ("initial nodes", str(len(self.initial))),
                ("edges", str(sum(len(n.trans) for n in self.nodes))),
                ("inputs", ", ".join(self.inputs)), ("outputs", ", ".join(self.outputs)),
                ("semantics", self.semantics), ("solver", self.solver)]
        body = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
                       f"<td>{html.escape(v)}</td></tr>" for k, v in rows)
        return f"<table><caption>explicit {html.escape(self.kind)}</caption>{body}</table>"

    def bit_values(self, node: int) -> dict[str, int]:
        """The bits of ``node`` by name."""
        return dict(zip(self.variables, self.nodes[node].state, strict=True))

    def values(self, node: int) -> dict[str, int]:
        """``node`` decoded: Booleans as 0/1 under their names, integers by value."""
        bits = self.bit_values(node)
        in_integer = {b for iv in self.integers.values() for b in iv.bits}
        out = {name: v for name, v in bits.items() if name not in in_integer}
        for name, iv in self.integers.items():
            out[name] = iv.low + sum(bits[b] << k for k, b in enumerate(iv.bits))
        return out

    def successors(self, node: int) -> tuple[int, ...]:
        return self.nodes[node].trans


def integers_to_json(integers: Mapping[str, IntegerVar]) -> dict[str, Any]:
    """The ``gaitc.integers`` object every controller file carries, sorted by name."""
    return {name: {"low": iv.low, "high": iv.high, "bits": list(iv.bits), "owner": iv.owner}
            for name, iv in sorted(integers.items())}


def integers_from_json(value: Any, bits: set[str],
                       need: Callable[[bool, str], None]) -> dict[str, IntegerVar]:
    """Read a ``gaitc.integers`` object, calling ``need(ok, message)`` on each check (the
    caller's reader raises with its own words)."""
    need(isinstance(value, dict), "'gaitc.integers' must be an object")
    out: dict[str, IntegerVar] = {}
    for name, raw in value.items():
        ok = (isinstance(raw, dict) and _is_int(raw.get("low")) and _is_int(raw.get("high"))
              and raw["low"] <= raw["high"] and raw.get("owner") in ("env", "sys")
              and isinstance(raw.get("bits"), list) and raw["bits"]
              and all(isinstance(b, str) and b in bits for b in raw["bits"]))
        need(bool(ok), f"'gaitc.integers.{name}' must give low <= high, its bits and owner")
        out[str(name)] = IntegerVar(raw["low"], raw["high"], tuple(raw["bits"]), raw["owner"])
    return out


def _is_int(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def integers_of(bit_names: tuple[str, ...], inputs: frozenset[str]) -> dict[str, IntegerVar]:
    """Recognise SLUGS integer encodings (``x@0.MIN.MAX``, ``x@1``, ...) among bit names."""
    return {name: IntegerVar(low, high, bits, "env" if bits[0] in inputs else "sys")
            for name, (low, high, bits) in cut_integers(bit_names).items()}


def spec_integers(spec: GR1Spec) -> dict[str, IntegerVar]:
    """The integer variables of ``spec`` as its controllers lay them out: each declared
    integer on its SLUGS bits, and SLUGS-encoded bit groups among its Boolean names."""
    ins, outs = spec_bits(spec)
    found = integers_of(ins + outs, frozenset(ins))
    for owner, variables in (("env", spec.inputs), ("sys", spec.outputs)):
        for v in variables:
            if v.low is not None and v.high is not None:
                found[v.name] = IntegerVar(v.low, v.high, tuple(integer_bits(v)), owner)
    return found


# ---------------------------------------------------------------- writing
def controller_to_dict(c: Controller) -> dict[str, Any]:
    """The JSON object of ``c`` (see docs/controller-format.md)."""
    extras: dict[str, Any] = {
        "format": CONTROLLER.version,
        "solver": c.solver,
        "semantics": c.semantics,
        "kind": c.kind,
        "inputs": list(c.inputs),
        "outputs": list(c.outputs),
        "integers": integers_to_json(c.integers),
        "initial": list(c.initial),
        "values": {str(k): c.values(k) for k in range(len(c.nodes))},
    }
    if c.source is not None:
        extras["source"] = dict(c.source)
    return {
        "version": 0,
        "slugs": c.slugs_version,
        "variables": list(c.variables),
        "nodes": {
            str(k): {"rank": n.rank, "state": list(n.state), "trans": list(n.trans)}
            for k, n in enumerate(c.nodes)
        },
        "gaitc": extras,
    }


def _dump(value: Any, depth: int, level: int = 0) -> str:
    """JSON with objects expanded down to ``depth`` levels and everything deeper on one line."""
    if isinstance(value, dict) and value and depth > 0:
        pad = " " * (level + 1)
        items = [
            f"{pad}{json.dumps(k)}: {_dump(v, depth - 1, level + 1)}" for k, v in value.items()
        ]
        return "{\n" + ",\n".join(items) + "\n" + " " * level + "}"
    return json.dumps(value, sort_keys=True)


def controller_to_json(c: Controller) -> str:
    """Deterministic JSON text of ``c`` (one node per line), ending in a newline."""
    return _dump(controller_to_dict(c), 2) + "\n"


# ---------------------------------------------------------------- reading
def _need(cond: bool, message: str, span: Span) -> None:
    if not cond:
        raise ControllerError(message, span, hint="regenerate it with 'gaitc synth -o FILE'")


def controller_from_dict(
    data: Any, filename: str = "<controller>", spec: GR1Spec | None = None
) -> Controller:
    """Check and convert a parsed JSON object (``spec`` splits I/O for raw SLUGS files)."""
    span = Span(filename, 1, 1)
    _need(isinstance(data, dict), "a controller file must hold one JSON object", span)
    variables = data.get("variables")
    _need(
        isinstance(variables, list) and all(isinstance(v, str) for v in variables),
        "'variables' must be a list of bit names",
        span,
    )
    raw_nodes = data.get("nodes")
    _need(isinstance(raw_nodes, dict), "'nodes' must be an object mapping node ids to nodes", span)
    count = len(raw_nodes)
    nodes: list[ControllerNode] = []
    for k in range(count):
        raw = raw_nodes.get(str(k))
        _need(raw is not None, f"node ids must be 0..{count - 1}; node {k} is missing", span)
        _need(isinstance(raw, dict), f"node {k} must be an object", span)
        state, trans, rank = raw.get("state"), raw.get("trans"), raw.get("rank", 0)
        _need(
            isinstance(state, list)
            and len(state) == len(variables)
            and all(b in (0, 1) and not isinstance(b, bool) for b in state),
            f"node {k}: 'state' must list one 0/1 value per variable ({len(variables)})",
            span,
        )
        _need(
            isinstance(trans, list)
            and all(
                isinstance(t, int) and not isinstance(t, bool) and 0 <= t < count for t in trans
            ),
            f"node {k}: 'trans' must list node ids between 0 and {count - 1}",
            span,
        )
        _need(isinstance(rank, int) and not isinstance(rank, bool),
              f"node {k}: 'rank' must be an integer", span)
        nodes.append(ControllerNode(rank, tuple(state), tuple(sorted(set(trans)))))
    extras = data.get("gaitc")
    names = tuple(variables)
    if isinstance(extras, dict):
        if "format" in extras:
            CONTROLLER.check(extras["format"], span, ControllerError)
        raw_in, raw_out = extras.get("inputs", ()), extras.get("outputs", ())
        for key, value in (("inputs", raw_in), ("outputs", raw_out)):
            _need(isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value),
                  f"'gaitc.{key}' must be a list of bit names", span)
        inputs, outputs = tuple(raw_in), tuple(raw_out)
        _need(
            set(inputs) | set(outputs) == set(names) and not set(inputs) & set(outputs),
            "'gaitc.inputs' and 'gaitc.outputs' must split 'variables' between the players",
            span,
        )
        initial = extras.get("initial", [])
        _need(
            isinstance(initial, list)
            and all(isinstance(t, int) and not isinstance(t, bool) and 0 <= t < count
                    for t in initial),
            "'gaitc.initial' must list node ids",
            span,
        )
        kind = extras.get("kind", ControllerKind.STRATEGY.value)
        _need(kind in KINDS, f"'gaitc.kind' must be one of {', '.join(KINDS)}", span)
        kind = ControllerKind(kind)
        semantics = extras.get("semantics", "default")
        _need(semantics in SEMANTICS,
              f"'gaitc.semantics' must be one of {', '.join(SEMANTICS)}", span)
        source = extras.get("source")
        return Controller(
            variables=names,
            inputs=inputs,
            outputs=outputs,
            nodes=tuple(nodes),
            initial=tuple(initial),
            integers=integers_of(names, frozenset(inputs)),
            kind=kind,
            solver=str(extras.get("solver", "embedded")),
            semantics=Semantics(str(semantics)),
            source=dict(source) if isinstance(source, dict) else None,
            slugs_version=str(data.get("slugs", "0.0.1")),
        )
    _need(spec is not None, "this SLUGS controller has no 'gaitc' section; give its spec", span)
    assert spec is not None
    ins, outs = spec_bits(spec)
    _need(
        set(ins) | set(outs) == set(names),
        "the controller's variables do not match the specification's inputs and outputs",
        span,
    )
    return Controller(
        variables=names,
        inputs=tuple(n for n in names if n in set(ins)),
        outputs=tuple(n for n in names if n in set(outs)),
        nodes=tuple(nodes),
        initial=(),
        integers=integers_of(names, frozenset(ins)),
        solver="slugs",
        slugs_version=str(data.get("slugs", "0.0.1")),
    )


def read_controller_json(path: str) -> Any:
    """The parsed JSON of a controller file (explicit or symbolic), with positioned errors."""
    return parse_controller_json(read_input(path, "controller file"), path)


def parse_controller_json(raw: bytes, path: str) -> Any:
    """The parsed JSON of the bytes ``raw`` of the controller file ``path``, with positioned
    errors."""
    text = decode_text(raw, path, ControllerError)
    try:
        return json.loads(text)
    except json.JSONDecodeError as err:
        raise ControllerError(
            f"not valid JSON: {err.msg}", span_at(text, path, err.pos)
        ) from None
    except RecursionError:
        raise ControllerError("the JSON nests too deeply to be a controller file",
                              Span(path, 1, 1)) from None
    except ValueError as err:  # e.g. an integer of thousands of digits
        raise ControllerError(f"not a controller file: {err}", Span(path, 1, 1)) from None


def load_controller(path: str, spec: GR1Spec | None = None) -> Controller:
    """Read an explicit controller JSON file; raises :class:`ControllerError` when it is
    malformed or holds a symbolic controller (read those with :mod:`gaitc.ir.bddfile`)."""
    data = read_controller_json(path)
    extras = data.get("gaitc") if isinstance(data, dict) else None
    if isinstance(extras, dict) and extras.get("format") == SYMBOLIC_FORMAT:
        raise ControllerError("this is a symbolic controller, where an explicit automaton is "
                              "needed", Span(path, 1, 1),
                              hint="synthesize an explicit one with 'gaitc synth' (without "
                              "--symbolic)")
    return controller_from_dict(data, path, spec)
