#!/usr/bin/env python3
"""Prints the estimator benchmark's JSON as a Markdown table.

usage: wbi_bench_estimation --benchmark_format=json > out.json && table.py out.json
"""
import json
import sys


def main(path):
    with open(path) as f:
        runs = json.load(f)["benchmarks"]
    print("| motion | method | RMSE dq (rad/s) | lag dq (ms) | RMSE ddq (rad/s²) | lag ddq (ms) "
          "| RMSE ddq away from reversals |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for run in runs:
        parts = run["name"].split("/")
        if parts[0] == "Accuracy":
            print(f"| {parts[1]} | {parts[2]} | {run['rmse_dq']:.4f} | {run['lag_dq_ms']:.2f} "
                  f"| {run['rmse_ddq']:.3f} | {run['lag_ddq_ms']:.2f} | {run['rmse_ddq_away']:.3f} |")
    print()
    print("| method | cost per 32-joint sample (µs) |")
    print("|---|---:|")
    for run in runs:
        parts = run["name"].split("/")
        if parts[0] == "Cost":
            scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3}[run["time_unit"]]
            print(f"| {parts[1]} | {run['cpu_time'] * scale:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1])
