"""How long the YAML readers take on large files (issue 38): read time against size.

A scenario of thesis robot A (one step per line: a leg degraded, a hazard switched) is
written at each size and read by ``load_scenario``, the path every YAML reader of the
project takes (``gaitc.diagnostics.yamltext.compose``: PyYAML's safe composer, the nesting
and alias limits, positions by the project's line rule).  The table gives the seconds, the
seconds per MB (constant when the reader is linear) and the same text with Windows line
ends (every node's position is then recounted).
Run: .venv/bin/python bench/bench_readers.py [--quick]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import gaitc  # noqa: E402
from gaitc.sim.scenario import load_scenario  # noqa: E402

SIZES_MB = [0.1, 1.0, 5.0, 10.0]
QUICK_SIZES_MB = [0.1, 1.0, 2.0]


def scenario_text(megabytes: float, line_end: str = "\n") -> str:
    """A scenario of about ``megabytes`` MB: one step per line, legs L1..L8 of robot A."""
    lines = ["steps:"]
    size, k = 7, 0
    while size < megabytes * 1_000_000:
        step = (f"  - {{degrade: [L{k % 8 + 1}]}}" if k % 3 else
                f"  - {{hazard: {'none' if k % 2 else 'blue'}}}")
        lines.append(step)
        size += len(step) + len(line_end)
        k += 1
    return line_end.join(lines) + line_end


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="sizes up to 2 MB")
    args = parser.parse_args()
    model = gaitc.load(str(ROOT / "specs" / "thesis_robot_a.gait")).model
    assert model is not None
    print(f"{'size MB':>8} {'steps':>8} {'read s':>8} {'s / MB':>7} {'CRLF s':>8} {'s / MB':>7}")
    with tempfile.TemporaryDirectory() as folder:
        for megabytes in QUICK_SIZES_MB if args.quick else SIZES_MB:
            cells = []
            for line_end in ("\n", "\r\n"):
                path = Path(folder) / "big.scenario.yaml"
                text = scenario_text(megabytes, line_end)
                path.write_bytes(text.encode("ascii"))
                began = time.perf_counter()
                steps = len(load_scenario(path, model).steps)
                cells.append(time.perf_counter() - began)
            real = len(text) / 1e6
            print(f"{real:8.2f} {steps:8d} {cells[0]:8.2f} {cells[0] / real:7.2f} "
                  f"{cells[1]:8.2f} {cells[1] / real:7.2f}", flush=True)


if __name__ == "__main__":
    main()
