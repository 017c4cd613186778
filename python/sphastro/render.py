"""SPH-kernel-weighted maps of particle data: slices and column integrals (``sphastro render``).

A particle field A is interpolated at the centre r of each pixel with the standard SPH sum
(Price 2007, PASA 24, 159, eq. 1; the SPLASH rendering)::

    A(r) = sum_j m_j / rho_j A_j W(|r - r_j|, h_j)                       (slice)
    N(R) = sum_j m_j / rho_j A_j F(|R - R_j|, h_j)                       (column)

with F the kernel integrated along the line of sight, F(R, h) = int W(sqrt(R^2 + z^2), h) dz
(Price 2007, eq. 3). For A = rho the sums are sum_j m_j W and sum_j m_j F: the density and the
surface density. The kernel is SPH-ASTRO's M4 cubic spline (src/SPH-ASTRO/sph_astro_kernel.h;
Monaghan & Lattanzio 1985): W(r, h) = sigma_d / h^d w(r/h), w(q) = 1 - 3/2 q^2 + 3/4 q^3 for
q < 1, (2 - q)^3 / 4 for 1 <= q < 2, 0 beyond (support 2h); sigma = 2/3, 10/(7 pi), 1/pi in
1, 2, 3 dimensions.

Input: LAMMPS text dumps (any frame, by default the last; columns x y [z], rho, h, optionally mass, vx vy vz,
u, pressure: the names the scenes of examples/ give their c_sph[...] columns) and HDF5
snapshots in SWIFT's layout (PartType0/Coordinates, Masses, Density, SmoothingLengths,
Velocities, InternalEnergies; read with h5py).
"""

import argparse
import math
import os
import sys
import warnings
import zlib

import numpy as np

__all__ = ["SIGMA", "kernel_w", "kernel_column", "Particles", "FileError", "RenderWarning",
           "read_particles",
           "periodic_images", "slice_map",
           "column_map", "render", "add_parser"]

#: M4 normalisation sigma_d in d = 1, 2, 3 (sph_astro_kernel.h, KernelCubic::sigma)
SIGMA = {1: 2.0 / 3.0, 2: 10.0 / (7.0 * math.pi), 3: 1.0 / math.pi}
#: SWIFT's cubic spline: support H = gamma_K h with gamma_K = 1.825742 in 3D, 1.778002 in 2D
#: (Dehnen & Aly 2012, MNRAS 425, 1068, table 1); SPH-ASTRO's M4 has support 2h
SWIFT_KERNEL_GAMMA = {2: 1.778002, 3: 1.825742}

#: the most pixels a map may have across either axis: the PNG shows the map on about 280, and
#: 4096^2 doubles are 134 MB per array the deposit holds
MAX_RES = 4096


def kernel_w(q):
    """The dimensionless M4 shape w(q) (support q < 2)."""
    q = np.asarray(q, dtype=float)
    t = np.clip(2.0 - q, 0.0, None)
    return np.where(q < 1.0, 1.0 - 1.5 * q * q + 0.75 * q * q * q, 0.25 * t * t * t)


def _column_table(n=2001):
    """F(q) = sigma_3 int w(sqrt(q^2 + s^2)) ds over the line of sight, q in [0, 2]
    (composite Simpson rule, 4000 intervals in s: relative error below 1e-9)."""
    q = np.linspace(0.0, 2.0, n)
    smax = np.sqrt(np.clip(4.0 - q * q, 0.0, None))
    x = np.linspace(0.0, 1.0, 4001)
    wts = np.ones_like(x)
    wts[1:-1:2], wts[2:-1:2] = 4.0, 2.0
    wts /= 3.0 * (len(x) - 1)
    s = smax[:, None] * x[None, :]
    f = kernel_w(np.sqrt(q[:, None] ** 2 + s * s)) @ wts * smax
    return q, 2.0 * SIGMA[3] * f


_COLUMN_Q, _COLUMN_F = _column_table()


def kernel_column(q):
    """F(q) of the 3D M4 kernel: the column integral is F(R/h) / h^2 (zero for q >= 2)."""
    q = np.asarray(q, dtype=float)
    return np.interp(q, _COLUMN_Q, _COLUMN_F, right=0.0)


class Particles:
    """Positions (N x dim), masses, densities, smoothing lengths (M4 convention: support 2h),
    further per-particle fields (dict name -> array), the box ((dim, 2) or None), the time."""

    def __init__(self, pos, mass, rho, h, fields=None, box=None, time=None, note=""):
        self.pos = np.asarray(pos, dtype=float)
        self.dim = self.pos.shape[1]
        n = len(self.pos)
        self.mass = np.broadcast_to(np.asarray(mass, dtype=float), (n,)).copy()
        self.rho = np.broadcast_to(np.asarray(rho, dtype=float), (n,)).copy()
        self.h = np.broadcast_to(np.asarray(h, dtype=float), (n,)).copy()
        self.fields = dict(fields or {})
        self.box = None if box is None else np.asarray(box, dtype=float)
        self.time = time
        self.note = note

    def field(self, name):
        """A per-particle field: rho, h, mass, a velocity magnitude ``v`` (from vx, vy, vz), or
        a named column."""
        if name == "rho":
            return self.rho
        if name == "h":
            return self.h
        if name == "mass":
            return self.mass
        if name == "v":
            comps = [self.fields[c] for c in ("vx", "vy", "vz") if c in self.fields]
            if not comps:
                raise KeyError("field 'v' needs the columns vx, vy (, vz)")
            return np.sqrt(sum(c * c for c in comps))
        if name not in self.fields:
            raise KeyError(f"no field '{name}' (available: {', '.join(self.available())})")
        return self.fields[name]

    def available(self):
        """The names :meth:`field` knows: rho, h, mass, the further fields, v with velocities."""
        return ["rho", "h", "mass", *sorted(self.fields)] + (["v"] if "vx" in self.fields else [])


