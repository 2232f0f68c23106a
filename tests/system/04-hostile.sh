#!/bin/bash
# Random bytes, huge length prefixes, truncated and undecodable messages on
# both sockets: the daemon answers or hangs up, and carries on.
. "$(dirname "$0")/../common.sh"

start_daemon || finish
send() { # SOCKET: stdin to the socket, the reply (if any) to stdout
	timeout 5 socat -t 1 - "UNIX-CONNECT:$1" 2>/dev/null
}
alive() {
	local c1 c2
	c1=$(status_field .cycle) && sleep 0.05 && c2=$(status_field .cycle) &&
		[ "$c2" -gt "$c1" ]
}
for s in status.sock control.sock; do
	head -c 65536 /dev/urandom | send "$SOCK/$s" >/dev/null
	check "$s: 64 KiB of random bytes, daemon alive" alive
	printf '\377\377\377\177' | send "$SOCK/$s" >"$TMP/reply"
	check "$s: a 2 GiB length prefix gets an error reply" test -s "$TMP/reply"
	check "$s: daemon alive after the huge prefix" alive
	printf '\144\000\000\000truncated' | send "$SOCK/$s" >/dev/null
	check "$s: a truncated message, daemon alive" alive
	printf '\010\000\000\000\377\377\377\377\377\377\377\377' | send "$SOCK/$s" >"$TMP/reply"
	check "$s: an undecodable message gets a reply" test -s "$TMP/reply"
	printf '\000\000\000\000' | send "$SOCK/$s" >"$TMP/reply"
	check "$s: an empty message gets a reply" test -s "$TMP/reply"
done
# many junk connections at once
pids=""
for i in $(seq 1 20); do
	head -c 1000 /dev/urandom | send "$SOCK/control.sock" >/dev/null &
	pids="$pids $!"
done
# shellcheck disable=SC2086
wait $pids
check "after 20 parallel junk clients, daemon alive" alive
check "and still takes commands" ctl enable
check "state ENABLED" test "$(status_field .state)" = ENABLED
check "no fault from any of it" test "$(status_field .fault_bits)" = 0
finish
