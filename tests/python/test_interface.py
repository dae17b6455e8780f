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

    def test_external_wrenches_are_an_estimate_kind(self):
        robot = wbi.DdsInterface(robot="nobody", urdf=ARM, joints=["joint_1"])
        self.assertIn("external_wrench", wbi.EstimateKind.__members__)
        with self.assertRaisesRegex(wbi.Error, "not initialized"):
            robot.external_wrench_links
        with self.assertRaisesRegex(wbi.Error, "not initialized"):
            robot.read_estimates(wbi.EstimateKind.external_wrench)

    def test_reads_and_outputs_check_sizes(self):
        robot = wbi.DdsInterface(robot="nobody", urdf=ARM, joints=["joint_1"])
        with self.assertRaisesRegex(ValueError, "out must be a writable contiguous vector of"):
            robot.read_estimates(wbi.EstimateKind.joint_position, out=np.zeros(5))

    def test_robot_state_arrays_are_views_on_one_structure(self):
        robot = wbi.DdsInterface(robot="nobody", urdf=ARM, joints=["joint_1", "joint_2"])
        state = robot.robot_state()
        self.assertEqual(state.q.shape, (2,))
        self.assertEqual(state.world_H_base.shape, (4, 4))
        self.assertEqual(state.base_velocity.shape, (6,))
        # Each access is a view on the same C++ storage, read-only: no copy per tick.
        self.assertEqual(state.q.ctypes.data, state.q.ctypes.data)
        self.assertFalse(state.dq.flags.writeable)
        with self.assertRaisesRegex(wbi.Error, "not initialized"):
            robot.read_robot_state(state)
        other = wbi.DdsInterface(robot="nobody", urdf=ARM, joints=["joint_1"])
        with self.assertRaisesRegex(ValueError, "has 2 joints, the interface 1"):
            other.read_robot_state(state)


if __name__ == "__main__":
    unittest.main(argv=sys.argv, verbosity=2)
