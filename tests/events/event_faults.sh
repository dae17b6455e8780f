#!/usr/bin/env bash
# The events of the real-time PD demo (deploy/demo.yaml under `wbi launch`:
# robot, estimator, model_service, controller) under injected faults, as
# `wbi events --json`, started before the launch, sees them (docs/events.md).
# Each fault must give its events in order, naming their source and kind:
#   robot stall       SIGSTOP 1 s: arm LOOP_STALL
#   estimator stall   SIGSTOP 1 s: the controller gets no state, sends no
#                     command: arm WATCHDOG_TRIP naming the joints
#   controller kill   SIGKILL: controller PROCESS_EXITED (signal 9),
#                     PROCESS_RESPAWNED, PROCESS_STARTED, then the new
#                     pd_gravity's LIFECYCLE to ACTIVE
#   bad commands      200 commands naming joint 41: one arm COMMANDS_REJECTED
#   forced claim      joint_7 taken with force: arm CLAIM_FORCED, CLAIM_CHANGED
# and the launcher's last events (its processes stopped) reach the reader
# before it exits. Also `wbi events` itself: a late reader gets the history
# (filtered by kind), a --count not met in --timeout exits 1, a bad kind is
# one line and exit 1.
#   event_faults.sh BINARY_DIR SOURCE_DIR
# Exit 0 pass, 1 fail.
set -euo pipefail
[[ $# -eq 2 ]] || { sed -n '2,20p' "$0"; exit 2; }
bin="$1/bin" injector="$1/tests/wbi_test_event_injector" src=$(cd "$2" && pwd)
source "$src/tests/support/launch_control.sh"
work=$(mktemp -d /tmp/wbi-events.XXXXXX)
deploy="$work/demo.yaml" log="$work/launch.log" events="$work/events.jsonl"
launch_pid="" events_pid=""
cleanup() {
  for pid in $launch_pid $events_pid; do
    kill -TERM "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "== wbi launch output"; cat "$log"
  echo "== wbi events --json"; cat "$events"; cat "$work/events.err" 2>/dev/null || true
  echo "FAIL: $*"; exit 1
}
expect() { python3 "$src/tests/events/expect_events.py" "$events" "$@"; }
lines() { wc -l <"$events"; }
# wait_until SECONDS COMMAND...: polls COMMAND every 0.1 s; false on timeout,
# and at once when the launch or the reader has ended.
wait_until() {
  local deadline=$((SECONDS + $1)); shift
  until "$@" 2>/dev/null; do
    ((SECONDS < deadline)) && kill -0 "$launch_pid" "$events_pid" 2>/dev/null || return 1
    sleep 0.1
  done
}
process_pid() { pgrep -f "wbi_host $deploy --process $1\$" | head -n 1; }
# stall PROCESS: SIGSTOP for 1 s, then SIGCONT.
stall() {
  local pid; pid=$(process_pid "$1")
  [[ -n "$pid" ]] || fail "no $1 process"
  kill -STOP "$pid"; sleep 1; kill -CONT "$pid"  # the fault itself: a one-second stall
}

# The demo with absolute paths (it is copied out of deploy/); it respawns the controller.
sed -e "s#config: robots/#config: $src/deploy/robots/#" -e "s#\.\./models/#$src/models/#g" \
    "$src/deploy/demo.yaml" >"$deploy"
"$bin/wbi" events --json >"$events" 2>"$work/events.err" &
events_pid=$!
"$bin/wbi" launch "$deploy" --duration 90 >"$log" 2>&1 &
launch_pid=$!

start=$SECONDS
wait_until 60 expect 0 robot/PROCESS_STARTED/INFO controller/PROCESS_STARTED/INFO ||
  fail "the launcher's PROCESS_STARTED events"
wait_until 60 expect 0 "pd_gravity/LIFECYCLE/INFO/INACTIVE -> ACTIVE" ||
  fail "the controller's LIFECYCLE event to ACTIVE"
commanding() { grep -q '^\[controller\] t = ' "$log"; }
wait_until 30 commanding || fail "the controller printed no progress"
echo "running after $((SECONDS - start)) s"

mark=$(lines)
stall robot
wait_until 20 expect "$mark" "arm/LOOP_STALL/WARNING/the process stalled?" ||
  fail "robot stall: no LOOP_STALL event from arm"

mark=$(lines)
stall estimator
wait_until 20 expect "$mark" "arm/WATCHDOG_TRIP/WARNING/joint_1" ||
  fail "estimator stall: no WATCHDOG_TRIP event from arm naming joint_1"

mark=$(lines)
kill -KILL "$(process_pid controller)"
wait_until 30 expect "$mark" "controller/PROCESS_EXITED/ERROR/signal 9 (SIGKILL)" \
  controller/PROCESS_RESPAWNED/WARNING controller/PROCESS_STARTED/INFO \
  "pd_gravity/LIFECYCLE/INFO/UNCONFIGURED -> INACTIVE" \
  "pd_gravity/LIFECYCLE/INFO/INACTIVE -> ACTIVE" ||
  fail "controller kill: the events of its exit, respawn, start and activation, in order"
# A reader that joins now gets the launcher's history (transient-local), filtered.
late=$("$bin/wbi" events --kind process_respawned --count 1 --timeout 10) ||
  fail "a late 'wbi events --kind process_respawned' got no event"
[[ $late =~ ^[0-9:.]+\ WARNING\ wbi\ launch:controller\ \ PROCESS_RESPAWNED\ \ respawn\ 1\ of\ 3$ ]] ||
  fail "the late reader's line: '$late'"

mark=$(lines)
"$injector" bad-commands arm 200 || fail "the injector could not send its commands"
wait_until 20 expect "$mark" "arm/COMMANDS_REJECTED/WARNING/command from 'fuzzer' rejected" ||
  fail "bad commands: no COMMANDS_REJECTED event from arm"

mark=$(lines)
"$injector" force-claim arm joint_7 || fail "the injector's forced claim"
wait_until 20 expect "$mark" "arm/CLAIM_FORCED/WARNING/joint_7" \
  "arm/CLAIM_CHANGED/INFO/'supervisor'" ||
  fail "forced claim: no CLAIM_FORCED then CLAIM_CHANGED event from arm"

# Scripts' options: a --count not met within --timeout, a bad kind.
set +e
message=$("$bin/wbi" events --kind divergence --count 1 --timeout 0.5 2>&1 >/dev/null); code=$?
[[ $code -eq 1 && $message == "wbi events: 0 of 1 event(s) within 0.5 s" ]] ||
  fail "--count with --timeout: exit $code, '$message'"
message=$("$bin/wbi" events --kind watchdog_trip,bogus 2>&1); code=$?
set -e
[[ $code -eq 1 && $(wc -l <<<"$message") -eq 1 && $message == *"unknown event kind 'bogus'"* ]] ||
  fail "a bad kind: exit $code, '$message'"

mark=$(lines)
stop_launch "$launch_pid" || fail "wbi launch did not end within 30 s of SIGINT"
launch_pid=""
# Sent as the launcher ended: flushed and acknowledged before it exited.
wait_for_last() { expect "$mark" "robot/PROCESS_EXITED/INFO/stopped by the launcher"; }
deadline=$((SECONDS + 5))
until wait_for_last 2>/dev/null; do
  ((SECONDS < deadline)) || fail "the launcher's last PROCESS_EXITED (robot) did not arrive"
  sleep 0.1
done
rejected=$(python3 "$src/tests/events/expect_events.py" --count "$events" 0 "arm/COMMANDS_REJECTED//'fuzzer'")
[[ $rejected -eq 1 ]] || fail "$rejected COMMANDS_REJECTED events for one burst (expected 1)"
echo "PASS: $(lines) events in $((SECONDS - start)) s; the faults' events in order"
