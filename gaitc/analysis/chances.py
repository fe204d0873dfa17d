"""How likely, not only whether: the chances of a patrol under rates, checked by Storm.

On the MDP of :mod:`gaitc.analysis.markov` (the robot's moves are the choices, the
environment's next inputs are drawn by the rates) Storm gives the best chance any controller
has of reaching each goal and of completing k patrols within N steps (step-bounded
``Pmax``, history-dependent schedulers included), and the best expected number of patrols in
N steps.  The controller it writes is Storm's optimal scheduler (``extract_scheduler=True``)
for completing K patrols on the model with the patrol counter (``Rmin`` of the steps where
they are sure, else unbounded ``Pmax``), its first layer's choices kept in every patrol;
its own chances are computed again on the Markov chain of the written file, and so is any
controller given (with the chance that the spec's assumptions hold for N steps and the
expected patrols before they first break).  Reference: Baier and Katoen, "Principles of Model
Checking", ch. 10 (MDPs, step-bounded reachability, optimal schedulers).
"""

from __future__ import annotations

import html
import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gaitc.analysis import storm
from gaitc.analysis.markov import (
    MAX_STATES,
    Arrays,
    ControllerChain,
    SpecModel,
    user_trans_clauses,
)
from gaitc.analysis.patrol_plot import write_patrol_plot
from gaitc.diagnostics import SpecSemanticError
from gaitc.ir.bits import encode_bits, spec_bits
from gaitc.ir.controller import Controller, ControllerKind, ControllerNode, spec_integers
from gaitc.ir.spec import GR1Spec
from gaitc.sim.domain import Domain, State
from gaitc.sim.rates import Rates, StepLaw
from gaitc.sim.strategy import strategy_from_controller
from gaitc.sim.view import StrategyView
from ltlcompiler.model import NO_GAIT, Model


@dataclass(frozen=True)
class ChancesOptions:
    """What to ask: the horizon in steps, the most patrols counted, and the most states the
    explicit model may have."""

    steps: int = 500
    patrols: int = 10
    max_states: int = MAX_STATES


@dataclass(frozen=True)
class Figures:
    """The chances of one robot (the best any controller can do, or one controller)."""

    patrols: tuple[float, ...]  # chance of at least k patrols within the horizon, k = 1..K
    goals: dict[str, float]  # chance of visiting each goal within the horizon
    expected_patrols: float  # expected patrols completed within the horizon
    states: int

    def steps_per_patrol(self, steps: int) -> float | None:
        return steps / self.expected_patrols if self.expected_patrols > 0 else None


@dataclass(frozen=True)
class Assumptions:
    """How long a controller's assumptions hold under the rates."""

    hold: float  # chance that no input breaks them within the horizon
    patrols_before_break: float | None  # expected patrols before the first break (None: ∞)


@dataclass(frozen=True)
class Gain:
    """What one change to the robot buys: the headline chance (at least K patrols within the
    horizon, the best any controller can do) and the expected patrols, before and after."""

    change: str  # in words: "one more health level on L3", "a cache in r8"
    patrols: float  # the headline chance with the change
    expected_patrols: float
    gain: float  # patrols - the headline chance without it
    states: int


