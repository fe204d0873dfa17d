"""Symbolic controllers: a strategy kept as BDDs, and its JSON file format.

A symbolic controller is what the GR(1) fixpoint leaves behind instead of an explicit
automaton: the winning region, the initial conditions, ρe, the system goals and, per goal
j, the relation of moves that make progress towards goal j (the strategy construction of
Bloem et al., JCSS 78(3) 2012, Sect. 5, before it is unrolled into nodes).  A run needs
only the current state and the goal counter; each step is a few BDD restrictions.

The BDDs are stored as one shared node table (``docs/controller-format.md``, "Symbolic
controllers"), written children first so that a reader rebuilds every function bottom-up
in any BDD package with ``ite``.  This module is pure data: it knows no solver, and
:func:`materialize` builds the functions in whatever manager the caller brings, so the
verifier can read a file without the solver that wrote it.
"""

from __future__ import annotations

import html
import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Final

from gaitc.diagnostics import ControllerError, Span
from gaitc.diagnostics.versions import SYMBOLIC_CONTROLLER
from gaitc.ir.controller import (
    SYMBOLIC_FORMAT,
    ControllerKind,
    IntegerVar,
    integers_from_json,
    integers_to_json,
)
from gaitc.ir.spec import SEMANTICS, Semantics

#: The single roots every symbolic controller has, and the per-goal lists.
SINGLE_ROOTS: Final = ("winning", "env_init", "sys_init", "env_trans")
GOAL_ROOTS: Final = ("goals", "strategies")

#: A reference into the node table: 0 is false, 1 true, k >= 2 node ``k - 2``, and -r the
#: complement of r.
Ref = int


@dataclass(frozen=True)
class SymbolicController:
    """A GR(1) strategy as BDDs over ``order`` (pre bits ``b`` and post bits ``b'``).

    ``nodes[k] = (variable index in order, low ref, high ref)``; ``roots`` maps each name
    of :data:`SINGLE_ROOTS` to a ref and each of :data:`GOAL_ROOTS` to one ref per goal.
    """

    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    order: tuple[str, ...]
    nodes: tuple[tuple[int, Ref, Ref], ...]
    roots: Mapping[str, Ref | tuple[Ref, ...]]
    integers: Mapping[str, IntegerVar] = field(default_factory=dict)
    semantics: Semantics = Semantics.DEFAULT
    solver: str = "embedded"
    source: Mapping[str, str] | None = None
    choice: tuple[str, ...] = ()  # bits, most significant first, for picking the smallest

    @property
    def choice_rank(self) -> dict[str, int]:
        """Rank of every bit and primed bit in :attr:`choice` (default: the variables)."""
        names = self.choice or self.variables
        return {n: k for k, b in enumerate(names) for n in (b, b + "'")}

    @property
    def variables(self) -> tuple[str, ...]:
        return self.inputs + self.outputs

    @property
    def kind(self) -> ControllerKind:
        return ControllerKind.STRATEGY

    @property
    def goal_count(self) -> int:
        strategies = self.roots["strategies"]
        return len(strategies) if isinstance(strategies, tuple) else 1

    def __repr__(self) -> str:
        source = f" for {self.source['file']!r}" if self.source and "file" in self.source else ""
        return (f"<SymbolicController{source}: {len(self.nodes)} BDD nodes, "
                f"{self.goal_count} goal(s), {len(self.inputs)} input and "
                f"{len(self.outputs)} output bits, {self.semantics} semantics>")

    def _repr_html_(self) -> str:
        rows = [("kind", "symbolic strategy"), ("BDD nodes", str(len(self.nodes))),
                ("goals", str(self.goal_count)), ("inputs", ", ".join(self.inputs)),
                ("outputs", ", ".join(self.outputs)), ("semantics", self.semantics)]
        body = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
                       f"<td>{html.escape(v)}</td></tr>" for k, v in rows)
        return f"<table><caption>symbolic controller</caption>{body}</table>"


