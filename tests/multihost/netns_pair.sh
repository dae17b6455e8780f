# Two network namespaces joined by a veth pair: two "hosts" on one machine.
# Sourced by the multi-host tests:
#   source netns_pair.sh
#   netns_pair_create || exit $?   # 77 (skip) when namespaces cannot be created
#   on_host_a CMD... / on_host_b CMD...
# With `netns_pair_create EMULATOR ARGS...` the link is instead two TAP devices
# joined by the link emulator (wbi_link_emulator: delay, jitter, loss; the
# kernel may have no netem), started as `EMULATOR --tap-a .. --tap-b .. ARGS...`.
# Host A is 10.77.0.1, host B 10.77.0.2 (/24). The addresses live only inside
# the pair, so concurrent runs do not collide; the names are unique per run.
# Everything is removed on exit, even on failure (trap), and the exit fails if
# anything this run started outlived it (netns_check_leftovers).

HOST_A_ADDRESS=10.77.0.1
HOST_B_ADDRESS=10.77.0.2
NETNS_A="wbi$$a"
NETNS_B="wbi$$b"
VETH_A="wbv$$a"  # the link's ends (veth, or TAP with the emulator); at most 15 characters
VETH_B="wbv$$b"
NETNS_EMULATOR_PID=""
NETNS_EMULATOR_LOG=""  # its output: "ready", then its counters when stopped
NETNS_PIDS=()    # started with on_host_*, each the leader of its process group: stopped by netns_pair_cleanup
NETNS_TEMP_DIR="" # removed by netns_pair_cleanup too (the tests' logs)
# Exported by netns_pair_create: every process this run starts inherits it, so
# that one outside the namespaces (or that left them) is still found as ours.
NETNS_RUN_MARK="WBI_NETNS_RUN=wbi$$"

# Stops the processes started with on_host_*, each with whatever it forked (its
# process group: `fastdds discovery` is a Python wrapper whose child, the
# server, outlived a SIGTERM to the wrapper alone): SIGTERM, SIGKILL after 5 s.
netns_stop_processes() {
  local pid
  for pid in "${NETNS_PIDS[@]}"; do kill -TERM -- "-$pid" 2>/dev/null || true; done
  for pid in "${NETNS_PIDS[@]}"; do
    for _ in $(seq 50); do kill -0 -- "-$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL -- "-$pid" 2>/dev/null || true
  done
  NETNS_PIDS=()
}

# netns_has_mark PID: whether PID's environment holds this run's mark. Builtins
# only: a forked helper would carry the mark itself.
netns_has_mark() {
  local entry entries
  mapfile -t -d '' entries 2>/dev/null <"/proc/$1/environ" || return 1
  for entry in "${entries[@]}"; do [[ $entry == "$NETNS_RUN_MARK" ]] && return 0; done
  return 1
}

