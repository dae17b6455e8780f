#!/usr/bin/env bash
# The link emulator between two network namespaces: UDP probes from host B to
# an echo on host A over a link with a one-way delay of 5 ms and 20 % loss
# each way. Passes when the answered probes took at least 10 ms (twice the
# delay: the frames really waited), some were lost and most were not (about
# 64 % answered: 0.8 x 0.8), and the emulator's counters saw both.
#   link_emulator.sh BINARY_DIR
# Exit 0 pass, 1 fail, 77 skipped (no root, no TAP devices).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/netns_pair.sh"
[[ $# -eq 1 ]] || { sed -n '2,7p' "$0"; exit 2; }
netns_pair_create "$1/bin/wbi_link_emulator" --delay-ms 5 --loss-percent 20 --seed 11 || exit $?
logs=$(mktemp -d /tmp/wbi-link-emulator-test.XXXXXX)
NETNS_TEMP_DIR=$logs
fail() { netns_stop_processes; netns_stop_emulator; cat "$NETNS_EMULATOR_LOG" "$logs"/*; echo "FAIL: $*"; exit 1; }

on_host_a "$logs/echo.log" python3 -u -c '
import socket
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.bind(("0.0.0.0", 7777))
print("listening")
while True:
    data, peer = s.recvfrom(64)
    s.sendto(data, peer)
'
wait_for_text "$logs/echo.log" "listening" 10 || fail "the echo did not start"
# 100 probes, each waiting at most 0.3 s for its own answer (late answers to older probes are skipped).
ip netns exec "$NETNS_B" python3 - "$HOST_A_ADDRESS" >"$logs/probes.txt" <<'PY' || fail "the probes failed"
import socket, sys, time
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
rtts = []
for i in range(100):
    sent = time.monotonic()
    s.sendto(str(i).encode(), (sys.argv[1], 7777))
    deadline = sent + 0.3
    while (left := deadline - time.monotonic()) > 0:
        s.settimeout(left)
        try:
            if s.recv(64) == str(i).encode():
                rtts.append(time.monotonic() - sent)
                break
        except socket.timeout:
            break
print(len(rtts), min(rtts) * 1e3 if rtts else 0.0)
PY
read -r answered min_rtt_ms <"$logs/probes.txt"
netns_stop_processes
netns_stop_emulator
cat "$NETNS_EMULATOR_LOG"
echo "answered $answered of 100 probes; shortest round trip $min_rtt_ms ms"
((answered >= 35 && answered <= 90)) || fail "$answered of 100 probes answered with 20 % loss each way (expected about 64)"
awk -v t="$min_rtt_ms" 'BEGIN { exit !(t >= 10) }' || fail "a round trip took $min_rtt_ms ms with a 5 ms one-way delay"
lost=$(sed -n 's/.*: forwarded [0-9]*, lost \([0-9]*\),.*/\1/p' "$NETNS_EMULATOR_LOG")
(($(wc -l <<<"$lost") == 2)) && ! grep -qx 0 <<<"$lost" || fail "the emulator counted no loss in one direction"
echo "PASS: link emulator; $answered of 100 answered, shortest round trip $min_rtt_ms ms"
