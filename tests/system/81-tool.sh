#!/bin/bash
# The tool through the working channel in the running daemon (issue 25):
# a case loaded has its polyps placed for the tool (the normal case none,
# the polyps case five); `endoctl tool select` hands a tool
# over (a snare of the default [tool] snare_size_m, or of --size MM) and
# the status says it (text and JSON, its keys in their order, every polyp
# in place); refused with nothing changed: on the read-only socket, an
# unknown tool (the tools listed), a snare of 9 or 31 mm (the sizes
# said). The hand's input on the simulated rig (`endoctl tool hand`)
# reaches the published loop: pushed DEPTH out with the handle at
# OPENING, the loop's diameter is d = min(D, 2 l / pi) with l = OPENING
# pi D / 2 (+ DEPTH while the sheath is in the channel), computed here
# from the formula; the pedal published while held. Once the input lapses
# the tool stays where it was and the pedal is up. Forceps and a clip
# closed beyond the wall bite the mucosa and place a clip. A session
# recorded across it all has each tool handed over and each of the
# tool's events (export --events, show and its JSON) and the tool's CSV
# columns; its measures (show, its JSON, the report) have the therapy:
# the bite, the clip, each polyp left. (Capture and cut, cycle for cycle:
# test_tool_loop; the model: test_tool; the assessment: test_resection.)
. "$(dirname "$0")/../common.sh"

start_daemon || finish

t_true() {
	status_true ".tool | $1"
}

check "the normal case: no polyps" t_true '.polyps == 0 and .polyp == []'
check_status "case load polyps" 0 ctl case load polyps
check "... its polyps placed for the tool" wait_for t_true '.polyps == 5'

check "status --json: the tool's keys, in their order" \
	test "$(ctl --json status | jq -c '.tool | keys_unsorted')" = \
	'["kind","pedal","snare_m","depth_m","opening","loop_m","tip","loop_centre","captured","events","event_polyp","clips","polyps","polyp","bleeding","bleed_m3_s","blood_m3","bleed_at","clip_at","lying_polyp","lying_at"]'
check "at the start: no tool, the case's five polyps in place" \
	t_true '.kind == "none" and .polyps == 5 and (.polyp | length) == 5
		and all(.polyp[]; .state == "in-place") and .captured == -1'

# a session recorded across it all
ID=$(ctl --json session start --trainee tool | jq -r .id)

# --- refused, and nothing changes -----------------------------------------
check_status "tool select on the read-only socket: refused (1)" 1 \
	"$ENDOCTL" --socket "$SOCK/status.sock" tool select forceps
check "... as read-only" grep -q "read-only" "$OUT"
check_status "tool hand on the read-only socket: refused (1)" 1 \
	"$ENDOCTL" --socket "$SOCK/status.sock" tool hand 10 1
check_status "tool status on the read-only socket: answered" 0 \
	"$ENDOCTL" --socket "$SOCK/status.sock" tool status
check_status "an unknown tool: refused (1)" 1 ctl tool select scalpel
check "... the tools listed" grep -q \
	"no tool 'scalpel': none, forceps, snare, needle or clip" "$OUT"
check_status "a snare of 9 mm: refused (1)" 1 ctl tool select snare --size 9
check "... the sizes said" grep -q "a snare of 9 mm: from 10 to 30 mm" "$OUT"
check_status "a snare of 31 mm: refused (1)" 1 ctl tool select snare --size 31
check_status "a size not a number: usage (2)" 2 ctl tool select snare --size x
check "nothing changed" t_true '.kind == "none" and .snare_m == 0'

# --- selected ------------------------------------------------------------
check_status "tool select snare: the default size" 0 ctl tool select snare
check "... says so" grep -q "^tool      snare of 15 mm$" "$OUT"
check "... published, 15 mm" t_true '.kind == "snare" and .snare_m == 0.015'
check_status "tool select snare --size 20" 0 ctl --json tool select snare \
	--size 20
check "... its JSON: a snare of 20 mm" \
	test "$(jq -c '[.kind, .snare_m]' "$OUT")" = '["snare",0.02]'
check_status "tool select forceps" 0 ctl tool select forceps
check "... published" t_true '.kind == "forceps" and .snare_m == 0'
check_status "tool select snare --size 20, again" 0 ctl tool select snare \
	--size 20

# --- the hand's input reaches the loop ----------------------------------
# d = min(D, 2 l / pi), l = opening pi D / 2 + min(depth, 0) (not below 0)
loop_mm() { # DEPTH_MM OPENING -> the loop's diameter for D = 20 mm, mm
	awk -v x="$1" -v o="$2" 'BEGIN { pi = atan2(0, -1); D = 20
		l = o * pi * D / 2; if (x < 0) l += x; if (l < 0) l = 0
		d = 2 * l / pi; if (d > D) d = D; printf "%.9f\n", d }'
}
# the published loop, within 1 um of WANT_MM (a float's sum on the wire)
loop_is() { # DEPTH_MM OPENING [PEDAL]
	local want
	want=$(loop_mm "$1" "$2")
	t_true "(.depth_m - $1e-3 | fabs) < 1e-9 and
		(.opening - $2 | fabs) < 1e-9 and
		(.loop_m * 1e3 - $want | fabs) < 1e-3 and
		.pedal == ${3:-false}"
}
for hold in "5 0.5" "5 1" "-3 0.5" "-40 1" "12 0.25"; do
	set -- $hold
	check_status "tool hand $1 mm, opening $2" 0 ctl tool hand "$1" "$2" \
		--for 10
	check "... the loop min(D, 2 l / pi) = $(loop_mm "$1" "$2") mm" \
		wait_for loop_is "$1" "$2"
