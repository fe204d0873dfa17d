"""The language server's keywords are the grammar's (issue 49): completion offers the
statement keywords, directions and formula keywords that :func:`ltlcompiler.parser.keywords`
reads from ``gait.lark``, and every keyword it offers in a statement, from the clause lists
written by hand, is a keyword of that statement's rule.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from gaitc.lsp.completion import CLAUSES, offers
from ltlcompiler.parser import keywords, statement_keywords

LARK = (Path(__file__).resolve().parents[2] / "ltlcompiler" / "gait.lark").read_text()
GRAMMAR_WORDS = set(re.findall(r'"([a-z]+)"', LARK))


def _offered(before: str) -> list[str]:
    return [o.label for o in offers(before, None) if o.kind == "keyword"]


def test_keywords_are_the_grammars_words() -> None:
    """Every quoted word of gait.lark, and nothing else (the lark file read as text)."""
    assert set(keywords()) == GRAMMAR_WORDS
    assert len(keywords()) == len(set(keywords()))
    assert keywords("direction") == ("north", "south", "east", "west")
    assert {"always", "eventually", "next", "until", "and", "or", "xor", "not", "true",
            "false", "health", "failed"} == set(keywords("formula"))
    with pytest.raises(KeyError):
        keywords("no_such_rule")


def test_statement_keywords_start_each_statement_of_the_grammar() -> None:
    statements = statement_keywords()
    assert set(statements.values()) == set(re.findall(r"^(\w+_decl):", LARK, re.M))
    assert statements["correction"] == statements["gait"] == "gait_decl"
    assert statements["caches"] == "cache_decl"
    assert _offered("") == list(statements)
    assert _offered("robot \"r\"\n") == list(statements)


@pytest.mark.parametrize("statement", sorted(CLAUSES))
def test_each_clause_word_is_a_keyword_of_its_statement(statement: str) -> None:
    rule = statement_keywords()[statement]
    words = set(keywords(rule))
    assert {c for c in CLAUSES[statement] if c.isalpha()} <= words


#: Texts that end inside a statement, for each statement keyword: after its keyword, a
#: name, a list, and each of its clause keywords.
def _inside(statement: str) -> list[str]:
    texts = [f"{statement} ", f"{statement} a ", f"{statement} a, b ", f"{statement} a -> b ",
             f"{statement} a -> b by ", f"{statement} a: ", f"{statement} a with ",
             f"{statement} (a & ", f"{statement} health(", f"{statement} 2 x 2 "]
    for clause in CLAUSES.get(statement, ()):
        texts += [f"{statement} a {clause} ", f"{statement} a {clause} b, "]
    return texts


@pytest.mark.parametrize("statement", list(statement_keywords()))
def test_completion_inside_a_statement_offers_only_its_rules_keywords(statement: str) -> None:
    rule = statement_keywords()[statement]
    allowed = set(keywords(rule))
    for text in _inside(statement):
        wrong = set(_offered(text)) - allowed
        assert not wrong, (text, wrong, rule)


def test_formulas_are_offered_the_formula_keywords_the_checker_accepts() -> None:
    """Across a formula's places every formula keyword is offered but ``until`` (outside
    GR(1): the parser refuses it); the temporal words only as the prefix."""
    for statement in ("assume", "guarantee"):
        places = ["", "always ", "always eventually ", "always x ", "always (x & "]
        offered = {word for text in places for word in _offered(f"{statement} {text}")}
        assert offered == set(keywords("formula")) - {"until"}
        assert "next" not in _offered(f"{statement} ")  # an initial condition
        assert "next" not in _offered(f"{statement} always next ")
        for text in ("always x & ", "always (", "always eventually "):
            assert not {"always", "eventually"} & set(_offered(f"{statement} {text}"))
