#!/usr/bin/env bash
# Set up gaitc on a fresh machine: Graphviz (for rendering), the AVR toolchain and simavr (for
# the valve-board firmware), a virtual environment in .venv,
# and gaitc installed into it with its test tools, Dask ('gaitc resilience --dask') and
# ipywidgets (the notebook player), MkDocs (the documentation site), ROS 2 with MCAP
# ('gaitc ros', 'simulate --mcap'; ROS 2's Python client and messages install as wheels) and
# stormpy ('gaitc chances').
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

# The valve-board firmware (gaitc firmware, tests/hardware/test_firmware.py): avr-gcc and simavr.
AVR_PACKAGES="gcc-avr avr-libc simavr libsimavr-dev libsimavrparts1"
if ! command -v avr-gcc >/dev/null 2>&1 || [ ! -e /usr/include/simavr/sim_avr.h ]; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        echo "setup: installing the AVR toolchain and simavr with apt-get" >&2
        # shellcheck disable=SC2086
        apt-get install -y -qq $AVR_PACKAGES >/dev/null 2>&1 \
            || { apt-get update -qq >/dev/null 2>&1 && apt-get install -y -qq $AVR_PACKAGES >/dev/null 2>&1; } \
            || echo "setup: could not install $AVR_PACKAGES; the firmware tests will be skipped" >&2
    else
        echo "setup: avr-gcc or simavr not found; 'gaitc firmware' and its tests need them" >&2
        echo "       (Debian/Ubuntu: sudo apt-get install $AVR_PACKAGES)" >&2
    fi
fi

# The VS Code extension (scripts/build-vscode.sh, tests/lsp/test_editor_extension.py): Node.js and npm.
if ! command -v npm >/dev/null 2>&1; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        echo "setup: installing Node.js and npm with apt-get" >&2
        apt-get install -y -qq nodejs npm >/dev/null 2>&1 \
            || { apt-get update -qq >/dev/null 2>&1 && apt-get install -y -qq nodejs npm >/dev/null 2>&1; } \
            || echo "setup: could not install npm; the editor extension's test will be skipped" >&2
    else
        echo "setup: npm not found; building the VS Code extension needs it" >&2
    fi
fi

PYTHON="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install -q --disable-pip-version-check -e '.[test,cluster,notebook,docs,peers,ros]'
# The ROS 2 wheels (the ros extra) pull in lark-parser 0.12 for rosidl's code generators (ROS's
# build-time tools, which gaitc does not run): it installs its files, and its type stubs, over
# lark's own 'lark' package, and gaitc's parser and mypy need lark 1.  So lark-parser is removed
# and lark's files are put back (rclpy does not use lark when it runs).
if .venv/bin/python -m pip show -q lark-parser >/dev/null 2>&1; then
    LARK="$(.venv/bin/python -m pip show lark 2>/dev/null | sed -n 's/^Version: //p')"
    .venv/bin/python -m pip uninstall -q -y lark-parser >/dev/null
    .venv/bin/python -m pip install -q --disable-pip-version-check --force-reinstall --no-deps \
        "lark==${LARK:-1.3.1}"
fi
.venv/bin/python -c 'import lark, sys; sys.exit(int(lark.__version__.split(".")[0]) < 1)' \
    || { echo "setup: the lark module is not lark 1 (gaitc's parser needs it)" >&2; exit 1; }
# 'gaitc chances' (Storm): stormpy ships manylinux_2_34 wheels (glibc 2.34 or newer); where
# none fits, the rest of gaitc works and the chances tests are skipped.
.venv/bin/python -m pip install -q --disable-pip-version-check -e '.[chances]' \
    || echo "setup: could not install stormpy (the chances extra); 'gaitc chances' and its tests will be skipped" >&2
# scripts/check.sh (the test command) runs ruff and mypy before the suite: both come with the
# test extra, and a setup without them is a failed setup.
for tool in ruff mypy vermin; do
    [ -x ".venv/bin/$tool" ] || { echo "setup: $tool was not installed into .venv" >&2; exit 1; }
done
