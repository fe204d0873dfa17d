"""The instances of the benchmark table: every family as a list of spec files to solve.

Generated families (thesis grids, AMBA in two encodings, GenBuf, the VMCAI 2006 arbiter
and lift, SYNTCOMP safety games, hazard grids, and the peers' shapes: gr1c's gridworlds and
troll games, SLUGS's evasion game) are written into a directory chosen by the caller; the
SLUGS examples and the random corpus are read where the repository keeps them (tests/data),
with the verdicts SLUGS recorded for them.
Lists are in a fixed order.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from bench.families import evasion_requests, gr1c_gridworld, trolls
from bench.families.amba import amba_text
from bench.families.amba_bits import amba_bits_text
from bench.families.evasion_requests import Evasion, evasion_requests_text
from bench.families.genbuf import genbuf_text
from bench.families.gr1c_gridworld import Gridworld, gr1c_gridworld_text
from bench.families.hazard_grid import SIDES, hazard_grid_text
from bench.families.safety_games import CINDERELLA, OBSTACLES, cinderella_text, obstacle_text
from bench.families.thesis import HEALTH, SIZES, gait_text
from bench.families.trolls import Trolls, trolls_text
from bench.families.vmcai import ARBITER_SIZES, LIFT_SIZES, arbiter_text, lift_text

ROOT = Path(__file__).resolve().parent.parent.parent
EXAMPLES = ROOT / "tests" / "data" / "slugs_examples"
CORPUS = ROOT / "tests" / "data" / "gr1_corpus"
ENCODINGS = ("onehot", "binary")
AMBA_SIZES = list(range(2, 11))

#: The ``--quick`` subsets.
QUICK_SIZES = SIZES[:3]
QUICK_HEALTH = HEALTH[:2]
QUICK_AMBA = list(range(2, 6))
#: GenBuf's senders: powers of two, where every SLC value names a sender, and sizes between.
GENBUF_SIZES = [2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64]
QUICK_GENBUF = [2, 4, 8, 16]
QUICK_SIDES = SIDES[:4]
QUICK_ARBITER = ARBITER_SIZES[:8]
QUICK_LIFT = LIFT_SIZES[:8]
#: The arbiter without its clients' fairness (unrealizable) at these sizes.
UNFAIR_ARBITER = [4, 64]
#: One-hot hazard grids beyond this side are left out (the one-hot hazard group makes the
#: embedded solver time out from 6 x 6 on; the binary encoding is the family's row).
ONEHOT_SIDE_LIMIT = 4
#: The peers' shapes (sides, or width x height) whose realizability is known and which the
#: embedded solver confirmed (``gaitc check``); larger ones are listed with ``recorded=None``.
#: Gridworlds and troll games are realizable by construction (see their modules); evasion
#: games are not argued so, and count as known where SLUGS found them realizable too.
CONFIRMED_GRIDWORLDS = (64, 128, 256, 512, 1024)
CONFIRMED_TROLLS = (8, 16, 32, 64, 128)
CONFIRMED_EVASION = ((8, 8), (12, 8), (16, 8), (24, 8), (32, 8))


@dataclass(frozen=True)
class Instance:
    """One row of the table: a spec file, its encoding (``.gait`` only), SLUGS's verdict."""

    family: str
    name: str
    path: Path
    encoding: str = "onehot"
    recorded: bool | None = None  # SLUGS's recorded default-semantics verdict, if any


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def thesis(workdir: Path, quick: bool) -> list[Instance]:
    """Thesis robots A and B, then thesis grids at every size and health level, both
    encodings (all realizable)."""
    out = [Instance("thesis", f"robot {robot} {enc}", ROOT / "specs" / f"thesis_robot_{robot}.gait",
                    enc, True) for robot in ("a", "b") for enc in ENCODINGS]
    for rows, cols in QUICK_SIZES if quick else SIZES:
        for health in QUICK_HEALTH if quick else HEALTH:
            path = _write(workdir / f"thesis_{rows}x{cols}_h{health}.gait",
                          gait_text(rows, cols, health))
            out += [Instance("thesis", f"{rows}x{cols} h{health} {enc}", path, enc, True)
                    for enc in ENCODINGS]
    return out


