"""Regenerate the figures of docs/figures/ (README and docs/simulation.md): one command,
``python tools/make_docs_figures.py``; needs Graphviz's ``dot``.

* ``robot_a_adversarial_run.svg``: thesis robot A (specs/thesis_robot_a.gait) on its map,
  20 steps against the adversarial environment, with the leg-health timeline (figure 3.7).
* ``patrol_2x2_automaton.svg``: the controller of specs/patrol_2x2.gait, every node drawn.
* ``thesis_robot_a_spec.svg``: robot A's region graph and gait map (``gaitc render spec``).
* ``robot_a_policy.svg`` and ``robot_a_first_steps.svg``: robot A's controller projected on
  the map (``gaitc render policy``) and its first 3 steps (``render automaton --steps 3``).

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

import gaitc  # noqa: E402
from gaitc.sim.automaton_view import automaton_view  # noqa: E402
from gaitc.sim.map_view import map_view, spec_view  # noqa: E402
from gaitc.sim.policy import controller_policy  # noqa: E402
from gaitc.sim.policy_view import policy_view  # noqa: E402
from gaitc.sim.steps_view import steps_view  # noqa: E402

FIGURES = ROOT / "docs" / "figures"
ROBOT_A = ROOT / "specs" / "thesis_robot_a.gait"
PATROL = ROOT / "specs" / "patrol_2x2.gait"


def controller_for(spec: Path, encoding: str) -> Path:
    digest = hashlib.sha256(spec.read_bytes()).hexdigest()[:16]
    path = Path(tempfile.gettempdir()) / f"gaitc-bench-{spec.stem}-{encoding}-{digest}.json"
    if not path.exists():
        print(f"synthesizing {spec.name} ({encoding}); this takes a while once", flush=True)
        found = gaitc.synthesize(gaitc.load(spec, encoding))
        if found.controller is None:
            raise SystemExit(f"{spec}: unrealizable")
        found.save(path)
    return path


def write(name: str, svg: str) -> None:
    path = FIGURES / name
    path.write_text(svg, encoding="utf-8")
    print(f"wrote {path.relative_to(ROOT)}")


def write_views(robot_a: gaitc.Session) -> None:
    """The readable views of robot A's controller (issue 13)."""
    policy = controller_policy(robot_a.strategy, robot_a.domain)
    write("robot_a_policy.svg", policy_view(policy, robot_a.domain).svg())
    write("robot_a_first_steps.svg", steps_view(robot_a.strategy, robot_a.domain, 3).svg())


def main() -> None:
    FIGURES.mkdir(parents=True, exist_ok=True)
    robot_a = gaitc.session(ROBOT_A, controller_for(ROBOT_A, "binary"), "binary")
    assert robot_a is not None
    run = gaitc.simulate(robot_a, env="adversarial", steps=20)
    write("robot_a_adversarial_run.svg", map_view(robot_a.model, run, 20).svg())
    write("thesis_robot_a_spec.svg", spec_view(robot_a.model).svg())
    write_views(robot_a)
    why = gaitc.explain(ROOT / "specs" / "thesis_robot_a_health2.gait", repairs=False)
    assert why.run is not None and why.run.model is not None
    write("robot_a_health2_play.svg", map_view(why.run.model, why.run, 30).svg())
    patrol = gaitc.session(PATROL)
    assert patrol is not None
    write("patrol_2x2_automaton.svg", automaton_view(patrol.strategy, patrol.domain,
                                                     "none").svg())


if __name__ == "__main__":
    main()
