#!/usr/bin/env bash
# netns_pair.sh's own teardown, with no wbi program (issue 44): every process a
# multi-host test starts must end with it.
#   1. forking programs started with on_host_a (a shell with two children and,
#      when fastdds-tools is installed, `fastdds discovery`: a Python wrapper
#      whose child is the server) are stopped whole by netns_stop_processes:
#      the namespaces are empty afterwards and the run passes its own check;
#   2. a run that leaves processes behind (one that left its process group
#      inside a namespace, one started on the host and never stopped) fails,
#      names both, and still ends with nothing of it left.
#   netns_pair_check.sh
# Exit 0 pass, 1 fail, 77 skipped (no root).
# (Internally: netns_pair_check.sh --run forking|leaking, one such run.)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/netns_pair.sh"

# run_forking: the programs' whole trees stopped; nothing in the namespaces after.
run_forking() {
  local log=$NETNS_TEMP_DIR/shell.log
  on_host_a "$log" sh -c 'sleep 300 & sleep 300 & echo started; wait'
  wait_for_text "$log" started 10 || { echo "FAIL: the shell did not start"; exit 1; }
  if command -v fastdds >/dev/null; then
    on_host_a "$NETNS_TEMP_DIR/server.log" stdbuf -oL fastdds discovery -i 0 -l "$HOST_A_ADDRESS" -p 11811
    wait_for_text "$NETNS_TEMP_DIR/server.log" "Server is running" 10 ||
      { cat "$NETNS_TEMP_DIR/server.log"; echo "FAIL: the discovery server did not start"; exit 1; }
  fi
  echo "in host A: $(ip netns pids "$NETNS_A" | wc -l) processes"
  netns_stop_processes
  local left
  left=$(ip netns pids "$NETNS_A"; ip netns pids "$NETNS_B")
  [[ -z "$left" ]] || { echo "FAIL: netns_stop_processes left $(wc -l <<<"$left") process(es) in the namespaces"; exit 1; }
}

# run_leaking: a process that left its group (setsid) in host A, one on the host.
run_leaking() {
  local log=$NETNS_TEMP_DIR/leak.log
  on_host_a "$log" sh -c 'setsid sleep 301 & echo started; wait'
  wait_for_text "$log" started 10 || { echo "FAIL: the shell did not start"; exit 1; }
  sleep 302 &
}

if [[ ${1:-} == --run ]]; then
  netns_pair_create || exit $?
  NETNS_TEMP_DIR=$(mktemp -d /tmp/wbi-netns-check.XXXXXX)
  echo "run $NETNS_A $NETNS_B"
  "run_$2"
  exit 0
fi

[[ $(id -u) -eq 0 ]] || { echo "skipped: cannot create network namespaces (needs root)"; exit 77; }
# one_run MODE: runs it; sets out (its output) and code (its exit code); fails
# when anything of it (its namespaces, a process with its mark) is left.
one_run() {
  set +e
  out=$("$0" --run "$1" 2>&1)
  code=$?
  set -e
  echo "$out" | sed "s/^/  [$1] /"
  ((code != 77)) || exit 77
  local names mark
  names=$(sed -n 's/^run \(wbi[0-9]*a\) \(wbi[0-9]*b\)$/\1 \2/p' <<<"$out")
  [[ -n "$names" ]] || { echo "FAIL: the $1 run did not make its namespaces"; exit 1; }
  for ns in $names; do
    ! ip netns list | grep -qw "$ns" || { echo "FAIL: the $1 run left namespace $ns"; exit 1; }
  done
  NETNS_RUN_MARK="WBI_NETNS_RUN=${names%%a *}"  # the run's mark: wbi<its pid>
  for pid in /proc/[0-9]*; do
    pid=${pid#/proc/}
    if [[ $pid != "$$" && $pid != "$BASHPID" ]] && netns_has_mark "$pid"; then
      echo "FAIL: the $1 run left pid $pid: $(tr '\0' ' ' <"/proc/$pid/cmdline")"; kill -KILL "$pid"; exit 1
    fi
  done
}

one_run forking
((code == 0)) || { echo "FAIL: the forking run failed (exit $code)"; exit 1; }
one_run leaking
((code == 1)) || { echo "FAIL: a run that left two processes behind exited $code, not 1"; exit 1; }
grep -q "sleep 301" <<<"$out" && grep -q "sleep 302" <<<"$out" ||
  { echo "FAIL: the leftovers were not both named"; exit 1; }
echo "PASS: forking programs stopped whole; a run leaving two processes failed and named them, and nothing of either run is left"
