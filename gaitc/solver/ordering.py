"""The BDD variable order of the embedded solver: mutex groups kept together, guards first.

Invariants are the transition clauses over next-state variables only (one-hot mutexes,
range limits); a group is the support of such a clause over one player's Boolean variables.
Groups are ranked by how often they guard an implication (``A -> B``: A's groups rank up, B's
down), so that a relation decides its case before it constrains the effect, the usual rule for
small transition BDDs (Bryant 1986; Aziz, Tasiran, Brayton, "BDD variable ordering for
interacting finite state machines", DAC 1994).  Last, when the system's goals are over
integers, the integer inputs of the environment's liveness go on top (a map's obstacle above
the robot's position, :func:`_movers_first`).  Measured in docs/design-notes.md.

An integer that SLUGS's compiler has already cut into bits (``x@0.MIN.MAX``, ``x@1``, ...:
a ``.slugsin`` file declares those Boolean bits, not ``x``) is ordered as the integer is
(:func:`_families`): its bits form one group and count as an integer, so a spec orders the
same from its ``.slugsin`` and from its ``.structuredslugs`` form (issue 59: the 1024 x 1024
gridworld took 186 s from the first and 29 s from the second before).
"""

from __future__ import annotations

from collections.abc import Sequence

from gaitc.ir.bits import cut_integers
from gaitc.ir.formula import Implies, Node, atoms
from gaitc.ir.spec import Clause, GR1Spec, Variable

Atoms = set[tuple[str, bool]]


class AtomCache:
    """``atoms`` of formulas, computed once per node object (big mutexes are walked once);
    an implication's from its two sides, which the guard scores ask for too.  One cache
    serves every pass of a :class:`~gaitc.solver.symbolic.SymbolicSpec` over its spec."""

    def __init__(self) -> None:
        self._seen: dict[int, tuple[Node, Atoms]] = {}

    def __call__(self, node: Node) -> Atoms:
        hit = self._seen.get(id(node))
        if hit is None:
            if isinstance(node, Implies):  # one level only: a chain of them stays iterative
                hit = (node, self._walked(node.left) | self._walked(node.right))
            else:
                hit = (node, atoms(node))
            self._seen[id(node)] = hit
        return hit[1]

    def _walked(self, node: Node) -> Atoms:
        hit = self._seen.get(id(node))
        if hit is None:
            hit = self._seen[id(node)] = (node, atoms(node))
        return hit[1]


ORDERS = ("guards", "occurrence", "declaration")
_SECTIONS = ("sys_trans", "env_trans", "env_init", "sys_init", "sys_liveness", "env_liveness")


def invariant_clauses(
    spec: GR1Spec, cache: AtomCache | None = None
) -> tuple[list[Clause], list[Clause]]:
    """The invariants of ρe (over primed inputs only) and of ρs (over primed variables only):
    transition clauses over next-state variables, which hold in every state after the first."""
    found = cache or AtomCache()
    inputs = {v.name for v in spec.inputs}

    def only_next(clause: Clause, names: set[str] | None) -> bool:
        used = found(clause.formula)
        return bool(used) and all(p and (names is None or n in names) for n, p in used)

    env = [c for c in spec.env_trans if only_next(c, inputs)]
    return env, [c for c in spec.sys_trans if only_next(c, None)]


def variable_order(spec: GR1Spec, how: str, cache: AtomCache | None = None) -> list[Variable]:
    """The variables of ``spec`` top to bottom for ordering ``how`` (one of :data:`ORDERS`)."""
    declared = list(spec.inputs) + list(spec.outputs)
    if how == "declaration":
        return declared
    if how not in ORDERS:
        raise ValueError(f"unknown variable order {how!r}; use one of {ORDERS}")
    found = cache or AtomCache()
    occurrence = _occurrence(spec, declared, found)
    if how == "occurrence":
        return occurrence
    rank = {v.name: k for k, v in enumerate(declared)}
    families = _families(spec)
    groups = _groups(spec, declared, found, families)
    score = _guard_scores(spec, groups, found)
    first = {v.name: k for k, v in enumerate(occurrence)}
    members: dict[str, list[Variable]] = {}
    for v in declared:
        members.setdefault(groups[v.name], []).append(v)
    ordered = sorted(
        members, key=lambda g: (-score.get(g, 0), min(first[v.name] for v in members[g]))
    )
    blocks = [sorted(members[g], key=lambda v: rank[v.name]) for g in ordered]
    follower = _per_member(spec, [[v.name for v in b] for b in blocks
                                  if b[0].name not in families], found)
    out: list[Variable] = []
    by_name = {v.name: v for v in declared}
    placed = set(follower.values())
    for block in blocks:
        if len(block) == 1 and block[0].name in placed:
            continue  # placed below its partner
        for v in block:
            out += [v] + ([by_name[follower[v.name]]] if v.name in follower else [])
    return _movers_first(spec, out, found, families)


