"""Helpers for the scripts that run LAMMPS: its environment and the provenance of a run."""

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
