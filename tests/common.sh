# common.sh - shared by the system tests (tests/system/NN-name.sh) and the
# demo: start endosimd on the simulated rig in a private socket directory
# with a private shm name, talk to it with endoctl, count checks.
#
# A test script sources this file, calls start_daemon, makes checks with
# `check DESCRIPTION COMMAND...` (or pass/fail, or skip for a check that
# cannot be made here), and ends with `finish`, which prints "N passed, N
# failed" (", N skipped" after it when any were) and exits non-zero on any
# failure. A daemon that does not come up is a failed check. The daemon and
# the temporary directory are cleaned up on exit whatever happens.

set -u

TOP=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
: "${BUILD:=build}"
case "$BUILD" in /*) ;; *) BUILD="$TOP/$BUILD" ;; esac
ENDOSIMD="$BUILD/endosimd"
# the shipped cases from the source tree (installed: $(DATADIR)/cases)
CASES="$TOP/config/cases"
ENDOCTL="$BUILD/endoctl"
TOOLS="$BUILD/tests"

TMP=$(mktemp -d /tmp/endosim-test.XXXXXX)
SOCK="$TMP/run"
SHM="/endosim-test-$$"
LOG="$TMP/endosimd.log"
DAEMON_PID=""
PASSED=0
FAILED=0
SKIPPED=0

pass() {
	PASSED=$((PASSED + 1))
	echo "ok - $1"
}

fail() {
	FAILED=$((FAILED + 1))
	echo "not ok - $1"
	if [ -n "${2:-}" ]; then
		echo "#   $2"
	fi
}

# skip WHY: a check that cannot be made here, and why; neither passed nor
# failed, counted apart.
skip() {
	SKIPPED=$((SKIPPED + 1))
	echo "skip - $1"
}

# check DESCRIPTION COMMAND...: passes when COMMAND succeeds. A failure is
# counted once, even when COMMAND recorded its own (start_daemon does).
check() {
	local what=$1 failed=$FAILED
	shift
	if "$@" >"$TMP/check.out" 2>&1; then
		pass "$what"
	else
		FAILED=$failed
		fail "$what" "$(tail -n 3 "$TMP/check.out" | tr '\n' ' ')"
	fi
}

# check_status DESCRIPTION STATUS COMMAND...: passes when COMMAND exits
# with STATUS. Its output stays in $OUT for the checks that follow.
OUT="$TMP/last.out"
check_status() {
	local what=$1 want=$2 got
	shift 2
	"$@" >"$OUT" 2>&1
	got=$?
	if [ "$got" = "$want" ]; then
		pass "$what"
	else
		fail "$what" "exit $got, expected $want: $(tail -n 2 "$OUT" | tr '\n' ' ')"
	fi
}

# ctl ARGS...: endoctl on the test's daemon; CTL_TIMEOUT_MS, when set,
# how long it waits for a reply (endoctl's own default otherwise). Under
# the sanitizers 20 s unless set: the instrumented daemon answers a
# request that loads a case several times slower (a session started with
# --case once took over endoctl's 2 s in the pool), and no check run
# there is about how soon an answer comes.
if [ -n "${SANITIZED:-}" ]; then
	CTL_TIMEOUT_MS=${CTL_TIMEOUT_MS:-20000}
fi
ctl() {
	"$ENDOCTL" --socket "$SOCK" \
		${CTL_TIMEOUT_MS:+--timeout "$CTL_TIMEOUT_MS"} "$@"
}

# status_field JQ: a jq expression over `endoctl --json status`.
status_field() {
	ctl --json status | jq -r "$1"
}

# status_true JQ: the jq expression over the status is true.
status_true() {
	[ "$(status_field "$1")" = true ]
}

# wait_for COMMAND...: retries for up to $WAIT_S seconds (default 20: a
# busy shared machine stalls for seconds at times; a pass costs no more).
# The limit is on the clock, not a count of tries: a COMMAND that itself
# takes a while (an export of a long recording under ASan) cannot stretch
# it into minutes.
wait_for() {
	local deadline=$((${EPOCHREALTIME//[!0-9]/} + ${WAIT_S:-20} * 1000000))
	while :; do
		if "$@" >/dev/null 2>&1; then
			return 0
		fi
		[ "${EPOCHREALTIME//[!0-9]/}" -lt "$deadline" ] || return 1
		sleep 0.05
	done
}

# What every daemon of a test gets: its own socket directory and shm name,
# no socket group (tests need not create one), the source tree's cases.
DAEMON_ARGS=(--socket-dir "$SOCK" --shm-name "$SHM" --set socket.group=
	--set "case.directory=$CASES" --session-dir "$TMP/sessions")
# In the system tests, an overrun budget no stall of a shared VM reaches:
# stalls of 100-150 ms (steal from a busy host) were seen, which the
# default budget (50 periods a second) rightly calls a fault on a rig with
# real drives, but which would latch one in tests about something else (on
# the simulated rig a missed budget only warns: [loop] overrun_fault).
# 54-fault-overrun stalls the loop past it; the soak bench keeps the
# default.
case "$0" in
*tests/system/*) DAEMON_ARGS+=(--set loop.overrun_budget=1000) ;;
esac

# endosimd ARGS...: the daemon in the foreground with DAEMON_ARGS.
endosimd() {
	"$ENDOSIMD" "${DAEMON_ARGS[@]}" "$@"
}

# answers_or_gone: the daemon answers, or has exited (no use waiting).
answers_or_gone() {
	ctl status || ! kill -0 "$DAEMON_PID" 2>/dev/null
}

# start_daemon [ARGS...]: endosimd on the simulated rig, in the background
# (not through the function above: $! must be the daemon's own pid). When
# it does not answer, that is a failed check, the daemon is killed and
# reaped (its exit status must not pass for a clean stop), and it returns
# 1: `start_daemon || finish`.
start_daemon() {
	local rc last

	"$ENDOSIMD" "${DAEMON_ARGS[@]}" --config "$TOP/config/endosimd.conf" \
		"$@" >>"$LOG" 2>&1 &
	DAEMON_PID=$!
	wait_for answers_or_gone
	if ! ctl status >/dev/null 2>&1; then
		kill -KILL "$DAEMON_PID" 2>/dev/null
		wait "$DAEMON_PID"
		rc=$?
		last=$(tail -n 1 "$LOG")
		fail "endosimd started" "no answer on $SOCK (exit $rc)${last:+: $last}"
		DAEMON_PID=""
		return 1
	fi
}

# live_status JQ: the recording session's status (`endoctl --json
# session status`) satisfies JQ.
live_status() { ctl --json session status | jq -e "$1"; }

# record NAME [N]: a session of trainee NAME on the test's (or the
# slot's) daemon, more than N records long (300 unless given), stopped.
record() {
	ctl session start --trainee "$1" >/dev/null &&
		wait_for live_status ".records > ${2:-300}" &&
		ctl session stop >/dev/null
}

# stop_daemon: SIGTERM and wait; returns the daemon's exit status.
stop_daemon() {
	local rc
	if [ -z "$DAEMON_PID" ]; then
		return 0
	fi
	kill -TERM "$DAEMON_PID" 2>/dev/null
	wait "$DAEMON_PID"
	rc=$?
	DAEMON_PID=""
	return $rc
}

# keep_picture FILE NAME: FILE, a screenshot the docs show, kept as
# $BUILD/pictures/NAME.png (`make pictures` copies them over docs/;
# tests/system/19-docs.sh checks that every picture the docs show is one
# that a test keeps so, NAME written out in its call). Nothing when the
# screenshot was not taken (its check has failed).
keep_picture() {
	[ -s "$1" ] || return 0
	mkdir -p "$BUILD/pictures" && cp "$1" "$BUILD/pictures/$2.png"
}

# --- more than one daemon ----------------------------------------------------
# A test may keep daemons in slots, each with its own socket directory, shm
# name, session directory and log (the first slot, "main", is the one
# above): one runs a course while the test checks another, instead of
# the test waiting for each course in turn (the simulated rig's clock
# counts the force loop's cycles, so a course reaches the same states
# whenever the test looks; a daemon at rest takes a few per cent of a CPU).
# use_slot NAME: from now on start_daemon, stop_daemon, ctl and the checks
# are NAME's; the daemon of the slot left keeps running (cleanup and
# finish see to every slot). A library keeps variables of its own per slot
# by naming them in SLOT_VARS (fault_lib.sh: the session file).
SLOT=main
declare -A SLOT_PID=([main]="") SLOT_SAVED=()
SLOT_VARS=()
use_slot() {
	local dir=$TMP i v
	SLOT_PID[$SLOT]=$DAEMON_PID
	for v in "${SLOT_VARS[@]}"; do
		SLOT_SAVED[$SLOT.$v]=${!v:-}
	done
	SLOT=$1
	DAEMON_PID=${SLOT_PID[$SLOT]:-}
	for v in "${SLOT_VARS[@]}"; do
		printf -v "$v" '%s' "${SLOT_SAVED[$SLOT.$v]:-}"
	done
	SHM="/endosim-test-$$"
	if [ "$SLOT" != main ]; then
		dir=$TMP/slot-$SLOT
		mkdir -p "$dir"
		SHM="$SHM-slot-$SLOT"
	fi
	SOCK="$dir/run"
	LOG="$dir/endosimd.log"
	for i in "${!DAEMON_ARGS[@]}"; do
		case "${DAEMON_ARGS[$i]}" in
		--socket-dir) DAEMON_ARGS[i + 1]=$SOCK ;;
		--shm-name) DAEMON_ARGS[i + 1]=$SHM ;;
		--session-dir) DAEMON_ARGS[i + 1]=$dir/sessions ;;
		esac
	done
}

# daemon_logs: the log of every slot's daemon
daemon_logs() {
	ls "$TMP"/endosimd.log "$TMP"/slot-*/endosimd.log 2>/dev/null
}

