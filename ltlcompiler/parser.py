"""The .gait parser: ``gait.lark`` (LALR) plus :mod:`ltlcompiler.parse_tree`, which builds
:mod:`ltlcompiler.syntax` from lark's tree without recursion.

With :mod:`ltlcompiler.parse_tree`, the only module that imports lark.  Lark's exceptions
are mapped to :class:`SpecSyntaxError` (or :class:`FormulaError`) with ``file:line:col``
and a message saying what was expected; lark objects never leave the two modules.  LALR
parsing keeps its own stack, so formulas of any depth parse; the builder refuses those
deeper than :data:`~ltlcompiler.parse_tree.MAX_NESTING`.
"""

from __future__ import annotations

import difflib
import hashlib
import json
import pkgutil
import re
import sys
from dataclasses import replace
from functools import cache
from typing import Any, Final

from lark import Lark, Token
from lark import __version__ as lark_version
from lark.exceptions import (
    UnexpectedCharacters,
    UnexpectedEOF,
    UnexpectedInput,
    UnexpectedToken,
)
from lark.grammar import Rule
from lark.lark import _LOAD_ALLOWED_OPTIONS
from lark.lexer import PatternStr, TerminalDef

from gaitc.diagnostics import (
    FormulaError,
    GaitcError,
    Span,
    SpecSyntaxError,
    source_lines,
    usercache,
    without_bom,
)
from gaitc.diagnostics.versions import PACKAGE
from ltlcompiler import syntax as s
from ltlcompiler.parse_tree import build, token_span

_OPERATORS = ("&", "|", "^", "->", "<->", "and", "or", "xor", "until")
_TERMINAL_WORDS = {
    "NAME": "a name",
    "INT": "a number",
    "STRING": "a string in double quotes",
    "AXIS": "an axis such as +x or -y",
    "$END": "end of file",
}
#: Operators of other languages, written doubled, and the .gait operator to use instead.
_DOUBLED = {
    "&": "'&' (or 'and') for conjunction",
    "|": "'|' (or 'or') for disjunction",
    "=": "'=' to compare, as in health(L1) = 2",
}
#: Characters pasted from typeset formulas, and the .gait spelling of each.
_LOOKALIKES = {
    "\u2192": "->",
    "\u2194": "<->",
    "\u2227": "&",
    "\u2228": "|",
    "\u00ac": "!",
    "\u201c": '"',
    "\u201d": '"',
}


#: How gait.lark is analysed: the options that are data, part of the grammar cache's key.
_GRAMMAR_OPTIONS: Final = {"parser": "lalr", "lexer": "contextual", "maybe_placeholders": True}
#: The grammar cache's file name in the user's cache folder (gaitc.diagnostics.usercache).
GRAMMAR_CACHE: Final = "gait-grammar.json"


@cache
def _lark() -> Lark:
    """The parser of gait.lark.  Lark's analysis of the grammar takes about 50 ms, a quarter
    of a ``gaitc lint``, so its result is kept in the user's cache as plain data (never
    Lark's own cache, a pickle), under a key made of the grammar, the options and the
    versions of Lark and Python; a cache that is missing, foreign, corrupt or made from
    anything else is built again and rewritten."""
    text = _grammar_text()
    key = _grammar_key(text)
    cached = usercache.load(GRAMMAR_CACHE, key)
    if isinstance(cached, dict):
        loaded = _from_cache(cached)
        if loaded is not None:
            return loaded
    built = Lark(text, **_GRAMMAR_OPTIONS, **_load_options())
    usercache.store(GRAMMAR_CACHE, key, _to_cache(built))
    return built


def _grammar_text() -> str:
    """gait.lark, read by the package's own loader (from a folder or a zip alike; lark has
    imported :mod:`pkgutil` already, while :mod:`importlib.resources` would import a dozen
    modules, 4 ms of a ``gaitc check``)."""
    data = pkgutil.get_data("ltlcompiler", "gait.lark")
    if data is None:  # a loader that cannot read data files: gaitc's own files are missing
        raise FileNotFoundError("the grammar gait.lark is missing from the ltlcompiler package")
    # line ends as a file opened as text reads them (the cache's key is made of this text)
    return data.decode("utf-8").replace("\r\n", "\n").replace("\r", "\n")


