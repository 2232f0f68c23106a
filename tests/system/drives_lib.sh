# drives_lib.sh - what the drive system tests (tests/system/3N-drives-*.sh)
# add to common.sh: the device emulators of tests/emulators/, endosimd
# started on a drive configuration (under the USB emulator when one runs),
# reading the emulators' state, and number comparisons.
#
# Nothing here depends on timing precision: every wait polls for a state
# with a generous deadline.

. "$(dirname "${BASH_SOURCE[0]}")/../common.sh"

EMU_DIR="$BUILD/emulators"
# The Modbus emulator answers as a drive does, whatever else this machine
# runs: SCHED_FIFO 60, below endosimd's bus threads (70) and force loop
# (80), where it may (root); else as an ordinary process. A busy test
# machine has made it late by more than the response timeout (a bus-error
# fault nobody injected). Not the USB emulator: umockdev's emulated ioctls
# keep it and endosimd busy on every exchange, and at that priority it
# would take the CPU from endosimd's ordinary threads (30 took 38 s, not 15).
EMU_RT=()
if chrt -f 60 true 2>/dev/null; then
	EMU_RT=(chrt -f 60)
fi
EPOS4_PID=""
MODBUS_PID=""
UMOCKDEV_ROOT=""

# --- numbers ---------------------------------------------------------------

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

# --- the daemon on drives ---------------------------------------------------------

state_is() {
	[ "$(status_field .state)" = "$1" ]
}

# fault_says TEXT: the status' fault (the first since reset) says TEXT
fault_says() {
	case "$(status_field .fault)" in *"$1"*) ;; *) return 1 ;; esac
}

# log_says TEXT: the newest FAULT line of the log says TEXT
log_says() {
	grep "error: FAULT" "$LOG" | tail -n 1 | grep -qF -- "$1"
}

# fault_lines: how many FAULT lines endosimd has logged
fault_lines() {
	grep -c "error: FAULT" "$LOG"
}

# daemon_time: seconds since endosimd started, on the clock its FAULT lines
# give ("... at T s: ...")
daemon_time() {
	status_field .uptime_s
}

# faults_since T: how many FAULT lines are of faults found at T s or later.
# Another thread writes a fault's line a moment after the loop found it,
# so lines counted before an event can miss one found just before it, which
# then counts as the event's (seen in 31: a drive's own fault, found as
# its bus came back, logged after the count): the line's own time tells.
faults_since() {
	grep "error: FAULT" "$LOG" |
		sed -n 's/.*(detail [0-9]*) at \([0-9.]*\) s: .*/\1/p' |
		awk -v t="$1" '$1 >= t { n++ } END { print n + 0 }'
}

reset_ok() {
	ctl reset >/dev/null 2>&1
}

reset_refused() {
	! ctl reset >/dev/null 2>&1
}

# The daemon runs under the USB emulator through this wrapper: umockdev's
# preload library redirects /sys and /dev/bus/usb into the testbed and
# hands the usbfs ioctls to the emulator; everything else passes through.
# (Under AddressSanitizer the preload library comes first: ASan is told.)
usb_wrapper() {
	cat >"$TMP/endosimd-usb" <<EOF
#!/bin/sh
export UMOCKDEV_DIR='$UMOCKDEV_ROOT' LD_PRELOAD=libumockdev-preload.so.0
export ASAN_OPTIONS="\${ASAN_OPTIONS:+\$ASAN_OPTIONS:}verify_asan_link_order=0"
exec '$BUILD/endosimd' "\$@"
EOF
	chmod +x "$TMP/endosimd-usb"
	ENDOSIMD="$TMP/endosimd-usb"
}

# start_on CONFIG [ARGS...]: endosimd on that drive configuration
start_on() {
	local conf=$1
	shift
	start_daemon --config "$conf" "$@"
}

# only_damping: the colon's forces and the knobs' end stops off, so that
# each axis renders only its light damping, -b v: a steady force at a
# steady speed, to compare what endosimd sends with what the emulated
# motors get (a wheel turned on past its stop would otherwise feel a
# torque that grows between reading the status and reading the drive)
only_damping() {
	local k
	for k in friction_n_s_per_m_rad torsion_n_m_s_per_rad2 \
		wall_stiffness_n_per_m wall_damping_n_s_per_m \
		wire_tension_n_m_per_m bending_stiffness_n_m_per_rad \
		wheel_stop_stiffness_n_m_per_rad \
		wheel_stop_damping_n_m_s_per_rad; do
		ctl set "haptics.$k" 0 >/dev/null || return 1
	done
}

