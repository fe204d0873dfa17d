"""Odd output targets for the commands that write files, and the codegen command's options.

Two input kinds, both confined to a fuzz folder (:class:`Area`) that is emptied and set up
again before each case.  ``target``: a file name, a mutant of one of :data:`NAMES` (put
under the folder by :func:`inside`: never outside it) or one of :data:`SPECIALS`, given to
every command of :func:`target_commands` that writes a file or a folder.  ``codegen``: the
words after ``codegen SPEC CONTROLLER``, a mutant of one of :data:`OPTIONS` (target names,
``--no-monitor``, ``--json``, ``-o``), every word that argparse could take for a path put
under the folder first (:func:`codegen_words`).  The codegen options are a kind of their
own rather than folded into ``target``: they are a list of words, not one name, and their
``-o`` folder is a good one as often as the mutation leaves it so.

Oracle, besides :func:`fuzz_oracle.run_command`'s (no exit 70, no traceback, within the
limit): a file outside the fuzz folder, which links inside it point to, keeps its bytes and
no file appears beside it (``escaped``).  A command line cannot hold a NUL, so a mutant's
NUL bytes are dropped before its name reaches a command.
"""

from __future__ import annotations

import os
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

from fuzz_cases import HAZARD_SPEC, PATROL, Fixtures
from fuzz_oracle import Verdict, run_command

# Seeds of the 'target' kind: names relative to the fuzz folder.  Some name what the
# folder holds already (a file, a folder, a dangling link), so that mutants meet them.
NAMES: tuple[tuple[str, bytes], ...] = (
    ("plain", b"spec.structuredslugs"),
    ("picture", b"spec.dot"),
    ("run", b"patrol.run.jsonl"),
    ("unicode", "ünï cödé.dot".encode()),
    ("in-a-folder", b"folder/new.dot"),
    ("nested", b"gen/out/controller.json"),
    ("file", b"file"),
    ("hidden", b".x.json"),
    ("deep", b"d/" * 40 + b"spec.dot"),
    ("dangling", b"dangling"),
)
# The fixed targets: (name, path); a relative path is taken in the fuzz folder.
SPECIALS: tuple[tuple[str, str], ...] = (
    ("proc-self", "/proc/self"),
    ("dev-full", "/dev/full"),
    ("through-a-file", "file/x"),
    ("name-300", "n" * 300),
    ("newline", "two\nlines.dot"),
    ("folder", "folder"),
    ("dangling-link", "dangling"),
    ("link-outside", "outside"),
    ("through-link-outside", "outside/x"),
    ("folder-with-link-outside", "linked"),
)
SPECIAL = "special:"  # the seed name of a special target: 'special:' + its name
VICTIM = b"a file outside the fuzz folder: no command may change it\n"
# Seeds of the 'codegen' kind: the words after 'codegen SPEC CONTROLLER'.
OPTIONS: tuple[tuple[str, bytes], ...] = (
    ("c", b"--target c -o gen"),
    ("avr", b"--target avr --no-monitor -o board"),
    ("json", b"--json --target=c --out gen/nested/deeper --no-monitor"),
    ("short", b"-ogen --target c --json"),
    ("existing", b"--target c --out folder"),
)


@dataclass(frozen=True)
class Area:
    """The fuzz folder (``folder``) and a file outside it (``victim``) that links inside
    the folder point to."""

    folder: Path
    victim: Path

    @classmethod
    def of(cls, fx: Fixtures) -> Area:
        """The area of a fixtures folder: ``out/targets``, the victim in a folder beside
        the fixtures' own (made by the same owner, so also a temporary one)."""
        outside = fx.folder.parent / f"{fx.folder.name}-outside"
        outside.mkdir(exist_ok=True)
        return cls(fx.out / "targets", outside / "victim.txt")

    def reset(self) -> None:
        """An empty fuzz folder, then: a file 'file', a folder 'folder', a link 'dangling'
        to a missing file inside, a link 'outside' to the victim, and a folder 'linked'
        whose 'patrol_2x2.gait' (an example's name) is a link to the victim."""
        if self.folder.is_symlink():
            self.folder.unlink()
        elif self.folder.exists():
            shutil.rmtree(self.folder)  # removes links, never follows them
        self.folder.mkdir(parents=True)
        (self.folder / "file").write_bytes(b"a plain file\n")
        (self.folder / "folder").mkdir()
        (self.folder / "dangling").symlink_to(self.folder / "made-through-the-link.dot")
        (self.folder / "outside").symlink_to(self.victim)
        (self.folder / "linked").mkdir()
        (self.folder / "linked" / "patrol_2x2.gait").symlink_to(self.victim)
        for other in self.victim.parent.iterdir():
            if other.is_dir() and not other.is_symlink():
                shutil.rmtree(other)
            elif other != self.victim:
                other.unlink()
        self.victim.write_bytes(VICTIM)

    def escapes(self) -> list[str]:
        """Property (d): the victim as it was, and nothing new beside it."""
        problems = []
        if not self.victim.is_file() or self.victim.is_symlink():
            problems.append(f"escaped: {self.victim} is no longer a plain file")
        elif self.victim.read_bytes() != VICTIM:
            problems.append(f"escaped: {self.victim} was written through a link "
                            f"({self.victim.read_bytes()[:60]!r})")
        others = sorted(p.name for p in self.victim.parent.iterdir() if p != self.victim)
        if others:
            problems.append(f"escaped: {others[:3]} made beside {self.victim}")
        return problems


