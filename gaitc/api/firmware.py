"""The valve board's firmware (``gaitc firmware``), as the facade names it: :func:`build`
compiles the board's C sources into an :class:`Image` (and the simavr harness), and
:func:`simulator_argv` is the command that runs the image in the harness, in real time
(:mod:`gaitc.hw.firmware`). Light to import: it loads neither the solver nor the parser.
"""

from __future__ import annotations

from gaitc.hw.firmware import FirmwareError, Image, build, simulator_argv

__all__ = ["FirmwareError", "Image", "build", "simulator_argv"]
