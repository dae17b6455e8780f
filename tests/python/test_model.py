"""wbi.Model agrees with the C++ model library: every quantity `wbi model eval`
prints (M, h, G, CoM, centroidal momentum, frame poses, Jacobians, dJν) at
random states of the project's arm and humanoid and of iCub (../shared), and the
quantities eval does not print (inverse and forward dynamics, A_G, J_com)
through the identities that tie them to those."""

import json
import sys
import unittest

import numpy as np

import support
import wbi

RNG = np.random.default_rng(7)


def random_state(model):
    """q, ν and the `wbi model eval` state giving the same configuration."""
    n = model.n_joints
    joints = RNG.uniform(-1.0, 1.0, n)
    dq = RNG.uniform(-2.0, 2.0, n)
    state = {"q": joints.tolist(), "dq": dq.tolist(), "gravity": [0.1, -0.2, -9.7]}
    if not model.floating_base:
        return joints, dq, state
    position = RNG.uniform(-1.0, 1.0, 3)
    quaternion = RNG.normal(size=4)
    quaternion /= np.linalg.norm(quaternion)
    base_velocity = RNG.uniform(-1.0, 1.0, 6)
    state.update(base_position=position.tolist(), base_quaternion=quaternion.tolist(),
                 base_velocity=base_velocity.tolist())
    return (np.concatenate([position, quaternion, joints]), np.concatenate([base_velocity, dq]),
            state)


def cpp_eval(urdf, state, joints=None):
    args = [support.BINARY_DIR / "bin" / "wbi", "model", "eval", urdf, "--state", "-"]
    if joints:
        args += ["--joints", ",".join(joints)]
    result = support.run(args, timeout_s=60, stdin=json.dumps(state))
    if result.returncode != 0:
        raise AssertionError(f"wbi model eval failed: {result.stderr}")
    return json.loads(result.stdout)


