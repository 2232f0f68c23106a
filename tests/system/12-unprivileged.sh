#!/bin/bash
# Without root or CAP_SYS_NICE the force loop cannot have SCHED_FIFO: the
# daemon says so once, reports SCHED_OTHER, and runs anyway.
. "$(dirname "$0")/../common.sh"

if [ "$(id -u)" != 0 ] || ! command -v setpriv >/dev/null; then
	skip "needs root and setpriv to drop privileges (running as $(id -un))"
	finish
fi
chmod 0777 "$TMP"
setpriv --reuid=65534 --regid=65534 --clear-groups --inh-caps=-all \
	--bounding-set=-all "$ENDOSIMD" --config "$TOP/config/endosimd.conf" \
	"${DAEMON_ARGS[@]}" >>"$LOG" 2>&1 &
DAEMON_PID=$!
check "comes up without privileges" wait_for ctl status
check "reports SCHED_OTHER" test "$(status_field .rt_policy)" = SCHED_OTHER
check "priority 0" test "$(status_field .rt_priority)" = 0
c1=$(status_field .cycle)
sleep 0.3
check "and runs anyway" test "$(status_field .cycle)" -gt "$c1"
check "one warning about SCHED_FIFO" test "$(grep -c 'no permission for SCHED_FIFO' "$LOG")" = 1
check "the warning says what is needed" grep -q "CAP_SYS_NICE" "$LOG"
check "stats say the same" test "$(ctl --json stats | jq -r .rt_policy)" = SCHED_OTHER
check "stops cleanly" stop_daemon
finish
