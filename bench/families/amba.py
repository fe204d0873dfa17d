"""The AMBA AHB arbiter family: a GR(1) specification for N bus masters as ``.structuredslugs``.

Written from the published description of the arbiter (Bloem, Galler, Jobstmann, Piterman,
Pnueli, Weiglhofer, "Specify, Compile, Run: Hardware from PSL", COCV 2007; Bloem et al.,
"Synthesis of Reactive(1) Designs", JCSS 2012, section 7) in the form of the SYNTCOMP
``amba_gr`` family: the same assumptions A1-A3 and guarantees G1-G11, the same auxiliary
monitors, master 0 as the default master, and G7 in the paper's form (see
:func:`amba_sections`).  Own choices: ``hmaster`` is one integer
``0...N-1``, the 4-beat burst counter ``stateG3`` is an integer counting the beats still
owed (``0...4``, 0 = no burst open), and A1 uses a one-bit monitor (see :func:`amba_text`).
References: Bloem et al. 2007 and 2012 (above); Jacobs et al., SYNTCOMP benchmarks.
"""

from __future__ import annotations

from dataclasses import dataclass

#: HBURST as two input bits, as in the published family: INCR = 00, BURST4 = hburst1 only;
#: the other two values are single transfers.
INCR = "(!hburst0 & !hburst1)"
BURST4 = "(!hburst0 & hburst1)"


@dataclass(frozen=True)
class Sections:
    """The eight ``.structuredslugs`` sections of one instance, each a list of lines."""

    inputs: list[str]
    outputs: list[str]
    env_init: list[str]
    env_trans: list[str]
    env_liveness: list[str]
    sys_init: list[str]
    sys_trans: list[str]
    sys_liveness: list[str]

    def text(self, title: str) -> str:
        """The instance as structuredslugs text, a comment line ``title`` first."""
        out = [f"# {title}", ""]
        for header, lines in (
            ("INPUT", self.inputs), ("OUTPUT", self.outputs), ("ENV_INIT", self.env_init),
            ("ENV_TRANS", self.env_trans), ("ENV_LIVENESS", self.env_liveness),
            ("SYS_INIT", self.sys_init), ("SYS_TRANS", self.sys_trans),
            ("SYS_LIVENESS", self.sys_liveness),
        ):
            out += [f"[{header}]", *lines, ""]
        return "\n".join(out)


def _p(name: str) -> str:
    """The next-step copy of variable ``name``."""
    return name + "'"


def _guarantees(n: int, half_g7: bool) -> list[str]:
    """SYS_TRANS: the monitors and G1-G8, G10, G11 (G9 is the liveness part)."""
    masters = range(n)
    out: list[str] = []
    # busreq is hbusreq of the current master (a definition, kept true at every step).
    out += [f"hmaster' = {i} -> (busreq' <-> hbusreq{i}')" for i in masters]
    # A1's monitor: stateA1 holds after a locked INCR transfer until busreq has fallen once.
    # With it, "G(hmastlock & INCR -> X F !busreq)" is the liveness assumption
    # "G F (!stateA1 | !busreq)" (ENV_LIVENESS).
    out.append(f"stateA1' <-> ((hmastlock & {INCR}) | (stateA1 & busreq))")
    # G1: a new transfer starts only when the slave is ready.
    out.append("!hready -> !start'")
    # G2: after the start of a locked INCR burst, no start until busreq falls (weak until).
    out.append(f"stateG2' <-> ((hmastlock & {INCR} & start) | (stateG2 & busreq))")
    out.append("stateG2' -> !start'")
    # G3: a locked 4-beat burst owns the bus for four hready beats, counted from its start.
    trigger = f"(hmastlock & {BURST4} & start)"
    out.append(f"(stateG3 = 0 & !{trigger}) -> stateG3' = 0")
    out.append(f"(stateG3 = 0 & {trigger} & hready) -> stateG3' = 3")
    out.append(f"(stateG3 = 0 & {trigger} & !hready) -> stateG3' = 4")
    for k in range(1, 5):
        out.append(f"(stateG3 = {k} & hready) -> stateG3' = {k - 1}")
        out.append(f"(stateG3 = {k} & !hready) -> stateG3' = {k}")
    out.append("stateG3' != 0 -> !start'")
    # G4, G5: on hready the grant decides the next master and the lock decides hmastlock.
    out += [f"hready -> (hgrant{i} <-> hmaster' = {i})" for i in masters]
    out.append("hready -> (locked <-> hmastlock')")
    # G6: without a start, the master and its lock stay.
    out.append("!start' -> (hmaster' = hmaster & (hmastlock' <-> hmastlock))")
    # G7: a decision that grants master i sets locked exactly when i asked for a lock (the
    # SYNTCOMP family keeps only the "not locked" half, which makes A1 vacuous).
    out += [f"(decide & !hlock{i} & hgrant{i}') -> !locked'" for i in masters]
    if not half_g7:
        out += [f"(decide & hlock{i} & hgrant{i}') -> locked'" for i in masters]
    # G8: grants and locked change only on a decision.
    out += [f"!decide -> (hgrant{i}' <-> hgrant{i})" for i in masters]
    out.append("!decide -> (locked' <-> locked)")
    # G10: a master other than 0 is not granted the bus before it asks for it; stateG10_i
    # remembers that at the previous step it was neither granted nor asking.
    for i in masters:
        if i == 0:
            continue
        out.append(f"stateG10_{i}' <-> (!hgrant{i} & !hbusreq{i})")
        out.append(f"(stateG10_{i}' & !hbusreq{i}') -> !hgrant{i}'")
    # G11: a decision with no request grants the bus to the default master 0.
    idle = " & ".join(f"!hbusreq{i}" for i in masters)
    out.append(f"(decide & {idle}) -> hgrant0'")
    return out


