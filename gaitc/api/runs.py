"""Runs, as the facade names them: a simulated, driven, played or explained run, its files
and its printed table (:mod:`gaitc.sim.run`, :mod:`gaitc.sim.terminal`).

A run is saved as ``.jsonl`` (read back by :func:`read_jsonl`, replayed by ``--env scripted
RUN.jsonl``, drawn by ``gaitc render map --run``) or ``.csv`` (a table);
:func:`run_format` says which a file name asks for; a run has at most :data:`MAX_STEPS`
steps (:func:`checked_steps`).
"""

from __future__ import annotations

from gaitc.sim.run import (
    MAX_STEPS,
    Run,
    Step,
    Summary,
    checked_steps,
    read_jsonl,
    run_format,
    save_run,
)
from gaitc.sim.terminal import step_table, summary_text, surprises_text, use_colour

__all__ = ["MAX_STEPS", "Run", "Step", "Summary", "checked_steps", "read_jsonl", "run_format",
           "save_run", "step_table", "summary_text", "surprises_text", "use_colour"]
