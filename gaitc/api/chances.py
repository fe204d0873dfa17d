"""Chances, as the facade names them: how likely a robot is to finish its patrols under
rates (:mod:`gaitc.analysis.chances`, Storm on the spec's MDP), and the controller that does
best in expectation, written as an explicit controller file.  Answers are kept in the user's
cache (:mod:`gaitc.diagnostics.usercache`) under a digest of the spec, the rates, the
options and the controller asked about."""

from __future__ import annotations

import hashlib
import json
import time
from pathlib import Path
from typing import Any

from gaitc.analysis.chances import Assumptions, Chances, ChancesOptions, Figures, Gain
from gaitc.analysis.chances import chances as compute
from gaitc.core.spec import Spec, SpecLike, as_spec
from gaitc.diagnostics import UsageError, usercache
from gaitc.diagnostics.files import write_atomically
from gaitc.diagnostics.versions import PACKAGE
from gaitc.forms.reader import load_runtime
from gaitc.forms.registry import entry
from gaitc.ir.controller import controller_from_dict, controller_to_dict
from gaitc.sim.domain import Domain
from gaitc.sim.rates import Rates, load_rates

#: The version of the cached answers (a change of the model or of what is cached bumps it).
CACHE_FORMAT = "chances 2"

__all__ = ["Chances", "ChancesOptions", "Rates", "chances", "load_rates", "save_best"]


def chances(spec: SpecLike, controller: str | Path | None = None, *,
            rates: Rates | str | Path | None = None, wear: float | None = None,
            options: ChancesOptions | None = None, write: bool = True,
            sensitivity: bool = False) -> Chances:
    """The chances of ``spec`` (a ``.gait`` spec) under ``rates`` (a rates file or
    :class:`Rates`; ``wear`` sets every leg's wear chance over it): the best any controller
    achieves, the controller Storm's scheduler gives (when ``write``) and, with
    ``controller`` (a controller file), that one's, with how long its assumptions hold; with
    ``sensitivity``, what one more health level on a leg or one more cache buys."""

    loaded: Spec = as_spec(spec)
    model = loaded.model
    if model is None:
        raise UsageError("gaitc chances reads a .gait spec: the rates speak of its legs, gaits "
                         "and hazards")
    if rates is None:
        chosen = Rates()
    elif isinstance(rates, Rates):
        chosen = rates
    else:
        chosen = load_rates(rates, model)
    chosen = chosen.with_wear(wear)
    opt = options or ChancesOptions()
    file = str(loaded.path or "<spec>")
    key = _key(loaded, chosen, opt, controller, write, sensitivity)
    clock = time.perf_counter()
    cached = _unpack(usercache.load(f"chances-{key[:24]}", key), file, chosen, opt)
    if cached is not None:
        cached.seconds = {"cache": time.perf_counter() - clock}
        return cached
    view = None if controller is None else load_runtime(controller, loaded)
    answer = compute(loaded.gr1, model, Domain(model, loaded.robot_encoding), chosen, file,
                     controller=view, options=opt, write=write, sensitive=sensitivity)
    usercache.store(f"chances-{key[:24]}", key, _pack(answer))
    return answer


def _key(spec: Spec, rates: Rates, opt: ChancesOptions, controller: str | Path | None,
         write: bool, sensitivity: bool) -> str:
    """The digest an answer is cached under: what it was computed from."""

    given = None if controller is None else hashlib.sha256(
        Path(controller).read_bytes()).hexdigest()
    made_from = {"format": CACHE_FORMAT, "gaitc": PACKAGE, "spec": spec.sha256,
                 "encoding": str(spec.robot_encoding),
                 "rates": {k: v for k, v in rates.to_json().items() if k != "file"},
                 "steps": opt.steps, "patrols": opt.patrols, "controller": given,
                 "max_states": opt.max_states,
                 "write": write, "sensitivity": sensitivity}
    return hashlib.sha256(json.dumps(made_from, sort_keys=True).encode()).hexdigest()


def _figures(f: Figures | None) -> list[Any] | None:
    return None if f is None else [list(f.patrols), dict(f.goals), f.expected_patrols,
                                   f.states]


def _pack(answer: Chances) -> dict[str, Any]:

    a = answer.assumptions
    return {"best": _figures(answer.best), "written": _figures(answer.written),
            "given": _figures(answer.given),
            "assumptions": None if a is None else [a.hold, a.patrols_before_break],
            "sensitivity": [[g.change, g.patrols, g.expected_patrols, g.gain, g.states]
                            for g in answer.sensitivity],
            "controller": None if answer.controller is None
            else controller_to_dict(answer.controller),
            "words": list(answer.rate_words)}


def _unpack(data: Any, file: str, rates: Rates, opt: ChancesOptions) -> Chances | None:
    """The cached answer, or None when ``data`` is not one (the cache then misses)."""

    def figures(raw: Any) -> Figures | None:
        if raw is None:
            return None
        patrols, goals, expected, states = raw
        return Figures(tuple(float(p) for p in patrols),
                       {str(k): float(v) for k, v in goals.items()}, float(expected),
                       int(states))

    try:
        best = figures(data["best"])
        if best is None:
            return None
        a = data["assumptions"]
        return Chances(
            file, rates, tuple(str(w) for w in data["words"]), opt, best,
            written=figures(data["written"]),
            controller=None if data["controller"] is None
            else controller_from_dict(data["controller"]),
            given=figures(data["given"]),
            assumptions=None if a is None else Assumptions(float(a[0]), a[1]),
            sensitivity=tuple(Gain(str(c), float(p), float(e), float(g), int(n))
                              for c, p, e, g, n in data["sensitivity"]))
    except (KeyError, TypeError, ValueError, UsageError):
        return None


def save_best(answer: Chances, path: str | Path) -> None:
    """Write the controller ``answer`` found (an explicit controller file)."""

    if answer.controller is None:
        raise UsageError("no controller was written: ask chances(..., write=True)")
    write_atomically(path, entry(answer.controller).to_file(answer.controller, path, None))
