"""Writing, compiling and sizing generated controllers for a host (``c``) or the board (``avr``).

``c``: ``gaitc_controller.h`` and ``gaitc_controller.c`` plus ``gaitc-run``, the controller
behind a line protocol on standard input (``host/driver.c``; ``--names`` for the spec's
names instead of value indices), for a Raspberry Pi class host and for the tests that
compare it with the Python runner.  No size limit.

``avr``: the same two files compiled into the valve-board firmware (``gaitboard.c`` with
``GAITC_CONTROLLER``), so the board decides on its own.  The image's flash (text + data) and
RAM (data + bss) are measured with ``avr-size`` and compared with the ATmega328P's 32 KB and
2 KB; a controller that does not fit is refused with the numbers, and nothing is left in the
output folder.
"""

from __future__ import annotations

import json
import re
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Final

from gaitc.codegen.board import BoardTables, board_header
from gaitc.codegen.emitter import header, source
from gaitc.codegen.recovery import recovery_sizes
from gaitc.codegen.tables import NOT_INPUT, Tables, flatten
from gaitc.compact.controller import CompactController
from gaitc.compact.recovery import RecoveringController
from gaitc.diagnostics import Span
from gaitc.diagnostics.choices import Choice
from gaitc.diagnostics.files import make_folder, write_atomically
from gaitc.hw.firmware import (
    AVR_FLAGS,
    HOST_FLAGS,
    SOURCES,
    FirmwareError,
    missing_tools,
    run_tool,
)

HOST = Path(__file__).resolve().parent / "host"
#: The ATmega328P: 32 KB of flash (the bootloader's 512 bytes kept free) and 2 KB of RAM, of
#: which the stack needs some: a build whose static RAM passes RAM_LIMIT is refused.
FLASH_LIMIT: Final = 32 * 1024 - 512
RAM_LIMIT: Final = 2048 - 256
HINT_TOO_BIG: Final = ("use --target c for a larger host, --no-monitor to leave the assumption "
                       "monitor out, or simplify the task (fewer regions, gaits or levels)")


class Target(Choice):
    """Where generated code runs."""

    C = "c"
    AVR = "avr"


@dataclass(frozen=True)
class Built:
    """What codegen wrote: the sources, the program or image, and its sizes."""

    target: Target
    files: tuple[Path, ...]
    program: Path | None  # gaitc-run (c) or gaitboard.elf (avr)
    table_bytes: int
    flash: int | None = None
    ram: int | None = None
    #: with recovery tables (codegen --recover): the bytes of each part, and the surprises
    #: the controller can only stop on, in words
    recovery: tuple[str, ...] = ()
    stops: tuple[str, ...] = ()
    recovering: bool = False

    @property
    def hint(self) -> str | None:
        """How to run a host build's ``gaitc-run`` in the spec's names; None for a board
        image or when gcc was missing."""
        if self.target != Target.C or self.program is None:
            return None
        return (f"'{self.program} --names' answers in the spec's names (region=r3 "
                "gait=north_a L1=2 ... goal=1) and reads them (s L1=2 ..., or the names "
                "alone); without --names it reads and prints value indices (docs/compact.md)")

    def summary(self) -> str:
        """The sizes, then for a host build a ``hint:`` line on running it with names."""
        text = f"{self.table_bytes} bytes of tables"
        if self.flash is not None and self.ram is not None:
            text += (f"; firmware image {self.flash} of {FLASH_LIMIT} bytes of flash, "
                     f"{self.ram} of {RAM_LIMIT} bytes of static RAM")
        if self.recovering:
            text += "\nrecovery tables: " + "; ".join(self.recovery)
        for words in self.stops:
            text += f"\nsurprise: {words}"
        if self.hint is not None:
            text += f"\nhint: {self.hint}"
        return text

    def to_json(self) -> dict[str, Any]:
        return {"target": str(self.target), "files": [str(f) for f in self.files],
                "program": None if self.program is None else str(self.program),
                "table_bytes": self.table_bytes, "flash": self.flash, "ram": self.ram,
                "flash_limit": FLASH_LIMIT if self.target == Target.AVR else None,
                "ram_limit": RAM_LIMIT if self.target == Target.AVR else None,
                "recovery": {"included": self.recovering, "tables": list(self.recovery),
                             "stops": list(self.stops)},
                "hint": self.hint}


def _where(file: str) -> Span:
    return Span(file or "<codegen>", 1, 1)


def write_sources(ctrl: CompactController, folder: Path, tables: Tables | None = None,
                  recovery: RecoveringController | None = None) -> tuple[Path, Path]:
    """``gaitc_controller.h`` and ``.c`` in ``folder``, each written whole or not at all
    (with ``recovery``, whose base is ``ctrl``, its tables and surprise step too)."""
    make_folder(folder)
    h, c = folder / "gaitc_controller.h", folder / "gaitc_controller.c"
    write_atomically(h, header(ctrl, recovery))
    write_atomically(c, source(ctrl, tables, recovery))
    return h, c


def sizes(elf: Path) -> tuple[int, int]:
    """Flash (text + data) and static RAM (data + bss) of an AVR image, by avr-size."""
    out = run_tool(["avr-size", "-A", str(elf)], "avr-size")
    section: dict[str, int] = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 2 and parts[0].startswith(".") and parts[1].isdigit():
            section[parts[0]] = int(parts[1])
    text, data, bss = (section.get(s, 0) for s in (".text", ".data", ".bss"))
    return text + data, data + bss


