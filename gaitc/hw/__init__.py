"""Hardware layer: drive a synthesized controller's gaits on a valve board (docs/hardware.md).

Modules: ``backend`` (the Backend interface, sensor readings, errors), ``simulated`` (the
default, a simulated robot), ``serial_board`` (a valve board over a serial line, protocol
v2), ``driver`` (the controller loop), ``sensing`` (actuator health from the waveguides,
thesis section 3.4.2), ``localisation`` (regions from an external tracker's poses),
``firmware`` (building the valve-board firmware and running it in simavr).
"""
