#!/usr/bin/env bash
# The test command (README.md's second line, and .ci/run): a fast stage first, then the suite.
#
# The fast stage (about half a minute) runs ruff, mypy (at Python 3.11, pyproject.toml) and
# the tests of the code's shape: the layering, its map in docs/background/layout.md, the
# quality rules and the minimum Python version. It stops the run with a message naming the
# stage that failed, so a lint or type error is reported before the 15-minute suite starts.
# Then the rest of the suite runs on every core; arguments are passed to that pytest run, e.g.
#     scripts/check.sh -m "not slow"      # the quick run (docs/background/testing.md)
# Set FAST_ONLY=1 to stop after the fast stage; VENV names another virtual environment.
set -uo pipefail
cd "$(dirname "$0")/.."

VENV="${VENV:-.venv}"
PY="$VENV/bin/python"
FAST_TESTS=(tests/codebase)  # the layering, its map, quality, modes, Python versions

fail() {
    echo >&2
    echo "check: FAILED at the fast stage: $1" >&2
    echo "check: the test suite was not run; fix the above and run scripts/check.sh again" >&2
    exit 1
}

for tool in ruff mypy; do
    [ -x "$VENV/bin/$tool" ] || fail "$tool is not installed in $VENV (run scripts/setup.sh)"
done

echo "check: ruff" >&2
"$VENV/bin/ruff" check gaitc ltlcompiler slugs_bridge tests bench tools typings \
    || fail "ruff found problems (listed above; 'ruff check --fix' fixes the ones marked [*])"

echo "check: mypy (Python 3.11, strict)" >&2
"$VENV/bin/mypy" || fail "mypy found type errors (listed above)"

echo "check: layering, layout map, quality and Python-version tests" >&2
# ruff and mypy ran just above: their two tests are not run a second time
"$PY" -m pytest -q "${FAST_TESTS[@]}" -k "not test_ruff_clean and not test_mypy_clean" \
    || fail "a layering, layout-map, quality or Python-version test failed (above)"

if [ "${FAST_ONLY:-0}" = 1 ]; then
    echo "check: fast stage passed (FAST_ONLY=1: the suite is not run)" >&2
    exit 0
fi

# The rest of the suite, on one worker more than the cores (pytest-xdist; GAITC_TEST_JOBS=1
# runs it in one process): many tests wait (on a child gaitc, the terminal player's frames,
# a board's watchdog period), and the extra worker runs while they wait; on two cores three
# workers took 13 min 24 s where two took 14 min 10 s (docs/background/testing.md).  Each
# test module stays on one worker, so its module-scoped fixtures are made once.
# tests/codebase passed above and is not run again.
CORES="$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)"
JOBS="${GAITC_TEST_JOBS:-$((CORES + 1))}"
PARALLEL=()
[ "$JOBS" = 1 ] || PARALLEL=(-n "$JOBS" --dist loadscope)
echo "check: fast stage passed; the whole test suite (workers: $JOBS)" >&2
exec "$PY" -m pytest "${PARALLEL[@]}" --ignore=tests/codebase --durations=20 "$@"
