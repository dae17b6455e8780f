#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Generate the robot models the wbi project ships: models/arm7.urdf and models/humanoid.urdf.

Both robots are the project's own design. Each robot is one table of segments below;
every inertia is computed here from the segment's primitive shape (box, cylinder or
sphere, homogeneous) and its mass, with the centre of mass at the centre of the shape.
Edit the tables, then run

    python3 models/tools/generate_models.py           # rewrite the .urdf files
    python3 models/tools/generate_models.py --check   # exit 1 if the files are stale
    python3 models/tools/check_models.py              # validate them

Conventions
  * Every link frame is parallel to the world frame when all joints are at zero
    (x forward, y left, z up); joint origins carry translations only, so the zero
    posture can be read off the table directly.
  * Units: m, kg, rad, rad/s, N m, N m s/rad.
  * Humanoid: rows whose names contain "{s}" describe the left side (y > 0) and are
    emitted twice, first as "l_", then mirrored in the sagittal plane as "r_"
    (y -> -y; roll and yaw axes change sign, pitch axes do not; limits stay the same).
    Equal joint values on both sides therefore give a mirror-symmetric posture.

Standard library only.
"""

import argparse
import math
import os
import sys
from collections import namedtuple

# ---------------------------------------------------------------------------
# Segment table row
#   link    child link created by this row (for the root row: the root link)
#   parent  parent link (None for the root row)
#   joint   joint name (None for the root row)
#   jtype   "revolute" or "fixed"
#   axis    joint axis in the joint frame (revolute only)
#   xyz     joint origin in the parent link frame (rotation is always zero)
#   shape   "box" | "cyl_x" | "cyl_y" | "cyl_z" | "sphere" | None (massless frame)
#   dims    box: (size_x, size_y, size_z); cylinder: (radius, length); sphere: (radius,)
#   at      centre of the shape (= centre of mass) in the link frame
#   mass    [kg] (0 for a massless frame)
#   limit   (lower, upper, velocity, effort) for revolute joints
#   dyn     (damping [N m s/rad], friction [N m]) for revolute joints
# ---------------------------------------------------------------------------
Seg = namedtuple("Seg", "link parent joint jtype axis xyz shape dims at mass limit dyn")

X, Y, Z, NY = (1, 0, 0), (0, 1, 0), (0, 0, 1), (0, -1, 0)
O = (0.0, 0.0, 0.0)


def rev(link, parent, joint, axis, xyz, shape, dims, at, mass, limit, dyn):
    return Seg(link, parent, joint, "revolute", axis, xyz, shape, dims, at, mass, limit, dyn)


def fix(link, parent, joint, xyz, shape=None, dims=None, at=O, mass=0.0):
    return Seg(link, parent, joint, "fixed", None, xyz, shape, dims, at, mass, None, None)


def root(link, shape=None, dims=None, at=O, mass=0.0):
    return Seg(link, None, None, None, None, O, shape, dims, at, mass, None, None)


# ===========================================================================
# arm7: fixed-base 7-joint serial arm (spherical shoulder j1-j3, elbow j4,
# spherical wrist j5-j7). Shoulder (j2) to flange (ee_link): 0.98 m.
# ===========================================================================
ARM7_NAME = "arm7"
ARM7 = [
    #    link          parent        joint       axis  origin xyz           shape    dims                at                    mass  limit (lo, hi, vel, effort)  dyn (damping, friction)
    root("world"),
    fix("base_link",   "world",      "base_link_fixed_joint", O,           "cyl_z", (0.08, 0.10),       (0.0, 0.0, 0.05),     1.0),
    rev("link_1",      "base_link",  "joint_1", Z, (0.0, 0.0, 0.10),        "cyl_z", (0.07, 0.24),       (0.0, 0.0, 0.12),     3.0, (-2.90, 2.90, 1.7, 120.0), (0.50, 0.30)),
    rev("link_2",      "link_1",     "joint_2", Y, (0.0, 0.0, 0.24),        "cyl_z", (0.065, 0.20),      (0.0, 0.0, 0.10),     3.0, (-2.00, 2.00, 1.7, 150.0), (0.50, 0.30)),
    rev("link_3",      "link_2",     "joint_3", Z, (0.0, 0.0, 0.20),        "cyl_z", (0.06, 0.25),       (0.0, 0.0, 0.125),    2.5, (-2.90, 2.90, 2.0, 80.0),  (0.30, 0.20)),
    rev("link_4",      "link_3",     "joint_4", Y, (0.0, 0.0, 0.25),        "cyl_z", (0.055, 0.20),      (0.01, 0.0, 0.10),    2.0, (-2.40, 2.40, 2.0, 80.0),  (0.30, 0.20)),
    rev("link_5",      "link_4",     "joint_5", Z, (0.0, 0.0, 0.20),        "cyl_z", (0.05, 0.22),       (0.0, 0.0, 0.11),     1.5, (-2.90, 2.90, 2.6, 40.0),  (0.20, 0.10)),
    rev("link_6",      "link_5",     "joint_6", Y, (0.0, 0.0, 0.22),        "cyl_z", (0.045, 0.06),      (0.01, 0.0, 0.03),    1.2, (-2.00, 2.00, 3.1, 30.0),  (0.10, 0.05)),
    rev("link_7",      "link_6",     "joint_7", Z, (0.0, 0.0, 0.06),        "cyl_z", (0.04, 0.05),       (0.0, 0.0, 0.025),    0.8, (-3.00, 3.00, 3.1, 20.0),  (0.10, 0.05)),
    fix("ee_link",     "link_7",     "ee_link_fixed_joint",    (0.0, 0.0, 0.05)),   # flange centre
    fix("tool_frame",  "ee_link",    "tool_frame_fixed_joint", (0.0, 0.0, 0.10)),   # tool centre point
]
ARM7_COLLISION = set()

# ===========================================================================
# humanoid: free-floating, 30 joints, iCub-like proportions (~1.09 m, ~33.8 kg).
# Heights at the zero posture above the soles: ankle axes 0.065, knee 0.265,
# hip centres 0.485, root_link origin 0.555, torso joints 0.625,
# shoulder centres 0.865, neck joints 0.925, top of head 1.09.
# ===========================================================================
FOOT_X = 0.005   # foot/sole centre ahead of the ankle axis (puts the CoM within 1 mm of the sole centres)
CHEST_X = 0.015  # chest centre of mass ahead of the torso axes
HUMANOID_NAME = "humanoid"
HUMANOID = [
    #    link              parent            joint                 axis origin xyz              shape    dims                 at                        mass  limit (lo, hi, vel, effort)  dyn (damping, friction)
    root("root_link",                                                                           "box",   (0.14, 0.22, 0.10),  (0.0, 0.0, -0.01),        4.0),   # pelvis
    fix("imu_frame",       "root_link",      "imu_frame_fixed_joint",  (0.03, 0.0, 0.02)),
    # --- legs: hip pitch/roll/yaw axes meet at the hip centre, ankle pitch/roll at the ankle centre
    rev("{s}_hip_1",       "root_link",      "{s}_hip_pitch",   Y, (0.0, 0.07, -0.07),     "cyl_x", (0.04, 0.08),        (0.0, 0.0, 0.0),          0.5, (-2.10, 0.50, 6.0, 60.0), (0.50, 0.30)),
    rev("{s}_hip_2",       "{s}_hip_1",      "{s}_hip_roll",    X, O,                      "cyl_z", (0.04, 0.06),        (0.0, 0.0, -0.03),        0.6, (-0.40, 1.50, 6.0, 50.0), (0.50, 0.30)),
    rev("{s}_upper_leg",   "{s}_hip_2",      "{s}_hip_yaw",     Z, O,                      "cyl_z", (0.045, 0.22),       (0.0, 0.0, -0.11),        2.2, (-1.20, 1.20, 7.0, 30.0), (0.50, 0.30)),
    rev("{s}_lower_leg",   "{s}_upper_leg",  "{s}_knee",        Y, (0.0, 0.0, -0.22),      "cyl_z", (0.04, 0.20),        (0.0, 0.0, -0.10),        1.6, (-0.05, 2.30, 7.0, 60.0), (0.50, 0.30)),
    rev("{s}_ankle_1",     "{s}_lower_leg",  "{s}_ankle_pitch", Y, (0.0, 0.0, -0.20),      "cyl_y", (0.03, 0.06),        (0.0, 0.0, 0.0),          0.3, (-0.70, 0.70, 7.0, 40.0), (0.50, 0.30)),
    rev("{s}_ankle_2",     "{s}_ankle_1",    "{s}_ankle_roll",  X, O,                      "box",   (0.06, 0.05, 0.03),  (0.0, 0.0, -0.015),       0.4, (-0.40, 0.40, 7.0, 25.0), (0.50, 0.30)),
    # 6-axis F/T sensor: the fixed joint's frame (= l_foot link frame) is the sensor frame, 0.035 m above the sole
    fix("{s}_foot",        "{s}_ankle_2",    "{s}_foot_ft_sensor",     (0.0, 0.0, -0.03),  "box",   (0.20, 0.08, 0.03),  (FOOT_X, 0.0, -0.02),     0.6),
    fix("{s}_sole",        "{s}_foot",       "{s}_sole_fixed_joint",   (FOOT_X, 0.0, -0.035)),   # centre of the sole (bottom face of the foot box)
    # --- torso: pitch/roll/yaw axes meet 0.07 m above the pelvis origin
    rev("torso_1",         "root_link",      "torso_pitch",     Y, (0.0, 0.0, 0.07),       "cyl_y", (0.04, 0.10),        (0.0, 0.0, 0.0),          0.5, (-0.35, 1.20, 4.0, 80.0), (0.50, 0.30)),
    rev("torso_2",         "torso_1",        "torso_roll",      X, O,                      "cyl_x", (0.04, 0.08),        (0.0, 0.0, 0.0),          0.5, (-0.50, 0.50, 4.0, 60.0), (0.50, 0.30)),
    rev("chest",           "torso_2",        "torso_yaw",       Z, O,                      "box",   (0.16, 0.24, 0.28),  (CHEST_X, 0.0, 0.16),     9.0, (-0.90, 0.90, 4.0, 40.0), (0.50, 0.30)),
    # --- arms: shoulder pitch/roll/yaw axes meet at the shoulder centre; wrist yaw is the forearm (pronation) axis
    rev("{s}_shoulder_1",  "chest",          "{s}_shoulder_pitch", Y, (0.0, 0.17, 0.24),   "cyl_y", (0.035, 0.06),       (0.0, 0.0, 0.0),          0.3, (-3.00, 0.80, 5.0, 20.0), (0.20, 0.10)),
    rev("{s}_shoulder_2",  "{s}_shoulder_1", "{s}_shoulder_roll",  X, O,                   "cyl_x", (0.035, 0.06),       (0.0, 0.0, 0.0),          0.3, (-0.20, 2.80, 5.0, 20.0), (0.20, 0.10)),
    rev("{s}_upper_arm",   "{s}_shoulder_2", "{s}_shoulder_yaw",   Z, O,                   "cyl_z", (0.03, 0.15),        (0.0, 0.0, -0.075),       1.0, (-1.30, 1.30, 6.0, 10.0), (0.20, 0.10)),
    rev("{s}_elbow_1",     "{s}_upper_arm",  "{s}_elbow",         NY, (0.0, 0.0, -0.15),   "cyl_y", (0.03, 0.05),        (0.0, 0.0, 0.0),          0.15, (-0.05, 2.40, 6.0, 10.0), (0.20, 0.10)),
    rev("{s}_forearm",     "{s}_elbow_1",    "{s}_wrist_yaw",      Z, O,                   "cyl_z", (0.028, 0.13),       (0.0, 0.0, -0.065),       0.6, (-1.50, 1.50, 8.0, 3.0),  (0.05, 0.02)),
    rev("{s}_palm",        "{s}_forearm",    "{s}_wrist_pitch",    Y, (0.0, 0.0, -0.13),   "box",   (0.06, 0.025, 0.08), (0.0, 0.0, -0.045),       0.3, (-1.20, 1.20, 8.0, 3.0),  (0.05, 0.02)),
    fix("{s}_hand",        "{s}_palm",       "{s}_hand_fixed_joint",  (0.0, 0.0, -0.06)),   # palm centre
    # --- neck: pitch/roll/yaw axes meet 0.30 m above the torso axes
    rev("neck_1",          "chest",          "neck_pitch",      Y, (0.0, 0.0, 0.30),       "cyl_y", (0.02, 0.05),        (0.0, 0.0, 0.0),          0.1, (-0.60, 0.70, 6.0, 8.0),  (0.05, 0.02)),
    rev("neck_2",          "neck_1",         "neck_roll",       X, O,                      "cyl_x", (0.02, 0.05),        (0.0, 0.0, 0.0),          0.15, (-0.35, 0.35, 6.0, 8.0), (0.05, 0.02)),
    rev("head",            "neck_2",         "neck_yaw",        Z, O,                      "box",   (0.15, 0.13, 0.15),  (0.01, 0.0, 0.09),        1.8, (-1.00, 1.00, 6.0, 6.0),  (0.05, 0.02)),
]
HUMANOID_COLLISION = {"l_foot", "r_foot"}

# Sensor metadata written as top-level <sensor> elements (urdfdom ignores them).
# (name, type, attach kind, attach name)
ARM7_SENSORS = []
HUMANOID_SENSORS = [
    ("imu", "imu", "link", "imu_frame"),
    ("l_foot_ft_sensor", "force_torque", "joint", "l_foot_ft_sensor"),
    ("r_foot_ft_sensor", "force_torque", "joint", "r_foot_ft_sensor"),
]


# ---------------------------------------------------------------------------
# Mirroring and expansion
# ---------------------------------------------------------------------------
def mirror_vec(v):
    return (v[0], -v[1], v[2])


def mirror_axis(a):
    # An axis is an axial vector: under the reflection y -> -y it maps to (-ax, ay, -az).
    return (-a[0], a[1], -a[2])


def side(seg, s):
    def name(n):
        return None if n is None else n.replace("{s}", s)

    seg = seg._replace(link=name(seg.link), parent=name(seg.parent), joint=name(seg.joint))
    if s == "r":
        seg = seg._replace(xyz=mirror_vec(seg.xyz), at=mirror_vec(seg.at),
                           axis=None if seg.axis is None else mirror_axis(seg.axis))
    return seg


def expand(table):
    """Emit each contiguous block of "{s}" rows first for the left, then for the right side."""
    out, block = [], []
    for seg in table + [None]:
        if seg is not None and "{s}" in seg.link:
            block.append(seg)
            continue
        for s in ("l", "r"):
            out.extend(side(b, s) for b in block)
        block = []
        if seg is not None:
            out.append(seg)
    return out


# ---------------------------------------------------------------------------
# Inertia of homogeneous primitives about their centre, in the link axes
# ---------------------------------------------------------------------------
def inertia(shape, dims, m):
    """Return (ixx, iyy, izz) of a homogeneous primitive about its centre."""
    if shape == "box":
        a, b, c = dims
        return (m * (b * b + c * c) / 12.0, m * (a * a + c * c) / 12.0, m * (a * a + b * b) / 12.0)
    if shape in ("cyl_x", "cyl_y", "cyl_z"):
        r, h = dims
        along = m * r * r / 2.0
        across = m * (3.0 * r * r + h * h) / 12.0
        return {"cyl_x": (along, across, across),
                "cyl_y": (across, along, across),
                "cyl_z": (across, across, along)}[shape]
    if shape == "sphere":
        (r,) = dims
        i = 2.0 * m * r * r / 5.0
        return (i, i, i)
    raise ValueError("unknown shape %r" % shape)


# ---------------------------------------------------------------------------
# URDF writer
# ---------------------------------------------------------------------------
def num(x):
    x = float(x)
    if x == 0.0:
        return "0"
    s = "%.9g" % x
    return s


def vec(v):
    return " ".join(num(c) for c in v)


def angles(v):
    # full precision, so that pi/2 is exact to double precision
    return " ".join("0" if c == 0.0 else repr(float(c)) for c in v)


def geometry(shape, dims, at, ind):
    """<origin> and <geometry> lines of a visual/collision element."""
    rpy = {"cyl_x": (0.0, math.pi / 2, 0.0), "cyl_y": (math.pi / 2, 0.0, 0.0)}.get(shape, O)
    if shape == "box":
        g = '<box size="%s"/>' % vec(dims)
    elif shape.startswith("cyl"):
        g = '<cylinder radius="%s" length="%s"/>' % (num(dims[0]), num(dims[1]))
    else:
        g = '<sphere radius="%s"/>' % num(dims[0])
    return [ind + '<origin xyz="%s" rpy="%s"/>' % (vec(at), angles(rpy)),
            ind + "<geometry>",
            ind + "  " + g,
            ind + "</geometry>"]


def link_xml(seg, collide):
    if seg.mass <= 0.0:
        return ['  <link name="%s"/>' % seg.link]
    ixx, iyy, izz = inertia(seg.shape, seg.dims, seg.mass)
    L = ['  <link name="%s">' % seg.link,
         "    <inertial>",
         '      <origin xyz="%s" rpy="0 0 0"/>' % vec(seg.at),
         '      <mass value="%s"/>' % num(seg.mass),
         '      <inertia ixx="%s" ixy="0" ixz="0" iyy="%s" iyz="0" izz="%s"/>' % (num(ixx), num(iyy), num(izz)),
         "    </inertial>",
         "    <visual>"]
    L += geometry(seg.shape, seg.dims, seg.at, "      ")
    L += ["    </visual>"]
    if collide:
        L += ["    <collision>"]
        L += geometry(seg.shape, seg.dims, seg.at, "      ")
        L += ["    </collision>"]
    L += ["  </link>"]
    return L


def joint_xml(seg):
    L = ['  <joint name="%s" type="%s">' % (seg.joint, seg.jtype),
         '    <origin xyz="%s" rpy="0 0 0"/>' % vec(seg.xyz),
         '    <parent link="%s"/>' % seg.parent,
         '    <child link="%s"/>' % seg.link]
    if seg.jtype == "revolute":
        lo, hi, vel, eff = seg.limit
        L += ['    <axis xyz="%s"/>' % vec(seg.axis),
              '    <limit lower="%s" upper="%s" velocity="%s" effort="%s"/>' % (num(lo), num(hi), num(vel), num(eff)),
              '    <dynamics damping="%s" friction="%s"/>' % (num(seg.dyn[0]), num(seg.dyn[1]))]
    L += ["  </joint>"]
    return L


def sensor_xml(sensors):
    L = []
    for name, kind, attach, target in sensors:
        L += ['  <sensor name="%s" type="%s">' % (name, kind),
              '    <parent %s="%s"/>' % (attach, target),
              '    <origin xyz="0 0 0" rpy="0 0 0"/>']
        if kind == "force_torque":
            L += ["    <force_torque>",
                  "      <frame>child</frame>",
                  "      <measure_direction>child_to_parent</measure_direction>",
                  "    </force_torque>"]
        L += ["  </sensor>"]
    return L


HEADER = """<?xml version="1.0"?>
<!--
  {name}.urdf - a robot model of the wbi project, the project's own design.
  License: BSD-3-Clause (same as the wbi project).
  GENERATED by models/tools/generate_models.py - edit the table there and regenerate.
  Every inertia is that of the homogeneous primitive shown as <visual>, with its mass.
  All link frames are parallel to the world frame at the zero posture (x forward, y left, z up).
