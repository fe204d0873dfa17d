"""Simulation and rendering of synthesized controllers: runs, environments, scenarios, views.

Pipeline after synthesis: :mod:`gaitc.sim.strategy` (controller) → :mod:`gaitc.sim.simulator` (with
an environment) → :mod:`gaitc.sim.run` → :mod:`gaitc.sim.terminal` / :mod:`gaitc.sim.map_view`.
"""
