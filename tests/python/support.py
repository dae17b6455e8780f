"""Paths and child processes for the Python tests (the counterpart of tests/support)."""

import os
import pathlib
import subprocess
import tempfile

SOURCE_DIR = pathlib.Path(os.environ.get("WBI_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("WBI_BINARY_DIR", SOURCE_DIR / "build"))
SHARED_MISSING = "../shared not found"


def project_model(name):
    return SOURCE_DIR / "models" / name


def shared_model(*parts):
    """A file under ../shared/models, or None when ../shared is absent."""
    path = SOURCE_DIR.parent / "shared" / "models" / pathlib.Path(*parts)
    return path if path.exists() else None


def run(args, timeout_s, stdin=None):
    """Runs a program to completion (bounded); returns the CompletedProcess, output as text."""
    return subprocess.run([str(a) for a in args], input=stdin, capture_output=True, text=True,
                          timeout=timeout_s, check=False)


def start(args):
    """Starts a program in the background, its output kept in a temporary file."""
    output = tempfile.TemporaryFile(mode="w+")
    process = subprocess.Popen([str(a) for a in args], stdout=output, stderr=subprocess.STDOUT,
                               text=True)
    process.output_file = output
    return process


def stop(process, grace_s=10):
    """SIGTERM, then SIGKILL after grace_s; returns everything the program printed."""
    process.terminate()
    try:
        process.wait(timeout=grace_s)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
    process.output_file.seek(0)
    return process.output_file.read()
