"""The ``--assert`` bounds of the analysis scripts: one parser, one check, one report.

A bounds specification is ``name=bound,name=bound,...``. Each named figure must be at most
its bound (an upper bound), or at least it for the names the script declares as lower
bounds; a nan, missing or non-finite figure fails. Every check prints one line::

    check rshock = 0.0512 <= 0.056: ok
    check umin = -1e-05 >= 0: FAILED

and :func:`report` prints the closing line and gives the exit status (0 all passed, 1 some
failed). A malformed specification or an unknown name is a usage error (``parser.error``:
exit status 2).

Typical use in a script::

    from sphastro import cli
    cli.add_assert_argument(parser, "e.g. rho=0.02,vx=0.03")
    ...
    if args.bounds:
        return cli.assert_bounds(args.bounds, {"rho": err["rho"], ...}, error=parser.error)
"""

import math

__all__ = ["add_assert_argument", "parse_bounds", "check_bounds", "report", "assert_bounds"]


def add_assert_argument(parser, help_text="fail (exit 1) unless every listed figure is within "
                        "its bound: name=bound,...", flag="--assert", dest="bounds"):
    """Add the ``--assert NAME=BOUND,...`` option (stored in ``args.bounds``) to ``parser``."""
    parser.add_argument(flag, dest=dest, default=None, metavar="NAME=BOUND,...", help=help_text)


def parse_bounds(spec):
    """``'a=1,b=2e-3'`` -> ``[('a', 1.0), ('b', 0.002)]`` (empty items are skipped).

    Raises ValueError for an item that is not ``name=number``."""
    bounds = []
    for item in spec.split(","):
        if not item.strip():
            continue
        name, sep, bound = item.partition("=")
        name = name.strip()
        try:
            if not sep or not name:
                raise ValueError
            value = float(bound)
        except ValueError:
            raise ValueError(f"--assert: '{item.strip()}' is not name=number") from None
        if math.isnan(value):
            raise ValueError(f"--assert: the bound of '{name}' is nan")
        bounds.append((name, value))
    return bounds


def _finite(value):
    try:
        return value is not None and math.isfinite(float(value))
    except (TypeError, ValueError):
        return False


def check_bounds(spec, values, lower=(), unavailable=None, conditions=None, error=None):
    """Check the figures named in ``spec`` against their bounds; print one line per check.

    values : dict name -> figure (a float; None or nan fails)
    lower : names whose bound is a LOWER bound (figure >= bound)
    unavailable : dict name -> reason, for figures this run cannot measure (e.g.
        ``{"energy": "needs --log"}``): naming one is a usage error
    conditions : dict description -> bool, further requirements checked with any bounds
        (e.g. ``{"particles in the measured window": n > 0}``), printed as ``check
        <description>: ok|FAILED``
    error : callable taking a message (``parser.error``) for usage errors; default: raise
        ValueError

    Returns the list of the names (and condition descriptions) that failed."""
    def usage(message):
        if error is None:
            raise ValueError(message)
        error(message)
        raise ValueError(message)        # error() returned: do not go on silently

    unavailable = unavailable or {}
    try:
        bounds = parse_bounds(spec)
    except ValueError as exc:
        usage(str(exc))
    failed = []
    for name, bound in bounds:
        if name in unavailable:
            usage(f"--assert: '{name}' {unavailable[name]}")
        if name not in values:
            usage(f"--assert: unknown figure '{name}' (known: {', '.join(sorted(values))})")
        value = values[name]
        shown = f"{float(value):.4g}" if value is not None else "None"
        if name in lower:
            ok = _finite(value) and float(value) >= bound
            text = f"check {name} = {shown} >= {bound:.4g}"
        else:
            ok = _finite(value) and float(value) <= bound
            text = f"check {name} = {shown} <= {bound:.4g}"
        print(f"{text}: {'ok' if ok else 'FAILED'}")
        if not ok:
            failed.append(name)
    for description, ok in (conditions or {}).items():
        print(f"check {description}: {'ok' if ok else 'FAILED'}")
        if not ok:
            failed.append(description)
    return failed


def report(failed, what="bounds"):
    """Print ``<what>: passed`` or ``<what>: FAILED (<names>)``; return the exit status."""
    if failed:
        print(f"{what}: FAILED ({', '.join(failed)})")
        return 1
    print(f"{what}: passed")
    return 0


def assert_bounds(spec, values, lower=(), unavailable=None, conditions=None, error=None,
                  what="bounds"):
    """:func:`check_bounds` then :func:`report`: the exit status of an ``--assert``."""
    return report(check_bounds(spec, values, lower, unavailable, conditions, error), what)
