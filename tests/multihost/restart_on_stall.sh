#!/usr/bin/env bash
# What `wbi launch` does for a process whose start stalled, for the tests that
# start each wbi_host by hand: runs COMMAND, and starts it again while it ends
# with exit code 75 (wbi_host's HandshakeWatch, runtime/handshake_watch.hpp:
# a secured handshake pending too long while it started), 3 restarts at most,
# as deploy/launcher does. SIGTERM and SIGINT are passed on to COMMAND; exits
# with COMMAND's last exit code.
#   restart_on_stall.sh COMMAND [ARGS...]
set -uo pipefail
[[ $# -ge 1 ]] || { sed -n '2,8p' "$0"; exit 2; }
child=""
stopping=0
forward() {
  stopping=1
  [[ -z $child ]] || kill "-$1" "$child" 2>/dev/null || true
}
trap 'forward TERM' TERM
trap 'forward INT' INT
for ((restarts = 0; ; restarts++)); do
  "$@" &
  child=$!
  # A trapped signal ends `wait` early: wait again until the child has ended.
  wait "$child"
  status=$?
  while kill -0 "$child" 2>/dev/null; do
    wait "$child"
    status=$?
  done
  ((status == 75 && restarts < 3 && stopping == 0)) || exit "$status"
  echo "restart_on_stall.sh: '$*' ended with exit code 75 (start-up stalled): starting it again"
done
