"""Reader for LAMMPS text ``dump custom`` (and ``dump atom``) files.

Each frame written by LAMMPS looks like::

    ITEM: UNITS                 (only with dump_modify units yes, first frame only)
    si
    ITEM: TIME                  (only with dump_modify time yes)
    0.2
    ITEM: TIMESTEP
    1000
    ITEM: NUMBER OF ATOMS
    3
    ITEM: BOX BOUNDS pp pp pp   (restricted triclinic: "xy xz yz pp pp pp", 3 numbers a line)
    -1.0 1.0
    -0.5 0.5
    -0.5 0.5
    ITEM: ATOMS id x y z vx rho
    1 0.1 0.0 0.0 0.5 1.0
    ...

Atom blocks are converted with ``numpy.fromstring`` in one call (a frame of
10^6 atoms with 9 columns takes about one second).  Files ending in ``.gz`` are read
through :mod:`gzip`.
"""

import collections
import gzip
import os
import warnings

import numpy as np

__all__ = ["Frame", "read_frames", "read_last_frame"]

Frame = collections.namedtuple("Frame", ["timestep", "time", "box", "columns"])
Frame.__doc__ = """One dump frame.

timestep : int
time : float or None
    Simulation time from the ``ITEM: TIME`` section, None if the dump has none.
box : numpy.ndarray, shape (3, 2)
    ``[[xlo, xhi], [ylo, yhi], [zlo, zhi]]`` as written in ``ITEM: BOX BOUNDS``
    (for a restricted triclinic box these are the bounding-box values; the tilt
    factors are not kept).
columns : dict
    Column name -> numpy.ndarray of length N.  ``id``, ``type``, ``mol``,
    ``proc`` and ``procp1`` are int64, other numeric columns float64, and
    non-numeric columns (e.g. ``element``) arrays of str.
"""

#: Columns LAMMPS always writes as integers.
INTEGER_COLUMNS = frozenset(["id", "type", "mol", "proc", "procp1"])

_CHUNK = 1 << 20
_FRAME_MARK = b"ITEM: TIMESTEP"


class _TruncatedFrame(Exception):
    """The file ends inside a frame (e.g. a dump still being written)."""


def _open(path):
    if str(path).endswith(".gz"):
        return gzip.open(path, "rb")
    return open(path, "rb")


def _value_line(stream, item):
    line = stream.readline()
    if not line:
        raise _TruncatedFrame(f"file ends after 'ITEM: {item}'")
    return line.strip()


def _atom_block(stream, natoms, names):
    """Read ``natoms`` lines with ``len(names)`` whitespace-separated values each."""
    lines = [stream.readline() for _ in range(natoms)]
    if natoms and not lines[-1].endswith(b"\n"):
        # An incomplete last line means the writer had not finished the frame.
        raise _TruncatedFrame(f"file ends inside the atom block ({natoms} atoms expected)")
    text = b"".join(lines)
    ncol = len(names)
    with warnings.catch_warnings():
        # fromstring warns (and stops early) on non-numeric text; checked via the size.
        warnings.simplefilter("ignore", DeprecationWarning)
        flat = np.fromstring(text, dtype=float, sep=" ") if text else np.empty(0)
    if flat.size == natoms * ncol:
        table = flat.reshape(natoms, ncol)
        columns = {}
        for k, name in enumerate(names):
            col = table[:, k]
            columns[name] = col.astype(np.int64) if name in INTEGER_COLUMNS else col.copy()
        return columns
    # Slow path: non-numeric columns (such as 'element') or malformed data.
    rows = text.decode().split()
    if len(rows) != natoms * ncol:
        raise ValueError(f"atom block has {len(rows)} values, expected {natoms} x {ncol}")
    table = np.array(rows, dtype=str).reshape(natoms, ncol)
    columns = {}
    for k, name in enumerate(names):
        try:
            col = table[:, k].astype(float)
        except ValueError:
            columns[name] = table[:, k]
            continue
        columns[name] = col.astype(np.int64) if name in INTEGER_COLUMNS else col
    return columns


