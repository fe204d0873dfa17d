"""The compact controller: decision diagrams over fields, its file format and its run.

A compact controller is a GR(1) strategy written as small functions, not as an automaton:

* ``moves[j]``: for goal j, the next output values (the leaf, a row of :attr:`moves`) from
  the current field values and the inputs the environment just chose;
* ``reached[j]``: whether the current state meets goal j (a boolean diagram), which moves
  the goal counter on, as every GR(1) controller's counter does (Bloem et al., JCSS 78(3)
  2012, Sect. 5);
* ``start``: under the default semantics, the first outputs from the first inputs; under the
  robotics semantics, which first states the controller accepts (a boolean diagram);
* ``assumed``: whether the inputs just chosen are a move ρe allows from the current state,
  on every state the controller can be in: a board that runs the controller on its own
  vents when its sensors break the assumptions its guarantee rests on.

Its only memory is the goal counter and the last state, so a microcontroller runs it from
tables in flash (:mod:`gaitc.codegen`).  :func:`to_symbolic` turns it back into BDD relations
so that the independent verifier (:mod:`gaitc.verifier.symbolic`) proves it on every state.
"""

from __future__ import annotations

import html
import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Final, TypedDict

from gaitc.compact.diagram import (
    Branch,
    Ref,
    Slot,
    evaluate,
    leaf,
    leaf_value,
    paths,
    reachable_nodes,
)
from gaitc.core.vocabulary import Field, Vocabulary
from gaitc.diagnostics import ControllerError, Span
from gaitc.ir.bddfile import SymbolicController, node_table
from gaitc.ir.bitblast import bitblast
from gaitc.ir.controller import ControllerKind, IntegerVar, integers_from_json, integers_to_json
from gaitc.ir.manager import manager
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.verifier.logic import Logic

if TYPE_CHECKING:
    from dd.cudd import BDD, Function

COMPACT_FORMAT: Final = "compact"
COMPACT_VERSION: Final = 1


