"""slugs_bridge: everything that touches SLUGS (Ehlers & Raman, CAV 2016).

Its two file formats, readers and writers (:mod:`slugs_bridge.slugsin`,
:mod:`slugs_bridge.structured` with :mod:`slugs_bridge.infix`, the shared section layout of
:mod:`slugs_bridge.sections`, the reader chosen by suffix in :mod:`slugs_bridge.formats`),
the readable LTL text written in SLUGS's infix operators (:mod:`slugs_bridge.ltltext`) and
the runner for the ``slugs`` binary (:mod:`slugs_bridge.runner`). Imports only :mod:`gr1`
and :mod:`diagnostics`: never the embedded solver nor the .gait front end.
"""