class AgreesWithCpp(unittest.TestCase):
    def check_model(self, urdf, joints=None, states=3):
        model = wbi.Model.from_urdf(str(urdf), joints=joints)
        frames = model.frame_names
        picked = sorted({frames[0], frames[len(frames) // 2], frames[-1]})
        gravity = np.array([0.1, -0.2, -9.7])
        for _ in range(states):
            q, nu, state = random_state(model)
            state["frames"] = picked
            expected = cpp_eval(urdf, state, joints)
            close = dict(rtol=1e-12, atol=1e-12)
            self.assertEqual(expected["joints"], model.joint_names)
            np.testing.assert_allclose(model.mass_matrix(q), expected["mass_matrix"], **close)
            np.testing.assert_allclose(model.bias_forces(q, nu, gravity), expected["bias_forces"],
                                       **close)
            np.testing.assert_allclose(model.gravity_forces(q, gravity),
                                       expected["gravity_forces"], **close)
            self.assertAlmostEqual(model.total_mass, expected["total_mass"], places=12)
            np.testing.assert_allclose(model.com(q), expected["com"], **close)
            np.testing.assert_allclose(model.centroidal_momentum(q, nu),
                                       expected["centroidal_momentum"], **close)
            for frame in picked:
                np.testing.assert_allclose(model.frame_pose(q, frame),
                                           expected["frames"][frame]["transform"], **close)
                np.testing.assert_allclose(model.jacobian(q, frame),
                                           expected["frames"][frame]["jacobian"], **close)
                np.testing.assert_allclose(model.dj_nu(q, nu, frame),
                                           expected["frames"][frame]["dJnu"], **close)
            self.check_identities(model, q, nu, gravity)

    def check_identities(self, model, q, nu, gravity):
        """ID, ABA, A_G and J_com against the quantities compared above."""
        M = model.mass_matrix(q)
        h = model.bias_forces(q, nu, gravity)
        dnu = RNG.uniform(-1.0, 1.0, model.nv)
        tau = model.inverse_dynamics(q, nu, dnu, gravity)
        np.testing.assert_allclose(tau, M @ dnu + h, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(model.forward_dynamics(q, nu, tau, gravity), dnu, rtol=1e-7,
                                   atol=1e-7)
        A = model.centroidal_momentum_matrix(q)
        np.testing.assert_allclose(A @ nu, model.centroidal_momentum(q, nu), rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(model.com_jacobian(q), A[:3] / model.total_mass, rtol=1e-9,
                                   atol=1e-9)
        # A wrench at a frame enters as −Jᵀw.
        frame = model.frame_names[-1]
        wrench = RNG.uniform(-5.0, 5.0, 6)
        with_wrench = model.inverse_dynamics(q, nu, dnu, gravity, wrenches={frame: wrench})
        np.testing.assert_allclose(with_wrench, tau - model.jacobian(q, frame).T @ wrench,
                                   rtol=1e-9, atol=1e-9)

    def test_arm(self):
        self.check_model(support.project_model("arm7.urdf"))

    def test_humanoid(self):
        self.check_model(support.project_model("humanoid.urdf"))

    def test_reduced_humanoid(self):
        model = wbi.Model.from_urdf(str(support.project_model("humanoid.urdf")))
        joints = model.joint_names[::3][:6]
        self.check_model(support.project_model("humanoid.urdf"), joints=joints, states=2)

    def test_icub(self):
        urdf = support.shared_model("iCubGenova09", "model.urdf")
        if urdf is None:
            print(support.SHARED_MISSING)
            self.skipTest(support.SHARED_MISSING)
        self.check_model(urdf, states=2)


class Inputs(unittest.TestCase):
    """No copies for float64 inputs; clear errors for bad ones."""

    def setUp(self):
        self.model = wbi.Model.from_urdf(str(support.project_model("humanoid.urdf")))

    def test_armature_adds_to_the_diagonal_of_the_mass_matrix_only(self):
        urdf = support.SOURCE_DIR / "models" / "arm7.urdf"
        plain = wbi.Model.from_urdf(str(urdf), fixed_base=True)
        geared = wbi.Model.from_urdf(str(urdf), fixed_base=True,
                                     armature={"joint_2": 0.25, "joint_5": 0.1})
        q = RNG.uniform(-1.0, 1.0, plain.nq)
        nu = RNG.uniform(-1.0, 1.0, plain.nv)
        added = np.zeros(plain.nv)
        added[1], added[4] = 0.25, 0.1
        np.testing.assert_allclose(geared.mass_matrix(q) - plain.mass_matrix(q), np.diag(added),
                                   atol=1e-12)
        np.testing.assert_allclose(geared.bias_forces(q, nu), plain.bias_forces(q, nu), atol=1e-12)
        with self.assertRaises(Exception):
            wbi.Model.from_urdf(str(urdf), fixed_base=True, armature={"no_such_joint": 1.0})

    def test_out_arrays_are_filled_in_place(self):
        q = self.model.neutral_configuration()
        M = np.zeros((self.model.nv, self.model.nv), order="F")
        result = self.model.mass_matrix(q, out=M)
        self.assertIs(result, M)
        np.testing.assert_array_equal(M, self.model.mass_matrix(q))
        g = np.zeros(self.model.nv)
        self.assertIs(self.model.gravity_forces(q, out=g), g)
        with self.assertRaisesRegex(ValueError, "Fortran-ordered"):
            self.model.mass_matrix(q, out=np.zeros((self.model.nv, self.model.nv)))

    def test_bad_inputs_name_what_is_wrong(self):
        q = self.model.neutral_configuration()
        with self.assertRaisesRegex(ValueError, "'q' has size 3"):
            self.model.mass_matrix(np.zeros(3))
        with self.assertRaisesRegex(ValueError, "unknown frame 'no_such_frame'"):
            self.model.jacobian(q, "no_such_frame")
        with self.assertRaisesRegex(IndexError, "frame index 100000"):
            self.model.jacobian(q, 100000)
        with self.assertRaisesRegex(ValueError, "no_such_joint"):
            wbi.Model.from_urdf(str(support.project_model("humanoid.urdf")),
                                joints=["no_such_joint"])
        with self.assertRaisesRegex(ValueError, "missing.urdf"):
            wbi.Model.from_urdf("missing.urdf")

    def test_configuration_from_a_base_pose(self):
        pose = np.eye(4)
        pose[:3, 3] = [1.0, 2.0, 3.0]
        q = self.model.configuration(pose, np.zeros(self.model.n_joints))
        np.testing.assert_allclose(q[:7], [1, 2, 3, 1, 0, 0, 0])
        np.testing.assert_allclose(self.model.frame_pose(q, self.model.frame_names[0])[:3, 3],
                                   [1, 2, 3], atol=1e-12)


if __name__ == "__main__":
    unittest.main(argv=sys.argv, verbosity=2)
