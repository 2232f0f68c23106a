#!/bin/bash
# Fault: feedback no longer renewed. On the simulated rig (the insertion's
# feedback frozen by the test command) and on the Modbus line (a drive
# that stops answering while its reply timeout is longer than the
# feedback's allowed age, so that the feedback grows old before the
# transaction fails): FAULT once the feedback is older than allowed, not
# before, with torque zero on every axis in that cycle; reset refused while
# it stays old, recovered once it is fresh again.
. "$(dirname "$0")/fault_lib.sh"

check "simulated rig up, enabled, every axis moving" start_sim
max_age=$(ctl get rig.feedback_max_age_s)
watch_fault 0x4
debug stale insertion
expect_fault "sim stale" stale-feedback insertion "no feedback for"
age_ms=$(awk -v ns="$(($(watched fault_ns) - $(watched watch_ns)))" 'BEGIN { print ns / 1e6 }')
check "sim stale: found once older than $max_age s, not before ($age_ms ms after the watch began)" \
	awk -v v="$(watched fault_value)" -v lim="$max_age" -v t="$age_ms" \
	'BEGIN { exit !(v > lim && v < lim + 0.5 && t >= lim * 1e3) }'
refused_while "sim stale"
debug clear insertion
recovers "sim stale"
stop_daemon

conf=$(mb_rig_conf)
# a silent drive's transaction waits 2 s; feedback may be 0.3 s old
sed -i -e 's/^response_timeout_s = .*/response_timeout_s = 2/' \
	-e 's/^feedback_max_age_s = .*/feedback_max_age_s = 0.3/' "$conf"
check "Modbus emulator up" start_modbus "$conf" --pty "$TMP/tty" "${MB_MOTOR[@]}"
check "endosimd up on it" start_on "$conf" "${FAULT_ARGS[@]}" --scenario "$SOAK"
mb "hand 1 0.004 1"
check "enabled" ctl enable
check "forces in full" wait_for status_true '.ramp == 1'
watch_fault 0x4
mb "mute 1 on"
expect_fault "Modbus stale" stale-feedback wheel_ud "no feedback for" \
	"limit 300 ms"
check "Modbus stale: found past 0.3 s (at $(watched fault_value) s)" \
	awk -v v="$(watched fault_value)" 'BEGIN { exit !(v > 0.3 && v < 2) }'
mb "mute 1 off"
recovers "Modbus stale"
finish