done
check_status "tool hand 5 mm, opening 0.5, the pedal down" 0 \
	ctl tool hand 5 0.5 --pedal --for 10
check "... the pedal published down" wait_for loop_is 5 0.5 true
check "tool status: the loop, the hand" eval \
	"ctl tool status | grep -qx 'hand      5.0 mm out of the channel, handle 50 % open, pedal down' &&
	 ctl tool status | grep -qx 'loop      10.0 mm'"
# lapsing: the tool still, the pedal up
check_status "tool hand 8 mm, opening 0.75, pedal, for 1.5 s" 0 \
	ctl tool hand 8 0.75 --pedal --for 1.5
check "... held: the pedal down" wait_for loop_is 8 0.75 true
check "... once it lapses: the tool and the handle still, the pedal up" \
	wait_for loop_is 8 0.75 false
check_status "a hand of 11 s: usage (2)" 2 ctl tool hand 5 1 --for 11
check_status "an opening of 2: refused (1)" 1 ctl tool hand 5 2
check "every polyp still in place" \
	t_true 'all(.polyp[]; .state == "in-place")'

# the forceps and a clip closed well beyond the lumen's wall: a bite of
# the mucosa, a clip placed
bite() { # TOOL: opened past one half, then closed, 200 mm out
	ctl tool select "$1" >/dev/null &&
		ctl tool hand 200 1 --for 10 >/dev/null &&
		wait_for t_true '.opening == 1' &&
		ctl tool hand 200 0 --for 10 >/dev/null &&
		wait_for t_true '.opening == 0'
}
check "forceps: opened and closed 200 mm out" bite forceps
check "a clip: opened and closed 200 mm out" bite clip
check "... the clip placed" t_true '.clips == 1'

# --- the session ------------------------------------------------------------
check_status "session stop" 0 ctl session stop
ctl session export "$ID" --csv --events --out "$TMP/events.csv" >/dev/null
for ev in ',tool,2,0,0.0149999997,"a 15 mm snare handed over"' \
	',tool,2,0,0.0199999996,"a 20 mm snare handed over"' \
	',tool,1,0,0,"forceps handed over"' ',tool,-1,32,0,"bite"' \
	',tool,4,0,0,"clip handed over"' ',tool,-1,64,0,"clip"'; do
	check "the session's events: ${ev#*\"}" grep -qF -- "$ev" "$TMP/events.csv"
done
check "session show lists them" eval \
	"ctl session show $ID >$TMP/show.txt &&
	 grep -q '^tool events$' $TMP/show.txt &&
	 grep -qE '^ +[0-9.]+ s  tool +a 20 mm snare handed over$' $TMP/show.txt"
check "... and its JSON" eval \
	"ctl --json session show $ID | jq -e '[.tool_events[].detail] |
		index(32) and index(64)'"
check "the therapy in its measures: the bite, the clip, the five polyps left" \
	eval "ctl --json session show $ID | jq -e '.metrics | .biopsies == 1 and
		.clips == 1 and .polyps_resected == 0 and
		(.polyps | length) == 5 and all(.polyps[]; .fate == \"left\")'"
check "... and in show's text, a line a polyp" eval \
	"grep -qE '^therapy +0 of 5 polyps resected, 0 partly' $TMP/show.txt &&
	 test \$(grep -cE '^  polyp [1-5]: left, cautery' $TMP/show.txt) = 5"
check "... and in its report: the therapy, a row a polyp, each left" eval \
	"ctl session report $ID --out $TMP/report >/dev/null &&
	 grep -q '<section id=\"therapy\">' $TMP/report/index.html &&
	 test \$(grep -cE \
		'<tr id=\"polyp-[1-5]\" class=\"bad\"><th>[1-5]</th><td>left<' \
		$TMP/report/index.html) = 5"
ctl session export "$ID" --csv --out "$TMP/s.csv" >/dev/null
check "the CSV: the tool's columns" eval \
	"head -n 1 $TMP/s.csv | grep -q ',patient_torn_segment,tool_kind,tool_snare_m,tool_depth_m,tool_opening_1,tool_pedal,tool_captured,tool_events,tool_event_polyp,tool_bleed_m3_s,tool_lying_polyp,tool_lying_x_m,tool_lying_y_m,tool_lying_z_m$'"
check "... the loop's opening 0.5 and the pedal recorded" eval \
	"awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[\$i] = i; next }
		\$c[\"tool_pedal\"] == 1 && \$c[\"tool_opening_1\"] == 0.5 { n++ }
		END { exit !(n > 0) }' $TMP/s.csv"
stop_daemon
check "endosimd stopped cleanly" test $? = 0
finish
