#!/usr/bin/env python3
"""Runs a tutorial (docs/tutorials/*.md) as written and checks its output.

The tutorial's Markdown says what runs:
  ```sh run                 a shell block the reader types: it runs, in order
  ```text expect            what the reader should see: each line is looked for, in
                            order, in the output of the run block just above it;
                            "…" (and the spaces around it) stands for any text
  ```cpp file=my_lab/x.cpp  a file the reader writes (any language): written there
Blocks without these words are shown, not run.

Every block runs in one bash script (set -euo pipefail) in a temporary folder
that looks like the repository's root: its entries are links to the sources,
`build` is the build under test, HOME is the folder's `home/`. The script runs
in its own process group on the DDS domain of WBI_DOMAIN_ID, bounded by
--timeout; whatever it leaves running is stopped at the end.

  run_tutorial.py TUTORIAL.md --source DIR --build DIR [--timeout S] [--keep] [--show]
  run_tutorial.py TUTORIAL.md --script      prints the script and exits
Exit 0 when every block ran and every expected line was seen, else 1.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^(`{3,})(.*)$")
MARKER = "@@wbi-tutorial-block {}@@ $EPOCHREALTIME"


class Block:
    def __init__(self, kind, line, text, path=None):
        self.kind, self.line, self.text, self.path = kind, line, text, path


def read_blocks(markdown_path):
    """The tutorial's run, expect and file blocks, in order."""
    blocks, fence, info, start, body = [], None, "", 0, []
    with open(markdown_path, encoding="utf-8") as markdown:
        for number, line in enumerate(markdown, 1):
            line = line.rstrip("\n")
            if fence is None:
                match = FENCE.match(line.strip())
                if match:
                    fence, info, start, body = match.group(1), match.group(2).split(), number, []
                continue
            if line.strip() == fence:
                block = classify(info, start, "\n".join(body) + "\n")
                if block:
                    blocks.append(block)
                fence = None
                continue
            body.append(line)
    if fence is not None:
        raise SystemExit(f"{markdown_path}:{start}: code block never closed")
    return blocks


def classify(info, line, text):
    words = info[1:] if info else []
    if "run" in words:
        return Block("run", line, text)
    if "expect" in words:
        return Block("expect", line, text)
    for word in words:
        if word.startswith("file="):
            return Block("file", line, text, word[len("file="):])
    return None


def script_of(blocks):
    """One bash script; a marker line before each run block splits its output."""
    lines = ["set -euo pipefail"]
    for index, block in enumerate(blocks):
        if block.kind == "run":
            lines.append(f'echo "{MARKER.format(index)}"')
            lines.append(block.text.rstrip("\n"))
        elif block.kind == "file":
            directory = os.path.dirname(block.path)
            if directory:
                lines.append(f"mkdir -p '{directory}'")
            lines.append(f"cat > '{block.path}' <<'WBI_TUTORIAL_EOF'")
            lines.append(block.text.rstrip("\n"))
            lines.append("WBI_TUTORIAL_EOF")
    lines.append('echo "' + MARKER.format("end") + '"')
    return "\n".join(lines) + "\n"


def outputs_by_block(output):
    """The output of each run block by the block's index, and when each began (s)."""
    parts, started, current, lines = {}, {}, None, []
    for line in output.splitlines():
        match = re.fullmatch(r"@@wbi-tutorial-block (\w+)@@ ([0-9.]+)", line)
        if match:
            if current is not None:
                parts[current] = lines
            current, lines = match.group(1), []
            started[current] = float(match.group(2))
        elif current is not None:
            lines.append(line)
    if current is not None:
        parts[current] = lines
    return parts, started


def block_seconds(blocks, started):
    """'line L: S s' for each run block that ran to its end."""
    keys = sorted((key for key in started if key != "end"), key=int)
    ends = keys[1:] + (["end"] if "end" in started else [])
    return [f"line {blocks[int(key)].line}: {started[end] - started[key]:.1f} s"
            for key, end in zip(keys, ends)]


def pattern_of(expected_line):
    """'…' and the spaces around it stand for any text."""
    return re.compile(".*".join(re.escape(piece) for piece in re.split(r"\s*…\s*", expected_line)))


