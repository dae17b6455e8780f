#!/usr/bin/env bash
# The real-time PD demo (deploy/demo.yaml under `wbi launch`: robot, estimator,
# model service, controller at 1 kHz, the controller respawned) with a
# windowed recorder beside it:
#   wbi record --window 5:2 --trigger $WINDOW_TRIGGER -o DIR 'wbi/arm/.*'
# Once the window has filled, the controller is killed (SIGKILL) twice, the
# second time once the first fault's file is written. The trigger is the
# launcher's event of the fault, PROCESS_EXITED (WINDOW_TRIGGER may name
# another kind, e.g. LIFECYCLE: the respawned controller's runner).
# Passes when each fault gave one file, and each covers at least 5 s before
# its first trigger and 2 s after its last with no gap in the Header.seq of
# wbi/arm/sensors (wbi_test_window_check, to within 20 ms: the first and last
# samples lie inside the window).
#   window_demo.sh BINARY_DIR SOURCE_DIR
# Exit 0 pass, 1 fail.
set -euo pipefail
[[ $# -eq 2 ]] || { sed -n '2,15p' "$0"; exit 2; }
bin="$1/bin" checker="$1/tests/wbi_test_window_check" src=$(cd "$2" && pwd)
trigger=${WINDOW_TRIGGER:-PROCESS_EXITED}
work=$(mktemp -d /tmp/wbi-window.XXXXXX)
deploy="$work/demo.yaml" log="$work/launch.log" recorder_log="$work/recorder.log"
windows="$work/windows"
launch_pid="" recorder_pid=""
stop_process() {  # stop_process PID: SIGINT, SIGKILL after 30 s
  kill -INT "$1" 2>/dev/null || return 0
  local deadline=$((SECONDS + 30))
  while kill -0 "$1" 2>/dev/null && ((SECONDS < deadline)); do sleep 0.1; done
  kill -KILL "$1" 2>/dev/null || true
  wait "$1" 2>/dev/null || true
}
cleanup() {
  [[ -z "$recorder_pid" ]] || stop_process "$recorder_pid"
  [[ -z "$launch_pid" ]] || stop_process "$launch_pid"
  rm -rf "$work"
}
trap cleanup EXIT
fail() {
  echo "== wbi launch output"; tail -n 40 "$log"
  echo "== recorder output"; cat "$recorder_log"
  echo "FAIL: $*"; exit 1
}
# wait_until SECONDS COMMAND...: polls COMMAND every 0.1 s; false on timeout.
wait_until() {
  local deadline=$((SECONDS + $1)); shift
  until "$@"; do
    ((SECONDS < deadline)) || return 1
    sleep 0.1
  done
}

# The demo with absolute paths (it is copied out of deploy/).
sed -e "s#config: robots/#config: $src/deploy/robots/#" -e "s#\.\./models/#$src/models/#g" \
    "$src/deploy/demo.yaml" >"$deploy"
"$bin/wbi" launch "$deploy" --duration 150 >"$log" 2>&1 &
launch_pid=$!
controller_running() { grep -q '^\[controller\] t = ' "$log"; }
wait_until 60 controller_running || fail "the controller printed no progress within 60 s"

"$bin/wbi" record --window 5:2 --trigger "$trigger" -o "$windows" --probe 0 'wbi/arm/.*' \
    >"$recorder_log" 2>&1 &
recorder_pid=$!
subscribed() { grep -q "recording wbi/arm/sensors" "$recorder_log" && grep -q "recording wbi/events" "$recorder_log"; }
wait_until 30 subscribed || fail "the recorder did not subscribe to wbi/arm/sensors and wbi/events"
sleep 6  # the window fills: 5 s before the first fault (the subject of the test, not a wait for an event)

controller_pid() { pgrep -f "wbi_host $deploy --process controller\$" | head -n 1; }
files() { find "$windows" -name '*.mcap' 2>/dev/null | wc -l; }
for fault in 1 2; do
  pid=$(controller_pid)
  [[ -n "$pid" ]] || fail "no controller process before fault $fault"
  kill -KILL "$pid"
  respawned() { local p; p=$(controller_pid); [[ -n "$p" && "$p" != "$pid" ]]; }
  wait_until 30 respawned || fail "the controller was not respawned after fault $fault"
  written() { (($(files) >= fault)); }
  wait_until 30 written || fail "no window file for fault $fault within 30 s of the respawn"
done
stop_process "$recorder_pid"
recorder_pid=""
grep -q "^window recorder: " "$recorder_log" || fail "the recorder printed no summary"
(($(files) == 2)) || fail "$(files) window files for 2 faults"
for file in $(find "$windows" -name '*.mcap' | sort); do
  "$checker" "$file" wbi/arm/sensors "$trigger" 5 2 || fail "the window file of a fault (above)"
done
grep "^window recorder: " "$recorder_log"
stop_process "$launch_pid"
launch_pid=""
left=$(pgrep -f "$work/" || true)
[[ -z "$left" ]] || fail "processes left behind: $(ps -o pid,args -p "${left//$'\n'/,}" || true)"
echo "PASS: 2 faults, 2 window files, each 5 s before and 2 s after with no sensor sample missing"
