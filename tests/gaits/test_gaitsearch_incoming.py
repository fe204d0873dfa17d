"""The incoming-edge store of the array LPA* (gaitc.search.incoming) against a plain list."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.search.incoming import DEAD, IncomingEdges

# chunks (source, targets, edges) as an expansion adds them, then rows to kill, then queries
chunks = st.lists(
    st.tuples(
        st.integers(0, 30),
        st.lists(st.tuples(st.integers(0, 30), st.integers(0, 200)), max_size=12),
    ),
    max_size=25,
)


@settings(max_examples=80, deadline=None)
@given(chunks, st.lists(st.integers(0, 400), max_size=10), st.lists(st.integers(0, 30)))
def test_rows_of_targets_are_those_added_and_killed_ones_are_dead(
    added: list[tuple[int, list[tuple[int, int]]]], kills: list[int], wanted: list[int]
) -> None:
    store = IncomingEdges(tail=5)  # small runs: settling and merging happen often
    rows: list[list[int]] = []  # [target, source, edge]
    for source, out in added:
        targets = np.array([t for t, _ in out], np.int64)
        edges = np.array([e for _, e in out], np.int64)
        store.add(targets, source, edges)
        rows.extend([t, source, e] for t, e in out)
    for k in kills:
        if rows:
            t, u, e = rows[k % len(rows)]
            if e != DEAD:
                store.kill(t, u, e)
                for row in rows:
                    if row == [t, u, e]:
                        row[2] = DEAD
    targets = np.array(sorted(set(wanted)), np.int64)
    seg, src, via = store.of(targets)
    got = sorted(zip(targets[seg].tolist(), src.tolist(), via.tolist(), strict=True))
    expected = sorted((t, u, e) for t, u, e in rows if t in set(wanted))
    assert got == expected
    assert len(store) == len(rows)


def test_an_empty_store_and_an_empty_query_have_no_rows() -> None:
    store = IncomingEdges()
    assert [len(a) for a in store.of(np.array([3], np.int64))] == [0, 0, 0]
    store.add(np.array([1, 2], np.int64), 0, np.array([5, 6], np.int64))
    assert [len(a) for a in store.of(np.array([], np.int64))] == [0, 0, 0]
    seg, src, via = store.of(np.array([2, 9], np.int64))
    assert seg.tolist() == [0] and src.tolist() == [0] and via.tolist() == [6]
