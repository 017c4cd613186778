#!/usr/bin/env python3
# SPH-ASTRO - astrophysical SPH for LAMMPS. Distributed under the GNU General Public License
# version 2 (the same licence as LAMMPS); see the LICENSE file.
"""The sentinel's warnings reach the screen at the step they concern, not at a later flush.

lmp runs a long job whose first step draws a warning (a fixed h whose kernel support is 3
times the periodic box length), its screen on a pipe (block-buffered); the warning must be read
from the pipe while lmp is still running. Without a flush it came with LAMMPS' next flush,
minutes later or at the end.

    source build/env.sh
    python3 unittest/warning_on_time.py OUTDIR

Exit status 1 if the warning does not arrive while the run goes on (a 300 s hang guard).
"""
import os
import subprocess
import sys
import threading

INPUT = """
units           lj
atom_style      atomic
atom_modify     map array
boundary        p p p
lattice         fcc 4.0
region          box block 0 1 0 1 0 1
create_box      1 box
create_atoms    1 box
mass            1 0.25
pair_style      sph/astro kernel m4 eos ideal 1.6666666666666667 viscosity classic 1 2
pair_coeff      * *
fix             gas all sph/astro dt fixed
set             group all d_h 1.5
set             group all d_u 1.0
timestep        1e-4
thermo          1000000
run             100000000
"""


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(outdir, exist_ok=True)
    path = os.path.join(outdir, "in.support")
    with open(path, "w") as f:
        f.write(INPUT)
    cmd = ["lmp", "-in", path, "-log", "none", "-nocite"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            cwd=outdir)
    timer = threading.Timer(300.0, proc.kill)    # a hang guard, not a speed bound
    timer.start()
    found, running = None, None
    try:
        for line in proc.stdout:
            if "meets its own periodic images" in line:
                found = line.strip()
                running = proc.poll() is None
                break
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait()
        timer.cancel()
    print(f"warning: {found}")
    ok = found is not None and running
    print(f"{'ok' if ok else 'FAILED'}: the warning arrived while lmp was running")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
