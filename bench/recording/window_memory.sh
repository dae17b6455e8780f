#!/usr/bin/env bash
# The windowed recorder's resident memory over a long run (issue 40): the
# 1 kHz demo (deploy/demo.yaml under `wbi launch`) with
#   wbi record --window 5:2 --trigger LIFECYCLE --all --max-memory SIZE
# beside it for DURATION s, a LIFECYCLE event (wbi_test_emit_event) every
# 10 s so that files are written while the ring is full. Samples the
# recorder's VmRSS every second; prints one JSON object: the printed bound,
# RSS when the bound was printed, every 10 s and at its peak, the growth,
# samples, files. The bound covers the recorder's own buffers; the DDS
# readers of the topics found after the start come on top.
#   bench/recording/window_memory.sh BINARY_DIR SOURCE_DIR [DURATION_S [SIZE]]
set -euo pipefail
[[ $# -ge 2 ]] || { sed -n '2,9p' "$0"; exit 2; }
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd) duration=${3:-60} size=${4:-32M}
bin="$build/bin"
work=$(mktemp -d /tmp/wbi-window-memory.XXXXXX)
launch_pid="" recorder_pid=""
cleanup() {
  for pid in $recorder_pid $launch_pid; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in $recorder_pid $launch_pid; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
export WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-229}
sed -e "s#config: robots/#config: $src/deploy/robots/#" -e "s#\.\./models/#$src/models/#g" \
    "$src/deploy/demo.yaml" >"$work/demo.yaml"
"$bin/wbi" launch "$work/demo.yaml" --duration $((duration + 30)) >"$work/launch.log" 2>&1 &
launch_pid=$!
"$bin/wbi" record --window 5:2 --trigger LIFECYCLE --all -o "$work/windows" --probe 0 \
    --max-memory "$size" >"$work/recorder.log" 2>&1 &
recorder_pid=$!
rss() { awk '/^VmRSS:/ { print $2 * 1024 }' "/proc/$recorder_pid/status"; }
until grep -q "memory bound" "$work/recorder.log"; do sleep 0.05; done
bound=$(sed -nE 's/.*memory bound .* \(([0-9]+) bytes.*/\1/p' "$work/recorder.log")
baseline=$(rss) peak=$baseline every_10s=""
for ((s = 1; s <= duration; ++s)); do
  sleep 1
  now=$(rss)
  ((now > peak)) && peak=$now
  if ((s % 10 == 0)); then
    "$build/tests/wbi_test_emit_event" LIFECYCLE memory_bench >/dev/null 2>&1 &
    every_10s="$every_10s${every_10s:+, }$now"
  fi
done
sleep 3
kill -INT "$recorder_pid"
wait "$recorder_pid" || true
recorder_pid=""
summary=$(grep '^window recorder: ' "$work/recorder.log")
printf '{"duration_s": %d, "bound_bytes": %d, "rss_at_start": %d, "rss_peak": %d, "growth": %d, "rss_every_10s": [%s], "summary": "%s"}\n' \
  "$duration" "$bound" "$baseline" "$peak" "$((peak - baseline))" "$every_10s" "$summary"
