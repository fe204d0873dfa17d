"""The AMBA AHB arbiter in the Boolean encoding of the public SYNTCOMP ``amba`` generator.

Issue 12 measured SLUGS on the instances of the generator that ships AMBA as
``.structuredslugs`` for SYNTCOMP's GR(1) track (after the RATSY generator of Bloem et al.,
"Specify, Compile, Run: Hardware from PSL", COCV 2007).  That text encodes the arbiter in
plain bits, unlike :mod:`bench.families.amba`: ``hmaster`` as ceil(log2 N) bits, least
significant first, with no range constraint when N is not a power of two; the A1 monitor
as the three-state machine of two bits ``stateA1_1 stateA1_0``; the G3 burst counter as
three bits stepping 000, 100, 010, 110, 001; G2 and G10 as explicit monitor automata whose
forbidden states are ``!(...)`` lines; ``busreq`` tied to the current (unprimed) master;
G7 in both directions; and G9 as the only system liveness.  This module writes the same
formulas, clause for clause and in the same order (the order of declarations and clauses
is what the solvers' variable orders start from), from that description; it shares no
code with the generator.
"""

from __future__ import annotations

from bench.families.amba import Sections

#: HBURST values as conditions on the two input bits: INCR = 00, BURST4 = 01 (hburst1).
INCR = "!hburst0 & !hburst1"
BURST4 = "!hburst0 & hburst1"


def master_bits(n: int) -> int:
    """Bits of ``hmaster`` for ``n`` masters (of any plain bit vector for ``n`` values):
    ceil(log2 n), at least one."""
    return max(1, (n - 1).bit_length())


def value_bits(name: str, width: int, value: int, primed: bool = False) -> str:
    """``name0 .. name{width-1}`` equal to ``value``, bit 0 least significant."""
    tick = "'" if primed else ""
    return " & ".join(("" if value >> j & 1 else "!") + f"{name}{j}{tick}"
                      for j in range(width))


def _state(bits: tuple[str, ...], values: str, primed: bool = False) -> str:
    """The monitor state where ``bits[k]`` has the value ``values[k]`` ("0" or "1")."""
    tick = "'" if primed else ""
    return " & ".join(("" if v == "1" else "!") + b + tick
                      for b, v in zip(bits, values, strict=True))


def _a1(out: list[str]) -> None:
    """A1's monitor: after a locked INCR transfer (state 10) busreq must fall; state 01
    remembers a fall followed at once by a new locked INCR transfer."""
    bits = ("stateA1_1", "stateA1_0")
    lock_incr = f"hmastlock & {INCR}"
    other = "(!hmastlock | hburst0 | hburst1)"
    moves = (
        ("00", other, "00"), ("00", lock_incr, "10"),
        ("10", "busreq", "10"), ("10", f"!busreq & {other}", "00"),
        ("10", f"!busreq & {lock_incr}", "01"),
        ("01", "busreq", "10"), ("01", lock_incr, "10"), ("01", f"!busreq & {other}", "00"),
    )
    out += [f"({_state(bits, src)} & {cond}) -> ({_state(bits, dst, True)})"
            for src, cond, dst in moves]


def _g2(out: list[str]) -> None:
    """G2's monitor: after a locked INCR start, no start until busreq falls."""
    out.append("(!stateG2 & (!hmastlock | !start | hburst0 | hburst1)) -> !stateG2'")
    out.append(f"(!stateG2 & hmastlock & start & {INCR}) -> stateG2'")
    out.append("(stateG2 & !start & busreq) -> stateG2'")
    out.append("!(stateG2 & start)")
    out.append("(stateG2 & !start & !busreq) -> !stateG2'")


def _g3(out: list[str]) -> None:
    """G3's counter: a locked 4-beat burst owns the bus for four ``hready`` beats."""
    bits = ("stateG3_0", "stateG3_1", "stateG3_2")
    start4 = f"hmastlock & start & {BURST4}"
    out.append(f"({_state(bits, '000')} & (!hmastlock | !start | hburst0 | !hburst1)) -> "
               f"({_state(bits, '000', True)})")
    out.append(f"({_state(bits, '000')} & {start4} & !hready) -> ({_state(bits, '100', True)})")
    out.append(f"({_state(bits, '000')} & {start4} & hready) -> ({_state(bits, '010', True)})")
    for here, after in (("100", "010"), ("010", "110"), ("110", "001"), ("001", "000")):
        out.append(f"({_state(bits, here)} & !start & !hready) -> ({_state(bits, here, True)})")
        out.append(f"({_state(bits, here)} & !start & hready) -> ({_state(bits, after, True)})")
        out.append(f"!({_state(bits, here)} & start)")


