"""Seeded random GR(1) specs of six structured shapes, as structuredslugs text.

The shapes are ones that the fixed families of this folder and the tiny random corpus
(tests/data/gr1_corpus) do not cover, each of 15-45 Boolean variables, with 1-4 liveness
assumptions and 1-4 liveness guarantees:

* ``counter``  integer counters stepped, held or reset by input bits, with targets;
* ``compare``  integer trackers/comparators of two slowly changing integer inputs;
* ``mutex``    requests and grants in one-hot or at-most-one groups, blocking pairs;
* ``graph``    robots on random graphs (integer positions) avoiding a moving obstacle and
  closed doors, with reachability goals;
* ``automata`` products of small random automata (integer states), input-driven, with
  forbidden joint states and accepting-state goals;
* ``invariant`` random 3-4 literal clauses with next-state literals, random liveness.

A spec is a function of its shape and seed alone (:func:`shape_text`).  Used by
bench/bench_random_families.py, the differential campaign against SLUGS.
"""

from __future__ import annotations

import random
from collections.abc import Callable

Sections = dict[str, list[str]]
SECTION_ORDER = ("INPUT", "OUTPUT", "ENV_INIT", "SYS_INIT", "ENV_TRANS", "SYS_TRANS",
                 "ENV_LIVENESS", "SYS_LIVENESS")


def empty() -> Sections:
    return {name: [] for name in SECTION_ORDER}


def render(sections: Sections, title: str) -> str:
    out = [f"# {title}", ""]
    for name in SECTION_ORDER:
        out += [f"[{name}]", *sections[name], ""]
    return "\n".join(out)


def pick(rng: random.Random, items: list[str], low: int, high: int) -> list[str]:
    """Between ``low`` and ``high`` distinct items (fewer if there are fewer)."""
    count = min(len(items), rng.randint(low, high))
    return rng.sample(items, count)


def lit(rng: random.Random, name: str) -> str:
    return name if rng.random() < 0.5 else f"!{name}"


def one_of(options: list[str]) -> str:
    return "(" + " | ".join(options) + ")" if len(options) > 1 else options[0]


# ----------------------------------------------------------------------------- shapes
def counter(rng: random.Random) -> Sections:
    """Counters ``c<i>:0...M`` stepped on ``inc<i>'``, reset on ``rst'``, with targets."""
    s = empty()
    friendly = rng.random() < 0.5  # sys-driven counters, a stable target, fair inputs
    n = rng.randint(2, 5)
    maxima = [rng.choice([5, 7, 11, 15, 23, 31, 47, 63]) for _ in range(n)]
    incs = [f"inc{i}" for i in range(n)]
    s["INPUT"] = [*incs, "rst", "hold"]
    target_max = rng.choice([3, 7, 15])
    if friendly:
        target_max = min(target_max, *maxima)
    s["INPUT"].append(f"tgt:0...{target_max}")
    counters = [f"c{i}" for i in range(n)]
    s["OUTPUT"] = [f"{c}:0...{m}" for c, m in zip(counters, maxima, strict=True)]
    s["OUTPUT"] += ["done", "busy"]
    s["ENV_INIT"] = ["!rst", "tgt = 0"] if rng.random() < 0.5 else ["!rst"]
    s["SYS_INIT"] = [f"{c} = 0" for c in counters if rng.random() < 0.7]
    # the target moves only when done, by at most one, or freely
    if friendly or rng.random() < 0.6:
        s["ENV_TRANS"].append("!done -> tgt' = tgt")
    if rng.random() < 0.5:
        s["ENV_TRANS"].append("tgt' <= tgt + 1")
    if friendly or rng.random() < 0.4:
        s["ENV_TRANS"].append("rst -> !rst'")
    if rng.random() < 0.4:
        s["ENV_TRANS"].append("busy -> !hold'")
    for c, m, inc in zip(counters, maxima, incs, strict=True):
        mode = rng.random() * (0.6 if friendly else 1.0) + (0.4 if friendly else 0.0)
        reset = rng.random() < (0.2 if friendly else 0.8)
        if mode < 0.4:  # exact: step on inc, hold otherwise
            s["SYS_TRANS"].append(f"(!rst' & {inc}' & {c} < {m}) -> {c}' = {c} + 1")
            s["SYS_TRANS"].append(f"(!rst' & !{inc}') -> {c}' = {c}")
        elif mode < 0.8:  # may step or hold, only when enabled
            s["SYS_TRANS"].append(f"({c}' = {c} | {c}' = {c} + 1 | {c}' = 0)")
            s["SYS_TRANS"].append(f"!{inc}' -> {c}' <= {c}")
        else:  # wraps
            s["SYS_TRANS"].append(f"({inc}' & {c} = {m}) -> {c}' = 0")
            s["SYS_TRANS"].append(f"({inc}' & {c} < {m}) -> {c}' = {c} + 1")
            s["SYS_TRANS"].append(f"!{inc}' -> ({c}' = {c} | rst')")
        if reset:
            s["SYS_TRANS"].append(f"rst' -> {c}' = 0")
        if rng.random() < 0.3:
            s["SYS_TRANS"].append(f"hold' -> {c}' = {c}")
    a, b = rng.sample(counters, 2)
    s["SYS_TRANS"].append(rng.choice([f"done' <-> {a}' = tgt'", f"done' <-> {a}' >= tgt'",
                                      f"done' <-> ({a}' = tgt' & {b}' <= {a}')"]))
    s["SYS_TRANS"].append(f"busy' <-> ({a}' != 0 | {b}' != 0)")
    if not friendly and rng.random() < 0.5:
        s["SYS_TRANS"].append(f"{a}' <= {b}' + {rng.randint(1, 4)}")
    env_live = [f"{i}" for i in incs] + ["!rst", "!hold", "rst", "tgt = 0"]
    s["ENV_LIVENESS"] = pick(rng, env_live, 1, 4)
    if friendly:
        s["ENV_LIVENESS"] = [f"inc{counters.index(a)} & !rst & !hold",
                             f"inc{counters.index(b)} & !rst & !hold", *s["ENV_LIVENESS"]][:4]
    sys_live = ["done", "!busy", f"{a} = {rng.randint(0, maxima[counters.index(a)])}",
                f"{b} = 0", f"{a} = {b}", f"{a} + {b} >= tgt", "busy"]
    s["SYS_LIVENESS"] = pick(rng, sys_live[:2] if friendly else sys_live, 1, 4)
    return s