@dataclass
class Chances:
    """The answer of ``gaitc chances``: numbers with the rates and the words that explain them."""

    spec: str
    rates: Rates
    rate_words: tuple[str, ...]
    options: ChancesOptions
    best: Figures
    written: Figures | None = None
    controller: Controller | None = None  # the best controller in expectation, to write
    given: Figures | None = None  # of the CONTROLLER given
    assumptions: Assumptions | None = None  # of the CONTROLLER given
    sensitivity: tuple[Gain, ...] = ()
    seconds: dict[str, float] = field(default_factory=dict)

    def plot(self, path: str) -> None:
        """Write the chance of at least k patrols against k (``.svg``, or ``.png`` with
        matplotlib)."""

        others = [(name, f.patrols) for name, f in (("the controller written", self.written),
                                                    ("the controller given", self.given))
                  if f is not None]
        write_patrol_plot(path, f"{self.spec}: at least k patrols within "
                          f"{self.options.steps} steps", self.best.patrols, others)

    def lines(self) -> list[str]:
        n = self.options.steps
        out = [f"{self.spec}: chances within {n} steps under these rates:"]
        out += [f"  - {w}" for w in self.rate_words]
        out.append(f"the best any controller can do (Storm, an MDP of {self.best.states} "
                   "states; the controller may remember anything):")
        out += _figure_lines(self.best, n)
        if self.written is not None:
            nodes = len(self.controller.nodes) if self.controller else 0
            out.append(f"the controller written (Storm's optimal scheduler for "
                       f"{self.options.patrols} patrols, in every patrol; {nodes} nodes):")
            out += _figure_lines(self.written, n)
        if self.given is not None:
            out.append("the controller given:")
            out += _figure_lines(self.given, n)
        if self.assumptions is not None:
            a = self.assumptions
            out.append(f"  its assumptions hold for {n} steps with chance {a.hold:.6f}")
            out.append("  expected patrols before they first break: " + (
                "unbounded (they hold for ever with a positive chance)"
                if a.patrols_before_break is None else f"{a.patrols_before_break:.2f}"))
        if self.sensitivity:
            k = self.options.patrols
            out.append(f"what one change buys (the best chance of at least {k} patrols within "
                       f"{n} steps, now {self.best.patrols[-1]:.6f}):")
            out += [f"  {g.change}: {g.patrols:.6f} ({g.gain:+.6f}), "
                    f"{g.expected_patrols:.3f} patrols expected" for g in self.sensitivity]
        return out

    def __str__(self) -> str:
        return "\n".join(self.lines())

    def __repr__(self) -> str:
        k = self.options.patrols
        written = "" if self.written is None else \
            f", the controller written {self.written.patrols[-1]:.6f}"
        return (f"<Chances of {self.spec!r} within {self.options.steps} steps: at least {k} "
                f"patrols, best {self.best.patrols[-1]:.6f}{written}; "
                f"{self.best.states} states>")

    def _repr_html_(self) -> str:
        head = f"<p><b>{html.escape(self.spec)}</b>: chances within {self.options.steps} steps</p>"
        rates = "".join(f"<li>{html.escape(w)}</li>" for w in self.rate_words)
        rows = "".join(
            f"<tr><td>{k}</td><td>{p:.6f}</td>"
            + (f"<td>{self.written.patrols[k - 1]:.6f}</td>" if self.written else "")
            + (f"<td>{self.given.patrols[k - 1]:.6f}</td>" if self.given else "") + "</tr>"
            for k, p in enumerate(self.best.patrols, 1))
        cols = "<th>k</th><th>best</th>" + ("<th>written</th>" if self.written else "") + \
            ("<th>given</th>" if self.given else "")
        return (f"{head}<ul>{rates}</ul><table><caption>chance of at least k patrols"
                f"</caption><tr>{cols}</tr>{rows}</table>")

    def to_json(self) -> dict[str, Any]:
        def figures(f: Figures | None) -> dict[str, Any] | None:
            if f is None:
                return None
            return {"patrols": [{"k": k, "probability": p} for k, p in enumerate(f.patrols, 1)],
                    "goals": dict(f.goals), "expected_patrols": f.expected_patrols,
                    "steps_per_patrol": f.steps_per_patrol(self.options.steps),
                    "states": f.states}

        best = figures(self.best)
        assert best is not None
        a = self.assumptions
        return {"spec": self.spec, "steps": self.options.steps, "rates": self.rates.to_json(),
                "explained": list(self.rate_words), **best,
                "written": figures(self.written), "given": figures(self.given),
                "assumptions": None if a is None else {
                    "hold": a.hold, "patrols_before_break": a.patrols_before_break},
                "sensitivity": [{"change": g.change, "probability": g.patrols, "gain": g.gain,
                                 "expected_patrols": g.expected_patrols, "states": g.states}
                                for g in self.sensitivity],
                "seconds": {k: round(v, 3) for k, v in self.seconds.items()}}


def _figure_lines(f: Figures, steps: int) -> list[str]:
    out = [f"  completes at least {k} patrol{'s' if k > 1 else ''} (the goals in their "
           f"order) with chance {p:.6f}" + (f" (misses with chance {1 - p:.2g})"
                                            if 0.999 < p < 1.0 - 1e-12 else "")
           for k, p in enumerate(f.patrols, 1)]
    out += [f"  visits {goal} with chance {p:.6f}" for goal, p in f.goals.items()]
    per = f.steps_per_patrol(steps)
    out.append(f"  expects {f.expected_patrols:.3f} patrols in {steps} steps" + (
        f": one every {per:.1f} steps, time stuck included" if per is not None else ""))
    return out


