"""Write the command-line reference (docs/reference/cli.md) from the argument parser itself.

``python tools/cli_reference.py`` walks ``gaitc.cli.build_parser()``: every command and
subcommand, in the order ``gaitc --help`` lists them, with the help text argparse prints
(80 columns) and the exit codes of :mod:`gaitc.cli.exitcodes`. The page cannot drift from
the code: ``tests/cli/test_docs.py`` regenerates it and fails on a difference. ``--check``
compares instead of writing.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
PAGE = ROOT / "docs" / "reference" / "cli.md"


def _subparsers(parser: argparse.ArgumentParser) -> list[tuple[str, argparse.ArgumentParser]]:
    found: list[tuple[str, argparse.ArgumentParser]] = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            seen: set[int] = set()
            for name, sub in action.choices.items():
                if id(sub) not in seen:
                    seen.add(id(sub))
                    found.append((name, sub))
    return found


def _section(words: list[str], parser: argparse.ArgumentParser, depth: int) -> list[str]:
    title = " ".join(words)
    lines = [f"{'#' * depth} `{title}`", "", "```text", parser.format_help().rstrip(), "```", ""]
    for name, sub in _subparsers(parser):
        lines += _section([*words, name], sub, depth + 1)
    return lines


def page() -> str:
    """The whole reference page."""
    os.environ["COLUMNS"] = "80"
    from gaitc.cli import build_parser
    from gaitc.cli.exitcodes import MEANINGS

    parser = build_parser()
    lines = ["# Command-line reference", "",
             "Generated from gaitc's argument parser by `tools/cli_reference.py`; every",
             "command prints the same text with `--help`.", "",
             "## Exit codes", "", "| code | meaning |", "|---|---|"]
    lines += [f"| {int(code)} | {meaning} |" for code, meaning in MEANINGS.items()]
    lines += ["", "## `gaitc`", "", "```text", parser.format_help().rstrip(), "```", ""]
    for name, sub in _subparsers(parser):
        lines += _section(["gaitc", name], sub, 2)
    return "\n".join(lines).rstrip() + "\n"


def main() -> int:
    check = "--check" in sys.argv[1:]
    text = page()
    if check:
        if not PAGE.exists() or PAGE.read_text(encoding="utf-8") != text:
            print("docs/reference/cli.md is out of date: run tools/cli_reference.py",
                  file=sys.stderr)
            return 1
        return 0
    PAGE.parent.mkdir(parents=True, exist_ok=True)
    PAGE.write_text(text, encoding="utf-8")
    print(f"wrote {PAGE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
