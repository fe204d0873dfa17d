"""What ``gaitc check`` of a small spec imports (issue 50): only what deciding it uses.

A check of a spec of a few variables should end in about a tenth of a second, and most of
that is imports (``bench/bench_startup.py`` times it).  These tests run the command line as
``python -m gaitc`` does, in a fresh interpreter, and read :data:`sys.modules` when it has
finished: the heavy libraries of other commands, and the parts of gaitc that only
synthesis, controller files or forked solvers need, must not be among them.  The test is of
structure, not of time, so a busy machine cannot make it fail.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from packages import ROOT

#: Libraries no check imports: numerics, graphs, drawing, YAML, the terminal player and the
#: language server (lark only for ``.gait``).
HEAVY = ("numpy", "scipy", "networkx", "pydot", "yaml", "textual", "pygls")
#: Parts of gaitc (and of the standard library) that deciding a SLUGS spec does not use:
#: the .gait front end, the extraction of controllers and their file formats, the
#: bit-blasting only the SLUGS binary needs, and the machinery of forked solvers (a spec
#: of a few bits is solved in the process itself).
NOT_FOR_CHECK = (
    "lark", "ltlcompiler.model", "ltlcompiler.parser",
    "gaitc.solver.strategy", "gaitc.solver.counter", "gaitc.solver.symbolic_strategy",
    "gaitc.ir.controller", "gaitc.ir.bddfile", "gaitc.ir.quotient", "gaitc.verifier",
    "gaitc.ir.bitblast",
    "gaitc.compact", "multiprocessing", "ctypes", "tempfile",
)
SMALL_SPECS = ("tests/data/gr1_corpus/rand3_0000.slugsin",
               "tests/data/gr1_corpus/rand3_0002.structuredslugs")

#: ``python -m gaitc check SPEC`` in this interpreter (``runpy``, as ``-m`` does), then the
#: names of the modules loaded, as one JSON line.
PROBE = """\
import json, runpy, sys
sys.argv = ["gaitc", "check", sys.argv[1]]
try:
    runpy.run_module("gaitc", run_name="__main__", alter_sys=True)
except SystemExit as done:
    code = done.code
print(json.dumps({"code": code,
                  "modules": sorted(k for k, v in sys.modules.items() if v is not None)}))
"""


def _check_loads(spec: str) -> set[str]:
    """The modules loaded once ``gaitc check spec`` has run (which must decide it)."""
    done = subprocess.run([sys.executable, "-c", PROBE, spec], cwd=ROOT,
                          capture_output=True, text=True, check=False, timeout=120)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout.splitlines()[-1])
    assert result["code"] in (0, 3), done.stdout + done.stderr  # realizable, unrealizable
    modules: set[str] = set(result["modules"])
    return modules


def _within(modules: set[str], packages: tuple[str, ...]) -> list[str]:
    """The modules of ``modules`` that are one of ``packages`` or below one."""
    return sorted(m for m in modules
                  if any(m == p or m.startswith(p + ".") for p in packages))


@pytest.mark.parametrize("spec", SMALL_SPECS)
def test_checking_a_small_slugs_spec_imports_only_what_deciding_needs(spec: str) -> None:
    loaded = _check_loads(spec)
    assert {"dd.cudd", "gaitc.solver.game"} <= loaded  # it did decide (not vacuous)
    assert _within(loaded, HEAVY) == []
    assert _within(loaded, NOT_FOR_CHECK) == [], (
        "the check path imports modules it does not use; import them in the functions "
        "that need them (see bench/bench_startup.py for what each costs)")


def test_checking_a_gait_spec_imports_lark_but_no_heavy_library() -> None:
    loaded = _check_loads("specs/patrol_2x2.gait")
    assert {"lark", "ltlcompiler.parser", "gaitc.solver.game"} <= loaded
    assert _within(loaded, HEAVY) == []


def test_the_probe_sees_a_module_that_is_loaded() -> None:
    """The scan is not vacuous: a package the check does import is found, by prefix too."""
    loaded = _check_loads(SMALL_SPECS[0])
    assert _within(loaded, ("dd",)) and _within(loaded, ("gaitc.solver",))
