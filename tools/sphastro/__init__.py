"""Python reference and analysis tools for SPH-ASTRO.

Modules: :mod:`riemann` (exact Riemann solver), :mod:`dump` (LAMMPS text dump
reader), :mod:`sod` (shock-tube error norms and profile plots), :mod:`sedov`
(Sedov-Taylor solution), :mod:`toystar` (toy-star lambda, profile and errors)
and :mod:`runs` (LAMMPS environment and log parsing for the scripts).
"""
