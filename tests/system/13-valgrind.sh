#!/bin/bash
# endosimd through a working session (commands, parameter changes,
# subscriptions, hostile input, users, groups and logins, a group's
# course, a trainee at the rig, SIGTERM): no memory errors, and nothing
# leaked at exit. The plain build runs under valgrind; the sanitizers'
# build (which valgrind cannot run) runs the same session under its own
# AddressSanitizer, with LeakSanitizer's check at exit.
. "$(dirname "$0")/../common.sh"

# endoctl with time to spare: under valgrind the daemon runs some 30 times
# slower, and a reply (set waits for the force loop to take the new
# configuration) took over endoctl's default 2 s on a loaded VM; this test
# is about memory, not about how fast the daemon answers
CTL_TIMEOUT_MS=20000

# session: the working session's commands, each a check
session() {
	WAIT_S=5
	check "enable" ctl enable
	check "set" ctl set limits.insertion_max_force_n 20
	check "get" ctl get
	check "stats" ctl stats
	check "watch" ctl --json watch --rate 20 --duration 1
	check "hand" ctl hand 1 0 0 0
	head -c 3000 /dev/urandom | timeout 5 socat -t 1 - "UNIX-CONNECT:$SOCK/control.sock" >/dev/null 2>&1
	printf '\377\377\377\177' | timeout 5 socat -t 1 - "UNIX-CONNECT:$SOCK/status.sock" >/dev/null 2>&1
	check "estop" ctl estop
	check "reset" ctl reset
	check "users and a group" eval 'ENDOSIM_NEW_PIN=48213579 ctl user add \
		Ann --role trainee && ENDOSIM_NEW_PIN=16180339 ctl user add \
		Ives --role instructor && ctl group add 2026 --instructor \
		Ives && ctl group join 2026 Ann && ctl group list'
	check "logged in: the group, the sessions" eval 'ENDOSIM_PIN=16180339 \
		ctl --as Ives group list && ENDOSIM_PIN=48213579 \
		ctl --as Ann session list'
	check_status "a wrong PIN" 1 eval 'ENDOSIM_PIN=00000000 \
		ctl --as Ann whoami'
	check "the group's course judges Ann's sessions" eval 'ctl group \
		assign 2026 basic && ctl trainee list'
	check "Ann trains at the rig, then logs out" eval 'ENDOSIM_PIN=48213579 \
		ctl login Ann && ctl status && ctl logout'
}

if ldd "$ENDOSIMD" | grep -q libasan; then
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 "$ENDOSIMD" \
		--config "$TOP/config/endosimd.conf" "${DAEMON_ARGS[@]}" \
		--scenario "$TOP/config/scenarios/demo.scn" >>"$LOG" 2>&1 &
	DAEMON_PID=$!
	WAIT_S=30
	check "comes up under AddressSanitizer" wait_for ctl status
	session
	check "SIGTERM: exit 0 (a leak at exit would make it 23)" stop_daemon
	check "no AddressSanitizer or LeakSanitizer report" \
		eval '! grep -E "ERROR: (AddressSanitizer|LeakSanitizer)" "$LOG"'
	finish
fi
if ! command -v valgrind >/dev/null; then
	fail "valgrind is missing (Debian package valgrind)"
	finish
fi
vg="$TMP/valgrind.log"
# valgrind runs the force loop tens of times slower than real time: its
# overruns are not what this test is about (budget 1000 periods in 10 ms)
valgrind --leak-check=full --show-leak-kinds=definite,indirect,possible \
	--errors-for-leak-kinds=definite,indirect,possible --error-exitcode=99 \
	--log-file="$vg" "$ENDOSIMD" --config "$TOP/config/endosimd.conf" \
	"${DAEMON_ARGS[@]}" --scenario "$TOP/config/scenarios/demo.scn" \
	--set loop.overrun_budget=1000 --set loop.overrun_window_s=0.01 \
	>>"$LOG" 2>&1 &
DAEMON_PID=$!
WAIT_S=30
check "comes up under valgrind" wait_for ctl status
session
check "SIGTERM: exit 0 (valgrind exits 99 on any error or leak)" stop_daemon
check "no memory errors" grep -q "ERROR SUMMARY: 0 errors" "$vg"
check "nothing leaked" grep -qE "All heap blocks were freed|definitely lost: 0 bytes" "$vg"
grep -E "total heap usage|ERROR SUMMARY" "$vg" | sed 's/^==[0-9]*== /# /'
finish