-->
"""


def urdf(name, table, collision, sensors):
    segs = expand(table)
    names = [s.link for s in segs]
    assert len(names) == len(set(names)), "duplicate link names"
    joints = [s.joint for s in segs if s.joint]
    assert len(joints) == len(set(joints)), "duplicate joint names"
    L = [HEADER.format(name=name).rstrip("\n"), '<robot name="%s">' % name]
    for seg in segs:
        if seg.parent is not None:
            L += joint_xml(seg)
        L += link_xml(seg, seg.link in collision)
    if sensors:
        L += ["  <!-- Sensors (metadata; the F/T frame is the child link frame of the fixed joint,"
              " the wrench is the one the child side exerts on the parent side) -->"]
        L += sensor_xml(sensors)
    L += ["</robot>", ""]
    return "\n".join(L)


ROBOTS = [
    ("arm7.urdf", ARM7_NAME, ARM7, ARM7_COLLISION, ARM7_SENSORS),
    ("humanoid.urdf", HUMANOID_NAME, HUMANOID, HUMANOID_COLLISION, HUMANOID_SENSORS),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true", help="only compare with the files on disk")
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."),
                    help="output directory (default: models/)")
    args = ap.parse_args()
    stale = False
    for fname, name, table, collision, sensors in ROBOTS:
        text = urdf(name, table, collision, sensors)
        path = os.path.join(args.out, fname)
        if args.check:
            try:
                with open(path) as f:
                    same = f.read() == text
            except OSError:
                same = False
            print("%s: %s" % (os.path.normpath(path), "up to date" if same else "STALE"))
            stale |= not same
        else:
            with open(path, "w") as f:
                f.write(text)
            print("wrote", os.path.normpath(path))
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