def compare(rng: random.Random) -> Sections:
    """Trackers ``m<i>`` of two slowly moving integer inputs, with comparator flags."""
    s = empty()
    friendly = rng.random() < 0.5  # consistent tracker rules, no rate limit
    top = rng.choice([7, 9, 15, 23, 31, 63])
    s["INPUT"] = [f"x:0...{top}", f"y:0...{top}", "frz"]
    trackers = [f"m{i}" for i in range(rng.randint(1, 4))]
    s["OUTPUT"] = [f"{m}:0...{top}" for m in trackers] + ["lt", "eq"]
    s["ENV_INIT"] = ["x = 0"] if rng.random() < 0.5 else []
    s["SYS_INIT"] = [f"{m} = 0" for m in trackers if rng.random() < 0.5]
    step = rng.choice([1, 1, 2, 3])
    for v in ("x", "y"):
        if rng.random() < 0.8:
            s["ENV_TRANS"].append(f"{v}' <= {v} + {step} & {v} <= {v}' + {step}")
        if rng.random() < 0.3:
            s["ENV_TRANS"].append(f"frz -> {v}' = {v}")
    if rng.random() < 0.3:
        s["ENV_TRANS"].append("frz -> !frz'")
    s["SYS_TRANS"].append("lt' <-> x' < y'")
    s["SYS_TRANS"].append("eq' <-> x' = y'")
    rules = [
        "{m}' >= x'", "{m}' >= y'", "({m}' = x' | {m}' = y')", "{m}' <= x' + y'",
        "{m}' <= {m} + {r} & {m} <= {m}' + {r}", "lt' -> {m}' >= y'", "!lt' -> {m}' <= x' + 1",
        "frz' -> {m}' = {m}", "{m}' + {r} >= x'", "eq -> {m}' = {m}",
    ]
    for m in trackers:
        for rule in pick(rng, rules[:4] if friendly else rules, 1, 3):
            s["SYS_TRANS"].append(rule.format(m=m, r=rng.randint(1, 3)))
    if len(trackers) > 1 and rng.random() < 0.6:
        s["SYS_TRANS"].append(f"{trackers[0]}' <= {trackers[1]}'")
    env_live = ["x = y", "x = 0", f"y = {top}", "!frz", "lt", "x < y", "y = 0"]
    s["ENV_LIVENESS"] = pick(rng, env_live, 1, 4)
    sys_live = [f"{m} = x" for m in trackers] + [f"{m} = y" for m in trackers]
    sys_live += [f"{trackers[0]} = 0", f"{trackers[-1]} >= x + 1", "eq | lt"]
    if friendly:
        m = trackers[0]
        sys_live = [f"{m} >= x", f"{m} >= y", f"eq | {m} = x | {m} = y", f"{m} + 1 >= x + y"]
    s["SYS_LIVENESS"] = pick(rng, sys_live, 1, 3)
    return s