@dataclass(frozen=True)
class CompactController:
    """Decision diagrams over :attr:`slots` sharing one node table (see the module text)."""

    vocabulary: Vocabulary
    slots: tuple[Slot, ...]
    nodes: tuple[Branch, ...]
    moves: tuple[tuple[int, ...], ...]  # per move, one value index per output field
    move_roots: tuple[Ref, ...]
    reached_roots: tuple[Ref, ...]
    start_root: Ref
    #: the assumption monitor's root; None when the file carries no monitor (a controller
    #: generated with ``--no-monitor``), which verify and the board then say
    assumed_root: Ref | None
    inputs: tuple[str, ...]  # the spec's bits, as in its other controller files
    outputs: tuple[str, ...]
    integers: Mapping[str, IntegerVar] = field(default_factory=dict)
    semantics: Semantics = Semantics.DEFAULT
    solver: str = "embedded"
    source: Mapping[str, str] | None = None

    @property
    def variables(self) -> tuple[str, ...]:
        """The spec's bits, inputs first (as every form lists them)."""
        return self.inputs + self.outputs

    # ---------------------------------------------------------------- sizes
    @property
    def goal_count(self) -> int:
        return len(self.move_roots)

    @property
    def monitored(self) -> bool:
        """Whether the controller carries an assumption monitor."""
        return self.assumed_root is not None

    @property
    def roots(self) -> tuple[Ref, ...]:
        """Every root in the generated tables' order; a missing monitor allows everything."""
        assumed = leaf(1) if self.assumed_root is None else self.assumed_root
        return (*self.move_roots, *self.reached_roots, self.start_root, assumed)

    @property
    def decision_nodes(self) -> int:
        """Decision nodes of the controller proper: below the move, goal and start roots."""
        return len(reachable_nodes(self.nodes, self.roots[:-1]))

    @property
    def monitor_nodes(self) -> int:
        """Decision nodes only the assumption monitor (the ``assumed`` diagram) uses."""
        return len(reachable_nodes(self.nodes, self.roots)) - self.decision_nodes

    @property
    def rules(self) -> int:
        """Rules of the move diagrams: one per path from a goal's root to a move."""
        return sum(len(paths(self.nodes, root, len(self.slots))) for root in self.move_roots)

    @property
    def kind(self) -> ControllerKind:
        return ControllerKind.STRATEGY

    # ---------------------------------------------------------------- reading
    def slot_values(self, state: Mapping[str, int], chosen: Mapping[str, int]) -> list[int]:
        """One value per slot from the current field values and the inputs just chosen."""
        out = []
        for slot in self.slots:
            source = chosen if slot.next else state
            out.append(source.get(slot.field.name, 0))
        return out

    def decide(self, goal: int, state: Mapping[str, int], chosen: Mapping[str, int]
               ) -> dict[str, int]:
        """The next output values for goal ``goal`` (field name -> value index)."""
        move = evaluate(self.nodes, self.move_roots[goal], self.slot_values(state, chosen))
        return dict(zip((f.name for f in self.vocabulary.outputs), self.moves[move],
                        strict=True))

    def first(self, chosen: Mapping[str, int]) -> dict[str, int]:
        """The first outputs for the first inputs ``chosen`` (default semantics)."""
        if self.semantics == Semantics.ROBOTICS:
            raise ValueError("under the robotics semantics the first state is given, not chosen")
        move = evaluate(self.nodes, self.start_root, self.slot_values({}, chosen))
        return dict(zip((f.name for f in self.vocabulary.outputs), self.moves[move],
                        strict=True))

    def accepts(self, state: Mapping[str, int]) -> bool:
        """Whether the controller can start in ``state`` (robotics semantics)."""
        return bool(evaluate(self.nodes, self.start_root, self.slot_values(state, {})))

    def assumes(self, state: Mapping[str, int], chosen: Mapping[str, int]) -> bool:
        """Whether ρe allows the inputs ``chosen`` from ``state`` (always, without a
        monitor)."""
        if self.assumed_root is None:
            return True
        return bool(evaluate(self.nodes, self.assumed_root, self.slot_values(state, chosen)))

    def advance(self, goal: int, state: Mapping[str, int]) -> int:
        """The goal counter after ``state``: past every goal the state meets, in turn."""
        values = self.slot_values(state, {})
        n, current = self.goal_count, goal
        for _ in range(n):
            if not evaluate(self.nodes, self.reached_roots[current], values):
                break
            current = (current + 1) % n
        return current

    # ---------------------------------------------------------------- display
    def summary(self) -> str:
        return (f"{self.rules} rules, {self.decision_nodes} decision nodes "
                f"(and {self.monitor_nodes} for the assumption monitor), "
                f"{self.goal_count} goal(s), {len(self.moves)} distinct moves")

    def __repr__(self) -> str:
        source = f" for {self.source['file']!r}" if self.source and "file" in self.source else ""
        return f"<CompactController{source}: {self.summary()}>"

    def _repr_html_(self) -> str:
        """Its sizes: which of its rules a run uses depends on the spec, so its rules are
        shown by ``gaitc.api.drawing.compact_rules(spec, controller)``."""
        return (f"<p>compact controller: {html.escape(self.summary())}; its rules, with the "
                "spec: <code>compact_rules(spec, controller)</code></p>")


class Runner:
    """A compact controller run step by step, as the board runs it: the state of every field
    and the goal counter."""

    def __init__(self, ctrl: CompactController, first: Mapping[str, int]) -> None:
        """Start from the first inputs (default semantics) or the whole first state
        (robotics semantics), each as field name -> value index."""
        self.ctrl = ctrl
        if ctrl.semantics == Semantics.ROBOTICS:
            if not ctrl.accepts(first):
                raise ControllerError("the controller cannot start in this state")
            self.state = dict(first)
        else:
            self.state = dict(first) | ctrl.first(first)
        self.goal = 0

    def step(self, chosen: Mapping[str, int]) -> dict[str, int]:
        """The environment chose the inputs ``chosen``: the controller's outputs."""
        move = self.ctrl.decide(self.goal, self.state, chosen)
        self.goal = self.ctrl.advance(self.goal, self.state)
        self.state = dict(self.state) | dict(chosen) | move
        return move