def build(ctrl: CompactController, out_dir: str | Path, target: Target | str,
          file: str = "", board: BoardTables | None = None,
          recovery: Recovery | None = None) -> Built:
    """Generate and compile ``ctrl`` for ``target`` into ``out_dir`` (see the module text).
    Compiled in a scratch folder first: a refused or failed build leaves ``out_dir`` as it
    was.  With ``board`` (avr), the firmware also runs the task on its own
    (:mod:`gaitc.codegen.board`); with ``recovery`` (whose controller's base is ``ctrl``),
    the tables and step of :mod:`gaitc.codegen.recovery` are added."""
    chosen = Target.parse(str(target), "--target")
    rc = None if recovery is None else recovery.controller
    tables = flatten(ctrl, () if rc is None else rc.extra_roots)
    out = Path(out_dir)
    made = _made(recovery)
    with tempfile.TemporaryDirectory(prefix="gaitc-codegen-") as scratch:
        work = Path(scratch)
        h, c = write_sources(ctrl, work, tables, rc)
        if chosen == Target.C:
            program: Path | None = None
            if shutil.which("gcc") is not None:
                program = work / "gaitc-run"
                # the input fields' order, so that gaitc-run --names reads names too
                order = [f for _, f in sorted((place, f) for f, place
                                              in enumerate(tables.input_pos)
                                              if place != NOT_INPUT)]
                fields = "{" + ",".join(str(f) for f in order or [0]) + "}"
                run_tool(["gcc", *HOST_FLAGS, "-DGAITC_DUMP", "-DGAITC_NAMES",
                          f"-DGAITC_INPUT_FIELDS={fields}", f"-I{work}", "-o", str(program),
                          str(c), str(HOST / "driver.c")], "gcc gaitc_controller.c")
            files, built = _publish(out, [h, c], program)
            return Built(chosen, files, built, tables.bytes, **made)
        need = missing_tools(simulator=False)
        if need:
            raise FirmwareError(f"cannot build the board's firmware: missing {', '.join(need)}",
                                _where(file), "apt-get install gcc-avr avr-libc "
                                "(scripts/setup.sh does it)")
        if tables.bytes > FLASH_LIMIT:  # the compiler would refuse arrays this large
            raise FirmwareError(
                f"the controller does not fit on the ATmega328P: its tables alone are "
                f"{tables.bytes} bytes, more than the {FLASH_LIMIT} bytes of flash",
                _where(file), HINT_TOO_BIG)
        elf = work / "gaitboard.elf"
        defines = ["-DGAITC_CONTROLLER"]
        extra: list[Path] = []
        if board is not None:
            extra.append(work / "gaitc_board.h")
            write_atomically(extra[0], board_header(board))
            defines.append("-DGAITC_BOARD")
        try:
            run_tool(["avr-gcc", *AVR_FLAGS, *defines, f"-I{work}", "-o", str(elf),
                  str(SOURCES / "gaitboard.c"), str(c)], "avr-gcc gaitboard.c with the controller")
        except FirmwareError as err:
            over = re.search(r"region .(text|data). overflowed by (\d+) bytes", err.message)
            if over is None:
                raise
            raise FirmwareError(
                f"the controller does not fit on the ATmega328P: the firmware overflows its "
                f"{'flash' if over.group(1) == 'text' else 'RAM'} by {over.group(2)} bytes; "
                f"its tables alone are {tables.bytes} bytes", _where(file),
                HINT_TOO_BIG) from None
        flash, ram = sizes(elf)
        if flash > FLASH_LIMIT or ram > RAM_LIMIT:
            raise FirmwareError(
                f"the controller does not fit on the ATmega328P: the firmware would take "
                f"{flash} bytes of flash (limit {FLASH_LIMIT}) and {ram} bytes of static RAM "
                f"(limit {RAM_LIMIT}); its tables alone are {tables.bytes} bytes",
                _where(file), HINT_TOO_BIG)
        hexfile = work / "gaitboard.hex"
        run_tool(["avr-objcopy", "-O", "ihex", "-R", ".eeprom", str(elf), str(hexfile)],
             "avr-objcopy gaitboard.elf")
        files, built = _publish(out, [h, c, *extra, hexfile], elf)
        return Built(chosen, files, built, tables.bytes, flash, ram, **made)


@dataclass(frozen=True)
class Recovery:
    """What ``build`` adds for surprises: the recovering controller (None: none fits, every
    surprise stops) and the surprises it can only stop on, in words."""

    controller: RecoveringController | None
    stops: tuple[str, ...] = ()


def _made(recovery: Recovery | None) -> dict[str, Any]:
    """The recovery fields of :class:`Built`."""
    if recovery is None:
        return {}
    rc = recovery.controller
    if rc is None:
        return {"stops": recovery.stops}

    return {"recovery": tuple(recovery_sizes(rc).lines()), "stops": recovery.stops,
            "recovering": True}


def _copy(path: Path, out: Path) -> Path:
    """``path`` into ``out`` whole or not at all, its mode kept (a program stays runnable)."""
    target, tmp = out / path.name, out / f".{path.name}.part"
    shutil.copy2(path, tmp)
    tmp.replace(target)
    return target


def _publish(out: Path, files: list[Path], program: Path | None
             ) -> tuple[tuple[Path, ...], Path | None]:
    """The built ``files`` and ``program`` copied from the scratch folder into ``out``."""
    make_folder(out)
    return (tuple(_copy(f, out) for f in files),
            None if program is None else _copy(program, out))


def read_dump(text: str) -> dict[str, list[int]]:
    """The tables a compiled ``gaitc-run`` prints for ``d``."""
    data = json.loads(text)
    return {k: [int(v) for v in values] for k, values in data.items()}
