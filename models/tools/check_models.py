#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Validate the URDF models of the wbi project (standard library only).

    python3 models/tools/check_models.py [file.urdf ...]   (default: models/arm7.urdf models/humanoid.urdf)

For every file:
  * XML structure: one <robot>, unique link and joint names, every joint's parent and
    child exist, exactly one root link, every link reached from it, no loops;
  * inertias: positive mass, positive-definite rotational inertia whose principal
    moments satisfy the triangle inequalities; the inertia equals that of the link's
    <visual> primitive (box, cylinder, sphere) with the link mass (warning otherwise);
  * joints: unit axis, limits with lower < upper, velocity > 0, effort > 0, <dynamics>;
  * forward kinematics at the zero posture (joint origins only: translations and fixed
    rpy rotations): total mass, centre of mass, bounding box of the geometry, frame poses;
  * left/right symmetry of l_/r_ joints and links;
  * robot-specific expectations (arm7: fixed base, 7 joints, frames; humanoid: free
    floating, 30 joints, sole frames at equal height, flat and at the bottom of the foot
    box, nothing below the soles, CoM above the midpoint between the soles);
  * sensor metadata (<sensor> elements) refers to existing frames;
  * urdfdom's check_urdf, when it is installed, parses the file.
Prints a summary and exits 1 when any check fails.
"""

import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

EPS = 1e-9


# ---------------------------------------------------------------------------
# Small linear algebra (3-vectors as tuples, 3x3 matrices as tuples of rows)
# ---------------------------------------------------------------------------
def matmul(A, B):
    return tuple(tuple(sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def matvec(A, v):
    return tuple(sum(A[i][k] * v[k] for k in range(3)) for i in range(3))


def transpose(A):
    return tuple(tuple(A[j][i] for j in range(3)) for i in range(3))


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def scale(s, a):
    return tuple(s * x for x in a)


def norm(a):
    return math.sqrt(sum(x * x for x in a))


I3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def rpy_matrix(r, p, y):
    """URDF convention: R = Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


def sym_eigenvalues(A, sweeps=50):
    """Eigenvalues of a symmetric 3x3 matrix (cyclic Jacobi)."""
    a = [list(row) for row in A]
    for _ in range(sweeps):
        off = sum(a[i][j] ** 2 for i in range(3) for j in range(3) if i != j)
        if off < 1e-30:
            break
        for p in range(2):
            for q in range(p + 1, 3):
                if abs(a[p][q]) < 1e-300:
                    continue
                theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q])
                t = (1.0 if theta >= 0 else -1.0) / (abs(theta) + math.sqrt(theta * theta + 1.0))
                c = 1.0 / math.sqrt(t * t + 1.0)
                s = t * c
                for k in range(3):  # columns p, q
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(3):  # rows p, q
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
    return sorted(a[i][i] for i in range(3))


def fnum(el, attr, default=None):
    v = el.get(attr)
    if v is None:
        if default is None:
            raise ValueError("<%s> without %s" % (el.tag, attr))
        return default
    return float(v)


def fvec(el, attr, default):
    if el is None or el.get(attr) is None:
        return default
    v = tuple(float(x) for x in el.get(attr).split())
    if len(v) != 3:
        raise ValueError("%s=%r is not 3 numbers" % (attr, el.get(attr)))
    return v


def origin(el):
    o = el.find("origin") if el is not None else None
    return fvec(o, "xyz", (0.0, 0.0, 0.0)), fvec(o, "rpy", (0.0, 0.0, 0.0))


def primitive_inertia(geom, m):
    """Inertia (3x3) about the centre of a homogeneous URDF primitive in its own frame, or None."""
    box, cyl, sph = geom.find("box"), geom.find("cylinder"), geom.find("sphere")
    if box is not None:
        a, b, c = fvec(box, "size", None)
        d = (m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)
    elif cyl is not None:
        r, h = fnum(cyl, "radius"), fnum(cyl, "length")
        across = m * (3 * r * r + h * h) / 12
        d = (across, across, m * r * r / 2)
    elif sph is not None:
        r = fnum(sph, "radius")
        d = (0.4 * m * r * r,) * 3
    else:
        return None
    return ((d[0], 0.0, 0.0), (0.0, d[1], 0.0), (0.0, 0.0, d[2]))


