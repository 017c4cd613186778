"""Thermo rows of a LAMMPS log file, as the scenes' analyses read them."""

import re

import numpy as np

_HEADER = re.compile(r"^\s*Step\s+")


def read_thermo(path):
    """All thermo rows of a LAMMPS log: dict column name -> numpy array (runs concatenated)."""
    data, names = {}, None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            if _HEADER.match(line):
                names = line.split()
                for name in names:
                    data.setdefault(name, [])
                continue
            if names is None:
                continue
            if line.startswith("Loop time") or line.startswith("fix sph/astro"):
                if line.startswith("Loop time"):
                    names = None
                continue
            parts = line.split()
            if len(parts) != len(names):
                continue
            try:
                values = [float(v) for v in parts]
            except ValueError:
                continue
            for name, v in zip(names, values):
                data[name].append(v)
    return {k: np.array(v) for k, v in data.items() if v}