# ---------------------------------------------------------------- the questions
def _figures(arrays: Arrays, full: NDArray[np.bool_], goal_states: list[NDArray[np.bool_] | None],
             labels: tuple[str, ...], groups: NDArray[np.int64] | None, opt: ChancesOptions,
             best: bool) -> Figures:
    """The patrol and goal chances and the expected patrols on a model (an MDP when
    ``groups`` is given, maximised; else a Markov chain)."""
    p = "Pmax" if best and groups is not None else "P"
    r = 'R{"patrols"}max' if best and groups is not None else 'R{"patrols"}'
    bound = opt.steps + 1  # the start's first transition is the environment's first input
    k_max, n = opt.patrols, len(full)
    lay = storm.layered(arrays, full, k_max)
    top = np.zeros(lay.states, dtype=bool)
    top[k_max * n:] = True
    model = storm.build(lay.rows, lay.cols, lay.vals, lay.groups if groups is not None else None,
                        {"top": top})
    values, _ = storm.check(model, f'{p}=? [F<={bound} "top"]')
    patrols = tuple(float(values[(k_max - k) * n]) for k in range(1, k_max + 1))
    rows, cols, vals, _ = arrays.numpy()
    known = {f"g{j}": states for j, states in enumerate(goal_states) if states is not None}
    model = storm.build(rows, cols, vals, groups, known)
    goals = {label: float(storm.check(model, f'{p}=? [F<={bound} "g{j}"]')[0][0])
             for j, label in enumerate(labels) if f"g{j}" in known}
    model = storm.build(rows, cols, vals, groups, {}, {"patrols": full.astype(np.float64)})
    expected, _ = storm.check(model, f'{r}=? [C<={bound + 1}]')
    return Figures(patrols, goals, float(expected[0]), n)


def _check_spec(model: Model, gr1: GR1Spec) -> None:
    if (model.assumptions or model.guarantees) and user_trans_clauses(gr1):
        raise SpecSemanticError(
            "gaitc chances reads the robot's physics (eqs. 3.3-3.9) and the goals; this "
            "spec also has written 'always' assumptions or guarantees, which its model "
            "does not take into account yet", None)


def chances(gr1: GR1Spec, model: Model, domain: Domain, rates: Rates, file: str, *,
            controller: StrategyView | None = None,
            options: ChancesOptions | None = None, write: bool = True,
            sensitive: bool = False) -> Chances:
    """The chances of the spec under ``rates``: the best, the controller it writes (when
    ``write``), the ``controller`` given and (when ``sensitive``) what one more health level
    or cache buys."""
    opt = options or ChancesOptions()
    _check_spec(model, gr1)
    law = StepLaw(model, rates)
    seconds: dict[str, float] = {}
    clock = time.perf_counter()
    mdp = SpecModel(model, domain, law, opt.max_states)
    seconds["model"] = time.perf_counter() - clock
    clock = time.perf_counter()
    groups = np.asarray(mdp.arrays.groups, dtype=np.int64)
    goal_states = [mdp.at_goal(j) for j in range(len(mdp.progress.labels))]
    best = _figures(mdp.arrays, mdp.full_states(), goal_states, mdp.progress.labels, groups,
                    opt, best=True)
    seconds["best"] = time.perf_counter() - clock
    answer = Chances(file, rates, tuple(rates.words(model)), opt, best, seconds=seconds)
    if write:
        clock = time.perf_counter()
        answer.controller = best_controller(gr1, mdp, opt.patrols)
        seconds["scheduler"] = time.perf_counter() - clock
        clock = time.perf_counter()

        view = strategy_from_controller(answer.controller, gr1, file="<written>")
        answer.written = chain_figures(view, domain, law, opt)
        seconds["written"] = time.perf_counter() - clock
    if sensitive:
        clock = time.perf_counter()
        answer.sensitivity = sensitivity(model, domain, rates, opt, best.patrols[-1])
        seconds["sensitivity"] = time.perf_counter() - clock
    if controller is not None:
        clock = time.perf_counter()
        answer.given = chain_figures(controller, domain, law, opt)
        answer.assumptions = assumptions(controller, domain, law, opt)
        seconds["given"] = time.perf_counter() - clock
    return answer


