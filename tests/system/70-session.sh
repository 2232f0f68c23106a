#!/bin/bash
# A training session on the simulated rig over a known course: the shipped
# demo's (scenario_gen on the normal case at 3 cm/s, 86 s). From the course:
#  - the cecum (its segment starts at s = 1.46 m, the sum of the case's
#    segments before it) is reached when the insertion target passes
#    1.46 m, at 59.32 s of the scenario (the target ramps 1.4506 -> 1.4653 m
#    over 59.0-59.5 s); the hand, a spring-damper, lags its target, and
#    the target rests at 1.48 m until 61.5 s, so the tip gets there in
#    [59.2, 61.5] s of the scenario;
#  - the loop: the tip reaches the splenic flexure (0.68 m) at 22.4 s and
#    is pushed on straight to 0.78 m until 27.5 s, then withdrawn to 0.62 m
#    by 30.5 s: loops (a bow over loop_threshold_m, 1 cm) lie within
#    [22.4, 31.0] s, at least one, none bigger than the sigmoid's mesentery
#    height (0.06 m);
#  - the force episode: the sigmoid's mesentery (600 N/m) holding a loop
#    of 2 cm or more needs 12 N from the hand, so with force_threshold_n
#    set to 10 N the push at the flexure is an episode of excessive force,
#    inside the loop's window; nowhere else does the course push on a held
#    tip.
# Session times become scenario times by the records' scenario clock.
# Also: live status, a parameter change and the state changes as events,
# list, show, export to CSV, and the file's size.
# Under the sanitizers (tests/run.sh's second pass, SANITIZED=1) the course
# is cut after 15 s: that pass looks for memory errors in the same code,
# not for the course's timing, which the plain pass has checked.
. "$(dirname "$0")/../common.sh"

# float_test EXPR: awk's arithmetic truth of EXPR
float_test() { awk "BEGIN { exit !($1) }"; }

SESS="$TMP/sessions"
"$TOOLS/scenario_gen" "$CASES/normal.case" 0.03 >"$TMP/course.scn"
start_daemon --session-dir "$SESS" --scenario "$TMP/course.scn" \
	--set session.force_threshold_n=10 || finish
check_status "session start" 0 ctl session start --trainee "Test Trainee"
check "... as session 1 in the session directory" \
	grep -q "^file $SESS/1.endoses" "$OUT"
ctl enable >/dev/null
sleep 5
check_status "live status" 0 ctl --json session status
check "... recording, records and live metrics coming in" \
	jq -e '.recording and .records > 3000 and .metrics.records > 3000 and
	       .metrics.max_tip_s_m > 0.05 and .drops == 0' "$OUT"
check_status "a parameter change during the session" 0 \
	ctl set limits.enable_ramp_s 0.5
if [ -n "${SANITIZED:-}" ]; then course_s=10; else course_s=84; fi
sleep "$course_s"
ctl disable >/dev/null
sleep 0.2
check_status "session stop" 0 ctl --json session stop
check "... ended, about $((course_s + 5)) s, nothing dropped" \
	jq -e --argjson t "$course_s" '.ended and .duration_s > $t + 1 and
	       .duration_s < $t + 16 and .drops == 0' "$OUT"

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
check "the CSV has a row per record ($(m records)) and names units" \
	test "$(($(wc -l <"$TMP/s.csv") - 1))" = "$(m records)" -a \
	"$(head -c 40 "$TMP/s.csv")" = "t_s,cycle,state,fault_bits,insertion_pos"
col() { head -1 "$TMP/s.csv" | tr , '\n' | grep -nx "$1" | cut -d: -f1; }
# scen T: the scenario's clock at session time T s (the first record at or
# after it). The simulated rig steps the scenario once per force-loop
# cycle, so a stall of this machine that skips periods slows the course
# against the session's clock: the course's windows are checked on its own.
scen() {
	awk -F, -v c="$(col scenario_time_s)" -v t="$1" '
		NR > 1 && $1 >= t { print $c; found = 1; exit }
		{ last = $c }
		END { if (!found) print last }' "$TMP/s.csv"
}
# episodes_within KIND LO HI: at least one episode of KIND (loops, force),
# each starting and ending within [LO, HI] s of the course
episodes_within() {
	local a b n=0
	while read -r a b; do
		float_test "$(scen "$a") >= $2 && $(scen "$b") <= $3" || return 1
		n=$((n + 1))
	done < <(jq -r ".metrics.$1[] | \"\(.start_s) \(.end_s)\"" \
		"$TMP/show.json")
	[ "$n" -ge 1 ]
}
echo "# scenario clock at the session's start: $(scen 0) s"
echo "# metrics: $(jq -c '.metrics | del(.force, .loops)' "$TMP/show.json")"
echo "# loops: $(jq -c .metrics.loops "$TMP/show.json"), force: $(jq -c .metrics.force "$TMP/show.json")"
check "every cycle recorded: consecutive cycles in the CSV" \
	awk -F, 'NR > 2 && $2 != prev + 1 { exit 1 } { prev = $2 }' "$TMP/s.csv"
if [ -z "${SANITIZED:-}" ]; then
	cecum=$(scen "$(m cecum_s)")
	check "cecum reached at $(m cecum_s) s, $cecum s of the course: in [59.2, 61.5] s" \
		float_test "$(m cecum_s) > 0 && $cecum >= 59.2 && $cecum <= 61.5"
	check "insertion time is the time to the cecum; a withdrawal follows" \
		float_test "$(m insertion_s) == $(m cecum_s) && $(m withdrawal_s) > 10"
	check "loops: $(m loop_episodes), all within [22.4, 31.0] s of the course" \
		episodes_within loops 22.4 31.0
	check "largest loop $(m largest_loop_m) m: over 0.01 m, under 0.06 m" \
		float_test "$(m largest_loop_m) > 0.01 && $(m largest_loop_m) < 0.06"
	check "force episodes: $(m force_episodes), all within the loop's window" \
		episodes_within force 22.4 31.0
	check "... each peaking over 10 N" \
		jq -e '.metrics.force | all(.peak > 10)' "$TMP/show.json"
	check "a full course sees most of the mucosa ($(m mucosa_seen))" \
		float_test "$(m mucosa_seen) > 0.5"
fi

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
check "316 bytes a record with its framing, and the header, config, case and events: $per_rec ($per_min MB a minute at 1 kHz)" \
	float_test "$per_rec > 316 && $per_rec < 320"
finish
