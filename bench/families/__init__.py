"""Generators of the GR(1) benchmark families of bench/bench_families.py, one module each.

``amba``: the AMBA AHB arbiter for N masters (structuredslugs); ``thesis``: robot A scaled to
any grid; ``hazard_grid``: N x N grids with one hazard per open cell; ``catalogue``: every
instance of the table; ``timing``: timed runs of the embedded solver and SLUGS.
"""
