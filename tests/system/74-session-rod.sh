#!/bin/bash
# The rod model on the wire and in a session (endosimd --set
# haptics.model=rod, the demo's course): `endoctl --json status` has the
# rod's keys (its contacts, the wall's forces, the shape's counts; the
# tube's reaction at the carriage under haptics) and `endoctl status` its
# line; a recorded session holds a SHAPE frame every 33rd cycle (30.3 Hz
# at 1 kHz) with the whole tube and the colon's nodes, its records the rod's
# fields (the CSV's columns), and the file grows by at most 42 MB a minute
# (34 of them the records, the patient's and the tool's fields included).
. "$(dirname "$0")/../common.sh"

# float_test EXPR: awk's arithmetic truth of EXPR
float_test() { awk "BEGIN { exit !($1) }"; }

SESS="$TMP/sessions"
start_daemon --session-dir "$SESS" --set haptics.model=rod \
	--scenario "$TOP/config/scenarios/demo.scn" || finish
ctl enable >/dev/null
check "the course goes on in the rod model (2 s of its clock)" \
	wait_for status_true '.scenario_time_s > 2 and .rod.model == "rod"'
check "status --json: the rod's keys, in their order" \
	test "$(ctl --json status | jq -c '.rod | keys_unsorted')" = \
	'["model","contacts","wall_n","friction_n","points","nodes"]'
check "status --json: the whole tube's points, the colon's nodes, the carriage's force" \
	status_true '.rod.points > 100 and .rod.nodes > 0 and
		(.haptics | has("trans_rod_n") and has("tube_rod_nm"))'
check "status: the rod's line" \
	eval 'ctl status | grep -q "^rod       model rod: [0-9]* contacts, wall"'

check_status "session start" 0 ctl session start --trainee Rod
check "6 s of the course recorded" \
	wait_for status_true '.scenario_time_s > 8'
check_status "session stop" 0 ctl --json session stop
check "... nothing dropped" jq -e '.drops == 0' "$OUT"
f="$SESS/1.endoses"
"$TOOLS/session_shapes" "$f" >"$TMP/shapes.txt"
read -r _ records c0 c1 first last <"$TMP/shapes.txt"
shapes=$(grep -c '^shape ' "$TMP/shapes.txt")
span_s=$(awk -v a="$first" -v b="$last" 'BEGIN { print (b - a) / 1e9 }')
echo "# $records records (cycles $c0..$c1) and $shapes shapes in $span_s s"
check "a SHAPE every 33rd cycle from the first record to the last: 30.3 Hz of the loop's 1 kHz" \
	awk -v c0="$c0" -v c1="$c1" '$1 == "shape" {
		if ($2 % 33 || $2 != (n ? prev + 33 : $2) || $2 - c0 >= 33 && !n)
			exit 1
		prev = $2; n++ } END { exit !(n && c1 - prev < 33) }' \
	"$TMP/shapes.txt"
check "each the whole tube (the status' points) and the colon's nodes" \
	awk -v p="$(status_field .rod.points)" '$1 == "shape" &&
		($4 != p || $5 < 1 || $6 != 40 + 16 * $4 + 12 * $5) { exit 1 }' \
	"$TMP/shapes.txt"
bytes=$(stat -c %s "$f")
per_min=$(awk -v b="$bytes" -v s="$span_s" 'BEGIN { printf "%.1f", b / s * 60 / 1e6 }')
check "the file grows by at most 42 MB a minute: $per_min ($bytes bytes in $span_s s)" \
	float_test "$per_min <= 42"

check_status "export 1 --csv" 0 ctl session export 1 --csv --out "$TMP/s.csv"
check "the CSV has the rod's columns after the haptics', then the guidance's" \
	test "$(head -n 1 "$TMP/s.csv" | cut -d, -f73-80)" = \
	"trans_rod_n,tube_rod_nm,rod_model,rod_contacts,rod_wall_n,rod_friction_n,guide_phase,guide_time_s"
check "... the rod model's rows: model 1, the wall pressing the tube" \
	awk -F, 'NR > 1 { if ($75 != 1) exit 1; if ($76 > 0 && $77 > 0) n++ }
		 END { exit n == 0 }' "$TMP/s.csv"
finish
