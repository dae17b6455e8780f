#!/usr/bin/env bash
# One process of the real-time PD demo (deploy/demo.yaml: robot, estimator,
# model_service, controller under `wbi launch`, each respawned) fails while
# the arm holds its target:
#   stall    SIGSTOP for 1 s, then SIGCONT;
#   restart  SIGKILL, respawned by `wbi launch`;
#   term     SIGTERM (a clean stop: the components shut down in order),
#            respawned; bounds and behaviour as for restart.
# Checked on the controller's progress lines (one a second, its max joint
# error): the error after the fault stays under BOUND and is back under 0.01
# rad within RECOVERY s of the process's return. `wbi record` of the robot's
# ground truth runs all along: at most the outage + 1 s of its samples are
# missing from the file (wbi_test_fault_recording, by sequence number), and
# nothing of the launch is left running once it is stopped. Bounds per case (below), with
# what each process does:
#   robot stall      the simulation pauses with its process (it used to step
#                    the missed second in a burst: 1.3-2.6 rad); the robot
#                    says it did not catch up.            0.05 rad, 3 s
#   robot restart    a new simulation at its initial posture (0.42 rad off);
#                    the estimator restarts its filters on the new writer (it
#                    used to ignore the new samples as out of order for 5 s,
#                    0.3-1.3 rad). Bound: the first start's error.   8 s
#   estimator, model_service, controller stall or restart: the robot's
#                    watchdog holds the arm (0.1 s without commands) until the
#                    controller's commands return.        0.08 rad (stall,
#                    1 s), 0.1 rad (restart, term: the outage is the new
#                    process's start, longer under load), 5 s
#   process_faults.sh BINARY_DIR SOURCE_DIR robot|estimator|model_service|controller stall|restart|term
# Exit 0 pass, 1 fail.
set -euo pipefail
[[ $# -eq 4 && $3 =~ ^(robot|estimator|model_service|controller)$ && $4 =~ ^(stall|restart|term)$ ]] ||
  { sed -n '2,26p' "$0"; exit 2; }
bin="$1/bin" checker="$1/tests/wbi_test_fault_recording" src=$(cd "$2" && pwd) target=$3 fault=$4
source "$src/tests/support/launch_control.sh"
work=$(mktemp -d /tmp/wbi-faults.XXXXXX)
deploy="$work/demo.yaml" log="$work/launch.log"
launch_pid=""
cleanup() {
  [[ -z "$launch_pid" ]] || { kill -TERM "$launch_pid" 2>/dev/null || true; wait "$launch_pid" 2>/dev/null || true; }
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "== wbi launch output"; cat "$log"; echo "FAIL: $*"; exit 1; }

# The demo with absolute paths (it is copied out of deploy/) and every process
# respawned once (the robot too: its restart is a case here).
sed -e "s#config: robots/#config: $src/deploy/robots/#" -e "s#\.\./models/#$src/models/#g" \
    -e "/^    respawn:/d" \
    -e "/^  - name: [a-z_]*$/a\\    respawn: {enabled: true, delay: 0.2, max_retries: 1}" \
    "$src/deploy/demo.yaml" >"$deploy"
(($(grep -c "respawn: {enabled: true" "$deploy") == 4)) || fail "could not add respawn to the 4 processes of deploy/demo.yaml"
cat >>"$deploy" <<EOF
  - name: recorder
    command: ["$bin/wbi", record, -o, "$work/run.mcap", wbi/arm/ground_truth]
EOF
"$bin/wbi" launch "$deploy" --duration 40 >"$log" 2>&1 &
launch_pid=$!

# errors_after LINE: the errors of the controller's progress lines after line LINE.
errors_after() { grep '^\[controller\] t = ' "$log" | tail -n +"$(($1 + 1))" | awk '{print $(NF-1)}'; }
progress_lines() { grep -c '^\[controller\] t = ' "$log" || true; }
# wait_until SECONDS COMMAND...: polls COMMAND every 0.1 s; false on timeout,
# and at once when the launch has ended.
wait_until() {
  local deadline=$((SECONDS + $1)); shift
  until "$@"; do
    ((SECONDS < deadline)) && kill -0 "$launch_pid" 2>/dev/null || return 1
    sleep 0.1
  done
}
on_target_after() { errors_after "$1" | awk '$1 < 0.01 { found = 1 } END { exit !found }'; }
target_pid() { pgrep -f "wbi_host $deploy --process $target\$" | head -n 1; }

wait_until 60 on_target_after 0 || fail "the arm did not reach its target (error < 0.01 rad) before the fault"
pid=$(target_pid)
[[ -n "$pid" ]] || fail "no $target process"
before=$(progress_lines)
# The first start's error, from the controller's t = 0 line (a line cut by
# another process's output would leave a later, smaller error here).
initial=$(grep '^\[controller\] t = *0\.00 s' "$log" | head -n 1 | awk '{print $(NF-1)}')
[[ -n "$initial" ]] || fail "no whole 't = 0.00 s' progress line of the controller in the log"
bound=0.05 recovery=5
[[ $target != robot ]] || recovery=3
# A restart's outage is the new process's start, not 1 s: 0.5-1 s here alone,
# over 2 s with the suite at ctest -j4 on 2 cores (0.058 rad seen after a
# controller's term). The watchdog's hold sags for as long: 0.1 rad.
[[ $target == robot || $fault == stall ]] || bound=0.1
# A stall of the estimator, model service or controller: the hold sags 0.011-0.022 rad
# here, but CI saw 0.0523 rad once after a model service's stall (the loop on
# a loaded machine adds its own spikes, above): 0.08.
[[ $target == robot || $fault != stall ]] || bound=0.08
[[ "$target $fault" != "robot restart" && "$target $fault" != "robot term" ]] || { bound=$(awk -v i="$initial" 'BEGIN { print i + 0.01 }'); recovery=8; }

start=$(date +%s.%N)
if [[ $fault == stall ]]; then
  kill -STOP "$pid"
  sleep 1  # the fault itself: a one-second stall
  kill -CONT "$pid"
  back_at=$SECONDS
  if [[ $target == robot ]]; then
    wait_until 20 grep -q "came [0-9.]* s late (the process stalled?)" "$log" ||
      fail "the robot did not report the stall"
  fi
else
  if [[ $fault == term ]]; then kill -TERM "$pid"; else kill -KILL "$pid"; fi
  new_process() { local p; p=$(target_pid); [[ -n "$p" && "$p" != "$pid" ]]; }
  wait_until 20 new_process || fail "the $target process was not respawned"
  back_at=$SECONDS
  if [[ $target == robot ]]; then
    wait_until 20 grep -q "sensor samples from a new writer" "$log" ||
      fail "the estimator did not see the new robot's writer"
  fi
fi
echo "$target-$fault $start $(date +%s.%N)" >"$work/events"
# A restarted controller starts its own progress lines again, at t = 0.
if [[ $target == controller && $fault != stall ]]; then
  second_start() { (($(grep -c '^\[controller\] t = *0\.00 s' "$log") >= 2)); }
  wait_until 30 second_start || fail "the respawned controller printed no progress"
fi
wait_until "$recovery" on_target_after "$before" ||
  fail "the error was not back under 0.01 rad within $recovery s of the $target's return ($fault)"
recovered_in=$((SECONDS - back_at))
seen_after() { (($(progress_lines) >= before + 3)); }
wait_until 30 seen_after || fail "the controller printed fewer than 3 progress lines after the fault"
worst=$(errors_after "$before" | sort -g | tail -n 1)
awk -v e="$worst" -v b="$bound" 'BEGIN { exit !(e <= b) }' ||
  fail "the error reached $worst rad after the $target's $fault (bound $bound rad)"

stop_launch "$launch_pid" || fail "wbi launch did not end within 30 s of SIGINT"
launch_pid=""
left=$(pgrep -f "$work/" || true)
[[ -z "$left" ]] || fail "processes left behind: $(ps -o pid,args -p "${left//$'\n'/,}" || true)"
"$checker" arm - - "$work/events" 0 "$work/run.mcap" || fail "the recording through the fault (above)"
echo "PASS: $target $fault: worst error after it $worst rad (bound $bound), back under 0.01 rad within ${recovered_in} s"
