"""Python reference and analysis tools for SPH-ASTRO.

Modules: :mod:`riemann` (exact Riemann solver), :mod:`dump` (LAMMPS text dump
reader) and :mod:`sod` (shock-tube error norms and profile plots).
"""
