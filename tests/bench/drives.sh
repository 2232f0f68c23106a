#!/usr/bin/env bash
# drives.sh - the exchange rate each bus thread reaches and its transaction
# latency, against the device emulators: one EPOS4 on emulated USB
# (umockdev), two wheel drives on a Modbus RTU pty (as fast as the pty goes,
# and delayed like a 115200 Bd and a 1 Mbd line, with and without the
# combined function 0x17), and on Modbus TCP over loopback; and what reading
# the handle's valves and the tool in the working channel on the drives'
# inputs adds to an exchange.
#
#   BUILD=build tests/bench/drives.sh [SECONDS]     (after make emulators)
#
# Emulator timings are not hardware timings: the figures say what the code
# and this machine manage, and what the wire time of a line costs; a real
# EPOS4 and real drives answer at their own pace.
set -u
cd "$(dirname "$0")/../.." || exit 1
BUILD=${BUILD:-build}
SECONDS_EACH=${1:-3}
BENCH=$BUILD/bench/drives-bench
T=$(mktemp -d "${TMPDIR:-/tmp}/endosim-bench.XXXXXX")
PIDS=()

cleanup() {
	for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null; done
	wait 2>/dev/null
	rm -rf "$T"
}
trap cleanup EXIT

wait_file() {
	for _ in $(seq 200); do [ -s "$1" ] && return 0; sleep 0.05; done
	return 1
}

# --- one EPOS4 on emulated USB -----------------------------------------------

cat >"$T/usb.conf" <<EOF
[rig]
backend = drives
[axis.insertion]
backend = epos4-usb
[epos4.insertion]
serial = BENCH
max_rate_hz = 100000
EOF
mkdir -p "$T/usb"
TMPDIR=$T/usb "$BUILD/emulators/epos4-emu" --device BENCH \
	--ready "$T/usb.ready" >/dev/null 2>&1 &
PIDS+=($!)
wait_file "$T/usb.ready" || { echo "epos4-emu did not start" >&2; exit 1; }

printf '%-46s %9s %18s %21s\n' "" "" "one exchange" "one transaction"
printf '%-46s %9s %7s %7s    %7s %7s\n' "bus (emulated; transactions per exchange)" \
	"rate" "p50" "p99" "p50" "p99"
UMOCKDEV_DIR=$(cat "$T/usb.ready") LD_PRELOAD=libumockdev-preload.so.0 \
	"$BENCH" -c "$T/usb.conf" --seconds "$SECONDS_EACH" \
	--label "epos4-usb, umockdev (4)"
UMOCKDEV_DIR=$(cat "$T/usb.ready") LD_PRELOAD=libumockdev-preload.so.0 \
	"$BENCH" -c "$T/usb.conf" --seconds "$SECONDS_EACH" \
	--label "epos4-usb, umockdev, valves on 0x60FD (5)" \
	--set epos4.insertion.valve_air_bit=16
UMOCKDEV_DIR=$(cat "$T/usb.ready") LD_PRELOAD=libumockdev-preload.so.0 \
	"$BENCH" -c "$T/usb.conf" --seconds "$SECONDS_EACH" \
	--label "epos4-usb, umockdev, valves and the tool (7)" \
	--set epos4.insertion.valve_air_bit=16 \
	--set epos4.insertion.tool_depth_sensor=2 \
	--set epos4.insertion.tool_opening_input=1 \
	--set epos4.insertion.tool_pedal_bit=20
kill "${PIDS[0]}"

# --- two wheel drives on Modbus ----------------------------------------------

cat >"$T/mb.conf" <<EOF
[rig]
backend = drives
[axis.wheel_ud]
backend = modbus
[axis.wheel_lr]
backend = modbus
[modbus]
device = $T/tty
max_rate_hz = 100000
response_timeout_s = 0.1
[modbus.wheel_ud]
slave = 1
torque = holding 0x0010 i16 scale=1e-5
enable = holding 0x0012
position = holding 0x0020 i32
velocity = holding 0x0022 i32
fault = holding 0x0024
[modbus.wheel_lr]
slave = 2
torque = holding 0x0010 i16 scale=1e-5
enable = holding 0x0012
position = holding 0x0020 i32
velocity = holding 0x0022 i32
fault = holding 0x0024
EOF

