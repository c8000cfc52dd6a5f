"""The ``ehl`` application: command line, planner, main job, sweeps, tasks and plots.

It sits on top of the model (:mod:`ehl_multigrid.model`) and the numerical packages
(:mod:`ehl_multigrid.line`, :mod:`ehl_multigrid.point`); nothing below it imports it. The layers
above (thermal, mixed) may import only its two leaf modules, :mod:`~ehl_multigrid.app.console`
(shared command-line options and printing) and :mod:`~ehl_multigrid.app.stages` (what a stage
of the main job receives and returns).
"""
