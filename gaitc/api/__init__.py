"""The facade: one module per stage of the pipeline, each a public function a notebook calls.

:mod:`gaitc` re-exports these names lazily; the command line (:mod:`gaitc.cli`) is a thin
layer over them.
"""
