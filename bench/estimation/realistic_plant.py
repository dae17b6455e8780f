#!/usr/bin/python3
"""The joint velocity and acceleration estimators on a recorded simulation run,
against the simulator's ground truth (estimation/README.md,
"On a realistic plant").

    bench/estimation/realistic_plant.py [--robot icub3] [--wbi build/bin/wbi] RUN.mcap...

Each recording needs the robot's wbi/<robot>/sensors and wbi/<robot>/ground_truth
topics (`wbi record -o RUN.mcap 'wbi/icub3/(sensors|ground_truth)'` beside a
`wbi launch` of a simulated robot). The encoder positions and their source stamps
go through `wbi estimate` for every method with its default settings, as the
estimator component would see them; the estimates are compared with the ground
truth's dq and ddq at the same stamps. Prints one Markdown table: RMSE over all
joints after --settle seconds at zero lag, the lag (the delay tau minimising the
RMSE between estimate(t) and truth(t - tau), 0.25 ms steps; negative: a lead),
and the RMSE as a multiple of adaptive-window's.
"""

import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

BUILD = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../build"))
sys.path.insert(0, os.path.join(BUILD, "python"))  # the wbi package as built (python/README.md)
from wbi.recording import Recording  # noqa: E402

METHODS = ["adaptive-window", "split-kalman", "kalman", "backward-difference"]
LAGS_MS = np.arange(-5.0, 20.0 + 1e-9, 0.25)


def matched(recording, robot):
    """Stamps [s], encoder positions, true dq and ddq of the samples in both topics."""
    sensors = recording.topic(f"wbi/{robot}/sensors")
    truth = recording.topic(f"wbi/{robot}/ground_truth")
    sensor_stamps = np.asarray(sensors["header.stamp_ns"], dtype=np.int64)
    truth_stamps = np.asarray(truth["header.stamp_ns"], dtype=np.int64)
    common, in_sensors, in_truth = np.intersect1d(sensor_stamps, truth_stamps,
                                                  return_indices=True)
    if common.size < 100:
        raise SystemExit(f"{recording.path}: only {common.size} samples have both a sensor "
                         "sample and a ground truth of the same stamp")
    q = np.asarray(sensors["encoder_position"], dtype=float)[in_sensors]
    dq = np.asarray(truth["dq"], dtype=float)[in_truth]
    ddq = np.asarray(truth["ddq"], dtype=float)[in_truth]
    return (common - common[0]) * 1e-9, q, dq, ddq


def estimate(wbi, method, t, q, folder):
    """dq, ddq of `wbi estimate --method method` on (t, q)."""
    n = q.shape[1]
    source = os.path.join(folder, "in.csv")
    target = os.path.join(folder, f"{method}.csv")
    header = "t," + ",".join(f"q{j}" for j in range(n))
    np.savetxt(source, np.column_stack([t, q]), delimiter=",", header=header, comments="",
               fmt="%.9f")
    subprocess.run([wbi, "estimate", "--method", method, "--input", source, "--output", target],
                   check=True)
    out = np.loadtxt(target, delimiter=",", skiprows=1)
    return out[:, 1:1 + n], out[:, 1 + n:1 + 2 * n]


def band_limited(x, hz):
    """x (1 kHz rows) without what lies above hz: zero-phase, by FFT."""
    spectrum = np.fft.rfft(x, axis=0)
    spectrum[np.fft.rfftfreq(x.shape[0], 1e-3) > hz] = 0.0
    return np.fft.irfft(spectrum, n=x.shape[0], axis=0)


def rmse(estimate_, truth):
    return float(np.sqrt(np.mean((estimate_ - truth) ** 2)))


def lag_ms(t, estimate_, truth, keep):
    """The delay minimising the RMSE of estimate(t) against truth(t - lag)."""
    best, best_lag = np.inf, 0.0
    for lag in LAGS_MS:
        shifted = np.column_stack([np.interp(t - 1e-3 * lag, t, truth[:, j])
                                   for j in range(truth.shape[1])])
        error = rmse(estimate_[keep], shifted[keep])
        if error < best:
            best, best_lag = error, lag
    return best_lag


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("recordings", nargs="+", help="runs recorded with wbi record (.mcap)")
    parser.add_argument("--robot", default="icub3", help="the robot's name (topics wbi/<robot>/...)")
    parser.add_argument("--wbi", default=os.path.join(BUILD, "bin", "wbi"),
                        help="the wbi program (default: build/bin/wbi)")
    parser.add_argument("--settle", type=float, default=1.5,
                        help="seconds left out at the start (default 1.5)")
    parser.add_argument("--band", type=float, default=0.0,
                        help="compare with the truth below this frequency [Hz] (zero-phase); "
                        "0 (default): the truth as it is")
    args = parser.parse_args()

    print("| run | method | RMSE dq (rad/s) | × adaptive-window | RMSE ddq (rad/s²) | "
          "× adaptive-window | lag dq (ms) | lag ddq (ms) |")
    print("|---|---|---|---|---|---|---|---|")
    for path in args.recordings:
        t, q, dq_true, ddq_true = matched(Recording(path), args.robot)
        if args.band > 0.0:
            dq_true, ddq_true = band_limited(dq_true, args.band), band_limited(ddq_true, args.band)
        keep = t > args.settle
        baseline = None
        with tempfile.TemporaryDirectory() as folder:
            for method in METHODS:
                dq, ddq = estimate(args.wbi, method, t, q, folder)
                row = (rmse(dq[keep], dq_true[keep]), rmse(ddq[keep], ddq_true[keep]))
                baseline = baseline or row
                print(f"| {os.path.basename(path)} | {method} | {row[0]:.4f} | "
                      f"{row[0] / baseline[0]:.2f} | {row[1]:.3f} | {row[1] / baseline[1]:.2f} | "
                      f"{lag_ms(t, dq, dq_true, keep):.2f} | "
                      f"{lag_ms(t, ddq, ddq_true, keep):.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