def inside(area: Path, data: bytes) -> Path:
    """``data`` as a path under ``area`` that stays there: its NULs dropped (a command
    line cannot hold one), its '..', '.' and empty parts dropped (so no absolute path), and,
    should it resolve outside (through a link), put under a plain folder 'refused'."""
    text = os.fsdecode(data.replace(b"\0", b""))
    parts = [p for p in text.split("/") if p not in ("", ".", "..")]
    path = area.joinpath(*parts) if parts else area / "unnamed"
    root = os.path.realpath(area)
    if os.path.commonpath([os.path.realpath(path), root]) != root:
        path = area / "refused" / "_".join(parts)
    if os.path.commonpath([os.path.realpath(path), root]) != root:
        raise AssertionError(f"the fuzz target {path!r} is outside {area}")
    return path


def special_path(area: Path, name: str) -> str:
    """The path of the special target ``name`` (see :data:`SPECIALS`)."""
    path = dict(SPECIALS)[name]
    return path if path.startswith("/") else str(area / path)


@dataclass(frozen=True)
class Writer:
    """A command that writes ``target``; ``follows`` when a link given as the output file
    is written through (the documented behaviour of ``write_atomically``)."""

    name: str
    argv: list[str]
    follows: bool


def target_commands(target: str, fx: Fixtures) -> list[Writer]:
    """Every command that writes to a path, with ``target`` as that path."""
    patrol = str(PATROL)
    return [
        Writer("compile -o", ["compile", patrol, "-o", target], True),
        Writer("synth -o", ["synth", patrol, "-o", target], True),
        Writer("render spec -o", ["render", "spec", patrol, "-o", target], True),
        Writer("simulate --out", ["simulate", patrol, str(fx.patrol_controller), "--env",
                                  "random", "--seed", "1", "--steps", "5", "--quiet",
                                  "--out", target], True),
        Writer("codegen -o", ["codegen", str(HAZARD_SPEC), str(fx.hazard_compact),
                              "--target", "c", "-o", target], False),
        Writer("examples", ["examples", target], False),
        Writer("examples --force", ["examples", "--force", target], False),
    ]


def _judged(name: str, argv: list[str], area: Area, limit: float) -> Verdict:
    """One run judged by :func:`run_command` and property (d); an argparse exit (--help)
    is the command's answer, not an escape from ``main``."""
    try:
        verdict = run_command(name, argv, {}, limit)
    except SystemExit as done:
        code = done.code if isinstance(done.code, int) else 1
        verdict = Verdict(name, code, 0.0)
    verdict.problems.extend(area.escapes())
    return verdict


def run_target(seed: str, data: bytes, fx: Fixtures, limit: float) -> list[Verdict]:
    """Every writing command on one target: the special one ``seed`` names, or ``data``
    under the fuzz folder.  The link to the victim is given as the output file only to
    the commands that must not write through it (``follows`` is false); the others write
    through a link by design (tests/cli/test_files.py), so they get the paths through it."""
    area = Area.of(fx)
    area.reset()
    special = seed.removeprefix(SPECIAL) if seed.startswith(SPECIAL) else None
    target = (special_path(area.folder, special) if special is not None
              else str(inside(area.folder, data)))
    verdicts = []
    for writer in target_commands(target, fx):
        if writer.follows and special == "link-outside":
            continue
        verdicts.append(_judged(writer.name, writer.argv, area, limit))
    return verdicts


def _sanitized(word: str, area: Path) -> str:
    return str(inside(area, os.fsencode(word)))


def codegen_words(data: bytes, area: Path) -> list[str]:
    """The option words of ``data`` (split at ASCII white space), each that argparse
    could take for a path put under ``area``: words that do not start with '-', values of
    '--name=value' (but --target's), what follows '-o' in a word, and words like '-1'
    that argparse takes for a value.  The word after a --target (or its abbreviation) is
    kept, being the target's name."""
    words: list[str] = []
    target_next = False
    for raw in data.replace(b"\0", b"").split():
        word = os.fsdecode(raw)
        if (target_next and not word.startswith("-")) or word == "--":
            words.append(word)  # a target's name, or the end of the options
        elif word.startswith("--"):
            name, equals, value = word.partition("=")
            is_target = len(name) >= 3 and "--target".startswith(name)
            words.append(word if not equals or is_target
                         else f"{name}={_sanitized(value, area)}")
            target_next = is_target and not equals
            continue
        elif re.fullmatch(r"-[A-Za-z]+", word, re.ASCII):
            head, o, rest = word.partition("o")
            words.append(head + o + (_sanitized(rest, area) if rest else ""))
        else:
            words.append(_sanitized(word, area))
        target_next = False
    return words


def run_codegen(data: bytes, fx: Fixtures, limit: float) -> list[Verdict]:
    """``codegen`` of the good hazard compact controller with the option words ``data``."""
    area = Area.of(fx)
    area.reset()
    argv = ["codegen", str(HAZARD_SPEC), str(fx.hazard_compact),
            *codegen_words(data, area.folder)]
    return [_judged("codegen", argv, area, limit)]
