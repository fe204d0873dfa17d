"""Hardware layer: drive a synthesized controller's gaits on a valve board (docs/hardware.md).

Modules: ``backend`` (the Backend interface, sensor readings, errors), ``simulated`` (the
default, a simulated robot), ``serial_board`` (a valve board over a serial line), ``driver``
(the controller loop).
"""
