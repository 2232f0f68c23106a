#!/usr/bin/env bash
# 65-valves.sh - the handle's valves on a real rig, through each backend's
# real code: the carriage's EPOS4 under umockdev (a bit of its digital
# inputs 0x60FD), then the wheels' Modbus drives on a pty (discrete
# inputs, function 0x02; one wired to open when pressed), its emulator
# replying as late as a 115200 Bd line would: an exchange then takes
# longer than the loop's 1 ms cycle, as on a rig, and "within one
# exchange" is not a race with the cycle (as fast as a pty goes, two
# exchanges took 1.2 ms and a loaded VM missed it once). The patient on:
#
#  - pressed on the emulated drive, the valve shows in the published state
#    within one exchange (the first input read after the press carries it;
#    the loop shows it before the emulator serves the third), and the gas
#    flows in that very cycle and on while it is held; released, it stops;
#  - every exchange reads the inputs (as many input reads as position
#    reads);
#  - the drive's feedback stale (the EPOS4 emulator stopped, a Modbus drive
#    silent for longer than the feedback may age), the valve reads released
#    while the drive still shows present, and the gas stops; fresh again,
#    pressed again;
#  - the drive lost (unplugged, the Modbus line gone), the valve reads
#    released and the gas stops, though the switch is still pressed.
#
# The published valves and gas are read from shared memory
# (tests/tools/shm_probe.c). Nothing here checks a duration but "within
# one exchange", counted in the emulators' own traces.
. "$(dirname "$0")/drives_lib.sh"

AIR=1
WATER=2
SUCTION=4
ARGS=(--set patient.enabled=yes --set haptics.model=paper)

# watch_valves MASK VALUE: a witness (watch_shm) until the valves & MASK
# are VALUE
watch_valves() {
	watch_shm --valves "$1" "$2"
}

# gas_flows / gas_still: the gas pumped in over half a second
gas_in_over() {
	local g1 g2
	g1=$(shm_field patient.gas_in_m3)
	sleep 0.5
	g2=$(shm_field patient.gas_in_m3)
	awk -v a="$g1" -v b="$g2" 'BEGIN { print b - a }'
}

# gas_flows: at least half the pump's 2 L/min over the half second
gas_flows() {
	local d
	d=$(gas_in_over)
	echo "pumped $d m3 in 0.5 s"
	awk -v d="$d" 'BEGIN { exit !(d > 0.5 * 2e-3 / 60 * 0.5) }'
}

gas_still() {
	local d
	d=$(gas_in_over)
	echo "pumped $d m3 in 0.5 s"
	awk -v d="$d" 'BEGIN { exit !(d == 0) }'
}

valves_are() {
	[ "$(shm_field patient.valves)" = "$1" ]
}

# gas_at_once: the first state with the valve had gas pumped in its cycle
gas_at_once() {
	awk -v a="$(seen before.patient.gas_in_m3)" \
		-v b="$(seen patient.gas_in_m3)" 'BEGIN { exit !(b > a) }'
}

# --- the EPOS4: air on 0x60FD bit 16, suction on bit 18 ----------------------

cat >"$TMP/usb.conf" <<EOF
[rig]
backend = drives
[axis.insertion]
backend = epos4-usb
[epos4.insertion]
serial = EMU-INS
timeout_s = 0.5
feedback_max_age_s = 0.5
valve_air_bit = 16
valve_suction_bit = 18
EOF

check "USB emulator up" start_epos4 EMU-INS
check "endosimd up on it, the patient on" start_on "$TMP/usb.conf" "${ARGS[@]}"
check "EPOS4: released at first, no gas flowing" valves_are 0
check "EPOS4: ... the gas still" gas_still

watch_valves $AIR $AIR
usb "input EMU-INS 16 on"
check "EPOS4 air pressed (0x60FD bit 16): shown" witnessed
check "EPOS4 air: within one exchange" within_one_exchange "$TMP/usb.trace" \
	"input EMU-INS 16 on" "ReadObject node 1 0x60fd/00"
said
check "EPOS4 air: the gas flows in that very cycle" gas_at_once
check "EPOS4 air: the gas flows while it is held" gas_flows
check "EPOS4: the inputs read in every exchange" reads_every_exchange \
	"$TMP/usb.trace" "ReadObject node 1 0x60fd/00" \
	"ReadObject node 1 0x6064/00"

