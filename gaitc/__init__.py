"""gaitc: a specification compiler and GR(1) synthesizer for walking soft robots.

The public API, one function per stage; each returns an object that shows itself in a
notebook (see ``docs/api.md``):

- :func:`load` / :func:`parse`: a ``.gait``, ``.slugsin`` or ``.structuredslugs`` file or
  text becomes a :class:`Spec` (the GR(1) IR, plus the robot model and source map for
  ``.gait``);
- :func:`lint`: the warnings of a ``.gait`` spec and the check of its valve primitives;
  :func:`separation`: whether the system can force the environment to break an
  assumption (well-separation);
- :func:`emit`: the spec as structuredslugs, slugsin or LTL text, exactly as
  ``gaitc compile`` writes it;
- :func:`check`: a :class:`Verdict`; :func:`synthesize` and :func:`counterstrategy`: a
  :class:`Synthesis` holding an automaton that :func:`verify` has proved;
- :func:`explain`: why a spec is unrealizable (kind, core, the environment's freedoms, a
  play, verified repairs), or the sanity checks of a realizable one;
- :func:`resilience`: which leg failures, health levels, caches and hazards a task
  tolerates or needs;
- :func:`simulate`: a run of a controller against an environment, checked against the spec;
- :func:`player` and :func:`player_widget`: a play stepped by hand, as the environment
  against a controller or as the robot against a counter-strategy (``gaitc play``);
- :func:`copy_examples`: the example robots and specs shipped in the package, copied out.

The robot half:

- :func:`gaits`: gait primitives of a robot file, from the chapter 2 gait graph, a chapter 4
  model, or a chapter 5 search in the global frame (:class:`GaitOptions`);
- :func:`learn`: a gait learned online on a simulated or modelled robot (thesis chapter 5,
  :class:`LearnOptions`);
- :func:`drive`: a controller's gaits run on a valve board (:class:`SimulatedBoard`,
  :class:`PhysicsBoard` or :class:`SerialBoard`; :class:`DriveOptions`);
- :func:`characterize` and :func:`calibrate`: a limb's spring-damper parameters and the
  legs' waveguide thresholds, fitted to recordings.

Every error a user can cause is a :class:`GaitcError` with a source span, and also the
builtin exception it means: a missing file is a :class:`FileNotFoundError`, a bad value a
:class:`ValueError`, a solver that cannot finish a :class:`RuntimeError`.

The command line (:mod:`gaitc.cli`) is a thin layer over these functions.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the names of _MODULES, for the type checker (tests/cli/test_cli_facade.py)
    from gaitc.api.answers import explain as explain
    from gaitc.api.answers import resilience as resilience
    from gaitc.api.chances import Chances as Chances
    from gaitc.api.chances import ChancesOptions as ChancesOptions
    from gaitc.api.chances import Rates as Rates
    from gaitc.api.chances import chances as chances
    from gaitc.api.characterizing import Recordings as Recordings
    from gaitc.api.characterizing import calibrate as calibrate
    from gaitc.api.characterizing import characterize as characterize
    from gaitc.api.compiling import FORMATS as FORMATS
    from gaitc.api.compiling import OutputFormat as OutputFormat
    from gaitc.api.compiling import emit as emit
    from gaitc.api.compiling import lint as lint
    from gaitc.api.compiling import separation as separation
    from gaitc.api.deciding import SOLVERS as SOLVERS
    from gaitc.api.deciding import Verdict as Verdict
    from gaitc.api.deciding import check as check
    from gaitc.api.drawing import controller_policy as controller_policy
    from gaitc.api.drawing import draw_automaton as draw_automaton
    from gaitc.api.drawing import draw_map as draw_map
    from gaitc.api.drawing import draw_spec as draw_spec
    from gaitc.api.driving import DriveOptions as DriveOptions
    from gaitc.api.driving import PhysicsBoard as PhysicsBoard
    from gaitc.api.driving import SerialBoard as SerialBoard
    from gaitc.api.driving import SimulatedBoard as SimulatedBoard
    from gaitc.api.driving import Tracker as Tracker
    from gaitc.api.driving import drive as drive
    from gaitc.api.examples import copy_examples as copy_examples
    from gaitc.api.gaits import GaitMethod as GaitMethod
    from gaitc.api.gaits import GaitOptions as GaitOptions
    from gaitc.api.gaits import GlobalSearch as GlobalSearch
    from gaitc.api.gaits import gaits as gaits
    from gaitc.api.generating import Target as Target
    from gaitc.api.generating import compact_policy as compact_policy
    from gaitc.api.generating import generate as generate
    from gaitc.api.learning import LearningBackend as LearningBackend
    from gaitc.api.learning import LearnOptions as LearnOptions
    from gaitc.api.learning import learn as learn
    from gaitc.api.playing import Autopilot as Autopilot
    from gaitc.api.playing import Player as Player
    from gaitc.api.playing import player as player
    from gaitc.api.playing import player_widget as player_widget
    from gaitc.api.simulation import Session as Session
    from gaitc.api.simulation import SurprisePolicy as SurprisePolicy
    from gaitc.api.simulation import session as session
    from gaitc.api.simulation import simulate as simulate
    from gaitc.api.solving import Synthesis as Synthesis
    from gaitc.api.solving import Tolerance as Tolerance
    from gaitc.api.solving import counterstrategy as counterstrategy
    from gaitc.api.solving import synthesize as synthesize
    from gaitc.api.solving import tolerate as tolerate
    from gaitc.api.solving import verify as verify
    from gaitc.core.modes import BackendKind as BackendKind
    from gaitc.core.modes import ControllerKind as ControllerKind
    from gaitc.core.modes import EncodingName as EncodingName
    from gaitc.core.modes import EnvironmentKind as EnvironmentKind
    from gaitc.core.modes import Form as Form
    from gaitc.core.modes import Role as Role
    from gaitc.core.modes import SearchMethod as SearchMethod
    from gaitc.core.modes import Semantics as Semantics
    from gaitc.core.spec import Spec as Spec
    from gaitc.core.spec import load as load
    from gaitc.core.spec import parse as parse
    from gaitc.diagnostics import ControllerError as ControllerError
    from gaitc.diagnostics import FileAccessError as FileAccessError
    from gaitc.diagnostics import FormulaError as FormulaError
    from gaitc.diagnostics import GaitcError as GaitcError
    from gaitc.diagnostics import MissingFileError as MissingFileError
    from gaitc.diagnostics import RatesError as RatesError
    from gaitc.diagnostics import ScenarioError as ScenarioError
    from gaitc.diagnostics import SlugsFormatError as SlugsFormatError
    from gaitc.diagnostics import SolverError as SolverError
    from gaitc.diagnostics import Span as Span
    from gaitc.diagnostics import SpecSemanticError as SpecSemanticError
    from gaitc.diagnostics import SpecSyntaxError as SpecSyntaxError
    from gaitc.diagnostics import UsageError as UsageError

#: The one list of the public names, by the module each lives in: ``__all__`` is derived
#: from it, the ``TYPE_CHECKING`` block above spells it out for the type checker (and
#: tests/cli/test_cli_facade.py holds the two equal). Modules load on first use, so ``gaitc
#: --help`` and a Ctrl-C at start-up do not wait for the solver, the parser and the gait
#: graph to import, and the packages below ``gaitc`` can import ``gaitc.diagnostics``
#: without a cycle.
_MODULES: dict[str, tuple[str, ...]] = {
    "gaitc.core.spec": ("Spec", "load", "parse"),
    "gaitc.core.modes": (
        "BackendKind", "ControllerKind", "EncodingName", "EnvironmentKind", "Form", "Role",
        "SearchMethod", "Semantics",
    ),
    "gaitc.api.compiling": ("FORMATS", "OutputFormat", "emit", "lint", "separation"),
    "gaitc.api.deciding": ("SOLVERS", "Verdict", "check"),
    "gaitc.api.solving": (
        "Synthesis", "Tolerance", "counterstrategy", "synthesize", "tolerate", "verify",
    ),
    "gaitc.api.answers": ("explain", "resilience"),
    "gaitc.api.chances": ("Chances", "ChancesOptions", "Rates", "chances"),
    "gaitc.api.simulation": ("Session", "SurprisePolicy", "session", "simulate"),
    "gaitc.api.playing": ("Autopilot", "Player", "player", "player_widget"),
    "gaitc.api.examples": ("copy_examples",),
    "gaitc.api.drawing": ("controller_policy", "draw_automaton", "draw_map", "draw_spec"),
    "gaitc.api.gaits": ("GaitMethod", "GaitOptions", "GlobalSearch", "gaits"),
    "gaitc.api.learning": ("LearnOptions", "LearningBackend", "learn"),
    "gaitc.api.driving": (
        "DriveOptions", "PhysicsBoard", "SerialBoard", "SimulatedBoard", "Tracker", "drive",
    ),
    "gaitc.api.characterizing": ("Recordings", "calibrate", "characterize"),
    "gaitc.api.generating": ("Target", "compact_policy", "generate"),
    "gaitc.diagnostics": (
        "ControllerError", "FileAccessError", "FormulaError", "GaitcError", "MissingFileError",
        "RatesError", "ScenarioError", "SlugsFormatError", "SolverError", "Span",
        "SpecSemanticError", "SpecSyntaxError", "UsageError",
    ),
}
_HOMES = {name: module for module, names in _MODULES.items() for name in names}


def __getattr__(name: str) -> Any:
    if name == "__version__":
        from gaitc.diagnostics.versions import PACKAGE

        return PACKAGE
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'gaitc' has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *_HOMES])


#: The public names, derived from :data:`_MODULES` (the one list of them).
__all__ = sorted(_HOMES)
