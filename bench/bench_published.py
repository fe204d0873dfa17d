"""The published GR(1) instances, gaitc and its peers side by side (issue 59).

Every instance of ``../shared/bench/`` (``$GAITC_PUBLISHED``; :mod:`bench.families.published`)
is run by each tool as a whole process on the form that tool reads, as published: gaitc
(``python -m gaitc check``) on each SLUGS form given (``.slugsin``, ``.structuredslugs``),
SLUGS on the ``.slugsin``, gr1c (``gr1c -r``) on the ``.spc`` and omega
(``python -m peers.omega_game``) on a SLUGS form.  Per run: wall seconds, CPU seconds of the
process tree and its peak MB (:mod:`bench.families.measure`), and the verdict: R, U, T (past
the time limit), E (failed), - (not run: no binary, no input in its form); ``!`` marks a
verdict that differs from the benchmark's.

After the tools, three columns compare: ``x peer``, gaitc's CPU (its faster form) over the
best peer's that decided the instance (``-`` when no peer did; a peer past its limit counts
as the limit, shown ``>``); ``forms``, gaitc's slower form over its faster one.

SLUGS and gr1c are found through ``$SLUGS`` and ``$GR1C`` or PATH, never built here; a
missing one's column says ``-``.

Run: .venv/bin/python bench/bench_published.py [--quick] [--timeout S] [--only TEXT]...
     [--save FILE]
``--quick`` stops every tool at 60 s (the run stays near 20 minutes); ``--save`` writes the
table, dated, to FILE as well (``bench/published_last.txt`` keeps the last full run).
"""

from __future__ import annotations

import argparse
import datetime
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Final

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from bench.families.measure import measure
from bench.families.published import GAITC_FORMS, ROOT, Published, folder, instances
from bench.families.solvers import _SLUGS_RESULT
from peers.runners import find_gr1c, omega_installed
from slugs_bridge.runner import find_slugs

QUICK_TIMEOUT: Final = 60.0
LETTERS: Final = {"realizable": "R", "unrealizable": "U", "timeout": "T", "error": "E",
                  "n/a": "-"}
#: The columns: a gaitc column per SLUGS form, then the peers.
COLUMNS: Final = (*(f"gaitc{f}" for f in GAITC_FORMS), "slugs", "gr1c", "omega")


@dataclass(frozen=True)
class Figures:
    """One tool on one instance."""

    verdict: str
    wall: float = 0.0
    cpu: float = 0.0
    mb: float = 0.0

    @property
    def decided(self) -> bool:
        return self.verdict in ("realizable", "unrealizable")


def _command(column: str, instance: Published, slugs: str | None, gr1c: str | None,
             omega: bool) -> list[str] | None:
    forms = instance.forms
    if column.startswith("gaitc"):
        form = column.removeprefix("gaitc")
        if form not in forms:
            return None
        return [sys.executable, "-m", "gaitc", "check", str(forms[form])]
    if column == "slugs":
        return None if slugs is None or ".slugsin" not in forms else [slugs,
                                                                      str(forms[".slugsin"])]
    if column == "gr1c":
        return None if gr1c is None or ".spc" not in forms else [gr1c, "-r",
                                                                 str(forms[".spc"])]
    if column == "omega":
        source = forms.get(".structuredslugs") or forms.get(".slugsin")
        if not omega or source is None:
            return None
        return [sys.executable, "-m", "peers.omega_game", str(source)]
    raise ValueError(column)


def _verdict(column: str, code: int | None, out: str, err: str) -> str:
    if column == "slugs":
        said = _SLUGS_RESULT.findall(err + out)
        return said[0] if code == 0 and len(said) == 1 else "error"
    if column == "gr1c":
        text = (out + err).lower()
        if code in (0, 3) and "not realizable" in text:
            return "unrealizable"
        return "realizable" if code == 0 and "realizable." in text else "error"
    return {0: "realizable", 3: "unrealizable"}.get(-1 if code is None else code, "error")


