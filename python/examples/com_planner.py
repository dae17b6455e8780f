#!/usr/bin/env python3
"""A planner in its own process: the balancer's CoM reference at 100 Hz.

It reads the robot's state as a controller does (no joint claimed), and
publishes on wbi/<robot>/references/<controller>/com the same reference as the
com_sinusoid generator (controllers/references/README.md): the measured CoM
while settling, then x0 + a sin(2 pi f (t - t_s) + phi) d, centred between the
soles along d and starting at the CoM. Points are stamped with the robot time
of the state they were computed at (Stamp.source_ns); between two of them the
balancer carries the last one by its velocity and acceleration.

    wbi launch deploy/balance_planner.yaml &
    PYTHONPATH=build/python python3 python/examples/com_planner.py \\
        --robot humanoid --urdf models/humanoid.urdf --controller balance
"""

import argparse
import math
import sys

import numpy as np

import wbi

HUMANOID_JOINTS = [
    "l_hip_pitch", "l_hip_roll", "l_hip_yaw", "l_knee", "l_ankle_pitch", "l_ankle_roll",
    "r_hip_pitch", "r_hip_roll", "r_hip_yaw", "r_knee", "r_ankle_pitch", "r_ankle_roll",
    "torso_pitch", "torso_roll", "torso_yaw",
    "l_shoulder_pitch", "l_shoulder_roll", "l_shoulder_yaw", "l_elbow", "l_wrist_yaw",
    "l_wrist_pitch",
    "r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw", "r_elbow", "r_wrist_yaw",
    "r_wrist_pitch",
    "neck_pitch", "neck_roll", "neck_yaw"]


class ComSinusoid:
    """The reference as a function of time since the planner's first state."""

    def __init__(self, amplitude, frequency_hz, direction, settle_s):
        self.amplitude = amplitude
        self.omega = 2.0 * math.pi * frequency_hz
        d = np.asarray(direction, dtype=float)
        if d.shape != (3,) or not np.any(d):
            raise ValueError("direction takes 3 values, not all zero")
        self.direction = d / np.linalg.norm(d)
        self.settle_s = settle_s
        self.origin = None
        self.phase = 0.0
        self.anchored = False

    def follow(self, t, com, feet_center):
        """Holds the CoM while settling; at the end of it, starts the swing at the CoM."""
        if t < self.settle_s:
            self.origin = com()
            return
        if self.anchored:
            return
        self.anchored = True
        now = com()
        lean = now - feet_center()
        lean[2] = 0.0  # the CoM's height is not a lean
        offset = float(np.clip(lean @ self.direction, -self.amplitude, self.amplitude))
        self.phase = math.asin(offset / self.amplitude) if self.amplitude > 0 else 0.0
        self.origin = now - offset * self.direction

    def at(self, t):
        """(position, velocity, acceleration) at time t."""
        if t <= self.settle_s:
            return self.origin, np.zeros(3), np.zeros(3)
        angle = self.omega * (t - self.settle_s) + self.phase
        a, w, d = self.amplitude, self.omega, self.direction
        return (self.origin + a * math.sin(angle) * d, a * w * math.cos(angle) * d,
                -a * w * w * math.sin(angle) * d)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--robot", default="humanoid")
    parser.add_argument("--urdf", default="models/humanoid.urdf")
    parser.add_argument("--joints", nargs="+", default=HUMANOID_JOINTS,
                        help="as the balancer's (default: the project humanoid's 30)")
    parser.add_argument("--controller", default="balance", help="whose `com` input to feed")
    parser.add_argument("--rate-hz", type=float, default=100.0,
                        help="points per second of robot time (default 100)")
    parser.add_argument("--amplitude", type=float, default=0.05)
    parser.add_argument("--frequency-hz", type=float, default=0.2)
    parser.add_argument("--direction", type=float, nargs=3, default=[0.0, 1.0, 0.0])
    parser.add_argument("--settle-s", type=float, default=1.0)
    parser.add_argument("--duration-s", type=float, default=0.0,
                        help="stop after this much robot time (0: until the robot stops)")
    parser.add_argument("--left-sole", default="l_sole")
    parser.add_argument("--right-sole", default="r_sole")
    parser.add_argument("--domain-id", type=int, default=None)
    args = parser.parse_args(argv)
    if args.rate_hz <= 0:
        parser.error("--rate-hz must be > 0")

    robot = wbi.DdsInterface(robot=args.robot, urdf=args.urdf, joints=args.joints,
                             controller="com_planner", claim="none", max_age_s=1.0,
                             domain_id=args.domain_id)
    robot.init(30.0)
    soles = [robot.frame_index(args.left_sole), robot.frame_index(args.right_sole)]
    writer = wbi.ReferenceWriter(args.robot, args.controller, "com", source="com_planner",
                                 domain_id=args.domain_id)
    reference = ComSinusoid(args.amplitude, args.frequency_hz, args.direction, args.settle_s)
    state = robot.robot_state()
    period_ns = int(round(1e9 / args.rate_hz))
    start_ns = next_ns = None
    print(f"com_planner: {writer.topic} at {args.rate_hz:g} Hz of robot time", flush=True)
    while True:
        try:
            stamp = robot.read_robot_state(state, wbi.ReadMode.blocking)
        except (wbi.TimeoutError, wbi.StaleDataError):
            print("com_planner: no state for 1 s: the robot stopped", flush=True)
            return 0
        if start_ns is None:
            start_ns = next_ns = stamp.source_ns
        if stamp.source_ns < next_ns:
            continue  # not yet this point's time
        t = 1e-9 * (stamp.source_ns - start_ns)
        reference.follow(t, lambda: robot.com(state.q, state.world_H_base),
                         lambda: 0.5 * sum(robot.frame_pose(state.q, state.world_H_base, s)[:3, 3]
                                           for s in soles))
        x, v, a = reference.at(t)
        writer.write(stamp.source_ns, x, v, a)
        next_ns += period_ns * max(1, (stamp.source_ns - next_ns) // period_ns + 1)
        if args.duration_s > 0 and t >= args.duration_s:
            print(f"com_planner: {writer.written} points sent", flush=True)
            return 0


if __name__ == "__main__":
    sys.exit(main())
