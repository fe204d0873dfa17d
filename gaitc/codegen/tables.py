"""A compact controller flattened to the integer tables that generated code reads.

Layout (every table read-only, in flash on a microcontroller):

* ``node_slot[n]`` (1 byte) the slot node n reads, ``node_first[n]`` (2 bytes, or 4 when
  ``kids`` is longer than 16 bits reach) where its children start in ``kids``;
* ``kids[k]`` (2 bytes): a child, a node index below ``LEAF`` or ``LEAF | value`` for a leaf;
* ``moves[m * outputs + i]`` (1 byte): output field i's value in move m;
* ``roots`` (2 bytes each): per goal the move diagram, per goal the goal diagram, the start
  and the assumptions;
* ``slot_field[s]``, ``slot_next[s]`` (1 byte each): which field a slot reads, and whether the
  value the environment just chose.

:func:`table_bytes` is the size of these tables; it is what ``synth`` reports and what must
fit in the board's flash beside the firmware.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Final

from gaitc.compact.controller import CompactController
from gaitc.compact.diagram import leaf_value, reachable_nodes
from gaitc.core.vocabulary import Field
from gaitc.diagnostics import ControllerError

LEAF: Final = 0x8000  # a child reference at or above this is a leaf
NOT_INPUT: Final = 255  # the input position of an output field


@dataclass(frozen=True)
class Tables:
    """The flattened controller (see the module text)."""

    node_slot: tuple[int, ...]
    node_first: tuple[int, ...]
    kids: tuple[int, ...]
    moves: tuple[int, ...]
    roots: tuple[int, ...]
    slot_field: tuple[int, ...]
    slot_next: tuple[int, ...]
    field_sizes: tuple[int, ...]
    input_pos: tuple[int, ...]  # per field its place among the inputs, NOT_INPUT for outputs
    output_field: tuple[int, ...]  # per output, its field
    goals: int

    @property
    def first_bytes(self) -> int:
        """The width of ``node_first``'s entries: 2 bytes, or 4 once ``kids`` passes the
        65,536 entries a 16-bit offset reaches (a host target; no board holds that)."""
        return 2 if max(self.node_first, default=0) <= 0xFFFF else 4

    @property
    def bytes(self) -> int:
        return (len(self.node_slot) + self.first_bytes * len(self.node_first)
                + 2 * len(self.kids)
                + len(self.moves) + 2 * len(self.roots) + 2 * len(self.slot_field)
                + 2 * len(self.field_sizes) + len(self.output_field))


def flatten(ctrl: CompactController, extra_roots: Sequence[int] = ()) -> Tables:
    """The tables of ``ctrl``: only nodes some root reaches, renumbered children first;
    ``extra_roots`` (a recovering controller's, :mod:`gaitc.compact.recovery`) follow
    the controller's own in ``roots``."""
    every = (*ctrl.roots, *extra_roots)
    used = reachable_nodes(ctrl.nodes, every)
    number = {old: new for new, old in enumerate(used)}
    if len(used) >= LEAF or len(ctrl.moves) >= LEAF:
        raise ControllerError(f"the controller has {len(used)} decision nodes and "
                              f"{len(ctrl.moves)} moves; generated code holds at most "
                              f"{LEAF - 1} of each")
    fields = list(ctrl.vocabulary.fields)
    if any(len(f.labels) > 255 for f in fields):
        raise ControllerError("a field has more than 255 values; generated code reads one "
                              "byte per field")

    def ref(r: int) -> int:
        return LEAF | leaf_value(r) if r < 0 else number[r]

    node_slot: list[int] = []
    node_first: list[int] = []
    kids: list[int] = []
    for old in used:
        branch = ctrl.nodes[old]
        node_slot.append(branch.field)
        node_first.append(len(kids))
        kids.extend(ref(k) for k in branch.kids)
    index = {f.name: k for k, f in enumerate(fields)}
    return Tables(
        node_slot=tuple(node_slot), node_first=tuple(node_first), kids=tuple(kids),
        moves=tuple(v for move in ctrl.moves for v in move),
        roots=tuple(ref(r) for r in every),
        slot_field=tuple(index[s.field.name] for s in ctrl.slots),
        slot_next=tuple(int(s.next) for s in ctrl.slots),
        field_sizes=tuple(len(f.labels) for f in fields),
        input_pos=input_positions(ctrl.vocabulary.fields),
        output_field=tuple(k for k, f in enumerate(fields) if not f.is_input),
        goals=ctrl.goal_count)


def input_positions(fields: Sequence[Field]) -> tuple[int, ...]:
    """Per field its place in the generated code's input array (:data:`NOT_INPUT` for an
    output field)."""
    out, n = [], 0
    for f in fields:
        out.append(n if f.is_input else NOT_INPUT)
        n += int(f.is_input)
    return tuple(out)


def table_bytes(ctrl: CompactController) -> int:
    """The bytes of generated tables for ``ctrl``."""
    return flatten(ctrl).bytes