def amba_sections(n: int, half_g7: bool = False) -> Sections:
    """The AMBA AHB arbiter for ``n`` masters (1 to 16).

    ``half_g7`` keeps only the half of G7 that the SYNTCOMP family has (a decision for a
    master that does not ask for a lock clears ``locked``); by default G7 is the paper's
    "decide & X hgrant_i -> (hlock_i <-> X locked)", under which A1 matters.
    """
    if not 1 <= n <= 16:
        raise ValueError(f"the AMBA family has 1 to 16 masters, not {n}")
    masters = range(n)
    inputs = ["hready", *(f"{name}{i}" for i in masters for name in ("hbusreq", "hlock")),
              "hburst0", "hburst1"]
    outputs = [f"hmaster:0...{n - 1}", "hmastlock", "start", "decide", "locked",
               *(f"hgrant{i}" for i in masters), "busreq", "stateA1", "stateG2",
               "stateG3:0...4", *(f"stateG10_{i}" for i in masters if i > 0)]
    env_init = [f"!{name}" for name in inputs]
    # A3: a master asks for a lock only together with a request.
    env_trans = [f"hlock{i}' -> hbusreq{i}'" for i in masters]
    # A1 (through its monitor) and A2: the slave is ready infinitely often.
    env_liveness = ["!stateA1 | !busreq", "hready"]
    sys_init = ["hmaster = 0", "!hmastlock", "start", "decide", "!locked", "hgrant0",
                *(f"!hgrant{i}" for i in masters if i > 0), "!busreq", "!stateA1",
                "!stateG2", "stateG3 = 0", *(f"!stateG10_{i}" for i in masters if i > 0)]
    # G9: every master that keeps asking is served infinitely often.
    sys_liveness = [f"hmaster = {i} | !hbusreq{i}" for i in masters]
    return Sections(inputs, outputs, env_init, env_trans, env_liveness, sys_init,
                    _guarantees(n, half_g7), sys_liveness)


def amba_text(n: int, half_g7: bool = False) -> str:
    """The ``.structuredslugs`` text of the ``n``-master arbiter (deterministic).

    A1, "G(hmastlock & INCR -> X F !busreq)", becomes the one-bit monitor
    ``stateA1' <-> (hmastlock & INCR) | (stateA1 & busreq)`` and the assumption
    ``G F (!stateA1 | !busreq)``: stateA1 is true exactly when some locked INCR transfer
    before now has not yet seen busreq fall, so the assumption holds iff each one does.
    """
    variant = ", G7 halved as in SYNTCOMP" if half_g7 else ""
    plural = "s" if n > 1 else ""
    return amba_sections(n, half_g7).text(f"AMBA AHB arbiter, {n} master{plural}{variant}")
