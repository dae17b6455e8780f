#!/usr/bin/python3
"""PD + gravity compensation in Python, the paper's first example:

    tau = G_j(q) - Kp (q - q_d) - Kd dq

through the whole-body interface over DDS, at 1 kHz by default, against the
demo's simulated arm (the robot and the estimator of deploy/demo.yaml). The
parameters are those of demo.yaml's pd_gravity component: the 7 arm joints,
the same target, gains for a critically damped 5 Hz response of every mode
from the joint inertia at the target (controllers/README.md, "Gains").

    wbi launch build/examples/python/pd_gravity.yaml          # robot, estimator, this
    python3 examples/python/pd_gravity.py --duration 5        # against a running robot

Prints the error once per second, the loop's timing, and last
`final max joint error: X rad`. PYTHONPATH must reach the wbi package
(build/python, or the installed site-packages).
"""

import argparse
import math
import pathlib
import signal
import sys

import numpy as np

import wbi

ARM_JOINTS = [f"joint_{i}" for i in range(1, 8)]
DEMO_TARGET = [0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0]
DEFAULT_URDF = pathlib.Path(__file__).resolve().parents[2] / "models" / "arm7.urdf"


class PdGravity:
    """One control tick per update(); the arrays are allocated once."""

    def __init__(self, robot, q_desired, kp, kd, gravity=(0.0, 0.0, -9.81)):
        n = robot.dofs
        self.robot = robot
        self.q_desired = np.asarray(q_desired, dtype=float)
        # kp, kd: n x n matrices, or n values for diagonal gains
        self.kp, self.kd = (np.diag(g) if np.ndim(g) == 1 else np.asarray(g, dtype=float)
                            for g in (np.asarray(kp, dtype=float), np.asarray(kd, dtype=float)))
        if self.q_desired.shape != (n,):
            raise ValueError(f"PD + gravity: q_desired has {self.q_desired.size} values, the "
                             f"robot has {n} controlled joints")
        for name, gain in (("kp", self.kp), ("kd", self.kd)):
            if gain.shape != (n, n):
                raise ValueError(f"PD + gravity: {name} is {gain.shape}, the robot has {n} "
                                 "controlled joints")
        self.gravity = np.asarray(gravity, dtype=float)
        self.state = robot.robot_state()  # its arrays are views, refilled each tick
        self.g = np.zeros(n + 6)
        self.tau = np.zeros(n)
        self.max_error = math.inf

    def start(self):
        self.robot.set_control_mode(wbi.ControlMode.torque)

    def update(self):
        robot = self.robot
        # q, dq and the base pose of one and the same estimate, in one call
        robot.read_robot_state(self.state)
        s = self.state
        robot.gravity_forces(s.q, s.world_H_base, self.gravity, out=self.g)
        error = s.q - self.q_desired
        np.subtract(self.g[6:], self.kp @ error + self.kd @ s.dq, out=self.tau)
        self.max_error = float(np.abs(error).max())
        robot.set_control_reference(self.tau)


def gains_from_bandwidth(robot, q_desired, bandwidth_hz):
    """Kp = w^2 M_jj, Kd = 2 w M_jj with the joint block of the inertia at the target:
    every mode critically damped at the bandwidth (the C++ PdGravityGains::from_inertia)."""
    M = robot.mass_matrix(np.asarray(q_desired, dtype=float), np.eye(4))
    joint_inertia = M[6:, 6:]
    omega = 2.0 * math.pi * bandwidth_hz
    return omega * omega * joint_inertia, 2.0 * omega * joint_inertia


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--robot", default="arm", help="robot name (topics wbi/ROBOT/...)")
    parser.add_argument("--urdf", default=str(DEFAULT_URDF), help="the robot's URDF")
    parser.add_argument("--target", type=float, nargs="+", default=DEMO_TARGET,
                        help="q_d, one per joint [rad]")
    parser.add_argument("--bandwidth-hz", type=float, default=5.0)
    parser.add_argument("--rate-hz", type=float, default=1000.0)
    parser.add_argument("--duration", type=float, default=None,
                        help="seconds of control (default: until SIGINT/SIGTERM)")
    parser.add_argument("--max-age", type=float, default=0.05,
                        help="reads fail on estimates older than this [s]")
    parser.add_argument("--init-timeout", type=float, default=30.0)
    parser.add_argument("--model", choices=["local", "remote"], default="local",
                        help="local: evaluate the URDF in this process (default); remote: ask "
                        "the robot's model service (wbi/ROBOT/model), as deploy/demo.yaml does")
    args = parser.parse_args(argv)

    robot = wbi.DdsInterface(robot=args.robot, urdf=args.urdf, joints=ARM_JOINTS,
                             controller="pd_gravity_python", model=args.model,
                             max_age_s=args.max_age)
    robot.init(timeout_s=args.init_timeout)
    kp, kd = gains_from_bandwidth(robot, args.target, args.bandwidth_hz)
    controller = PdGravity(robot, args.target, kp, kd)
    controller.start()

    loop = wbi.PeriodicLoop(args.rate_hz)
    for signal_number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signal_number, lambda *_: loop.stop())
    stale = timeouts = 0
    next_progress = 0.0

    def step(t):
        nonlocal stale, timeouts, next_progress
        try:
            controller.update()
        except wbi.StaleDataError:
            stale += 1  # no fresh estimate this tick: no command; the robot's watchdog guards
            return True
        except wbi.TimeoutError:
            timeouts += 1  # a remote model call not answered in time: likewise
            return True
        if t >= next_progress:
            next_progress += 1.0
            print(f"t = {t:6.2f} s  max joint error {controller.max_error:.4f} rad", flush=True)
        return True

    statistics = loop.run(step, duration_s=args.duration)
    robot.close()
    print(statistics)
    print(f"stale cycles: {stale}" + (f", model timeouts: {timeouts}" if timeouts else ""))
    print(f"final max joint error: {controller.max_error:.9g} rad", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
