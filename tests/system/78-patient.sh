#!/bin/bash
# The patient's commands and what they publish (issue 22), with [patient]
# enabled on the normal case (its sites llq and umbilical): `endoctl
# patient` turns the patient (the status says turning, then settled),
# has the assistant press at a site with the default force and with
# --force, and let go; works the simulated handle's valves (air held
# raises the gas volume; the valves held stay held; off lets go at once);
# a wall made weak tears the uppermost segment (a perforation); the
# tip's thresholds set low, the hand's push tears a wall (a tear), no
# fault. Sedation: the session started with --sedation none has the
# patient unsedated from its first record (a sedation event, the CSV's
# patient_sedation column), `patient sedation deep` shows in `patient
# status`, an unknown level is refused with the levels listed; the pain
# is a number on the 0-10 scale.
# Refused, with nothing changed: on the read-only socket, an unknown
# position or site (the valid ones listed), a press above hand_max_n,
# and every command when the patient is disabled. The status (JSON and
# text) and `scene info` have the patient's fields and the case's sites;
# a session recorded across it all has each change as an event (export
# --events, show, the report), its measures (a turn, a press, the gas, a
# perforation) and the patient's CSV columns. (The
# mailbox and the refusals in the loop, cycle for cycle: test_mailbox;
# the records and their columns: test_fields, test_session_file.)
. "$(dirname "$0")/../common.sh"

# the patient disabled, in a slot of its own, meanwhile
use_slot off
start_daemon --set haptics.model=paper || finish
use_slot main
start_daemon --set patient.enabled=yes --set patient.turn_s=3 || finish

p_true() {
	status_true ".patient | $1"
}

check "status --json: the patient's keys, in their order" \
	test "$(ctl --json status | jq -c '.patient | keys_unsorted')" = \
	'["enabled","valves","position","turning","turn","down","gas_m3","pressure_pa","gas_in_m3","factor","transmural_pa","tension_n_per_m","fluid_m3","fluid_level_m","fluid_up","hand_site","site","tip_in_fluid","hand_n","pad_n","lens_smear","lens_murk","lens_redout","burst_segment","sedation","pain","pain_stimulus","pain_cause","pain_place","heart_rate_bpm","spo2","torn_segment"]'
check "at the start: left lateral, settled, the gas at 15 mmHg, no hand, no valve, whole" \
	p_true '.enabled and .position == "left-lateral" and (.turning | not)
		and (.pressure_pa / 133.322 | . > 14 and . < 16)
		and .gas_m3 > 0.001 and (.factor | length) == 9
		and .hand_site == -1 and .site == "" and .valves == "none"
		and .burst_segment == -1'
check "status: the patient's line" eval \
	"ctl status | grep -qE '^patient   left-lateral, gas [0-9.]+ L at [0-9.]+ mmHg, hand off, valves none, pain [0-9.]+( [a-z]+)?, moderate sedation$'"
check "scene info: the case's sites" eval \
	"ctl scene info >$TMP/scene.txt && grep -q '^  site llq  ' $TMP/scene.txt &&
	 grep -q '^  site umbilical ' $TMP/scene.txt"
check "scene info --json: their names" \
	test "$(ctl --json scene info | jq -c .sites)" = '["llq","umbilical"]'

# the session with the patient unsedated: the instructor's choice
ID=$(ctl --json session start --trainee patient --sedation none | jq -r .id)
check "session start --sedation none: the patient unsedated" \
	p_true '.sedation == "none"'

# --- refused, and nothing changes -----------------------------------------
for cmd in "position supine" "press llq" release "valve air on"; do
	# shellcheck disable=SC2086 # the words of the command
	check_status "patient $cmd on the read-only socket: refused (1)" 1 \
		"$ENDOCTL" --socket "$SOCK/status.sock" patient $cmd
	check "... as read-only" grep -q "read-only" "$OUT"
done
check_status "an unknown position: refused (1)" 1 ctl patient position sitting
check "... the positions listed" grep -q \
	"no position 'sitting': left-lateral, supine, right-lateral or prone" "$OUT"
check_status "an unknown site: refused (1)" 1 ctl patient press rlq
check "... the case's sites listed" grep -q \
	"no site 'rlq' in case normal: llq, umbilical" "$OUT"
check_status "a press of 70 N: refused (1)" 1 ctl patient press llq --force 70
check "... the strongest said" grep -q "to 60 N (\[patient\] hand_max_n)" "$OUT"
check_status "an unknown sedation: refused (1)" 1 ctl patient sedation drunk
check "... the levels listed" grep -q \
	"no sedation 'drunk': none, minimal, moderate or deep" "$OUT"
