"""Benchmark: how big the readable controller views are next to the whole automaton.

Usage: python bench/bench_views.py [SPEC.gait ...] [--controller FILE --encoding E]
(default: thesis robot A and the hazard patrol, controllers synthesized; with
--controller, one SPEC and that controller, e.g. the binary robot-A controller that
tools/make_docs_figures.py caches)

Per spec (a controller synthesized with the default preferences, onehot encoding): the
automaton's nodes and edges, the groups of its region-and-gait quotient (what
``render automaton`` draws above 40 nodes), the rules of ``render policy`` (and the most
in one region), and the nodes and edges of ``render automaton --steps K`` for K = 1..3,
with the seconds each view takes to build (DOT text, no Graphviz run).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from gaitc.api.simulation import session
from gaitc.sim.automaton_view import automaton_view
from gaitc.sim.policy import project
from gaitc.sim.policy_view import policy_view
from gaitc.sim.steps_view import steps_view
from gaitc.sim.strategy import Strategy

ROOT = Path(__file__).resolve().parent.parent
DEFAULT = [ROOT / "specs" / "thesis_robot_a.gait", ROOT / "tests" / "data" / "hazard_patrol.gait"]


def measure(
    path: Path, controller: str | None = None, encoding: str | None = None
) -> list[tuple[str, str, str]]:
    loaded = session(str(path), controller, encoding)
    if loaded is None or not isinstance(loaded.strategy, Strategy):
        return [(path.stem, "unrealizable or symbolic", "")]
    strategy, domain = loaded.strategy, loaded.domain
    edges = sum(len(set(s)) for s in strategy.successors)
    rows = [(path.stem, "automaton (nodes / edges)", f"{len(strategy)} / {edges}")]
    start = time.perf_counter()
    quotient = automaton_view(strategy, domain, "region-gait")
    quotient.dot()
    rows.append(
        (
            "",
            "quotient by region and gait (groups)",
            f"{len(quotient.groups)}   ({time.perf_counter() - start:.3f} s)",
        )
    )
    start = time.perf_counter()
    policy = project(strategy, domain)
    policy_view(policy, domain).dot()
    most = max(sum(1 for r in policy.rules if r.region == g) for g in policy.regions)
    rows.append(
        (
            "",
            "policy (regions / rules / most in a region)",
            f"{len(policy.regions)} / {len(policy.rules)} / {most}   "
            f"({time.perf_counter() - start:.3f} s)",
        )
    )
    for k in (1, 2, 3):
        start = time.perf_counter()
        view = steps_view(strategy, domain, k, cap=10**6)
        view.dot()
        rows.append(
            (
                "",
                f"first {k} steps (nodes / edges)",
                f"{len(view.depth)} / {len(view.edges)}   ({time.perf_counter() - start:.3f} s)",
            )
        )
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("specs", nargs="*", type=Path)
    parser.add_argument("--controller")
    parser.add_argument("--encoding", choices=("onehot", "binary"))
    args = parser.parse_args()
    paths = args.specs or DEFAULT
    if args.controller is not None and len(paths) != 1:
        parser.error("--controller goes with exactly one SPEC")
    rows = [("spec", "view", "size   (seconds)")]
    for path in paths:
        rows += measure(path, args.controller, args.encoding)
    widths = [max(len(r[i]) for r in rows) for i in range(2)]
    for row in rows:
        print(f"{row[0]:<{widths[0]}}  {row[1]:<{widths[1]}}  {row[2]}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
