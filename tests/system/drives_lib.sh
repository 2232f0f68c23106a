# drives_lib.sh - what the drive system tests share: the device emulators
# (tests/emulators/), endosimd started against them in a private directory,
# and small checks. Sourced by tests/system/3*-drives-*.sh.
#
# Nothing here depends on timing precision: every wait polls for a state
# with a generous deadline.

BUILD=${BUILD:-build}
EMU_DIR=$BUILD/emulators
PASSED=0
FAILED=0

T=$(mktemp -d "${TMPDIR:-/tmp}/endosim-drives.XXXXXX")
SHM=/endosim-test-$$
DAEMON_PID=
EPOS4_PID=
MODBUS_PID=
UMOCKDEV_ROOT=

# --- reporting -------------------------------------------------------------

ok() {
	PASSED=$((PASSED + 1))
	echo "ok - $1"
}

not_ok() {
	FAILED=$((FAILED + 1))
	echo "not ok - $1"
	[ -n "${2:-}" ] && echo "#   $2"
	return 0
}

# check NAME CMD...: passes when CMD succeeds
check() {
	local name=$1
	shift
	if "$@"; then ok "$name"; else not_ok "$name" "failed: $*"; fi
}

# finish: the summary line, and the exit status
finish() {
	echo "$PASSED passed, $FAILED failed"
	[ "$FAILED" -eq 0 ]
}

# wait_for SECONDS CMD...: polls CMD until it succeeds
wait_for() {
	local deadline=$(($(date +%s%N) + $1 * 1000000000))
	shift
	until "$@"; do
		[ "$(date +%s%N)" -gt "$deadline" ] && return 1
		sleep 0.05
	done
}

# approx A B REL ABS: |A - B| <= REL * |B| + ABS
approx() {
	awk -v a="$1" -v b="$2" -v rel="$3" -v abs="$4" 'BEGIN {
		d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b
		exit !(d <= rel * m + abs) }'
}

# nonzero X MIN: |X| >= MIN
nonzero() {
	awk -v x="$1" -v m="$2" 'BEGIN { if (x < 0) x = -x; exit !(x >= m) }'
}

# --- the daemon ---------------------------------------------------------------

ctl() {
	"$BUILD/endoctl" --socket "$T" "$@"
}

# st JQ: one value of `endoctl --json status`
st() {
	ctl --json status 2>/dev/null | jq -r "$1"
}

state_is() {
	[ "$(st .state)" = "$1" ]
}

# start_daemon CONFIG [ARGS...]: endosimd under the USB emulator when one
# runs; returns once it answers (1 if it exited instead)
start_daemon() {
	local conf=$1
	shift
	if [ -n "$UMOCKDEV_ROOT" ]; then
		UMOCKDEV_DIR=$UMOCKDEV_ROOT LD_PRELOAD=libumockdev-preload.so.0 \
			"$BUILD/endosimd" -c "$conf" --socket-dir "$T" \
			--shm-name "$SHM" --set socket.group= "$@" \
			>>"$T/daemon.log" 2>&1 &
	else
		"$BUILD/endosimd" -c "$conf" --socket-dir "$T" --shm-name "$SHM" \
			--set socket.group= "$@" >>"$T/daemon.log" 2>&1 &
	fi
	DAEMON_PID=$!
	wait_for 15 daemon_answers_or_died
	ctl status >/dev/null 2>&1
}

daemon_answers_or_died() {
	ctl status >/dev/null 2>&1 || ! kill -0 "$DAEMON_PID" 2>/dev/null
}

# run_daemon_expecting_failure CONFIG [ARGS...]: its exit status
run_daemon_expecting_failure() {
	local conf=$1 rc
	shift
	if [ -n "$UMOCKDEV_ROOT" ]; then
		UMOCKDEV_DIR=$UMOCKDEV_ROOT LD_PRELOAD=libumockdev-preload.so.0 \
			timeout 20 "$BUILD/endosimd" -c "$conf" --socket-dir "$T" \
			--shm-name "$SHM" --set socket.group= "$@" \
			>"$T/failed.log" 2>&1
	else
		timeout 20 "$BUILD/endosimd" -c "$conf" --socket-dir "$T" \
			--shm-name "$SHM" --set socket.group= "$@" \
			>"$T/failed.log" 2>&1
	fi
	rc=$?
	echo "$rc"
}

stop_daemon() {
	if [ -n "$DAEMON_PID" ]; then
		kill "$DAEMON_PID" 2>/dev/null
		wait "$DAEMON_PID" 2>/dev/null
		DAEMON_PID=
	fi
}

# fault_lines: how many FAULT lines the daemon has logged
fault_lines() {
	grep -c "error: FAULT" "$T/daemon.log"
}

# --- the emulators ------------------------------------------------------------

# start_epos4 SERIAL...: the USB emulator with these devices
start_epos4() {
	local args=()
	for s in "$@"; do args+=(--device "$s"); done
	mkdir -p "$T/usb"
	TMPDIR=$T/usb "$EMU_DIR/epos4-emu" "${args[@]}" --ready "$T/usb.ready" \
		--control "$T/usb.ctl" --state "$T/usb.state" \
		--trace "$T/usb.trace" >"$T/usb.out" 2>"$T/usb.err" &
	EPOS4_PID=$!
	wait_for 10 test -s "$T/usb.ready" || return 1
	UMOCKDEV_ROOT=$(cat "$T/usb.ready")
}

usb() {
	echo "$*" >"$T/usb.ctl"
}

# emu_get FILE ID FIELD: FIELD of the state file's line that starts with ID
emu_get() {
	awk -v s="$2" -v f="$3=" '$1 == s {
		for (i = 2; i <= NF; i++) if (index($i, f) == 1)
			print substr($i, length(f) + 1) }' "$1"
}

# usb_get SERIAL FIELD: from the USB emulator's state file
usb_get() {
	emu_get "$T/usb.state" "serial=$1" "$2"
}

# start_modbus CONFIG WHERE...: the Modbus emulator (--pty LINK, --listen PORT)
start_modbus() {
	local conf=$1
	shift
	"$EMU_DIR/modbus-emu" --config "$conf" "$@" --control "$T/mb.ctl" \
		--state "$T/mb.state" --trace "$T/mb.trace" \
		>"$T/mb.out" 2>>"$T/mb.err" &
	MODBUS_PID=$!
	wait_for 10 grep -q ready "$T/mb.out"
}

kill_modbus() {
	kill -9 "$MODBUS_PID" 2>/dev/null
	wait "$MODBUS_PID" 2>/dev/null
	MODBUS_PID=
}

mb() {
	echo "$*" >"$T/mb.ctl"
}

# mb_get SLAVE FIELD: from the Modbus emulator's state file
mb_get() {
	emu_get "$T/mb.state" "slave=$1" "$2"
}

# --- cleaning up ----------------------------------------------------------------

cleanup() {
	# the daemon first: it dies with the USB emulator (the preload library)
	stop_daemon
	[ -n "$MODBUS_PID" ] && kill "$MODBUS_PID" 2>/dev/null && wait "$MODBUS_PID" 2>/dev/null
	[ -n "$EPOS4_PID" ] && kill "$EPOS4_PID" 2>/dev/null && wait "$EPOS4_PID" 2>/dev/null
	if [ "$FAILED" -ne 0 ] || [ -n "${KEEP:-}" ]; then
		echo "# kept $T (daemon.log, *.state, *.trace)"
	else
		rm -rf "$T"
	fi
}
trap cleanup EXIT
