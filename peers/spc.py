"""gaitc's GR(1) IR as gr1c's ``.spc`` text, with the flags that make gr1c decide what gaitc does.

References: gr1c's ``doc/spc_format.md`` (the grammar and the interpretations of initial
conditions) and ``check_realizable_internal`` in its ``src/solve.c``; Bloem et al.,
"Synthesis of Reactive(1) designs", JCSS 78(3), 2012.

Variables.  gr1c has Booleans and integers over ``[0,n]``; an integer over ``low..high`` is
declared ``[0,high-low]`` and every number written for it is shifted by ``-low``.  A name
keeps its spelling when gr1c can read it; other characters become ``_``, a leading digit
gets ``v_`` and ``True``/``False`` get a ``_``.  gr1c names the bits of an integer ``x``
``x0``, ``x1``, ..., so in a spec with integers every name that ends in a digit gets a
``_`` too: then no declared name ends in a digit and every bit name does.  Names that
still meet get more ``_``.

Formulas.  gr1c's grammar gives ``&``, ``|``, ``!`` and ``=`` one precedence, so every
operator is bracketed; xor is ``!(a <-> b)``; comparisons are rewritten by
:mod:`peers.comparisons` into comparisons of one variable with a number; liveness is over
one state (:mod:`peers.game`).  gr1c has no definitions, so a subformula shared in the IR is
written out where it is used; a clause longer than :data:`MAX_CHARS` is an error.

Initial conditions.  Let W be the winning region: the states from which the system wins
the game of ρe, ρs and the liveness goals, a move outside ρe winning for the system.
gaitc, SLUGS and gr1c compute the same W; they differ only in which states must be in it.
With the integer ranges conjoined to θe (inputs) and θs (outputs), gaitc decides

    default:   ∀x. θe(x) → ∃y. θs(x,y) ∧ W(x,y)
    robotics:  ∀x,y. θe ∧ θs → W

while gr1c decides (``check_realizable_internal``)

    ALL_ENV_EXIST_SYS_INIT:  ∀x. (∃y. θe ∧ θs) ↔ (∃y. θe ∧ θs ∧ W),
                             θe over inputs only, θs over outputs only
    ALL_INIT:                θe ∧ θs ≠ ∅  and  θe ∧ θs ⊆ W.

:func:`emit_spc` writes one of three forms (:data:`START_FORMS`), chosen with a BDD of the
initial conditions (their satisfiability is all it needs):

``direct``, robotics, θe ∧ θs satisfiable: ``-n ALL_INIT`` is gaitc's condition word for
word.  Default, θs over outputs only and satisfiable: then ∃y. θe ∧ θs is θe(x) and
∃y. θe ∧ θs ∧ W is θe(x) ∧ ∃y. θs ∧ W, so gr1c's default condition says that every x with
θe(x) has a y with θs ∧ W, which is gaitc's.

``started``, default otherwise: θs mentions an input (gr1c's default rejects that) or is
unsatisfiable (gr1c's equivalence then holds with both sides empty, while gaitc needs an
output for every allowed input).  A fresh system bit ``s`` puts one step before the game:
``-n ALL_INIT`` with SYSINIT ``!s``, so that every state with ``!s`` is initial (there is
one, so the set is not empty); ENVTRANS ``!s -> θe'`` and ``s -> ρe``; SYSTRANS
``!s -> (s' & θs')``, ``s -> s'`` and ``s -> ρs``; the goals as they are.  Once ``s`` is
set it stays set and the game is the original one, so a state ``(x, y, s)`` is winning
exactly when ``(x, y)`` ∈ W.  From a state with ``!s`` the environment picks ``x'`` with θe(x') (it
has no move when θe is unsatisfiable, and the system wins, as in gaitc), then the system
must pick ``y'`` with θs(x', y') and set ``s``; so every such state is winning exactly
when ∀x'. θe(x') → ∃y'. θs(x', y') ∧ W(x', y'), which ALL_INIT asks of all of them: gaitc's
default condition.  The goals are □◇ conditions, which one more step at the start does not
change.

``vacuous``, robotics with θe ∧ θs unsatisfiable: gaitc says realizable (there is no
initial state to lose from), ALL_INIT says unrealizable (the empty set).  A fresh system bit
``v``: SYSINIT ``v | (θe & θs & !v)``, SYSTRANS ``v -> v'``, ``!v -> !v'`` and ``v | ρs``,
the goals ``v | φ``.  From a state with ``v`` the system keeps ``v`` and every goal holds,
so those states are winning; with ``!v`` the game is the original one.  The initial states
are the ``v`` states (never none) and θe ∧ θs ∧ ``!v``, so ALL_INIT holds exactly when
θe ∧ θs ⊆ W: gaitc's robotics condition, true here.

A spec without variables gets one free system bit (gr1c needs a variable; a free bit
changes no verdict).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Final, Literal

from gaitc.diagnostics import PeerFormatError, Span
from gaitc.ir.bitblast import bitblast
from gaitc.ir.formula import (
    Add,
    Always,
    And,
    Compare,
    Const,
    Eventually,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Or,
    Var,
    Xor,
    atoms,
    conj,
    node_kind,
    prime,
    unreachable,
)
from gaitc.ir.spec import Clause, GR1Spec, Origin, Semantics, Variable
from gaitc.ir.traversal import Memo, Node, Text, fold, join_text, separated
from gaitc.verifier.logic import Logic
from peers.comparisons import LIMIT, expand_comparison
from peers.game import peer_game

#: The longest clause :func:`emit_spc` writes, in characters (shared subformulas written out).
MAX_CHARS: Final = 20_000_000
StartForm = Literal["direct", "started", "vacuous"]
#: How the initial condition is written (see the module's docstring).
START_FORMS: Final[tuple[StartForm, ...]] = ("direct", "started", "vacuous")
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_RESERVED = frozenset({"True", "False"})


@dataclass(frozen=True)
class SpcProgram:
    """gr1c's input for one spec: the ``.spc`` text, the flags to run it with (before the
    file name), and which form of the initial condition the text uses."""

    text: str
    flags: tuple[str, ...]
    start: StartForm


def emit_spc(spec: GR1Spec, semantics: Semantics = Semantics.DEFAULT, *,
             comments: bool = True, limit: int = LIMIT) -> SpcProgram:
    """``spec`` as a gr1c specification deciding realizability under ``semantics``.

    ``comments`` writes each clause's origin above it; ``limit`` bounds the combinations of
    values a comparison may range over (:func:`peers.comparisons.expand_comparison`).
    Raises :class:`~gaitc.diagnostics.PeerFormatError` for what gr1c cannot be given.
    """
    game = peer_game(spec)
    form = start_form(game, semantics)
    writer = _Writer(game, limit)
    return SpcProgram(writer.program(form, comments), _flags(form, semantics), form)


def start_form(spec: GR1Spec, semantics: Semantics) -> StartForm:
    """Which form of the initial condition writes ``spec`` under ``semantics`` exactly."""
    if semantics == Semantics.ROBOTICS:
        return "direct" if _satisfiable(spec, with_env=True) else "vacuous"
    inputs = {v.name for v in spec.inputs}
    on_inputs = any(name in inputs for c in spec.sys_init for name, _ in atoms(c.formula))
    if on_inputs or not _satisfiable(spec, with_env=False):
        return "started"
    return "direct"


def _flags(form: StartForm, semantics: Semantics) -> tuple[str, ...]:
    if form == "direct" and semantics == Semantics.DEFAULT:
        return ("-n", "ALL_ENV_EXIST_SYS_INIT")
    return ("-n", "ALL_INIT")


# ---------------------------------------------------------------- satisfiability
def _satisfiable(spec: GR1Spec, with_env: bool) -> bool:
    """Whether θs (θe ∧ θs when ``with_env``) holds in some state within the ranges (the
    clauses bit-blasted and read as BDDs by the verifiers' :class:`Logic`)."""
    logic = Logic(bitblast(GR1Spec(inputs=spec.inputs, outputs=spec.outputs,
                                   env_init=spec.env_init if with_env else (),
                                   sys_init=spec.sys_init)))
    found = logic.bdd.true
    for section in ("sys_init", "env_init") if with_env else ("sys_init",):
        for _, clause in logic.clauses(section):
            found &= clause
            if found == logic.bdd.false:
                return False
    return True


# ---------------------------------------------------------------- names
def spc_names(spec: GR1Spec) -> dict[str, str]:
    """The name gr1c reads for each variable of ``spec`` (see the module's docstring)."""
    taken: set[str] = set()
    out: dict[str, str] = {}
    for var in spec.variables():
        out[var.name] = _fresh(var.name, taken, spec.has_integers)
    return out


def _fresh(name: str, taken: set[str], has_integers: bool) -> str:
    written = re.sub(r"[^A-Za-z0-9_]", "_", name) or "v"
    if not _IDENTIFIER.match(written):
        written = "v_" + written
    if written in _RESERVED or (has_integers and written[-1].isdigit()):
        written += "_"
    while written in taken:
        written += "_"
    taken.add(written)
    return written


# ---------------------------------------------------------------- writing
#: A piece of text and its length once joined.
_Piece = tuple[Text, int]


def _one_line(text: str) -> str:
    return " ".join(text.split())


def _made(formula: Expr, why: str) -> Clause:
    """A clause of the reductions, with what it is for as its origin."""
    return Clause(formula, Origin(f"gaitc: {why}"))


def _note(clause: Clause) -> str | None:
    origin = clause.origin
    if origin is None:
        return None
    where = f" ({origin.span})" if origin.span is not None else ""
    return _one_line(origin.rule + where)


class _Writer:
    """The text of one spec: names, shifted ranges, formulas written once each."""

    def __init__(self, spec: GR1Spec, limit: int) -> None:
        self.spec = spec
        self.limit = limit
        self.names = spc_names(spec)
        self.taken = set(self.names.values())
        self.low = {v.name: v.low for v in spec.variables() if v.low is not None}
        self.domains = {v.name: (v.low, v.high) for v in spec.variables()
                        if v.low is not None and v.high is not None}
        self.memo: Memo[_Piece] = {}
        self.native_memo: Memo[_Piece] = {}
        self.comparisons: dict[Compare, _Piece] = {}

    # formulas
    def formula(self, expr: Expr, span: Span | None = None) -> Text:
        """``expr`` in gr1c's syntax, every operator bracketed."""
        text, size = fold(expr, lambda n, k: self._piece(n, k, native=False),
                          children=_formula_children, memo=self.memo)
        if size > MAX_CHARS:
            raise PeerFormatError(
                f"a clause would take {size} characters in gr1c's format, more than "
                f"{MAX_CHARS}: gr1c has no definitions, so each shared subformula is "
                "written out where it is used", span or expr.span)
        return text

    def _piece(self, node: Node, kids: list[_Piece], native: bool) -> _Piece:
        kind = node_kind(node)
        match kind:
            case Const():
                word = "True" if kind.value else "False"
                return word, len(word)
            case Var():
                word = self.names[kind.name] + ("'" if kind.primed else "")
                return word, len(word)
            case Not():
                return ("!", kids[0][0]), 1 + kids[0][1]
            case And() | Or():
                if not kids:
                    word = "True" if isinstance(kind, And) else "False"
                    return word, len(word)
                if len(kids) == 1:
                    return kids[0]
                glue = " & " if isinstance(kind, And) else " | "
                text = separated(glue, [t for t, _ in kids])
                return ("(", text, ")"), 2 + sum(n for _, n in kids) + 3 * (len(kids) - 1)
            case Xor() | Iff() | Implies():
                glue, head = {Xor: (" <-> ", "!("), Iff: (" <-> ", "("),
                              Implies: (" -> ", "(")}[type(kind)]
                (a, na), (b, nb) = kids
                return (head, a, glue, b, ")"), len(head) + na + len(glue) + nb + 1
            case Compare():
                if native:
                    return self._native(kind)
                found = self.comparisons.get(kind)
                if found is None:  # equal comparisons (not only shared ones) written once
                    expanded = expand_comparison(kind, self.domains, self.limit)
                    found = self.comparisons[kind] = fold(
                        expanded, lambda n, k: self._piece(n, k, native=True),
                        children=_formula_children, memo=self.native_memo)
                return found
            case IntConst() | IntVar() | Add() | Next() | Always() | Eventually():
                raise AssertionError(f"no {type(kind).__name__} in a GR(1) section's formula")
            case _:
                unreachable(kind)

    def _native(self, node: Compare) -> _Piece:
        """A comparison of one variable with a number in its range (from the expansion)."""
        var, number = node.left, node.right
        assert isinstance(var, IntVar) and isinstance(number, IntConst)
        word = (f"{self.names[var.name]}{chr(39) if var.primed else ''} {node.op} "
                f"{number.value - self.low[var.name]}")
        return word, len(word)

    # names of fresh bits
    def fresh(self, base: str) -> str:
        """A new system bit's name, also its key in :attr:`names`: it is no variable's
        written name, and an identifier that ends in a letter is written as itself, so no
        variable of the spec has it for its own name either."""
        name = _fresh(base, self.taken, True)
        self.names[name] = name
        return name

    # the program
    def program(self, form: StartForm, comments: bool) -> str:
        spec = self.spec
        sections = _Sections(self, comments)
        extra: list[str] = []
        if not spec.variables():
            extra.append(self.fresh("gaitc_free"))
        if form == "direct":
            sections.add("ENVINIT", spec.env_init)
            sections.add("SYSINIT", spec.sys_init)
            sections.add("ENVTRANS", spec.env_trans, "[]")
            sections.add("SYSTRANS", spec.sys_trans, "[]")
            sections.add("ENVGOAL", spec.env_liveness, "[]<>")
            sections.add("SYSGOAL", spec.sys_liveness, "[]<>")
        elif form == "started":
            s = self.fresh("gaitc_started")
            extra.append(s)
            self._started(sections, s)
        else:
            v = self.fresh("gaitc_vacuous")
            extra.append(v)
            self._vacuous(sections, v)
        head = [f"# gr1c specification written by gaitc from {_one_line(spec.name or '-')}",
                f"# initial condition: {form} form (see peers/spc.py)"]
        return "\n".join([*(head if comments else []),
                          self._declare("ENV", spec.inputs, []),
                          self._declare("SYS", spec.outputs, extra),
                          *sections.blocks]) + "\n"

    def _declare(self, header: str, variables: tuple[Variable, ...], extra: list[str]) -> str:
        words = [self.names[v.name] + ("" if v.low is None or v.high is None
                                       else f" [0,{v.high - v.low}]") for v in variables]
        return f"{header}: {' '.join(words + extra)};".replace(": ;", ":;")

    def _started(self, sections: _Sections, s: str) -> None:
        spec = self.spec
        bit, now = Var(s), Not(Var(s))
        after = Var(s, True)
        sections.add("SYSINIT", (_made(now, "before the game starts"),))
        first_env = _made(Implies(now, prime(conj(c.formula for c in spec.env_init))),
                          "the environment's first move: θe on the first state")
        sections.add("ENVTRANS", (first_env, *(Clause(Implies(bit, c.formula), c.origin)
                                               for c in spec.env_trans)), "[]")
        first_sys = _made(Implies(now, And((after, prime(conj(c.formula
                                                              for c in spec.sys_init))))),
                          "the system's first move: θs on the first state; the game starts")
        sections.add("SYSTRANS", (first_sys, _made(Implies(bit, after), "the game goes on"),
                                  *(Clause(Implies(bit, c.formula), c.origin)
                                    for c in spec.sys_trans)), "[]")
        sections.add("ENVGOAL", spec.env_liveness, "[]<>")
        sections.add("SYSGOAL", spec.sys_liveness, "[]<>")

    def _vacuous(self, sections: _Sections, v: str) -> None:
        spec = self.spec
        bit, now = Var(v), Not(Var(v))
        init = conj(c.formula for c in spec.env_init + spec.sys_init)
        sections.add("SYSINIT", (_made(Or((bit, And((init, now)))),
                                       "θe and θs together, or a trivially winning state"),))
        sections.add("ENVTRANS", spec.env_trans, "[]")
        sections.add("SYSTRANS", (_made(Implies(bit, Var(v, True)), "trivially winning stays"),
                                  _made(Implies(now, Not(Var(v, True))), "the game stays"),
                                  *(Clause(Or((bit, c.formula)), c.origin)
                                    for c in spec.sys_trans)), "[]")
        sections.add("ENVGOAL", spec.env_liveness, "[]<>")
        sections.add("SYSGOAL", tuple(Clause(Or((bit, c.formula)), c.origin)
                                      for c in spec.sys_liveness), "[]<>")


def _formula_children(node: Node) -> tuple[Node, ...]:
    """A comparison is a leaf of the written formula (its terms are not written as such)."""
    return () if isinstance(node, Compare) else node.children()


class _Sections:
    """The sections of the text, each clause on its lines with its note above it."""

    def __init__(self, writer: _Writer, comments: bool) -> None:
        self.writer = writer
        self.comments = comments
        self.blocks: list[str] = []

    def add(self, header: str, clauses: tuple[Clause, ...], operator: str = "") -> None:
        """A section of ``clauses``: joined by ``&``, each under ``operator`` (``[]``,
        ``[]<>``) when given."""
        if not clauses:
            if header == "SYSGOAL":  # no goal: the system need only stay safe
                self.blocks.append("SYSGOAL: []<>True;")
            return
        lines = [f"{header}:"]
        for k, clause in enumerate(clauses):
            note = _note(clause)
            if self.comments and note:
                lines.append(f"  # {note}")
            text = join_text(self.writer.formula(
                clause.formula, clause.origin.span if clause.origin else None))
            if operator:  # a bracketed formula stays as it is; an atom gets brackets
                text = operator + (text if text.startswith("(") else f"({text})")
            lines.append(f"  {'& ' if k else ''}{text}")
        lines[-1] += ";"
        self.blocks.append("\n".join(lines))