def check_expectations(blocks, parts, markdown_path):
    """Failures: each expect block's lines, in order, in its run block's output."""
    failures, met = [], 0
    for index, block in enumerate(blocks):
        if block.kind != "expect":
            continue
        run_index = next((i for i in range(index - 1, -1, -1) if blocks[i].kind == "run"), None)
        if run_index is None:
            failures.append(f"{markdown_path}:{block.line}: an expect block with no run block above")
            continue
        output = parts.get(str(run_index))
        if output is None:
            failures.append(f"{markdown_path}:{block.line}: its run block (line "
                            f"{blocks[run_index].line}) never ran")
            continue
        position = 0
        for expected in filter(str.strip, block.text.splitlines()):
            pattern = pattern_of(expected.strip())
            while position < len(output) and not pattern.search(output[position]):
                position += 1
            if position == len(output):
                failures.append(f"{markdown_path}:{block.line}: not seen in the output of the "
                                f"block at line {blocks[run_index].line}: {expected.strip()}")
                break
            position += 1
            met += 1
    return failures, met


def make_workspace(source, build):
    """A temporary folder that looks like the repository's root."""
    workspace = tempfile.mkdtemp(prefix="wbi-tutorial-")
    for entry in os.listdir(source):
        if entry == ".git" or entry.startswith("build"):
            continue
        os.symlink(os.path.join(source, entry), os.path.join(workspace, entry))
    os.symlink(build, os.path.join(workspace, "build"))
    os.mkdir(os.path.join(workspace, "home"))
    return workspace


def environment_for(workspace):
    environment = dict(os.environ)
    # The reader's compiler cache stays theirs: a tutorial that builds reuses it.
    environment.setdefault("CCACHE_DIR", os.path.join(os.path.expanduser("~"), ".cache", "ccache"))
    environment["HOME"] = os.path.join(workspace, "home")
    environment.setdefault("WBI_DOMAIN_ID", "0")
    return environment


def run_script(script, workspace, timeout):
    """Runs it in its own process group; returns (exit code or None on timeout, output)."""
    process = subprocess.Popen(["bash", "-c", script], cwd=workspace, env=environment_for(workspace),
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               start_new_session=True, text=True, errors="replace")
    try:
        output, _ = process.communicate(timeout=timeout)
        code = process.returncode
    except subprocess.TimeoutExpired:
        code = None
    finally:
        stop_group(process.pid)
    if code is None:
        output, _ = process.communicate()
    return code, output


def stop_group(pgid):
    """SIGINT first (a launch stops its processes in order), SIGKILL after 10 s."""
    for sig, grace in ((signal.SIGINT, 10.0), (signal.SIGKILL, 0.0)):
        try:
            os.killpg(pgid, sig)
        except ProcessLookupError:
            return
        deadline = time.monotonic() + grace
        while time.monotonic() < deadline:
            try:
                os.killpg(pgid, 0)
            except ProcessLookupError:
                return
            time.sleep(0.1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("tutorial")
    parser.add_argument("--source", help="the repository's root")
    parser.add_argument("--build", help="the build under test")
    parser.add_argument("--timeout", type=float, default=300, help="seconds for the whole tutorial")
    parser.add_argument("--keep", action="store_true", help="keep the temporary folder")
    parser.add_argument("--script", action="store_true", help="print the script and exit")
    parser.add_argument("--show", action="store_true", help="print the output, also on success")
    arguments = parser.parse_args()

    blocks = read_blocks(arguments.tutorial)
    runs = sum(block.kind == "run" for block in blocks)
    if runs == 0:
        print(f"{arguments.tutorial}: no ```sh run block: nothing to run")
        return 1
    script = script_of(blocks)
    if arguments.script:
        print(script, end="")
        return 0
    if not arguments.source or not arguments.build:
        parser.error("--source and --build are needed to run")

    workspace = make_workspace(os.path.abspath(arguments.source), os.path.abspath(arguments.build))
    started = time.monotonic()
    code, output = run_script(script, workspace, arguments.timeout)
    seconds = time.monotonic() - started
    parts, started = outputs_by_block(output)
    failures, met = check_expectations(blocks, parts, arguments.tutorial)
    if code is None:
        failures.insert(0, f"{arguments.tutorial}: not done within {arguments.timeout:.0f} s")
    elif code != 0:
        last = max((int(key) for key in parts if key != "end"), default=None)
        where = f" in the block at line {blocks[last].line}" if last is not None else ""
        failures.insert(0, f"{arguments.tutorial}: a command failed{where} (exit {code})")

    if failures or arguments.show:
        print("== the tutorial's output")
        print(output)
        print("\n".join(failures))
    print(f"{os.path.basename(arguments.tutorial)}: {runs} run blocks, {met} expected lines seen, "
          f"{seconds:.1f} s{'' if not failures else ', FAILED'}")
    print("run blocks: " + ", ".join(block_seconds(blocks, started)))
    if arguments.keep or failures:
        print(f"its folder: {workspace}")
    else:
        shutil.rmtree(workspace, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
