"""Byte- and line-level mutation of input files, for the fuzz tests and ``bench/fuzz.py``.

A mutant is a seed file with one to four edits: bytes flipped, inserted or deleted, lines
deleted, duplicated, swapped or spliced in from another seed, numbers made huge or odd,
brackets nested deep, the text cut short. Every choice goes through a :class:`Chooser`, so
the same seed (``random.Random``) or the same hypothesis draws give the same mutant.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from typing import Protocol


class Chooser(Protocol):
    """The two choices a mutation makes; ``random.Random`` is one."""

    def randint(self, a: int, b: int) -> int: ...  # a <= result <= b


# Bytes that readers have tripped over: line separators other than \n (form feed,
# vertical tab, \x1c-\x1e, NEL, U+2028/9), NUL, a lone \r, bytes that are not UTF-8 (a
# stray continuation byte, a truncated sequence), a BOM, digits that are not ASCII.
ODD: tuple[bytes, ...] = (
    b"\x00", b"\r", b"\t", b"\x0b", b"\x0c", b"\x1c", b"\x1d", b"\x1e", b"\x7f",
    "\x85".encode(), "\u2028".encode(), "\u2029".encode(), b"\xff", b"\xc3", b"\x80",
    b"\xe2\x80", "\ufeff".encode(), "²".encode(), "٣".encode(), "é".encode(), b"\n", b"\r\n",
    b" ", b"-", b"#", b":", b",", b"{", b"}", b"[", b"]", b"(", b")", b'"', b"'", b"!", b"&",
    b"|", b"->", b"<->", b"$", b"?", b"=", b"...", b"'", b"*", b"&", b"@",
)
NUMBERS: tuple[bytes, ...] = (
    b"0", b"-1", b"1", b"2", b"101", b"100000", b"1000000000", b"9" * 19, b"1" * 5000,
    b"1e400", b"nan", b"inf", b"-0", b"0x10", b"1.5", b"", b"\xd9\xa3",
)
NUMBER = re.compile(rb"-?\d+(?:\.\d+)?")


def _pick(chooser: Chooser, items: Sequence[bytes]) -> bytes:
    return items[chooser.randint(0, len(items) - 1)]


def _position(chooser: Chooser, data: bytes) -> int:
    return chooser.randint(0, len(data))


def _lines(data: bytes) -> list[bytes]:
    return data.splitlines(keepends=True) or [b""]


def flip_byte(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    if not data:
        return bytes([chooser.randint(0, 255)])
    i = chooser.randint(0, len(data) - 1)
    return data[:i] + bytes([chooser.randint(0, 255)]) + data[i + 1:]


def insert_odd(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    i = _position(chooser, data)
    return data[:i] + _pick(chooser, ODD) * chooser.randint(1, 3) + data[i:]


def delete_range(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    i = _position(chooser, data)
    return data[:i] + data[i + chooser.randint(1, 16):]


def duplicate_range(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    i = _position(chooser, data)
    piece = data[i:i + chooser.randint(1, 24)]
    return data[:i] + piece * chooser.randint(2, 4) + data[i:]


def truncate(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    return data[:_position(chooser, data)]


def delete_line(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    lines = _lines(data)
    del lines[chooser.randint(0, len(lines) - 1)]
    return b"".join(lines)


def duplicate_line(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    lines = _lines(data)
    i = chooser.randint(0, len(lines) - 1)
    lines.insert(i, lines[i])
    return b"".join(lines)


def swap_lines(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    lines = _lines(data)
    i, j = chooser.randint(0, len(lines) - 1), chooser.randint(0, len(lines) - 1)
    lines[i], lines[j] = lines[j], lines[i]
    return b"".join(lines)


def splice_line(data: bytes, chooser: Chooser, donors: Sequence[bytes]) -> bytes:
    """A line of another seed of the same kind, put in at a random line."""
    donor = _lines(_pick(chooser, donors) if donors else data)
    lines = _lines(data)
    lines.insert(chooser.randint(0, len(lines)), donor[chooser.randint(0, len(donor) - 1)])
    return b"".join(lines)


def odd_number(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    """One number of the text replaced by a huge, negative, fractional or odd one."""
    found = list(NUMBER.finditer(data))
    if not found:
        return insert_odd(data, chooser, _donors)
    m = found[chooser.randint(0, len(found) - 1)]
    return data[:m.start()] + _pick(chooser, NUMBERS) + data[m.end():]


def deep_nesting(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    """Hundreds or thousands of opening brackets (or ``!``), sometimes closed again."""
    pair = _pick(chooser, (b"[]", b"{}", b"()", b"!!", b"- ", b"&|"))
    opening, closing = pair[:1], pair[1:]
    count = (300, 1200, 6000)[chooser.randint(0, 2)]
    i = _position(chooser, data)
    middle = opening * count + (closing * count if chooser.randint(0, 1) else b"")
    return data[:i] + middle + data[i:]


def repeat_token(data: bytes, chooser: Chooser, _donors: Sequence[bytes]) -> bytes:
    """A word of the text repeated with an operator between, hundreds of times."""
    words = list(re.finditer(rb"[A-Za-z_][A-Za-z_0-9]*", data))
    if not words:
        return duplicate_range(data, chooser, _donors)
    m = words[chooser.randint(0, len(words) - 1)]
    glue = _pick(chooser, (b" & ", b" | ", b" -> ", b", ", b" "))
    times = chooser.randint(50, 600)
    return data[:m.start()] + glue.join([m.group()] * times) + data[m.end():]


# Values of the wrong type, size or shape, for the structure-aware mutations below.
ODD_JSON: tuple[object, ...] = (
    [[1]], 5, -1, "bogus", None, {}, [], True, 1.5, 10**30, "x" * 300, {"a": [None]},
    [1] * 500, "\u2028", float("inf"),
)
ODD_YAML: tuple[bytes, ...] = (
    b"[[1]]", b"{a: 1}", b"-5", b"~", b"!!binary AAAA", b"&x 1", b"*x", "'\u2028'".encode(),
    b"1e999", b".nan", b"!!python/object:os.system {}", b"|\n  text", b"? a", b"yes",
    b"99999999999999999999999", b"[L1, L1]", b"{h: [1, 2]}", b"-", b"''",
)


def _json_values(node: object, out: list[tuple[object, object]]) -> None:
    """Every (container, key) of a parsed JSON value, in document order."""
    stack = [node]
    while stack:
        item = stack.pop()
        pairs: list[tuple[object, object]] = []
        if isinstance(item, dict):
            pairs = [(item, k) for k in item]
        elif isinstance(item, list):
            pairs = [(item, i) for i in range(len(item))]
        out.extend(pairs)
        stack.extend(c[k] for c, k in pairs if isinstance(c[k], (dict, list)))  # type: ignore[index]


def odd_json_value(data: bytes, chooser: Chooser, donors: Sequence[bytes]) -> bytes:
    """One value of a JSON document replaced by one of another type or size."""
    import json

    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        return odd_yaml_value(data, chooser, donors)
    places: list[tuple[object, object]] = []
    _json_values(doc, places)
    if not places:
        return insert_odd(data, chooser, donors)
    container, key = places[chooser.randint(0, len(places) - 1)]
    container[key] = ODD_JSON[chooser.randint(0, len(ODD_JSON) - 1)]  # type: ignore[index]
    return json.dumps(doc, indent=chooser.randint(0, 2) or None).encode()


def odd_yaml_value(data: bytes, chooser: Chooser, donors: Sequence[bytes]) -> bytes:
    """The value after one ``key:`` (or ``- ``) replaced by an odd YAML value."""
    found = list(re.finditer(rb"(?:: |- )([^\n,{}\[\]#]+)", data))
    if not found:
        return insert_odd(data, chooser, donors)
    m = found[chooser.randint(0, len(found) - 1)]
    return data[:m.start(1)] + _pick(chooser, ODD_YAML) + data[m.end(1):]


Mutation = Callable[[bytes, Chooser, Sequence[bytes]], bytes]
MUTATIONS: tuple[Mutation, ...] = (
    flip_byte, insert_odd, delete_range, duplicate_range, truncate, delete_line,
    duplicate_line, swap_lines, splice_line, odd_number, deep_nesting, repeat_token,
    odd_json_value, odd_yaml_value,
)
# Mutants stay below this size so that a run's time measures the reader, not the disk.
MAX_MUTANT = 200_000


def mutate(seed: bytes, chooser: Chooser, donors: Sequence[bytes] = ()) -> bytes:
    """``seed`` with one to four random edits (each from :data:`MUTATIONS`)."""
    data = seed
    for _ in range(chooser.randint(1, 4)):
        data = MUTATIONS[chooser.randint(0, len(MUTATIONS) - 1)](data, chooser, donors)
        data = data[:MAX_MUTANT]
    return data
