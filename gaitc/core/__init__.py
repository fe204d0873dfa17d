"""The core objects every stage passes around: the spec and the named modes.

This layer sits just above the front end (:mod:`ltlcompiler`) and below everything that
works on a compiled spec (compact controllers, simulation, analysis, play, code
generation).  :mod:`gaitc.core.modes` defines each choice a command makes once, as an
enumeration (:class:`~gaitc.diagnostics.choices.Choice`); :mod:`gaitc.core.spec` holds
:class:`~gaitc.core.spec.Spec`, the compiled specification with its domain model, encoding
and source, read from any supported format; :mod:`gaitc.core.vocabulary` the fields a
compact controller of a spec decides in; :mod:`gaitc.core.presentation` the small HTML
tables results show in a notebook.
"""