check_status "no such valve: usage (2)" 2 ctl patient valve oxygen on
check_status "a valve held 11 s: usage (2)" 2 ctl patient valve air on --for 11
check "nothing changed" p_true '.position == "left-lateral" and
	(.turning | not) and .hand_site == -1 and .valves == "none" and
	.sedation == "none"'

# --- sedation and pain ---------------------------------------------------------
check "status --json: the pain a number on the 0-10 scale" \
	p_true '.pain | type == "number" and . >= 0 and . <= 10'
check_status "patient sedation deep" 0 ctl patient sedation deep
check "patient status: sedation deep" eval \
	"ctl patient status | grep -q '^sedation  deep$'"
check "status --json: deep" p_true '.sedation == "deep"'

# --- the position ------------------------------------------------------------
check_status "patient position supine" 0 ctl patient position supine
check "... the reply: turning to supine" grep -q "^patient   turning to supine, " "$OUT"
check "status: turning to supine" \
	p_true '.position == "supine" and .turning and .turn < 1'
check "patient status: turning" eval \
	"ctl patient status | grep -qE '^position  supine \(turning: [0-9]+ %\)$'"

# --- the hand (while it turns) ------------------------------------------------
check_status "patient press llq" 0 ctl patient press llq
check "... at llq with the default 20 N" \
	p_true '.site == "llq" and .hand_site == 0 and .hand_n == 20'
check_status "patient press llq --force 30" 0 ctl patient press llq --force 30
check "... with 30 N" p_true '.site == "llq" and .hand_n == 30'
check "status and patient status say so" eval \
	"ctl status | grep -q '^patient   .*, hand llq 30 N, ' &&
	 ctl patient status | grep -q '^hand      llq, 30 N '"
check_status "patient release" 0 ctl patient release
check "... no hand" p_true '.hand_site == -1 and .site == "" and .hand_n == 0'
check "settled supine, gravity towards the back" wait_for \
	p_true '.position == "supine" and (.turning | not) and .down[1] > 0.999'

# --- the valves ------------------------------------------------------------
gas0=$(status_field .patient.gas_m3)
check_status "patient valve air on" 0 ctl patient valve air on
check "... held 2 s" grep -q "^valves air for 2.0 s$" "$OUT"
check_status "patient valve water on: the air valve stays held with it" 0 \
	ctl patient valve water on --for 0.5
check "... both" grep -q "^valves air,water for 0.5 s$" "$OUT"
check "released once held, as a finger lifts" wait_for p_true '.valves == "none"'
check "the pump's air raised the gas volume (by more than 10 mL)" \
	p_true ".gas_m3 > $gas0 + 1e-5 and .gas_in_m3 > 1e-5"
check_status "patient valve suction on" 0 ctl patient valve suction on --for 5
check "... held" p_true '.valves == "suction"'
check_status "patient valve suction off" 0 ctl patient valve suction off
check "... let go at once" wait_for p_true '.valves == "none"'
check "patient status --json: the patient's object" eval \
	"ctl --json patient status | jq -e '.enabled and .position == \"supine\" and .valves == \"none\"'"

# --- a perforation: supine, the transverse colon lies uppermost and is
# the most distended (its wall's tension ~37 N/m at 15 mmHg, the others'
# under 30): a wall of 32 N/m tears it and no other -------------------------
check_status "a weak wall (set live)" 0 ctl set patient.wall_strength_n_per_m 32
check "the transverse colon tears: burst_segment 5" \
	wait_for p_true '.burst_segment == 5'
check "status: PERFORATED" eval \
	"ctl status | grep -q '^patient   .*, PERFORATED: transverse$'"

# --- a tear by the tip: its thresholds set low, the hand pushes the tube
# in until the tip holds a wall (the real ones, end to end in lockstep:
# test_patient) ----------------------------------------------------------------
check_status "a wall weak to the tip (set live)" 0 eval \
	"ctl set patient.perforation_straight_n 1 &&
	 ctl set patient.perforation_bent_n 1"
check_status "the hand pushes the tube in" 0 ctl hand 30 0 0 0 --hold-ms 4000
check "the tip tears a wall: torn_segment set" \
	wait_for p_true '.torn_segment >= 0'
check "... no fault, the state as it was (IDLE)" \
	status_true '.fault_bits == 0 and .state == "IDLE"'

