"""The PD + gravity controller written in Python (examples/python/pd_gravity.py)
brings the demo's arm to its target: `wbi launch` runs the demo's robot and
estimator (wbi_host) and the Python controller as three processes, from the
deploy file the build generates (examples/python/pd_gravity.yaml.in)."""

import re
import sys
import unittest

import support


class PythonPdGravity(unittest.TestCase):
    def test_three_processes_bring_the_arm_to_its_target(self):
        deploy = support.BINARY_DIR / "examples" / "python" / "pd_gravity.yaml"
        result = support.run([support.BINARY_DIR / "bin" / "wbi", "launch", deploy,
                              "--duration", "6"], timeout_s=120)
        out = result.stdout + result.stderr
        self.assertEqual(result.returncode, 0, out)
        for process in ("robot", "estimator", "controller"):
            self.assertIn(f"[launch] {process}: started", out)
        # t is the loop's measured time (under load the line after 1 s may read
        # 1.01): the run's progress, not one line's text.
        times = [float(t) for t in re.findall(r"\[controller\] t = +([0-9.]+) s", out)]
        self.assertGreaterEqual(len(times), 2, f"no progress lines\n{out}")
        self.assertGreaterEqual(times[-1], 1.0, out)
        loop = re.search(r"\[controller\] loop: (\d+) iterations at ([\d.]+) Hz", out)
        self.assertIsNotNone(loop, out)
        self.assertGreater(int(loop.group(1)), 0)
        last = result.stdout.rstrip("\n").split("\n")[-1]
        match = re.fullmatch(r"final max joint error: (\S+) rad", last)
        self.assertIsNotNone(match, f"the error is not the last line:\n{out}")
        self.assertLess(float(match.group(1)), 0.01, out)


if __name__ == "__main__":
    unittest.main(argv=sys.argv, verbosity=2)