def half_extents(geom):
    """Half extents of a primitive's bounding box in its own frame, or None (meshes)."""
    box, cyl, sph = geom.find("box"), geom.find("cylinder"), geom.find("sphere")
    if box is not None:
        return scale(0.5, fvec(box, "size", None))
    if cyl is not None:
        r = fnum(cyl, "radius")
        return (r, r, 0.5 * fnum(cyl, "length"))
    if sph is not None:
        r = fnum(sph, "radius")
        return (r, r, r)
    return None


# ---------------------------------------------------------------------------
# Expectations for the robots the project ships (keyed by <robot name>)
# ---------------------------------------------------------------------------
EXPECT = {
    "arm7": dict(floating=False, root="world", dof=7,
                 frames=["world", "base_link", "ee_link", "tool_frame"],
                 mass=(13.0, 17.0)),
    "humanoid": dict(floating=True, root="root_link", dof=30,
                     frames=["root_link", "l_sole", "r_sole", "l_foot", "r_foot", "imu_frame",
                             "l_hand", "r_hand", "chest", "head"],
                     fixed_joints=["l_foot_ft_sensor", "r_foot_ft_sensor"],
                     prefixes=("l_", "r_", "torso_", "neck_"),
                     mass=(30.0, 35.0), height=(1.0, 1.1), mirror=True),
}
COM_LATERAL_TOL = 0.003   # [m] CoM distance from the sagittal mid-plane between the soles
COM_SAGITTAL_TOL = 0.02   # [m] warning if the CoM is further than this ahead/behind the sole centres


class Report:
    def __init__(self):
        self.errors, self.warnings = [], []

    def error(self, msg):
        self.errors.append(msg)

    def warn(self, msg):
        self.warnings.append(msg)


