#!/bin/bash
# The read-only socket answers status but refuses commands; modes of the two
# sockets.
. "$(dirname "$0")/../common.sh"

start_daemon || finish
ro="$SOCK/status.sock"
check "status.sock is mode 0666" test "$(stat -c %a "$ro")" = 666
check "control.sock is mode 0660" test "$(stat -c %a "$SOCK/control.sock")" = 660
check "status on the read-only socket" "$ENDOCTL" --socket "$ro" status
check "stats on the read-only socket" "$ENDOCTL" --socket "$ro" stats
check "get on the read-only socket" "$ENDOCTL" --socket "$ro" get
for cmd in enable disable estop reset "set limits.insertion_max_force_n 10" "hand 1 0 0 0"; do
	# shellcheck disable=SC2086
	check_status "'$cmd' refused on the read-only socket (exit 1)" 1 \
		"$ENDOCTL" --socket "$ro" $cmd
done
check "the refusal says why, with status READ_ONLY (4)" \
	test "$("$ENDOCTL" --socket "$ro" --json enable 2>/dev/null | jq .status)" = 4
check "nothing changed: still IDLE" test "$(status_field .state)" = IDLE
check "nothing changed: limit kept" test "$(ctl get limits.insertion_max_force_n)" = 45
finish
