"""The BDD library, CUDD through ``dd.cudd``, imported in one place.

``dd`` imports networkx, if it is installed, for an export of BDDs as graphs that gaitc
never uses; networkx takes about 80 ms to import, two thirds of ``dd.cudd``'s import and a
third of a small ``gaitc check``.  So ``dd`` is imported here with networkx marked as
missing (a ``None`` entry in :data:`sys.modules` makes ``import networkx`` raise
ImportError, which dd handles by leaving the export out), and the entry is taken away at
once, so that the modules that do use networkx import it as usual.  When networkx is
already loaded, dd gets it.
"""

from __future__ import annotations

import sys

if "networkx" in sys.modules:
    import dd.cudd as cudd
else:
    sys.modules["networkx"] = None  # type: ignore[assignment]
    try:
        import dd.cudd as cudd
    finally:
        del sys.modules["networkx"]

__all__ = ["cudd"]
