#!/usr/bin/python3
"""Joint torques and external wrenches estimated from F/T sensors (the estimator's
`joint_torques: force_torque`) on a recorded simulation run, against the
simulator's ground truth (estimation/wrenches/README.md, "Closed loop").

    bench/estimation/torque_estimation.py [--robot icub3] [--contacts A,B,..]
        [--push chest:10:0.1:40] RUN.mcap...

Each recording needs wbi/<robot>/description, state and ground_truth, and for
the torques either the ground truth's applied_torque or the sensor samples'
joint_torque (`wbi record -o RUN.mcap 'wbi/icub3/(description|state|sensors|ground_truth)'`
beside a `wbi launch`). Prints one Markdown table per run:

- joint torques of the joints matching --joints (default: legs and torso):
  RMSE as a percentage of their RMS torque, after --settle seconds;
- contact forces: the RMS of |f_estimated − f_true| per contact link, as a
  percentage of the body weight (the mean total vertical contact force);
- a push LINK:START:DURATION:FORCE: the estimated peak force on LINK during the
  push against FORCE, and the delay from START to the link's first `loaded`;
- joint accelerations of the same joints against the ground truth's ddq: the
  RMSE below 20 Hz (the error's spectrum cut there) and the lag (the delay that
  best aligns estimate and truth), for the state's ddq and for the adaptive
  window run offline (`wbi estimate`) on the state's encoder positions.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

BUILD = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../build"))
sys.path.insert(0, os.path.join(BUILD, "python"))  # the wbi package as built (python/README.md)
from wbi.recording import Recording  # noqa: E402


def matched(recording, robot):
    """State and truth rows of the same source stamp: (t [s], state, truth, their rows)."""
    state = recording.topic(f"wbi/{robot}/state")
    truth = recording.topic(f"wbi/{robot}/ground_truth")
    s_stamps = np.asarray(state["header.stamp_ns"], dtype=np.int64)
    t_stamps = np.asarray(truth["header.stamp_ns"], dtype=np.int64)
    common, in_state, in_truth = np.intersect1d(s_stamps, t_stamps, return_indices=True)
    if common.size < 100:
        raise SystemExit(f"{recording.path}: only {common.size} state estimates have a ground "
                         "truth of the same stamp")
    return common * 1e-9, state, truth, in_state, in_truth


def true_torques(recording, robot, truth, in_truth, stamps_ns):
    """The applied torques from the ground truth, else the sensed ones at the same stamps."""
    if "applied_torque" in truth.fields:
        return np.asarray(truth["applied_torque"], dtype=float)[in_truth], "ground truth"
    sensors = recording.topic(f"wbi/{robot}/sensors")
    stamps = np.asarray(sensors["header.stamp_ns"], dtype=np.int64)
    _, in_common, in_sensors = np.intersect1d(stamps_ns, stamps, return_indices=True)
    if in_common.size != stamps_ns.size:
        raise SystemExit(f"{recording.path}: no applied_torque in the ground truth and "
                         "sensor samples missing for some estimates")
    return np.asarray(sensors["joint_torque"], dtype=float)[in_sensors], "sensed"


def link_column(state, rows, link):
    """The index of `link` among the state's external wrenches."""
    names = state["external_wrenches.link"][rows[0]]
    if link not in list(names):
        raise SystemExit(f"no external-wrench estimate on '{link}' (the state has "
                         f"{', '.join(names) or 'none'}: is joint_torques force_torque?)")
    return list(names).index(link)


def forces(data, rows, prefix, column):
    return np.column_stack([np.asarray(data[f"{prefix}.force.{axis}"], dtype=float)[rows, column]
                            for axis in "xyz"])


def below(signal, hz, rate_hz=1000.0):
    """`signal` (samples × columns) with its spectrum above `hz` removed."""
    spectrum = np.fft.rfft(signal, axis=0)
    spectrum[np.fft.rfftfreq(signal.shape[0], 1.0 / rate_hz) > hz] = 0.0
    return np.fft.irfft(spectrum, n=signal.shape[0], axis=0)


def acceleration_figures(estimate, truth, band_hz=20.0, max_lag=40):
    """(RMSE below band_hz, lag in samples) of estimate against truth (samples × joints)."""
    def rmse(lag):
        e = estimate[lag:] - truth[:truth.shape[0] - lag]
        return float(np.sqrt(np.mean(below(e, band_hz) ** 2)))
    lag = min(range(max_lag + 1), key=rmse)
    return rmse(0), lag


