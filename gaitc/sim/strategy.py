"""The controller as the simulator and renderer see it: spec-level values per node, successors.

Adapts a ``gaitc.ir.controller.Controller`` (JSON of ``docs/controller-format.md``, from the
embedded solver or SLUGS), checked against the spec it claims to implement, so a user learns
early that a controller belongs to another spec.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gaitc.diagnostics import ControllerError, Span
from gaitc.ir.bits import bits_mismatch, spec_bits
from gaitc.ir.controller import Controller, ControllerKind
from gaitc.ir.spec import GR1Spec
from gaitc.sim.monitor import compile_formula
from gaitc.sim.view import Indexed, InputKey, NodeReading, StrategyView

__all__ = ["Indexed", "InputKey", "NodeReading", "Strategy", "StrategyView", "explicit",
           "strategy_from_controller"]


@dataclass(frozen=True)
class Strategy(NodeReading):
    """An explicit Mealy machine over the spec's variables (inputs first, then outputs)."""

    variables: tuple[str, ...]
    n_inputs: int
    values: tuple[tuple[int, ...], ...]  # per node, in ``variables`` order
    successors: tuple[tuple[int, ...], ...]
    ranks: tuple[int, ...]
    initial: tuple[int, ...]
    kind: ControllerKind = ControllerKind.STRATEGY
    file: str = ""
    _options: dict[int, dict[InputKey, int]] = field(
        default_factory=dict, compare=False, repr=False
    )

    def __len__(self) -> int:
        return len(self.values)

    def options(self, node: int) -> dict[InputKey, int]:
        """The environment's possible moves at ``node``: input values → successor (lowest id)."""
        found = self._options.get(node)
        if found is None:
            found = {}
            for succ in self.successors[node]:
                found.setdefault(self.input_key(succ), succ)
            found = dict(sorted(found.items()))
            self._options[node] = found
        return found


def _where(file: str) -> Span:
    return Span(file or "<controller>", 1, 1)


def strategy_from_controller(controller: Controller, spec: GR1Spec, file: str = "") -> Strategy:
    """Adapt ``controller`` to ``spec``: spec-level values per node, ranges checked.

    A raw SLUGS file lists no initial nodes; then every node satisfying the spec's initial
    clauses may start a run.
    """
    inputs = tuple(v.name for v in spec.inputs)
    variables = inputs + tuple(v.name for v in spec.outputs)
    ins, outs = spec_bits(spec)
    mismatch = bits_mismatch(controller.variables, ins + outs, order_matters=False)
    if mismatch is not None:  # the words of 'gaitc verify'; bits are read by name here
        raise ControllerError(mismatch, _where(file),
                              hint="synthesize it again from this spec with 'gaitc synth'")
    values: list[tuple[int, ...]] = []
    for node in range(len(controller.nodes)):
        decoded = controller.values(node)
        missing = [name for name in variables if name not in decoded]
        if missing:
            raise ControllerError(
                f"controller does not belong to this spec: node {node} has no value for "
                f"{', '.join(repr(m) for m in missing[:3])}",
                _where(file), hint="synthesize it again from this spec with 'gaitc synth'",
            )
        values.append(tuple(int(decoded[name]) for name in variables))
    _check_ranges(spec, variables, values, file)
    initial = tuple(sorted(set(controller.initial)))
    if not initial:
        initial = _initial_nodes(spec, variables, values)
    return Strategy(

        variables=variables,
        n_inputs=len(inputs),
        values=tuple(values),
        successors=tuple(tuple(sorted(n.trans)) for n in controller.nodes),
        ranks=tuple(n.rank for n in controller.nodes),
        initial=initial,
        kind=controller.kind,
        file=file,
    )


def _initial_nodes(
    spec: GR1Spec, variables: tuple[str, ...], values: list[tuple[int, ...]]
) -> tuple[int, ...]:
    checks = [compile_formula(c.formula, variables) for c in spec.env_init + spec.sys_init]
    return tuple(n for n, row in enumerate(values) if all(fn(row + row) for fn in checks))


def _check_ranges(
    spec: GR1Spec, variables: tuple[str, ...], values: list[tuple[int, ...]], file: str
) -> None:
    bounds = []
    for name in variables:
        var = spec.variable(name)
        if var is None or var.low is None or var.high is None:
            bounds.append((0, 1))
        else:
            bounds.append((var.low, var.high))
    for node, row in enumerate(values):
        for name, value, (low, high) in zip(variables, row, bounds, strict=True):
            if not low <= value <= high:
                raise ControllerError(
                    f"controller does not belong to this spec: node {node} gives {name} = "
                    f"{value}, outside {low}..{high}",
                    _where(file), hint="synthesize it again from this spec with 'gaitc synth'",
                )


def explicit(view: StrategyView, what: str) -> Strategy:
    """``view`` as an explicit automaton, for ``what`` needs every node listed."""
    if isinstance(view, Strategy):
        return view
    raise ControllerError(
        f"{what} needs an explicit controller, and {view.file or 'this one'} is symbolic "
        "(its nodes are found by running it)", _where(view.file),
        hint="synthesize an explicit controller with 'gaitc synth' (without --symbolic), or "
        "draw a run of this one with 'render map --run'")