def periodic_images(p, axes=None):
    """``p`` with the periodic images of the particles within 2 h_max of the faces of its box
    across ``axes`` (default all; a column map: the two in-plane axes only) added, for maps of
    periodic boxes up to their edges."""
    if p.box is None:
        raise ValueError("periodic images need the box (dump BOX BOUNDS or HDF5 BoxSize)")
    reach = 2.0 * p.h.max()
    idx = np.arange(len(p.pos))
    pos = p.pos.copy()
    for a in (range(p.dim) if axes is None else axes):
        lo, hi = p.box[a]
        length = hi - lo
        near_lo = pos[:, a] < lo + reach
        near_hi = pos[:, a] > hi - reach
        shift_up, shift_down = pos[near_lo].copy(), pos[near_hi].copy()
        shift_up[:, a] += length
        shift_down[:, a] -= length
        pos = np.vstack([pos, shift_up, shift_down])
        idx = np.concatenate([idx, idx[near_lo], idx[near_hi]])
    fields = {k: np.asarray(v)[idx] for k, v in p.fields.items()}
    return Particles(pos, p.mass[idx], p.rho[idx], p.h[idx], fields, p.box, p.time, p.note)


class FileError(ValueError):
    """A dump or snapshot that cannot be read, or a picture that cannot be written; the
    message starts with the file's name (``sphastro render``: one line, exit status 1)."""


