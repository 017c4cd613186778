"""Python reference and analysis tools for SPH-ASTRO.

Modules: :mod:`riemann` (exact Riemann solver), :mod:`dump` (LAMMPS text dump reader),
:mod:`sod` (shock-tube error norms and profile plots), :mod:`sedov` (Sedov-Taylor solution),
:mod:`noh` (Noh implosion), :mod:`gresho` (Gresho-Chan vortex), :mod:`toystar` (toy-star
lambda, profile and errors), :mod:`evrard` (Evrard collapse energies), :mod:`render`
(SPH-kernel-weighted slice and column maps: ``sphastro render``), :mod:`cli` (the
``--assert`` bounds of the analysis scripts) and :mod:`runs` (LAMMPS environment and log
parsing for the scripts).
"""