def check_file(path, rep):
    tree = ET.parse(path)
    robot = tree.getroot()
    if robot.tag != "robot":
        rep.error("root element is <%s>, not <robot>" % robot.tag)
        return None
    name = robot.get("name", "?")
    links = {}
    for l in robot.findall("link"):
        if l.get("name") in links:
            rep.error("duplicate link %s" % l.get("name"))
        links[l.get("name")] = l
    joints, joint_order = {}, []
    for j in robot.findall("joint"):
        if j.get("name") in joints:
            rep.error("duplicate joint %s" % j.get("name"))
        joints[j.get("name")] = j
        joint_order.append(j.get("name"))

    # --- tree structure -------------------------------------------------------------
    parent_of, children = {}, {n: [] for n in links}
    for jn in joint_order:
        j = joints[jn]
        p, c = j.find("parent").get("link"), j.find("child").get("link")
        for l in (p, c):
            if l not in links:
                rep.error("joint %s refers to missing link %s" % (jn, l))
        if c in parent_of:
            rep.error("link %s is the child of two joints (%s, %s)" % (c, parent_of[c], jn))
        parent_of[c] = jn
        if p in children:
            children[p].append(jn)
    roots = [n for n in links if n not in parent_of]
    if len(roots) != 1:
        rep.error("%d root links: %s" % (len(roots), roots))
        return None
    root = roots[0]

    # --- forward kinematics at the zero posture (also detects loops / unreachable links)
    pose = {root: (I3, (0.0, 0.0, 0.0))}
    stack, order = [root], []
    while stack:
        ln = stack.pop()
        order.append(ln)
        R, p = pose[ln]
        for jn in reversed(children.get(ln, [])):
            j = joints[jn]
            c = j.find("child").get("link")
            if c in pose:
                rep.error("loop at link %s" % c)
                continue
            xyz, rpy = origin(j)
            pose[c] = (matmul(R, rpy_matrix(*rpy)), add(p, matvec(R, xyz)))
            stack.append(c)
    unreached = set(links) - set(pose)
    if unreached:
        rep.error("links not reached from the root (loop?): %s" % sorted(unreached))

    # --- joints ---------------------------------------------------------------------
    dofs = []
    for jn in joint_order:
        j = joints[jn]
        t = j.get("type")
        if t not in ("revolute", "continuous", "prismatic", "fixed", "floating", "planar"):
            rep.error("joint %s: unknown type %s" % (jn, t))
            continue
        if t in ("floating", "planar"):
            rep.error("joint %s: type %s is not supported by the project" % (jn, t))
            continue
        if t == "fixed":
            continue
        dofs.append(jn)
        axis = fvec(j.find("axis"), "xyz", (1.0, 0.0, 0.0))
        if abs(norm(axis) - 1.0) > 1e-6:
            rep.error("joint %s: axis %s is not a unit vector" % (jn, axis))
        lim = j.find("limit")
        if t != "continuous":
            if lim is None:
                rep.error("joint %s: no <limit>" % jn)
                continue
            lo, hi = fnum(lim, "lower", 0.0), fnum(lim, "upper", 0.0)
            if not lo < hi:
                rep.error("joint %s: lower %g >= upper %g" % (jn, lo, hi))
            if t == "revolute" and (lo < -2 * math.pi or hi > 2 * math.pi):
                rep.warn("joint %s: range [%g, %g] exceeds a full turn" % (jn, lo, hi))
            if t == "revolute" and not lo <= 0.0 <= hi:
                rep.warn("joint %s: the zero posture is outside [%g, %g]" % (jn, lo, hi))
        if lim is None or fnum(lim, "velocity", 0.0) <= 0.0 or fnum(lim, "effort", 0.0) <= 0.0:
            rep.error("joint %s: velocity and effort limits must be > 0" % jn)
        dyn = j.find("dynamics")
        if dyn is None:
            rep.warn("joint %s: no <dynamics>" % jn)
        elif fnum(dyn, "damping", 0.0) < 0 or fnum(dyn, "friction", 0.0) < 0:
            rep.error("joint %s: negative damping or friction" % jn)

    # --- inertias, mass, CoM, geometry ------------------------------------------------
    total, moment = 0.0, (0.0, 0.0, 0.0)
    lo_bb, hi_bb = [math.inf] * 3, [-math.inf] * 3
    masses = {}
    for ln in order:
        l = links[ln]
        R, p = pose[ln]
        inl = l.find("inertial")
        m = 0.0
        if inl is not None:
            m = fnum(inl.find("mass"), "value")
            ie = inl.find("inertia")
            I = ((fnum(ie, "ixx"), fnum(ie, "ixy"), fnum(ie, "ixz")),
                 (fnum(ie, "ixy"), fnum(ie, "iyy"), fnum(ie, "iyz")),
                 (fnum(ie, "ixz"), fnum(ie, "iyz"), fnum(ie, "izz")))
            if m <= 0.0:
                if m < 0.0 or any(abs(x) > 0 for row in I for x in row):
                    rep.error("link %s: mass %g must be positive" % (ln, m))
                else:
                    rep.warn("link %s: <inertial> with zero mass (omit it for a massless frame)" % ln)
            else:
                ev = sym_eigenvalues(I)
                tol = 1e-9 * max(1e-12, ev[2])
                if ev[0] <= 0.0:
                    rep.error("link %s: inertia not positive definite (principal moments %s)" % (ln, ev))
                elif ev[0] + ev[1] < ev[2] - tol:
                    rep.error("link %s: principal moments %s violate the triangle inequality" % (ln, ev))
                # compare with the <visual> primitive
                vis = l.findall("visual")
                ixyz, irpy = origin(inl)
                if len(vis) == 1:
                    vxyz, vrpy = origin(vis[0])
                    P = primitive_inertia(vis[0].find("geometry"), m)
                    if P is None:
                        rep.warn("link %s: visual is not a primitive; inertia not compared" % ln)
                    elif norm(sub(vxyz, ixyz)) > 1e-9:
                        rep.warn("link %s: centre of mass is not the centre of its visual primitive" % ln)
                    else:
                        Rv, Ri = rpy_matrix(*vrpy), rpy_matrix(*irpy)
                        Q = matmul(transpose(Ri), Rv)  # primitive frame -> inertial frame
                        Pi = matmul(matmul(Q, P), transpose(Q))
                        err = max(abs(Pi[r][c] - I[r][c]) for r in range(3) for c in range(3))
                        if err > 1e-6 * max(abs(x) for row in Pi for x in row):
                            rep.warn("link %s: inertia differs from its visual primitive's (max %.3g)" % (ln, err))
                else:
                    rep.warn("link %s: %d visuals; inertia not compared with a shape" % (ln, len(vis)))
                total += m
                moment = add(moment, scale(m, add(p, matvec(R, ixyz))))
        masses[ln] = m
        for g in l.findall("visual") + l.findall("collision"):
            gxyz, grpy = origin(g)
            h = half_extents(g.find("geometry"))
            if h is None:
                continue
            Rg = matmul(R, rpy_matrix(*grpy))
            c = add(p, matvec(R, gxyz))
            for k in range(3):
                ext = sum(abs(Rg[k][i]) * h[i] for i in range(3))
                lo_bb[k] = min(lo_bb[k], c[k] - ext)
                hi_bb[k] = max(hi_bb[k], c[k] + ext)
    com = scale(1.0 / total, moment) if total > 0 else (0.0, 0.0, 0.0)
    if total <= 0.0:
        rep.error("total mass is zero")

    # --- base ---------------------------------------------------------------------
    root_has_mass = masses.get(root, 0.0) > 0.0
    root_children = children.get(root, [])
    fixed_base = (not root_has_mass and len(root_children) == 1
                  and joints[root_children[0]].get("type") == "fixed")

    # --- left/right symmetry (an error for the project's robots, a warning for others)
    exp = EXPECT.get(name)
    asym = rep.error if exp and exp.get("mirror") else rep.warn
    for jn in joint_order:
        if not jn.startswith("l_"):
            continue
        rn = "r_" + jn[2:]
        if rn not in joints:
            asym("joint %s has no right counterpart %s" % (jn, rn))
            continue
        jl, jr = joints[jn], joints[rn]
        xl, rl = origin(jl)
        xr, rr = origin(jr)
        if norm(sub(xl, (xr[0], -xr[1], xr[2]))) > 1e-9 or norm(sub(rl, (-rr[0], rr[1], -rr[2]))) > 1e-9:
            asym("joints %s/%s: origins are not mirror images" % (jn, rn))
        if jl.get("type") != jr.get("type"):
            asym("joints %s/%s: different types" % (jn, rn))
        if jl.get("type") != "fixed":
            al, ar = fvec(jl.find("axis"), "xyz", (1, 0, 0)), fvec(jr.find("axis"), "xyz", (1, 0, 0))
            if norm(sub(al, (-ar[0], ar[1], -ar[2]))) > 1e-9:
                asym("joints %s/%s: axes are not mirror images (%s, %s)" % (jn, rn, al, ar))
            if jl.find("limit").attrib != jr.find("limit").attrib:
                asym("joints %s/%s: different limits" % (jn, rn))
        cl, cr = jl.find("child").get("link"), jr.find("child").get("link")
        if abs(masses.get(cl, 0.0) - masses.get(cr, 0.0)) > 1e-12:
            asym("links %s/%s: different masses" % (cl, cr))

    # --- sensors ------------------------------------------------------------------
    sensors = []
    for s in robot.findall("sensor"):
        par = s.find("parent")
        kind = s.get("type")
        target = None
        if par is not None and par.get("joint"):
            target = par.get("joint")
            if target not in joints:
                rep.error("sensor %s: missing joint %s" % (s.get("name"), target))
            elif kind == "force_torque" and joints[target].get("type") != "fixed":
                rep.error("sensor %s: F/T joint %s is not fixed" % (s.get("name"), target))
            else:
                target = "joint %s (frame %s)" % (target, joints[target].find("child").get("link"))
        elif par is not None and par.get("link"):
            target = par.get("link")
            if target not in links:
                rep.error("sensor %s: missing link %s" % (s.get("name"), target))
        else:
            rep.error("sensor %s: no <parent joint=...> or <parent link=...>" % s.get("name"))
        sensors.append((s.get("name"), kind, target))

    # --- robot-specific expectations ---------------------------------------------
    info = dict(name=name, root=root, fixed_base=fixed_base, dofs=dofs, joints=joints, links=links,
                total=total, com=com, bbox=(lo_bb, hi_bb), pose=pose, sensors=sensors, extra=[])
    if exp:
        if exp["floating"] == fixed_base:
            rep.error("expected a %s base" % ("floating" if exp["floating"] else "fixed"))
        if root != exp["root"]:
            rep.error("root link is %s, expected %s" % (root, exp["root"]))
        if exp["floating"] and not root_has_mass:
            rep.error("floating-base root link %s has no mass" % root)
        if len(dofs) != exp["dof"]:
            rep.error("%d joints, expected %d" % (len(dofs), exp["dof"]))
        for f in exp["frames"]:
            if f not in links:
                rep.error("missing frame %s" % f)
        for f in exp.get("fixed_joints", []):
            if f not in joints or joints[f].get("type") != "fixed":
                rep.error("missing fixed joint %s" % f)
        if "prefixes" in exp:
            for jn in dofs:
                if not jn.startswith(exp["prefixes"]):
                    rep.error("joint %s: name not prefixed by one of %s" % (jn, exp["prefixes"]))
        lo, hi = exp["mass"]
        if not lo <= total <= hi:
            rep.error("total mass %.3f kg outside [%g, %g]" % (total, lo, hi))

    if "l_sole" in pose and "r_sole" in pose:
        strict = rep.error if exp else rep.warn  # the stance checks bind the project's robots only
        (Rl, pl), (Rr, pr) = pose["l_sole"], pose["r_sole"]
        for sn, R in (("l_sole", Rl), ("r_sole", Rr)):
            if max(abs(R[i][k] - I3[i][k]) for i in range(3) for k in range(3)) > 1e-9:
                strict("%s is not parallel to the world frame (z up, x forward) at zero" % sn)
        if abs(pl[2] - pr[2]) > 1e-9:
            strict("sole heights differ: %.6f vs %.6f" % (pl[2], pr[2]))
        mid = scale(0.5, add(pl, pr))
        # lateral = along the line between the soles, sagittal = across it (horizontal)
        d = sub(pl, pr)
        u = (d[0], d[1], 0.0)
        u = scale(1.0 / norm(u), u)
        v = (-u[1], u[0], 0.0)
        rel = sub(com, mid)
        lat = sum(a * b for a, b in zip(rel, u))
        sag = -sum(a * b for a, b in zip(rel, v))  # positive: CoM ahead of the sole centres
        if abs(lat) > COM_LATERAL_TOL:
            strict("CoM is %.4f m off the mid-plane between the soles" % lat)
        if abs(sag) > COM_SAGITTAL_TOL:
            rep.warn("CoM is %.4f m ahead (+) / behind (-) the sole centres" % sag)
        if lo_bb[2] < pl[2] - 1e-9:
            strict("geometry reaches %.4f m below the soles" % (pl[2] - lo_bb[2]))
        # each sole is the centre of the bottom face of its parent's collision box
        for sn, (R, p) in (("l_sole", (Rl, pl)), ("r_sole", (Rr, pr))):
            foot = joints[parent_of[sn]].find("parent").get("link")
            cols = links[foot].findall("collision")
            boxes = [c for c in cols if c.find("geometry/box") is not None]
            if len(boxes) != 1:
                strict("%s: parent link %s has no single <collision> box" % (sn, foot))
                continue
            Rf, pf = pose[foot]
            cxyz, crpy = origin(boxes[0])
            Rc = matmul(Rf, rpy_matrix(*crpy))
            h = scale(0.5, fvec(boxes[0].find("geometry/box"), "size", None))
            bottom = add(add(pf, matvec(Rf, cxyz)), matvec(Rc, (0.0, 0.0, -h[2])))
            if norm(sub(bottom, p)) > 1e-9 or abs(Rc[2][2] - 1.0) > 1e-9:
                strict("%s is not the centre of the bottom face of %s's collision box" % (sn, foot))
        height = hi_bb[2] - pl[2]
        info["extra"] += [
            "soles (world, root at origin): l_sole %s, r_sole %s" % (fmt(pl), fmt(pr)),
            "height (sole to top of geometry): %.3f m; root_link origin %.3f m above the soles"
            % (height, pose[root][1][2] - pl[2]),
            "CoM relative to the sole midpoint: %s (lateral %.2e m; %+.4f m ahead (+) / behind (-) the sole centres)"
            % (fmt(rel), lat, sag),
        ]
        if exp and "height" in exp and not exp["height"][0] <= height <= exp["height"][1]:
            rep.error("height %.3f m outside %s" % (height, exp["height"]))
    return info


