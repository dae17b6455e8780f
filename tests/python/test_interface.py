"""wbi.DdsInterface over real DDS: options as keyword arguments, and the errors
of the C++ interface as wbi.Error / wbi.TimeoutError naming what is wrong."""

import sys
import unittest

import numpy as np

import support
import wbi

ARM = str(support.project_model("arm7.urdf"))


class DdsInterfaceTest(unittest.TestCase):
    def test_options_are_checked(self):
        with self.assertRaisesRegex(wbi.Error, "(?i)urdf"):
            wbi.DdsInterface(robot="nobody")
        with self.assertRaisesRegex(ValueError, "model is 'cloud'; expected local or remote"):
            wbi.DdsInterface(robot="nobody", urdf=ARM, model="cloud")
        with self.assertRaisesRegex(wbi.Error, "joint 'joint_1' added twice"):
            wbi.DdsInterface(robot="nobody", urdf=ARM, joints=["joint_1", "joint_1"])

    def test_init_names_the_missing_robot(self):
        robot = wbi.DdsInterface(robot="nobody", urdf=ARM, joints=["joint_1", "joint_2"])
        self.assertEqual(robot.dofs, 2)
        self.assertEqual(robot.joint_list, ["joint_1", "joint_2"])
        with self.assertRaisesRegex(wbi.TimeoutError, "nobody"):
            robot.init(timeout_s=0.3)
        with self.assertRaises(wbi.Error):
            robot.read_estimates(wbi.EstimateKind.joint_position)

    def test_reads_and_outputs_check_sizes(self):
        robot = wbi.DdsInterface(robot="nobody", urdf=ARM, joints=["joint_1"])
        with self.assertRaisesRegex(ValueError, "out must be a writable contiguous vector of"):
            robot.read_estimates(wbi.EstimateKind.joint_position, out=np.zeros(5))


if __name__ == "__main__":
    unittest.main(argv=sys.argv, verbosity=2)