def _is_hdf5(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89HDF\r\n\x1a\n"


def _one_line(exc):
    """An exception's text on one line (h5py's and matplotlib's may run over several)."""
    text = exc.args[0] if isinstance(exc, KeyError) and exc.args else str(exc)
    return " ".join(str(text).split())


def _check_particles(path, pos, mass, rho, h, ids=None):
    """Refuse particles the kernel sums cannot hold: a position that is not finite, h or rho
    not positive and finite, a negative or non-finite mass. A NaN would blank every pixel it
    reaches and an h <= 0 divide by zero, neither with a word of why."""
    n = len(pos)
    if n == 0:
        raise FileError(f"{path}: no particles in the file (or the frame): nothing to "
                        "render")
    values = {"xyz"[a]: pos[:, a] for a in range(pos.shape[1])}
    values.update(h=h, rho=rho, mass=mass)
    with np.errstate(invalid="ignore"):
        good = {name: np.isfinite(v) for name, v in values.items()}
        for name in ("h", "rho"):
            good[name] &= values[name] > 0.0
        good["mass"] &= mass >= 0.0
    for name, ok in good.items():
        bad = np.flatnonzero(~ok)
        if len(bad):
            k = bad[0]
            who = f"id {ids[k]}" if ids is not None else f"particle {k} of the file"
            what = {"h": "not a positive finite number", "rho": "not a positive finite number",
                    "mass": "negative or not finite"}.get(name, "not finite")
            raise FileError(f"{path}: {len(bad)} of {n} particles have {name} {what} "
                            f"(first: {who}, {name} = {values[name][k]:g}); the map cannot "
                            "hold them")


def _read_hdf5(path, h_factor=None, frame=-1):
    if frame not in (0, -1):
        raise ValueError(f"--frame {frame}: {path} is an HDF5 snapshot, one frame "
                         "(allowed: 0 or -1)")
    try:
        import h5py
    except ImportError:
        raise FileError(f"{path} is HDF5: reading it needs h5py (Debian: python3-h5py)") \
            from None
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        # a truncated file: "Unable to open file (truncated file: eof = ..., stored_eof = ...)"
        raise FileError(f"{path}: not a readable HDF5 file ({_one_line(exc)})") from None
    try:
        with f:
            return _read_hdf5_file(path, f, h_factor)
    except FileError:
        raise
    except (OSError, ValueError, KeyError, IndexError, TypeError) as exc:
        # h5py's and numpy's own complaints about a damaged or unexpected file
        raise FileError(f"{path}: cannot read the snapshot ({_one_line(exc)})") from None


def _read_hdf5_file(path, f, h_factor):
    if "PartType0" not in f:
        raise FileError(f"{path}: no PartType0 group (SWIFT snapshot layout expected)")
    g = f["PartType0"]
    need = ("Coordinates", "Masses", "Density", "SmoothingLengths")
    missing = [k for k in need if k not in g]
    if missing:
        raise FileError(f"{path}: PartType0 lacks {', '.join(missing)}")
    header = f["Header"].attrs if "Header" in f else {}
    dim = int(np.ravel(header.get("Dimension", [3]))[0])
    if dim not in (2, 3):
        raise FileError(f"{path}: Header Dimension {dim}: render maps 2D and 3D data")
    coords = np.asarray(g["Coordinates"], dtype=float)
    if coords.ndim != 2 or coords.shape[1] < dim:
        raise FileError(f"{path}: PartType0/Coordinates has the shape {coords.shape}, "
                        f"expected (N, {'2) or (N, 3' if dim == 2 else '3'})")
    n = len(coords)
    data = {}
    for key in ("Masses", "Density", "SmoothingLengths", "InternalEnergies", "Pressures",
                "ParticleIDs", "Velocities"):
        if key in g:
            data[key] = np.asarray(g[key])
            shape = data[key].shape
            if key == "Velocities":
                ok, want = len(shape) == 2 and shape[0] == n and shape[1] >= dim, f"({n}, {dim})"
            else:
                ok, want = shape == (n,), f"({n},)"
            if not ok:
                raise FileError(f"{path}: PartType0/{key} has the shape {shape} for {n} "
                                f"particles, expected {want}")
    pos = coords[:, :dim]
    box = None
    if "BoxSize" in header:
        size = np.ravel(np.asarray(header["BoxSize"], dtype=float))
        size = np.resize(size, dim)
        box = np.column_stack([np.zeros(dim), size])
    time = float(np.ravel(header["Time"])[0]) if "Time" in header else None
    if h_factor is None:
        # fix sph/astro/snapshot (Code group "SPH-ASTRO ...") stores the run's own h
        code = f["Code"].attrs.get("Code", b"") if "Code" in f else b""
        code = code.decode() if isinstance(code, bytes) else str(code)
        h_factor = 1.0 if code.startswith("SPH-ASTRO") else \
            SWIFT_KERNEL_GAMMA.get(dim, 1.825742) / 2.0
    fields = {}
    if "Velocities" in data:
        for k, c in enumerate(("vx", "vy", "vz")[:dim]):
            fields[c] = data["Velocities"][:, k].astype(float)
    for name, key in (("u", "InternalEnergies"), ("pressure", "Pressures")):
        if key in data:
            fields[name] = data[key].astype(float)
    mass, rho = data["Masses"].astype(float), data["Density"].astype(float)
    h = h_factor * data["SmoothingLengths"].astype(float)
    _check_particles(path, pos, mass, rho, h, data.get("ParticleIDs"))
    return Particles(pos, mass, rho, h, fields, box, time,
                     note=f"h = {h_factor:.6g} x SmoothingLengths")


def _dump_frame(path, frame):
    """The frame of the dump ``path`` (index ``frame``); dump.py's ValueErrors on text that is
    no dump, and its warnings on a truncated last frame, become a :class:`FileError` naming
    the file when no frame is left."""
    from .dump import read_frames, read_last_frame

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            frames = [read_last_frame(path)] if frame == -1 else list(read_frames(path))
        except (ValueError, EOFError, OSError, zlib.error) as exc:
            if "no complete frame" not in str(exc):
                raise FileError(f"{path}: not a readable LAMMPS text dump "
                                f"({_one_line(exc)})") from None
            frames = []
    # dump.py's words for a frame cut short ("skipping incomplete last frame", "last frame
    # incomplete") and for a file without one ("no complete frame")
    truncated = [w for w in caught if "incomplete" in str(w.message)]
    if not frames and truncated:
        raise FileError(f"{path}: the file ends inside its first frame (a truncated dump, or "
                        "one still being written): no complete frame")
    if not frames:
        raise FileError(f"{path}: not a LAMMPS text dump (no 'ITEM: TIMESTEP' frame) nor an "
                        "HDF5 snapshot")
    for w in caught:                        # e.g. the last frame incomplete, an earlier one used
        warnings.warn(w.message)
    if frame == -1:
        return frames[0]
    n = len(frames)
    if not -n <= frame < n:
        raise ValueError(f"--frame {frame}: {path} has {n} frame{'s' if n != 1 else ''} "
                         f"(allowed: {-n} to {n - 1})")
    return frames[frame]


def _read_dump(path, mass=None, hfact=1.2, h_factor=None, frame=-1):
    frame = _dump_frame(path, frame)
    c = frame.columns
    axes = [a for a in ("x", "y", "z") if a in c]
    if axes[:2] != ["x", "y"]:
        raise FileError(f"{path}: the dump needs the columns x, y (and z in 3D)")
    alias = {"c_sph[1]": "rho", "c_sph[2]": "pressure", "c_sph[3]": "u", "c_sph[4]": "h"}
    cols = {alias.get(k, k): v for k, v in c.items()}
    for k in ("rho", "h"):
        if k not in cols:
            raise FileError(f"{path}: the dump needs a '{k}' column (e.g. compute "
                            "sph/astro/atom rho pressure u h, dump_modify colname ...)")
    for k in axes + ["rho", "h"] + (["mass"] if "mass" in cols else []):
        # dump.py keeps a column with a word in it as text
        if np.asarray(cols[k]).dtype.kind not in "fi":
            raise FileError(f"{path}: column {k} is not numeric (e.g. {cols[k][0]!r})")
    # a 2d LAMMPS run keeps every z at 0 (dump columns x y z of a 2d run: 2D)
    if "z" in axes and len(c["z"]) and not np.any(np.asarray(c["z"], dtype=float)):
        axes = ["x", "y"]
    dim = len(axes)
    h = cols["h"] * (h_factor or 1.0)
    note = ""
    if "mass" in cols:
        m = cols["mass"]
    elif mass is not None:
        m = float(mass)
        note = f"mass {m:.6g} (given)"
    else:
        # the smoothing-length constraint h = hfact (m / rho)^(1/d) (Price 2012, JCP 231, 759,
        # eq. 10), exact for variable-h runs (fix sph/astro/h iterate)
        with np.errstate(all="ignore"):     # non-finite rho, h: refused below
            m = cols["rho"] * (cols["h"] / hfact) ** dim
        note = f"mass from rho (h/hfact)^d, hfact {hfact:g}"
    skip = set(axes) | {"rho", "h", "mass", "id", "type"}
    fields = {k: np.asarray(v, dtype=float) for k, v in cols.items()
              if k not in skip and np.asarray(v).dtype.kind in "fi"}
    pos = np.column_stack([cols[a] for a in axes]).astype(float)
    n = len(pos)
    _check_particles(path, pos, np.broadcast_to(np.asarray(m, dtype=float), (n,)),
                     np.asarray(cols["rho"], dtype=float), np.asarray(h, dtype=float),
                     cols.get("id"))
    return Particles(pos, m, cols["rho"], h, fields, frame.box[:dim], frame.time, note)


def read_particles(path, mass=None, hfact=1.2, h_factor=None, frame=-1):
    """:class:`Particles` of a LAMMPS text dump (``frame``: its index, -1 the last) or a
    SWIFT-layout HDF5 snapshot.

    Dumps: ``mass`` (a number) when the dump has no mass column, else m = rho (h/hfact)^d;
    HDF5: ``h_factor`` scales SmoothingLengths to SPH-ASTRO's h (default: 1 for files of fix
    sph/astro/snapshot, SWIFT's gamma_K / 2 for others).

    A file that cannot be read (missing, empty, truncated, not a dump, particles with
    non-finite or non-positive h, rho) raises :class:`FileError`, a ``frame`` it lacks a
    ValueError."""
    for name, value in (("--mass", mass), ("--hfact", hfact), ("--h-factor", h_factor)):
        if value is not None and not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} {value!r}: expected a positive finite number")
    if not os.path.exists(path):
        raise FileError(f"{path}: no such file")
    if os.path.isdir(path):
        raise FileError(f"{path}: a directory, not a dump or a snapshot")
    try:
        if os.path.getsize(path) == 0:
            raise FileError(f"{path}: empty file (expected a LAMMPS text dump or an HDF5 "
                            "snapshot)")
        hdf5 = _is_hdf5(path)
    except OSError as exc:
        raise FileError(f"{path}: cannot read it ({exc.strerror or _one_line(exc)})") from None
    if hdf5:
        return _read_hdf5(path, h_factor, frame)
    return _read_dump(path, mass, hfact, h_factor, frame)