# -------------------------------------------------------------------- back to BDDs
class Relations(TypedDict):
    """A compact controller's diagrams as BDDs (:func:`relations`)."""

    strategies: list[Function]
    goals: list[Function]
    start: Function
    assumed: Function


def relations(bdd: BDD, ctrl: CompactController) -> Relations:
    """The diagrams as BDDs of ``bdd`` over the spec's bits: per goal the move relation
    (path cube and move cube), the goal functions, the start relation or set and the
    assumption monitor (true without one)."""
    move_cubes = [_move_cube(bdd, ctrl, k, primed=True) for k in range(len(ctrl.moves))]
    truth = [bdd.false, bdd.true]
    # nodes shared by several roots are built once per reading of the leaves
    cache: dict[int, dict[Ref, Function]] = {id(move_cubes): {}, id(truth): {}}

    def diagram(root: Ref, leaves: Sequence[Function]) -> Function:
        built = cache[id(leaves)]
        for index in reachable_nodes(ctrl.nodes, [root]):
            if index in built:
                continue
            branch = ctrl.nodes[index]
            slot = ctrl.slots[branch.field]
            out = bdd.false
            for value, kid in enumerate(branch.kids):
                below = leaves[leaf_value(kid)] if kid < 0 else built[kid]
                out |= bdd.cube(slot.field.cube(value, slot.next)) & below
            built[index] = out
        return leaves[leaf_value(root)] if root < 0 else built[root]

    start_leaves: Sequence[Function] = truth if ctrl.semantics == Semantics.ROBOTICS else move_cubes
    start = diagram(ctrl.start_root, start_leaves)
    if ctrl.semantics != Semantics.ROBOTICS:
        # the start diagram reads the first inputs as next values: bring them to now
        rename = {b + "'": b for b in (*ctrl.inputs, *ctrl.outputs)}
        start = bdd.let(rename, start)
    return {
        "strategies": [diagram(r, move_cubes) for r in ctrl.move_roots],
        "goals": [diagram(r, truth) for r in ctrl.reached_roots],
        "start": start,
        "assumed": bdd.true if ctrl.assumed_root is None else diagram(ctrl.assumed_root, truth),
    }


def monitor_function(bdd: BDD, ctrl: CompactController) -> Function:
    """The assumption monitor as a BDD of ``bdd`` over current bits and the inputs' next
    bits (true when the controller carries none)."""
    return relations(bdd, ctrl)["assumed"]


def _move_cube(bdd: BDD, ctrl: CompactController, index: int, primed: bool) -> Function:
    cube: dict[str, bool] = {}
    for f, value in zip(ctrl.vocabulary.outputs, ctrl.moves[index], strict=True):
        cube.update(f.cube(value, primed))
    return bdd.cube(cube)


def diagram_order(ctrl: CompactController) -> list[str]:
    """A BDD variable order that follows the diagrams: the bits of each slot in slot order,
    then the other bits, the outputs' next values last (where the leaves set them)."""
    order: list[str] = []
    for slot in ctrl.slots:  # a field's bits next to their next values: ρe stays small
        if slot.field.is_input:
            order.extend(v for b in sorted(slot.field.bits) for v in (b + "'", b)
                         if v not in set(order))
        else:
            order.extend(b for b in sorted(slot.field.bits) if b not in set(order))
    rest = [v for b in (*ctrl.inputs, *ctrl.outputs) for v in (b, b + "'")]
    post_out = {b + "'" for b in ctrl.outputs}
    order += [v for v in rest if v not in set(order) and v not in post_out]
    return order + [b + "'" for b in ctrl.outputs]


