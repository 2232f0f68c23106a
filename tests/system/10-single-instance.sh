#!/bin/bash
# A second daemon on the same sockets or the same shared memory refuses to
# start, and the first one carries on.
. "$(dirname "$0")/../common.sh"

start_daemon || finish
check_status "same socket directory: refused" 69 endosimd \
	--shm-name "/endosim-other-$$"
check "says another endosimd is running" grep -q "another endosimd is running" "$OUT"
check_status "same shared memory: refused" 69 endosimd \
	--socket-dir "$TMP/other"
check "says the shm is in use" grep -q "in use by another endosimd" "$OUT"
check "the first daemon still answers" ctl status
check "its sockets are intact" test -S "$SOCK/control.sock" -a -S "$SOCK/status.sock"
check_status "a missing socket group is a start-up error" 69 endosimd \
	--socket-dir "$TMP/g" --shm-name "/endosim-g-$$" \
	--set socket.group=no-such-group-xyz
check "naming the group" grep -q "group 'no-such-group-xyz' does not exist" "$OUT"
finish
