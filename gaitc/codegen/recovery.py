"""Generated C for a recovering compact controller, its table sizes and the board's budget.

A recovering controller (:mod:`gaitc.compact.recovery`, after Ehlers and Topcu, HSCC 2014)
adds roots to the compact tables: the recoverable flag and the recovery move, then per
fallback its flag, its entry move and its goals' move and goal diagrams.  The C here walks
them as :class:`gaitc.compact.recovery.RecoveringRunner` does, step for step:

    uint8_t gaitc_step_surprise(gaitc_state *s, const uint8_t in[], uint16_t *move);
    uint16_t gaitc_kept(const gaitc_state *s);

``gaitc_step_surprise`` returns ``GAITC_ALLOWED`` (an ordinary step), ``GAITC_RECOVERED``,
``GAITC_DEGRADED`` (``s->mode`` is now the fallback) or ``GAITC_STOPPED`` (no move: the
board vents); ``gaitc_kept`` is the bit mask of the spec's goals still pursued.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final

from gaitc.codegen.tables import flatten
from gaitc.compact.recovery import RecoveringController, told
from gaitc.diagnostics import ControllerError

#: Flash the firmware itself takes beside the tables (measured: gaitboard.c with a linked
#: controller, the board tables and the recovery walk is 5.5 KB of code and data, shuttle).
FIRMWARE_BYTES: Final = 5632
MAX_GOALS: Final = 16  # gaitc_kept is a 16-bit mask


@dataclass(frozen=True)
class TablePart:
    """One part of the tables and the bytes it adds to the parts before it."""

    name: str
    bytes: int


@dataclass(frozen=True)
class RecoverySizes:
    """Bytes per part: the controller, the recovery diagrams, each fallback."""

    parts: tuple[TablePart, ...]

    @property
    def total(self) -> int:
        return sum(p.bytes for p in self.parts)

    def lines(self) -> list[str]:
        return [f"{p.name}: {p.bytes} bytes" for p in self.parts] + \
            [f"total: {self.total} bytes of tables"]


def fallback_bytes(count: int) -> int:
    """The fallbacks' own tables: per fallback its first root (2), goal count (1), mask (2)."""
    return 5 * max(count, 1)


def recovery_sizes(rc: RecoveringController) -> RecoverySizes:
    """The bytes each part of ``rc``'s tables adds (nodes shared with an earlier part are
    counted there)."""
    base = rc.base
    parts = [TablePart("controller and assumption monitor", flatten(base).bytes)]
    roots: list[int] = [rc.recoverable_root, rc.recover_root]
    done = flatten(base, roots).bytes
    parts.append(TablePart("recovery (recoverable flag and recovery move)",
                           done - parts[0].bytes + fallback_bytes(len(rc.fallbacks))))
    for fb in rc.fallbacks:
        roots += fb.roots
        now = flatten(base, roots).bytes
        kept = ", ".join(str(j + 1) for j in fb.kept)
        parts.append(TablePart(f"fallback to goal(s) {kept}", now - done))
        done = now
    return RecoverySizes(tuple(parts))


def fit(rc: RecoveringController, budget: int) -> tuple[RecoveringController | None, list[str]]:
    """``rc`` with as many fallbacks as fit in ``budget`` bytes of tables (the last ones
    dropped first), or None when not even the recovery diagrams fit; and, in words, the
    surprises the board can then only stop on."""
    keep = len(rc.fallbacks)
    trimmed = rc
    while _total(trimmed) > budget and keep:
        keep -= 1
        trimmed = rc.without_fallbacks(keep)
    total = _total(trimmed)
    if total > budget:
        return None, [none_fits(total, budget)]
    return trimmed, stops(trimmed)


def none_fits(needed: int | float, budget: int) -> str:
    """The words for a board on which not even the recovery diagrams fit: every surprise
    stops; ``needed`` is what the tables take (or pass, when building stopped early)."""
    over = "more bytes than can be addressed" if needed == float("inf") \
        else f"at least {int(needed)} bytes"
    return (f"every surprise: stop (the recovery tables do not fit: with the controller they "
            f"take {over}, and the board has {budget} for tables; --target c builds them "
            "for a larger host)")


def _total(rc: RecoveringController) -> int | float:
    """The tables' bytes; infinite when the tables cannot even address their nodes."""
    try:
        return recovery_sizes(rc).total
    except ControllerError:
        return float("inf")


def stops(rc: RecoveringController) -> list[str]:
    """The surprise classes on which the board stops, in words: how many of their cases
    (state and inputs) stop because no goal is achievable, how many because their fallback
    tables were left out, and how many recover."""
    out = []
    for c in rc.classes:
        why = []
        if c.stopped:
            why.append(f"stop in {c.stopped} case(s) (no goal is achievable)")
        dropped = 0 if c.included else sum(c.degraded.values())
        if dropped:
            why.append(f"stop in {dropped} case(s) (its fallback tables do not fit)")
        if why:
            rest = f"; {c.recovered} case(s) recover" if c.recovered else ""
            out.append(f"{told(c.surprise)}: {', '.join(why)}{rest}")
    return out


