"""A symbolic controller run step by step: the simulator's view of BDDs as an automaton.

Nodes (a state of every bit and the goal being pursued) are numbered as a run discovers
them; each node's moves are decided by BDD restrictions of the stored per-goal relations
(:mod:`gaitc.ir.bddfile`), exactly as the explicit extraction decides them
(:func:`gaitc.solver.strategy.extract_strategy`): for every input ρe allows, the smallest move of
the goal's relation that also keeps ρe, the goal counter advanced past every goal the move
reaches.  So a symbolic and an explicit controller of the same game make the same moves,
and a run never enumerates more of the controller than it visits.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from typing import Any, Generic, TypeVar

from gaitc.diagnostics import ControllerError, Span
from gaitc.ir.bddfile import SymbolicController, declare, materialize
from gaitc.ir.bddwalk import State, all_assignments, first_assignment, holds_at
from gaitc.ir.bits import bits_mismatch, spec_bits
from gaitc.ir.controller import ControllerKind
from gaitc.ir.manager import manager
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.sim.view import InputKey, NodeReading

T = TypeVar("T")


class SymbolicStrategy(NodeReading):
    """The interface of :class:`gaitc.sim.strategy.Strategy`, over a symbolic controller."""

    kind = ControllerKind.STRATEGY

    def __init__(self, ctrl: SymbolicController, spec: GR1Spec, file: str = "") -> None:
        self.ctrl, self.file = ctrl, file
        names = tuple(v.name for v in spec.inputs), tuple(v.name for v in spec.outputs)
        self.variables: tuple[str, ...] = names[0] + names[1]
        self.n_inputs = len(names[0])
        ins, outs = spec_bits(spec)
        if (ins, outs) != (ctrl.inputs, ctrl.outputs):  # in the words of 'gaitc verify'
            mismatch = bits_mismatch(ctrl.inputs + ctrl.outputs, ins + outs) or (
                "controller does not belong to this spec: its inputs and outputs are split "
                "differently from the spec's")
            raise ControllerError(
                mismatch, Span(file or "<controller>", 1, 1),
                hint="synthesize it again from this spec with 'gaitc synth --symbolic'")
        self._decoders = _decoders(ctrl, self.variables, file)
        bdd = manager()
        bits = ctrl.inputs + ctrl.outputs
        declare(bdd, ctrl)
        roots = materialize(bdd, ctrl)
        self.winning, self.env_init, self.sys_init = (
            roots["winning"], roots["env_init"], roots["sys_init"])
        self.env_trans = roots["env_trans"]
        self.goals: list[Any] = roots["goals"]
        self.strategies: list[Any] = roots["strategies"]
        # The manager after its functions: when the garbage collector clears a runtime
        # (its lazy tables refer back to it), the attributes go in this order, and CUDD
        # refuses to close a manager whose nodes are still referenced.
        del roots
        self.bdd = bdd
        self.pre = list(bits)
        self.rank = ctrl.choice_rank
        self.post_in = [b + "'" for b in ctrl.inputs]
        self.post_out = [b + "'" for b in ctrl.outputs]
        self._nodes: list[tuple[State, int]] = []
        self._index: dict[tuple[State, int], int] = {}
        self._options: dict[int, dict[InputKey, int]] = {}
        self.values: _Lazy[tuple[int, ...]] = _Lazy(self._value_of)
        self.successors: _Lazy[tuple[int, ...]] = _Lazy(self._successors_of)
        self.ranks: _Lazy[int] = _Lazy(lambda n: self._nodes[n][1])
        self.initial = tuple(self._node(s, 0) for s in self._initial_states())

    # ------------------------------------------------------------ Strategy interface
    def __len__(self) -> int:
        """The nodes discovered so far (a symbolic controller is never enumerated)."""
        return len(self._nodes)

    def options(self, node: int) -> dict[InputKey, int]:
        """The environment's possible moves at ``node``: input values → successor."""
        found = self._options.get(node)
        if found is None:
            found = dict(sorted((self.input_key(n), n) for n in self._expand(node)))
            self._options[node] = found
        return found

    def enter(self, bits: Mapping[str, bool], goal: int) -> int:
        """The node of the state ``bits`` (every input and output bit) pursuing ``goal``: a
        run that jumped there (a broken assumption, :mod:`gaitc.sim.recovery`) goes on from
        it.  The state must lie in the winning region for the node to have moves."""
        return self._node(tuple(int(bits[b]) for b in self.pre), goal % max(1, len(self.goals)))

    # ------------------------------------------------------------ stepping
    def _node(self, state: State, goal: int) -> int:
        key = (state, goal)
        found = self._index.get(key)
        if found is None:
            found = self._index[key] = len(self._nodes)
            self._nodes.append(key)
        return found

    def _initial_states(self) -> list[State]:
        bdd, ins, outs = self.bdd, list(self.ctrl.inputs), list(self.ctrl.outputs)
        if self.ctrl.semantics == Semantics.ROBOTICS:
            return all_assignments(bdd, self.env_init & self.sys_init & self.winning,
                                   ins + outs)
        out = []
        allowed = bdd.exist(set(outs), self.env_init)
        for x in all_assignments(bdd, allowed, ins):
            at = {b: bool(v) for b, v in zip(ins, x, strict=True)}
            y = first_assignment(bdd, bdd.let(at, self.sys_init & self.winning), outs,
                                 self.rank)
            if y is not None:
                out.append(x + y)
        return out

    def _expand(self, node: int) -> list[int]:
        """Every successor of ``node``: one per input ρe allows, in input order."""
        try:
            return self._expand_unchecked(node)
        except ValueError as err:  # a relation reads bits a runtime does not choose
            raise ControllerError(
                f"the symbolic controller cannot be run: at node {node} {err}; it is not a "
                "controller of this spec (gaitc verify says why)",
                Span(self.file or "<controller>", 1, 1),
                hint="synthesize it again from this spec with 'gaitc synth --symbolic'",
            ) from None

    def _expand_unchecked(self, node: int) -> list[int]:
        bdd = self.bdd
        state, goal = self._nodes[node]
        at = dict(zip(self.pre, map(bool, state), strict=True))
        here = bdd.let(at, self.strategies[goal])
        env_here = bdd.let(at, self.env_trans)
        keeping = here & env_here  # the moves that also keep ρe, preferred
        out = []
        for x in all_assignments(bdd, bdd.exist(set(self.post_out), env_here), self.post_in):
            at_x = dict(zip(self.post_in, map(bool, x), strict=True))
            choices = bdd.let(at_x, keeping)
            if choices == bdd.false:
                choices = bdd.let(at_x, here)
            y = first_assignment(bdd, choices, self.post_out, self.rank)
            if y is None:
                raise ControllerError(
                    f"the symbolic controller has no move at node {node} for an input ρe "
                    "allows; it is not a winning strategy for this spec",
                    Span(self.file or "<controller>", 1, 1))
            move = at | at_x | dict(zip(self.post_out, map(bool, y), strict=True))
            out.append(self._node(x + y, self._next_goal(goal, move)))
        return out

    def _next_goal(self, goal: int, move: Mapping[str, bool]) -> int:
        n, current = len(self.goals), goal
        for _ in range(n):
            if not holds_at(self.goals[current], move):
                break
            current = (current + 1) % n
        return current

    def _successors_of(self, node: int) -> tuple[int, ...]:
        return tuple(sorted(set(self.options(node).values())))

    def _value_of(self, node: int) -> tuple[int, ...]:
        bits = dict(zip(self.pre, self._nodes[node][0], strict=True))
        return tuple(decode(bits) for decode in self._decoders)