#: The AMBA families: each one's text for N masters and the stem of its files.
ARBITERS: dict[str, tuple[Callable[[int], str], str]] = {
    "amba": (amba_text, "amba"),  # an integer hmaster (bench/families/amba.py)
    "amba-bits": (amba_bits_text, "amba_bits"),  # the SYNTCOMP generator's bit encoding
}


def amba(workdir: Path, quick: bool, sizes: list[int] | None = None,
         family: str = "amba") -> list[Instance]:
    """AMBA AHB arbiters of ``family`` (see :data:`ARBITERS`) for N = 2..10 masters (all
    realizable)."""
    text, stem = ARBITERS[family]
    chosen = sizes or (QUICK_AMBA if quick else AMBA_SIZES)
    return [Instance(family, f"N={n}", _write(workdir / f"{stem}_{n}.structuredslugs",
                                              text(n)), recorded=True)
            for n in chosen]


def genbufs(workdir: Path, quick: bool) -> list[Instance]:
    """Generalized buffers for N senders and two receivers (all realizable)."""
    return [Instance("genbuf", f"N={n}", _write(workdir / f"genbuf_{n}.structuredslugs",
                                                genbuf_text(n)), recorded=True)
            for n in (QUICK_GENBUF if quick else GENBUF_SIZES)]


def hazard_grids(workdir: Path, quick: bool) -> list[Instance]:
    """Hazard grids, binary encoding at every side and one-hot at the small ones."""
    out = []
    for n in QUICK_SIDES if quick else SIDES:
        path = _write(workdir / f"hazard_{n}x{n}.gait", hazard_grid_text(n))
        encodings = ENCODINGS if n <= ONEHOT_SIDE_LIMIT else ("binary",)
        out += [Instance("hazard", f"{n}x{n} h2 {enc}", path, enc, True) for enc in encodings]
    return out


def arbiters(workdir: Path, quick: bool) -> list[Instance]:
    """The VMCAI 2006 arbiter for N clients (realizable), and without the clients' fairness
    at the sizes of :data:`UNFAIR_ARBITER` (unrealizable)."""
    out = [Instance("arbiter", f"N={n}", _write(workdir / f"arbiter_{n}.structuredslugs",
                                                arbiter_text(n)), recorded=True)
           for n in (QUICK_ARBITER if quick else ARBITER_SIZES)]
    return out + [Instance("arbiter", f"N={n} unfair",
                           _write(workdir / f"arbiter_unfair_{n}.structuredslugs",
                                  arbiter_text(n, fair=False)), recorded=False)
                  for n in UNFAIR_ARBITER[:1 if quick else None]]


def lifts(workdir: Path, quick: bool) -> list[Instance]:
    """The VMCAI 2006 lift for N floors (all realizable)."""
    return [Instance("lift", f"N={n}", _write(workdir / f"lift_{n}.structuredslugs",
                                              lift_text(n)), recorded=True)
            for n in (QUICK_LIFT if quick else LIFT_SIZES)]


def safety_games(workdir: Path, quick: bool) -> list[Instance]:
    """The SYNTCOMP safety games (Cinderella-Stepmother, moving obstacle) with their
    published verdicts; ``quick`` keeps the configurations decided in about a second."""
    out = []
    for game, realizable in CINDERELLA:
        if not quick or game.buckets == 5:
            stem = f"cinderella_n{game.buckets}c{game.adjacent}_{game.capacity}by{game.units}"
            out.append(Instance("safety", f"cinderella {game.name}",
                                _write(workdir / f"{stem}.structuredslugs",
                                       cinderella_text(game)), recorded=realizable))
    for obstacle, realizable in OBSTACLES:
        if not quick or obstacle.side <= 8:
            stem = f"obstacle_{obstacle.side}_{obstacle.glitches}"
            out.append(Instance("safety", f"obstacle {obstacle.name}",
                                _write(workdir / f"{stem}.structuredslugs",
                                       obstacle_text(obstacle)), recorded=realizable))
    return out


