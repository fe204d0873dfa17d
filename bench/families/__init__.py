"""Generators of the GR(1) benchmark families of bench/bench_families.py, one module each.

``amba``: the AMBA AHB arbiter for N masters (structuredslugs).
"""