def header_lines(rc: RecoveringController) -> list[str]:
    """The recovery part of ``gaitc_controller.h``."""
    if rc.goal_count > MAX_GOALS:
        raise ControllerError(f"recovery tables hold at most {MAX_GOALS} goals; the "
                              f"controller has {rc.goal_count} (generate with --no-recover)")
    return [
        "",
        "/* recovery after broken assumptions (gaitc codegen --recover, docs/compact.md) */",
        "#define GAITC_RECOVER 1",
        f"#define GAITC_FALLBACKS {len(rc.fallbacks)}",
        "#define GAITC_ALLOWED 0   /* the inputs kept the assumptions */",
        "#define GAITC_RECOVERED 1 /* a surprise, and a move back into the winning region */",
        "#define GAITC_DEGRADED 2  /* a surprise; a fallback with fewer goals was entered */",
        "#define GAITC_STOPPED 3   /* a surprise with neither: no move, stop (vent) */",
        "/* s->mode: 0 every goal (a zeroed state too), 1 stopped, 2 + k fallback k */",
        "#define GAITC_NORMAL 0",
        "#define GAITC_STOP 1",
        "/* one step whatever the inputs: the outcome; *move the move made (not when stopped) */",
        "uint8_t gaitc_step_surprise(gaitc_state *s, const uint8_t in[GAITC_INPUTS], "
        "uint16_t *move);",
        "/* the spec's goals still pursued, bit j for goal j + 1 */",
        "uint16_t gaitc_kept(const gaitc_state *s);",
    ]


def source_part(rc: RecoveringController, roots: int) -> str:
    """The recovery walk (after the controller's own functions); ``roots`` is the number of
    the base controller's roots, where the recovery roots start."""
    firsts, at = [], roots + 2
    for fb in rc.fallbacks:
        firsts.append(at)
        at += len(fb.roots)
    count = max(1, len(rc.fallbacks))

    def array(ctype: str, name: str, values: list[int]) -> str:
        body = ", ".join(str(v) for v in (values or [0]))
        return f"static const {ctype} {name}[{count}] GAITC_FLASH = {{{body}}};"

    every = (1 << rc.goal_count) - 1
    return "\n".join([
        f"#define GAITC_RECOVERABLE_ROOT {roots}",
        f"#define GAITC_RECOVER_ROOT {roots + 1}",
        f"#define GAITC_EVERY_GOAL {every}u",
        *([array("uint16_t", "fb_first", firsts),
           array("uint8_t", "fb_goals", [len(fb.kept) for fb in rc.fallbacks]),
           array("uint16_t", "fb_mask", [fb.mask for fb in rc.fallbacks])]
          if rc.fallbacks else []),
        """
/* a move of the diagrams from root move_first (+ the goal unless one), the goal counter
 * moved on by the goal diagrams from root reached_first, as gaitc_step does */
static uint16_t play(gaitc_state *s, const uint8_t *in, uint16_t move_first, uint8_t one,
                     uint16_t reached_first, uint8_t goals)
{
    uint16_t move = walk(GAITC_U16(roots[move_first + (one ? 0 : s->goal)]), s->value, in);
    uint8_t k;
    for (k = 0; k < goals; k++) {
        if (!walk(GAITC_U16(roots[reached_first + s->goal]), s->value, in)) break;
        s->goal = (uint8_t)((s->goal + 1) % goals);
    }
    set_inputs(s, in);
    set_outputs(s, move);
    return move;
}

uint8_t gaitc_step_surprise(gaitc_state *s, const uint8_t in[GAITC_INPUTS], uint16_t *move)
{
    uint8_t i;
    if (s->mode == GAITC_STOP) return GAITC_STOPPED;
    if (s->mode == GAITC_NORMAL) {
        if (gaitc_assumed(s, in)) {
            *move = gaitc_step(s, in);
            return GAITC_ALLOWED;
        }
        if (walk(GAITC_U16(roots[GAITC_RECOVERABLE_ROOT]), s->value, in)) {
            *move = play(s, in, GAITC_RECOVER_ROOT, 1, GAITC_REACHED_ROOT(0), GAITC_GOALS);
            return GAITC_RECOVERED;
        }
#if GAITC_FALLBACKS > 0
        for (i = 0; i < GAITC_FALLBACKS; i++) {
            uint16_t r = GAITC_U16(fb_first[i]);
            if (walk(GAITC_U16(roots[r]), s->value, in)) {
                *move = walk(GAITC_U16(roots[r + 1]), s->value, in);
                set_inputs(s, in);
                set_outputs(s, *move);
                s->mode = (uint8_t)(i + 2);
                s->goal = 0;
                return GAITC_DEGRADED;
            }
        }
    } else if (gaitc_assumed(s, in)) {
        uint16_t r = GAITC_U16(fb_first[s->mode - 2]);
        uint8_t goals = GAITC_U8(fb_goals[s->mode - 2]);
        *move = play(s, in, (uint16_t)(r + 2), 0, (uint16_t)(r + 2 + goals), goals);
        return GAITC_ALLOWED;
#else
        (void)i;
#endif
    }
    s->mode = GAITC_STOP;
    return GAITC_STOPPED;
}

uint16_t gaitc_kept(const gaitc_state *s)
{
    if (s->mode == GAITC_NORMAL) return GAITC_EVERY_GOAL;
    if (s->mode == GAITC_STOP) return 0;
#if GAITC_FALLBACKS > 0
    return GAITC_U16(fb_mask[s->mode - 2]);
#else
    return 0;
#endif
}
""",
    ])