def _families(spec: GR1Spec) -> dict[str, str]:
    """Each Boolean variable that is a bit of an integer cut into bits by SLUGS's compiler
    (``x@0.MIN.MAX``, ``x@1``, ..., all of one player), with the integer's name."""
    return {bit: integer
            for side in (spec.inputs, spec.outputs)
            for integer, (_, _, bits) in cut_integers(
                v.name for v in side if not v.is_integer).items()
            for bit in bits}


def _unit(name: str, families: dict[str, str]) -> str:
    """The variable ``name`` stands for when ordering: its integer if it is a SLUGS bit."""
    return families.get(name, name)


def _movers_first(spec: GR1Spec, order: list[Variable], found: AtomCache,
                  families: dict[str, str] | None = None) -> list[Variable]:
    """``order`` with the environment's fair integers on top, when the system's goals are
    over integers too: the integer inputs that the environment's liveness mentions (an
    obstacle that must come home infinitely often) above everything else.

    On a map whose position is a pair of wide integers, the fixpoint's sets are ranges of
    the position that differ with the obstacle's few cells only near the obstacle: with the
    obstacle's bits on top, each of its values keeps one copy of a range BDD that shares
    almost everything with the others, and a step of the inner fixpoint (a CPre, two
    conjunctions) is 5-6 times cheaper than with the position on top, which the guard
    scores choose because every move clause is guarded by the position.  Gridworld
    256 x 256 with an obstacle in an 8 x 8 box: 3.3 s against 17.7 s for the guards order
    alone; evasion 24 x 24: 3.1 s against 8.2 s (docs/design-notes.md, issue 37).  Boolean
    obstacles (one variable per cell) stay where the guards put them: 64 of them on top
    make every set enumerate the obstacle's cells first (over 300 s)."""

    bits = families or {}

    def mentioned(clauses: Sequence[Clause]) -> set[str]:
        return {_unit(name, bits) for c in clauses for name, _ in found(c.formula)}

    def integer(v: Variable) -> bool:
        return v.is_integer or v.name in bits

    inputs = {_unit(v.name, bits) for v in spec.inputs}
    fair = mentioned(spec.env_liveness) & inputs
    movers = [v for v in order if integer(v) and _unit(v.name, bits) in fair]
    goals = mentioned(spec.sys_liveness) - fair
    if not movers or not any(integer(v) and _unit(v.name, bits) in goals for v in order):
        return order
    return movers + [v for v in order if v not in movers]


def _per_member(spec: GR1Spec, blocks: list[list[str]], found: AtomCache) -> dict[str, str]:
    """Variables that each belong to one member of a group, such as a lift's call button to
    its floor or an arbiter's request to its grant: for a group of at least three members,
    at least half of which are each the partner (:func:`_partners`) of exactly one
    ungrouped variable, and none of more, each such member and its variable.

    The variable is then placed right below its member, inside the group.  A relation
    between a group and per-member variables kept apart needs a node for every combination
    of the group's values above them (the lift's rule ``b_i & f_i -> !b_i'``, every floor
    above every button); interleaved, each pair is decided in one place.  Lift with 64
    floors: 3.6 s to check instead of 0.7 s (docs/design-notes.md).  A member that many
    variables lean on (AMBA's ``start``) is a hub, not a pairing, and moves nothing."""
    grouped = {name for b in blocks if len(b) > 1 for name in b}
    lean: dict[str, list[str]] = {}
    for v, m in _partners(spec, grouped, found).items():
        lean.setdefault(m, []).append(v)
    out: dict[str, str] = {}
    for block in blocks:
        paired = [m for m in block if len(lean.get(m, [])) == 1]
        if (len(block) >= 3 and 2 * len(paired) >= len(block)
                and all(len(lean.get(m, [])) <= 1 for m in block)):
            out.update((m, lean[m][0]) for m in paired)
    return out