def _read_frame(stream):
    """Parse the next frame from a binary stream; return None at a clean end of file."""
    time = None
    timestep = natoms = box = None
    started = False
    while True:
        line = stream.readline()
        if not line:
            if started:
                raise _TruncatedFrame("file ends inside a frame header")
            return None
        line = line.strip()
        if not line:
            continue
        if not line.startswith(b"ITEM:"):
            raise ValueError(f"unexpected line in dump header: {line[:80]!r}")
        started = True
        item = line[5:].strip().decode()
        if item == "UNITS":
            _value_line(stream, item)
        elif item == "TIME":
            time = float(_value_line(stream, item))
        elif item == "TIMESTEP":
            timestep = int(_value_line(stream, item))
        elif item == "NUMBER OF ATOMS":
            natoms = int(_value_line(stream, item))
        elif item.startswith("BOX BOUNDS"):
            if item.split()[2:4] == ["abc", "origin"]:
                raise ValueError("general triclinic boxes ('BOX BOUNDS abc origin') "
                                 "are not supported")
            box = np.array([[float(v) for v in _value_line(stream, item).split()[:2]]
                            for _ in range(3)])
        elif item.startswith("ATOMS"):
            if timestep is None or natoms is None or box is None:
                raise ValueError("'ITEM: ATOMS' before TIMESTEP, NUMBER OF ATOMS and BOX BOUNDS")
            names = item.split()[1:]
            return Frame(timestep, time, box, _atom_block(stream, natoms, names))
        else:
            raise ValueError(f"unknown dump section 'ITEM: {item}'")


def read_frames(path):
    """Yield every frame of the dump file ``path`` as a :class:`Frame`, in file order.

    A trailing incomplete frame (a dump still being written) is skipped with a
    ``RuntimeWarning``.
    """
    with _open(path) as stream:
        while True:
            try:
                frame = _read_frame(stream)
            except _TruncatedFrame as exc:
                warnings.warn(f"{path}: skipping incomplete last frame ({exc})", RuntimeWarning)
                return
            if frame is None:
                return
            yield frame


def _frame_starts_before(f, end):
    """Offset of the last frame that starts before byte ``end``, or None.

    Searches backwards for a line ``ITEM: TIMESTEP`` and then steps back over
    the ``ITEM: TIME`` / ``ITEM: UNITS`` sections LAMMPS writes in front of it.
    """
    pos = end
    overlap = len(_FRAME_MARK)
    while pos > 0:
        lo = max(0, pos - _CHUNK)
        f.seek(lo)
        buf = f.read(min(end, pos + overlap) - lo)
        hit = len(buf)
        while True:
            hit = buf.rfind(_FRAME_MARK, 0, hit)
            if hit < 0:
                break
            at = lo + hit
            if at < end and (at == 0 or buf[hit - 1:hit] == b"\n"):
                return _step_back_over_prefix(f, at)
        pos = lo
    return None


def _step_back_over_prefix(f, start):
    """Move ``start`` back over preceding ``ITEM: TIME``/``ITEM: UNITS`` value pairs."""
    while start > 0:
        lo = max(0, start - 4096)
        f.seek(lo)
        lines = f.read(start - lo).split(b"\n")[:-1]      # text ends with "\n"
        if len(lines) < 2 or lines[-2].strip() not in (b"ITEM: TIME", b"ITEM: UNITS"):
            break
        start -= len(lines[-1]) + len(lines[-2]) + 2
    return start


def read_last_frame(path):
    """Return the last complete frame of the dump file ``path`` as a :class:`Frame`.

    For uncompressed files only the last frame is parsed (the file is searched
    backwards), so long dumps of large systems are cheap.  If the final frame
    is incomplete, the previous one is returned with a ``RuntimeWarning``.
    """
    if str(path).endswith(".gz"):
        last = None
        for last in read_frames(path):
            pass
        if last is None:
            raise ValueError(f"{path}: no complete frame")
        return last
    with open(path, "rb") as f:
        end = f.seek(0, os.SEEK_END)
        while True:
            start = _frame_starts_before(f, end)
            if start is None:
                raise ValueError(f"{path}: no complete frame")
            f.seek(start)
            try:
                frame = _read_frame(f)
            except _TruncatedFrame as exc:
                warnings.warn(f"{path}: last frame incomplete ({exc}); using the previous one",
                              RuntimeWarning)
                end = start
                continue
            if frame is None:
                raise ValueError(f"{path}: no complete frame")
            return frame