cleanup() {
	local pid
	SLOT_PID[$SLOT]=$DAEMON_PID
	for pid in "${SLOT_PID[@]}"; do
		if [ -n "$pid" ]; then
			kill -KILL "$pid" 2>/dev/null
			wait "$pid" 2>/dev/null
		fi
	done
	rm -f "/dev/shm/endosim-test-$$" "/dev/shm/endosim-test-$$-slot-"*
	rm -rf "$TMP"
}
trap cleanup EXIT

finish() {
	local slot
	if [ -n "$DAEMON_PID" ]; then
		check "endosimd exits cleanly on SIGTERM" stop_daemon
	fi
	if [ "${#SLOT_PID[@]}" -gt 1 ]; then
		SLOT_PID[$SLOT]=$DAEMON_PID
		for slot in "${!SLOT_PID[@]}"; do
			[ -n "${SLOT_PID[$slot]}" ] || continue
			use_slot "$slot"
			check "endosimd ($slot) exits cleanly on SIGTERM" stop_daemon
		done
	fi
	if grep -qE "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:" \
		$(daemon_logs) /dev/null 2>/dev/null; then
		fail "sanitizer report in endosimd's log"
	fi
	[ "$FAILED" -eq 0 ] || print_logs
	tally
}

# print_logs: every slot's daemon log (its last 25 lines, so that a
# failure's reader sees each slot's in what CI keeps), for a failure
print_logs() {
	local log slot
	for log in $(daemon_logs); do
		[ -s "$log" ] || continue
		slot=${log%/endosimd.log}
		slot=${slot#"$TMP"}
		echo "# endosimd log${slot:+ (${slot#/})}:"
		grep -v "warning: force loop overrun: " "$log" | tail -n 25 |
			sed 's/^/#   /'
	done
}

# tally: the closing line; exits 0 when nothing failed
tally() {
	[ -s "$TMP/notes" ] && cat "$TMP/notes"
	if [ "$SKIPPED" -gt 0 ]; then
		echo "$PASSED passed, $FAILED failed, $SKIPPED skipped"
	else
		echo "$PASSED passed, $FAILED failed"
	fi
	[ "$FAILED" -eq 0 ]
	exit $?
}

# A suite stopped from outside (tests/run.sh's time limit) says so, with
# the daemons' logs and its tally, rather than vanishing mid-check.
stopped() {
	trap - TERM
	fail "the suite was stopped (SIGTERM) in the middle of a check"
	print_logs
	tally
}
trap stopped TERM