def _partners(spec: GR1Spec, grouped: set[str], found: AtomCache) -> dict[str, str]:
    """For each variable outside a group that the clauses tie to one group member above all
    (it shares strictly more clauses with that member than with any other), the member."""
    shared: dict[str, dict[str, int]] = {}
    for section in _SECTIONS:
        for clause in spec.section(section):
            names = {name for name, _ in found(clause.formula)}
            members = names & grouped
            for v in names - grouped:
                counts = shared.setdefault(v, {})
                for m in members:
                    counts[m] = counts.get(m, 0) + 1
    out: dict[str, str] = {}
    for v, counts in shared.items():
        ranked = sorted(counts.values(), reverse=True)
        if ranked and (len(ranked) == 1 or ranked[0] > ranked[1]):
            out[v] = max(counts, key=lambda m: counts[m])
    return out


def _occurrence(spec: GR1Spec, declared: list[Variable], found: AtomCache) -> list[Variable]:
    """Variables in the order the transition clauses first mention them."""
    by_name = {v.name: v for v in declared}
    seen: dict[str, None] = {}
    for section in _SECTIONS:
        for clause in spec.section(section):
            for name, _ in sorted(found(clause.formula)):
                if name in by_name:
                    seen.setdefault(name, None)
    for v in declared:
        seen.setdefault(v.name, None)
    return [by_name[n] for n in seen]


def _groups(spec: GR1Spec, declared: list[Variable], found: AtomCache,
            families: dict[str, str] | None = None) -> dict[str, str]:
    """Each variable's group representative (union-find over one-player Boolean invariants;
    the bits of an integer cut by SLUGS's compiler, ``families``, are one group)."""
    parent = {v.name: v.name for v in declared}
    bits = families or {}
    heads: dict[str, str] = {}
    for name in parent:
        if name in bits:
            parent[name] = heads.setdefault(bits[name], name)

    def find(name: str) -> str:
        while parent[name] != name:
            parent[name] = parent[parent[name]]
            name = parent[name]
        return name

    booleans = {v.name for v in declared if not v.is_integer and v.name not in bits}
    players = [{v.name for v in spec.inputs}, {v.name for v in spec.outputs}]
    env, sys = invariant_clauses(spec, found)
    for clause in env + sys:
        names = sorted({name for name, _ in found(clause.formula)})
        if len(names) < 2 or not set(names) <= booleans:
            continue
        if not any(set(names) <= side for side in players):
            continue
        root = find(names[0])
        for name in names[1:]:
            parent[find(name)] = root
    return {name: find(name) for name in parent}


def _guard_scores(spec: GR1Spec, groups: dict[str, str], found: AtomCache) -> dict[str, int]:
    """Per group: transition clauses it guards minus clauses whose effect it is."""
    score: dict[str, int] = {}
    for clause in list(spec.env_trans) + list(spec.sys_trans):
        formula = clause.formula
        if not isinstance(formula, Implies):
            continue
        guard = {groups[n] for n, _ in found(formula.left) if n in groups}
        effect = {groups[n] for n, _ in found(formula.right) if n in groups}
        for g in guard - effect:
            score[g] = score.get(g, 0) + 1
        for g in effect - guard:
            score[g] = score.get(g, 0) - 1
    return score


def group_members(spec: GR1Spec) -> list[list[str]]:
    """The mutex groups with two or more variables, each in declaration order (for reporting)."""
    declared = list(spec.inputs) + list(spec.outputs)
    groups = _groups(spec, declared, AtomCache())
    out: dict[str, list[str]] = {}
    for v in declared:
        out.setdefault(groups[v.name], []).append(v.name)
    return [names for names in out.values() if len(names) > 1]