# refused_at_start CONFIG STATUS TEXT [ARGS...]: endosimd exits with STATUS
# before its force loop runs, saying TEXT
refused_at_start() {
	local conf=$1 want=$2 what=$3 rc
	shift 3
	timeout 30 "$ENDOSIMD" --config "$conf" "${DAEMON_ARGS[@]}" "$@" \
		>"$TMP/failed.log" 2>&1
	rc=$?
	[ "$rc" = "$want" ] || { echo "exit $rc, expected $want"; return 1; }
	grep -qF -- "$what" "$TMP/failed.log" || { cat "$TMP/failed.log"; return 1; }
	! grep -q "force loop:" "$TMP/failed.log"
}

# --- the emulators ------------------------------------------------------------

# emu_get FILE ID FIELD: FIELD of the state file's line that starts with ID
emu_get() {
	awk -v s="$2" -v f="$3=" '$1 == s {
		for (i = 2; i <= NF; i++) if (index($i, f) == 1)
			print substr($i, length(f) + 1) }' "$1"
}

# start_epos4 SERIAL...: the USB emulator with these devices; the daemon
# starts under it from now on
start_epos4() {
	local args=() s
	for s in "$@"; do args+=(--device "$s"); done
	mkdir -p "$TMP/usb"
	TMPDIR="$TMP/usb" "$EMU_DIR/epos4-emu" "${args[@]}" \
		--ready "$TMP/usb.ready" --control "$TMP/usb.ctl" \
		--state "$TMP/usb.state" --trace "$TMP/usb.trace" \
		>"$TMP/usb.out" 2>"$TMP/usb.err" &
	EPOS4_PID=$!
	wait_for test -s "$TMP/usb.ready" || return 1
	UMOCKDEV_ROOT=$(cat "$TMP/usb.ready")
	usb_wrapper
}

# usb COMMAND: to the USB emulator (see tests/emulators/epos4_emu.c)
usb() {
	echo "$*" >"$TMP/usb.ctl"
}

# usb_get SERIAL FIELD: what the USB emulator's device sees
usb_get() {
	emu_get "$TMP/usb.state" "serial=$1" "$2"
}

# start_modbus CONFIG WHERE...: the Modbus emulator (--pty LINK, --listen PORT)
start_modbus() {
	local conf=$1
	shift
	: >"$TMP/mb.out"
	"${EMU_RT[@]}" "$EMU_DIR/modbus-emu" --config "$conf" "$@" \
		--control "$TMP/mb.ctl" \
		--state "$TMP/mb.state" --trace "$TMP/mb.trace" \
		>"$TMP/mb.out" 2>>"$TMP/mb.err" &
	MODBUS_PID=$!
	wait_for grep -q ready "$TMP/mb.out"
}

kill_modbus() {
	kill -KILL "$MODBUS_PID" 2>/dev/null
	wait "$MODBUS_PID" 2>/dev/null
	MODBUS_PID=""
}

# mb COMMAND: to the Modbus emulator (see tests/emulators/modbus_emu.c)
mb() {
	echo "$*" >"$TMP/mb.ctl"
}

# mb_get SLAVE FIELD: what the Modbus emulator's drive sees
mb_get() {
	emu_get "$TMP/mb.state" "slave=$1" "$2"
}

# --- the rig's inputs, as published (65-valves, 66-tool-rig) -------------------

PRESENT=1
LOST_BITS=12 # fault, bus error
WATCH_PID=""

shm_field() {
	"$TOOLS/shm_probe" "$SHM" --once | sed -n "s/^$1=//p"
}

# watch_shm --valves MASK VALUE | --tool DEPTH_MM OPENING_PC PEDAL: a
# witness reading every state from now until it is so (tests/tools/
# shm_probe.c), started before the action that makes it so
watch_shm() {
	"$TOOLS/shm_probe" "$SHM" "$@" 10 >"$TMP/watch.out" 2>&1 &
	WATCH_PID=$!
	# it refuses a state that is so already: the action waits until it
	# has read the state before it
	wait_for grep -q '^watching$' "$TMP/watch.out"
}

# seen KEY: in the first state the witness saw so (before.KEY: the one
# before it)
seen() {
	sed -n "s/^$1=//p" "$TMP/watch.out"
}

witnessed() {
	wait "$WATCH_PID"
}

# read_after TRACE COMMAND PATTERN N: the time of the Nth line with PATTERN
# after the control line COMMAND
read_after() {
	awk -v cmd="control  ; $2" -v pat="$3" -v n="$4" '
		!on && index($0, cmd) { on = 1; next }
		on && index($0, pat) { if (++k == n) { print $1; exit } }' "$1"
}

# has_read TRACE COMMAND PATTERN N: the Nth such read is in the trace
has_read() {
	[ -n "$(read_after "$@")" ]
}

