"""Delta debugging (Zeller and Hildebrandt 2002), the search behind explain's cores and
needed freedoms: on any monotone test the answer still fails and is 1-minimal."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from gaitc.analysis.ddmin import ddmin


@settings(max_examples=200, deadline=None)
@given(st.integers(min_value=1, max_value=12).flatmap(
    lambda n: st.tuples(st.just(n), st.lists(st.frozensets(st.integers(0, n - 1), min_size=1,
                                                          max_size=n), min_size=1, max_size=4))))
def test_the_answer_fails_and_is_one_minimal(case: tuple[int, list[frozenset[int]]]) -> None:
    n, causes = case

    def fails(kept: tuple[int, ...]) -> bool:  # monotone: some cause is wholly kept
        return any(cause <= set(kept) for cause in causes)

    found = ddmin(tuple(range(n)), fails)
    assert fails(found)
    assert list(found) == sorted(found)  # a subsequence, in the original order
    for x in found:  # dropping any element loses the failure
        assert not fails(tuple(y for y in found if y != x))