class _Lazy(Generic[T]):
    """A read-only sequence filled on demand: ``seq[k]`` computes and caches item k."""

    def __init__(self, make: Callable[[int], T]) -> None:
        self._cache: dict[int, T] = {}
        self._make = make

    def __getitem__(self, k: int) -> T:
        found = self._cache.get(k)
        if found is None:
            found = self._cache[k] = self._make(k)
        return found

    def __iter__(self) -> Iterator[T]:
        raise TypeError("a symbolic controller's nodes are found by running it, not listed")


def _decoders(ctrl: SymbolicController, variables: tuple[str, ...], file: str) -> list[Any]:
    """Per spec variable, a function from the bit values to its value."""
    out = []
    bits = set(ctrl.inputs) | set(ctrl.outputs)
    for name in variables:
        iv = ctrl.integers.get(name)
        if iv is not None:
            out.append(lambda v, iv=iv: iv.low + sum(v[b] << k for k, b in enumerate(iv.bits)))
        elif name in bits:
            out.append(lambda v, name=name: v[name])
        else:
            raise ControllerError(
                f"controller does not belong to this spec: it has no bit for {name!r}",
                Span(file or "<controller>", 1, 1),
                hint="synthesize it again from this spec with 'gaitc synth --symbolic'")
    return out
