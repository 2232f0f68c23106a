#!/bin/bash
# A training session in the running daemon, on the simulated rig over the
# shipped demo course (scenario_gen on the normal case at 3 cm/s): session
# start, live status, a parameter change and the state changes as events,
# stop, list, show, export to CSV, every cycle in the file, and the file's
# size. Every wait is on a state. What the session's metrics make of the
# whole course (the cecum, the loops and the force episode in their
# windows) depends on how many cycles ran: checked in lockstep, cycle for
# cycle, by tests/unit/test_course.c (test_session_metrics, the paper
# model on config/scenarios/demo-paper.scn, which is checked here to still
# be scenario_gen --model paper's course) and test_rodcourse.c (the rod
# model on config/scenarios/demo.scn, which that test checks is the
# trainee's course).
. "$(dirname "$0")/../common.sh"

# float_test EXPR: awk's arithmetic truth of EXPR
float_test() { awk "BEGIN { exit !($1) }"; }

SESS="$TMP/sessions"
"$TOOLS/scenario_gen" --model paper "$CASES/normal.case" 0.03 \
	>"$TMP/course.scn"
check "the shipped paper demo is scenario_gen's course at 3 cm/s on normal" \
	cmp "$TMP/course.scn" "$TOP/config/scenarios/demo-paper.scn"
start_daemon --session-dir "$SESS" \
	--scenario "$TOP/config/scenarios/demo.scn" \
	--set session.force_threshold_n=10 || finish
check_status "session start" 0 ctl session start --trainee "Test Trainee"
check "... as session 1 in the session directory" \
	grep -q "^file $SESS/1.endoses" "$OUT"
# the scenario's clock runs from the daemon's start: the session's from
# its own (at or before this reading)
t_start=$(status_field .scenario_time_s)
ctl enable >/dev/null
check "live status: recording, records and live metrics coming in" \
	wait_for live_status '.recording and .records > 3000 and
	       .metrics.records > 3000 and .metrics.max_tip_s_m > 0.05'
check_status "a parameter change during the session" 0 \
	ctl set limits.enable_ramp_s 0.5
check "the course goes on 8 s of its clock into the session" \
	wait_for status_true ".scenario_time_s > $t_start + 8"
ctl disable >/dev/null
check "disabled" wait_for status_true '.state == "IDLE"'
check_status "session stop" 0 ctl --json session stop
check "... ended, over 8 s, nothing dropped" \
	jq -e '.ended and .duration_s > 8 and .drops == 0' "$OUT"

check_status "list" 0 ctl --json session list
check "... the one session, ended, its trainee and case" \
	jq -e '.sessions | length == 1 and .[0].ended and
	       .[0].trainee == "Test Trainee" and .[0].case == "normal"' "$OUT"
check_status "show 1" 0 ctl --json session show 1
cp "$OUT" "$TMP/show.json"
check "its end: its start plus its duration, UTC" \
	jq -e '(.ended_at | fromdateiso8601) - (.started | fromdateiso8601) -
	       .duration_s | fabs <= 1' "$TMP/show.json"
check_status "export 1 --csv" 0 ctl session export 1 --csv --out "$TMP/s.csv"
m() { jq -r ".metrics.$1" "$TMP/show.json"; }
echo "# metrics: $(jq -c '.metrics | del(.force, .loops)' "$TMP/show.json")"
check "the CSV has a row per record ($(m records)) and names units" \
	test "$(($(wc -l <"$TMP/s.csv") - 1))" = "$(m records)" -a \
	"$(head -c 40 "$TMP/s.csv")" = "t_s,cycle,state,fault_bits,insertion_pos"
check "every cycle recorded: consecutive cycles in the CSV" \
	awk -F, 'NR > 2 && $2 != prev + 1 { exit 1 } { prev = $2 }' "$TMP/s.csv"
check "the live metrics went into the file: the tip deeper than 0.1 m" \
	float_test "$(m max_tip_s_m) > 0.1"
check "... and the scope's handling: pushed in, the tip following" \
	float_test "$(m shaft_in_m) > 0.1 && $(m chase_efficiency) > 0.5"
check_status "export 1 --summary" 0 ctl session export 1 --summary \
	--out "$TMP/summary.csv"
summary() { # the summary CSV's column $1
	awk -F, -v k="$1" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i }
		NR == 2 { print $c[k] }' "$TMP/summary.csv"
}
check "... one row: the session, its trainee, its measures as show has them" \
	eval '[ "$(wc -l <"$TMP/summary.csv")" = 2 ] &&
	      [ "$(summary id)" = 1 ] &&
	      [ "$(summary trainee)" = "\"Test Trainee\"" ] &&
	      float_test "$(summary shaft_in_m) == $(m shaft_in_m)"'

ctl session export 1 --csv --events --out "$TMP/events.csv"
check "events: IDLE first, then ENABLED, then IDLE after the disable" \
	test "$(awk -F, '$2 == "state" { printf "%s ", $6 }' "$TMP/events.csv")" \
	= '"IDLE" "ENABLED" "IDLE" '
check "events: the parameter change" \
	grep -q ',param,.*"limits.enable_ramp_s=0.5"' "$TMP/events.csv"
check "events: no drops, no fault" \
	test -z "$(awk -F, '$2 == "drops" || $2 == "fault"' "$TMP/events.csv")"

f="$SESS/1.endoses"
check "the file starts with its magic" test "$(head -c 8 "$f")" = ENDOSES1
bytes=$(stat -c %s "$f")
per_rec=$(awk -v b="$bytes" -v n="$(m records)" \
	'BEGIN { printf "%.1f", b / n }')
per_min=$(awk -v r="$per_rec" 'BEGIN { printf "%.1f", r * 60e3 / 1e6 }')
echo "# file: $bytes bytes, $(m records) records in $(m duration_s) s"
# the rod model (the default): a record is 584 bytes with its framing
# (format 8: 572 and 12), and every 33rd cycle the tube's shape (a SHAPE
# frame of 3096 bytes on the normal case: 161 points, 39 colon nodes) adds
# 93.8 bytes a record; what else the file holds (the header, config, case
# and events, ~47 kB) under 50 kB. The shapes are counted in the file
# (session_shapes): N records hold N/33 of them or one more, as the cycle
# the session starts on falls, and that frame moved the average of ~8100
# records by 0.4 byte, all of the old bound's margin (683.98 against 684)
n=$(m records)
shapes=$("$TOOLS/session_shapes" "$f" | grep -c '^shape ')
rest=$((bytes - 584 * n - 3096 * shapes))
check "584 bytes a record with its framing, a 3096-byte shape every 33rd ($shapes), the rest under 50 kB: $rest bytes ($per_rec a record, $per_min MB a minute at 1 kHz, at most 42)" \
	float_test "$rest >= 0 && $rest <= 50000 && $per_min <= 42 &&
		    $shapes >= int($n / 33) && $shapes <= int($n / 33) + 1"
finish