# the same drives with the handle's valves: on discrete inputs (one more
# read a drive), or in holding registers beside the feedback (none)
sed 's/^fault = holding 0x0024$/&\nvalve_air = discrete 0x0000/' "$T/mb.conf" \
	>"$T/mb-discrete.conf"
sed 's/^fault = holding 0x0024$/&\nvalve_air = holding 0x0025/' "$T/mb.conf" \
	>"$T/mb-span.conf"
sed -i '0,/^valve_air/s//valve_suction/' "$T/mb-discrete.conf" \
	"$T/mb-span.conf"
# the tool on the first drive: its depth and handle on input registers
# (one more 0x04 read), its pedal on a discrete input (one more 0x02)
sed '0,/^fault = holding 0x0024$/s//&\ntool_depth = input 0x0000 i32 scale=1e-5\ntool_opening = input 0x0002 u16 scale=0.0001\ntool_pedal = discrete 0x0000/' \
	"$T/mb.conf" >"$T/mb-tool.conf"

# modbus LABEL EMULATOR-ARGS -- BENCH-ARGS (the drives of $MB_CONF)
MB_CONF=$T/mb.conf
modbus() {
	local label=$1 emu=() pid
	shift
	while [ "$1" != -- ]; do emu+=("$1"); shift; done
	shift
	"$BUILD/emulators/modbus-emu" --config "$MB_CONF" "${emu[@]}" \
		>"$T/mb.out" 2>&1 &
	pid=$!
	for _ in $(seq 200); do grep -qs ready "$T/mb.out" && break; sleep 0.05; done
	"$BENCH" -c "$MB_CONF" --seconds "$SECONDS_EACH" --label "$label" "$@"
	kill "$pid"
	wait "$pid" 2>/dev/null
}

C17=(--set modbus.wheel_ud.combined_0x17=yes
     --set modbus.wheel_lr.combined_0x17=yes)

modbus "modbus rtu pty, 2 drives (4)" --pty "$T/tty" --
modbus "modbus rtu pty, 2 drives, 0x17 (2)" --pty "$T/tty" -- "${C17[@]}"
modbus "modbus rtu 115200 Bd wire, 2 drives (4)" --pty "$T/tty" \
	--baud 115200 --
modbus "modbus rtu 115200 Bd wire, 2 drives, 0x17 (2)" --pty "$T/tty" \
	--baud 115200 -- "${C17[@]}"
modbus "modbus rtu 1 MBd wire, 2 drives (4)" --pty "$T/tty" \
	--baud 1000000 -- --set modbus.baud=1000000
modbus "modbus rtu 1 MBd wire, 2 drives, 0x17 (2)" --pty "$T/tty" \
	--baud 1000000 -- --set modbus.baud=1000000 "${C17[@]}"
modbus "modbus tcp loopback, 2 drives (4)" --listen 15020 -- \
	--set modbus.transport=tcp --set modbus.port=15020
MB_CONF=$T/mb-discrete.conf
modbus "115200 Bd, valves on discrete inputs (6)" --pty "$T/tty" \
	--baud 115200 --
MB_CONF=$T/mb-span.conf
modbus "115200 Bd, valves beside the feedback (4)" --pty "$T/tty" \
	--baud 115200 --
MB_CONF=$T/mb-tool.conf
modbus "115200 Bd, the tool on the first drive (6)" --pty "$T/tty" \
	--baud 115200 --

cat <<'EOF'

Rates are exchanges per second of one bus thread; an exchange writes the
setpoint to and reads the feedback of every drive on the bus (the figure in
brackets: transactions per exchange), so each drive gets that rate. The
force loop keeps its own rate and uses the newest sample.
EMULATOR TIMINGS, NOT HARDWARE TIMINGS: umockdev relays every usbfs ioctl
through a socket (~1 ms per USB round trip here); the pty and loopback have
no speed of their own; the "wire" rows add only the bytes' time on the line
and 3.5 characters of silence per frame, not the drive's own reply time
(modbus-emu --turnaround). Measure on the rig for real figures.
EOF
