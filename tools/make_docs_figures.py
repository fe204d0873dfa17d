"""Regenerate the figures of docs/figures/ (README and docs/simulation.md): one command,
``python tools/make_docs_figures.py``; needs Graphviz's ``dot``.

* ``robot_a_adversarial_run.svg``: thesis robot A (specs/thesis_robot_a.gait) on its map,
  20 steps against the adversarial environment, with the leg-health timeline (figure 3.7).
* ``patrol_2x2_automaton.svg``: the controller of specs/patrol_2x2.gait, every node drawn.
* ``thesis_robot_a_spec.svg``: robot A's region graph and gait map (``gaitc render spec``).

Robot A is synthesized in the binary encoding (about ten seconds); the result is cached
in the system's temporary directory, keyed by the spec's hash.
"""

from __future__ import annotations

import hashlib
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from gaitc.commands.simulating import load_session  # noqa: E402
from gaitc.loading import load  # noqa: E402
from gaitsim.automaton_view import automaton_view  # noqa: E402
from gaitsim.environments import AdversarialEnvironment  # noqa: E402
from gaitsim.map_view import map_view, spec_view  # noqa: E402
from gaitsim.simulator import simulate  # noqa: E402
from gr1.controller import controller_to_json  # noqa: E402
from solver.synthesis import synthesize  # noqa: E402

FIGURES = ROOT / "docs" / "figures"
ROBOT_A = ROOT / "specs" / "thesis_robot_a.gait"
PATROL = ROOT / "specs" / "patrol_2x2.gait"


def controller_for(spec: Path, encoding: str) -> Path:
    digest = hashlib.sha256(spec.read_bytes()).hexdigest()[:16]
    path = Path(tempfile.gettempdir()) / f"gaitc-bench-{spec.stem}-{encoding}-{digest}.json"
    if not path.exists():
        print(f"synthesizing {spec.name} ({encoding}); this takes a while once", flush=True)
        controller = synthesize(load(str(spec), encoding).gr1)
        if controller is None:
            raise SystemExit(f"{spec}: unrealizable")
        path.write_text(controller_to_json(controller), encoding="utf-8")
    return path


def write(name: str, svg: str) -> None:
    path = FIGURES / name
    path.write_text(svg, encoding="utf-8")
    print(f"wrote {path.relative_to(ROOT)}")


def main() -> None:
    FIGURES.mkdir(parents=True, exist_ok=True)
    robot_a = load_session(str(ROBOT_A), str(controller_for(ROBOT_A, "binary")), "binary")
    assert robot_a is not None
    run = simulate(robot_a.strategy, robot_a.domain, robot_a.monitor, AdversarialEnvironment(),
                   20, "specs/thesis_robot_a.gait")
    write("robot_a_adversarial_run.svg", map_view(robot_a.model, run, 20).svg())
    write("thesis_robot_a_spec.svg", spec_view(robot_a.model).svg())
    patrol = load_session(str(PATROL), None)
    assert patrol is not None
    write("patrol_2x2_automaton.svg", automaton_view(patrol.strategy, patrol.domain,
                                                     "none").svg())


if __name__ == "__main__":
    main()
