#!/usr/bin/env bash
# One process of the lockstep humanoid balancing (deploy/balance.yaml: robot,
# estimator, controller; plus `wbi record` of the ground truth and the CoM
# reference, all under `wbi launch`, each respawned) fails three times in one
# run while the CoM follows its sinusoid:
#   stall    SIGSTOP for 1 s, then SIGCONT;
#   kill     SIGKILL, respawned by `wbi launch`;
#   term     SIGTERM (a clean stop), respawned.
# Each fault is followed by 3 s of simulated time (and at least 4 s of wall
# time) before the next. Then the launch is stopped and nothing of it may be
# left running. The recording (one file per start of the recorder) is checked
# by wbi_test_fault_recording (check_recording.cpp) on the robot's ground
# truth: per fault, the CoM error from its start to 2 s after the component's
# return under BOUND, and under 1 cm from then on; ground-truth samples
# missing (counted by sequence number, across the recorder's files) under
# (the recorder's outages + 1 s) of samples.
#
# Lockstep: the robot steps tick k only once the controller has answered it
# (else after lockstep_timeout_s, 2 s, per tick), and the controller answers
# only a new estimate. A stopped or dead robot, estimator or controller so
# stops the simulation itself: the robot cannot drift while the loop is down
# (a stall costs time, not accuracy), and the bound is the undisturbed
# tracking error (2-4 mm) with margin: 1 cm, for every row. A restarted robot
# is a new simulation at its initial posture, which the controller takes up
# while it settles (its reference's origin follows the CoM for t < 1 s of the
# new simulation's time); a new estimator has a frame of its own (a legged
# base starts at x = y = 0), which the controller's reference follows (it
# moved the robot 5 cm before). The recorder does not touch the loop.
#   balance_faults.sh BINARY_DIR SOURCE_DIR robot|estimator|controller|recorder
# Exit 0 pass, 1 fail.
set -euo pipefail
[[ $# -eq 3 && $3 =~ ^(robot|estimator|controller|recorder)$ ]] || { sed -n '2,27p' "$0"; exit 2; }
bin="$1/bin" checker="$1/tests/wbi_test_fault_recording" src=$(cd "$2" && pwd) target=$3
source "$src/tests/support/launch_control.sh"
work=$(mktemp -d /tmp/wbi-balance-faults.XXXXXX)
deploy="$work/balance.yaml" log="$work/launch.log" events="$work/events"
launch_pid=""
cleanup() {
  [[ -z "$launch_pid" ]] || { kill -TERM "$launch_pid" 2>/dev/null || true; wait "$launch_pid" 2>/dev/null || true; }
  if [[ -n "${WBI_FAULTS_KEEP:-}" ]]; then echo "kept: $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT
fail() { echo "== wbi launch output"; cat "$log"; echo "FAIL: $*"; exit 1; }

# The balancing with absolute paths, run until the launch ends (no exit_after_s,
# no shutdown_on_exit), every process respawned, and a recorder process that
# writes a new file at each start.
respawn="    respawn: {enabled: true, delay: 0.2, max_retries: 3}"
sed -e "s#config: robots/#config: $src/deploy/robots/#" -e "s#\.\./models/#$src/models/#g" \
    -e "/^    respawn:/d" -e "/^    shutdown_on_exit:/d" -e "s/exit_after_s: [0-9.]*/exit_after_s: 0/" \
    -e "/^  - name: [a-z_]*$/a\\$respawn" \
    "$src/deploy/balance.yaml" >"$deploy"
cat >>"$deploy" <<EOF
  - name: recorder
$respawn
    command: [sh, -c, 'exec "$bin/wbi" record -o "$work/rec_\$(date +%s%N).mcap" "wbi/humanoid/(description|ground_truth|signals/balance)"']
EOF
(($(grep -c "respawn: {enabled: true" "$deploy") == 4)) || fail "could not add respawn to the processes of deploy/balance.yaml"
: >"$log"  # before the first poll: the launch's redirection may come after it
"$bin/wbi" launch "$deploy" --grace 3 >"$log" 2>&1 &
launch_pid=$!

now() { date +%s.%N; }
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
target_pid() {
  if [[ $target == recorder ]]; then
    pgrep -f "^$bin/wbi record -o $work/" | head -n 1
  else
    pgrep -f "wbi_host $deploy --process $target\$" | head -n 1
  fi
}
# The starts of the target that run: its components, or the recorder's
# subscription to the ground truth (its outage lasts until then).
runs() {
  if [[ $target == recorder ]]; then
    grep -c "^\[recorder\] recording wbi/humanoid/ground_truth " "$log" || true
  else
    grep -c "^\[$target\] wbi_host: running" "$log" || true
  fi
}
# After the fault: 3 more progress lines (3 s of simulated time) and at least
# 4 s of wall time since the component's return (the checker's window).
observed() { (($(progress_lines) >= lines_at_return + 3)) && awk -v b="$back" -v n="$(now)" 'BEGIN { exit !(n - b >= 4) }'; }

wait_until 90 eval '(($(progress_lines) >= 3))' || fail "the balancing did not run 3 s before the faults"
for fault in stall kill term; do
  pid=$(target_pid)
  [[ -n "$pid" ]] || fail "no $target process before the $fault"
  runs_before=$(runs)
  start=$(now)
  case $fault in
    stall) kill -STOP "$pid"; sleep 1; kill -CONT "$pid" ;;  # the fault itself: a one-second stall
    kill) kill -KILL "$pid" ;;
    term) kill -TERM "$pid" ;;
  esac
  if [[ $fault != stall ]]; then
    new_process() { local p; p=$(target_pid); [[ -n "$p" && "$p" != "$pid" ]]; }
    wait_until 30 new_process || fail "the $target process was not respawned after the $fault"
    more_runs() { (($(runs) > runs_before)); }
    wait_until 60 more_runs || fail "the respawned $target did not run (its components, or its recording)"
  fi
  back=$(now)
  echo "$target-$fault $start $back" >>"$events"
  lines_at_return=$(progress_lines)
  wait_until 60 observed || fail "the balancing did not go on for 3 s after the $target's $fault"
done

stop_launch "$launch_pid" || fail "wbi launch did not end within 30 s of SIGINT"
launch_pid=""
left=$(pgrep -f "$work/" || true)
[[ -z "$left" ]] || fail "processes left behind: $(ps -o pid,args -p "${left//$'\n'/,}" || true)"

bound=0.01
shopt -s nullglob
files=("$work"/rec_*.mcap)
((${#files[@]} > 0)) || fail "no recording"
if ! "$checker" humanoid balance "$src/models/humanoid.urdf" "$events" "$bound" "${files[@]}"; then
  fail "the recording through the faults (above)"
fi
echo "PASS: $target stall, kill, term: ${#files[@]} recording file(s)"