def _guarantees(n: int) -> list[str]:
    """SYS_TRANS in the generator's clause order."""
    width = master_bits(n)
    masters = range(n)
    out = [f"({value_bits('hmaster', width, i)}) -> (hbusreq{i} <-> busreq)" for i in masters]
    _a1(out)
    out.append("!hready -> !start'")  # G1
    _g2(out)
    _g3(out)
    # G4, G5: on hready the grant names the next master, and locked the next hmastlock.
    out += [f"hready -> (hgrant{i} <-> ({value_bits('hmaster', width, i, True)}))" for i in masters]
    out.append("hready -> (!locked <-> !hmastlock')")
    # G6: without a new start the master and its lock stay.
    out += [f"!start' -> (({value_bits('hmaster', width, i)}) <-> "
            f"({value_bits('hmaster', width, i, True)}))" for i in masters]
    out.append("!start' -> (hmastlock <-> hmastlock')")
    # G7: a decision for master i sets locked exactly when i asks for a lock.
    out += [f"(decide & hgrant{i}') -> (hlock{i} <-> locked')" for i in masters]
    # G8: grants and locked change only on a decision.
    out += [f"!decide -> (!hgrant{i} <-> !hgrant{i}')" for i in masters]
    out.append("!decide -> (!locked <-> !locked')")
    # G10: a master other than 0 is not granted before it asks (stateG10_i: it has not).
    for i in range(1, n):
        t = f"stateG10_{i}"
        out.append(f"(!{t} & (hgrant{i} | hbusreq{i})) -> !{t}'")
        out.append(f"(!{t} & !hgrant{i} & !hbusreq{i}) -> {t}'")
        out.append(f"({t} & !hgrant{i} & !hbusreq{i}) -> {t}'")
        out.append(f"!({t} & hgrant{i} & !hbusreq{i})")
        out.append(f"({t} & hbusreq{i}) -> !{t}'")
    # G11: a decision with no request grants the default master 0.
    idle = " & ".join(f"!hbusreq{i}" for i in masters)
    out.append(f"(decide & {idle}) -> hgrant0'")
    return out


def amba_bits_sections(n: int) -> Sections:
    """The ``n``-master arbiter (2 to 16 masters) in the generator's encoding."""
    if not 2 <= n <= 16:
        raise ValueError(f"the SYNTCOMP AMBA family has 2 to 16 masters, not {n}")
    width = master_bits(n)
    masters = range(n)
    inputs = ["hready", *(f"{name}{i}" for i in masters for name in ("hbusreq", "hlock")),
              "hburst0", "hburst1"]
    outputs = [*(f"hmaster{j}" for j in range(width)), "hmastlock", "start", "decide",
               "locked", *(f"hgrant{i}" for i in masters), "busreq", "stateA1_0",
               "stateA1_1", "stateG2", "stateG3_0", "stateG3_1", "stateG3_2",
               *(f"stateG10_{i}" for i in range(1, n))]
    env_init = [f"!{name}" for name in inputs]
    env_trans = [f"hlock{i} -> hbusreq{i}" for i in masters]  # A3 (current step)
    env_liveness = ["!stateA1_1", "hready"]  # A1 through its monitor, A2
    initial_true = {"start", "decide", "hgrant0"}
    sys_init = [name if name in initial_true else f"!{name}" for name in outputs]
    sys_liveness = [f"({value_bits('hmaster', width, i)}) | !hbusreq{i}" for i in masters]  # G9
    return Sections(inputs, outputs, env_init, env_trans, env_liveness, sys_init,
                    _guarantees(n), sys_liveness)


def amba_bits_text(n: int) -> str:
    """The ``.structuredslugs`` text of the ``n``-master arbiter (deterministic)."""
    return amba_bits_sections(n).text(f"AMBA AHB arbiter, {n} masters, SYNTCOMP bit encoding")