def to_symbolic(ctrl: CompactController, spec: GR1Spec | None = None) -> SymbolicController:
    """The compact controller as a :class:`SymbolicController` whose relations allow just
    the moves it makes, for the independent verifier and the symbolic runtime.  With
    ``spec``, its θe and ρe are the controller's (a runtime enumerates the environment's
    moves from them); without, they are left true (the verifier reads the spec's own)."""
    env_init = env_trans = None
    if spec is not None:

        logic = Logic(bitblast(spec), diagram_order(ctrl))
        bdd = logic.bdd
        env_init, env_trans = logic.conjunction("env_init"), logic.conjunction("env_trans")
    else:
        bdd = manager()
        bdd.declare(*diagram_order(ctrl))
    roots = relations(bdd, ctrl)
    table = {
        "winning": bdd.true,
        "env_init": bdd.true if env_init is None else env_init,
        "sys_init": roots["start"],
        "env_trans": bdd.true if env_trans is None else env_trans,
        "goals": roots["goals"],
        "strategies": roots["strategies"],
    }
    order, nodes, refs = node_table(bdd, table)
    return SymbolicController(inputs=ctrl.inputs, outputs=ctrl.outputs, order=order,
                              nodes=nodes, roots=refs, integers=dict(ctrl.integers),
                              semantics=ctrl.semantics, solver=ctrl.solver, source=ctrl.source)


# -------------------------------------------------------------------- JSON
def compact_to_dict(ctrl: CompactController) -> dict[str, Any]:
    return {
        "gaitc": {
            "format": COMPACT_FORMAT, "version": COMPACT_VERSION, "solver": ctrl.solver,
            "semantics": str(ctrl.semantics), "domain": ctrl.vocabulary.domain,
            "inputs": list(ctrl.inputs), "outputs": list(ctrl.outputs),
            "integers": integers_to_json(ctrl.integers),
            **({"source": dict(ctrl.source)} if ctrl.source is not None else {}),
        },
        "fields": [{"name": f.name, "input": f.is_input, "numeric": f.numeric,
                    "values": [{"label": label, "bits": {b: int(on) for b, on in cube}}
                               for label, cube in zip(f.labels, f.cubes, strict=True)]}
                   for f in ctrl.vocabulary.fields],
        "slots": [[s.field.name, int(s.next)] for s in ctrl.slots],
        "moves": [list(m) for m in ctrl.moves],
        "roots": {"moves": list(ctrl.move_roots), "reached": list(ctrl.reached_roots),
                  "start": ctrl.start_root, "assumed": ctrl.assumed_root},
        "nodes": [[b.field, list(b.kids), list(b.unused)] for b in ctrl.nodes],
    }


def compact_to_json(ctrl: CompactController) -> str:
    """Deterministic JSON text (one node per line), ending in a newline."""
    data = compact_to_dict(ctrl)
    nodes = data.pop("nodes")
    body = json.dumps(data, sort_keys=True, indent=1)[:-2]
    lines = ",\n".join(f"  {json.dumps(n)}" for n in nodes)
    return body + ',\n "nodes": [\n' + lines + ("\n" if lines else "") + " ]\n}\n"


def is_compact(data: Any) -> bool:
    extras = data.get("gaitc") if isinstance(data, dict) else None
    return isinstance(extras, dict) and extras.get("format") == COMPACT_FORMAT


class _Reader:
    """Checks a parsed compact controller file, naming the first thing wrong."""

    def __init__(self, file: str) -> None:
        self.span = Span(file or "<controller>", 1, 1)

    def fail(self, what: str) -> ControllerError:
        return ControllerError(f"malformed compact controller: {what}", self.span,
                               hint="write it again with 'gaitc synth --compact'")

    def need(self, ok: bool, what: str) -> None:
        if not ok:
            raise self.fail(what)

    def ints(self, value: Any, what: str) -> list[int]:
        self.need(isinstance(value, list) and all(type(v) is int for v in value),
                  f"{what} must be a list of integers")
        return list(value)