def _load_options() -> dict[str, Any]:
    """The options that are code or that Lark does not keep, given again on each load."""
    return {"propagate_positions": True, "lexer_callbacks": {"NAME": _reserved}}


def _grammar_key(text: str) -> str:
    """A digest of everything the analysed grammar depends on: the grammar's text, the
    options, the versions of Lark, Python and gaitc."""
    options = json.dumps(_GRAMMAR_OPTIONS, sort_keys=True)
    python = ".".join(map(str, sys.version_info[:2]))
    made_of = "\0".join((text, options, repr(sorted(_load_options())), lark_version,
                         python, f"gaitc {PACKAGE}"))
    return hashlib.sha256(made_of.encode("utf-8")).hexdigest()


def _to_cache(parser: Lark) -> dict[str, Any]:
    """The analysed grammar as plain data, as :meth:`Lark.save` has it before pickling: the
    options given on each load (code among them) left out."""
    data, memo = parser.memo_serialize([TerminalDef, Rule])
    data["options"] = {name: value for name, value in data["options"].items()
                       if name not in _LOAD_ALLOWED_OPTIONS}
    return {"data": data, "memo": memo}


def _from_cache(cached: dict[str, Any]) -> Lark | None:
    """The parser rebuilt from :func:`_to_cache`'s data; None when the data is not that."""
    try:  # Lark._load_from_dict, typed
        return Lark.__new__(Lark)._load({"data": cached["data"], "memo": cached["memo"]},
                                        **_load_options())
    except Exception:  # data from a file: any failure at all means build it again
        return None


# ---------------------------------------------------------------- the grammar's keywords
@cache
def keywords(rule: str = "start") -> tuple[str, ...]:
    """The keywords of gait.lark that may occur within ``rule`` (the whole file by
    default), in the grammar's order: its string terminals made of letters, read from the
    analysed grammar, so that the editor's lists cannot drift from the language."""
    parser = _lark()
    words = {t.name: t.pattern.value for t in parser.terminals
             if isinstance(t.pattern, PatternStr) and t.pattern.value.isalpha()}
    expansions: dict[str, list[list[str]]] = {}
    for r in parser.rules:
        expansions.setdefault(r.origin.name, []).append([s.name for s in r.expansion])
    if rule not in expansions:
        raise KeyError(f"gait.lark has no rule {rule!r}")
    found: dict[str, None] = {}
    seen: set[str] = set()
    stack = [rule]
    while stack:  # depth first, in the order the rules write their symbols
        name = stack.pop()
        if name in seen:
            continue
        seen.add(name)
        later: list[str] = []
        for expansion in expansions[name]:
            for symbol in expansion:
                if symbol in words:
                    found.setdefault(words[symbol])
                elif symbol in expansions and symbol not in seen:
                    later.append(symbol)
        stack.extend(reversed(later))
    return tuple(found)


@cache
def statement_keywords() -> dict[str, str]:
    """Each keyword a statement can start with (``robot``, ``legs``, ``correction``, ...)
    and the grammar rule of that statement, in the grammar's order."""
    parser = _lark()
    words = {t.name: t.pattern.value for t in parser.terminals
             if isinstance(t.pattern, PatternStr) and t.pattern.value.isalpha()}
    statements = [r.expansion[0].name for r in parser.rules
                  if r.origin.name == "_statement" and len(r.expansion) == 1]
    found: dict[str, str] = {}
    for statement in statements:
        for r in parser.rules:
            if r.origin.name == statement and r.expansion and r.expansion[0].name in words:
                found.setdefault(words[r.expansion[0].name], statement)
    return found


def _reserved(tok: Token) -> Token:
    """'always'/'eventually' lexed as a name: they sit where GR(1) forbids them."""
    if tok in ("always", "eventually"):
        raise FormulaError(
            f"'{tok}' may only start an assume or guarantee: GR(1) allows 'always φ' (safety) "
            "and 'always eventually φ' (liveness), never a temporal word inside a formula or "
            "as a name",
            token_span("", tok),
        )
    return tok


