"""gr1: the logic layer, a GR(1) specification as data.

The formula IR (:mod:`gr1.formula`, an immutable DAG with spans, walked by the one
iterative traversal of :mod:`gr1.traversal`, so depth never matters), its evaluation on
valuations, the specification IR with its six named sections (:mod:`gr1.spec`),
SLUGS-compatible bit-blasting of integers (:mod:`gr1.bitblast`, with the bit names of
:mod:`gr1.bits`) and explicit automata with their JSON file format (:mod:`gr1.controller`).
It imports only :mod:`diagnostics`; every other package builds on it.
"""
