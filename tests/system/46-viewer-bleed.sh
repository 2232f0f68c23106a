#!/bin/bash
# A bleeding stalk and the clip that stops it in endoview's endoscopic
# image (issue 25), on a virtual screen (Xvfb, Mesa's llvmpipe): the
# daemon on the simulated rig in the straight colon with one stalked
# polyp at 5 o'clock (a 5 mm stalk 25 mm long, reaching the snare's loop
# from the wall), the scope held 9.6 cm in (the angle, the places and the
# bend found by trying: the straight colon's frame u is the image's 12
# o'clock at no roll). A 20 mm snare closed round
# the stalk and then all the way, cold: the stalk cut, bleeding its
# documented flow (tool.h: 1 mm/s over its section) from its foot; the
# image redder than with the snare round the stalk uncut. Then (the
# scenario at 15 s; the cut and its checks take about 4) the scope 11.3
# cm in, its tip bent towards 5 o'clock, and a clip pushed out by as
# much as brings its jaws to the bleeding point (from the published tool
# and scope), closed: the point clipped,
# no flow, the image's red gone again. ENDOSIM_KEEP_SHOTS=DIR keeps the
# pictures. A session recorded across it keeps the bleeding's events
# (its start with the flow, the clip that stopped it) and its flow in the
# CSV. The cut polyp falls to the lowest wall (lying on the left side:
# at 9 o'clock here). endoview --replay of the session, at the records
# the live shots showed, has the bleeding point, the cut polyp where it
# lay and the clip where live had them (the state within a float's
# rounding, the image's pixel within 2, the pixels round each as live
# drew them); replayed at the cut and half a second on, the image
# changed where it lies (the polyp fell there) and hardly elsewhere. No
# run has an OpenGL error.
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

start_xvfb || finish
mkdir -p "$TMP/cases"
sed 's/^name = straight/name = bleed/' "$TOP/tests/cases/straight.case" \
	>"$TMP/cases/bleed.case"
cat >>"$TMP/cases/bleed.case" <<'CASE'

[polyp]
s_m = 0.120
angle_deg = 150
diameter_m = 0.009
shape = pedunculated
stalk_length_m = 0.025
stalk_diameter_m = 0.005
CASE
SCN="$TMP/scope.scn"
printf '%s\n' '0 insertion target 0.096 1.5' '15 insertion target 0.113 1.5' \
	'15 wheel_ud target -0.18 1.5' '15 wheel_lr target 0.10 1.5' \
	'120 end' >"$SCN"
start_daemon --set "case.directory=$TMP/cases" --set case.name=bleed \
	--set haptics.model=paper --scenario "$SCN" || finish
ctl enable >/dev/null
WAIT_S=20 check "the scope held 9.6 cm in" \
	wait_for status_true '.axes.insertion.position > 0.094'
POLYP=$(ctl --json status | jq '.tool.polyps - 1')

# hand DEPTH_MM OPENING: the hand holds the tool so, until published
hand() {
	ctl tool hand "$1" "$2" --for 10 >/dev/null &&
		wait_for status_true "(.tool.depth_m * 1000 - $1 | fabs) < 0.01
			and (.tool.opening - $2 | fabs) < 0.001"
}

# shot NAME: the endoscopic view (1280x720) in $TMP/NAME.png; the image
# circle's square in $IMAGE
shot() {
	local x y w h
	view --view endo --size 1280x720 --frames 8 --print-state \
		--screenshot "$TMP/$1.png" || return 1
	cp "$VIEW_OUT" "$TMP/$1.out"
	read -r x y w h < <(view_rect endo)
	IMAGE="rect:$x,$y,$w,$h"
	[ -z "${ENDOSIM_KEEP_SHOTS:-}" ] ||
		cp "$TMP/$1.png" "$ENDOSIM_KEEP_SHOTS/bleed-$1.png"
}

ID=$(ctl --json session start --trainee bleed | jq -r .id)
ctl tool select snare --size 20 >/dev/null
check "the snare open 15 mm out" hand 15 1
check "... closed round the stalk" hand 15 0.1
check "... which it holds" status_true ".tool.captured == $POLYP"
check "the snare round the stalk: screenshot" shot held
check "the snare closed all the way: the stalk cut" hand 15 0
check "... and bleeding from its foot" wait_for status_true \
	".tool.polyp[$POLYP].state == \"cut\" and .tool.bleeding == 1 and
	 (.tool.bleed_m3_s - 1e-3 * 3.14159265 * 0.005 * 0.005 / 4 | fabs)
	 < 1e-12"