def mutex(rng: random.Random) -> Sections:
    """Request/grant clients, grants grouped one-hot or at most one, with blocking pairs."""
    s = empty()
    friendly = rng.random() < 0.5  # requests held until granted and released, no blocking
    n = rng.randint(7, 20)
    reqs = [f"r{i}" for i in range(n)]
    grants = [f"g{i}" for i in range(n)]
    s["INPUT"] = [*reqs, "pause"]
    s["OUTPUT"] = list(grants)
    order = list(range(n))
    rng.shuffle(order)
    groups: list[list[int]] = []
    while order:
        size = min(len(order), rng.randint(2, 5))
        groups.append(order[:size])
        order = order[size:]
    for k, group in enumerate(groups):
        members = [f"{grants[i]}'" for i in group]
        for x in range(len(members)):
            for y in range(x + 1, len(members)):
                s["SYS_TRANS"].append(f"!({members[x]} & {members[y]})")
        if rng.random() < 0.35:  # one-hot with an idle output
            idle = f"idle{k}"
            s["OUTPUT"].append(idle)
            s["SYS_TRANS"].append(one_of([*members, f"{idle}'"]))
            s["SYS_TRANS"] += [f"!({idle}' & {m})" for m in members]
    s["ENV_INIT"] = [f"!{r}" for r in reqs if rng.random() < 0.6]
    s["SYS_INIT"] = [f"!{g}" for g in grants if rng.random() < 0.6]
    sticky = friendly or rng.random() < 0.7
    for r, g in zip(reqs, grants, strict=True):
        if sticky:
            s["ENV_TRANS"].append(f"({r} & !{g}) -> {r}'")
        if friendly or rng.random() < 0.5:
            s["ENV_TRANS"].append(f"({r} & {g}) -> !{r}'")
        s["SYS_TRANS"].append(rng.choice([f"{g}' -> {r}'", f"{g}' -> ({r} | {r}')",
                                          f"({g} & {r}') -> {g}'"][:2 if friendly else 3]))
    for _ in range(0 if friendly else rng.randint(0, 3)):  # a request of j blocks i's grant
        i, j = rng.sample(range(n), 2)
        s["SYS_TRANS"].append(f"{reqs[j]}' -> !{grants[i]}'")
    if rng.random() < 0.5:
        s["SYS_TRANS"].append("pause' -> " + " & ".join(f"!{g}'" for g in grants[:3]))
    # at most four guarantees: clients are bundled into conjunctions
    bundles = rng.randint(1, 4)
    if friendly:  # one client a guarantee: a round robin serves them
        for i in rng.sample(range(n), bundles):
            s["SYS_LIVENESS"].append(f"{reqs[i]} -> {grants[i]}")
        bundles = 0
    members_of: list[list[int]] = [[] for _ in range(bundles)]
    for i in range(n if bundles else 0):
        members_of[rng.randrange(bundles)].append(i)
    for members in members_of[:bundles]:
        if members:
            form = rng.choice(["({r} -> {g})", "({r} <-> {g})", "!({r} & !{g})"])
            s["SYS_LIVENESS"].append(" & ".join(form.format(r=reqs[i], g=grants[i])
                                                for i in members))
    env_live = ["!pause"] + [f"!{r}" for r in reqs] + [f"!({r} & {g})"
                                                       for r, g in zip(reqs, grants, strict=True)]
    s["ENV_LIVENESS"] = pick(rng, env_live, 1, 4)
    return s


def _graph(rng: random.Random, size: int, degree: int) -> list[list[int]]:
    """Successor lists of a random graph on ``size`` nodes, a cycle through all plus chords."""
    order = list(range(size))
    rng.shuffle(order)
    succ: list[set[int]] = [set() for _ in range(size)]
    for k in range(size):
        if rng.random() < 0.85:
            succ[order[k]].add(order[(k + 1) % size])
    for v in range(size):
        for _ in range(rng.randint(0, degree)):
            succ[v].add(rng.randrange(size))
        if rng.random() < 0.5:
            succ[v].add(v)
        if not succ[v]:
            succ[v].add(rng.randrange(size))
    return [sorted(x) for x in succ]


