#!/usr/bin/env bash
# The lockstep demo on two "hosts" (network namespaces joined by a veth pair):
# the robot on host A; the estimator, the model service and the controller on
# host B; user data over UDP only. Passes when the simulated run (3 s, lockstep)
# ends with a final max joint error below 0.01 rad and the data crossed the link.
#   demo_across_hosts.sh BINARY_DIR SOURCE_DIR MODE
# MODE: multicast  deploy/multihost_lockstep.yaml as it is (multicast, interface allow-list)
#       peers      initial peers only; multicast turned off on the link
#       server     a Fast DDS discovery server (fastdds discovery) on host A
#       secure     multicast, with DDS Security (scripts/wbi-security-setup, test CA)
# Prints the time from start to the controller's first state (discovery, and
# the security handshakes). Exit 0 pass, 1 fail, 77 skipped (no root, or no
# fastdds tool for "server").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/netns_pair.sh"
[[ $# -eq 3 ]] || { sed -n '2,10p' "$0"; exit 2; }
bin="$1/bin" deploy="$2/deploy/multihost_lockstep.yaml" mode="$3"
# A discovery server's client that never got the robot (1 CI run, 2026-11-29,
# among other multihost tests; not reproduced in 10 runs here, cause not found)
# and a secured pair that never authenticates (Fast DDS 2.9.1) stall start-up:
# 3 attempts from scratch (netns_attempts), each retry printed.
if [[ $mode == server || $mode == secure ]] && [[ -z ${WBI_NETNS_ATTEMPT:-} ]]; then
  netns_attempts 3 "$0" "$@"
fi
netns_pair_create || exit $?
logs=$(mktemp -d /tmp/wbi-multihost.XXXXXX)
NETNS_TEMP_DIR=$logs

overrides=()
case "$mode" in
  multicast) ;;
  peers) overrides=(WBI_DDS_DISCOVERY=peers "WBI_DDS_PEERS=$HOST_A_ADDRESS,$HOST_B_ADDRESS") ;;
  server)
    command -v fastdds >/dev/null || { echo "skipped: no fastdds tool (apt-get install fastdds-tools)"; exit 77; }
    overrides=(WBI_DDS_DISCOVERY=server "WBI_DDS_DISCOVERY_SERVER=$HOST_A_ADDRESS:11811") ;;
  secure)
    WBI="$1/bin/wbi" "$2/scripts/wbi-security-setup" "$deploy" "$logs/keys" >/dev/null
    overrides=("WBI_DDS_SECURITY_DIRECTORY=$logs/keys") ;;
  *) echo "unknown mode '$mode' (multicast, peers, server, secure)"; exit 2 ;;
esac

if [[ $mode == peers ]]; then
  ip -n "$NETNS_A" link set "$VETH_A" multicast off
  ip -n "$NETNS_B" link set "$VETH_B" multicast off
fi
if [[ $mode == server ]]; then
  # A Python wrapper running fast-discovery-server as its child: both are in
  # on_host_a's process group, stopped together (netns_pair.sh).
  on_host_a "$logs/server.log" stdbuf -oL fastdds discovery -i 0 -l "$HOST_A_ADDRESS" -p 11811
  wait_for_text "$logs/server.log" "Server is running" 10 || { cat "$logs/server.log"; echo "FAIL: the discovery server did not start"; exit 1; }
fi

# A wbi_host whose secured start stalled (exit 75) is started again, as by
# `wbi launch` (restart_on_stall.sh).
host() {  # host a|b PROCESS
  "on_host_$1" "$logs/$2.log" env "WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-0}" "${overrides[@]}" \
    "$here/restart_on_stall.sh" stdbuf -oL "$bin/wbi_host" "$deploy" --process "$2"
}
started=$(date +%s%N)
netns_start_all_but_controller "$mode" "$logs"
host b controller

show_logs() { for log in "$logs"/*.log; do echo "== $(basename "$log")"; cat "$log"; done; }
# 20 s where a stall is tried again (above), else 60 s.
if ! wait_for_text "$logs/controller.log" "t =   0.00" "$([[ -n ${WBI_NETNS_ATTEMPT:-} ]] && echo 20 || echo 60)"; then
  netns_stop_processes; show_logs
  [[ -z ${WBI_NETNS_ATTEMPT:-} ]] || { echo "STALLED: the controller never received the robot's state ($mode)"; exit 75; }
  echo "FAIL: the controller never received the robot's state ($mode)"; exit 1
fi
echo "first state at the controller: $((($(date +%s%N) - started) / 1000000)) ms after start ($mode)"
# The end of the simulated run (the robot's duration_s), not a point on the way:
# stopping at some wall time would cut a slower (secured) run short of its target.
if ! wait_for_text "$logs/robot.log" "reached: stopped stepping" 60; then
  netns_stop_processes; show_logs; echo "FAIL: the robot did not finish its simulated run ($mode)"; exit 1
fi
netns_stop_processes  # the controller prints its final error when stopped
link_bytes=$(ip netns exec "$NETNS_A" cat "/sys/class/net/$VETH_A/statistics/rx_bytes")
show_logs
echo "bytes received by host A over the link: $link_bytes"
error=$(sed -n 's/^final max joint error: \([0-9.e+-]*\) rad$/\1/p' "$logs/controller.log" | tail -n 1)
stale=$(sed -n 's/^stale cycles: \([0-9]*\)$/\1/p' "$logs/controller.log" | tail -n 1)
# The robot's "not answered ... stepping on" lines: lockstep ticks it took without a command.
lockstep_timeouts=$(grep -c "not answered by every controller" "$logs/robot.log" || true)
echo "final max joint error ${error:-?} rad, stale cycles ${stale:-?}, lockstep timeouts $lockstep_timeouts ($mode)"
[[ -n "$error" ]] || { echo "FAIL: no final error line"; exit 1; }
if ! awk -v e="$error" 'BEGIN { exit !(e < 0.01) }'; then
  echo "FAIL: final max joint error $error rad >= 0.01 ($mode)"; exit 1
fi
# Commands for ~2 s at 2 kHz: far more than discovery alone would send.
if ((link_bytes < 1000000)); then
  echo "FAIL: only $link_bytes bytes crossed the link: the data did not go over UDP between the hosts"; exit 1
fi
echo "PASS: $mode across hosts, final max joint error $error rad"