def compact_from_dict(data: Any, file: str = "") -> CompactController:
    """Read a compact controller; a malformed or tampered file raises ControllerError."""
    r = _Reader(file)
    r.need(is_compact(data), "it is not a compact controller (no gaitc.format 'compact')")
    head = data["gaitc"]
    r.need(head.get("version") == COMPACT_VERSION,
           f"format version {head.get('version')!r}, this gaitc reads {COMPACT_VERSION}")
    try:
        semantics = Semantics(head.get("semantics", "default"))
    except ValueError:
        raise r.fail(f"unknown semantics {head.get('semantics')!r}") from None
    inputs, outputs = head.get("inputs"), head.get("outputs")
    r.need(isinstance(inputs, list) and all(isinstance(b, str) for b in inputs)
           and isinstance(outputs, list) and all(isinstance(b, str) for b in outputs),
           "gaitc.inputs and gaitc.outputs must be lists of bit names")
    bits = set(inputs) | set(outputs)
    fields = []
    raw_fields = data.get("fields")
    r.need(isinstance(raw_fields, list) and bool(raw_fields), "'fields' must be a non-empty list")
    for k, raw in enumerate(raw_fields):
        r.need(isinstance(raw, dict) and isinstance(raw.get("name"), str)
               and isinstance(raw.get("values"), list) and bool(raw["values"]),
               f"field {k} needs a name and a non-empty list of values")
        labels, cubes = [], []
        for value in raw["values"]:
            r.need(isinstance(value, dict) and isinstance(value.get("label"), str)
                   and isinstance(value.get("bits"), dict)
                   and all(b in bits and v in (0, 1) for b, v in value["bits"].items()),
                   f"a value of field {raw['name']!r} is not a label with bits of the spec")
            labels.append(value["label"])
            cubes.append(tuple(sorted((b, bool(v)) for b, v in value["bits"].items())))
        fields.append(Field(raw["name"], bool(raw.get("input")), tuple(labels), tuple(cubes),
                            bool(raw.get("numeric"))))
    vocabulary = Vocabulary(tuple(fields), str(head.get("domain", "spec")))
    by_name = {f.name: f for f in fields}
    slots = []
    raw_slots = data.get("slots")
    r.need(isinstance(raw_slots, list), "'slots' must be a list")
    for raw in raw_slots:
        r.need(isinstance(raw, list) and len(raw) == 2 and isinstance(raw[0], str)
               and raw[0] in by_name and type(raw[1]) is int and raw[1] in (0, 1),
               f"slot {raw!r} names no field")
        r.need(by_name[raw[0]].is_input or not raw[1],
               f"slot {raw!r} reads the next value of output field {raw[0]!r}; only the "
               "environment's inputs have a value chosen before the controller moves")
        slots.append(Slot(by_name[raw[0]], bool(raw[1])))
    outs = vocabulary.outputs
    moves = []
    raw_moves = data.get("moves")
    r.need(isinstance(raw_moves, list), "'moves' must be a list")
    for raw in raw_moves:
        row = r.ints(raw, "a move")
        r.need(len(row) == len(outs) and all(0 <= v < len(f.labels)
                                             for v, f in zip(row, outs, strict=True)),
               f"move {row} has no value for every output field")
        moves.append(tuple(row))
    nodes = []
    raw_nodes = data.get("nodes")
    r.need(isinstance(raw_nodes, list), "'nodes' must be a list")
    for index, raw in enumerate(raw_nodes):
        r.need(isinstance(raw, list) and len(raw) == 3 and type(raw[0]) is int
               and 0 <= raw[0] < len(slots), f"node {index} reads no slot")
        kids = r.ints(raw[1], f"node {index}'s children")
        unused = r.ints(raw[2], f"node {index}'s unused values")
        r.need(all(0 <= v < len(kids) for v in unused), f"node {index}'s unused values")
        r.need(len(kids) == len(slots[raw[0]].field.labels),
               f"node {index} has {len(kids)} children for a field of "
               f"{len(slots[raw[0]].field.labels)} values")
        for kid in kids:
            r.need(kid < index if kid >= 0 else leaf_value(kid) < max(len(moves), 2),
                   f"node {index} points to {kid}, which is not an earlier node or a leaf")
        nodes.append(Branch(raw[0], tuple(kids), tuple(unused)))
    roots = data.get("roots")
    r.need(isinstance(roots, dict), "'roots' must be an object")
    move_roots = r.ints(roots.get("moves"), "roots.moves")
    reached = r.ints(roots.get("reached"), "roots.reached")
    start, assumed = roots.get("start"), roots.get("assumed")
    r.need(type(start) is int, "roots.start must be an integer")
    r.need(type(assumed) is int or assumed is None,
           "roots.assumed must be an integer, or null for a controller without a monitor")
    r.need(len(move_roots) == len(reached) and bool(move_roots),
           "roots.moves and roots.reached need one root per goal")
    for ref in (*move_roots, *reached, start, *([] if assumed is None else [assumed])):
        r.need(ref < len(nodes) if ref >= 0 else leaf_value(ref) < max(len(moves), 2),
               f"root {ref} is not a node or a leaf")
    integers = integers_from_json(head.get("integers", {}), bits, r.need)
    source = head.get("source")
    found = CompactController(
        vocabulary=vocabulary, slots=tuple(slots), nodes=tuple(nodes), moves=tuple(moves),
        move_roots=tuple(move_roots), reached_roots=tuple(reached), start_root=start,
        assumed_root=assumed, inputs=tuple(inputs), outputs=tuple(outputs), integers=integers,
        semantics=semantics, solver=str(head.get("solver", "embedded")),
        source=dict(source) if isinstance(source, dict) else None)
    _check_diagrams(r, found)
    return found