# --- the session ------------------------------------------------------------
check_status "session stop" 0 ctl session stop
ctl session export "$ID" --csv --events --out "$TMP/events.csv" >/dev/null
for ev in ',position,-1,0,0,"settled left-lateral"' \
	',position,-1,1,1,"turning to supine"' \
	',position,-1,0,1,"settled supine"' \
	',hand,0,1,20,"pressed at llq, 20 N"' \
	',hand,0,1,30,"pressed at llq, 30 N"' ',hand,-1,0,0,"released"' \
	',valve,-1,1,1,"air on"' ',valve,-1,2,1,"water on"' \
	',valve,-1,1,0,"air off"' ',valve,-1,4,1,"suction on"' \
	',valve,-1,4,0,"suction off"' ',perforation,-1,5,' \
	',sedation,-1,0,0,"sedation none"' ',sedation,-1,0,3,"sedation deep"'; do
	check "the session's events: ${ev#*\"}" grep -qF -- "$ev" "$TMP/events.csv"
done
check "the perforation's words" grep -qE \
	',perforation,-1,5,[0-9.]+,"transverse torn at [0-9.]+ mmHg"' "$TMP/events.csv"
check "the tip's tear: its event and words" grep -qE \
	',tear,-1,[0-8],[0-9.]+,"[a-z_]+ torn by the tip at [0-9.]+ N"' "$TMP/events.csv"
check "the report's event table has them" eval \
	"ctl session report $ID --out $TMP/report >/dev/null &&
	 grep -q '<tr class=\"hand\">.*<td>hand</td><td>pressed at llq, 30 N</td>' $TMP/report/index.html &&
	 grep -q '<td>perforation</td><td>transverse torn at' $TMP/report/index.html"
check "session show lists them" eval \
	"ctl session show $ID >$TMP/show.txt &&
	 grep -q '^patient events$' $TMP/show.txt &&
	 grep -qE '^ +[0-9.]+ s  hand +pressed at llq, 30 N$' $TMP/show.txt"
check "... and its JSON" eval \
	"ctl --json session show $ID | jq -e '[.patient_events[].kind] |
		index(\"position\") and index(\"valve\")'"
check "the session's measures: a turn, a press (stronger, same site), gas in, two perforations (the gas's, the tip's)" eval \
	"ctl --json session show $ID | jq -e '.metrics | .position_changes == 1 and
		.hand_uses == 1 and .gas_used_l > 0.01 and .perforations == 2 and
		.peak_gas_pressure_pa > 1000 and .gloucester >= 1'"
check "... in session show" grep -qE \
	'^patient +1 position changes, 1 hand presses, 2 perforations$' "$TMP/show.txt"
check "... and the report: the perforation marked, the pain's table" eval \
	"grep -q '<tr class=\"bad\"><th>Perforations</th><td>2</td>' $TMP/report/index.html &&
	 grep -q '<h3>Pain</h3>' $TMP/report/index.html"
check "... its pain plotted when the patient felt any" eval \
	"ctl --json session show $ID | jq -e '.metrics.peak_pain == 0' >/dev/null ||
	 grep -q '<figure id=\"plot-pain\">' $TMP/report/index.html"
ctl session export "$ID" --csv --out "$TMP/s.csv" >/dev/null
col() {
	awk -F, -v k="$1" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
		{ print $(c[k]) }' "$TMP/s.csv" | sort -u | tr '\n' ' '
}
check "the CSV: the patient's columns" eval \
	"head -n 1 $TMP/s.csv | grep -q ',patient_enabled,patient_valves,patient_position,patient_turning,patient_turn_1,patient_gas_m3,patient_pressure_pa,patient_gas_in_m3,patient_factor_anal_canal_1,.*,patient_fluid_cecum_m3,patient_hand_site,patient_hand_n,patient_lens_smear_1,patient_lens_murk_1,patient_lens_redout_1,patient_burst_segment,patient_sedation,patient_pain,.*,patient_torn_segment,tool_kind,'"
check "... enabled throughout, left lateral then supine" \
	test "$(col patient_enabled)$(col patient_position)" = "1 0 1 "
check "... the hand at llq and none" test "$(col patient_hand_site)" = "-1 0 "
check "... the valves' bits: none, air, air and water, suction" \
	test "$(col patient_valves)" = "0 1 3 4 "
check "... the sedation: none (0) from the first record, then deep (3)" \
	test "$(col patient_sedation)" = "0 3 "

# --- no patient --------------------------------------------------------------
use_slot off
check "disabled: status says enabled false, no patient line" eval \
	"ctl --json status | jq -e '.patient.enabled == false' >/dev/null &&
	 ! ctl status | grep -q '^patient '"
check_status "disabled: position refused (1)" 1 ctl patient position supine
check "... there is none" grep -q "there is none (\[patient\] enabled = no)" "$OUT"
check_status "disabled: press refused (1)" 1 ctl patient press llq
check_status "patient status: none" 0 ctl patient status
check "... said so" grep -q "^patient   none" "$OUT"
finish
