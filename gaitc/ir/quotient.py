"""Merging equivalent nodes of an explicit controller: its bisimulation quotient.

Two nodes of a Mealy strategy are equivalent when they carry the same values of every
variable and, input by input, move to equivalent nodes: then no run of the environment
can tell them apart, so one node can stand for both (issue 12, "smaller explicit
controllers").  The coarsest such partition is found by partition refinement from the
blocks of equal values (Kanellakis and Smolka, "CCS expressions, finite state processes,
and three problems of equivalence", 1990; Paige and Tarjan 1987 for the fast version):
each round splits a block by the blocks of its members' successors, until no block
splits.  A node's successors differ in their input bits, so the set of successor blocks
fixes the block reached on each input.  The quotient keeps the first member of each block
(in node order, so breadth-first order survives) as its representative, with that
member's goal index.
"""

from __future__ import annotations

from dataclasses import replace

from gaitc.ir.controller import Controller, ControllerKind, ControllerNode


def equivalence_blocks(controller: Controller) -> list[int]:
    """The block of each node in the coarsest partition into equivalent nodes, numbered
    by the first node of each block."""
    nodes = controller.nodes
    ids: dict[tuple[int, ...], int] = {}
    blocks = [ids.setdefault(node.state, len(ids)) for node in nodes]
    count = len(ids)
    if count == len(nodes):  # no two nodes share their values (the thesis robots' case)
        return blocks
    while True:
        signatures: dict[tuple[int, frozenset[int]], int] = {}
        refined = [signatures.setdefault((blocks[k], frozenset(blocks[t] for t in node.trans)),
                                         len(signatures))
                   for k, node in enumerate(nodes)]
        if len(signatures) == count:  # nothing split: stable
            return refined
        blocks, count = refined, len(signatures)


def merge_equivalent(controller: Controller) -> Controller:
    """``controller`` with each set of equivalent nodes merged into one; the controller
    itself when no two nodes are equivalent.  Counter-strategies are returned unchanged
    (their nodes answer system moves, not inputs)."""
    if controller.kind != ControllerKind.STRATEGY:
        return controller
    blocks = equivalence_blocks(controller)
    count = max(blocks, default=-1) + 1
    if count == len(controller.nodes):
        return controller
    first: dict[int, int] = {}  # block: its first node (blocks are numbered in that order)
    for k, block in enumerate(blocks):
        first.setdefault(block, k)
    merged = []
    for block in range(count):
        node = controller.nodes[first[block]]
        merged.append(ControllerNode(node.rank, node.state,
                                     tuple(sorted({blocks[t] for t in node.trans}))))
    initial = tuple(sorted({blocks[k] for k in controller.initial}))
    return replace(controller, nodes=tuple(merged), initial=initial)
