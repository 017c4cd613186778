"""Tests of sphastro.cli: the --assert bounds shared by the analysis scripts."""

import argparse
import contextlib
import io
import math
import unittest

from sphastro import cli


def quiet(fn, *args, **kw):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        result = fn(*args, **kw)
    return result, out.getvalue()


class ParseTest(unittest.TestCase):
    def test_items(self):
        self.assertEqual(cli.parse_bounds("a=1, b=2e-3,,"), [("a", 1.0), ("b", 0.002)])

    def test_malformed(self):
        for spec in ("a", "a=", "=1", "a=x", "a=nan"):
            with self.assertRaises(ValueError, msg=spec):
                cli.parse_bounds(spec)


class CheckTest(unittest.TestCase):
    def test_upper_and_lower_bounds(self):
        failed, out = quiet(cli.check_bounds, "err=0.1,umin=0", {"err": 0.05, "umin": -1e-5},
                            lower=("umin",))
        self.assertEqual(failed, ["umin"])
        self.assertIn("check err = 0.05 <= 0.1: ok", out)
        self.assertIn("check umin = -1e-05 >= 0: FAILED", out)

    def test_nan_and_none_fail(self):
        failed, _ = quiet(cli.check_bounds, "a=1,b=1,c=1",
                          {"a": math.nan, "b": None, "c": math.inf})
        self.assertEqual(failed, ["a", "b", "c"])

    def test_conditions(self):
        failed, out = quiet(cli.check_bounds, "a=1", {"a": 0.5},
                            conditions={"particles measured": False})
        self.assertEqual(failed, ["particles measured"])
        self.assertIn("check particles measured: FAILED", out)

    def test_unknown_and_unavailable_names_are_usage_errors(self):
        parser = argparse.ArgumentParser()
        with self.assertRaises(SystemExit) as cm, contextlib.redirect_stderr(io.StringIO()):
            cli.check_bounds("nope=1", {"a": 1.0}, error=parser.error)
        self.assertEqual(cm.exception.code, 2)
        with self.assertRaises(ValueError):
            quiet(cli.check_bounds, "energy=1", {"a": 1.0},
                  unavailable={"energy": "needs --log"})

    def test_exit_status(self):
        self.assertEqual(quiet(cli.assert_bounds, "a=1", {"a": 1.0})[0], 0)
        status, out = quiet(cli.assert_bounds, "a=1", {"a": 1.5})
        self.assertEqual(status, 1)
        self.assertIn("bounds: FAILED (a)", out)


if __name__ == "__main__":
    unittest.main()