def _check_diagrams(r: _Reader, ctrl: CompactController) -> None:
    """Each diagram returns only what its role allows and reads only the slots its runtime
    gives it values for: a move diagram ends in moves, a yes/no diagram in 0 or 1; the goal
    diagrams and the robotics start read the current state alone, the default start the
    first inputs alone (as :class:`Runner`, :func:`relations` and the generated C do)."""
    nodes, slots, moves = ctrl.nodes, ctrl.slots, len(ctrl.moves)
    move_roots, reached, start = ctrl.move_roots, ctrl.reached_roots, ctrl.start_root
    assumed = ctrl.assumed_root
    robotics = ctrl.semantics == Semantics.ROBOTICS
    roles: list[tuple[str, Ref, int, str]] = [
        (f"the move diagram of goal {j + 1}", root, moves, "any")
        for j, root in enumerate(move_roots)]
    roles += [(f"the diagram of goal {j + 1}", root, 2, "now")
              for j, root in enumerate(reached)]
    roles.append(("the start diagram", start, 2 if robotics else moves,
                  "now" if robotics else "chosen"))
    if assumed is not None:
        roles.append(("the assumption monitor", assumed, 2, "any"))
    for what, root, leaves, reads in roles:
        below = reachable_nodes(nodes, [root])
        ends = [root] if root < 0 else [k for n in below for k in nodes[n].kids if k < 0]
        for ref in ends:
            value = leaf_value(ref)
            r.need(value < leaves, f"{what} ends in {value}, where it may only return "
                   + ("0 or 1" if leaves == 2 else f"one of the {moves} moves"))
        for n in below:
            slot = slots[nodes[n].field]
            r.need(reads != "now" or not slot.next,
                   f"{what} reads the inputs just chosen (node {n}); it may read only the "
                   "current state")
            r.need(reads != "chosen" or (slot.next and slot.field.is_input),
                   f"{what} reads the current state (node {n}); it may read only the first "
                   "inputs")
