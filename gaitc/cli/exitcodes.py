"""The exit codes of every gaitc command, defined once with what each means.

Commands print their own ``exit codes:`` block in ``--help`` with :func:`exit_code_help`,
which takes the general meaning from :data:`MEANINGS` unless the command says more.
"""

from __future__ import annotations

import textwrap
from collections.abc import Mapping
from enum import IntEnum


class ExitCode(IntEnum):
    """What ``gaitc`` returns to the shell."""

    OK = 0
    USER = 1
    USAGE = 2
    UNREALIZABLE = 3
    SOLVER = 4
    WARNING = 5
    INTERNAL = 70
    INTERRUPTED = 130
    TERMINATED = 143


MEANINGS: Mapping[ExitCode, str] = {
    ExitCode.OK: "success; for check and synth: realizable",
    ExitCode.USER: "an error in an input file (syntax, names, malformed controller), or a "
    "controller that fails verification",
    ExitCode.USAGE: "the command line is wrong (an unknown option, a missing file)",
    ExitCode.UNREALIZABLE: "unrealizable (check, synth; counter: realizable)",
    ExitCode.SOLVER: "the solver could not finish (timeout, memory limit, SLUGS failure)",
    ExitCode.WARNING: "explain, lint --deep: realizable, with a sanity warning",
    ExitCode.INTERNAL: "a bug in gaitc (GAITC_DEBUG=1 prints the traceback)",
    ExitCode.INTERRUPTED: "interrupted (Ctrl-C)",
    ExitCode.TERMINATED: "terminated (SIGTERM); no file is left half-written",
}

#: The codes every command's help lists; 70, 130 and 143 are described once, in ``gaitc --help``.
_LISTED = (ExitCode.OK, ExitCode.USER, ExitCode.USAGE, ExitCode.UNREALIZABLE, ExitCode.SOLVER)


def exit_code_help(meanings: Mapping[ExitCode, str] | None = None,
                   codes: tuple[ExitCode, ...] = _LISTED) -> str:
    """An ``exit codes:`` block for ``--help``: ``meanings`` override the general ones
    (a command's own block says plain "success" for 0 unless it says more; the list of every
    code, ``gaitc --help``, keeps what 0 means for check and synth)."""
    lines = ["exit codes:"]
    own = codes != tuple(ExitCode)
    for code in codes:
        general = "success" if own and code is ExitCode.OK else MEANINGS[code]
        text = (meanings or {}).get(code, general)
        lines.extend(textwrap.wrap(text, 88, initial_indent=f"  {int(code):<2} ",
                                   subsequent_indent=" " * 5))
    return "\n".join(lines) + "\n"