# absurd scales (a window of 1e200, h of 1e-300) overflow to inf, and w(inf) = 0: an empty
# map is reported, with its reason, by render's warnings rather than numpy's
@np.errstate(all="ignore")
def _deposit(grid_shape, x0, dx, centres, h, weights, profile, offset=None,
             batch=4_000_000):
    """Sum weights_j profile(|r - r_j| / h_j, h_j) over the pixel centres r within 2 h_j of each
    particle; |r - r_j|^2 is the in-plane distance squared plus offset_j^2 (the distance of a
    particle from a slice plane). grid_shape (ny, nx), x0 (lower-left corner) and dx (pixel
    size) per image axis; ``profile(q, h)`` is the normalised kernel factor."""
    ny, nx = grid_shape
    img = np.zeros(ny * nx)
    off2 = np.zeros(len(h)) if offset is None else np.asarray(offset, dtype=float) ** 2
    # the pixels around the one holding each particle, 2h and one more on either side,
    # clipped to the image: a particle far outside it costs nothing, and one far larger than
    # it (a window much smaller than h) at most the image, where the whole square of pixels
    # would exhaust the memory
    bounds, reach = [], []
    for a, n in ((0, nx), (1, ny)):
        at = np.floor((centres[:, a] - x0[a]) / dx[a])
        reach.append(np.ceil(2.0 * h / dx[a]) + 1.0)
        bounds += [np.clip(at - reach[-1], 0, n), np.clip(at + reach[-1], -1, n - 1)]
    keep = (bounds[1] >= bounds[0]) & (bounds[3] >= bounds[2])     # False for a NaN too
    ilo, ihi, jlo, jhi = (np.where(keep, b, 0).astype(int) for b in bounds)
    # footprints grouped by their width in pixels, so that each group is one array operation;
    # the unclipped width (at most the image's) keeps the groups few, the mask below the
    # image's edges
    width = np.minimum(2.0 * np.maximum(*reach) + 1.0, max(nx, ny)).astype(int)
    for k in np.unique(width[keep]):
        sel = np.flatnonzero(keep & (width == k))
        off = np.arange(k)
        per = max(1, batch // (k * k))
        for start in range(0, len(sel), per):
            idx = sel[start:start + per]
            c = centres[idx]
            hh = h[idx, None, None]
            ii = ilo[idx, None, None] + off[None, None, :]
            jj = jlo[idx, None, None] + off[None, :, None]
            px = x0[0] + (ii + 0.5) * dx[0]
            py = x0[1] + (jj + 0.5) * dx[1]
            r2 = (px - c[:, 0, None, None]) ** 2 + (py - c[:, 1, None, None]) ** 2 \
                + off2[idx, None, None]
            q = np.sqrt(r2) / hh
            # w = 0 beyond q = 2 exactly, also where the kernel's 1/h^d overflows (no inf x 0)
            val = np.where(q < 2.0, weights[idx, None, None] * profile(q, hh), 0.0)
            ii, jj, val = np.broadcast_arrays(ii, jj, val)
            inside = (ii <= ihi[idx, None, None]) & (jj <= jhi[idx, None, None]) & (val != 0.0)
            img += np.bincount(jj[inside] * nx + ii[inside], weights=val[inside],
                               minlength=ny * nx)
    return img.reshape(ny, nx)


def _grid(extent, res):
    """extent ((xlo, xhi), (ylo, yhi)) and res (nx or (nx, ny)) -> shape, corner, pixel size;
    square pixels: ny follows from the aspect ratio when one number is given."""
    (xlo, xhi), (ylo, yhi) = extent
    with np.errstate(over="ignore"):
        widths = np.array([xhi - xlo, yhi - ylo], dtype=float)
    if not (np.all(np.isfinite([xlo, xhi, ylo, yhi])) and xlo < xhi and ylo < yhi and
            np.all(np.isfinite(widths))):
        raise ValueError(f"--extent {xlo:g},{xhi:g},{ylo:g},{yhi:g}: expected four finite "
                         "numbers with X0 < X1 and Y0 < Y1, the widths finite")
    if np.ndim(res) == 0:
        nx = int(res)
        ny = nx * ((yhi - ylo) / (xhi - xlo))
        if not ny <= MAX_RES:               # an inf too
            raise ValueError(f"--extent {xlo:g},{xhi:g},{ylo:g},{yhi:g}: a window {ny / nx:.3g} "
                             f"times taller than wide has {ny:.3g} pixels up at --res {nx} (at "
                             f"most {MAX_RES}): widen it or lower --res")
        ny = max(1, int(round(ny)))
    else:
        nx, ny = (int(v) for v in res)
    if not (1 <= nx <= MAX_RES and 1 <= ny <= MAX_RES):           # a tuple given
        raise ValueError(f"--res {res}: expected a whole number of pixels from 1 to {MAX_RES}")
    dx = np.array([(xhi - xlo) / nx, (yhi - ylo) / ny])
    return (ny, nx), np.array([xlo, ylo]), dx


def _extent(p, axes):
    if p.box is not None:
        return tuple(tuple(p.box[a]) for a in axes)
    lo = p.pos.min(axis=0) - 2.0 * p.h.max()
    hi = p.pos.max(axis=0) + 2.0 * p.h.max()
    return tuple((lo[a], hi[a]) for a in axes)


AXES = {"x": 0, "y": 1, "z": 2}


def slice_map(p, values, axis="z", at=0.0, res=256, extent=None, normalise=False):
    """The SPH interpolant of ``values`` on the plane ``axis`` = ``at`` (3D) or on the plane
    of 2D data: sum_j m_j/rho_j A_j W(|r - r_j|, h_j). Returns (image (ny, nx), extent); the
    image axes are the two other coordinates in the order x, y, z. ``normalise``: divide by
    sum_j m_j/rho_j W (exact for a constant field; SPLASH's normalised interpolation)."""
    if p.dim == 2:
        axes, dist = (0, 1), np.zeros(len(p.pos))
    else:
        k = AXES[axis]
        axes = tuple(a for a in range(3) if a != k)
        dist = p.pos[:, k] - at
    extent = extent or _extent(p, axes)
    shape, x0, dx = _grid(extent, res)
    near = np.abs(dist) < 2.0 * p.h
    sigma, dim = SIGMA[p.dim], p.dim
    vol = p.mass[near] / p.rho[near]
    centres = p.pos[near][:, axes]

    def run(weights):
        return _deposit(shape, x0, dx, centres, p.h[near], weights,
                        lambda q, hh: sigma / hh ** dim * kernel_w(q), offset=dist[near])

    img = run(vol * np.asarray(values, dtype=float)[near])
    if normalise:
        norm = run(vol)
        with np.errstate(invalid="ignore", divide="ignore"):
            img = np.where(norm > 0.0, img / norm, np.nan)
    return img, extent


def column_map(p, values, axis="z", res=256, extent=None):
    """The line-of-sight integral along ``axis`` of the SPH interpolant of ``values`` (3D):
    sum_j m_j/rho_j A_j F(|R - R_j|, h_j), F(R, h) = F(R/h) / h^2. Returns (image, extent)."""
    if p.dim != 3:
        raise ValueError("a column map needs 3D data (2D data: use a slice)")
    k = AXES[axis]
    axes = tuple(a for a in range(3) if a != k)
    extent = extent or _extent(p, axes)
    shape, x0, dx = _grid(extent, res)
    vol = p.mass / p.rho
    a = np.asarray(values, dtype=float)
    img = _deposit(shape, x0, dx, p.pos[:, axes], p.h, vol * a,
                   lambda q, hh: kernel_column(q) / (hh * hh))
    return img, extent


def _option_value(what):
    """An argparse ``type`` check: ``what`` (the allowed values) is said in the message, which
    argparse prefixes with "argument --OPTION:" and ends with the exit status 2."""
    def decorate(parse):
        def check(text):
            try:
                return parse(text)
            except (ValueError, TypeError):
                raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}") from None
        check.__name__ = parse.__name__
        return check
    return decorate


