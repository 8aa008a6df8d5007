#!/usr/bin/python3
"""Unit tests for bench/bdrate.py: synthetic curves with known answers."""
import math
import os
import sys
import unittest

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bdrate  # noqa: E402

# A typical geometry-codec curve: PSNR roughly linear in log(rate), slightly bent.
CURVE_A = [(0.25, 60.0), (0.5, 65.5), (1.0, 71.0), (2.0, 76.0), (3.0, 79.0), (4.0, 81.0)]


class BDRateTest(unittest.TestCase):
    def test_identical_curves_give_zero(self):
        pct, lo, hi = bdrate.bd_rate(CURVE_A, CURVE_A)
        self.assertAlmostEqual(pct, 0.0, places=9)
        self.assertEqual((lo, hi), (60.0, 81.0))

    def test_half_rate_gives_minus_fifty(self):
        b = [(r * 0.5, p) for r, p in CURVE_A]
        pct, _, _ = bdrate.bd_rate(CURVE_A, b)
        self.assertAlmostEqual(pct, -50.0, places=6)
        pct_back, _, _ = bdrate.bd_rate(b, CURVE_A)
        self.assertAlmostEqual(pct_back, 100.0, places=6)

    def test_shifted_psnr_on_log_linear_curve(self):
        # PSNR = 6.02 dB per doubling: a +6.02 dB shift is exactly half the rate.
        a = [(2.0 ** k, 50.0 + 6.02 * k) for k in range(6)]
        b = [(r, p + 6.02) for r, p in a]
        pct, lo, hi = bdrate.bd_rate(a, b)
        self.assertAlmostEqual(pct, -50.0, places=6)
        self.assertAlmostEqual(lo, 56.02)
        self.assertAlmostEqual(hi, 50.0 + 6.02 * 5)

    def test_fewer_than_four_points_lowers_degree(self):
        a = [(1.0, 60.0), (4.0, 72.0)]
        b = [(0.25, 60.0), (1.0, 72.0)]
        pct, _, _ = bdrate.bd_rate(a, b)
        self.assertAlmostEqual(pct, -75.0, places=6)

    def test_non_overlapping_raises(self):
        b = [(r, p + 40.0) for r, p in CURVE_A]
        with self.assertRaises(bdrate.BDError):
            bdrate.bd_rate(CURVE_A, b)
        with self.assertRaises(bdrate.BDError):
            bdrate.bd_rate(CURVE_A, [(1.0, 70.0)])

    def test_rate_at_psnr_and_ratio(self):
        self.assertAlmostEqual(bdrate.rate_at_psnr(CURVE_A, 71.0), 1.0)
        mid = bdrate.rate_at_psnr(CURVE_A, 73.5)
        self.assertAlmostEqual(mid, math.sqrt(2.0))
        self.assertIsNone(bdrate.rate_at_psnr(CURVE_A, 90.0))
        self.assertIsNone(bdrate.rate_at_psnr(CURVE_A, 50.0))
        b = [(r * 8.0, p) for r, p in CURVE_A]
        self.assertAlmostEqual(bdrate.size_ratio(b, CURVE_A, 70.0), 8.0)
        self.assertIsNone(bdrate.size_ratio(b, CURVE_A, 85.0))
        self.assertAlmostEqual(bdrate.psnr_at_rate(CURVE_A, math.sqrt(2.0)), 73.5)

    def test_pareto_front_merges_settings(self):
        pts = [(1.0, 70.0), (1.2, 69.0), (2.0, 75.0), (1.5, 74.0), (3.0, 74.5)]
        self.assertEqual(bdrate.pareto_front(pts), [(1.0, 70.0), (1.5, 74.0), (2.0, 75.0)])


if __name__ == "__main__":
    unittest.main()
