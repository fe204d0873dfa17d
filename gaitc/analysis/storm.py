"""Storm, the probabilistic model checker (Hensel et al., "The probabilistic model checker
Storm", STTT 2022), on the arrays of :mod:`gaitc.analysis.markov`: the only module that
imports ``stormpy`` (the ``chances`` extra).

A model is built with stormpy's sparse matrix builder, labelled, and checked with PCTL:
step-bounded reachability ``Pmax=? [F<=n "target"]`` (exact: n matrix-vector products over
the choices), unbounded ``Pmax=? [F "target"]`` with the optimal memoryless scheduler, and
expected rewards.  The patrol count is a product with a saturating counter (layers 0..K):
one bounded query on it gives the chances of every k at once, since the value of the start
in layer c is the chance of K - c more patrols.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from gaitc.analysis.markov import Arrays
from gaitc.diagnostics import UsageError

EXTRA = "chances"
PRECISION = 1e-10  # the value iteration's relative precision for the unbounded properties


def require_storm() -> Any:
    """The ``stormpy`` module, or a usage error naming the extra that installs it."""
    try:
        # lazy: the chances extra (stormpy) may be missing; gaitc chances then names it
        import stormpy
    except ImportError:
        raise UsageError(f"gaitc chances needs Storm's Python binding: pip install "
                         f"'gaitc[{EXTRA}]' (or scripts/setup.sh)") from None
    return stormpy


@dataclass
class Layered:
    """The arrays of a model, repeated once per patrol count 0..K: an entry into a state
    that completes a patrol moves up a layer (layer K keeps counting K)."""

    rows: NDArray[np.int64]
    cols: NDArray[np.int64]
    vals: NDArray[np.float64]
    groups: NDArray[np.int64]
    states: int


def layered(arrays: Arrays, full: NDArray[np.bool_], layers: int) -> Layered:
    """``arrays`` in ``layers`` + 1 copies (counts 0..``layers``)."""
    rows, cols, vals, _ = arrays.numpy()
    n, nrows = len(full), len(arrays.starts) - 1
    groups = np.asarray(arrays.groups, dtype=np.int64)
    up = full[cols].astype(np.int64)
    all_rows, all_cols, all_groups = [], [], []
    for c in range(layers + 1):
        all_rows.append(rows + c * nrows)
        all_cols.append(np.minimum(layers, c + up) * n + cols)
        all_groups.append(groups + c * nrows)
    return Layered(np.concatenate(all_rows), np.concatenate(all_cols),
                   np.tile(vals, layers + 1), np.concatenate(all_groups), n * (layers + 1))


def _matrix(stormpy: Any, rows: NDArray[np.int64], cols: NDArray[np.int64],
            vals: NDArray[np.float64], groups: NDArray[np.int64] | None) -> Any:
    count = int(rows.max()) + 1 if len(rows) else 0
    states = count if groups is None else len(groups)
    builder = stormpy.datastructures.SparseMatrixBuilder(
        rows=count, columns=states, entries=len(vals), force_dimensions=True,
        has_custom_row_grouping=groups is not None, row_groups=states if groups is not None
        else 0)
    builder.add_next_values(rows.tolist(), cols.tolist(), vals.tolist(),
                            [] if groups is None else groups.tolist())
    return builder.build()


def build(rows: NDArray[np.int64], cols: NDArray[np.int64], vals: NDArray[np.float64],
          groups: NDArray[np.int64] | None, labels: dict[str, NDArray[np.bool_]],
          rewards: dict[str, NDArray[np.float64]] | None = None) -> Any:
    """A Storm MDP (``groups``: the first row of each state) or Markov chain (None) with
    state 0 initial, ``labels`` over the states and state ``rewards``."""
    stormpy = require_storm()
    models = stormpy.models
    matrix = _matrix(stormpy, rows, cols, vals, groups)
    count = matrix.nr_columns
    labelling = models.StateLabeling(count)
    labelling.add_label("init")
    labelling.add_label_to_state("init", 0)
    for name, states in labels.items():
        labelling.add_label(name)
        for s in np.flatnonzero(states).tolist():
            labelling.add_label_to_state(name, s)
    reward_models = {name: models.SparseRewardModel(optional_state_reward_vector=v.tolist())
                     for name, v in (rewards or {}).items()}
    components = models.SparseModelComponents(transition_matrix=matrix,
                                              state_labeling=labelling,
                                              reward_models=reward_models)
    if groups is None:
        return models.SparseDtmc(components)
    return models.SparseMdp(components)


def _environment(stormpy: Any) -> Any:
    env = stormpy.Environment()
    try:
        env.solver.minmax.precision = stormpy.Rational(PRECISION)
        env.solver.native.precision = stormpy.Rational(PRECISION)
    except (AttributeError, TypeError):  # older bindings: Storm's default precision
        pass
    return env


def check(model: Any, formula: str, scheduler: bool = False) -> tuple[NDArray[np.float64], Any]:
    """The values of ``formula`` at every state, and the scheduler when asked for."""
    stormpy = require_storm()
    prop = stormpy.parse_properties(formula)[0]
    result = stormpy.model_checking(model, prop, extract_scheduler=scheduler,
                                    environment=_environment(stormpy))
    values = np.asarray(result.get_value_vector(), dtype=np.float64)
    return values, (result.get_scheduler() if scheduler else None)


def choices(scheduler: Any, states: int) -> list[int]:
    """The scheduler's choice (a row offset within its state) at every state."""
    return [scheduler.get_choice(s).get_deterministic_choice() for s in range(states)]


def finite(value: float) -> float | None:
    return value if math.isfinite(value) else None