def _finite(text):
    # float() accepts "nan" and "inf": neither places a plane, a window or a colour limit
    v = float(text)
    if not math.isfinite(v):
        raise ValueError(text)
    return v


@_option_value("a positive finite number")
def _positive(text):
    v = _finite(text)
    if v <= 0.0:
        raise ValueError(text)
    return v


@_option_value(f"a whole number of pixels from 1 to {MAX_RES}")
def _pixels(text):
    v = int(text)
    if not 1 <= v <= MAX_RES:
        raise ValueError(text)
    return v


@_option_value("AXIS=VALUE with AXIS x, y or z and VALUE a finite number (e.g. z=0.5)")
def _slice(text):
    axis, sep, value = text.partition("=")
    if axis not in AXES or not sep:
        raise ValueError(text)
    return axis, _finite(value)


@_option_value("LO,HI: two finite numbers with LO < HI, HI - LO finite (log10 of the map "
               "with --log)")
def _range(text):
    lo, hi = (_finite(v) for v in text.split(","))
    if not (lo < hi and math.isfinite(hi - lo)):
        raise ValueError(text)
    return lo, hi


@_option_value("X0,X1,Y0,Y1: four finite numbers with X0 < X1 and Y0 < Y1, the widths "
               "finite")
def _window(text):
    x0, x1, y0, y1 = (_finite(v) for v in text.split(","))
    if not (x0 < x1 and y0 < y1 and math.isfinite(x1 - x0) and math.isfinite(y1 - y0)):
        raise ValueError(text)
    return (x0, x1), (y0, y1)


