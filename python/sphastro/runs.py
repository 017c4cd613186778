"""Helpers for the scripts that run LAMMPS: its environment and the provenance of a run."""

import math
import os
import re
import shutil
import subprocess
import sys
import time



def repo_root(root=None):
    """The SPH-ASTRO source tree: ``root`` if given, else $SPH_ASTRO_ROOT (set by build/env.sh);
    exits with a message when neither names a directory with examples/."""
    root = root or os.environ.get("SPH_ASTRO_ROOT")
    if not root:
        sys.exit("error: the SPH-ASTRO source tree is not known: pass it as an argument or "
                 "set SPH_ASTRO_ROOT (source build/env.sh)")
    if not os.path.isdir(os.path.join(root, "examples")):
        sys.exit(f"error: {root} (SPH_ASTRO_ROOT) is not an SPH-ASTRO source tree "
                 "(no examples/ in it)")
    return os.path.abspath(root)


def lammps_environment():
    """os.environ, plus build/env.sh's settings (from $SPH_ASTRO_BUILD) if ``lmp`` is not on
    PATH yet; exits with a message when no ``lmp`` can be found."""
    env = dict(os.environ)
    if shutil.which("lmp", path=env.get("PATH")):
        return env
    build = os.environ.get("SPH_ASTRO_BUILD")
    env_sh = os.path.join(build, "env.sh") if build else None
    if env_sh and os.path.exists(env_sh):
        out = subprocess.run(["bash", "-c", f'source "{env_sh}" >/dev/null && env -0'],
                             check=True, capture_output=True).stdout
        env = dict(item.split("=", 1) for item in out.decode().split("\0") if "=" in item)
    if not shutil.which("lmp", path=env.get("PATH")):
        sys.exit("error: lmp not found; source build/env.sh (or run tools/setup.sh) first, or "
                 "set SPH_ASTRO_BUILD to the build directory")
    return env


def provenance(log_path, root=None):
    """'git <commit>[ +local changes], plugin <path> (<mtime>)' for a table header; the commit
    only when ``root`` (default $SPH_ASTRO_ROOT) is a git checkout."""
    parts = []
    root = root or os.environ.get("SPH_ASTRO_ROOT")
    try:
        if not root:
            raise OSError("no source tree")
        head = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], check=True,
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", root, "status", "--porcelain", "--", "src",
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
