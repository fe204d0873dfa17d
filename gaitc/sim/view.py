"""What a run reads of a controller, whichever its form: per-node values, successors, inputs.

:class:`StrategyView` is the interface the simulator, the driver and the environments use;
:class:`gaitc.sim.strategy.Strategy` (an explicit automaton) and
:class:`gaitc.sim.symbolic_view.SymbolicStrategy` (BDDs, nodes found as a run goes) both
provide it, sharing the look-ups of :class:`NodeReading`; :func:`reachable` is the
breadth-first search from the initial nodes that the readable views (policy, first steps)
share.
"""

from __future__ import annotations

from collections import deque
from typing import Protocol, TypeVar

InputKey = tuple[int, ...]
T_co = TypeVar("T_co", covariant=True)


class Indexed(Protocol[T_co]):
    """What a run reads of a controller's per-node data: item ``k`` of node ``k``."""

    def __getitem__(self, k: int, /) -> T_co: ...


class StrategyView(Protocol):
    """A controller as a run sees it: explicit (:class:`Strategy`) or symbolic
    (:class:`gaitc.sim.symbolic_view.SymbolicStrategy`, whose nodes are found as it runs)."""

    @property
    def variables(self) -> tuple[str, ...]: ...
    @property
    def n_inputs(self) -> int: ...
    @property
    def values(self) -> Indexed[tuple[int, ...]]: ...
    @property
    def successors(self) -> Indexed[tuple[int, ...]]: ...
    @property
    def ranks(self) -> Indexed[int]: ...
    @property
    def initial(self) -> tuple[int, ...]: ...
    @property
    def kind(self) -> str: ...
    @property
    def file(self) -> str: ...
    @property
    def inputs(self) -> tuple[str, ...]: ...
    def __len__(self) -> int: ...
    def input_key(self, node: int) -> InputKey: ...
    def valuation(self, node: int) -> dict[str, int]: ...
    def options(self, node: int) -> dict[InputKey, int]: ...
    def initial_options(self) -> dict[InputKey, int]: ...


class NodeReading:
    """What both kinds of controller answer alike from their per-node values."""

    variables: tuple[str, ...]
    n_inputs: int
    values: Indexed[tuple[int, ...]]
    initial: tuple[int, ...]

    @property
    def inputs(self) -> tuple[str, ...]:
        return self.variables[: self.n_inputs]

    def input_key(self, node: int) -> InputKey:
        return self.values[node][: self.n_inputs]

    def valuation(self, node: int) -> dict[str, int]:
        return dict(zip(self.variables, self.values[node], strict=True))

    def initial_options(self) -> dict[InputKey, int]:
        """The environment's possible first inputs → initial node (lowest id)."""
        found: dict[InputKey, int] = {}
        for node in self.initial:
            found.setdefault(self.input_key(node), node)
        return dict(sorted(found.items()))


def reachable(
    strategy: StrategyView, steps: int, cap: int | None = None
) -> tuple[dict[int, int], bool]:
    """Node → fewest moves from an initial node, for the nodes within ``steps`` moves
    (breadth first, in node order); stops after ``cap`` nodes.  Returns the depths and
    whether the cap cut the search short."""
    depth: dict[int, int] = {}
    queue: deque[int] = deque()
    for node in sorted(set(strategy.initial)):
        if cap is not None and len(depth) >= cap:
            return depth, True
        depth[node] = 0
        queue.append(node)
    while queue:
        node = queue.popleft()
        if depth[node] >= steps:
            continue
        for succ in strategy.successors[node]:
            if succ in depth:
                continue
            if cap is not None and len(depth) >= cap:
                return depth, True
            depth[succ] = depth[node] + 1
            queue.append(succ)
    return depth, False