def _cmap(text):
    try:
        from matplotlib import colormaps
        known = text in colormaps
    except ImportError:                     # matplotlib < 3.5
        from matplotlib import cm
        try:
            cm.get_cmap(text)
            known = True
        except ValueError:
            known = False
    if not known:
        raise argparse.ArgumentTypeError(
            f"expected a matplotlib colour map (viridis, magma, inferno, gray, RdBu_r, ...: "
            f"the names in matplotlib.colormaps), got {text!r}")
    return text


def _title(text):
    # a title with paired $ is mathtext; an unknown symbol would fail only when the PNG is drawn
    from matplotlib import cbook
    from matplotlib.mathtext import MathTextParser
    if cbook.is_math_text(text):
        try:
            MathTextParser("path").parse(text)
        except ValueError as exc:
            why = " ".join(str(exc).split())
            raise argparse.ArgumentTypeError(
                f"matplotlib cannot typeset '{text}' ({why}); escape a literal dollar "
                r"sign as \$") from None
    return text


def _picture(text):
    """--out: a file name whose suffix is a format matplotlib writes (none: PNG)."""
    from matplotlib.figure import Figure
    formats = Figure().canvas.get_supported_filetypes()
    if os.path.isdir(text):
        raise argparse.ArgumentTypeError(f"{text!r} is a directory: expected the name of "
                                         "the picture to write, e.g. rho.png")
    suffix = os.path.splitext(text)[1][1:].lower()
    if suffix and suffix not in formats:
        raise argparse.ArgumentTypeError(
            f"expected a file name ending in .png or another format matplotlib writes "
            f"({', '.join(sorted(formats))}), got {text!r}")
    return text


class RenderWarning(UserWarning):
    """A picture that comes out blank or of one colour; the message says why."""


def _why_blank(p, values, img, data, ext, plane, field, log, vrange, slice_=None):
    """Why the picture of ``data`` (``img``, or its log10; ``values`` the field's) is blank or
    of one colour, or None: no particle's kernel reaches the slice plane (``slice_`` = (axis,
    value)) or the window ``ext``, kernels between the pixel centres, no positive pixel for
    --log, no finite pixel, one value everywhere, the whole map outside --range."""
    near = np.ones(len(p.pos), dtype=bool)
    if slice_ is not None:
        axis, at = slice_
        k = AXES[axis]
        near = np.abs(p.pos[:, k] - at) < 2.0 * p.h
        if not near.any():
            lo, hi = np.min(p.pos[:, k] - 2.0 * p.h), np.max(p.pos[:, k] + 2.0 * p.h)
            return (f"slice {axis} = {at:g}: no particle's kernel reaches the plane (they span "
                    f"{axis} = {lo:.4g} to {hi:.4g}): the map is empty and the picture blank "
                    "(choose the plane with --slice)")
    reach = near.copy()
    for a, (lo, hi) in zip(plane, ext):
        reach &= (p.pos[:, a] - 2.0 * p.h < hi) & (p.pos[:, a] + 2.0 * p.h > lo)
    if not reach.any():
        window = ", ".join(f"{'xyz'[a]} = {lo:g} to {hi:g}" for a, (lo, hi) in zip(plane, ext))
        span = ", ".join(f"{'xyz'[a]} = {np.min(p.pos[near, a] - 2.0 * p.h[near]):.4g} to "
                         f"{np.max(p.pos[near, a] + 2.0 * p.h[near]):.4g}" for a in plane)
        return (f"the window {window}: no particle's kernel"
                f"{' in the slice' if slice_ is not None else ''} reaches it (they span "
                f"{span}): the map is empty and the picture blank (choose the window with "
                "--extent)")
    pixel = max((hi - lo) / n for (lo, hi), n in zip(ext, img.shape[::-1]))
    support = 2.0 * p.h[reach]
    if not np.any(img[np.isfinite(img)] != 0.0) and np.any((p.mass * values)[reach] != 0.0) \
            and support.min() < pixel:
        return (f"the kernels of the particles that reach the window ({len(support)}; 2h "
                f"from {support.min():.3g} to {support.max():.3g}) fall between the pixel "
                f"centres, {pixel:.3g} apart: the map is 0 and the picture blank (raise --res "
                "or narrow --extent)")
    finite = data[np.isfinite(data)]
    if log and finite.size == 0:
        pixels = img[np.isfinite(img)]
        span = f" ({field} from {pixels.min():.4g} to {pixels.max():.4g})" if pixels.size else ""
        return (f"--log: no pixel of the map is positive{span}: the picture is blank "
                "(leave out --log)")
    if finite.size == 0:
        return f"no pixel of the map of {field} is finite: the picture is blank"
    lo, hi = finite.min(), finite.max()
    if lo == hi:
        return (f"the map of {field} is {lo:.4g}{' in log10' if log else ''} wherever "
                "particles reach: the picture has one colour")
    if vrange is not None and (hi < vrange[0] or lo > vrange[1]):
        return (f"--range {vrange[0]:g},{vrange[1]:g}: the map runs from {lo:.4g} to "
                f"{hi:.4g}{' in log10' if log else ''}, wholly outside the range: the picture "
                "has one colour")
    return None


