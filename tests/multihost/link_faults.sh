#!/usr/bin/env bash
# Network faults between the robot's host and the controller's host, with the
# real-time demo (deploy/multihost_demo.yaml) on two network namespaces:
#   1. (with `impaired`) the whole run over the link emulator (wbi_link_emulator:
#      the kernel may have no netem) with a one-way delay of 2 ms +- 1 ms and 1 %
#      loss each way: the controller keeps running (its status; its rate is
#      printed, a benchmark figure, not a check) and the arm reaches its target
#      (error < 0.01 rad); the emulator's counters must show frames lost both
#      ways (the loss was real);
#   2. the link cut (ip link set down) for ~2.5 s: the controller keeps running
#      and counts stale cycles; the robot's actuator watchdog trips and holds
#      the arm (its status, read on the robot's host);
#   3. the link back: the arm returns to its target (final error < 0.01 rad).
# Without `impaired` the link is a plain veth pair and step 1 is left out.
#   link_faults.sh BINARY_DIR SOURCE_DIR [impaired]
# Exit 0 pass, 1 fail, 77 skipped (no root, no TAP devices).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/netns_pair.sh"
[[ $# -eq 2 || ( $# -eq 3 && $3 == impaired ) ]] || { sed -n '2,15p' "$0"; exit 2; }
impaired=$([[ $# -eq 3 ]] && echo 1 || echo 0)
bin="$1/bin" deploy="$2/deploy/multihost_demo.yaml"
((!impaired)) || [[ -x "$bin/wbi_bench_multihost_latency" ]] ||
  { echo "skipped: $bin/wbi_bench_multihost_latency not built (WBI_BUILD_BENCH=OFF); it reads the controller's rate across the link"; exit 77; }
if ((impaired)); then
  netns_pair_create "$bin/wbi_link_emulator" --delay-ms 2 --jitter-ms 1 --loss-percent 1 || exit $?
else
  netns_pair_create || exit $?
fi
logs=$(mktemp -d /tmp/wbi-multihost.XXXXXX)
NETNS_TEMP_DIR=$logs

host() { "on_host_$1" "$logs/$2.log" env "WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-0}" stdbuf -oL "$bin/wbi_host" "$deploy" --process "$2"; }
show_logs() { for log in "$logs"/*.log $NETNS_EMULATOR_LOG; do echo "== $(basename "$log")"; cat "$log"; done; }
stop_all() { netns_stop_processes; netns_stop_emulator; }
fail() { stop_all; show_logs; echo "FAIL: $*"; exit 1; }
progress_lines() { grep -c '^t = ' "$logs/controller.log" || true; }
# error_after LINE: the error of the newest progress line after line LINE (empty if none yet).
error_after() { grep '^t = ' "$logs/controller.log" | tail -n +"$(($1 + 1))" | tail -n 1 | awk '{print $8}'; }
# wait_for_progress COUNT SECONDS: until the controller has printed COUNT progress lines
# (one a second, at whatever t its own timer reached: "t =   1.01" under load).
wait_for_progress() {
  local deadline=$((SECONDS + $2)) lines
  while ((SECONDS < deadline)); do
    lines=$(progress_lines 2>/dev/null)
    ((${lines:-0} >= $1)) && return 0
    sleep 0.1
  done
  return 1
}
# wait_on_target LINE SECONDS: until a progress line after LINE has an error below 0.01 rad.
wait_on_target() {
  local deadline=$((SECONDS + $2)) error
  while ((SECONDS < deadline)); do
    error=$(error_after "$1")
    [[ -n "$error" ]] && awk -v e="$error" 'BEGIN { exit !(e < 0.01) }' && return 0
    sleep 0.1
  done
  return 1
}
# echo_status NETNS COUNT: COUNT samples of wbi/status, read on that host (loopback discovery).
echo_status() { ip netns exec "$1" env "WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-0}" timeout 10 "$bin/wbi" topic echo wbi/status --count "$2" 2>&1 || true; }
# controller_rate FILE: the controller's loop rate (Hz) from the first and last of its status samples.
controller_rate() {
  python3 - "$1" <<'PY'
import sys, yaml
samples = [s for s in yaml.safe_load_all(open(sys.argv[1])) if isinstance(s, dict) and s.get("type") == "pd_gravity"]
if len(samples) < 2:
    sys.exit("fewer than two controller status samples")
first, last = samples[0], samples[-1]
seconds = (last["header"]["stamp_ns"] - first["header"]["stamp_ns"]) * 1e-9
print(round((last["iterations"] - first["iterations"]) / seconds) if seconds > 0 else 0)
PY
}

# The controller must not wait on the link: a loop that waited for a round trip
# (4 ms +- 2 ms) every tick would run at <= 250 Hz. Its rate is a speed, which
# the 2 cores shared by six processes set as much as the code (405-990 Hz alone
# on this VM with the same binaries, one day to the next; 877 and 492 Hz in
# CI): bench/multihost (wbi_bench_multihost_latency, loop_rate_hz) measures it,
# and this test prints it. The test checks what holds under any load: the
# controller keeps running (its iterations grow), over the impaired link and
# while the link is cut.

host a robot
host b estimator
host b model_service
host b controller
wait_for_progress 2 60 || fail "the controller did not start (no second progress line within 60 s)"

if ((impaired)); then
  # 1. The impaired link: the controller's rate from its status and the
  # sensor-to-command latency, observed on the robot's host by
  # wbi_bench_multihost_latency (placed by the deploy file: `wbi topic echo`
  # discovers on loopback only, which reaches these participants only while the
  # link is down), then the arm on target.
  ip netns exec "$NETNS_A" env "WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-0}" timeout 90 \
    "$bin/wbi_bench_multihost_latency" --deploy "$deploy" --warmup 1.5 --duration 4 >"$logs/impaired.txt" 2>&1 ||
    fail "no controller status or commands on the impaired link: $(cat "$logs/impaired.txt")"
  read -r rate latency_ms < <(tail -n 1 "$logs/impaired.txt" | python3 -c 'import json, sys; r = json.load(sys.stdin); print(round(r["loop_rate_hz"]), round(r["latency_p50_us"] / 1000, 1))')
  ((rate > 0)) || fail "the controller did not run with 2 ms delay and 1 % loss: $(tail -n 1 "$logs/impaired.txt")"
  wait_on_target 0 30 || fail "the arm did not reach its target (error < 0.01 rad) with 2 ms delay and 1 % loss"
  echo "delay 2 ms +- 1 ms and 1 % loss: the controller ran at $rate Hz (sensor to command $latency_ms ms p50); the arm reached its target (error $(error_after 0) rad)"
fi

# 2. The link cut. While it is down, each host reads the status topic:
# host A the robot's, host B the controller's.
netns_link down
echo_status "$NETNS_A" 3 >"$logs/status_a.txt" &
status_a_pid=$!
echo_status "$NETNS_B" 9 >"$logs/status_b.txt"
wait "$status_a_pid"
netns_link up
grep -q "watchdog: joint" "$logs/status_a.txt" || { cat "$logs/status_a.txt"; fail "the robot's watchdog did not trip while the link was cut"; }
rate=$(controller_rate "$logs/status_b.txt") || { cat "$logs/status_b.txt"; fail "no controller status while the link was cut"; }
((rate > 0)) || fail "the controller did not run while the link was cut (its status: $rate Hz)"
echo "link cut: the controller kept running at $rate Hz; the robot reported: $(grep -m1 -o "watchdog: joint '[^']*' got no command[^\"]*" "$logs/status_a.txt")"

# 3. The link back: on target again within 20 s.
back_at_line=$(progress_lines)
wait_on_target "$back_at_line" 20 || fail "the arm did not return to its target within 20 s of the link coming back"
stop_all
show_logs
error=$(sed -n 's/^final max joint error: \([0-9.e+-]*\) rad$/\1/p' "$logs/controller.log" | tail -n 1)
stale=$(sed -n 's/^stale cycles: \([0-9]*\)$/\1/p' "$logs/controller.log" | tail -n 1)
[[ -n "$error" && -n "$stale" ]] || { echo "FAIL: no final error or stale-cycle line"; exit 1; }
((stale >= 500)) || { echo "FAIL: only $stale stale cycles reported for a cut of ~2 s at 1 kHz"; exit 1; }
# Recovery is the on-target check above. The final error is one snapshot of a
# real-time loop on a loaded 2-core machine (CI saw 0.018-0.033 rad spikes with
# the link intact), so here it only rules out divergence.
awk -v e="$error" 'BEGIN { exit !(e < 0.1) }' || { echo "FAIL: final max joint error $error rad >= 0.1 after the link came back"; exit 1; }
((impaired)) || { echo "PASS: link cut and back; $stale stale cycles, final max joint error $error rad"; exit 0; }
# The loss was real: the emulator dropped frames in both directions.
lost=$(sed -n 's/.*: forwarded [0-9]*, lost \([0-9]*\),.*/\1/p' "$NETNS_EMULATOR_LOG")
(($(wc -l <<<"$lost") == 2)) && ! grep -qx 0 <<<"$lost" || { echo "FAIL: the emulator lost no frames in one direction (lost: $(echo $lost))"; exit 1; }
echo "PASS: link faults; $stale stale cycles, final max joint error $error rad"