# within_one_exchange TRACE COMMAND PATTERN: the witness' first state
# showing the press was published before the third input read after it
# (which the emulator may serve after the witness has seen the state)
within_one_exchange() {
	local r1 r3 t
	wait_for has_read "$1" "$2" "$3" 3
	r1=$(read_after "$1" "$2" "$3" 1)
	r3=$(read_after "$1" "$2" "$3" 3)
	t=$(seen stamp_ns)
	echo "the press read at $r1 s, the third read at $r3 s; shown by" \
		"the cycle of $(awk -v t="$t" 'BEGIN { printf "%.6f", t / 1e9 }') s"
	[ -n "$r1" ] && [ -n "$r3" ] &&
		awk -v t="$t" -v r="$r3" 'BEGIN { exit !(t / 1e9 <= r) }'
}

# said: what the last check's command said, as a comment
said() {
	sed 's/^/# /' "$TMP/check.out"
}

# more_reads_than N TRACE PATTERN: over N lines with PATTERN in TRACE
more_reads_than() {
	[ "$(grep -c -- "$3" "$2")" -gt "$1" ]
}

# reads_every_exchange TRACE INPUT POSITION: as many input reads as
# position reads (one exchange may be under way), counted in one copy of
# the trace (the emulator goes on writing it) once it holds over 100 (a
# line as slow as 115200 Bd makes ~70 exchanges a second)
reads_every_exchange() {
	local i p
	wait_for more_reads_than 100 "$1" "$2"
	cp "$1" "$TMP/trace.copy"
	i=$(grep -c -- "$2" "$TMP/trace.copy")
	p=$(grep -c -- "$3" "$TMP/trace.copy")
	echo "$i input reads, $p position reads"
	[ "$i" -gt 100 ] && [ $((i - p)) -le 1 ] && [ $((p - i)) -le 1 ]
}

# present_not_lost AXIS / lost AXIS: the drive status in the witnessed
# state: present without a fault or bus error / not
present_not_lost() {
	local st
	st=$(seen "$1.drive_status")
	echo "drive status $st"
	[ -n "$st" ] && [ $((st & PRESENT)) -ne 0 ] &&
		[ $((st & LOST_BITS)) -eq 0 ]
}

lost() {
	local st
	st=$(seen "$1.drive_status")
	echo "drive status $st"
	[ -n "$st" ] &&
		{ [ $((st & PRESENT)) -eq 0 ] || [ $((st & LOST_BITS)) -ne 0 ]; }
}


# wheels_conf FILE UD_LINES LR_LINES: the two wheels on Modbus drives
# behind $TMP/tty (slave 1 read with 0x04, slave 2 written and read with
# 0x17), a silent drive's transaction waiting 2 s and the feedback aging
# 0.3 s; each drive's section ends with its lines (the valves', the
# tool's)
wheels_conf() {
	cat >"$1" <<EOF
[rig]
backend = drives
[axis.wheel_ud]
backend = modbus
[axis.wheel_lr]
backend = modbus
[modbus]
device = $TMP/tty
; a silent drive's transaction waits 2 s; feedback may be 0.3 s old
response_timeout_s = 2
feedback_max_age_s = 0.3
[modbus.wheel_ud]
slave = 1
torque = holding 0x0000 i16 scale=1e-5
enable = coil 0x0000
position = input 0x0000 i32 cdab
velocity = input 0x0002 f32 cdab
fault = input 0x0004 u16
$2
[modbus.wheel_lr]
slave = 2
combined_0x17 = yes
torque = holding 0x0010 i32 scale=1e-6
enable = holding 0x0012 u16
position = holding 0x0020 i32
velocity = holding 0x0022 i32
fault = holding 0x0024 u16
$3
EOF
}

# --- cleaning up ----------------------------------------------------------------

# drives_diagnose: after a failure, whether the emulators still ran and
# what they said (the daemon under the USB emulator dies with it)
drives_diagnose() {
	local pid name
	for name in EPOS4 MODBUS; do
		pid=${name}_PID
		[ -n "${!pid}" ] || continue
		kill -0 "${!pid}" 2>/dev/null || echo "# the $name emulator had died"
	done
	for name in usb mb; do
		[ -s "$TMP/$name.err" ] && sed "s/^/# $name emulator: /" "$TMP/$name.err" | tail -n 5
	done
}

drives_cleanup() {
	[ "$FAILED" -gt 0 ] && drives_diagnose
	# the daemon first: under the preload library it ends with the emulator
	if [ -n "$DAEMON_PID" ]; then
		kill -KILL "$DAEMON_PID" 2>/dev/null
		wait "$DAEMON_PID" 2>/dev/null
		DAEMON_PID=""
	fi
	[ -n "$MODBUS_PID" ] && kill "$MODBUS_PID" 2>/dev/null
	[ -n "$EPOS4_PID" ] && kill "$EPOS4_PID" 2>/dev/null
	wait 2>/dev/null
	cleanup
}
trap drives_cleanup EXIT