def _moves(var: str, succ: list[list[int]]) -> list[str]:
    return [f"{var} = {v} -> " + one_of([f"{var}' = {w}" for w in ws])
            for v, ws in enumerate(succ)]


def graph(rng: random.Random) -> Sections:
    """1-2 robots on a random graph avoiding an obstacle and closed doors, visiting targets."""
    s = empty()
    friendly = rng.random() < 0.5  # an undirected graph, the obstacle moves, doors open
    size = rng.randint(12, 64)
    obst = rng.randint(4, 32)
    robots = ["p", "q"][:rng.randint(1, 2)]
    doors = [f"d{k}" for k in range(rng.randint(1, 8))]
    s["INPUT"] = [f"o:0...{obst - 1}", *doors]
    s["OUTPUT"] = [f"{p}:0...{size - 1}" for p in robots]
    succ = _graph(rng, size, rng.choice([1, 2, 3]))
    if friendly:
        both = [set(ws) for ws in succ]
        for v, ws in enumerate(succ):
            for w in ws:
                both[w].add(v)
        succ = [sorted(ws | {v}) for v, ws in enumerate(both)]
    osucc = _graph(rng, obst, rng.choice([1, 2]))
    s["ENV_INIT"] = [f"o = {obst - 1}"]
    s["SYS_INIT"] = [f"{p} = {k}" for k, p in enumerate(robots)]
    s["ENV_TRANS"] = _moves("o", osucc)
    if friendly or rng.random() < 0.6:  # doors close one at a time
        for x in range(len(doors)):
            for y in range(x + 1, len(doors)):
                s["ENV_TRANS"].append(f"!({doors[x]}' & {doors[y]}')")
    for p in robots:
        s["SYS_TRANS"] += _moves(p, succ)
        s["SYS_TRANS"].append(f"{p}' != o'")
        if rng.random() < 0.5:
            s["SYS_TRANS"].append(f"{p}' != o")
        for d in doors:
            s["SYS_TRANS"].append(f"{d}' -> {p}' != {rng.randrange(size)}")
    if len(robots) == 2:
        s["SYS_TRANS"].append("p' != q'")
    env_live = [f"o = {rng.randrange(obst)}" for _ in range(3)] + [f"!{d}" for d in doors]
    s["ENV_LIVENESS"] = pick(rng, env_live, 1, 4)
    if friendly:
        s["ENV_LIVENESS"] = ["o = 0 & " + " & ".join(f"!{d}" for d in doors),
                             f"o = {obst - 1}"][:rng.randint(1, 2)]
    targets = [f"{rng.choice(robots)} = {rng.randrange(size)}" for _ in range(4)]
    targets.append(f"{robots[0]} = {rng.randrange(size)} | {robots[-1]} = {rng.randrange(size)}")
    s["SYS_LIVENESS"] = pick(rng, targets, 1, 4)
    return s


