"""SLUGS's names for the bits of integer variables: the one place that knows ``x@0.MIN.MAX``.

SLUGS's converter (tools/StructuredSlugsParser/compiler.py) encodes an integer ``x`` in
``MIN...MAX`` little-endian as bits ``x@0.MIN.MAX``, ``x@1``, ``x@2``, ... with value
``MIN`` + the unsigned bits; the first bit's name carries the range, so controllers and
counter-strategies written by SLUGS can be decoded without the spec.  :func:`bits_mismatch`
says how a controller's bits differ from a spec's, in the words verify and simulate share.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence

from gaitc.ir.spec import GR1Spec, Variable

_FIRST_BIT = re.compile(r"^(?P<name>.+)@0\.(?P<low>-?\d+)\.(?P<high>-?\d+)$")


def first_bit(name: str, low: int, high: int) -> str:
    """The name of bit 0 of integer ``name`` in ``low...high``."""
    return f"{name}@0.{low}.{high}"


def bit_name(name: str, index: int) -> str:
    """The name of bit ``index`` >= 1 of integer ``name``."""
    return f"{name}@{index}"


def parse_first_bit(bit: str) -> tuple[str, int, int] | None:
    """(name, MIN, MAX) when ``bit`` is a first bit ``x@0.MIN.MAX``, else None."""
    m = _FIRST_BIT.match(bit)
    if m is None:
        return None
    return m.group("name"), int(m.group("low")), int(m.group("high"))


def cut_integers(bit_names: Iterable[str]) -> dict[str, tuple[int, int, tuple[str, ...]]]:
    """The integers SLUGS's compiler cut into ``bit_names`` (``x@0.MIN.MAX``, ``x@1``, ...
    in a row): each integer's name with its MIN, MAX and bits, least significant first."""
    names = list(bit_names)
    present = set(names)
    out: dict[str, tuple[int, int, tuple[str, ...]]] = {}
    for bit in names:
        first = parse_first_bit(bit)
        if first is None:
            continue
        name, low, high = first
        bits = [bit]
        while bit_name(name, len(bits)) in present:
            bits.append(bit_name(name, len(bits)))
        out[name] = (low, high, tuple(bits))
    return out


def bit_count(var: Variable) -> int:
    """Bits of ``var``: the least n >= 1 with 2**n > MAX - MIN (:attr:`Variable.bits`).

    SLUGS's converter gives a one-value range (MIN = MAX) no bits at all; gaitc keeps one
    bit, fixed to 0 by the range constraint, so every integer has a first bit to decode.
    """
    return var.bits


def integer_bits(var: Variable) -> list[str]:
    """SLUGS's bit names for ``var``, least significant first (``[name]`` for a Boolean)."""
    if var.low is None or var.high is None:
        return [var.name]
    low, high = var.low, var.high
    return [
        first_bit(var.name, low, high) if i == 0 else bit_name(var.name, i)
        for i in range(bit_count(var))
    ]


def split_bit_name(bit: str) -> tuple[str, int] | None:
    """``("x", k)`` for a SLUGS bit name ``x@0.MIN.MAX`` or ``x@k``; None for other names."""
    name, at, rest = bit.rpartition("@")
    if not at or not name:
        return None
    index = rest.split(".", 1)[0]
    return (name, int(index)) if index.isdigit() else None


def decode_bits(var: Variable, valuation: Mapping[str, object], primed: bool = False) -> int:
    """The value of integer ``var`` from a valuation of its bits (``x@1`` or ``x@1'`` keys)."""
    assert var.low is not None
    suffix = "'" if primed else ""
    value = 0
    for i, bit in enumerate(integer_bits(var)):
        if valuation[bit + suffix]:
            value |= 1 << i
    return var.low + value


def encode_bits(var: Variable, value: int, primed: bool = False) -> dict[str, bool]:
    """The bit valuation SLUGS uses for ``var = value`` (keys primed when ``primed``)."""
    assert var.low is not None and var.high is not None
    if not var.low <= value <= var.high:
        raise ValueError(f"{value} lies outside {var.name}'s range {var.low}...{var.high}")
    suffix = "'" if primed else ""
    offset = value - var.low
    return {bit + suffix: bool(offset >> i & 1) for i, bit in enumerate(integer_bits(var))}


def decode_valuation(
    variables: Iterable[Variable], valuation: Mapping[str, object], primed: bool = False
) -> dict[str, bool | int]:
    """Values of the original (integer or Boolean) variables from a bit-level valuation."""
    suffix = "'" if primed else ""
    out: dict[str, bool | int] = {}
    for var in variables:
        if var.is_integer:
            out[var.name] = decode_bits(var, valuation, primed)
        else:
            out[var.name] = bool(valuation[var.name + suffix])
    return out


def spec_bits(spec: GR1Spec) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The bit names of a spec's inputs and outputs, in SLUGS order."""
    ins = tuple(b for v in spec.inputs for b in integer_bits(v))
    outs = tuple(b for v in spec.outputs for b in integer_bits(v))
    return ins, outs


def _listed(names: Sequence[str], shown: int = 6) -> str:
    quoted = ", ".join(repr(n) for n in names[:shown])
    more = f" and {len(names) - shown} more ({len(names)} in all)" if len(names) > shown else ""
    return f"variable{'s' if len(names) > 1 else ''} {quoted}{more}"


def bits_mismatch(
    controller: Sequence[str], spec: Sequence[str], order_matters: bool = True
) -> str | None:
    """Why a controller whose bits are ``controller`` does not belong to a spec whose bits
    are ``spec`` (both inputs first, then outputs): the spec's variables it lacks and those it
    has that the spec does not; None when they agree (in order, if ``order_matters``)."""
    have, want = set(controller), set(spec)
    missing = [b for b in spec if b not in have]
    extra = [b for b in controller if b not in want]
    parts = []
    if missing:
        parts.append(f"it lacks the spec's {_listed(missing)}")
    if extra:
        parts.append(f"it has {_listed(extra)}, which the spec does not have")
    if not parts:
        if not order_matters or tuple(controller) == tuple(spec):
            return None
        parts.append(f"it lists the spec's variables in another order: {list(controller)} "
                     f"instead of {list(spec)} (inputs first, then outputs)")
    return "controller does not belong to this spec: " + "; ".join(parts)
