#!/usr/bin/env bash
# 66-tool-rig.sh - the tool in the working channel on a real rig (issue
# 25), sensed, not driven, through each backend's real code: the
# carriage's EPOS4 under umockdev (its auxiliary encoder 0x60E4:02 for the
# depth, its analogue input 0x3160:01 for the handle, bit 20 of its
# digital inputs 0x60FD for the cautery's pedal), then the wheels' Modbus
# drives on a pty (input registers, function 0x04, for the depth and the
# handle; a discrete input, function 0x02, for the pedal, on the drive
# read with 0x17), its emulator replying as late as a 115200 Bd line
# would (an exchange longer than the loop's 1 ms cycle, as on a rig;
# 65-valves.sh says why):
#
#  - moved on the emulated drive, the tool's depth, its handle's opening
#    and the pedal show in the published state within one exchange (the
#    loop shows them before the emulator serves the third read of that
#    input after the change), each scaled as configured;
#  - every exchange reads them (as many reads of each as of the position);
#  - the drive's feedback stale (the EPOS4 emulator stopped, a Modbus
#    drive silent for longer than the feedback may age), the pedal reads
#    up while the drive still shows present, and the tool holds where it
#    was while its encoder moves on; fresh again, as read again;
#  - the drive lost (unplugged, the Modbus line gone): the pedal up, the
#    tool held.
#
# The published tool is read from shared memory (tests/tools/shm_probe.c).
# Nothing here checks a duration but "within one exchange", counted in the
# emulators' own traces.
. "$(dirname "$0")/drives_lib.sh"

ARGS=(--set haptics.model=paper)

# watch_tool DEPTH_MM OPENING_PC PEDAL: a witness until the tool reads so
watch_tool() {
	watch_shm --tool "$@"
}

