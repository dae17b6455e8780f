#!/usr/bin/env bash
# A secured deployment started as a user starts it: `wbi launch` on each of two
# hosts (network namespaces), deploy/multihost_lockstep.yaml with DDS Security
# (scripts/wbi-security-setup, test CA): host A's launch runs the robot, host
# B's the estimator, the model service and the controller (`--process`). No
# retry here: a secured handshake that stalls (Fast DDS 2.9.1, README.md) is
# the product's to recover, its process exiting 75 and the launch starting it
# again. Passes when the controller gets its first state within 30 s, the
# simulated run (3 s) ends with a final max joint error below 0.01 rad, and
# neither launch names a failure in its summary.
#   secure_launch.sh BINARY_DIR SOURCE_DIR [RUNS]
# RUNS > 1: that many runs, each from new namespaces, then the distribution of
# the start times (launch to the controller's first state) and every failure.
# Exit 0 pass, 1 fail, 77 skipped (no root).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
[[ $# -ge 2 && $# -le 3 ]] || { sed -n '2,14p' "$0"; exit 2; }
runs=${3:-1}
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "RUNS must be a positive number, got '$runs'"; exit 2; }

if ((runs > 1)); then
  starts=() failed=0 stalled=0
  for ((run = 1; run <= runs; run++)); do
    status=0
    out=$("$0" "$1" "$2") || status=$?
    ((status != 77)) || { echo "$out"; exit 77; }
    start=$(sed -n 's/^first state at the controller: \([0-9]*\) ms.*/\1/p' <<<"$out")
    restarts=$(grep -c "its start stalled" <<<"$out" || true)
    stalled=$((stalled + restarts))
    [[ -z $start ]] || starts+=("$start")
    if ((status == 0)); then
      echo "run $run: pass, first state after ${start} ms, $restarts stalled start(s) started again"
    else
      failed=$((failed + 1))
      echo "run $run: FAIL (exit $status)"
      echo "$out" | sed 's/^/    /'
    fi
  done
  if ((${#starts[@]} > 0)); then
    printf '%s\n' "${starts[@]}" | sort -n | awk -v runs="$runs" '
      { t[NR] = $1 } $1 <= 10000 { within++ }
      END { printf "start (ms): min %d, median %d, p90 %d, max %d; %d of %d runs within 10 s\n",
            t[1], t[int((NR + 1) / 2)], t[int(0.9 * NR + 0.999)], t[NR], within, runs }'
  fi
  echo "$((runs - failed)) of $runs runs passed; $stalled stalled start(s) started again by a launch"
  ((failed == 0))
  exit
fi

source "$here/netns_pair.sh"
bin="$1/bin" deploy="$2/deploy/multihost_lockstep.yaml"
netns_pair_create || exit $?
logs=$(mktemp -d /tmp/wbi-secure-launch.XXXXXX)
NETNS_TEMP_DIR=$logs
WBI="$1/bin/wbi" "$2/scripts/wbi-security-setup" "$deploy" "$logs/keys" >/dev/null

launch() {  # launch a|b PROCESSES
  "on_host_$1" "$logs/$1.log" env "WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-0}" \
    stdbuf -oL "$bin/wbi" launch "$deploy" --process "$2" --security "$logs/keys"
}
show_logs() { for log in a b; do echo "== host $log: wbi launch"; cat "$logs/$log.log"; done; }
started=$(date +%s%N)
launch a robot
launch_a=$!
launch b estimator,model_service,controller
launch_b=$!

if ! wait_for_text "$logs/b.log" "[controller] t =   0.00" 30; then
  netns_stop_processes; show_logs; echo "FAIL: the controller never received the robot's state"; exit 1
fi
echo "first state at the controller: $((($(date +%s%N) - started) / 1000000)) ms after the launches started"
if ! wait_for_text "$logs/a.log" "reached: stopped stepping" 60; then
  netns_stop_processes; show_logs; echo "FAIL: the robot did not finish its simulated run"; exit 1
fi
# As a user ends a launch (Ctrl-C): each stops its processes and prints its summary.
kill -INT "$launch_b" "$launch_a"
codes=()
for pid in "$launch_b" "$launch_a"; do
  status=0
  timeout 20 tail --pid="$pid" -f /dev/null || { netns_stop_processes; show_logs; echo "FAIL: a launch did not stop within 20 s"; exit 1; }
  wait "$pid" || status=$?
  codes+=("$status")
done
NETNS_PIDS=()
show_logs
# 130: interrupted, as asked; any process's failure would make it 1.
[[ ${codes[*]} == "130 130" ]] || { echo "FAIL: the launches exited ${codes[*]} (B, A), not 130 130"; exit 1; }
if grep -q "FAILED" "$logs/a.log" "$logs/b.log"; then
  echo "FAIL: a launch's summary names a failure"; exit 1
fi
error=$(sed -n 's/^\[controller\] final max joint error: \([0-9.e+-]*\) rad$/\1/p' "$logs/b.log" | tail -n 1)
[[ -n "$error" ]] || { echo "FAIL: no final error line"; exit 1; }
if ! awk -v e="$error" 'BEGIN { exit !(e < 0.01) }'; then
  echo "FAIL: final max joint error $error rad >= 0.01"; exit 1
fi
echo "PASS: secured launches on two hosts, final max joint error $error rad"
