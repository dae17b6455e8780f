#!/usr/bin/env bash
# Where an event-driven controller's cycle runs: on the DDS thread that
# delivers its state (cycle_on_state_thread: true, the default) or on the
# runner's loop thread, woken by the state (false). One lockstep deploy file,
# in its own processes and with --one-process, both ways, ROUNDS interleaved
# rounds (default 3); the same binaries, so only the parameter differs.
#   bench/controller_host/cycle_thread.sh BUILD SOURCE [ROUNDS] [DEPLOY]
# DEPLOY: default deploy/icub3_balance.yaml (needs ../shared; else
# deploy/balance.yaml). Per run: real time, the tick's wall time, its parts
# (the robot's own work, the estimator, one controller cycle; in one process
# with the cycle on the state's thread, the robot's work holds the other two,
# which Fast DDS runs inside its publish), the controller
# cycles per tick and how many ran on the state's thread, and the figure the
# run ends on (it must not change). Medians per mode; the last line is JSON.
# The copy with the parameter set is written beside the deploy file (its
# relative paths stay valid) and removed on exit.
set -euo pipefail
if [[ $# -lt 2 || $1 == -h || $1 == --help ]]; then
  sed -n '2,/^set /p' "$0" | grep '^#' | sed 's/^# \{0,1\}//'
  [[ $# -ge 1 ]] && exit 0 || exit 2
fi
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
rounds=${3:-3}
deploy=${4:-}
if [[ -z $deploy ]]; then
  deploy=$source_dir/deploy/icub3_balance.yaml
  [[ -d $source_dir/../shared/models ]] || deploy=$source_dir/deploy/balance.yaml
fi
[[ -f $deploy ]] || { echo "cycle_thread.sh: no deploy file $deploy" >&2; exit 2; }
grep -q 'wait_for_state: true' "$deploy" ||
  { echo "cycle_thread.sh: $deploy has no event-driven controller (wait_for_state: true)" >&2; exit 2; }

loop_copy=$(dirname "$deploy")/.cycle_thread_$$.yaml
trap 'rm -f "$loop_copy"' EXIT
sed 's/^\( *\)wait_for_state: true.*/&\n\1cycle_on_state_thread: false/' "$deploy" >"$loop_copy"

# run FILE PLACEMENT: one launch; prints "rt tick work estimator cycle cycles ticks on_thread figure".
run() {
  local out
  out=$("$build/bin/wbi" launch "$1" --duration 300 $2 2>&1) ||
    { echo "cycle_thread.sh: $1 $2 failed:" >&2; tail -20 <<<"$out" >&2; exit 1; }
  python3 - "$out" <<'PY'
import re, sys
out = sys.argv[1]
def num(pattern):
    m = re.search(pattern, out)
    if not m:
        sys.exit(f"cycle_thread.sh: no match for {pattern!r} in the run's output")
    return float(m.group(1))
rt = num(r"lockstep: simulated [0-9.]+ s in [0-9.]+ s wall: ([0-9.]+)x real time")
tick = num(r"per tick ([0-9.]+) ms")
work = num(r"the robot's own work mean ([0-9.]+) ms")
estimator = num(r"from sample in to state out \(its DDS write not included\) mean ([0-9.]+) ms")
m = re.search(r"\[(?:controller|all)\] (balance|walking|pd_gravity): (\d+) cycles, read \+ update \+ write mean ([0-9.]+) ms[^\n]*?(?:; (\d+) on their event's thread)?\n", out)
if not m:
    sys.exit("cycle_thread.sh: no controller cycle line")
cycles, cycle, on_thread = int(m.group(2)), float(m.group(3)), int(m.group(4) or 0)
ticks = int(num(r"ground truth over (\d+) ticks"))
figure = re.findall(r"\n(?:\[(?:controller|all)\] )?(com tracking rms: [0-9.]+ m|final max joint error: [0-9.e-]+ rad)", out)
print(rt, tick, work, estimator, cycle, cycles, ticks, on_thread, (figure[-1] if figure else "-").replace(" ", "_"))
PY
}

declare -A results
for ((round = 1; round <= rounds; round++)); do
  for placement in "" "--one-process"; do
    for mode in state loop; do
      file=$deploy
      [[ $mode == loop ]] && file=$loop_copy
      line=$(run "$file" "$placement")
      key="${placement:-processes}/$mode"
      results[$key]+="$line"$'\n'
      echo "round $round ${placement:-own processes} cycle on the $mode thread: $line" >&2
    done
  done
done

python3 - "$deploy" "${results[processes/state]}" "${results[processes/loop]}" \
  "${results[--one-process/state]}" "${results[--one-process/loop]}" <<'PY'
import json, statistics, sys
deploy = sys.argv[1]
names = ["own processes, state thread", "own processes, loop thread",
         "one process, state thread", "one process, loop thread"]
summary = {"deploy": deploy}
print(f"{'run':32} {'real time':>9} {'tick ms':>8} {'parts ms':>9} {'tick/parts':>10} {'cycles/tick':>11} {'on state thread':>15}  figure")
for name, text in zip(names, sys.argv[2:]):
    rows = [line.split() for line in text.strip().splitlines()]
    med = lambda i: statistics.median(float(r[i]) for r in rows)
    rt, tick = med(0), med(1)
    # In one process with the cycle on the state's thread, the robot's own work
    # already holds the estimator and the cycle: Fast DDS delivers in the
    # writer's thread, so both run inside the robot's publish.
    nested = name == "one process, state thread"
    parts = statistics.median(float(r[2]) + (0 if nested else float(r[3]) + float(r[4])) for r in rows)
    per_tick = statistics.median(int(r[5]) / int(r[6]) for r in rows)
    on_thread = statistics.median(int(r[7]) / int(r[5]) for r in rows)
    figures = sorted({r[8].replace("_", " ") for r in rows})
    print(f"{name:32} {rt:8.2f}x {tick:8.3f} {parts:9.3f} {tick / parts:9.2f}x {per_tick:11.3f} {100 * on_thread:14.1f}%  {' | '.join(figures)}")
    summary[name.replace(", ", "_").replace(" ", "_")] = {
        "real_time": rt, "tick_ms": tick, "parts_ms": parts, "tick_over_parts": tick / parts,
        "cycles_per_tick": per_tick, "on_state_thread": on_thread, "figures": figures}
print("parts: the robot's own work + the estimator + one controller cycle (one process, state thread:")
print("the robot's own work alone, which holds the other two)")
print(json.dumps(summary))
PY
