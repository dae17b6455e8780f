"""Controllers driven from Python (issue 36): wbi.ControllerHost lists the
controllers of deploy/arm_controller_host.yaml while `wbi launch` runs it,
halves a gain and reads it back, is refused a value out of range with the
host's one line (and nothing changes), and switches the arm to hold."""

import time
import unittest

import support
import wbi


class ControllerHostFromPython(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.launch = support.start([support.BINARY_DIR / "bin" / "wbi", "launch",
                                    support.SOURCE_DIR / "deploy" / "arm_controller_host.yaml",
                                    "--duration", "60"])
        cls.host = wbi.ControllerHost("arm", timeout_s=5.0)
        deadline = time.monotonic() + 60.0
        while True:  # the host answers once its process is up, and has an
            try:     # active controller once its component is activated
                cls.host.controllers()
                if cls.host.active() is not None:
                    break
            except TimeoutError:
                pass
            if time.monotonic() > deadline:
                raise TimeoutError("the controller host of deploy/arm_controller_host.yaml "
                                   "had no active controller within 60 s")
            time.sleep(0.05)  # polling the service: no event to await from Python

    @classmethod
    def tearDownClass(cls):
        support.stop(cls.launch)

    def test_1_lists_the_controllers(self):
        names = {c["name"]: c for c in self.host.controllers()}
        self.assertEqual(set(names), {"pd", "hold"})
        self.assertEqual(names["pd"]["type"], "pd_gravity")
        self.assertEqual(self.host.active(), "pd")

    def test_2_sets_a_gain_and_refuses_a_bad_one(self):
        self.assertEqual(self.host.set("pd", "gain_scale", 0.5), "pd.gain_scale = 0.5")
        self.assertEqual(self.host.get("pd", "gain_scale"), 0.5)
        with self.assertRaises(ValueError) as refused:
            self.host.set("pd", "gain_scale", 20)
        self.assertEqual(str(refused.exception), "pd: gain_scale = 20 is outside [0, 10]")
        self.assertEqual(self.host.get("pd", "gain_scale"), 0.5)
        target = self.host.get("pd", "target")
        self.assertEqual(len(target), 7)
        with self.assertRaises(ValueError):
            self.host.set("pd", "target", [0.0, 0.0])  # one value per joint

    def test_3_switches_to_hold(self):
        with self.assertRaises(ValueError) as refused:
            self.host.switch(activate="balance", deactivate="pd")
        self.assertIn("unknown controller 'balance'", str(refused.exception))
        text = self.host.switch(activate="hold", deactivate="pd")
        self.assertTrue(text.startswith("pd → hold at t = "), text)
        self.assertEqual(self.host.active(), "hold")


if __name__ == "__main__":
    unittest.main()