# ---------------------------------------------------------------- errors
def _check_brackets(text: str, file: str) -> None:
    """Report an unclosed '(' or an unmatched ')' where it is, before lark gets lost."""
    stack: list[Span] = []
    in_comment = in_string = False
    line, col = 1, 0
    for ch in text:
        col += 1
        if ch == "\n":
            line, col = line + 1, 0
            in_comment = in_string = False
            continue
        if in_comment:
            continue
        if in_string:
            in_string = ch != '"'
            continue
        if ch == "#":
            in_comment = True
        elif ch == '"':
            in_string = True
        elif ch == "(":
            stack.append(Span(file, line, col, line, col))
        elif ch == ")":
            if not stack:
                here = Span(file, line, col, line, col)
                raise SpecSyntaxError("')' has no matching '('; remove it or add '('", here)
            stack.pop()
    if stack:
        raise SpecSyntaxError("'(' is never closed; add a matching ')'", stack[-1])


def _describe_terminal(name: str) -> str:
    if name in _TERMINAL_WORDS:
        return _TERMINAL_WORDS[name]
    try:
        pattern = _lark().get_terminal(name).pattern
    except KeyError:
        return name.lower()
    if isinstance(pattern, PatternStr):
        return f"'{pattern.value}'"
    return name.lower()


def _describe_expected(expected: set[str]) -> str:
    words = sorted({_describe_terminal(name) for name in expected})
    statements = [w for w in words if w.strip("'") in statement_keywords()]
    if len(statements) >= 5:
        words = [w for w in words if w not in statements] + ["a new statement"]
    operators = [w for w in words if w.strip("'") in _OPERATORS]
    if len(operators) >= 3:
        words = ["an operator such as & or ->"] + [w for w in words if w not in operators]
    if len(words) == 1:
        return words[0]
    return ", ".join(words[:-1]) + " or " + words[-1]


def _describe_token(tok: Token) -> str:
    if tok.type == "$END":
        return "end of file"
    if tok.type == "NAME":
        return f"name '{tok}'"
    if tok.type == "INT":
        return f"number '{tok}'"
    if tok.type == "STRING":
        return f"string {tok}"
    return f"'{tok}'"


def _end_span(text: str, file: str) -> Span:
    lines = source_lines(text) or [""]
    return Span(file, len(lines), len(lines[-1]) + 1)


def _suggestion(word: str, candidates: list[str]) -> str | None:
    close = [c for c in candidates if _swapped(word, c)]
    close = close or difflib.get_close_matches(word, candidates, n=1)
    return f"did you mean '{close[0]}'?" if close else None


def _swapped(word: str, keyword: str) -> bool:
    """Whether ``word`` is ``keyword`` with two neighbouring letters swapped (nxet, wset)."""
    diff = [k for k in range(len(word)) if len(word) == len(keyword) and word[k] != keyword[k]]
    if len(diff) != 2 or diff[1] != diff[0] + 1:
        return False
    return (word[diff[0]], word[diff[1]]) == (keyword[diff[1]], keyword[diff[0]])


def _mistyped_word(err: UnexpectedToken, expected: set[str], file: str) -> GaitcError | None:
    """A mistyped ``next``, ``always``, ``health`` ... in a formula is read as a name, and
    lark fails only at the word after it (``nxet r2``, ``helth(L1)``): point at the name.
    So too for a statement keyword read as a region of a list that may end there
    (``hazard fire:`` then ``cahce r3``)."""
    described = {_describe_terminal(name) for name in expected}
    if "'&'" in described:  # after an atom of a formula
        words: tuple[str, ...] = keywords("formula")
    elif "'cache'" in described and err.token.type == "NAME":  # where a statement may start
        words = tuple(statement_keywords())
    else:
        return None
    stack = _value_stack(err)
    if not stack or not isinstance(stack[-1], Token) or stack[-1].type != "NAME":
        return None
    name = str(stack[-1])
    close = [w for w in words if _swapped(name, w)]
    close = close or difflib.get_close_matches(name, words, n=1, cutoff=0.8)
    if not close:
        return None
    return SpecSyntaxError(
        f"name '{name}' cannot be followed by {_describe_token(err.token)}; expected "
        f"{_describe_expected(expected)} after it",
        token_span(file, stack[-1]),
        f"did you mean '{close[0]}'?",
    )


