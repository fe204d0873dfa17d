"""slugs_bridge: everything that touches SLUGS (Ehlers & Raman, CAV 2016).

Its two file formats, readers and writers (:mod:`slugs_bridge.slugsin`,
:mod:`slugs_bridge.structured` with :mod:`slugs_bridge.infix` and
:mod:`slugs_bridge.infixtext`, the shared section layout of :mod:`slugs_bridge.sections`,
the reader chosen by suffix in :mod:`slugs_bridge.formats`), the readable LTL text written
in SLUGS's infix operators and read back (:mod:`slugs_bridge.ltltext`), the renaming of
names a format cannot carry (:mod:`slugs_bridge.names`), what slugsin keeps of a formula
(:mod:`slugs_bridge.prefixform`) and the runner for the ``slugs`` binary
(:mod:`slugs_bridge.runner`). Imports only :mod:`gaitc.ir` and :mod:`gaitc.diagnostics`: never the
embedded solver nor the .gait front end.
"""
