#!/usr/bin/python3
"""Cost of the Python layer: wbi.Model calls from Python (binding overhead
included) and the timing of an idle wbi.PeriodicLoop. Prints JSON.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_python.py [--urdf URDF]
        [--rate-hz 1000] [--loop-seconds 2] [-o result.json]

model: median ns per call over repetitions of 200 calls at one random state,
for a new result array and with out= (no allocation). loop: statistics of a
loop whose step does nothing, i.e. the wake-up precision of the machine.
"""

import argparse
import json
import pathlib
import statistics
import sys
import time

import numpy as np

import wbi

ROOT = pathlib.Path(__file__).resolve().parents[2]


def per_call_ns(call, calls=200, repeats=15):
    samples = []
    for _ in range(repeats):
        start = time.perf_counter_ns()
        for _ in range(calls):
            call()
        samples.append((time.perf_counter_ns() - start) / calls)
    return statistics.median(samples)


def bench_model(urdf):
    model = wbi.Model.from_urdf(urdf)
    rng = np.random.default_rng(1)
    pose = np.eye(4)
    q = model.configuration(pose, rng.uniform(-1, 1, model.n_joints)) if model.floating_base \
        else rng.uniform(-1, 1, model.n_joints)
    nu = rng.uniform(-1, 1, model.nv)
    frame = model.frame_names[-1]
    M_out = np.zeros((model.nv, model.nv), order="F")
    v_out = np.zeros(model.nv)
    J_out = np.zeros((6, model.nv), order="F")
    cases = {
        "mass_matrix": lambda: model.mass_matrix(q),
        "mass_matrix_out": lambda: model.mass_matrix(q, out=M_out),
        "bias_forces": lambda: model.bias_forces(q, nu),
        "gravity_forces": lambda: model.gravity_forces(q),
        "gravity_forces_out": lambda: model.gravity_forces(q, out=v_out),
        "forward_dynamics": lambda: model.forward_dynamics(q, nu, v_out),
        "jacobian": lambda: model.jacobian(q, frame),
        "jacobian_out": lambda: model.jacobian(q, frame, out=J_out),
        "centroidal_momentum_matrix": lambda: model.centroidal_momentum_matrix(q),
    }
    return {"urdf": str(urdf), "nv": model.nv,
            "ns_per_call": {name: round(per_call_ns(call)) for name, call in cases.items()}}


def bench_loop(rate_hz, seconds):
    stats = wbi.PeriodicLoop(rate_hz).run(lambda t: None, duration_s=seconds)
    return {"rate_hz": rate_hz, "iterations": stats.iterations,
            "measured_rate_hz": stats.measured_rate_hz, "period_mean_s": stats.period_mean_s,
            "period_jitter_s": stats.period_jitter_s, "period_max_s": stats.period_max_s,
            "overruns": stats.overruns}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--urdf", default=str(ROOT / "models" / "humanoid.urdf"))
    parser.add_argument("--rate-hz", type=float, default=1000.0)
    parser.add_argument("--loop-seconds", type=float, default=2.0)
    parser.add_argument("-o", "--output", help="also write the JSON here")
    args = parser.parse_args(argv)
    result = {"model": bench_model(args.urdf), "loop": bench_loop(args.rate_hz, args.loop_seconds)}
    text = json.dumps(result, indent=2)
    print(text)
    if args.output:
        pathlib.Path(args.output).write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
