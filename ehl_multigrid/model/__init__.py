"""The physics foundation: errors, lubricant and solid properties, Hertz, dimensionless groups,
film-thickness fits, scenes, results (HDF5) and convergence reports.

Imports nothing from the solvers or the application above it.
"""
