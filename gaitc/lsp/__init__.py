"""Editor support: the language server of ``gaitc lsp`` (pygls).

:mod:`gaitc.lsp.analysis` runs the compiler on a document, :mod:`gaitc.lsp.index` finds
where each name is declared and used, :mod:`gaitc.lsp.hover`,
:mod:`gaitc.lsp.completion` and :mod:`gaitc.lsp.actions` answer the editor's questions,
:mod:`gaitc.lsp.positions` converts positions, and :mod:`gaitc.lsp.server` wires them to
the protocol.
"""