def gr1c_gridworlds(workdir: Path, quick: bool) -> list[Instance]:
    """gr1c-shaped gridworlds at every side: two goals and one moving obstacle (the shape of
    gr1c's 1024 x 1024 example), then four goals and two obstacles (all realizable)."""
    out = []
    for side in gr1c_gridworld.QUICK_SIDES if quick else gr1c_gridworld.SIDES:
        for world in (Gridworld(side), Gridworld(side, goals=4, obstacles=2)):
            stem = f"gr1c_grid_{side}_g{world.goals}_o{world.obstacles}"
            out.append(Instance("gr1c-grid", world.name,
                                _write(workdir / f"{stem}.structuredslugs",
                                       gr1c_gridworld_text(world)),
                                recorded=True if side in CONFIRMED_GRIDWORLDS else None))
    return out


def troll_games(workdir: Path, quick: bool) -> list[Instance]:
    """Troll games at every side, with two goals and with three (all realizable)."""
    out = []
    for side in trolls.QUICK_SIDES if quick else trolls.SIDES:
        for game in (Trolls(side), Trolls(side, goals=3)):
            out.append(Instance("trolls", game.name,
                                _write(workdir / f"trolls_{side}_g{game.goals}.structuredslugs",
                                       trolls_text(game)),
                                recorded=True if side in CONFIRMED_TROLLS else None))
    return out


def evasion_games(workdir: Path, quick: bool) -> list[Instance]:
    """Evasion games in the shape of SLUGS's basicEvasion (24 x 8 is the example itself)."""
    out = []
    for width, height in evasion_requests.QUICK_SIZES if quick else evasion_requests.SIZES:
        game = Evasion(width, height)
        out.append(Instance("evasion", game.name,
                            _write(workdir / f"evasion_{width}x{height}.structuredslugs",
                                   evasion_requests_text(game)),
                            recorded=True if (width, height) in CONFIRMED_EVASION else None))
    return out


def slugs_examples() -> list[Instance]:
    """The SLUGS distribution's examples with their recorded verdicts."""
    out = []
    for line in (EXAMPLES / "verdicts.tsv").read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            name, default = line.split("\t")[:2]
            short = Path(name).stem.replace("specification_debugging_examples__", "debug/")
            short = short.replace("twoDimensionalCost__", "2dcost/").replace("__", "/")
            out.append(Instance("slugs-ex", short, EXAMPLES / name,
                                recorded=default == "realizable"))
    return sorted(out, key=lambda i: i.name)


def corpus() -> list[Instance]:
    """The random corpus (its .slugsin files) with the recorded verdicts."""
    records = json.loads((CORPUS / "verdicts.json").read_text(encoding="utf-8"))
    return sorted(
        (Instance("corpus", r["name"], CORPUS / f"{r['name']}.slugsin",
                  recorded=r["default"] == "realizable") for r in records),
        key=lambda i: i.name,
    )


FAMILIES = ("thesis", "amba", "amba-bits", "genbuf", "arbiter", "lift", "safety", "slugs-ex",
            "hazard", "gr1c-grid", "trolls", "evasion", "corpus")


def instances(workdir: Path, quick: bool, families: tuple[str, ...] = FAMILIES,
              amba_sizes: list[int] | None = None) -> list[Instance]:
    """Every instance of ``families`` in table order; generated files go to ``workdir``."""
    out: list[Instance] = []
    for family in FAMILIES:
        if family not in families:
            continue
        if family == "thesis":
            out += thesis(workdir, quick)
        elif family in ARBITERS:
            out += amba(workdir, quick, amba_sizes, family)
        elif family == "genbuf":
            out += genbufs(workdir, quick)
        elif family == "arbiter":
            out += arbiters(workdir, quick)
        elif family == "lift":
            out += lifts(workdir, quick)
        elif family == "safety":
            out += safety_games(workdir, quick)
        elif family == "slugs-ex":
            out += slugs_examples()
        elif family == "hazard":
            out += hazard_grids(workdir, quick)
        elif family == "gr1c-grid":
            out += gr1c_gridworlds(workdir, quick)
        elif family == "trolls":
            out += troll_games(workdir, quick)
        elif family == "evasion":
            out += evasion_games(workdir, quick)
        else:
            out += corpus()
    return out
