#!/bin/bash
# systemd's watchdog follows the force loop: a stalled loop (the test
# command) stops the WATCHDOG=1 pings while the rest of the daemon still
# runs and answers. Then, as systemd does after WatchdogSec without a
# ping, the daemon is aborted: the drives are already off (their bus
# stopped them when the loop's commands grew old), and a restarted daemon
# comes up IDLE with no torque. A stall shorter than that leaves the
# daemon in FAULT (overrun budget) with torque zero. The notify socket is
# the test's own (tests/tools/notify_listen).
. "$(dirname "$0")/fault_lib.sh"

ulimit -c 0 # an aborted daemon leaves no core behind
notify="$TMP/notify.sock"
"$TOOLS/notify_listen" "$notify" >"$TMP/notify.log" 2>&1 &
listener=$!
wait_for test -S "$notify"

# mark NAME: a line in the listener's log, on its clock
mark() {
	printf 'MARK=%s' "$1" | socat -u - "UNIX-SENDTO:$notify"
	wait_for grep -q "MARK=$1" "$TMP/notify.log"
}

# pings MARK FROM TO: how many WATCHDOG=1 between FROM and TO s after MARK
pings() {
	awk -v m="MARK=$1" -v a="$2" -v b="$3" '
		NR == FNR { if ($2 == m) t0 = $1; next }
		$2 == "WATCHDOG=1" && $1 > t0 + a && $1 < t0 + b { n++ }
		END { print n + 0 }' "$TMP/notify.log" "$TMP/notify.log"
}

grep -qE "^WatchdogSec=" "$TOP/systemd/endosimd.service"
check "the unit has a watchdog (WatchdogSec) ..." [ $? = 0 ]
check "... and restarts the service when it fires" \
	grep -q "^Restart=on-failure" "$TOP/systemd/endosimd.service"

# a short stall: pings stop, then the loop is back in FAULT
export NOTIFY_SOCKET="$notify" WATCHDOG_USEC=200000
check "simulated rig up, enabled (a missed budget a fault)" start_sim --set loop.overrun_fault=yes
sleep 0.6
# the marks come once the loop has taken the stall (the command's answer
# is the loop's): a busy machine that delays the command moves no window
check "the loop stalled for 1.5 s" ctl debug stall 1.5
mark stall
check "the daemon answers while its loop is stalled" ctl status
sleep 2.6
mark after
check "pinged before the stall ($(pings stall -0.6 -0.1) pings)" \
	[ "$(pings stall -0.6 -0.1)" -ge 2 ]
check "no ping while the loop is stalled" [ "$(pings stall 0.25 1.0)" = 0 ]
check "pings again once the loop runs ($(pings stall 1.6 2.5))" \
	[ "$(pings stall 1.6 2.5)" -ge 1 ]
check "afterwards: FAULT, the overrun budget" fault_says "overrun-budget"
check "afterwards: torque zero on every axis" \
	status_true '[.axes[].limited] | all(. == 0)'
stop_daemon

# a stall as long as systemd's patience: what systemd does, done by hand
check "Modbus rig up, enabled" start_mb_rig
check "the loop stalled for 5 s" ctl debug stall 5
mark stall2
sleep 1.2
check "no ping for a second" [ "$(pings stall2 0.25 1.2)" = 0 ]
check "the wheel drives stopped meanwhile" wheels_off
kill -ABRT "$DAEMON_PID"
wait "$DAEMON_PID"
rc=$?
DAEMON_PID=""
check "aborted as systemd does at WatchdogSec (status $rc)" [ "$rc" -ge 128 ]
check "the wheel drives stay off" wheels_off
unset NOTIFY_SOCKET WATCHDOG_USEC
check "restarted" start_on "$TMP/mb-rig.conf"
check "restarted: IDLE, no fault" \
	[ "$(status_field .state)/$(status_field .fault_bits)" = IDLE/0 ]
check "restarted: torque zero, wheels off" \
	status_true '[.axes[].limited] | all(. == 0)'
check "restarted: the drives stay disabled until enable" wheels_off
kill "$listener" 2>/dev/null
finish
