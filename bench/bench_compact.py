"""Benchmark: compact controllers against the explicit and symbolic ones (issue 35).

Per spec, side by side: the explicit controller's nodes and synthesis time, the symbolic
controller's BDD nodes and time, the compact controller's rules, decision nodes (and the
assumption monitor's), table bytes and time (symbolic synthesis, compaction and the
symbolic proof together), and the AVR firmware image's flash and static RAM with the
controller linked in (avr-gcc; "-" without the toolchain, "too big" when refused).

Specs: the thesis robots A and B, the shipped examples, and a generated family of 8-leg
robots with health 3, twelve two-leg gaits, two caches and two hazard sets on a growing
grid (``lab8``).

Usage: python bench/bench_compact.py [--quick]
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import gaitc
from bench.families.lab8 import lab8
from gaitc.codegen.build import Target
from gaitc.codegen.tables import table_bytes
from gaitc.compact.controller import CompactController
from gaitc.diagnostics import GaitcError
from gaitc.hw.firmware import missing_tools

ROOT = Path(__file__).resolve().parent.parent
SPECS = ROOT / "specs"

def tasks(quick: bool) -> list[tuple[str, str, Path]]:
    shipped = ["thesis_robot_a.gait", "thesis_robot_b.gait", "corridor_hazard.gait",
               "patrol_2x2.gait", "radial8_patrol.gait"]
    if not quick:
        shipped += ["radial12_patrol.gait", "thesis_robot_a_health2.gait",
                    "shuttle_2leg.gait", "correction_edges.gait"]
    out = [(name, (SPECS / name).read_text(encoding="utf-8"), SPECS / name) for name in shipped]
    sizes = [(3, 5)] if quick else [(3, 5), (4, 5), (4, 6)]
    out += [(f"lab8 {r}x{c}", lab8(r, c), SPECS / f"lab8_{r}x{c}.gait") for r, c in sizes]
    return out


def _avr(spec: gaitc.Spec, ctrl: CompactController) -> str:
    if missing_tools(simulator=False):
        return "-"
    with tempfile.TemporaryDirectory() as folder:
        try:
            built = gaitc.generate(spec, ctrl, Target.AVR, folder)
        except GaitcError:
            try:
                built = gaitc.generate(spec, ctrl, Target.AVR, folder, monitor=False)
            except GaitcError:
                return "too big"
            return f"too big; {built.flash}/{built.ram} without the monitor"
    return f"{built.flash}/{built.ram}"


def row(name: str, text: str, path: Path) -> str:
    spec = gaitc.parse(text, name=str(path))
    t = time.perf_counter()
    explicit = gaitc.synthesize(spec, form="explicit")
    explicit_s = time.perf_counter() - t
    t = time.perf_counter()
    symbolic = gaitc.synthesize(spec, form="symbolic")
    symbolic_s = time.perf_counter() - t
    t = time.perf_counter()
    made = gaitc.synthesize(spec, form="compact")
    compact_s = time.perf_counter() - t
    ctrl = made.controller
    assert made.verified and isinstance(ctrl, CompactController), name
    assert explicit.controller is not None and symbolic.controller is not None
    return (f"| {name} | {len(explicit.controller.nodes)} | {explicit_s:.1f} | "
            f"{len(symbolic.controller.nodes)} | {symbolic_s:.1f} | {ctrl.rules} | "
            f"{ctrl.decision_nodes} + {ctrl.monitor_nodes} | {table_bytes(ctrl)} | "
            f"{_avr(spec, ctrl)} | {compact_s:.1f} |")


def main() -> None:
    quick = "--quick" in sys.argv
    print("| spec | explicit nodes | s | symbolic BDD nodes | s | compact rules | "
          "decision + monitor nodes | table bytes | AVR flash/RAM bytes | compact s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, text, path in tasks(quick):
        print(row(name, text, path), flush=True)


if __name__ == "__main__":
    main()
