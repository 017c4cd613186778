"""Tests of sphastro.evrard: thermo rows of examples/evrard/in.evrard and the particle-updates
of an individual-step run against a global-step run."""

import os
import tempfile
import unittest

from sphastro import evrard

HEADER = ("Step Time Dt c_sum[8] c_sum[9] c_sum[10] c_sum[11] c_sum[12] c_sum[13] c_sum[14] "
          "f_hvar[3] f_hvar[4] f_hvar[5] v_updates {own}CPU")


def write_log(path, rows, own=False):
    """A LAMMPS log with one run of thermo rows (step, time, updates[, own-rate updates])."""
    with open(path, "w") as fh:
        fh.write("LAMMPS (4 Feb 2025)\n" + HEADER.format(own="v_ownupdates " if own else "") + "\n")
        for row in rows:
            step, time, updates = row[:3]
            extra = f" {row[3]}" if own else ""
            fh.write(f"{step} {time} 0.01 0.1 0.2 -0.9 -0.6 1e-4 0.05 0.3 0 0 0 {updates}{extra} "
                     "1.0\n")
        fh.write("Loop time of 1.0 on 1 procs for 10 steps with 100 atoms\n"
                 "Total wall time: 0:00:02\n")


class UpdatesAgainstTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        glob = os.path.join(self.dir.name, "log.global")
        ind = os.path.join(self.dir.name, "log.individual")
        # global: 100 particles, 10 steps to t 1 (own rates need 40 % of the updates);
        # individual: 300 updates to t 0.5, 600 to t 1
        write_log(glob, [(0, 0.0, 0, 0), (5, 0.5, 500, 200), (10, 1.0, 1000, 400)], own=True)
        write_log(ind, [(0, 0.0, 0), (4, 0.5, 300), (9, 1.0, 600)])
        self.glob, _ = evrard.read_log(glob)
        self.ind, self.wall = evrard.read_log(ind)

    def tearDown(self):
        self.dir.cleanup()

    def test_reads_the_updates_column(self):
        self.assertEqual([r["v_updates"] for r in self.ind], [0, 300, 600])
        self.assertEqual(self.wall, 2)

    def test_times_fewer_at_the_same_time(self):
        updates, fewer, own_fewer = evrard.updates_against(self.ind, self.glob, 1.0)
        self.assertEqual(updates, 600)
        self.assertAlmostEqual(fewer, 1000 / 600)
        self.assertAlmostEqual(own_fewer, 1000 / 400)
        # between thermo rows: linear in time (t 0.75: 450 against 750)
        updates, fewer, _ = evrard.updates_against(self.ind, self.glob, 0.75)
        self.assertAlmostEqual(updates, 450)
        self.assertAlmostEqual(fewer, 750 / 450)

    def test_without_a_reference_or_past_the_end(self):
        self.assertEqual(evrard.updates_against(self.ind, None, 0.5), (300, None, None))
        self.assertEqual(evrard.updates_against(self.ind, self.glob, 1.5), (None, None, None))
        # the reference without own-rate column, and at t 0 (no updates yet)
        plain = [{k: v for k, v in r.items() if k != "v_ownupdates"} for r in self.glob]
        self.assertIsNone(evrard.updates_against(self.ind, plain, 1.0)[2])
        self.assertEqual(evrard.updates_against(self.ind, self.glob, 0.0), (0, None, None))


if __name__ == "__main__":
    unittest.main()