def _value_stack(err: UnexpectedToken) -> list[object]:
    """What the LALR parser had shifted when it failed (tokens and finished subtrees)."""
    parser = getattr(err, "interactive_parser", None)
    return list(parser.parser_state.value_stack) if parser is not None else []


def _keywords(expected: set[str]) -> list[str]:
    """The keywords among the terminals lark expected (what a mistyped word may have been)."""
    words = []
    for name in expected:
        try:
            pattern = _lark().get_terminal(name).pattern
        except KeyError:
            continue
        if isinstance(pattern, PatternStr) and pattern.value.isalpha():
            words.append(pattern.value)
    return sorted(words)


def _bad_character(char: str, pos: int, text: str, here: Span) -> GaitcError:
    """A character no token starts with: a fraction, a non-ASCII letter or a lookalike."""
    digits = "0123456789"
    if char == "." and 0 < pos < len(text) - 1 and {text[pos - 1], text[pos + 1]} <= set(digits):
        start, end = pos - 1, pos + 2
        while start > 0 and text[start - 1] in digits:
            start -= 1
        while end < len(text) and text[end] in digits:
            end += 1
        number = text[start:end]
        span = Span(
            here.file,
            here.line,
            here.column - (pos - start),
            here.line,
            here.column + (end - pos - 1),
        )
        if re.search(r"\bhealth\s+[0-9]+$", text[max(0, start - 40) : pos]):
            return SpecSyntaxError(
                f"health must be a whole number of levels (1 to 100), not {number}", span
            )
        return SpecSyntaxError(
            f"'{number}' is not a whole number: numbers in a .gait file are whole numbers "
            "such as 2 or 10",
            span,
        )
    code = f"U+{ord(char):04X}"
    if char in _LOOKALIKES:
        return SpecSyntaxError(
            f"unexpected character '{char}' ({code}); write '{_LOOKALIKES[char]}'", here
        )
    if not char.isascii() and char.isalnum():
        return SpecSyntaxError(
            f"'{char}' ({code}) cannot be part of a name: names use only the ASCII letters "
            "A-Z and a-z, the digits 0-9 and '_', and do not start with a digit",
            here,
        )
    shown = repr(char)[1:-1] if not char.isprintable() else char
    return SpecSyntaxError(
        f"unexpected character '{shown}': names use letters, digits and '_', "
        "comments start with '#'",
        here,
        _range_slip(char, pos, text),
    )


def _range_slip(char: str, pos: int, text: str) -> str | None:
    """``L1-L8`` (or ``L1 - L8``, ``L1:L8``) written for the range ``L1..L8``."""
    if char not in "-:" or pos < 0:
        return None
    before = re.search(r"([A-Za-z_]\w*?)(\d+)\s*$", text[max(0, pos - 40):pos])
    after = re.match(r"\s*([A-Za-z_]\w*?)(\d+)\b", text[pos + 1:pos + 41])
    if before is None or after is None or before.group(1) != after.group(1):
        return None
    first, last = before.group(1) + before.group(2), after.group(1) + after.group(2)
    return f"a range of names is written with two dots: {first}..{last}"


#: Statements of other tools or of plain English that a .gait file writes otherwise.
_SLIPS: dict[str, str] = {
    "goal": "visit {rest} infinitely often",
    "goals": "visit {rest} infinitely often",
    "reach": "visit {rest} infinitely often",
    "patrol": "visit {rest} infinitely often",
    "avoid": "guarantee always !({rest})",
    "never": "guarantee always !({rest})",
    "initial": "start {rest}",
    "init": "start {rest}",
    "leg": "legs {rest}",
}


def _statement_slip(tok: Token, text: str) -> str | None:
    """A hint for a statement written in another tool's words (``goal a, b``)."""
    word = str(tok)
    if tok.type != "NAME" or word.lower() not in _SLIPS or tok.line is None:
        return None
    line = source_lines(text)[tok.line - 1]
    column = (tok.column or 1) - 1
    if line[:column].strip():
        return None  # not at the start of a statement
    rest = line[column + len(word):].split("#")[0].strip() or "..."
    return f"write '{_SLIPS[word.lower()].format(rest=rest)}'"


