#!/usr/bin/env bash
# Set up gaitc on a fresh machine: Graphviz (for rendering), a virtual environment in .venv,
# and gaitc installed into it with its test tools and Dask ('gaitc resilience --dask').
# Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v dot >/dev/null 2>&1; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        echo "setup: installing Graphviz with apt-get" >&2
        apt-get install -y -qq graphviz >/dev/null 2>&1 \
            || { apt-get update -qq >/dev/null && apt-get install -y -qq graphviz >/dev/null; }
    else
        echo "setup: Graphviz 'dot' not found; rendering to svg/png/pdf needs it" >&2
        echo "       (Debian/Ubuntu: sudo apt-get install graphviz, macOS: brew install graphviz)" >&2
    fi
fi

PYTHON="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install -q --disable-pip-version-check -e '.[test,cluster]'
