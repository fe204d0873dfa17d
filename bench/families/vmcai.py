"""The arbiter and lift families of the first GR(1) paper, as ``.structuredslugs``.

Piterman, Pnueli and Sa'ar, "Synthesis of Reactive(1) Designs" (VMCAI 2006, section 5)
introduced GR(1) synthesis with two parameterized examples, written here from the paper's
formulas:

* **Arbiter** for N clients: requests ``r<i>`` (environment) and grants ``g<i>`` (system).
  A request is raised or lowered only when it equals its grant, and every client releases
  the resource infinitely often (``GF !(r & g)``, N justice assumptions); the arbiter gives
  no grant at the start, at most one at a time, changes a grant only when it differs from its
  request, and answers every client infinitely often (``GF (r <-> g)``, N justice
  guarantees).  Its N x N assumption-goal pairs stress the fixpoint's inner loop, which the
  other families, with one or two assumptions, do not.  ``fair=False`` drops the clients'
  fairness, which makes the task unrealizable (a client that keeps its grant starves the
  others): a large unrealizable row.
* **Lift** for N floors: call buttons ``b<i>`` (environment; pressed, a button stays on until
  the lift is at its floor, and goes off then) and the floor ``f<i>`` one-hot (system; the
  lift starts at floor 0, moves at most one floor per step, moves up only while some button
  is on, serves every call infinitely often, and returns to floor 0 or is called infinitely
  often).  One-hot floors leave most valuations of the state bits unreachable.

Both are realizable as written; the rows' verdicts in the benchmark are these.
"""

from __future__ import annotations

from bench.families.amba import Sections

#: Sizes of the families in the benchmark table.
ARBITER_SIZES = [2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]
LIFT_SIZES = [2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]


def arbiter_sections(n: int, fair: bool = True) -> Sections:
    """The arbiter for ``n`` clients (at least 1); ``fair=False`` leaves out the clients'
    justice assumptions."""
    if n < 1:
        raise ValueError(f"the arbiter family has at least 1 client, not {n}")
    clients = range(n)
    requests = [f"r{i}" for i in clients]
    grants = [f"g{i}" for i in clients]
    pairs = list(zip(requests, grants, strict=True))
    env_trans = [f"!({r} <-> {g}) -> ({r}' <-> {r})" for r, g in pairs]
    env_liveness = [f"!({r} & {g})" for r, g in pairs] if fair else []
    sys_trans = [f"!({grants[i]}' & {grants[j]}')" for i in clients for j in clients if i < j]
    sys_trans += [f"({r} <-> {g}) -> ({g}' <-> {g})" for r, g in pairs]
    sys_liveness = [f"{r} <-> {g}" for r, g in pairs]
    return Sections(requests, grants, [f"!{r}" for r in requests], env_trans, env_liveness,
                    [f"!{g}" for g in grants], sys_trans, sys_liveness)


def arbiter_text(n: int, fair: bool = True) -> str:
    """The ``.structuredslugs`` text of the ``n``-client arbiter (deterministic)."""
    variant = "" if fair else ", without the clients' fairness (unrealizable)"
    return arbiter_sections(n, fair).text(f"arbiter, {n} clients{variant} (VMCAI 2006)")


def lift_sections(n: int) -> Sections:
    """The lift for ``n`` floors (at least 2)."""
    if n < 2:
        raise ValueError(f"the lift family has at least 2 floors, not {n}")
    floors = range(n)
    buttons = [f"b{i}" for i in floors]
    at = [f"f{i}" for i in floors]
    env_trans = []
    for b, f in zip(buttons, at, strict=True):
        env_trans.append(f"({b} & {f}) -> !{b}'")  # a served call ends
        env_trans.append(f"({b} & !{f}) -> {b}'")  # an open call stays
    some_button = "(" + " | ".join(buttons) + ")"
    sys_trans = [f"!({at[i]}' & {at[j]}')" for i in floors for j in floors if i < j]
    sys_trans.append("(" + " | ".join(f"{f}'" for f in at) + ")")  # at some floor
    for i in floors:
        near = [at[k] + "'" for k in (i - 1, i, i + 1) if 0 <= k < n]
        sys_trans.append(f"{at[i]} -> ({' | '.join(near)})")  # at most one floor a step
        if i + 1 < n:
            sys_trans.append(f"({at[i]} & {at[i + 1]}') -> {some_button}")  # up only if called
    sys_liveness = [f"{b} -> {f}" for b, f in zip(buttons, at, strict=True)]
    sys_liveness.append(f"{at[0]} | {some_button}")
    return Sections(buttons, at, [f"!{b}" for b in buttons], env_trans, [],
                    [at[0], *(f"!{f}" for f in at[1:])], sys_trans, sys_liveness)


def lift_text(n: int) -> str:
    """The ``.structuredslugs`` text of the ``n``-floor lift (deterministic)."""
    return lift_sections(n).text(f"lift, {n} floors (VMCAI 2006)")