def adaptive_window(t, q):
    """ddq of the adaptive window run offline on positions q (samples × joints)."""
    wbi = os.path.join(BUILD, "bin", "wbi")
    with tempfile.TemporaryDirectory() as folder:
        given, out = os.path.join(folder, "q.csv"), os.path.join(folder, "d.csv")
        header = "t," + ",".join(f"q{j}" for j in range(q.shape[1]))
        np.savetxt(given, np.column_stack([t, q]), delimiter=",", header=header, comments="",
                   fmt="%.17g")
        subprocess.run([wbi, "estimate", "--method", "adaptive-window", "--input", given,
                        "--output", out], check=True)
        return np.loadtxt(out, delimiter=",", skiprows=1)[:, 1 + q.shape[1]:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("recordings", nargs="+", help="runs recorded with wbi record (.mcap)")
    parser.add_argument("--robot", default="icub3", help="the robot's name (topics wbi/<robot>/...)")
    parser.add_argument("--joints", default="hip|knee|ankle|torso",
                        help="regular expression of the joints the torque figure covers")
    parser.add_argument("--contacts", default="l_foot_rear,l_foot_front,r_foot_rear,r_foot_front",
                        help="the ground truth's contact links, in its order (the robot config's)")
    parser.add_argument("--push", default="", help="LINK:START_S:DURATION_S:FORCE_N")
    parser.add_argument("--settle", type=float, default=1.5,
                        help="seconds left out at the start (default 1.5)")
    args = parser.parse_args()
    contacts = [c for c in args.contacts.split(",") if c]

    for path in args.recordings:
        recording = Recording(path)
        t, state, truth, in_state, in_truth = matched(recording, args.robot)
        stamps_ns = np.asarray(state["header.stamp_ns"], dtype=np.int64)[in_state]
        names = list(recording.topic(f"wbi/{args.robot}/description")["joint_names"][0])
        keep = t - t[0] > args.settle
        print(f"\n{os.path.basename(path)}: {keep.sum()} estimates after {args.settle} s\n")
        print("| figure | value |\n|---|---|")

        tau_true, source = true_torques(recording, args.robot, truth, in_truth, stamps_ns)
        tau = np.asarray(state["tau"], dtype=float)[in_state]
        chosen = [j for j, name in enumerate(names) if re.search(args.joints, name)]
        error = tau[keep][:, chosen] - tau_true[keep][:, chosen]
        rms_torque = np.sqrt(np.mean(tau_true[keep][:, chosen] ** 2))
        rmse = np.sqrt(np.mean(error ** 2))
        worst = chosen[int(np.argmax(np.sqrt(np.mean(error ** 2, axis=0))))]
        print(f"| joint torque RMSE, {len(chosen)} joints ({source}) | {rmse:.3f} N·m = "
              f"{100 * rmse / rms_torque:.2f} % of their RMS torque {rms_torque:.2f} N·m |")
        print(f"| worst joint | {names[worst]}: "
              f"{np.sqrt(np.mean(error[:, chosen.index(worst)] ** 2)):.3f} N·m |")

        weight = None
        for i, link in enumerate(contacts):
            f_true = forces(truth, in_truth, "contact_wrenches", i)
            f_est = forces(state, in_state, "external_wrenches.wrench", link_column(state, in_state,
                                                                                    link))
            if weight is None:
                total = sum(forces(truth, in_truth, "contact_wrenches", k)[:, 2]
                            for k in range(len(contacts)))
                weight = float(np.mean(total[keep]))
            err = np.linalg.norm(f_est[keep] - f_true[keep], axis=1)
            print(f"| {link} force error (RMS, max) | {np.sqrt(np.mean(err ** 2)):.2f} N, "
                  f"{err.max():.2f} N = {100 * np.sqrt(np.mean(err ** 2)) / weight:.2f} %, "
                  f"{100 * err.max() / weight:.2f} % of the weight {weight:.1f} N |")

        if args.push:
            link, start, duration, force = args.push.split(":")
            start, duration, force = float(start), float(duration), float(force)
            column = link_column(state, in_state, link)
            f_est = np.linalg.norm(forces(state, in_state, "external_wrenches.wrench", column),
                                   axis=1)
            since = t - t[0]
            during = (since >= start) & (since <= start + duration + 0.02)
            peak = float(f_est[during].max())
            loaded = np.asarray(state["external_wrenches.loaded"], dtype=bool)[in_state, column]
            after = np.nonzero(loaded & (since >= start))[0]
            delay = (since[after[0]] - start) * 1e3 if after.size else float("nan")
            before = (since > args.settle) & (since < start)
            print(f"| push on {link}: estimated peak | {peak:.1f} N for {force:.1f} N "
                  f"({100 * (peak - force) / force:+.1f} %) |")
            print(f"| push on {link}: detected (loaded) after | {delay:.1f} ms |")
            print(f"| {link} force before the push (RMS) | "
                  f"{np.sqrt(np.mean(f_est[before] ** 2)):.2f} N |")
            print(f"| {link} loaded before the push (false alarms) | "
                  f"{100 * np.mean(loaded[before]):.2f} % of the estimates |")

        if "ddq" in truth.fields:
            ddq_true = np.asarray(truth["ddq"], dtype=float)[in_truth][keep][:, chosen]
            ddq = np.asarray(state["ddq"], dtype=float)[in_state][keep][:, chosen]
            q = np.asarray(state["q"], dtype=float)[in_state]
            window = adaptive_window(t - t[0], q)[keep][:, chosen]
            rms = np.sqrt(np.mean(below(ddq_true, 20.0) ** 2))
            for label, estimate in (("state", ddq), ("adaptive window (offline)", window)):
                rmse, lag = acceleration_figures(estimate, ddq_true)
                print(f"| ddq RMSE below 20 Hz, {label} | {rmse:.3f} rad/s² "
                      f"({100 * rmse / rms:.1f} % of the truth's {rms:.2f}), lag {lag} ms |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
