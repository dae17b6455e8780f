# Two network namespaces joined by a veth pair: two "hosts" on one machine.
# Sourced by the multi-host tests:
#   source netns_pair.sh
#   netns_pair_create || exit $?   # 77 (skip) when namespaces cannot be created
#   on_host_a CMD... / on_host_b CMD...
# Host A is 10.77.0.1, host B 10.77.0.2 (/24). The addresses live only inside
# the pair, so concurrent runs do not collide; the names are unique per run.
# Everything is removed on exit, even on failure (trap).

HOST_A_ADDRESS=10.77.0.1
HOST_B_ADDRESS=10.77.0.2
NETNS_A="wbi$$a"
NETNS_B="wbi$$b"
VETH_A="wbv$$a"  # at most 15 characters
VETH_B="wbv$$b"
NETNS_PIDS=()    # processes started with on_host_*: stopped by netns_pair_cleanup
NETNS_TEMP_DIR="" # removed by netns_pair_cleanup too (the tests' logs)

# Stops the processes started with on_host_*: SIGTERM, SIGKILL after 5 s.
netns_stop_processes() {
  local pid
  for pid in "${NETNS_PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${NETNS_PIDS[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  done
  NETNS_PIDS=()
}

netns_pair_cleanup() {
  netns_stop_processes
  ip netns del "$NETNS_A" 2>/dev/null || true  # also removes the veth pair
  ip netns del "$NETNS_B" 2>/dev/null || true
  [[ -z "$NETNS_TEMP_DIR" ]] || rm -rf "$NETNS_TEMP_DIR"
}

netns_pair_create() {
  if [[ $(id -u) -ne 0 ]] || ! ip netns add "$NETNS_A" 2>/dev/null; then
    echo "skipped: cannot create network namespaces (needs root)"
    return 77
  fi
  trap netns_pair_cleanup EXIT
  trap 'exit 130' INT TERM
  ip netns add "$NETNS_B"
  ip link add "$VETH_A" type veth peer name "$VETH_B"
  ip link set "$VETH_A" netns "$NETNS_A"
  ip link set "$VETH_B" netns "$NETNS_B"
  local ns dev address
  for ns in A B; do
    if [[ $ns == A ]]; then ns=$NETNS_A dev=$VETH_A address=$HOST_A_ADDRESS; else ns=$NETNS_B dev=$VETH_B address=$HOST_B_ADDRESS; fi
    ip -n "$ns" link set lo up
    ip -n "$ns" addr add "$address/24" dev "$dev"
    ip -n "$ns" link set "$dev" up
    # As on a real host: a default route (multicast needs a route to go out).
    ip -n "$ns" route add default dev "$dev"
  done
}

# on_host_a LOG CMD...: starts CMD in host A's namespace, output to LOG; $! is its pid.
on_host_a() { local log=$1; shift; ip netns exec "$NETNS_A" "$@" >"$log" 2>&1 & NETNS_PIDS+=($!); }
on_host_b() { local log=$1; shift; ip netns exec "$NETNS_B" "$@" >"$log" 2>&1 & NETNS_PIDS+=($!); }

# The link between the hosts: netns_link down|up, netns_netem ARGS (tc netem on both ends).
netns_link() { ip -n "$NETNS_A" link set "$VETH_A" "$1"; ip -n "$NETNS_B" link set "$VETH_B" "$1"; }
netns_netem() {
  tc -n "$NETNS_A" qdisc replace dev "$VETH_A" root netem "$@"
  tc -n "$NETNS_B" qdisc replace dev "$VETH_B" root netem "$@"
}

# wait_for_text FILE TEXT SECONDS: 0 once FILE contains TEXT, 1 on timeout.
wait_for_text() {
  local deadline=$((SECONDS + $3))
  while ((SECONDS < deadline)); do
    grep -qF -- "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  return 1
}