watch_valves $SUCTION $SUCTION
usb "input EMU-INS 18 on"
check "EPOS4 suction pressed (bit 18): shown beside air" witnessed
check "EPOS4 suction: both valves" [ "$(seen patient.valves)" = $((AIR | SUCTION)) ]
watch_valves $((AIR | SUCTION)) 0
usb "input EMU-INS 16 off"
usb "input EMU-INS 18 off"
check "EPOS4 released: shown" witnessed
check "EPOS4 released: the gas stops" gas_still

# stale: the emulator stopped, the bus thread waits in its transfer
usb "input EMU-INS 16 on"
check "EPOS4 air pressed again" wait_for valves_are $AIR
watch_valves $AIR 0
kill -STOP "$EPOS4_PID"
check "EPOS4 stale (emulator stopped): released" witnessed
check "EPOS4 stale: released while the drive still shows present" \
	present_not_lost insertion
check "EPOS4 stale: the gas stops" gas_still
kill -CONT "$EPOS4_PID"
check "EPOS4 fresh again: pressed again" wait_for valves_are $AIR

# lost: unplugged with the switch still pressed
watch_valves $AIR 0
usb "unplug EMU-INS"
check "EPOS4 unplugged: released" witnessed
check "EPOS4 unplugged: the state shows the drive lost" lost insertion
check "EPOS4 unplugged: the gas stops" gas_still
check "EPOS4 unplugged: stays released" valves_are 0
usb "plug EMU-INS"
check "EPOS4 back: pressed again" wait_for valves_are $AIR
check "EPOS4 back: the gas flows" gas_flows
check "endosimd stops cleanly" stop_daemon
kill "$EPOS4_PID" 2>/dev/null
wait "$EPOS4_PID" 2>/dev/null
EPOS4_PID=""
ENDOSIMD="$BUILD/endosimd"

# --- Modbus: air and suction on slave 1's discrete inputs 0x10, 0x11;
# water on slave 2's, an input that opens when pressed ------------------------

wheels_conf "$TMP/mb.conf" "valve_air = discrete 0x0010
valve_suction = discrete 0x0011" \
	"valve_water = discrete 0x0000 u16 scale=-1 offset=1"

check "Modbus emulator up on a pty" start_modbus "$TMP/mb.conf" --pty "$TMP/tty" \
	--baud 115200
check "endosimd up on it, the patient on" start_on "$TMP/mb.conf" "${ARGS[@]}"
check "Modbus: released at first (the inverted input reads 1)" valves_are 0

watch_valves $AIR $AIR
mb "valve 1 air on"
check "Modbus air pressed (discrete 0x10): shown" witnessed
check "Modbus air: within one exchange" within_one_exchange "$TMP/mb.trace" \
	"valve 1 air on" "function 0x02 at 0x0010"
said
check "Modbus air: the gas flows in that very cycle" gas_at_once
check "Modbus air: the gas flows while it is held" gas_flows
check "Modbus: slave 1's inputs read in every exchange" reads_every_exchange \
	"$TMP/mb.trace" "function 0x02 at 0x0010" "function 0x04 at 0x0000"
check "Modbus: slave 2's, after its write-and-read (0x17)" \
	reads_every_exchange "$TMP/mb.trace" "function 0x02 at 0x0000" \
	"function 0x17 at 0x0020"

watch_valves $WATER $WATER
mb "valve 2 water on"
check "Modbus water pressed (slave 2, input open when pressed): shown" witnessed
watch_valves $((AIR | WATER)) 0
mb "valve 1 air off"
mb "valve 2 water off"
check "Modbus released: shown" witnessed
check "Modbus released: the gas stops" gas_still

# stale: slave 1 silent; its transaction fails only after 2 s
mb "valve 1 air on"
check "Modbus air pressed again" wait_for valves_are $AIR
watch_valves $AIR 0
mb "mute 1 on"
check "Modbus stale (slave 1 silent): released" witnessed
check "Modbus stale: released while the drive still shows present" \
	present_not_lost wheel_ud
check "Modbus stale: the gas stops" gas_still
mb "mute 1 off"
check "Modbus fresh again: pressed again" wait_for valves_are $AIR

# lost: the emulator killed, the pty gone
watch_valves $AIR 0
kill_modbus
check "Modbus line gone: released" witnessed
check "Modbus line gone: the state shows the drive lost" lost wheel_ud
check "Modbus line gone: the gas stops" gas_still
check "Modbus line gone: stays released" valves_are 0
check "endosimd stops cleanly" stop_daemon

finish
