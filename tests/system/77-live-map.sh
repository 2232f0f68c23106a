#!/bin/bash
# The unseen-mucosa map live (SessionMap, `endoctl session map`, endoview's
# M key) while a session records on the simulated rig: the paper model's
# demo course on the polyps case. Refused, saying so, with no session
# recording; during one, on the read-only socket, 160 x 24 cells, the
# segments, and a seen share that grows as the scope goes in (the map
# asked for twice); the polyps found only (none at the start). In
# endoview, M draws the overlay over the bottom of the window (red
# unseen, green seen where the picture before M had neither), its line
# says which session and how much is seen; after the session stops it
# says that none records. (The quantisation: test_livemap; the map's
# computation, the report's: test_metrics.)
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

RO=(--socket "$SOCK/status.sock")
start_daemon --set haptics.model=paper --set case.name=polyps \
	--scenario "$TOP/config/scenarios/demo-paper.scn" || finish

check_status "no session: session map refused (1)" 1 ctl session map
check "... saying no session is recording" \
	grep -q "no session is recording" "$OUT"

ID=$(ctl --json session start --trainee mapped | jq -r .id)
ctl enable >/dev/null
# map_is JQ: the map over the read-only socket satisfies JQ (kept in $1.json)
map_json() { "$ENDOCTL" "${RO[@]}" --json session map >"$TMP/$1.json"; }
check "the map on the read-only socket" wait_for map_json first
check "... of this session, 160 cells along, 24 around" jq -e \
	".session_id == $ID and .along == 160 and .around == 24" \
	"$TMP/first.json"
check "... every cell a byte: 160 x 24 of them" jq -e \
	'(.cells | length) == 160 and (.cells | all(length == 24)) and
	 ([.cells[][]] | all(. >= 0 and . <= 255))' "$TMP/first.json"
check "... the case's nine segments from the anal canal to the cecum" \
	jq -e '(.regions | length) == 9 and .regions[0].name == "anal_canal"
	       and .regions[8].name == "cecum" and .regions[0].s0_m == 0' \
	"$TMP/first.json"
check "... no polyp found at the start" jq -e '.found == []' \
	"$TMP/first.json"
first=$(jq .cells_seen "$TMP/first.json")

check "the scope 20 cm in along the course" wait_for status_true \
	'.scope.tip_s_m > 0.2'
map_json second
second=$(jq .cells_seen "$TMP/second.json")
echo "# cells seen: $first -> $second"
check "asked again: more of the map seen" float_test "$second > $first + 0.05"
check "... and of the mucosa" jq -e --slurpfile a "$TMP/first.json" \
	'.mucosa_seen > $a[0].mucosa_seen and .time_s > $a[0].time_s' \
	"$TMP/second.json"
check "... the polyps found are the session's (its status' count)" eval \
	"test \"\$(jq '.found | length' $TMP/second.json)\" -le \
	 \"\$(ctl --json session status | jq .metrics.polyps_seen)\""
check_status "the map as text" 0 ctl session map
check "... 24 rows around, 160 cells each" test "$(grep -cE \
	'^ *[0-9]+  [ .:+#]{160}$' "$OUT")" = 24

if ! start_xvfb; then
	skip "endoview: the map on M" "no Xvfb here"
	finish
fi
live_view polyps --size 960x540 --print-state --stats
# shot N: P, the picture saved as $TMP/shotN.png
shot() {
	local before
	before=$(grep -c "saved endoview-" "$TMP/live.out")
	xdotool key p
	wait_for eval "[ \$(grep -c 'saved endoview-' $TMP/live.out) -gt $before ]"
	mv "$(ls -t "$TMP"/endoview-*.png | head -n 1)" "$TMP/shot$1.png"
}
shot 1
xdotool key m
sleep 1.5 # the map asked for (2 Hz) and drawn
shot 2
ctl session stop >/dev/null
sleep 1.5
xdotool key q
wait "$VIEWER"
check "Q quits the viewer cleanly" test $? = 0
[ -z "${ENDOSIM_KEEP_SHOTS:-}" ] ||
	cp "$TMP/shot2.png" "$ENDOSIM_KEEP_SHOTS/live-map.png"
keep_picture "$TMP/shot2.png" endoview-map
read -r mx my mw mh < <(grep '^endoview: layout' "$TMP/live.out" |
	tr ' ' '\n' | sed -n 's/^map=//p' | tr ',' ' ')
check "the overlay's place is given (M shown)" test "${mw:-0}" -gt 0
MAP="rect:$mx,$my,$mw,$mh"
before_red=$(png_value "$TMP/shot1.png" "$MAP" red)
before_green=$(png_value "$TMP/shot1.png" "$MAP" scope)
red=$(png_value "$TMP/shot2.png" "$MAP" red)
green=$(png_value "$TMP/shot2.png" "$MAP" scope)
echo "# the overlay's region: red $before_red -> $red," \
	"green $before_green -> $green"
check "M: the map's unseen cells in red" float_test \
	"$red > 0.05 && $red > $before_red + 0.04"
check "... its seen cells in green" float_test \
	"$green > 0.05 && $green > $before_green + 0.04"
check "after the session's stop the overlay says none records" \
	grep -q '^map: no session is recording$' "$TMP/live.out"
finish