# ---------------------------------------------------------------- BDDs <-> table
def node_table(bdd: Any, roots: Mapping[str, Any | Sequence[Any]]
               ) -> tuple[tuple[str, ...], tuple[tuple[int, Ref, Ref], ...],
                          dict[str, Ref | tuple[Ref, ...]]]:
    """The shared node table of ``roots`` (dd.cudd functions of ``bdd``), children first.

    Returns the variables in the manager's order (those the table uses), the nodes and
    the root refs.  Iterative, so BDDs of any depth and size are fine.
    """
    index: dict[int, Ref] = {}
    rows: list[tuple[str, Ref, Ref]] = []
    true, false = bdd.true, bdd.false

    def ref_of(u: Any) -> Ref:
        if u == true:
            return 1
        if u == false:
            return 0
        regular = ~u if u.negated else u
        stack = [regular]
        while stack:
            top = stack[-1]
            if int(top) in index:
                stack.pop()
                continue
            pending = [c for c in (top.low, top.high) if c.var is not None
                       and int(~c if c.negated else c) not in index]
            if pending:
                stack.extend(~c if c.negated else c for c in pending)
                continue
            stack.pop()
            rows.append((str(top.var), _ref(top.low, index, true, false),
                         _ref(top.high, index, true, false)))
            index[int(top)] = len(rows) + 1
        found = index[int(regular)]
        return -found if u.negated else found

    refs: dict[str, Ref | tuple[Ref, ...]] = {}
    for name, value in roots.items():
        if isinstance(value, (list, tuple)):
            refs[name] = tuple(ref_of(u) for u in value)
        else:
            refs[name] = ref_of(value)
    used = {var for var, _, _ in rows}
    order = tuple(sorted(used, key=bdd.level_of_var))
    position = {v: k for k, v in enumerate(order)}
    return order, tuple((position[v], lo, hi) for v, lo, hi in rows), refs


def _ref(child: Any, index: Mapping[int, Ref], true: Any, false: Any) -> Ref:
    if child == true:
        return 1
    if child == false:
        return 0
    regular = ~child if child.negated else child
    found = index[int(regular)]
    return -found if child.negated else found


def declare(bdd: Any, ctrl: SymbolicController) -> None:
    """Declare ``ctrl``'s variables in ``bdd``: its order first, then every other bit and
    primed bit of its inputs and outputs."""
    listed = set(ctrl.order)
    bdd.declare(*ctrl.order, *(v for b in ctrl.variables for v in (b, b + "'")
                              if v not in listed))


def materialize(bdd: Any, ctrl: SymbolicController) -> dict[str, Any]:
    """Every root of ``ctrl`` as a function of ``bdd`` (whose variables include ``order``).

    Per-goal roots come back as lists.  Built bottom-up with ``ite``, one call per node.
    """
    built: list[Any] = [bdd.false, bdd.true]
    for var, low, high in ctrl.nodes:
        built.append(bdd.ite(bdd.var(ctrl.order[var]), _get(built, high), _get(built, low)))
    out: dict[str, Any] = {}
    for name, value in ctrl.roots.items():
        out[name] = ([_get(built, r) for r in value] if isinstance(value, tuple)
                     else _get(built, value))
    return out


def _get(built: list[Any], ref: Ref) -> Any:
    return ~built[-ref] if ref < 0 else built[ref]


# ---------------------------------------------------------------- JSON
def symbolic_to_json(ctrl: SymbolicController) -> str:
    """Deterministic JSON text of ``ctrl`` (one BDD node per line), ending in a newline."""
    head = {
        "gaitc": {
            "format": SYMBOLIC_FORMAT,
            "version": SYMBOLIC_CONTROLLER.version,
            "solver": ctrl.solver,
            "semantics": ctrl.semantics,
            "inputs": list(ctrl.inputs),
            "outputs": list(ctrl.outputs),
            "integers": integers_to_json(ctrl.integers),
            **({"source": dict(ctrl.source)} if ctrl.source is not None else {}),
        },
        "order": list(ctrl.order),
        "choice": list(ctrl.choice or ctrl.variables),
        "roots": {k: (list(v) if isinstance(v, tuple) else v)
                  for k, v in sorted(ctrl.roots.items())},
    }
    lines = ",\n".join(f"  {json.dumps(list(n))}" for n in ctrl.nodes)
    body = json.dumps(head, sort_keys=True, indent=1)[:-2]  # reopen the object
    return body + ',\n "nodes": [\n' + lines + "\n ]\n}\n"


def is_symbolic(data: Any) -> bool:
    """Whether a parsed controller file is a symbolic controller."""
    extras = data.get("gaitc") if isinstance(data, dict) else None
    return isinstance(extras, dict) and extras.get("format") == SYMBOLIC_FORMAT


