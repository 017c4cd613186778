"""Helpers for the scripts that run LAMMPS: its environment and the provenance of a run."""

import math
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir,
                                     os.pardir))


def lammps_environment():
    """os.environ, plus build/env.sh's settings ($SPH_ASTRO_BUILD or ./build) if ``lmp`` is
    not on PATH yet; exits with a message when no ``lmp`` can be found."""
    env = dict(os.environ)
    if shutil.which("lmp", path=env.get("PATH")):
        return env
    env_sh = os.path.join(os.environ.get("SPH_ASTRO_BUILD", os.path.join(ROOT, "build")),
                          "env.sh")
    if os.path.exists(env_sh):
        out = subprocess.run(["bash", "-c", f'source "{env_sh}" >/dev/null && env -0'],
                             check=True, capture_output=True).stdout
        env = dict(item.split("=", 1) for item in out.decode().split("\0") if "=" in item)
    if not shutil.which("lmp", path=env.get("PATH")):
        sys.exit("error: lmp not found; source build/env.sh (or run tools/setup.sh) first")
    return env


def provenance(log_path):
    """'git <commit>[ +local changes], plugin <path> (<mtime>)' for a table header."""
    parts = []
    try:
        head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], check=True,
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--", "src",
                                "cmake"], capture_output=True, text=True).stdout.strip()
        parts.append(f"git {head}{' + local changes in src/cmake' if dirty else ''}")
    except (OSError, subprocess.CalledProcessError):
        pass
    try:
        with open(log_path, encoding="utf-8", errors="replace") as f:
            m = re.search(r"^Loaded \d+ plugins? from (\S+)", f.read(4096), re.M)
        if m:
            so = os.path.join(m.group(1), "sphastroplugin.so")
            when = (time.strftime("%Y-%m-%d %H:%M", time.localtime(os.path.getmtime(so)))
                    if os.path.exists(so) else "?")
            parts.append(f"plugin {m.group(1)} (built {when})")
    except OSError:
        pass
    return ", ".join(parts) or "unknown"


_LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)


def parse_sph_log(path, loops="last"):
    """Energy error, capped particles and run size from the LAMMPS log of an SPH-ASTRO scene.

    Reads the thermo blocks that have the column ``c_sum[12]`` (compute sph/astro/global's
    relative energy error) and, if present, ``f_hvar[4]`` (fix sph/astro/h: particles at the
    h cap), and the ``Loop time`` lines: ``loops="last"`` takes the last run (scenes with a
    ``run 0`` before the real one), ``loops="sum"`` adds up all runs (a ``run 0`` adds no
    steps; an input may also run in several ``run`` commands).
    Returns a dict; missing items are nan.
    """
    out = {"energy": math.nan, "energy_max": math.nan, "capped": math.nan,
           "capped_max": math.nan, "steps": math.nan, "natoms": math.nan, "loop_s": math.nan,
           "procs": math.nan, "runs": 0}
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    header = None
    err, capped = [], []
    for line in text.splitlines():
        words = line.split()
        if words[:1] == ["Step"] and "c_sum[12]" in words:
            header = words
            continue
        if header is None:
            continue
        if len(words) != len(header):
            header = None if line.startswith("Loop time") else header
            continue
        try:
            row = [float(w) for w in words]
        except ValueError:
            continue
        err.append(row[header.index("c_sum[12]")])
        if "f_hvar[4]" in header:
            capped.append(row[header.index("f_hvar[4]")])
    if err:
        out["energy"] = err[-1]
        out["energy_max"] = max(abs(e) for e in err)
    if capped:
        out["capped"] = capped[-1]
        out["capped_max"] = max(capped)
    found = _LOOP.findall(text)
    if found:
        chosen = found if loops == "sum" else found[-1:]
        out.update(loop_s=sum(float(lp[0]) for lp in chosen), procs=int(found[-1][1]),
                   steps=sum(int(lp[2]) for lp in chosen), natoms=int(found[-1][3]),
                   runs=len(found))
    return out


def check_bounds(spec, values, lower=(), needs_log=(), have_log=True, all_finite=True,
                 error=None):
    """The ``--assert`` checks of the scene analyses: ``spec`` is ``name=bound,...``; each
    figure in ``values`` must be <= its bound, those named in ``lower`` >= it; nan (or
    ``all_finite`` false) fails. Figures in ``needs_log`` need the LAMMPS log. ``error`` (e.g.
    ``parser.error``) reports a malformed spec. Prints one line per check and returns the
    names of the failed ones."""
    def fail(message):
        if error is None:
            raise ValueError(message)
        error(message)

    failed = []
    for item in spec.split(","):
        if not item.strip():
            continue
        name, bound = item.split("=")
        name = name.strip()
        if name in needs_log and not have_log:
            fail(f"--assert: '{name}' needs --log")
        if name not in values:
            fail(f"--assert: unknown figure '{name}' ({', '.join(sorted(values))})")
        value, bound = values[name], float(bound)
        if name in lower:
            ok = value >= bound
            text = f"check {name} = {value:.4g} >= {bound:.4g}"
        else:
            ok = value <= bound
            text = f"check {name} = {value:.4g} <= {bound:.4g}"
        ok = ok and value == value and all_finite          # nan fails
        print(f"{text}: {'ok' if ok else 'FAILED'}")
        if not ok:
            failed.append(name)
    return failed