def fmt(v):
    return "(" + ", ".join("%+.4f" % x for x in v) + ")"


def run_check_urdf(path, rep):
    exe = shutil.which("check_urdf")
    if exe is None:
        return "check_urdf not installed (apt-get install liburdfdom-tools): skipped"
    r = subprocess.run([exe, path], capture_output=True, text=True)
    if r.returncode != 0 or "Successfully Parsed" not in r.stdout:
        rep.error("check_urdf failed: %s" % (r.stderr.strip() or r.stdout.strip())[:500])
        return "check_urdf: FAILED"
    return "check_urdf (urdfdom): parsed OK"


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    files = argv[1:] or [os.path.join(here, "..", f) for f in ("arm7.urdf", "humanoid.urdf")]
    failed = False
    for path in files:
        path = os.path.normpath(path)
        rep = Report()
        try:
            info = check_file(path, rep)
        except (ET.ParseError, ValueError, AttributeError, OSError) as e:
            rep.error("cannot read: %s" % e)
            info = None
        urdfdom = run_check_urdf(path, rep) if os.path.exists(path) else ""
        print("=" * 78)
        print(path)
        if info:
            lo, hi = info["bbox"]
            print("  robot %s, root link %s, %s base, %d links, %d joints (%d movable)"
                  % (info["name"], info["root"], "fixed" if info["fixed_base"] else "floating",
                     len(info["links"]), len(info["joints"]), len(info["dofs"])))
            print("  total mass %.4f kg, CoM at zero posture (root frame) %s" % (info["total"], fmt(info["com"])))
            print("  geometry bounding box (root frame): min %s max %s" % (fmt(lo), fmt(hi)))
            for line in info["extra"]:
                print("  " + line)
            print("  joints in order (axis in joint frame, [lower, upper] rad, velocity rad/s, effort N m):")
            for i, jn in enumerate(info["dofs"]):
                j = info["joints"][jn]
                lim = j.find("limit")
                print("    %2d %-18s axis %-8s [%+.2f, %+.2f] %5.1f %6.1f"
                      % (i, jn, fvec(j.find("axis"), "xyz", (1, 0, 0)).__repr__().replace(" ", ""),
                         fnum(lim, "lower", 0.0), fnum(lim, "upper", 0.0),
                         fnum(lim, "velocity", 0.0), fnum(lim, "effort", 0.0)))
            frames = [ln for ln in info["links"] if "inertial" not in [c.tag for c in info["links"][ln]]]
            print("  massless frames: " + ", ".join(
                "%s %s" % (f, fmt(info["pose"][f][1])) for f in frames if f in info["pose"]))
            for s in info["sensors"]:
                print("  sensor %s (%s) on %s" % s)
        print("  " + urdfdom)
        for w in rep.warnings:
            print("  WARNING: " + w)
        for e in rep.errors:
            print("  ERROR: " + e)
        print("  => %s (%d errors, %d warnings)" % ("OK" if not rep.errors else "FAILED",
                                                  len(rep.errors), len(rep.warnings)))
        failed |= bool(rep.errors)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