def automata(rng: random.Random) -> Sections:
    """Product of small random automata: system ones read input letters and a choice bit."""
    s = empty()
    friendly = rng.random() < 0.5  # fewer forbidden joint states
    letters = [f"a{k}" for k in range(rng.randint(2, 5))]
    s["INPUT"] = list(letters)
    env_autos = [f"e{j}" for j in range(rng.randint(0, 2))]
    sys_autos = [f"s{i}" for i in range(rng.randint(3, 6))]
    states = {a: rng.randint(3, 12) for a in env_autos + sys_autos}
    s["INPUT"] += [f"{e}:0...{states[e] - 1}" for e in env_autos]
    s["OUTPUT"] = [f"{a}:0...{states[a] - 1}" for a in sys_autos]
    s["OUTPUT"] += [f"ch{i}" for i in range(len(sys_autos))]
    s["ENV_INIT"] = [f"{e} = 0" for e in env_autos]
    s["SYS_INIT"] = [f"{a} = 0" for a in sys_autos]
    for e in env_autos:  # env automata read outputs' current choice and their own letters
        guard = rng.choice(sys_autos)
        for q in range(states[e]):
            for bit in (f"ch{sys_autos.index(guard)}", f"!ch{sys_autos.index(guard)}"):
                nexts = sorted({rng.randrange(states[e]) for _ in range(rng.randint(1, 2))})
                s["ENV_TRANS"].append(f"({e} = {q} & {bit}) -> "
                                      + one_of([f"{e}' = {w}" for w in nexts]))
    for i, a in enumerate(sys_autos):
        reads = rng.sample(letters, rng.randint(1, 2))
        for q in range(states[a]):
            for mask in range(2 ** len(reads)):
                cond = [r if mask >> k & 1 else f"!{r}" for k, r in enumerate(reads)]
                for ch in (f"ch{i}'", f"!ch{i}'"):
                    target = rng.randrange(states[a])
                    s["SYS_TRANS"].append(f"({a} = {q} & " + " & ".join(f"{c}'" for c in cond)
                                          + f" & {ch}) -> {a}' = {target}")
    for _ in range(rng.randint(0, 1) if friendly else rng.randint(1, 4)):  # forbidden
        x, y = rng.sample(sys_autos + env_autos, 2)
        s["SYS_TRANS"].append(f"!({x}' = {rng.randrange(states[x])} & "
                              f"{y}' = {rng.randrange(states[y])})")
    if rng.random() < 0.5:
        x, y = rng.sample(letters, 2)
        s["ENV_TRANS"].append(f"!({x}' & {y}')")
    env_live = [lit(rng, a) for a in letters]
    env_live += [f"{e} = {rng.randrange(states[e])}" for e in env_autos]
    s["ENV_LIVENESS"] = pick(rng, env_live, 1, 4)
    sys_live = [f"{a} = {rng.randrange(states[a])}" for a in sys_autos]
    sys_live.append(" | ".join(f"{a} = {states[a] - 1}" for a in sys_autos[:2]))
    s["SYS_LIVENESS"] = pick(rng, sys_live, 1, 4)
    return s


def invariant(rng: random.Random) -> Sections:
    """Random clauses of 3-4 literals over current and next values, random liveness."""
    s = empty()
    friendly = rng.random() < 0.5  # sparser system clauses, goals over outputs only
    ni, no = rng.randint(7, 20), rng.randint(8, 25)
    xs = [f"x{k}" for k in range(ni)]
    ys = [f"y{k}" for k in range(no)]
    s["INPUT"], s["OUTPUT"] = xs, ys

    def clause(must: list[str], pool: list[str], width: int) -> str:
        first = lit(rng, rng.choice(must))
        rest = [lit(rng, v) for v in rng.sample(pool, width - 1)]
        if rng.random() < 0.15:
            return f"({first} ^ {rest[0]}) | " + " | ".join(rest[1:] or ["FALSE"])
        return " | ".join([first, *rest])

    everything = xs + ys
    s["ENV_INIT"] = [lit(rng, x) for x in rng.sample(xs, rng.randint(0, 3))]
    s["SYS_INIT"] = [lit(rng, y) for y in rng.sample(ys, rng.randint(0, 3))]
    env_pool = everything + [f"{x}'" for x in xs]
    for _ in range(rng.randint(1, max(2, ni // 3))):
        s["ENV_TRANS"].append(clause([f"{x}'" for x in xs], env_pool, rng.randint(3, 4)))
    sys_pool = env_pool + [f"{y}'" for y in ys]
    density = rng.uniform(0.3, 0.8) if friendly else rng.uniform(0.5, 1.6)
    for _ in range(max(3, int(no * density))):
        s["SYS_TRANS"].append(clause([f"{y}'" for y in ys], sys_pool, rng.randint(3, 4)))

    def live(pool: list[str]) -> str:
        vs = rng.sample(pool, rng.randint(1, 3))
        joint = rng.choice([" & ", " | "])
        return joint.join(lit(rng, v) for v in vs)

    s["ENV_LIVENESS"] = [live(xs) for _ in range(rng.randint(1, 4))]
    s["SYS_LIVENESS"] = [live(ys if friendly else everything) for _ in range(rng.randint(1, 4))]
    return s


SHAPES: dict[str, Callable[[random.Random], Sections]] = {
    "counter": counter, "compare": compare, "mutex": mutex, "graph": graph,
    "automata": automata, "invariant": invariant,
}


def shape_text(shape: str, seed: int) -> str:
    """The structuredslugs text of ``shape`` (a key of :data:`SHAPES`) drawn with ``seed``."""
    rng = random.Random(f"{shape}:{seed}")
    return render(SHAPES[shape](rng), f"{shape} seed {seed} (bench/bench_random_families.py)")
