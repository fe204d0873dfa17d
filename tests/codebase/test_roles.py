"""Meaning is read from a clause's role, never from its label (issue 61).

The front end writes each clause with a label for people (``Origin.rule``: "eq. 3.5: under
east legs L1, L2 may lose one level ...") and a typed role (:mod:`gaitc.ir.roles`).  Before
roles, seven modules parsed the label back (``startswith("eq. 3.9 graded")``,
``removeprefix("eq. 3.4: leg ")``, ``split("): ")``).  This test reads every module with
:mod:`ast` and lists the string methods called on a label (``.rule``, or a variable named
``rule``) that read its words; only display code may, as often as :data:`DISPLAY`
says.  It then checks
that every clause the front end writes for the shipped specs has a role, and that the
roles agree with what the model declares.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from packages import PACKAGES, ROOT

import gaitc
from gaitc.ir.roles import (
    Goal,
    HazardEffect,
    LegFailure,
    Moves,
    Restores,
    Shape,
    Spares,
    StartHealth,
    UserClause,
    Wears,
)
from gaitc.ir.spec import SECTIONS

#: String methods that read a text's words.
READING = {"startswith", "endswith", "split", "rsplit", "partition", "rpartition",
           "removeprefix", "removesuffix", "find", "index"}
#: Display code that may read a label, only to show it, and how many times: whether a label
#: already names its line before a message, a report group or a SLUGS comment adds it.
DISPLAY = {"gaitc/analysis/separation.py": 1, "gaitc/analysis/tolerance.py": 1,
           "slugs_bridge/sections.py": 1}


def _labels_read(tree: ast.AST) -> list[int]:
    """Lines where a label's words are read: ``X.rule.m(...)`` or ``rule.m(...)`` for a
    reading method m, or ``"..." in X.rule``."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr in READING and _is_label(node.func.value):
            out.append(node.lineno)
        if isinstance(node, ast.Compare) and any(isinstance(op, (ast.In, ast.NotIn))
                                                 for op in node.ops) \
                and any(_is_label(c) for c in node.comparators):
            out.append(node.lineno)
    return out


def _is_label(node: ast.expr) -> bool:
    return (isinstance(node, ast.Attribute) and node.attr == "rule") or (
        isinstance(node, ast.Name) and node.id == "rule")


def test_no_module_reads_meaning_out_of_a_label() -> None:
    found = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            name = path.relative_to(ROOT).as_posix()
            lines = _labels_read(ast.parse(path.read_text(encoding="utf-8")))
            if len(lines) > DISPLAY.get(name, 0):
                found += [f"{name}:{line}" for line in lines]
    assert found == [], "read the clause's role (gaitc.ir.roles) instead"


def test_the_check_sees_a_label_being_parsed() -> None:
    """The test above can fail: the patterns the roles replaced are found."""
    old = ("def f(u, c):\n    a = u.rule.removeprefix('eq. 3.4: leg ')\n"
           "    return c.origin.rule.startswith('goal') or '): ' in c.origin.rule\n")
    assert _labels_read(ast.parse(old)) == [2, 3, 3]


SPECS = sorted((ROOT / "specs").glob("*.gait"))


@pytest.mark.parametrize("path", SPECS, ids=[p.stem for p in SPECS])
@pytest.mark.parametrize("encoding", ["onehot", "binary"])
def test_every_clause_of_a_shipped_spec_has_a_role_the_model_agrees_with(
        path: Path, encoding: str) -> None:
    spec = gaitc.load(path, encoding)
    model = spec.model
    assert model is not None
    legs = {leg.name for leg in model.legs}
    gaits = {g.name for g in model.gaits}
    hazards = {h.name: h for h in model.hazards}
    for section in SECTIONS:
        for clause in spec.gr1.section(section):
            assert clause.origin is not None and clause.origin.role is not None, clause
            role = clause.origin.role
            match role:
                case Shape():
                    assert section in ("env_init", "sys_init", "env_trans", "sys_trans")
                case StartHealth(leg=leg) | LegFailure(leg=leg):
                    assert leg in legs
                case Moves(region=region):
                    assert section == "sys_trans" and region in {r.name for r in model.regions}
                case Spares(gait=gait):
                    assert section == "env_trans" and gait in gaits
                case Wears(gait=gait, legs=used):
                    assert gait in gaits and set(used) <= set(model.gait(gait).legs)
                case HazardEffect(hazard=hazard, gait=gait, legs=used, harm=harm):
                    assert hazards[hazard].harm == harm and gait in gaits
                    assert set(used) <= set(model.gait(gait).legs)
                case Restores(cache=cache):
                    assert cache in model.caches
                case Goal(title=title):
                    assert section == "sys_liveness" and clause.origin.rule.endswith(title)
                case UserClause(assumption=assumption):
                    assert section.startswith("env" if assumption else "sys")
    goals = [c for c in spec.gr1.sys_liveness
             if c.origin is not None and isinstance(c.origin.role, Goal)]
    assert len(goals) == len(model.goals)