# tool_is DEPTH_MM OPENING_PC PEDAL: the published tool now, rounded
tool_is() {
	local now
	now=$("$TOOLS/shm_probe" "$SHM" --once | awk -F= '
		$1 == "tool.depth_m" { d = $2 } $1 == "tool.opening" { o = $2 }
		$1 == "tool.pedal" { p = $2 }
		END { printf "%.0f %.0f %d", d * 1e3, o * 1e2, p }')
	echo "the tool reads $now"
	[ "$now" = "$*" ]
}

# held DEPTH_MM OPENING_PC PEDAL: so now and for half a second on
held() {
	tool_is "$@" && sleep 0.5 && tool_is "$@"
}

# --- the EPOS4: depth on sensor 2 (10 um a count, -20 mm at count 0),
# the handle on analogue input 1 (0.5 V closed, 4.5 V open), the pedal on
# bit 20 ------------------------------------------------------------------------

cat >"$TMP/usb.conf" <<EOF
[rig]
backend = drives
[axis.insertion]
backend = epos4-usb
[epos4.insertion]
serial = EMU-INS
timeout_s = 0.5
feedback_max_age_s = 0.5
tool_depth_sensor = 2
tool_m_per_count = 1e-5
tool_depth_offset_m = -0.02
tool_opening_input = 1
tool_closed_mv = 500
tool_open_mv = 4500
tool_pedal_bit = 20
EOF

check "USB emulator up" start_epos4 EMU-INS
check "endosimd up on it" start_on "$TMP/usb.conf" "${ARGS[@]}"
check "EPOS4: the tool at count 0, the handle closed, the pedal up" \
	wait_for tool_is -20 0 0

watch_tool 12 0 0
usb "aux EMU-INS 2 3200"
check "EPOS4 depth (0x60E4:02 at 3200 counts): 12 mm shown" witnessed
check "EPOS4 depth: within one exchange" within_one_exchange \
	"$TMP/usb.trace" "aux EMU-INS 2 3200" "ReadObject node 1 0x60e4/02"
said

watch_tool 12 75 0
usb "analog EMU-INS 1 3500"
check "EPOS4 handle (0x3160:01 at 3.5 V): 75 % open shown" witnessed
check "EPOS4 handle: within one exchange" within_one_exchange \
	"$TMP/usb.trace" "analog EMU-INS 1 3500" "ReadObject node 1 0x3160/01"
said

watch_tool 12 75 1
usb "input EMU-INS 20 on"
check "EPOS4 pedal down (0x60FD bit 20): shown" witnessed
check "EPOS4 pedal: within one exchange" within_one_exchange \
	"$TMP/usb.trace" "input EMU-INS 20 on" "ReadObject node 1 0x60fd/00"
said
check "EPOS4: the depth read in every exchange" wait_for reads_every_exchange \
	"$TMP/usb.trace" "ReadObject node 1 0x60e4/02" \
	"ReadObject node 1 0x6064/00"
check "EPOS4: the handle read in every exchange" wait_for reads_every_exchange \
	"$TMP/usb.trace" "ReadObject node 1 0x3160/01" \
	"ReadObject node 1 0x6064/00"

# stale: the emulator stopped, the bus thread waits in its transfer
watch_tool 12 75 0
kill -STOP "$EPOS4_PID"
check "EPOS4 stale (emulator stopped): the pedal up" witnessed
check "EPOS4 stale: while the drive still shows present" \
	present_not_lost insertion
check "EPOS4 stale: the tool held" held 12 75 0
kill -CONT "$EPOS4_PID"
check "EPOS4 fresh again: the pedal down again" wait_for tool_is 12 75 1

# lost: unplugged with the pedal down, the tool moved on meanwhile
watch_tool 12 75 0
usb "unplug EMU-INS"
check "EPOS4 unplugged: the pedal up" witnessed
check "EPOS4 unplugged: the state shows the drive lost" lost insertion
usb "aux EMU-INS 2 5200"
usb "analog EMU-INS 1 1500"
check "EPOS4 unplugged: the tool held while its encoder moves" \
	held 12 75 0
usb "plug EMU-INS"
check "EPOS4 back: the tool where the encoder is, the pedal down" \
	wait_for tool_is 32 25 1
check "endosimd stops cleanly" stop_daemon
kill "$EPOS4_PID" 2>/dev/null
wait "$EPOS4_PID" 2>/dev/null
EPOS4_PID=""
ENDOSIMD="$BUILD/endosimd"

# --- Modbus: depth and handle on slave 1's input registers 0x20, 0x22 (in
# the span its feedback reads already); the pedal on slave 2's discrete
# input 0x00, read after its write-and-read (0x17) ----------------------------

wheels_conf "$TMP/mb.conf" "tool_depth = input 0x0020 i32 scale=1e-5
tool_opening = input 0x0022 u16 scale=0.0001" "tool_pedal = discrete 0x0000"

check "Modbus emulator up on a pty" start_modbus "$TMP/mb.conf" --pty "$TMP/tty" \
	--baud 115200
check "endosimd up on it" start_on "$TMP/mb.conf" "${ARGS[@]}"
check "Modbus: the tool at 0, the handle closed, the pedal up" \
	wait_for tool_is 0 0 0

watch_tool 12 0 0
mb "tool 1 depth 0.012"
check "Modbus depth (input 0x20): 12 mm shown" witnessed
check "Modbus depth: within one exchange" within_one_exchange \
	"$TMP/mb.trace" "tool 1 depth 0.012" "function 0x04 at 0x0000"
said

watch_tool 12 75 0
mb "tool 1 opening 0.75"
check "Modbus handle (input 0x22): 75 % open shown" witnessed
check "Modbus handle: within one exchange" within_one_exchange \
	"$TMP/mb.trace" "tool 1 opening 0.75" "function 0x04 at 0x0000"
said

watch_tool 12 75 1
mb "tool 2 pedal on"
check "Modbus pedal down (slave 2's discrete 0x00): shown" witnessed
check "Modbus pedal: within one exchange" within_one_exchange \
	"$TMP/mb.trace" "tool 2 pedal on" "function 0x02 at 0x0000"
said
check "Modbus: slave 2's pedal read after every write-and-read (0x17)" \
	reads_every_exchange "$TMP/mb.trace" "function 0x02 at 0x0000" \
	"function 0x17 at 0x0020"

# stale: slave 1 silent; its transaction fails only after 2 s, and until
# then the bus' whole exchange (slave 2's pedal too) grows old
watch_tool 12 75 0
mb "mute 1 on"
check "Modbus stale (slave 1 silent): the pedal up" witnessed
check "Modbus stale: while the drive still shows present" \
	present_not_lost wheel_ud
mb "tool 1 depth 0.030"
check "Modbus stale: the tool held while its encoder moves" held 12 75 0
mb "mute 1 off"
check "Modbus fresh again: the tool where the encoder is, the pedal down" \
	wait_for tool_is 30 75 1

# lost: the emulator killed, the pty gone
watch_tool 30 75 0
kill_modbus
check "Modbus line gone: the pedal up" witnessed
check "Modbus line gone: the state shows the drive lost" lost wheel_ud
check "Modbus line gone: the tool held" held 30 75 0
check "endosimd stops cleanly" stop_daemon

# --- both: the depth and the handle on the EPOS4, the pedal on a Modbus
# drive (another bus): the pedal's drive silent, the pedal up while the
# tool goes on moving; the tool's stale, the tool held and the pedal up
# (the model takes a pedal without a tool for none) ----------------------------

wheels_conf "$TMP/both.conf" "" "tool_pedal = discrete 0x0000"
grep -v -e pedal -e '^\[rig\]' -e '^backend = drives' "$TMP/usb.conf" \
	>>"$TMP/both.conf"

rm -f "$TMP/usb.ready" # the first emulator's testbed
check "both emulators up" start_epos4 EMU-INS
check "... the Modbus one" start_modbus "$TMP/both.conf" --pty "$TMP/tty" \
	--baud 115200
check "endosimd up on both" start_on "$TMP/both.conf" "${ARGS[@]}"
usb "aux EMU-INS 2 3200"
usb "analog EMU-INS 1 3500"
mb "tool 2 pedal on"
check "both: the tool from the EPOS4, the pedal from Modbus" \
	wait_for tool_is 12 75 1

watch_tool 12 75 0
mb "mute 2 on"
check "both, the pedal's drive silent: the pedal up" witnessed
check "both, the pedal's drive silent: while it still shows present" \
	present_not_lost wheel_lr
usb "aux EMU-INS 2 4200"
check "both, the pedal's drive silent: the tool moves on" \
	wait_for tool_is 22 75 0
check "both, the pedal's drive silent: the pedal stays up" held 22 75 0
mb "mute 2 off"
check "both, the pedal's drive back: the pedal down" wait_for tool_is 22 75 1

watch_tool 22 75 0
kill -STOP "$EPOS4_PID"
check "both, the tool's drive stale: the pedal up" witnessed
check "both, the tool's drive stale: the tool held" held 22 75 0
kill -CONT "$EPOS4_PID"
check "both, the tool's drive fresh: the pedal down" wait_for tool_is 22 75 1
check "endosimd stops cleanly" stop_daemon

finish
