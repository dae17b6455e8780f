#!/usr/bin/env bash
# Cross-host figures on two network namespaces joined by a veth pair (the
# hosts of tests/multihost), user data over UDP, with and without DDS Security:
#   service  the model service on host A, wbi_bench_multihost_service on host B:
#            gravity round trip and discovery time (fresh participant + client
#            until connected), for each discovery mode: multicast, peers,
#            server (when fastdds-tools is installed) and multicast secured;
#   latency  bench/multihost/latency_demo.yaml (robot on A; estimator, model
#            service and controller on B), wbi_bench_multihost_latency on A:
#            sensor-to-command latency and deadline misses, plain and secured.
# Prints a Markdown table with the load average of each row, and keeps each
# run's JSON in OUTDIR when given.
#   bench/multihost/run.sh BINARY_DIR SOURCE_DIR [--calls N] [--duration S] [--out OUTDIR]
# Needs root (exit 77 otherwise). Build first:
#   cmake --build BUILD --target wbi wbi_host wbi_bench_multihost_service wbi_bench_multihost_latency
set -euo pipefail
[[ $# -ge 2 ]] || { sed -n '2,15p' "$0"; exit 2; }
bin="$1/bin" source_dir=$(cd "$2" && pwd)
shift 2
calls=5000 duration=20 out=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --calls) calls=$2; shift 2 ;;
    --duration) duration=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "unknown option '$1'"; exit 2 ;;
  esac
done
source "$source_dir/tests/multihost/netns_pair.sh"
netns_pair_create || exit $?
work=$(mktemp -d /tmp/wbi-bench-multihost.XXXXXX)
NETNS_TEMP_DIR=$work
[[ -z "$out" ]] || mkdir -p "$out"
export WBI_DOMAIN_ID=${WBI_DOMAIN_ID:-220}
service_deploy="$source_dir/deploy/multihost_lockstep.yaml"
latency_deploy="$source_dir/bench/multihost/latency_demo.yaml"
"$source_dir/scripts/wbi-security-setup" "$latency_deploy" "$work/keys" >/dev/null

load() { cut -d' ' -f1-3 /proc/loadavg; }
# on HOST NAME [VAR=value...] -- CMD...: CMD on host a|b with the overrides, output to $work/NAME.log.
on() {
  local host=$1 name=$2 overrides=()
  shift 2
  while [[ $1 != -- ]]; do overrides+=("$1"); shift; done
  shift
  "on_host_$host" "$work/$name.log" env "${overrides[@]}" stdbuf -oL "$@"
}
# measure NAME HOST [VAR=value...] -- CMD...: runs CMD on HOST in the foreground; its JSON line.
measure() {
  local name=$1 host=$2 overrides=()
  shift 2
  while [[ $1 != -- ]]; do overrides+=("$1"); shift; done
  shift
  local netns=$NETNS_A
  [[ $host == b ]] && netns=$NETNS_B
  if ! ip netns exec "$netns" env "${overrides[@]}" timeout 300 "$@" >"$work/$name.out" 2>&1; then
    netns_stop_processes
    for log in "$work"/*.log "$work/$name.out"; do echo "== $log"; cat "$log"; done
    echo "FAIL: $name"
    exit 1
  fi
  [[ -z "$out" ]] || tail -n 1 "$work/$name.out" >"$out/$name.json"
  tail -n 1 "$work/$name.out"
}
field() { python3 -c 'import json, sys; print(round(json.loads(sys.argv[1])[sys.argv[2]], 1))' "$1" "$2"; }

rows=()
# service MODE [VAR=value...]: the model service on A, the client on B.
service() {
  local mode=$1
  shift
  if [[ $mode == server ]]; then
    on a discovery_server -- fastdds discovery -i 0 -l "$HOST_A_ADDRESS" -p 11811
    wait_for_text "$work/discovery_server.log" "Server is running" 10 || { cat "$work/discovery_server.log"; exit 1; }
  fi
  on a "service_$mode" "$@" -- "$bin/wbi_host" "$service_deploy" --process model_service
  local json
  json=$(measure "service_$mode" b "$@" -- "$bin/wbi_bench_multihost_service" \
    --deploy "$service_deploy" --identity controller --calls "$calls")
  netns_stop_processes
  rows+=("| model service, gravity round trip | $mode | $(field "$json" rtt_p50_us) / $(field "$json" rtt_p99_us) µs | $(field "$json" discovery_p50_ms) ms (max $(field "$json" discovery_max_ms)) | $(load) |")
}
# latency MODE [VAR=value...]: the demo across the hosts, observed on A.
latency() {
  local mode=$1
  shift
  on a "robot_$mode" "$@" -- "$bin/wbi_host" "$latency_deploy" --process robot
  on b "estimator_$mode" "$@" -- "$bin/wbi_host" "$latency_deploy" --process estimator
  on b "model_service_$mode" "$@" -- "$bin/wbi_host" "$latency_deploy" --process model_service
  on b "controller_$mode" "$@" -- "$bin/wbi_host" "$latency_deploy" --process controller
  local json
  json=$(measure "latency_$mode" a "$@" -- "$bin/wbi_bench_multihost_latency" \
    --deploy "$latency_deploy" --duration "$duration")
  netns_stop_processes
  rows+=("| sensor to command, demo at 1 kHz | $mode | $(field "$json" latency_p50_us) / $(field "$json" latency_p99_us) µs (max $(field "$json" latency_max_us)); deadline misses $(field "$json" deadline_miss_percent) % | — | $(load) |")
}

secured=("WBI_DDS_SECURITY_DIRECTORY=$work/keys")
service multicast
service secure "${secured[@]}"
service peers WBI_DDS_DISCOVERY=peers "WBI_DDS_PEERS=$HOST_A_ADDRESS,$HOST_B_ADDRESS"
if command -v fastdds >/dev/null; then
  service server WBI_DDS_DISCOVERY=server "WBI_DDS_DISCOVERY_SERVER=$HOST_A_ADDRESS:11811"
else
  echo "no fastdds tool (apt-get install fastdds-tools): discovery server mode left out"
fi
latency multicast
latency secure "${secured[@]}"

echo "| figure | mode | p50 / p99 | discovery | load average |"
echo "|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