def run(column: str, instance: Published, found: tuple[str | None, str | None, bool],
        timeout: float) -> Figures:
    line = _command(column, instance, *found)
    if line is None:
        return Figures("n/a")
    env = dict(os.environ)
    # as installed: Python writes its bytecode once (a setting that stops it would charge
    # gaitc's and omega's every run the compiling of their modules, 0.1-0.2 s)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), env.get("PYTHONPATH")) if p)
    done = measure(line, timeout, cwd=ROOT, env=env)
    verdict = ("timeout" if done.timed_out
               else _verdict(column, done.returncode, done.stdout, done.stderr))
    return Figures(verdict, done.wall, done.cpu, done.peak_mb)


def _cell(f: Figures, expected: str) -> str:
    mark = "!" if f.decided and f.verdict != expected else " "
    if f.verdict == "n/a":
        return f"{'-':>6} {'-':>6} {'-':>5} {'-':>2} "
    wall = f"{f.wall:6.2f}" if f.verdict != "timeout" else f"{'>' + format(f.wall, '.0f'):>6}"
    return f"{wall} {f.cpu:6.2f} {f.mb:5.0f} {LETTERS[f.verdict]:>2}{mark}"


def compare(row: dict[str, Figures], timeout: float) -> tuple[str, str]:
    """The ``x peer`` and ``forms`` columns of a row."""
    ours = [row[c] for c in COLUMNS if c.startswith("gaitc") and row[c].decided]
    peers = [row[c] for c in COLUMNS if not c.startswith("gaitc") and row[c].verdict != "n/a"]
    forms = f"{max(f.cpu for f in ours) / max(1e-3, min(f.cpu for f in ours)):.2f}" if len(
        ours) > 1 else "-"
    if not ours or not peers:
        return "-", forms
    decided = [p.cpu for p in peers if p.decided]
    best = min(decided) if decided else timeout
    ratio = min(f.cpu for f in ours) / max(1e-3, best)
    return (f"{ratio:.2f}" if decided else f"<{ratio:.2f}"), forms


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="every tool stops at 60 s")
    parser.add_argument("--timeout", type=float, default=None, help="seconds per run")
    parser.add_argument("--only", action="append", default=[],
                        help="only instances whose source/name contains this (repeatable)")
    parser.add_argument("--tools", default=",".join(COLUMNS),
                        help=f"columns to run (default all: {','.join(COLUMNS)})")
    parser.add_argument("--save", type=Path, help="write the table to this file too")
    args = parser.parse_args(argv)
    timeout = args.timeout or (QUICK_TIMEOUT if args.quick else 600.0)
    wanted = set(args.tools.split(","))
    found = (find_slugs(), find_gr1c(), omega_installed())
    rows = [i for i in instances() if not args.only or any(o in i.title for o in args.only)]
    lines = [f"published instances: {folder()}; {datetime.date.today()}; time limit "
             f"{timeout:g} s; slugs: {found[0] or 'not found'}; gr1c: "
             f"{found[1] or 'not found'}; omega: {'installed' if found[2] else 'not installed'}",
             ""]
    head = f"{'instance':<52}|" + "|".join(f"{c:^23}" for c in COLUMNS) + "| x peer  forms"
    sub = f"{'':<52}|" + "|".join(f"{'s':>6} {'cpu s':>6} {'MB':>5} {'v':>2} "
                                  for _ in COLUMNS) + "|"
    lines += [head, sub]
    print("\n".join(lines), flush=True)
    for instance in rows:
        row = {c: run(c, instance, found, timeout) if c in wanted else Figures("n/a")
               for c in COLUMNS}
        ratio, forms = compare(row, timeout)
        line = (f"{instance.title[:51]:<52}|"
                + "|".join(_cell(row[c], instance.verdict) for c in COLUMNS)
                + f"| {ratio:>6} {forms:>6}")
        print(line, flush=True)
        lines.append(line)
    legend = ("R realizable, U unrealizable, T past the time limit, E failed, - not run; "
              "! differs from the benchmark's verdict; x peer: gaitc's CPU (faster form) / "
              "the best peer's; forms: gaitc's slower form / its faster")
    print("\n" + legend)
    lines += ["", legend]
    if args.save is not None:
        args.save.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
