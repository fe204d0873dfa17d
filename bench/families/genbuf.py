"""The generalized buffer (GenBuf) family: a GR(1) specification for N senders and two receivers.

GenBuf is the second benchmark of Bloem, Jobstmann, Piterman, Pnueli, Sa'ar, "Synthesis of
Reactive(1) designs" (JCSS 78(3), 2012, section 8.2), after the IBM buffer of the RATSY
case studies (Bloem et al., "Specify, Compile, Run: Hardware from PSL", COCV 2007), and a
family of SYNTCOMP's GR(1) benchmarks beside AMBA.  The buffer takes data from N senders
(four-phase handshakes ``StoB_REQ``/``BtoS_ACK``), stores it in a FIFO it drives with
``ENQ``/``DEQ`` (whose ``FULL``/``EMPTY`` flags the environment sets), tells the
multiplexer which sender to store through the select bits ``SLC`` (ceil(log2 N) bits, least
significant first, with no range constraint), and hands the data to two receivers
(handshakes ``BtoR_REQ``/``RtoB_ACK``) in turn.

This module writes the published assumptions A1-A4 and guarantees G1-G12 in the form of
the benchmark's generator: the round-robin guarantee G7 as a two-bit monitor automaton
(``stateG7_1 stateG7_0``), the liveness G12 ("a non-empty FIFO is dequeued eventually")
through a one-bit monitor ``stateG12``, G1 and A2 as the fairness conditions
``StoB_REQ_i <-> BtoS_ACK_i`` and ``BtoR_REQ_j <-> RtoB_ACK_j``, and the safety
guarantees that the generator states over the current step (G5, G7's mutual exclusion, G11
and the monitor's forbidden states) over the current step here too.  The code is written
from the formulas; it shares none with the generator.
"""

from __future__ import annotations

from bench.families.amba import Sections
from bench.families.amba_bits import master_bits, value_bits

#: The receivers: the published G7 monitor is built for exactly two.
RECEIVERS = 2
#: The sizes the family is defined for (SLC of 1 to 6 bits).
SENDERS = range(2, 65)


#: Bits of the multiplexer select ``SLC`` for ``n`` senders: ceil(log2 n), at least one.
select_bits = master_bits


def _senders(n: int) -> tuple[list[str], list[str]]:
    """A1 (the sender's side of the handshake) and G2-G5 for every sender."""
    env: list[str] = []
    sys: list[str] = []
    for i in range(n):
        req, ack = f"StoB_REQ{i}", f"BtoS_ACK{i}"
        sys.append(f"(!{req} & {req}') -> !{ack}'")  # G2: a new request is not acked at once
        sys.append(f"(!{ack} & !{req}) -> !{ack}'")  # G3: no ack without a request
        sys.append(f"({ack} & {req}) -> {ack}'")  # G4: an ack stays while the request does
        env.append(f"({req} & !{ack}) -> {req}'")  # A1: a request stays until acked
        env.append(f"{ack} -> !{req}'")  # A1: an ack ends the request
        sys += [f"!{ack} | !BtoS_ACK{k}" for k in range(i + 1, n)]  # G5: one ack at a time
    return env, sys


def _receivers() -> tuple[list[str], list[str]]:
    """A3, A4 (the receiver's side) and G6-G8 for both receivers, G7 as its monitor."""
    env: list[str] = []
    sys: list[str] = []
    for j in range(RECEIVERS):
        req, ack = f"BtoR_REQ{j}", f"RtoB_ACK{j}"
        env.append(f"!{req} -> !{ack}'")  # A3: no ack without a request
        env.append(f"({req} & {ack}) -> {ack}'")  # A4: an ack stays while the request does
        sys.append(f"({req} & !{ack}) -> {req}'")  # G6: a request stays until acked
        sys += [f"!{req} | !BtoR_REQ{k}" for k in range(j + 1, RECEIVERS)]  # G7: one at a time
        sys.append(f"{ack} -> !{req}'")  # G8: an ack ends the request
    # G7, round robin: after a request rises for one receiver, none rises for it again
    # before one rose for the other.  stateG7_1 remembers whose turn it is; stateG7_0 that
    # neither receiver is asked at the moment.
    r0, r1 = "BtoR_REQ0", "BtoR_REQ1"
    moves = (
        (f"!stateG7_1 & !{r0} & {r1}", "stateG7_1' & !stateG7_0'"),
        (f"stateG7_1 & {r0} & !{r1}", "!stateG7_1' & !stateG7_0'"),
        (f"!stateG7_1 & !{r0} & !{r1}", "!stateG7_1' & stateG7_0'"),
        (f"stateG7_1 & !{r0} & !{r1}", "stateG7_1' & stateG7_0'"),
        (f"!stateG7_1 & !stateG7_0 & {r0} & !{r1}", "!stateG7_1' & !stateG7_0'"),
        (f"stateG7_1 & !stateG7_0 & !{r0} & {r1}", "stateG7_1' & !stateG7_0'"),
    )
    sys.append(f"!({r0} & {r1})")
    sys += [f"({src}) -> ({dst})" for src, dst in moves]
    sys.append(f"!(!stateG7_1 & stateG7_0 & {r0})")
    sys.append(f"!(stateG7_1 & stateG7_0 & {r1})")
    return env, sys


