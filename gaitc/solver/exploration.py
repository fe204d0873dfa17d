"""The breadth-first exploration that builds an explicit automaton from its initial nodes.

Strategy and counter-strategy extraction (:mod:`gaitc.solver.strategy`,
:mod:`gaitc.solver.counter`) both number their nodes in the order they are found and
expand them in that order, each expansion naming its successors.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Hashable, Iterable, Iterator
from typing import Generic, TypeVar

from gaitc.solver.game import too_large

Key = TypeVar("Key", bound=Hashable)


class Exploration(Generic[Key]):
    """Nodes, each a key, numbered in the order found and expanded breadth first.

    :meth:`number` gives a key's node, adding it (to be expanded later) when it is new;
    iterating yields the nodes still to expand, oldest first, while expanding them adds
    more; :meth:`expanded` records a node's successors, sorted."""

    def __init__(self, what: str, max_nodes: int | None) -> None:
        """``what`` names the automaton in the error raised past ``max_nodes`` nodes."""
        self.what = what
        self.max_nodes = max_nodes
        self.index: dict[Key, int] = {}
        self.nodes: list[Key] = []
        self.successors: list[list[int]] = []
        self._queue: deque[int] = deque()

    def number(self, key: Key) -> int:
        """The node of ``key``, a new one (queued for expansion) if it was not found yet."""
        if key not in self.index:
            if self.max_nodes is not None and len(self.nodes) >= self.max_nodes:
                raise too_large(self.what, self.max_nodes)
            self.index[key] = len(self.nodes)
            self.nodes.append(key)
            self.successors.append([])
            self._queue.append(self.index[key])
        return self.index[key]

    def __iter__(self) -> Iterator[tuple[int, Key]]:
        """The nodes to expand, with their keys, in the order they were found."""
        while self._queue:
            k = self._queue.popleft()
            yield k, self.nodes[k]

    @property
    def pending(self) -> int:
        """How many nodes are found but not yet expanded."""
        return len(self._queue)

    def expanded(self, k: int, targets: Iterable[int]) -> None:
        """Record the successors of node ``k`` (sorted, each once)."""
        self.successors[k] = sorted(set(targets))
