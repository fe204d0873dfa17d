"""Benchmark: explicit controllers on disk, SLUGS's JSON against the tables layout (issue 51).

Per spec: the explicit controller's nodes, the seconds of synthesis with extraction (and of
the symbolic form, for comparison), then for each layout (SLUGS's JSON, the old default,
and the gzip-compressed tables) the bytes on disk, the seconds to write the file (encoding
and the atomic write) and to read it back through the one reader (:mod:`gaitc.forms.reader`),
in CPU seconds, so that a busy machine does not blur the comparison.
A spec that is unrealizable gets its counter-strategy, which is explicit too.

Specs: the thesis robots A and B, robot A with health 2 (unrealizable), the 8-leg radial
patrol and the five-arm courier of issue 51 (``tests/data/five_arm_courier.gait``).

Usage: python bench/bench_explicit.py [--quick]
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import gaitc
from gaitc.forms.reader import read_controller
from gaitc.forms.synthesis import Synthesis
from gaitc.ir.controller import Controller

ROOT = Path(__file__).resolve().parent.parent
SPECS = [ROOT / "specs" / "thesis_robot_a.gait", ROOT / "specs" / "thesis_robot_b.gait",
         ROOT / "specs" / "thesis_robot_a_health2.gait"]
LARGE = [ROOT / "specs" / "radial8_patrol.gait", ROOT / "tests" / "data" / "five_arm_courier.gait"]
LAYOUTS = (("slugs-json", ".json"), ("tables", ".ctl.gz"))


def _cpu() -> float:
    """CPU seconds of this process and of its children that have ended (a solver may run
    in a forked child, :mod:`gaitc.solver.portfolio`)."""
    times = os.times()
    return time.process_time() + times.children_user + times.children_system


def _timed_synthesis(spec: gaitc.Spec, form: str) -> tuple[Synthesis, float]:
    start = _cpu()
    found = gaitc.synthesize(spec, form=form, verify=False, max_nodes=None)
    if found.controller is None:
        found = gaitc.counterstrategy(spec, verify=False)
    return found, _cpu() - start


def _layout(found: Synthesis, spec: gaitc.Spec, folder: Path, layout: str, suffix: str
            ) -> tuple[int, float, float]:
    path = folder / f"controller{suffix}"
    start = _cpu()
    found.save(path, layout=layout)
    wrote = _cpu() - start
    start = _cpu()
    back = read_controller(path, spec)
    read = _cpu() - start
    if back != found.controller:
        raise SystemExit(f"{path}: the controller read back differs from the one written")
    return path.stat().st_size, wrote, read


def main(argv: list[str]) -> int:
    quick = "--quick" in argv
    specs = SPECS if quick else SPECS + LARGE
    head = (f"{'spec':<28} {'kind':<8} {'nodes':>6} {'synth s':>8} {'symb s':>7} "
            f"{'JSON bytes':>11} {'write s':>8} {'read s':>7} "
            f"{'tables bytes':>12} {'write s':>8} {'read s':>7} {'ratio':>6}")
    print(head)
    print("-" * len(head))
    with tempfile.TemporaryDirectory(prefix="gaitc-bench-explicit-") as scratch:
        folder = Path(scratch)
        for path in specs:
            spec = gaitc.load(path)
            found, seconds = _timed_synthesis(spec, "explicit")
            controller = found.controller
            assert isinstance(controller, Controller)
            symbolic = "-"
            if found.realizable:
                symbolic = f"{_timed_synthesis(spec, 'symbolic')[1]:.2f}"
            cells = [_layout(found, spec, folder, layout, suffix)
                     for layout, suffix in LAYOUTS]
            (json_bytes, json_write, json_read), (tab_bytes, tab_write, tab_read) = cells
            kind = "strategy" if found.realizable else "counter"
            print(f"{path.name:<28} {kind:<8} {len(controller.nodes):>6} {seconds:>8.2f} "
                  f"{symbolic:>7} {json_bytes:>11,} {json_write:>8.3f} {json_read:>7.3f} "
                  f"{tab_bytes:>12,} {tab_write:>8.3f} {tab_read:>7.3f} "
                  f"{json_bytes / tab_bytes:>5.0f}x")
    print("\nSeconds are CPU seconds of this process and its children (the machine may be "
          "shared; a write's wait for the disk\nis not counted).  synth s: solving and "
          "extracting the explicit controller (not proved); symb s: the same spec's\nsymbolic "
          "form; write s: encoding and the atomic write; read s: reading and checking the file "
          "(gaitc.forms.reader).")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