def _headline(model: Model, domain: Domain, rates: Rates, opt: ChancesOptions
              ) -> tuple[float, float, int]:
    """The best chance of at least K patrols within the horizon, the best expected patrols and
    the MDP's size."""
    mdp = SpecModel(model, domain, StepLaw(model, rates), opt.max_states)
    full = mdp.full_states()
    groups = np.asarray(mdp.arrays.groups, dtype=np.int64)
    n, k_max, bound = mdp.size, opt.patrols, opt.steps + 1
    lay = storm.layered(mdp.arrays, full, k_max)
    top = np.zeros(lay.states, dtype=bool)
    top[k_max * n:] = True
    values, _ = storm.check(storm.build(lay.rows, lay.cols, lay.vals, lay.groups,
                                        {"top": top}), f'Pmax=? [F<={bound} "top"]')
    rows, cols, vals, _ = mdp.arrays.numpy()
    expected, _ = storm.check(storm.build(rows, cols, vals, groups, {},
                                          {"patrols": full.astype(np.float64)}),
                              f'R{{"patrols"}}max=? [C<={bound + 1}]')
    return float(values[0]), float(expected[0]), n


def sensitivity(model: Model, domain: Domain, rates: Rates, opt: ChancesOptions,
                headline: float) -> tuple[Gain, ...]:
    """The gain in the headline chance from one more health level on each leg that has more
    than one, and from a cache on each free cell (no cache, no hazard), best first."""

    variants: list[tuple[str, Model]] = []
    for i, leg in enumerate(model.legs):
        if leg.health <= 1:
            continue
        more = replace(leg, health=leg.health + 1,
                       initial=leg.initial + (leg.initial == leg.health))
        legs = (*model.legs[:i], more, *model.legs[i + 1:])
        variants.append((f"one more health level on {leg.name}", replace(model, legs=legs)))
    hot = {r for h in model.hazards for r in h.regions}
    for region in model.regions:
        if region.name not in model.caches and region.name not in hot:
            variants.append((f"a cache in {region.name}",
                             replace(model, caches=(*model.caches, region.name))))
    gains = []
    for words, variant in variants:
        p, expected, states = _headline(variant, Domain(variant, domain.encoding), rates, opt)
        gains.append(Gain(words, p, expected, p - headline, states))
    return tuple(sorted(gains, key=lambda g: (-g.gain, -g.expected_patrols, g.change)))


def chain_figures(view: StrategyView, domain: Domain, law: StepLaw,
                  opt: ChancesOptions) -> Figures:
    """The chances of one controller (its Markov chain under the law)."""
    chain = ControllerChain(view, domain, law)
    goal_states = [chain.at_goal(j) for j in range(len(chain.progress.labels))]
    return _figures(chain.arrays, chain.full_states(), goal_states, chain.progress.labels,
                    None, opt, best=False)


def assumptions(view: StrategyView, domain: Domain, law: StepLaw,
                opt: ChancesOptions) -> Assumptions:
    """The chance that no input breaks the controller's assumptions within the horizon (a
    sudden failure beyond eq. 3.5, or an input it has no answer to), and the expected
    patrols before the first break."""
    chain = ControllerChain(view, domain, law)
    rows, cols, vals, breaks = chain.arrays.numpy()
    n = chain.size
    broken = n  # one more state: the assumptions broke
    cols = np.where(breaks | (cols == 1), broken, cols)
    rows = np.concatenate([rows, [rows.max() + 1]])
    cols = np.concatenate([cols, [broken]])
    vals = np.concatenate([vals, [1.0]])
    mark = np.zeros(n + 1, dtype=bool)
    mark[broken] = True
    reward = np.concatenate([chain.full_states().astype(np.float64), [0.0]])
    model = storm.build(rows, cols, vals, None, {"broken": mark}, {"patrols": reward})
    values, _ = storm.check(model, f'P=? [F<={opt.steps + 1} "broken"]')
    ever, _ = storm.check(model, 'P=? [F "broken"]')
    before: float | None = None
    if ever[0] >= 1.0 - 1e-9:
        expected, _ = storm.check(model, 'R{"patrols"}=? [F "broken"]')
        before = storm.finite(float(expected[0]))
    return Assumptions(max(0.0, 1.0 - float(values[0])), before)


