#!/usr/bin/python3
"""The model library from Python, standalone: load a URDF and evaluate the
dynamics and kinematics in the mixed representation (no robot, no DDS).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/model_tour.py [URDF] [FRAME]

Prints the sizes, the mass matrix's diagonal, gravity forces, a frame's pose
and Jacobian, the CoM and the centroidal momentum at a random state, and checks
that forward dynamics inverts inverse dynamics.
"""

import pathlib
import sys

import numpy as np

import wbi

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main(argv):
    urdf = argv[1] if len(argv) > 1 else str(ROOT / "models" / "humanoid.urdf")
    model = wbi.Model.from_urdf(urdf)
    frame = argv[2] if len(argv) > 2 else model.frame_names[-1]
    print(model, f"nq = {model.nq}, nv = {model.nv}, mass {model.total_mass:.3f} kg")

    rng = np.random.default_rng(0)
    world_H_base = np.eye(4)
    world_H_base[:3, 3] = [0.0, 0.0, 1.0]
    joints = rng.uniform(-0.5, 0.5, model.n_joints)
    q = model.configuration(world_H_base, joints) if model.floating_base else joints
    nu = rng.uniform(-1.0, 1.0, model.nv)  # (base linear, base angular: world axes; joints)
    np.set_printoptions(precision=4, suppress=True, linewidth=110)

    M = model.mass_matrix(q)
    print("diag M:", np.diag(M))
    print("G(q):", model.gravity_forces(q))
    print(f"world_H_{frame}:\n{model.frame_pose(q, frame)}")
    J = model.jacobian(q, frame)
    print(f"J_{frame} nu (linear, angular velocity):", J @ nu)
    print("CoM:", model.com(q), " centroidal momentum:", model.centroidal_momentum(q, nu))

    dnu = rng.uniform(-1.0, 1.0, model.nv)
    tau = model.inverse_dynamics(q, nu, dnu)
    error = np.abs(model.forward_dynamics(q, nu, tau) - dnu).max()
    print(f"|ABA(RNEA(dnu)) - dnu| = {error:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
