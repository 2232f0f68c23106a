#!/bin/bash
# SIGTERM and SIGINT: torque to zero, exit 0 within a second, sockets and
# shared memory removed.
. "$(dirname "$0")/../common.sh"

ms() { echo $(($(date +%s%N) / 1000000)); }
for sig in TERM INT; do
	start_daemon --scenario "$TOP/config/scenarios/demo.scn" || finish
	ctl enable >/dev/null
	sleep 0.3
	t0=$(ms)
	kill -"$sig" "$DAEMON_PID"
	wait "$DAEMON_PID"
	rc=$?
	dt=$(($(ms) - t0))
	DAEMON_PID=""
	check "SIG$sig: exit status 0" test "$rc" = 0
	check "SIG$sig: gone within a second (${dt} ms)" test "$dt" -lt 1000
	check "SIG$sig: torque off logged" grep -q "stopping, torque off" "$LOG"
	check "SIG$sig: sockets removed" test ! -e "$SOCK/control.sock" -a ! -e "$SOCK/status.sock"
	check "SIG$sig: shared memory removed" test ! -e "/dev/shm$SHM"
	: >"$LOG"
done
finish
