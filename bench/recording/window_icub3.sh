#!/usr/bin/env bash
# Does the windowed recorder keep up with everything iCub 3 balancing
# publishes (issue 40)? The real run, not a synthetic load: deploy/icub3_balance.yaml
# (MuJoCo, lockstep, 21 s of simulated time, every process and topic of it)
# under `wbi launch`, and beside it
#   wbi record --window 5:2 --trigger LIFECYCLE --all -o DIR
# started first, so that the components' own LIFECYCLE events at their start
# and end trigger files; a LIFECYCLE event from wbi_test_emit_event 12 s into
# the run triggers one more. Every file is read: each topic whose type has a
# Header is counted on its Header.seq, and a step over a number is a loss
# (there are no outages in this run). Prints one JSON object (and writes it to
# FILE with --json FILE): files, samples, gaps and missing samples (target 0),
# the recorder's samples received, evicted inside the window, lost to a file,
# its CPU seconds and CPU µs per sample received. RECORDER=plain runs the
# plain `wbi record --all` instead, for a baseline on the same machine: its one
# file is checked the same way.
#   bench/recording/window_icub3.sh BINARY_DIR SOURCE_DIR [--json FILE]
# Skipped (exit 0, a message) without ../shared/models beside the repository.
set -euo pipefail
[[ $# -eq 2 || ($# -eq 4 && $3 == --json) ]] || { sed -n '2,19p' "$0"; exit 2; }
plain=0
[[ ${RECORDER:-window} != plain ]] || plain=1
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd) json_file=${4:-}
bin="$build/bin" tests="$build/tests"
if [[ ! -d "$src/../shared/models" ]]; then
  echo "skipped: ../shared not found (deploy/icub3_balance.yaml needs ../shared/models)"
  exit 0
fi
work=$(mktemp -d /tmp/wbi-window-icub3.XXXXXX)
deploy="$work/icub3_balance.yaml" windows="$work/windows"
launch_pid="" recorder_pid=""
cleanup() {
  for pid in $launch_pid $recorder_pid; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in $launch_pid $recorder_pid; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
export WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-231}

sed -e "s#config: robots/#config: $src/deploy/robots/#" -e "s#\.\./\.\./shared/#$src/../shared/#g" \
    "$src/deploy/icub3_balance.yaml" >"$deploy"
if ((plain)); then
  mkdir -p "$windows"
  "$bin/wbi" record --all -o "$windows/plain.mcap" >"$work/recorder.log" 2>&1 &
else
  "$bin/wbi" record --window 5:2 --trigger LIFECYCLE --all -o "$windows" --probe 0 \
      --max-memory 512M >"$work/recorder.log" 2>&1 &
fi
recorder_pid=$!
start=$SECONDS
"$bin/wbi" launch "$deploy" >"$work/launch.log" 2>&1 &
launch_pid=$!
balancing() { grep -q '^\[controller\]' "$work/launch.log"; }
until balancing || ! kill -0 "$launch_pid" 2>/dev/null || ((SECONDS - start > 120)); do sleep 0.2; done
sleep 12  # into the run: the event below falls in the middle of the balancing
"$tests/wbi_test_emit_event" LIFECYCLE bench_trigger
wait "$launch_pid" || { echo "wbi launch failed:"; tail -n 20 "$work/launch.log"; exit 1; }
launch_pid=""
sleep 3  # the last window's AFTER (2 s) and its close
read -r utime stime < <(awk '{print $14, $15}' "/proc/$recorder_pid/stat")
cpu_s=$(awk -v u="$utime" -v s="$stime" -v hz="$(getconf CLK_TCK)" 'BEGIN { printf "%.2f", (u + s) / hz }')
kill -INT "$recorder_pid"
wait "$recorder_pid" || true
recorder_pid=""
if ((plain)); then
  summary=$(grep '^recorded ' "$work/recorder.log") || { cat "$work/recorder.log"; exit 1; }
  received=$(sed -E 's/^recorded ([0-9]+) messages.*/\1/' <<<"$summary")
  summary="evicted inside the window 0, lost to a file 0"
else
  summary=$(grep '^window recorder: ' "$work/recorder.log") || { cat "$work/recorder.log"; exit 1; }
  received=$(sed -E 's/.* ([0-9]+) samples on .*/\1/' <<<"$summary")
fi
files=0 samples=0 gaps=0 missing=0
for file in $(find "$windows" -name '*.mcap' | sort); do
  report=$("$tests/wbi_test_window_check" "$file" '*' LIFECYCLE 0 0 || true)
  echo "$report" >&2
  line=$(head -n 1 <<<"$report")
  files=$((files + 1))
  samples=$((samples + $(sed -E 's/.*; \*: ([0-9]+) samples.*/\1/' <<<"$line")))
  gaps=$((gaps + $(sed -E 's/.* ([0-9]+) gaps .*/\1/' <<<"$line")))
  missing=$((missing + $(sed -E 's/.*\(([0-9]+) missing\).*/\1/' <<<"$line")))
done
evicted=$(sed -E 's/.*evicted inside the window ([0-9]+).*/\1/' <<<"$summary")
lost=$(sed -E 's/.*lost to a file ([0-9]+).*/\1/' <<<"$summary")
per_sample=$(awk -v c="$cpu_s" -v n="$received" 'BEGIN { printf "%.2f", (n > 0) ? c * 1e6 / n : 0 }')
json=$(printf '{"deploy": "icub3_balance.yaml", "recorder": "%s", "files": %d, "samples_in_files": %d, "gaps": %d, "missing": %d, "received": %d, "evicted_in_window": %d, "lost_to_file": %d, "recorder_cpu_s": %s, "cpu_us_per_sample": %s, "wall_s": %d}' \
  "${RECORDER:-window}" "$files" "$samples" "$gaps" "$missing" "$received" "$evicted" "$lost" "$cpu_s" "$per_sample" "$((SECONDS - start))")
echo "$json"
[[ -z "$json_file" ]] || echo "$json" >"$json_file"
