"""Joint claims from Python (issue 22 item 1): a script that asks for a joint
another controller holds gets wbi.Error naming the joint and its owner, before
it sends anything; a forced claim takes the joint, and the previous owner's next
command fails naming the new one. The robot (sim_robot, the arm) and its
estimator run in a wbi_host process of their own."""

import pathlib
import sys
import tempfile
import threading
import time
import unittest

import support
import wbi

URDF = str(support.project_model("arm7.urdf"))


class JointClaims(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        host_file = pathlib.Path(cls.dir.name) / "arm.yaml"
        host_file.write_text(
            "components:\n"
            "  - {name: arm, type: sim_robot, parameters: {robot: arm_claims, config: "
            f"{support.SOURCE_DIR / 'deploy' / 'robots' / 'arm.yaml'}}}}}\n"
            "  - {name: estimator, type: estimator, parameters: {robot: arm_claims}}\n")
        cls.host = support.start([support.BINARY_DIR / "bin" / "wbi_host", host_file])

    @classmethod
    def tearDownClass(cls):
        support.stop(cls.host)
        cls.dir.cleanup()

    def interface(self, controller, joints, claim="claim"):
        robot = wbi.DdsInterface(robot="arm_claims", urdf=URDF, joints=joints,
                                 controller=controller, claim=claim, max_age_s=1.0)
        robot.init(30.0)
        return robot

    def test_a_held_joint_is_refused_then_taken_by_force(self):
        owner = self.interface("pd", ["joint_1", "joint_2"])
        owner.set_control_mode(wbi.ControlMode.position_direct)
        # The owner streams (a claim whose owner is silent for the watchdog
        # time ends), until a command of its fails.
        failure = []

        def stream():
            deadline = time.monotonic() + 60.0
            while time.monotonic() < deadline:
                try:
                    owner.set_control_reference([0.0, 0.0])
                except wbi.Error as error:
                    failure.append(str(error))
                    return
                time.sleep(0.002)

        streaming = threading.Thread(target=stream)
        streaming.start()
        try:
            with self.assertRaises(wbi.Error) as refused:
                self.interface("rogue", ["joint_2", "joint_3"])
            self.assertIn("claim of 'rogue' refused: joint_2 (held by 'pd')",
                          str(refused.exception))
            supervisor = self.interface("supervisor", ["joint_2"], claim="force")
        finally:
            streaming.join(timeout=70.0)
        self.assertEqual(len(failure), 1, "the owner's commands went on after the takeover")
        self.assertIn("joint 'joint_2' is held by 'supervisor'", failure[0])
        supervisor.close()

    def test_a_bad_claim_keyword_is_named(self):
        with self.assertRaises(ValueError) as bad:
            wbi.DdsInterface(robot="arm_claims", urdf=URDF, claim="mine")
        self.assertIn("claim is 'mine'", str(bad.exception))


if __name__ == "__main__":
    unittest.main(argv=sys.argv, verbosity=2)
