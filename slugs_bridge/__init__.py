"""slugs_bridge: the GR(1) IR, SLUGS's file formats, the embedded solver and the SLUGS runner.

This package never imports :mod:`ltlcompiler`; the .gait front end depends on it, not
the other way round.
"""
