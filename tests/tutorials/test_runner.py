#!/usr/bin/env python3
"""Checks run_tutorial.py on the fixtures: each wrong tutorial fails with the line
that names its fault, the right one passes.
  test_runner.py RUNNER FIXTURES SOURCE BUILD"""
import subprocess
import sys

runner, fixtures, source, build = sys.argv[1:5]
cases = {
    # fixture: (exit code, text its output must hold)
    "passes.md": (0, "1 run blocks, 2 expected lines seen"),
    "command_fails.md": (1, "a command failed in the block at line 1 (exit 1)"),
    "line_missing.md": (1, "not seen in the output of the block at line 1: launch: all processes"),
    "unclosed.md": (1, "code block never closed"),
}
failed = 0
for fixture, (code, text) in cases.items():
    result = subprocess.run([sys.executable, runner, f"{fixtures}/{fixture}", "--source", source,
                             "--build", build, "--timeout", "30"],
                            capture_output=True, text=True, timeout=50)
    output = result.stdout + result.stderr
    if result.returncode != code or text not in output:
        failed += 1
        print(f"FAIL {fixture}: exit {result.returncode} (expected {code}), "
              f"expected to see: {text}\n{output}")
    else:
        print(f"ok {fixture}")
sys.exit(1 if failed else 0)