# ---------------------------------------------------------------- the written controller
def best_controller(gr1: GR1Spec, mdp: SpecModel, patrols: int) -> Controller:
    """Storm's optimal scheduler for completing ``patrols`` patrols, as an explicit controller
    over the spec's variables.  On the model with the patrol counter: where the patrols are
    sure, the fastest way in expectation (``Rmin`` of the steps); elsewhere the likeliest
    (``Pmax``).  The controller keeps the choices of the counter's first layer (``patrols``
    still to go) in every patrol, so that, as a GR(1) controller, it remembers only the next
    goal (its rank: compact controllers and code generation keep nothing else): it never
    ends a patrol on legs it will miss for the next ones, but does not count them either.
    One node per (state, goal pursued); it answers every input the spec's physics allow (a
    sudden failure beyond them is an input it has no answer to)."""
    n = mdp.size
    lay = storm.layered(mdp.arrays, mdp.full_states(), patrols)
    top = np.zeros(lay.states, dtype=bool)
    top[patrols * n:] = True
    steps = np.ones(lay.states, dtype=np.float64)
    model = storm.build(lay.rows, lay.cols, lay.vals, lay.groups, {"top": top},
                        {"steps": steps})
    chance, likeliest = storm.check(model, 'Pmax=? [F "top"]', scheduler=True)
    _, fastest = storm.check(model, 'R{"steps"}min=? [F "top"]', scheduler=True)
    sure = (chance >= 1.0 - 1e-9).tolist()
    choice = [f if ok else c for f, c, ok in zip(storm.choices(fastest, n),
                                                  storm.choices(likeliest, n),
                                                  sure[:n], strict=True)]
    groups = np.asarray(mdp.arrays.groups, dtype=np.int64)
    domain, law, progress = mdp.domain, mdp.law, mdp.progress
    ins, outs = spec_bits(gr1)
    variables = {v.name: v for v in (*gr1.inputs, *gr1.outputs)}

    def bits(state: State) -> tuple[int, ...]:
        values = domain.encode(state)
        found: dict[str, bool] = {}
        for name, value in values.items():
            var = variables.get(name)
            if var is None:
                continue
            if var.low is not None:
                found.update(encode_bits(var, value))
            else:
                found[name] = bool(value)
        return tuple(int(found.get(b, False)) for b in (*ins, *outs))

    def move(region: str, levels: tuple[int, ...], hazard: str | None, mask: int
             ) -> tuple[str, str]:
        index = mdp.index.get((region, levels, hazard, mask))
        if index is None:  # a state the rates never reach: stay (always allowed)
            return region, NO_GAIT
        return mdp.actions[int(groups[index]) + choice[index]]  # layer 0: K patrols to go

    nodes: dict[tuple[State, int], int] = {}
    order: list[tuple[State, int]] = []
    full = progress.full

    def node(state: State, rank: int) -> int:
        """The node of ``state`` reached while pursuing goal ``rank`` (SLUGS's ranks: the
        node's moves are those of the goal after it when ``state`` reaches it)."""
        key = (state, rank)
        found = nodes.get(key)
        if found is None:
            found = nodes[key] = len(order)
            order.append(key)
        return found

    spec_model = mdp.model
    initial = [node(State(spec_model.start, NO_GAIT, mdp.start.health, hazard), 0)
               for hazard in (None, *(h.name for h in spec_model.hazards))]
    trans: list[tuple[int, ...]] = []
    k = 0
    while k < len(order):
        state, rank = order[k]
        mask = progress.step(rank, state)
        succ = set()
        for outcome in law.outcomes(state):
            if outcome.breaks:
                continue
            region, gait = move(state.region, outcome.levels, outcome.hazard, mask)
            entered = State(region, gait, outcome.health, outcome.hazard)
            succ.add(node(entered, 0 if mask == full else mask))
        trans.append(tuple(sorted(succ)))
        k += 1
    built = tuple(ControllerNode(rank, bits(state), trans[i])
                  for i, (state, rank) in enumerate(order))
    return Controller(variables=(*ins, *outs), inputs=ins, outputs=outs, nodes=built,
                      initial=tuple(initial), integers=spec_integers(gr1),
                      kind=ControllerKind.STRATEGY, solver="storm")

