"""Regenerate the tutorial's outputs and pictures (docs/tutorial/out/) from the current code.

``python tools/tutorial.py`` runs every command of docs/tutorial/index.md, in order, in a
scratch folder holding the tutorial's robot (docs/tutorial/lab8.gait) and the radial robot
file, exactly as a reader types them, and writes each one's terminal output (the command
line, then what it printed, then its exit code when not 0) and each picture it draws.
Wall-clock times in the output are written as ``… s``, so the files change only when the
code's answers change; ``tests/cli/test_docs.py`` regenerates them and fails on any drift.
``--check`` compares instead of writing and exits 1 on a difference.
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TUTORIAL = ROOT / "docs" / "tutorial"
OUT = TUTORIAL / "out"
SPEC = TUTORIAL / "lab8.gait"
#: The first draft the reader writes: only the store is a cache.
DRAFT_EDIT = ("cache store, lab", "cache store")

#: (output name, command line as the reader types it in the scratch folder). A name ending
#: in ``.svg`` names a picture the command writes with ``-o``.
STEPS: tuple[tuple[str, str], ...] = (
    ("01-lint", "gaitc lint draft.gait"),
    ("02-check-draft", "gaitc check draft.gait"),
    ("03-explain", "gaitc explain draft.gait"),
    ("04-check", "gaitc check lab8.gait"),
    ("05-synth", "gaitc synth lab8.gait -o lab8.json"),
    ("06-simulate", "gaitc simulate lab8.gait lab8.json --env adversarial --steps 12 "
                    "--out run.jsonl"),
    ("07-render", "gaitc render map lab8.gait --run run.jsonl -o map.svg"),
    ("08-resilience", "gaitc resilience lab8.gait"),
    ("09-gaits", "gaitc gaits radial8.yaml --direction +y"),
    ("10-drive", "gaitc drive lab8.gait lab8.json --backend sim --steps 6"),
)
PICTURES = ("map.svg",)
#: Wall-clock times: "(0.04 s)", "(67 solver calls, 1.96 s)", "parametric games: 0.05 s".
_SECONDS = re.compile(r"(?<=[(,:] )\d+\.\d+ s(?=\)|;|$)|(?<=\()\d+\.\d+ s(?=[);])", re.M)


def scratch_folder() -> Path:
    """A new folder holding the tutorial's files, as the reader has them."""
    folder = Path(tempfile.mkdtemp(prefix="gaitc-tutorial-"))
    text = SPEC.read_text(encoding="utf-8")
    shutil.copy(SPEC, folder / "lab8.gait")
    draft = text.replace(*DRAFT_EDIT).replace(
        "Spare parts wait in the store and in the lab", "Spare parts wait in the store")
    (folder / "draft.gait").write_text(draft, encoding="utf-8")
    shutil.copy(TUTORIAL / "radial8.yaml", folder / "radial8.yaml")
    return folder


def run(command: str, folder: Path) -> str:
    """The terminal transcript of ``command`` run in ``folder``."""
    argv = shlex.split(command)
    gaitc = [sys.executable, "-m", "gaitc"]
    env = dict(os.environ, COLUMNS="100", NO_COLOR="1", PYTHONPATH=str(ROOT))
    done = subprocess.run([*gaitc, *argv[1:]], cwd=folder, capture_output=True, text=True,
                          env=env, timeout=600)
    body = (done.stdout + done.stderr).rstrip("\n")
    body = _SECONDS.sub("… s", body)
    tail = f"\n[exit {done.returncode}]" if done.returncode else ""
    return f"$ {command}\n{body}{tail}\n"


def outputs() -> dict[str, str]:
    """Every output file's name and contents, made fresh."""
    folder = scratch_folder()
    try:
        found = {f"{name}.txt": run(command, folder) for name, command in STEPS}
        for picture in PICTURES:
            found[picture] = (folder / picture).read_text(encoding="utf-8")
        found["draft.gait"] = (folder / "draft.gait").read_text(encoding="utf-8")
        return found
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare; do not write")
    args = parser.parse_args()
    fresh = outputs()
    if args.check:
        stale = [name for name, text in fresh.items()
                 if not (OUT / name).exists() or (OUT / name).read_text() != text]
        for name in stale:
            print(f"docs/tutorial/out/{name} is out of date", file=sys.stderr)
        return 1 if stale else 0
    OUT.mkdir(parents=True, exist_ok=True)
    for name, text in fresh.items():
        (OUT / name).write_text(text, encoding="utf-8")
    print(f"wrote {len(fresh)} files to {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
