"""A planner in another process drives the balancer (issue 36): `wbi launch
deploy/balance_planner.yaml` runs the humanoid, its estimator and the balancer
in lockstep; python/examples/com_planner.py, a separate Python process, reads
the state and publishes the CoM reference at 100 Hz of robot time on
wbi/humanoid/references/balance/com. The balancer follows it: the CoM swings
by the planner's ±5 cm and tracks it within millimetres; the host counts the
points it got and the ticks it carried them over."""

import re
import sys
import unittest

import support


def numbers_after(pattern, text):
    return [float(v) for v in re.findall(pattern, text)]


class PlannerDrivesTheBalancer(unittest.TestCase):
    def test_the_com_follows_the_planners_sinusoid(self):
        launch = support.start([support.BINARY_DIR / "bin" / "wbi", "launch",
                                support.SOURCE_DIR / "deploy" / "balance_planner.yaml",
                                "--duration", "150"])
        planner = support.start([sys.executable, support.SOURCE_DIR / "python" / "examples" /
                                 "com_planner.py", "--urdf",
                                 support.project_model("humanoid.urdf")])
        try:
            launch.wait(timeout=150)  # the balancer ends the run after 21 s of robot time
        finally:
            output = support.stop(launch)
            planner_output = support.stop(planner)
        self.assertEqual(launch.returncode, 0, output)
        self.assertIn("com_planner: wbi/humanoid/references/balance/com at 100 Hz",
                      planner_output)

        points = numbers_after(r"reference balance/com: (\d+) points", output)
        self.assertEqual(len(points), 1, output)
        self.assertGreater(points[0], 1000, output)  # ≥ 10 s of robot time at 100 Hz
        carried = numbers_after(r"ticks: (\d+) carried", output)
        self.assertGreater(carried[0], 5 * points[0], output)  # 1 kHz ticks between 100 Hz points

        # The CoM's lateral position, once a second: the planner's swing, ±5 cm.
        com_y = numbers_after(r"\] t = +[\d.]+ s  com \([-\d.]+, ([-\d.]+),", output)
        self.assertGreater(len(com_y), 15, output)
        self.assertGreater(max(com_y) - min(com_y), 0.06, output)

        rms = numbers_after(r"com tracking rms: ([\d.]+) m", output)
        worst = numbers_after(r"max com error: ([\d.]+) m", output)
        self.assertLess(rms[0], 0.003, output)   # generator in step: 1.28 mm
        self.assertLess(worst[0], 0.01, output)


if __name__ == "__main__":
    unittest.main()
