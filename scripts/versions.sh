#!/bin/sh
# The quick suite on every Python gaitc declares (pyproject.toml: 3.11 to 3.13) that this
# machine has: for each, a fresh virtual environment in .venvs/pyX.Y with gaitc and its
# test extra, the README's first job (synthesize thesis robot A) and then the tests of
# scripts/check.sh -m "not slow" on every core.  ruff and mypy are left out: they check the
# source once, with the development environment's pinned tools and stubs (a fresh
# environment takes the newest numpy, whose stubs differ: numpy 2.5 on 3.13 rejects eight
# ndarray.min/max calls that 2.4's accept).  The full suite's tests/cli/test_package.py
# installs the wheel alone on each version; this is the longer check (about 5 minutes a
# version on two cores).  Usage: scripts/versions.sh [3.12 ...]
set -eu
cd "$(dirname "$0")/.."
versions="${*:-3.11 3.12 3.13}"
status=0
for v in $versions; do
    python=""
    for candidate in "$(command -v "python$v" 2>/dev/null || true)" \
                     "${PYENV_ROOT:-$HOME/.pyenv}"/versions/"$v".*/bin/python"$v"; do
        if [ -n "$candidate" ] && [ -x "$candidate" ] && "$candidate" --version >/dev/null 2>&1; then
            python="$candidate"
            break
        fi
    done
    if [ -z "$python" ]; then
        echo "versions: no Python $v on this machine: skipped" >&2
        continue
    fi
    env=".venvs/py$v"
    echo "versions: Python $v ($python) in $env" >&2
    rm -rf "$env"
    "$python" -m venv "$env"
    "$env/bin/python" -m pip install -q --disable-pip-version-check -e ".[test,peers,notebook]"
    out="$(mktemp -d)"
    "$env/bin/gaitc" synth specs/thesis_robot_a.gait -o "$out/robot_a.controller.json"
    rm -rf "$out"
    if "$env/bin/python" -m pytest -q -n auto --dist loadscope -m "not slow" \
            -k "not test_ruff_clean and not test_mypy_clean" -p no:cacheprovider; then
        echo "versions: Python $v: passed" >&2
    else
        echo "versions: Python $v: FAILED" >&2
        status=1
    fi
done
exit $status
