#!/usr/bin/env python3
"""Tests of binomial.py against tails known in closed form."""
import math
import pathlib
import sys
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import binomial  # noqa: E402


class BinomialTest(unittest.TestCase):
    def test_a_fair_coins_lower_tail(self):
        # 1 + 10 + 45 of the 1024 outcomes of ten tosses have at most two heads.
        self.assertAlmostEqual(binomial.at_most(10, 2), 56 / 1024, delta=1e-16)
        self.assertEqual(binomial.at_most(10, -1), 0.0)
        self.assertEqual(binomial.at_most(10, 10), 1.0)

    def test_an_upper_tail_keeps_its_small_values(self):
        # P(B >= n) = p^n, far below what 1 - P(B < n) could hold.
        self.assertAlmostEqual(binomial.at_least(30, 30, 0.01) / 1e-60, 1.0, delta=1e-12)
        self.assertEqual(binomial.at_least(30, 0, 0.01), 1.0)
        # Twenty frames of which a tenth are lost: at least one lost, 1 - 0.9^20.
        self.assertAlmostEqual(binomial.at_least(20, 1, 0.1), 1 - 0.9**20, delta=1e-15)

    def test_the_sign_test_is_two_sided_and_symmetric(self):
        self.assertAlmostEqual(binomial.two_sided_sign_p(10, 0), 2 / 1024, delta=1e-16)
        self.assertEqual(binomial.two_sided_sign_p(10, 3), binomial.two_sided_sign_p(10, 7))
        self.assertAlmostEqual(binomial.two_sided_sign_p(10, 3), 2 * 176 / 1024, delta=1e-15)
        self.assertEqual(binomial.two_sided_sign_p(10, 5), 1.0)  # 2 P(B <= 5) > 1, capped
        self.assertEqual(binomial.two_sided_sign_p(0, 0), 1.0)

    def test_the_tails_sum_to_one(self):
        for n, p in ((7, 0.5), (40, 0.3), (101, 0.02)):
            for k in range(n + 1):
                self.assertTrue(math.isclose(binomial.at_most(n, k - 1, p) +
                                             binomial.at_least(n, k, p), 1.0, rel_tol=1e-12))


if __name__ == "__main__":
    unittest.main()
