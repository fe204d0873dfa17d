"""Simulation and rendering of synthesized controllers: runs, environments, scenarios, views.

Pipeline after synthesis: :mod:`gaitsim.strategy` (controller) → :mod:`gaitsim.simulator`
(with an environment) → :mod:`gaitsim.run` → :mod:`gaitsim.terminal` / :mod:`gaitsim.map_view`.
"""