check "... endoctl tool says so" eval \
	"ctl tool status | grep -qE '^polyp $POLYP +cut .*, bleeding 1.2 mL/min'"
check "the bleeding: screenshot" shot bleeding
keep_picture "$TMP/bleeding.png" tool-bleeding
check "... the panel says it, in red" \
	grep -qx 'hud: bleeding: 1 point, 1.2 mL/min, [0-9.]* mL shed' \
	"$TMP/bleeding.out"
held=$(png_value "$TMP/held.png" "$IMAGE" blood)
bleeding=$(png_value "$TMP/bleeding.png" "$IMAGE" blood)
check "... the image redder ($bleeding of it blood-red, $held before)" \
	float_test "$bleeding > $held + 0.05"

check "the cut's checks done before the scope moves (15 s)" \
	status_true '.scenario_time_s < 15'
WAIT_S=30 check "the scope 11.3 cm in, bent towards 5 o'clock" \
	wait_for status_true '.scenario_time_s > 18'
ctl tool select clip >/dev/null
hand 5 0 >/dev/null
# the jaws (clip_m, 5 mm, beyond the tool's tip) onto the point
depth=$(ctl --json status | jq '.tool as $t | .scope.dir as $d |
	[range(3) | $t.tip[.] - $t.depth_m * $d[.]] as $exit |
	([range(3) | ($t.bleed_at[.] - $exit[.]) * $d[.]] | add) - 0.005 |
	. * 1000 | round')
check "the clip open $depth mm out, over the point" hand "$depth" 1
check "... closed: placed" hand "$depth" 0
check "... on the point: the bleeding clipped, no flow" wait_for status_true \
	".tool.clips == 1 and .tool.polyp[$POLYP].bleed == \"clipped\" and
	 .tool.bleeding == 0 and .tool.bleed_m3_s == 0"
check "the clip on the point: screenshot" shot clipped
keep_picture "$TMP/clipped.png" tool-clipped
clipped=$(png_value "$TMP/clipped.png" "$IMAGE" blood)
check "... the image's red gone ($clipped blood-red, $bleeding bleeding)" \
	float_test "$clipped < $bleeding - 0.05"

# the session: the bleeding's events with the flow, its start and stop
check "session stop" ctl session stop
ctl session export "$ID" --csv --events --out "$TMP/events.csv" >/dev/null
check "the session's events: the cut and the bleeding (the flow, m^3/s)" \
	grep -qE ",tool,$POLYP,128,1.96[0-9]*e-08,\"bleed, polyp $POLYP \(1.2 mL/min bleeding\)\"" "$TMP/events.csv"
check "... the clip that stopped it, none bleeding after" \
	grep -qE ",tool,$POLYP,256,0,\"clipped, polyp $POLYP \(0.0 mL/min bleeding\)\"" "$TMP/events.csv"
check "... session show lists them" eval \
	"ctl session show $ID | grep -qE '^ +[0-9.]+ s  tool +clipped, polyp $POLYP'"
ctl session export "$ID" --csv --out "$TMP/s.csv" >/dev/null
check "... the CSV's flow: 5 mm's while it bled" eval \
	"awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[\$i] = i; next }
		\$c[\"tool_bleed_m3_s\"] > 1.9e-8 { n++ } END { exit !(n > 1000) }' \
		$TMP/s.csv"

# --- the session replayed: what the tools left, where live had it ---
FILE="$TMP/sessions/$ID.endoses"
# replay_at NAME T: the file replayed, paused T s after its first record,
# as the live shots; its screenshot $TMP/replay-NAME.png, its output
# $TMP/replay-NAME.out
replay_at() {
	endoview --no-vsync --replay "$FILE" --seek "$2" --paused --view endo \
		--size 1280x720 --frames 3 --print-state \
		--screenshot "$TMP/replay-$1.png" >"$TMP/replay-$1.out" 2>&1 ||
		return 1
	[ -z "${ENDOSIM_KEEP_SHOTS:-}" ] ||
		cp "$TMP/replay-$1.png" "$ENDOSIM_KEEP_SHOTS/bleed-replay-$1.png"
}
# since T_S: T_S (the CSVs' clock) as the replay's, from the first record
since() {
	awk -F, -v t="$1" 'NR == 2 { printf "%.4f", t - $1 + 0.0002; exit }' \
		"$TMP/s.csv"
}
# cycle_t SHOT: the CSVs' time of the record the live shot showed
cycle_t() {
	awk -F, -v c="$(sed -n 's/^state: cycle=//p' "$TMP/$1.out")" '
		NR == 1 { for (i = 1; i <= NF; i++) k[$i] = i; next }
		$k["cycle"] == c { print $1; exit }' "$TMP/s.csv"
}
# state OUT KEY: a key of the state a run printed
state() { sed -n "s/^state: $2=//p" "$1"; }
# drawn OUT WHAT: where a run's image put WHAT ("X,Y")
drawn() { sed -n "s/^endo: $2 at //p" "$1"; }
# near A B TOL: the comma-separated numbers A and B within TOL each
near() {
	echo "$1 ~ $2"
	awk -v a="$1" -v b="$2" -v tol="$3" 'BEGIN {
		n = split(a, p, ","); m = split(b, q, ",")
		if (n != m || n == 0) exit 1
		for (i = 1; i <= n; i++) {
			d = p[i] - q[i]; d = d < 0 ? -d : d
			if (!(d <= tol)) exit 1
		}
	}'
}
# disc XY R: png_stats' disc of radius R round "X,Y"
disc() { echo "disc:$1,$2"; }

cut=$(awk -F, -v p="$POLYP" '$2 == "tool" && $3 == p && $4 == 4 {
	print $1; exit }' "$TMP/events.csv")
check "replayed at the cut" replay_at cut "$(since "$cut")"
check "... and half a second on" \
	replay_at fallen "$(since "$(awk -v t="$cut" 'BEGIN { print t + 0.5 }')")"
check "... the scope's tip where it was at the cut" near \
	"$(state "$TMP/replay-fallen.out" tip)" \
	"$(state "$TMP/replay-cut.out" tip)" 1e-4
LIE=$(drawn "$TMP/replay-fallen.out" "polyp $POLYP lying")
moved=$(png_changed "$TMP/replay-fallen.png" "$TMP/replay-cut.png" \
	"$(disc "$LIE" 20)")
still=$(png_changed "$TMP/replay-fallen.png" "$TMP/replay-cut.png" \
	"$IMAGE")
check "the polyp fallen since the cut: the image changed where it lies, $LIE ($moved of a disc there, $still of the image)" \
	float_test "$moved > 0.5 && $still < 0.05"
check "replayed when live showed the bleeding" \
	replay_at bleeding "$(since "$(cycle_t bleeding)")"
check "... the same record" test "$(state "$TMP/replay-bleeding.out" cycle)" = \
	"$(state "$TMP/bleeding.out" cycle)"
check "... the bleeding point where live had it" near \
	"$(state "$TMP/replay-bleeding.out" tool_bleed_at)" \
	"$(state "$TMP/bleeding.out" tool_bleed_at)" 1e-6
check "... the cut polyp lying where live had it" near \
	"$(state "$TMP/replay-bleeding.out" tool_lying | tr ':' ',')" \
	"$(state "$TMP/bleeding.out" tool_lying | tr ':' ',')" 1e-5
LIE=$(drawn "$TMP/bleeding.out" "polyp $POLYP lying")
check "... drawn where live drew it ($LIE)" near \
	"$(drawn "$TMP/replay-bleeding.out" "polyp $POLYP lying")" "$LIE" 2
same=$(png_changed "$TMP/replay-bleeding.png" "$TMP/bleeding.png" \
	"$(disc "$LIE" 20)")
check "... as live drew it there ($same of a disc round it differs)" \
	float_test "$same < 0.1"
check "replayed when live showed the clip" \
	replay_at clipped "$(since "$(cycle_t clipped)")"
check "... the clip where live had it" near \
	"$(state "$TMP/replay-clipped.out" tool_clip_at)" \
	"$(state "$TMP/clipped.out" tool_clip_at)" 1e-5
check "... the point clipped: none bleeding" \
	test -z "$(state "$TMP/replay-clipped.out" tool_bleeding)"
CLIP=$(drawn "$TMP/clipped.out" clip)
check "... drawn where live drew it ($CLIP)" near \
	"$(drawn "$TMP/replay-clipped.out" clip)" "$CLIP" 2
same=$(png_changed "$TMP/replay-clipped.png" "$TMP/clipped.png" \
	"$(disc "$CLIP" 12)")
check "... and looks as live ($same of a disc round it differs)" \
	float_test "$same < 0.1"

check "no run had an OpenGL error" eval \
	'! grep -h "^endoview: frames=" "$TMP"/*.out | grep -qv " gl_errors=0 "'
finish
