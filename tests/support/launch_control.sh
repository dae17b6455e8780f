# Shell helpers for the tests that run `wbi launch` in the background (sourced).

# stop_launch PID: SIGINT to the launch, which stops its processes in order,
# then waits for it, at most 30 s. False when it has not ended by then.
stop_launch() {
  local pid=$1 deadline=$((SECONDS + 30))
  kill -INT "$pid"
  while kill -0 "$pid" 2>/dev/null && ((SECONDS < deadline)); do sleep 0.1; done
  kill -0 "$pid" 2>/dev/null && return 1
  wait "$pid" || true
}
