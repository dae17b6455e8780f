"""wbi.PeriodicLoop: step calls, stopping, and the counting of overruns."""

import sys
import time
import unittest

import wbi


class PeriodicLoopTest(unittest.TestCase):
    def test_runs_the_given_number_of_steps_with_increasing_times(self):
        times = []
        loop = wbi.PeriodicLoop(500)
        stats = loop.run(lambda t: times.append(t), iterations=20)
        self.assertEqual(stats.iterations, 20)
        self.assertEqual(len(times), 20)
        self.assertLess(times[0], 0.01)  # the first step runs at once
        self.assertTrue(all(b > a for a, b in zip(times, times[1:])))
        self.assertGreater(stats.period_mean_s, 0.0)
        self.assertGreaterEqual(stats.period_max_s, stats.period_mean_s)
        self.assertIn("20 iterations", str(stats))

    def test_step_returning_false_or_stop_ends_the_loop(self):
        loop = wbi.PeriodicLoop(1000)
        self.assertEqual(loop.run(lambda t: loop.statistics is None, iterations=100).iterations, 1)
        calls = []

        def step(t):
            calls.append(t)
            if len(calls) == 3:
                loop.stop()
        self.assertEqual(loop.run(step, duration_s=10.0).iterations, 3)

    def test_duration_bounds_the_run(self):
        stats = wbi.PeriodicLoop(1000).run(lambda t: None, duration_s=0.05)
        self.assertGreater(stats.iterations, 0)

    def test_a_late_step_is_an_overrun_and_skips_missed_deadlines(self):
        def step(t):
            if stats_calls.append(t) or len(stats_calls) == 5:
                time.sleep(0.0035)  # 3.5 periods: the next deadlines pass meanwhile
        stats_calls = []
        stats = wbi.PeriodicLoop(1000).run(step, iterations=10)
        self.assertGreaterEqual(stats.overruns, 1)
        self.assertGreaterEqual(stats.missed_deadlines, 2)
        self.assertGreaterEqual(stats.step_max_s, 0.0035)

    def test_bad_rate_is_named(self):
        with self.assertRaisesRegex(ValueError, "rate_hz is 0"):
            wbi.PeriodicLoop(0)


if __name__ == "__main__":
    unittest.main(argv=sys.argv, verbosity=2)
