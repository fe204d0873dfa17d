"""Choose the tests the quick run leaves out (tests/slow_tests.txt), from measured times.

The quick run (``scripts/check.sh -m "not slow"``) should take under three minutes on two
cores, the whole suite about fourteen.  Marking hundreds of parametrized cases by hand does
not keep up with the suite, so the ``slow`` mark is also given from a list:
``tests/conftest.py`` marks every case of each test function named in
``tests/slow_tests.txt``.  This tool writes that list from the times of a whole run::

    .venv/bin/python -m pytest -n 3 --dist loadscope --durations=0 -p no:randomly \\
        > /tmp/durations.log
    .venv/bin/python tools/slow_tests.py /tmp/durations.log

A test function is slow when one of its cases took more than ``--bound`` seconds (default
1), or all its cases together more than eight times that.  A function marked
``@pytest.mark.slow`` in its module needs no line here; a name no test module defines any
more is an error of ``tests/codebase/test_slow_list.py``.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections import defaultdict
from pathlib import Path
from typing import Final

ROOT: Final = Path(__file__).resolve().parent.parent
LIST: Final = ROOT / "tests" / "slow_tests.txt"
#: One line of pytest's ``--durations`` report: seconds, phase, node id.
LINE: Final = re.compile(r"^(?P<seconds>\d+(?:\.\d+)?)s (?P<phase>call|setup|teardown) +"
                         r"(?P<node>\S.*)$")
HEADER: Final = """\
# The test functions the quick run (-m "not slow") leaves out, every case of each: one
# path::function a line (path::Class::function for a method).  Written by
# tools/slow_tests.py from the times of a whole run (docs/background/testing.md); a
# function is here when one case took more than {bound:g} s, or all its cases more than
# {total:g} s.  tests/conftest.py reads it.
"""


def function_of(node: str) -> str:
    """The test function a node id names, without its parameters."""
    return node.split("[", 1)[0]


def slow_functions(report: str, bound: float) -> list[str]:
    """The functions whose slowest case passed ``bound`` seconds, or whose cases together
    passed eight times that, in a ``--durations`` report."""
    cases: dict[str, list[float]] = defaultdict(list)
    for line in report.splitlines():
        found = LINE.match(line.strip())
        if found is not None and found["phase"] == "call":
            cases[function_of(found["node"])].append(float(found["seconds"]))
    return sorted(name for name, times in cases.items()
                  if max(times) > bound or sum(times) > 8 * bound)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("report", type=Path, help="the output of a pytest --durations=0 run")
    parser.add_argument("--bound", type=float, default=1.0,
                        help="seconds a case may take in the quick run (default 1)")
    args = parser.parse_args(argv)
    try:
        report = args.report.read_text(encoding="utf-8")
    except OSError as err:
        print(f"slow_tests: cannot read {args.report}: {err.strerror}", file=sys.stderr)
        return 1
    names = slow_functions(report, args.bound)
    if not names:
        print(f"slow_tests: {args.report} has no '--durations' lines", file=sys.stderr)
        return 1
    LIST.write_text(HEADER.format(bound=args.bound, total=8 * args.bound)
                    + "".join(f"{name}\n" for name in names), encoding="utf-8")
    print(f"slow_tests: {len(names)} test functions written to {LIST.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
