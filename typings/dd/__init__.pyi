# Stubs for the part of `dd` that gaitc uses: only its CUDD binding, `dd.cudd`, a compiled
# Cython module that ships no stubs of its own. The pure-Python rest of `dd` is not used.