def symbolic_from_dict(data: Any, filename: str = "<controller>") -> SymbolicController:
    """Check and convert a parsed symbolic controller file."""
    span = Span(filename, 1, 1)
    _need(is_symbolic(data), "not a symbolic controller file", span)
    extras = data["gaitc"]
    SYMBOLIC_CONTROLLER.check(extras.get("version"), span, ControllerError)
    inputs, outputs = _names(extras.get("inputs"), "gaitc.inputs", span), _names(
        extras.get("outputs"), "gaitc.outputs", span)
    _need(not set(inputs) & set(outputs), "a bit is both an input and an output", span)
    order = _names(data.get("order"), "order", span)
    bits = set(inputs) | set(outputs)
    known = bits | {b + "'" for b in bits}
    stray = [v for v in order if v not in known]
    _need(not stray, f"'order' names {stray[:1]!r}, which is no input or output bit "
          "(primed or not)", span)
    _need(len(set(order)) == len(order), "'order' lists a variable twice", span)
    choice = _names(data.get("choice"), "choice", span)
    _need(sorted(choice) == sorted(bits), "'choice' must list every input and output bit once",
          span)
    nodes = _nodes(data.get("nodes"), len(order), span)
    roots = _roots(data.get("roots"), len(nodes), span)
    semantics = extras.get("semantics", "default")
    _need(semantics in SEMANTICS, f"'gaitc.semantics' must be one of {', '.join(SEMANTICS)}",
          span)
    _check_supports(nodes, roots, order, set(outputs), span)
    integers = integers_from_json(extras.get("integers", {}), bits,
                                  lambda ok, message: _need(ok, message, span))
    source = extras.get("source")
    return SymbolicController(

        inputs=inputs,
        outputs=outputs,
        order=order,
        nodes=nodes,
        roots=roots,
        integers=integers,
        semantics=Semantics(str(semantics)),
        solver=str(extras.get("solver", "embedded")),
        source={str(k): str(v) for k, v in source.items()} if isinstance(source, dict) else None,
        choice=choice,
    )


def _check_supports(nodes: tuple[tuple[int, Ref, Ref], ...],
                    roots: Mapping[str, Ref | tuple[Ref, ...]], order: tuple[str, ...],
                    outputs: set[str], span: Span) -> None:
    """Each single root reads only what a runtime gives it: the winning region and the
    initial conditions the current state, ρe the current state and the inputs just chosen
    (the per-goal relations and goals may read every bit, primed or not)."""
    for name in SINGLE_ROOTS:
        root = roots[name]
        assert isinstance(root, int)
        seen: set[int] = set()
        stack = [abs(root)]
        while stack:
            ref = stack.pop()
            if ref < 2 or ref in seen:
                continue
            seen.add(ref)
            var, low, high = nodes[ref - 2]
            bit = order[var]
            primed = bit.endswith("'")
            wrong = primed and (name != "env_trans" or bit[:-1] in outputs)
            _need(not wrong, f"'roots.{name}' reads {bit!r}, which "
                  + ("it may not read: it reads the current state only" if name != "env_trans"
                     else "ρe may not read: the environment moves before the system"), span)
            stack.extend((abs(low), abs(high)))


def _need(cond: bool, message: str, span: Span) -> None:
    if not cond:
        raise ControllerError(message, span,
                              hint="regenerate it with 'gaitc synth --symbolic -o FILE'")


def _is_int(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _names(value: Any, key: str, span: Span) -> tuple[str, ...]:
    _need(isinstance(value, list) and all(isinstance(v, str) for v in value),
          f"'{key}' must be a list of bit names", span)
    return tuple(value)


def _nodes(value: Any, n_vars: int, span: Span) -> tuple[tuple[int, Ref, Ref], ...]:
    _need(isinstance(value, list), "'nodes' must be a list of [variable, low, high]", span)
    out: list[tuple[int, Ref, Ref]] = []
    levels: list[int] = []
    for k, row in enumerate(value):
        _need(isinstance(row, list) and len(row) == 3 and all(_is_int(x) for x in row),
              f"BDD node {k} must be [variable, low, high] integers", span)
        var, low, high = row
        _need(0 <= var < n_vars, f"BDD node {k}: variable {var} is not in 'order'", span)
        for child in (low, high):
            _need(abs(child) < k + 2,
                  f"BDD node {k}: reference {child} is not an earlier node", span)
            if abs(child) >= 2:
                _need(levels[abs(child) - 2] > var,
                      f"BDD node {k}: its child is not below it in 'order'", span)
        _need(low != high, f"BDD node {k} has equal children (not reduced)", span)
        out.append((var, low, high))
        levels.append(var)
    return tuple(out)


def _roots(value: Any, n_nodes: int, span: Span) -> dict[str, Ref | tuple[Ref, ...]]:
    _need(isinstance(value, dict), "'roots' must be an object", span)
    out: dict[str, Ref | tuple[Ref, ...]] = {}

    def valid(r: Any) -> bool:
        return _is_int(r) and abs(r) < n_nodes + 2

    for name in SINGLE_ROOTS:
        r = value.get(name)
        _need(valid(r), f"'roots.{name}' must be a reference into 'nodes'", span)
        out[name] = r
    counts = set()
    for name in GOAL_ROOTS:
        rs = value.get(name)
        _need(isinstance(rs, list) and bool(rs) and all(valid(r) for r in rs),
              f"'roots.{name}' must be a non-empty list of references into 'nodes'", span)
        out[name] = tuple(rs)
        counts.add(len(rs))
    _need(len(counts) == 1, "'roots.goals' and 'roots.strategies' must have one entry per "
          "goal each", span)
    return out