def _fifo(n: int) -> tuple[list[str], list[str]]:
    """A4 (the FIFO's flags) and G9-G12: ENQ and SLC on a new sender ack, DEQ on a receiver's
    fallen ack, the FIFO never over- or underflows, and G12's monitor."""
    sys: list[str] = []
    for i in range(n):
        rose = f"(!BtoS_ACK{i} & BtoS_ACK{i}')"
        sys.append(f"{rose} -> ENQ'")  # G9: data is stored on each new ack
        link = "->" if i == 0 else "<->"  # sender 0 is SLC = 0 also when nobody sends
        slc = value_bits("SLC", select_bits(n), i, primed=True)
        sys.append(f"{rose} {link} ({slc})")  # G9: from the sender acked
    no_rise = " & ".join(f"(BtoS_ACK{i} | !BtoS_ACK{i}')" for i in range(n))
    sys.append(f"({no_rise}) -> !ENQ'")
    for j in range(RECEIVERS):
        sys.append(f"(RtoB_ACK{j} & !RtoB_ACK{j}') -> DEQ'")  # G10: a receiver took the data
    no_fall = " & ".join(f"(!RtoB_ACK{j} | RtoB_ACK{j}')" for j in range(RECEIVERS))
    sys.append(f"({no_fall}) -> !DEQ'")
    sys.append("(FULL & !DEQ) -> !ENQ")  # G11: never store into a full FIFO
    sys.append("EMPTY -> !DEQ")  # G11: never take from an empty one
    # G12: a non-empty FIFO is dequeued eventually; stateG12 is "owed a DEQ".
    sys += ["(!stateG12 & EMPTY) -> !stateG12'", "(!stateG12 & DEQ) -> !stateG12'",
            "(!stateG12 & !EMPTY & !DEQ) -> stateG12'", "(stateG12 & !DEQ) -> stateG12'",
            "(stateG12 & DEQ) -> !stateG12'"]
    env = ["(ENQ & !DEQ) -> !EMPTY'", "(DEQ & !ENQ) -> !FULL'",
           "(ENQ <-> DEQ) -> ((FULL <-> FULL') & (EMPTY <-> EMPTY'))"]
    return env, sys


def genbuf_sections(n: int) -> Sections:
    """The buffer for ``n`` senders (see :data:`SENDERS`) and two receivers."""
    if n not in SENDERS:
        raise ValueError(f"the GenBuf family has {SENDERS.start} to {SENDERS.stop - 1} "
                         f"senders, not {n}")
    senders, receivers = range(n), range(RECEIVERS)
    inputs = [*(f"StoB_REQ{i}" for i in senders), *(f"RtoB_ACK{j}" for j in receivers),
              "FULL", "EMPTY"]
    outputs = [*(f"BtoS_ACK{i}" for i in senders), *(f"BtoR_REQ{j}" for j in receivers),
               "stateG7_0", "stateG7_1", "ENQ", "DEQ", "stateG12",
               *(f"SLC{b}" for b in range(select_bits(n)))]
    env_init = [f"!{name}" for name in inputs if name != "EMPTY"] + ["EMPTY"]
    sys_init = [name if name == "stateG7_1" else f"!{name}" for name in outputs]
    env_s, sys_s = _senders(n)
    env_r, sys_r = _receivers()
    env_f, sys_f = _fifo(n)
    env_liveness = [f"BtoR_REQ{j} <-> RtoB_ACK{j}" for j in receivers]  # A2
    sys_liveness = [*(f"StoB_REQ{i} <-> BtoS_ACK{i}" for i in senders),  # G1
                    "!stateG12"]  # G12
    return Sections(inputs, outputs, env_init, env_s + env_r + env_f, env_liveness, sys_init,
                    sys_s + sys_r + sys_f, sys_liveness)


def genbuf_text(n: int) -> str:
    """The ``.structuredslugs`` text of the buffer for ``n`` senders (deterministic)."""
    return genbuf_sections(n).text(f"generalized buffer, {n} senders, 2 receivers")