# netns_leftovers: the pids of every process still in the pair's namespaces or,
# anywhere on the host, carrying this run's mark (this shell excluded).
netns_leftovers() {
  local ns pid
  local -A found=()
  for ns in "$NETNS_A" "$NETNS_B"; do
    for pid in $(ip netns pids "$ns" 2>/dev/null); do found[$pid]=1; done
  done
  for pid in /proc/[0-9]*; do
    pid=${pid#/proc/}
    [[ $pid != "$$" && $pid != "$BASHPID" ]] && netns_has_mark "$pid" && found[$pid]=1
  done
  echo "${!found[@]}"
}

# netns_check_leftovers: after everything was stopped, nothing this run
# started may remain (issue 44: orphaned discovery servers piled up, one per
# run). Names each leftover, then kills it; 1 if there was any.
netns_check_leftovers() {
  local pids pid command where
  pids=$(netns_leftovers)
  [[ -n "$pids" ]] || return 0
  echo "FAIL: processes left behind by this test (stopped now):"
  for pid in $pids; do
    mapfile -t -d '' command 2>/dev/null <"/proc/$pid/cmdline" || command=("?")
    where=$(ip netns identify "$pid" 2>/dev/null || true)
    echo "  pid $pid (parent $(awk '{print $4}' "/proc/$pid/stat" 2>/dev/null), ${where:+in }${where:-on the host}): ${command[*]}"
  done
  kill -TERM $pids 2>/dev/null || true
  for _ in $(seq 50); do
    pids=$(netns_leftovers)
    [[ -n "$pids" ]] || return 1
    sleep 0.1
  done
  kill -KILL $pids 2>/dev/null || true
  return 1
}

# The EXIT trap: stops and removes everything; a clean exit becomes a failure
# when something outlived the test.
netns_pair_cleanup() {
  local status=$?
  netns_stop_processes
  netns_stop_emulator
  if ! netns_check_leftovers && ((status == 0 || status == 77)); then status=1; fi
  [[ -z "$NETNS_EMULATOR_LOG" ]] || rm -f "$NETNS_EMULATOR_LOG"
  ip netns del "$NETNS_A" 2>/dev/null || true  # also removes the veth pair
  ip netns del "$NETNS_B" 2>/dev/null || true
  [[ -z "$NETNS_TEMP_DIR" ]] || rm -rf "$NETNS_TEMP_DIR"
  exit "$status"
}

# Stops the link emulator (the TAP devices go with it); its counters stay in its log.
netns_stop_emulator() {
  [[ -n "$NETNS_EMULATOR_PID" ]] || return 0
  kill -TERM "$NETNS_EMULATOR_PID" 2>/dev/null || true
  wait "$NETNS_EMULATOR_PID" 2>/dev/null || true
  NETNS_EMULATOR_PID=""
}

# The emulator in this (the root) namespace, its two TAP devices moved to the hosts'.
# Skipped only when this machine gives no TAP device (no /dev/net/tun, or the
# kernel refuses `ip tuntap add`, tried first); the emulator not saying
# "ready" once the machine has them is a failure of the emulator.
netns_start_emulator() {
  if [[ ! -c /dev/net/tun ]]; then
    echo "skipped: no /dev/net/tun: the link emulator needs TAP devices"
    return 77
  fi
  local probe="wbt$$p"
  if ! ip tuntap add dev "$probe" mode tap 2>/dev/null; then
    echo "skipped: this kernel gives no TAP device (ip tuntap add failed): the link emulator needs them"
    return 77
  fi
  ip link del "$probe" 2>/dev/null || true
  NETNS_EMULATOR_LOG=$(mktemp /tmp/wbi-link-emulator.XXXXXX)
  "$@" --tap-a "$VETH_A" --tap-b "$VETH_B" >"$NETNS_EMULATOR_LOG" 2>&1 &
  NETNS_EMULATOR_PID=$!
  if ! wait_for_text "$NETNS_EMULATOR_LOG" "ready" 10; then
    cat "$NETNS_EMULATOR_LOG"
    echo "FAIL: the link emulator did not say \"ready\" within 10 s, although ip tuntap makes TAP devices here"
    return 1
  fi
}

# Namespaces of earlier runs killed before their EXIT trap could run (SIGKILL):
# wbi<PID>a/b whose PID is gone. Their processes are killed and the names
# removed, so that such a run leaves nothing behind for longer than the next run.
netns_remove_stale() {
  local ns pids
  for ns in $(ip netns list 2>/dev/null | awk '{print $1}'); do
    [[ $ns =~ ^wbi([0-9]+)[ab]$ && ! -e /proc/${BASH_REMATCH[1]} ]] || continue
    pids=$(ip netns pids "$ns" 2>/dev/null)
    echo "removing namespace $ns of a run that ended without cleaning up (processes: ${pids:-none})"
    [[ -z "$pids" ]] || kill -KILL $pids 2>/dev/null || true
    ip netns del "$ns" 2>/dev/null || true
  done
}

netns_pair_create() {
  [[ $(id -u) -ne 0 ]] || netns_remove_stale
  if [[ $(id -u) -ne 0 ]] || ! ip netns add "$NETNS_A" 2>/dev/null; then
    echo "skipped: cannot create network namespaces (needs root)"
    return 77
  fi
  trap netns_pair_cleanup EXIT
  trap 'exit 130' INT TERM
  export "$NETNS_RUN_MARK"
  ip netns add "$NETNS_B"
  if (($# > 0)); then
    netns_start_emulator "$@" || return $?
  else
    ip link add "$VETH_A" type veth peer name "$VETH_B"
  fi
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

# on_host_a LOG CMD...: starts CMD in host A's namespace, output to LOG; $! is
# its pid and the id of its own process group (setsid), which holds whatever it
# forks, so that netns_stop_processes stops them all. (`ip netns exec` and
# setsid exec, they do not fork: a background job of a script without job
# control is no group leader, the one case where setsid would fork.)
on_host_a() { local log=$1; shift; ip netns exec "$NETNS_A" setsid "$@" >"$log" 2>&1 & NETNS_PIDS+=($!); }
on_host_b() { local log=$1; shift; ip netns exec "$NETNS_B" setsid "$@" >"$log" 2>&1 & NETNS_PIDS+=($!); }

# The link between the hosts: netns_link down|up (both ends).
netns_link() { ip -n "$NETNS_A" link set "$VETH_A" "$1"; ip -n "$NETNS_B" link set "$VETH_B" "$1"; }

# wait_for_text FILE TEXT SECONDS: 0 once FILE contains TEXT, 1 on timeout.
# netns_attempts N SCRIPT ARGS...: runs SCRIPT ARGS... (WBI_NETNS_ATTEMPT set,
# so that it runs once) up to N times while it exits 75, a start-up that
# stalled where the DDS layer, not wbi, is suspected (tests/multihost/README.md,
# "Attempts"); each retry is printed. Exits with the last attempt's status.
netns_attempts() {
  local attempts=$1 attempt status
  shift
  for ((attempt = 1; attempt <= attempts; attempt++)); do
    status=0
    WBI_NETNS_ATTEMPT=$attempt "$@" || status=$?
    ((status == 75)) || exit "$status"
    echo "attempt $attempt: start-up stalled; starting again from new namespaces"
  done
  echo "FAIL: $attempts attempts stalled at start-up"
  exit 1
}

# netns_joined MODE LOG: in the discovery-server mode, waits (15 s at most) for
# the wbi_host writing LOG to be running, so that clients join the server one
# at a time (clients that joined together under load once never learnt of each
# other: "Attempts" in tests/multihost/README.md). Other modes: no wait.
netns_joined() { [[ $1 != server ]] || wait_for_text "$2" "wbi_host: running" 15 || true; }

# netns_start_all_but_controller MODE LOGS: the robot on host A, the estimator
# and the model service on host B, through the caller's `host A|B PROCESS`,
# each joined (netns_joined) before the next; the caller starts the controller.
netns_start_all_but_controller() {
  host a robot
  netns_joined "$1" "$2/robot.log"
  host b estimator
  netns_joined "$1" "$2/estimator.log"
  host b model_service
  netns_joined "$1" "$2/model_service.log"
}

wait_for_text() {
  local deadline=$((SECONDS + $3))
  while ((SECONDS < deadline)); do
    grep -qF -- "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  return 1
}
