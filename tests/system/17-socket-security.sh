#!/bin/bash
# Socket security: the control socket checks the peer's credentials on top
# of its file mode; a bounded number of clients; a client that never reads
# is disconnected without disturbing anyone; idle and half-sent connections
# time out.
. "$(dirname "$0")/../common.sh"

if [ "$(id -u)" != 0 ]; then
	skip "needs root to act as other users (running as $(id -un))"
	finish
fi
start_daemon --set socket.group=users --set socket.max_clients=6 \
	--set socket.idle_timeout_s=1.5 --set socket.partial_timeout_s=0.5 \
	--set socket.max_queued_bytes=65536 || finish
as_nobody() { setpriv --reuid=65534 --regid=65534 --clear-groups "$@"; }
as_users() { setpriv --reuid=65534 --regid=65534 --groups=100 "$@"; }
chmod 0777 "$TMP"
check_status "mode 0660 keeps others off control.sock" 3 \
	as_nobody "$ENDOCTL" --socket "$SOCK/control.sock" status
chmod 0666 "$SOCK/control.sock" # a mistaken mode: credentials still hold
check_status "credentials: a stranger's command is refused" 1 \
	as_nobody "$ENDOCTL" --socket "$SOCK/control.sock" enable
check "with status PERMISSION (12)" test "$(as_nobody "$ENDOCTL" --socket "$SOCK/control.sock" --json enable 2>/dev/null | jq .status)" = 12
check "the refusal is logged" grep -q "refused: not root or in the command group" "$LOG"
check "the stranger may still read status" as_nobody "$ENDOCTL" --socket "$SOCK/control.sock" status
check "a member of the group may command" as_users "$ENDOCTL" --socket "$SOCK/control.sock" enable
check "-> ENABLED" test "$(status_field .state)" = ENABLED
ctl disable >/dev/null

# bounded clients: six silent holders fill the table, a seventh is turned
# away. Each holder is a socat that connects once this shell opens the
# FIFO it reads and sends nothing until the shell closes it: the holders
# stay however slowly they start, and leave together. The seventh tries
# once all six are in (ss: the daemon's connected sockets on the path).
mkfifo "$TMP/hold"
holders=""
for i in 1 2 3 4 5 6; do
	socat -u "OPEN:$TMP/hold" "UNIX-CONNECT:$SOCK/status.sock" 2>/dev/null &
	holders="$holders $!"
done
exec 3>"$TMP/hold"
# connected N: N clients or more on status.sock
connected() {
	[ "$(ss -x state established | grep -cF " $SOCK/status.sock ")" -ge "$1" ]
}
check "six silent holders connected" wait_for connected 6
check_status "a seventh client is turned away" 4 "$ENDOCTL" --socket "$SOCK" --timeout 500 status
check "too many clients is logged" grep -q "too many clients (6)" "$LOG"
exec 3>&-
# shellcheck disable=SC2086
wait $holders
check "served again once they left" wait_for ctl status

# idle and half-sent connections time out
sleep 5 | socat -u - "UNIX-CONNECT:$SOCK/status.sock" 2>/dev/null &
idle=$!
(printf '\100\000'; sleep 5) | socat -u - "UNIX-CONNECT:$SOCK/status.sock" 2>/dev/null &
partial=$!
check "an unfinished request is dropped" wait_for grep -q "unfinished request, disconnected" "$LOG"
check "an idle client is disconnected" wait_for grep -q "idle, disconnected" "$LOG"
kill $idle $partial 2>/dev/null

# a subscriber at 1000 Hz that never reads its replies: the frame is
# Request{version 1, seq 1, subscribe {rate_hz 1000.0}}, encoded by hand
subscribe='\020\000\000\000\010\001\020\001\232\001\011\011\000\000\000\000\000\100\217\100'
(printf "$subscribe"; sleep 10) | socat -u - "UNIX-CONNECT:$SOCK/status.sock" 2>/dev/null &
slow=$!
check "a client that never reads is disconnected" wait_for grep -q "replies unread, disconnected" "$LOG"
check "others are served meanwhile" ctl status
check "the loop did not notice: no fault" test "$(status_field .fault_bits)" = 0
kill $slow 2>/dev/null
finish