def render(path, out, field="rho", slice_=None, column=None, res=256, vrange=None, log=False,
           vectors=False, extent=None, mass=None, hfact=1.2, h_factor=None, normalise=False,
           cmap="viridis", title=None, periodic=False, frame=-1):
    """Read ``path``, make a slice (``slice_`` = (axis, value); the default for 3D data is
    z = the middle of the box) or a column map (``column`` = axis) of ``field`` and write the
    PNG ``out`` (matplotlib). ``vectors``: in-plane velocity arrows (from vx, vy, vz).
    ``periodic``: add the periodic images of the particles near the box faces.
    Returns (image, extent, particles).

    Options the data do not fit (an unknown ``field``, ``column`` of 2D data, ...) raise a
    ValueError naming the option, a file that cannot be read or written a :class:`FileError`.
    A picture that comes out blank or of one colour is written all the same (a series of
    frames stays complete), with a :class:`RenderWarning` saying why."""
    from matplotlib.figure import Figure     # no pyplot: no GUI backend, no global state

    p = read_particles(path, mass=mass, hfact=hfact, h_factor=h_factor, frame=frame)
    # options that do not fit these data: usage errors naming the option (ValueError)
    available = f"available: {', '.join(p.available())}"
    if p.dim == 2 and column is not None:
        raise ValueError(f"--column {column}: {path} holds 2D data, and a column map needs 3D "
                         "(without --column the map is the plane of the data)")
    if normalise and column is not None:
        raise ValueError(f"--normalise divides a slice by sum_j m_j/rho_j W; a column map "
                         f"(--column {column}) has no such division (leave out one of them)")
    if p.dim == 2 and slice_ is not None:
        raise ValueError(f"--slice {slice_[0]}={slice_[1]:g}: {path} holds 2D data, and the "
                         "map is their plane (leave out --slice)")
    if field not in p.available():
        need = " (the speed needs the columns vx, vy (, vz))" if field == "v" else ""
        raise ValueError(f"--field {field!r}: {path} has no such field{need} ({available})")
    if vectors:
        if column is not None:
            plane = [a for a in range(3) if a != AXES[column]]
        elif p.dim == 3:
            plane = [a for a in range(3) if a != AXES[slice_[0] if slice_ else "z"]]
        else:
            plane = [0, 1]
        need = [f"v{'xyz'[a]}" for a in plane]
        if any(c not in p.fields for c in need):
            raise ValueError(f"--vectors: the arrows need the velocity columns "
                             f"{', '.join(need)}, which {path} lacks ({available})")
    if periodic and p.box is None:
        raise ValueError(f"--periodic: {path} has no box to wrap the particles in (a dump's "
                         "BOX BOUNDS, an HDF5 snapshot's Header BoxSize)")
    bad = np.count_nonzero(~np.isfinite(p.field(field)))
    if bad:
        warnings.warn(f"--field {field}: {bad} of {len(p.pos)} particles have a value that is "
                      "not finite: the pixels they reach are blank", RenderWarning, stacklevel=2)
    if p.box is not None and (extent is None or periodic):
        for a, (lo, hi) in enumerate(p.box):
            if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
                raise FileError(f"{path}: the box is empty along {'xyz'[a]} ({lo:g} to {hi:g}): "
                                + ("--periodic has no period" if periodic else
                                   "give the window with --extent"))
    if periodic:
        p = periodic_images(p, None if column is None else
                            [a for a in range(3) if a != AXES[column]])
    values = p.field(field)
    names = "xyz"
    if column is not None:
        img, ext = column_map(p, values, column, res, extent)
        axes = [a for a in range(3) if a != AXES[column]]
        label = (r"$\Sigma = \int \rho\,dl$" if field == "rho"
                 else rf"$\int {field}\,dl$")
        where = f"column along {column}"
    else:
        if slice_ is None and p.dim == 3:
            zlo, zhi = p.box[2] if p.box is not None else (p.pos[:, 2].min(), p.pos[:, 2].max())
            slice_ = ("z", 0.5 * (zlo + zhi))
        axis, at = slice_ if slice_ is not None else ("z", 0.0)
        img, ext = slice_map(p, values, axis, at, res, extent, normalise)
        axes = [0, 1] if p.dim == 2 else [a for a in range(3) if a != AXES[axis]]
        label = {"rho": r"$\rho$", "v": r"$|v|$"}.get(field, field)
        where = "2D" if p.dim == 2 else f"slice {axis} = {at:g}"
    fig = Figure(figsize=(4.6, 3.8))
    ax = fig.subplots()
    data = np.log10(np.where(img > 0.0, img, np.nan)) if log else img
    why = _why_blank(p, values, img, data, ext, axes, field, log, vrange,
                     None if column is not None or p.dim == 2 else (axis, at))
    if why:
        warnings.warn(why, RenderWarning, stacklevel=2)
    finite = data[np.isfinite(data)]
    vmin, vmax = vrange if vrange is not None else \
        (finite.min(), finite.max()) if finite.size else (None, None)
    im = ax.imshow(data, origin="lower", extent=[*ext[0], *ext[1]], cmap=cmap, vmin=vmin,
                   vmax=vmax, interpolation="nearest")
    fig.colorbar(im, ax=ax, label=("log10 " if log else "") + label)
    if vectors:
        comps = [p.field(f"v{names[a]}") for a in axes]
        coarse = max(8, (res if np.ndim(res) == 0 else res[0]) // 12)
        maps = []
        for comp in comps:
            if column is not None:
                num, e2 = column_map(p, comp * p.rho, column, coarse, ext)
                den, _ = column_map(p, p.rho, column, coarse, ext)
                with np.errstate(invalid="ignore", divide="ignore"):
                    maps.append(np.where(den > 0, num / den, 0.0))
            else:
                m, e2 = slice_map(p, comp, axis, at, coarse, ext, normalise=True)
                maps.append(np.nan_to_num(m))
        ny, nx = maps[0].shape
        xs = np.linspace(e2[0][0], e2[0][1], nx + 1)
        ys = np.linspace(e2[1][0], e2[1][1], ny + 1)
        ax.quiver(0.5 * (xs[1:] + xs[:-1]), 0.5 * (ys[1:] + ys[:-1]), maps[0], maps[1],
                  color="white", pivot="mid", width=0.004)
    ax.set_xlabel(names[axes[0]])
    ax.set_ylabel(names[axes[1]])
    t = f", t = {p.time:g}" if p.time is not None else ""
    # a file name with two $ would be typeset as mathtext
    name = os.path.basename(path).replace("$", r"\$")
    ax.set_title(title if title is not None else f"{name}: {where}{t}",
                 fontsize=9)
    fig.tight_layout()
    try:
        os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
        # matplotlib adds ".png" to a name without a suffix; write the file named
        fig.savefig(out, dpi=100, format=None if os.path.splitext(out)[1] else "png")
    except OSError as exc:
        raise FileError(f"--out {out}: cannot write it ({exc.strerror or _one_line(exc)})") \
            from None
    return img, ext, p


def add_parser(sub):
    """The ``render`` subcommand of ``sphastro``."""
    r = sub.add_parser("render", help="SPH-kernel-weighted slice or column map of a dump or "
                       "snapshot to a PNG",
                       description="Slice (sum_j m_j/rho_j A_j W) or column (line-of-sight "
                       "integral) map of a LAMMPS text dump (any frame) or a SWIFT-layout "
                       "HDF5 snapshot, with SPH-ASTRO's M4 kernel (Price 2007, PASA 24, 159).",
                       epilog="Exit status 2: a bad option value (or one the data do not fit); "
                       "1: a file that cannot be read or written; 0: the picture written, also "
                       "when it comes out blank or of one colour (then with a warning on stderr "
                       "saying why).")
    r.add_argument("snapshot", help="LAMMPS text dump (columns x y [z] rho h ...) or HDF5")
    r.add_argument("--out", required=True, type=_picture,
                   help="PNG to write (or .pdf, .svg, ...: the formats of matplotlib)")
    r.add_argument("--field", default="rho",
                   help="rho (default), v (speed), h, mass or a dump column (u, pressure, vx...)")
    g = r.add_mutually_exclusive_group()
    g.add_argument("--slice", default=None, metavar="AXIS=VALUE", type=_slice,
                   help="slice plane, e.g. z=0.5 (3D default: the middle of the box in z)")
    g.add_argument("--column", default=None, choices=("x", "y", "z"),
                   help="integrate along this axis instead (3D)")
    r.add_argument("--res", type=_pixels, default=256,
                   help=f"pixels across (default 256, at most {MAX_RES})")
    r.add_argument("--range", default=None, metavar="LO,HI", type=_range,
                   help="colour range, LO < HI; with --log in log10 of the map "
                        "(--range=-1,2 when it starts with a minus sign)")
    r.add_argument("--log", action="store_true", help="colour by log10 of the map")
    r.add_argument("--vectors", action="store_true", help="overlay in-plane velocity arrows")
    r.add_argument("--extent", default=None, metavar="X0,X1,Y0,Y1", type=_window,
                   help="image window in the plane's coordinates (default: the box); write "
                        "--extent=-1,1,-1,1 when it starts with a minus sign")
    r.add_argument("--periodic", action="store_true",
                   help="the box is periodic: include the images of particles near its faces")
    r.add_argument("--normalise", action="store_true",
                   help="slice: divide by sum_j m_j/rho_j W (normalised interpolation)")
    r.add_argument("--mass", type=_positive, default=None,
                   help="particle mass for a dump without a mass column (default: "
                        "rho (h/hfact)^d)")
    r.add_argument("--hfact", type=_positive, default=1.2,
                   help="h = hfact (m/rho)^(1/d), to infer masses (default 1.2)")
    r.add_argument("--h-factor", type=_positive, default=None,
                   help="scale the file's smoothing lengths to SPH-ASTRO's h (support 2h); "
                        "HDF5 default: 1 for fix sph/astro/snapshot files, SWIFT's gamma_K/2 = 0.912871 (3D) for others")
    r.add_argument("--frame", type=int, default=-1,
                   help="dump frame by index (0 the first, -1 the last: default)")
    r.add_argument("--cmap", default="viridis", type=_cmap, help="matplotlib colour map")
    r.add_argument("--title", default=None, type=_title,
                   help="title (default: the file, the plane, the time); $...$ is mathtext")
    r.set_defaults(func=_run)
    return r


def _run(args, parser):
    failure = None
    # warnings (a blank picture and why, dump.py's incomplete last frame) as one line each,
    # without the source line Python's warnings module would print under them
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            img, _, p = render(args.snapshot, args.out, args.field, args.slice, args.column,
                               args.res, args.range, args.log, args.vectors, args.extent,
                               args.mass, args.hfact, args.h_factor, args.normalise,
                               args.cmap, args.title, args.periodic, args.frame)
        except (ValueError, KeyError) as exc:
            failure = exc
    for text in dict.fromkeys(_one_line(w.message) for w in caught):
        print(f"{parser.prog}: warning: {text}", file=sys.stderr)
    if isinstance(failure, FileError):
        # the command line was fine, the file is not: no usage text, exit status 1
        parser.exit(1, f"{parser.prog}: error: {_one_line(failure)}\n")
    if failure is not None:
        parser.error(_one_line(failure))
    finite = img[np.isfinite(img)]
    span = f"from {finite.min():.4g} to {finite.max():.4g}" if finite.size else "no finite pixel"
    print(f"{args.snapshot}: {len(p.pos)} particles{' with periodic images' if args.periodic else ''} ({p.dim}D{'; ' + p.note if p.note else ''}); "
          f"map {img.shape[1]} x {img.shape[0]}, {args.field} {span}; wrote {args.out}")
    return 0