def _doubled_operator(tok: Token, text: str, file: str) -> GaitcError | None:
    """``&&``, ``||`` or ``==`` from another language: lark stops at the second character."""
    start = tok.start_pos
    if str(tok) not in _DOUBLED or start is None or start < 1 or text[start - 1] != str(tok):
        return None
    line, column = tok.line or 1, (tok.column or 2) - 1
    return SpecSyntaxError(
        f"'{tok}{tok}' is not a .gait operator; write {_DOUBLED[str(tok)]}",
        Span(file, line, column, line, column + 1),
    )


def _dangling_name(err: UnexpectedToken, expected: set[str], file: str) -> GaitcError | None:
    """A name that lark read as the start of a transition ``a -> b`` (``moves wset``): it
    fails only at the next token, usually the next statement, so point at the name."""
    if {_describe_terminal(name) for name in expected} != {"'->'"}:
        return None
    stack = _value_stack(err)
    if len(stack) < 2 or not isinstance(stack[-1], Token) or stack[-1].type != "NAME":
        return None
    name, before = stack[-1], stack[-2]
    span = token_span(file, name)
    if isinstance(before, Token) and before.type == "MOVES":
        return SpecSyntaxError(
            f"'{name}' after 'moves' is not a direction; expected north, south, east or west, "
            "or region transitions such as 'a -> b'",
            span,
            _suggestion(str(name), list(keywords("direction"))),
        )
    return SpecSyntaxError(f"transition from '{name}' has no '->'; write '{name} -> REGION'", span)


def _syntax_error(err: UnexpectedInput, text: str, file: str) -> GaitcError:
    if isinstance(err, UnexpectedCharacters):
        here = Span(file, err.line, err.column, err.line, err.column)
        pos = err.pos_in_stream if err.pos_in_stream is not None else -1
        char = text[pos] if 0 <= pos < len(text) else "?"
        if char == '"':
            return SpecSyntaxError("unterminated string: add the closing '\"' on this line", here)
        return _bad_character(char, pos, text, here)
    if isinstance(err, UnexpectedToken):
        tok = err.token
        expected = set(err.accepts or err.expected or ())
        if tok.type == "$END":
            return SpecSyntaxError(
                f"unexpected end of file; expected {_describe_expected(expected)}",
                _end_span(text, file),
            )
        found = (
            _doubled_operator(tok, text, file)
            or _dangling_name(err, expected, file)
            or _mistyped_word(err, expected, file)
        )
        if found is not None:
            return found
        hint = _suggestion(str(tok), _keywords(expected)) if tok.type == "NAME" else None
        hint = _statement_slip(tok, text) or hint
        return SpecSyntaxError(
            f"unexpected {_describe_token(tok)}; expected {_describe_expected(expected)}",
            token_span(file, tok),
            hint,
        )
    if isinstance(err, UnexpectedEOF):
        expected = set(err.expected or ())
        return SpecSyntaxError(
            f"unexpected end of file; expected {_describe_expected(expected)}",
            _end_span(text, file),
        )
    return SpecSyntaxError(str(err).splitlines()[0], _end_span(text, file))


# ---------------------------------------------------------------- public API
def parse(text: str, file: str = "<string>") -> s.SpecFile:
    """Parse .gait source ``text`` (reported as ``file``) into a :class:`~syntax.SpecFile`.

    A byte-order mark at the start is skipped (columns count from the character after it).
    Raises :class:`SpecSyntaxError` or :class:`FormulaError` with a span on bad input.
    """
    text = without_bom(text)
    _check_brackets(text, file)
    try:
        tree = _lark().parse(text)
    except UnexpectedInput as err:
        raise _syntax_error(err, text, file) from None
    except FormulaError as err:  # from the lexer callback, which does not know the file
        span = None if err.span is None else replace(err.span, file=file)
        raise FormulaError(err.message, span) from None
    return build(tree, file)
