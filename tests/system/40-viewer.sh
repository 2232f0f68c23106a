#!/bin/bash
# The viewer, endoview, on a virtual screen of its own (Xvfb, Mesa's
# llvmpipe), measured from its screenshots' pixels: without a daemon it
# shows its banner and exits cleanly; with the daemon on the simulated rig
# in a colon without bends (tests/cases/straight.case) the endoscopic image
# is a dark lumen amid lit walls, the lit wall fills it once the tip is
# steered at the wall, the overview shows the scope's shape growing with
# the insertion, the HUD is drawn; a loop bows the sigmoid amber in the
# overview and the HUD warns of it, a contact shows red (the demo's course,
# pushed straight into the splenic flexure); in the rod model the
# overview draws the published tube (green inside the patient, dimmer in
# the rig's pipe), the sigmoid where its nodes moved it (amber there,
# round the tube), and the HUD names the model and the loop the state
# gives, warning of a loop only beyond the daemon's loop threshold (the
# metrics'); a stalled daemon reads as stale; the keyboard and the mouse drive
# the simulated hand; a daemon that goes away is shown gone, and its
# successor's colon is fetched. No run has an OpenGL error.
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

start_xvfb || finish
# the straight case, the paper model (the tip where its kinematics put it)
STRAIGHT=(--set "case.directory=$TOP/tests/cases" --set case.name=straight
	  --set haptics.model=paper)
SMALL=(--size 640x480)

# scenario NAME LINE...: a scenario file for the simulated hand; its path.
scenario() {
	local f="$TMP/$1.scn"
	shift
	printf '%s\n' "$@" >"$f"
	echo "$f"
}

# rect_of VIEW: X Y W H CX CY of a view in the last run's layout.
rect_of() {
	read -r X Y W H < <(view_rect "$1")
	CX=$((X + W / 2))
	CY=$((Y + H / 2))
}

# the last run: frames drawn, no OpenGL error, the daemon seen as $1
ran_clean() {
	[ "$(view_field gl_errors)" = 0 ] && [ "$(view_field daemon)" = "$1" ]
}

# discs POINTS R: a png_stats disc of R pixels round each point of POINTS
# ("X,Y;X,Y;...") that lies R or more inside the last rect_of's view.
discs() {
	tr ';' '\n' <<<"$1" | awk -F, -v r="$2" -v x=$X -v y=$Y -v w=$W -v h=$H \
		'$1 >= x + r && $1 < x + w - r && $2 >= y + r && $2 < y + h - r {
			printf "disc:%s,%s,%s\n", $1, $2, r }'
}

# share_of FILE POINTS TEST: "N SHARE": of the discs of 3 pixels round
# the POINTS in the view, how many, and the share whose png_stats values
# pass TEST (awk, on lit, scope).
share_of() {
	local regions
	regions=$(discs "$2" 3)
	[ -n "$regions" ] || { echo "0 0"; return; }
	# shellcheck disable=SC2086 # a region a word
	"$PNG_STATS" "$1" $regions |
		sed 's/.* lit=\([^ ]*\) .* scope=\([^ ]*\) .*/\1 \2/' |
		awk "{ lit = \$1; scope = \$2; n++; k += ($3) }
		     END { printf \"%d %.3f\\n\", n, n ? k / n : 0 }"
}

# drawn KEY: a line of what the last run's overview said (overview_print).
drawn() {
	sed -n "s/^overview: $1//p" "$VIEW_OUT"
}

# scope_box FILE: the overview's scope-green pixels' share and box height.
scope_box() {
	local box
	rect_of overview
	read -r SHARE box < <("$PNG_STATS" "$1" "rect:$X,$Y,$W,$H" |
		sed -n 's/.* scope=\([^ ]*\) box=\([^ ]*\).*/\1 \2/p')
	IFS=, read -r _ Y0 _ Y1 <<<"$box"
	TALL=$((Y1 - Y0))
}

# --- the courses, started ahead --------------------------------------------
# Each section below looks at a course on a daemon of its own: all five
# start here, each in a slot of its own (common.sh), and run while the
# sections before theirs are checked, instead of each section waiting for
# its course in turn (15 s for the loop's). The simulated rig's clock
# counts the loop's cycles: a course reaches the same states whenever its
# section looks. Every course ends holding what its section checks: down
# a straight lumen, 30 cm in; in it, 60 cm in, the tip steered up into the
# wall; the demo's course at 10 cm/s (scenario_gen) held at 40 cm, before
# the sigmoid; the same course on into the splenic flexure, which holds
# the tip while the sigmoid bows, and up to the cecum, held there (its
# withdrawal, after 22 s, would reduce the loop before a slow machine had
# come to look at it); these three in the paper model (its demo course,
# scenario_gen --model paper). The rod model's: the tube pushed in
# straight at 10 cm/s, its tip stopped in the sigmoid, which it carries
# away from where it lay (5 cm by 8 s), on a daemon whose metrics count
# a loop from 20 cm only.
"$TOOLS/scenario_gen" --model paper "$TOP/config/cases/normal.case" 0.1 \
	>"$TMP/fast.scn"
awk '/^#/ || $1 <= 4.5' "$TMP/fast.scn" >"$TMP/held.scn"
echo '60 end' >>"$TMP/held.scn"
awk '/^#/ || ($1 <= 22 && $2 != "end")' "$TMP/fast.scn" >"$TMP/loop.scn"
echo '60 end' >>"$TMP/loop.scn"
use_slot lumen
start_daemon "${STRAIGHT[@]}" \
	--scenario "$(scenario lumen '0 insertion target 0.30 1.5')" || finish
ctl enable >/dev/null
# (the wheel stops where the hand's spring meets the wheel motor's
# 0.1 N m: the wall pushes back harder than the motor can)
use_slot wall
start_daemon "${STRAIGHT[@]}" --scenario "$(scenario wall \
	'0 insertion target 0.60 1.5' '2 wheel_ud target 0.6 1.0')" || finish
ctl enable >/dev/null
use_slot held
start_daemon --scenario "$TMP/held.scn" --set haptics.model=paper || finish
ctl enable >/dev/null
use_slot loop
start_daemon --scenario "$TMP/loop.scn" --set haptics.model=paper || finish
ctl enable >/dev/null
use_slot rod
start_daemon --set haptics.model=rod --set session.loop_threshold_m=0.2 \
	--scenario "$(scenario rod \
	'0 insertion target 0.90 9' '0 wheel_ud target 0 0.1' \
	'0 wheel_lr target 0 0.1' '60 end')" || finish
ctl enable >/dev/null
use_slot main

# --- no daemon -----------------------------------------------------------
check_status "no daemon: draws its frames and exits cleanly" 0 \
	view "${SMALL[@]}" --frames 8 --screenshot "$TMP/none.png"
check "no daemon: says so, no OpenGL error" ran_clean none
rect_of endo
check "no daemon: the red NO DAEMON banner across the image" float_test \
	"$(png_value "$TMP/none.png" "rect:$X,$Y,$W,$H" red) > 0.002"

# --- down a straight lumen ---------------------------------------------
use_slot lumen
check "the scope goes in 30 cm" \
	wait_for status_true '.axes.insertion.position > 0.29'
check_status "lumen: screenshot" 0 \
	view "${SMALL[@]}" --view endo --frames 20 --screenshot "$TMP/lumen.png"
keep_picture "$TMP/lumen.png" endoview-lumen
check "lumen: the straight colon, live, no OpenGL error" eval \
	'ran_clean live && [ "$(view_field colon)" = straight ]'
rect_of endo
ENDO="rect:$X,$Y,$W,$H" # the same in every run at this size
ENDO_CX=$CX
ENDO_CY=$CY
centre=$(png_value "$TMP/lumen.png" "disc:$CX,$CY,$((W / 10))" mean)
walls=$(png_value "$TMP/lumen.png" \
	"ring:$CX,$CY,$((W * 3 / 10)),$((W * 9 / 20))" mean)
echo "# lumen: mean luma $centre at the centre, $walls on the ring around"
check "lumen: a dark hole at the centre, lit walls around it" \
	float_test "$centre < 0.35 * $walls && $walls > 40"
# At full size (a GPU's way): drawn offscreen where it lies in the window
# and copied texel for texel; the same lumen, sharper.
check_status "lumen at full size: screenshot" 0 \
	view "${SMALL[@]}" --view endo --frames 20 --image-scale 1 \
	--screenshot "$TMP/lumen-full.png"
full_centre=$(png_value "$TMP/lumen-full.png" "disc:$CX,$CY,$((W / 10))" mean)
full_walls=$(png_value "$TMP/lumen-full.png" \
	"ring:$CX,$CY,$((W * 3 / 10)),$((W * 9 / 20))" mean)
changed=$("$PNG_STATS" "$TMP/lumen-full.png" --diff "$TMP/lumen.png" \
	"$ENDO" | sed -n 's/.* changed=\([^ ]*\).*/\1/p')
echo "# lumen at full size: mean luma $full_centre at the centre," \
	"$full_walls around; $changed of the image changed from the scaled one"
check "lumen at full size: the same hole and walls, no OpenGL error" \
	eval 'ran_clean live && float_test "$full_centre < 0.35 * $full_walls &&
		$full_walls > 0.9 * $walls && $full_walls < 1.1 * $walls &&
		$changed < 0.05"'
check "lumen: thousands of triangles drawn of the colon's 290 000" \
	float_test "$(view_field triangles) > 1000 && \
		    $(view_field triangles) < 20000"
rect_of panel
check "the HUD is drawn beside the image" float_test \
	"$(png_value "$TMP/lumen.png" "rect:$X,$Y,$W,$H" lit) > 0.01"
check_status "overview at 30 cm: screenshot" 0 \
	view "${SMALL[@]}" --view overview --frames 8 \
	--screenshot "$TMP/over30.png"
scope_box "$TMP/over30.png"
share30=$SHARE
tall30=$TALL
check "overview: the scope's green along its shape" \
	float_test "$share30 > 0.001 && $tall30 > 0.1 * $H"

# --- steered at the wall, deeper -----------------------------------------
stop_daemon
use_slot wall
check "the scope goes in 60 cm, the tip turns up into the wall" wait_for \
	status_true '.axes.insertion.position > 0.58 and
		     .axes.wheel_ud.position > 0.45 and .haptics.contact'
check_status "wall: screenshot" 0 \
	view "${SMALL[@]}" --view endo --frames 20 --screenshot "$TMP/wall.png"
check "wall: no OpenGL error" ran_clean live
rect_of endo
wall=$(png_value "$TMP/wall.png" "disc:$CX,$CY,$((W / 10))" mean)
lit=$(png_value "$TMP/wall.png" "disc:$CX,$CY,$((W * 3 / 10))" lit)
echo "# wall: mean luma $wall at the centre (lumen: $centre), lit $lit"
check "wall: the lit wall fills the view" \
	float_test "$wall > 3 * $centre && $wall > 60 && $lit > 0.9"
check_status "overview at 60 cm: screenshot" 0 \
	view "${SMALL[@]}" --view overview --frames 8 \
	--screenshot "$TMP/over60.png"
scope_box "$TMP/over60.png"
check "overview: the scope's shape grows with the insertion" \
	float_test "$SHARE > 1.3 * $share30 && $TALL > 1.3 * $tall30"
OVER="rect:$X,$Y,$W,$H"

# --- a loop and a contact, from the force model ------------------------
# The paper model's demo course at 10 cm/s (scenario_gen): steered through the
# sigmoid, then pushed straight into the splenic flexure, which holds the
# tip while the sigmoid bows. Before: the same course held at 40 cm
# (and its daemon, stalled, read as stale); the loop's section comes last,
# its course being the longest.
stop_daemon
use_slot held
check "the scope goes in 40 cm in the default case, along the lumen" \
	wait_for status_true '.axes.insertion.position > 0.39 and
			      .scenario_time_s > 6'
check "held there: no loop, no contact" \
	status_true '.scope.bow_m[0] == 0 and (.haptics.contact | not)'
check_status "overview, no loop: screenshot" 0 view --view overview \
	--frames 8 --screenshot "$TMP/plain.png"
rect_of overview
OVER="rect:$X,$Y,$W,$H"

# --- a stalled daemon (the one held at 40 cm) ----------------------------
kill -STOP "$DAEMON_PID"
check_status "stalled daemon: screenshot" 0 \
	view "${SMALL[@]}" --frames 15 --screenshot "$TMP/stale.png"
kill -CONT "$DAEMON_PID"
check "stalled daemon: seen stale, no OpenGL error" ran_clean stale
stop_daemon

# --- the rod model: the whole tube, the colon where its nodes put it -----
use_slot rod
WAIT_S=40 check "rod: the tube pushed on, the sigmoid moves 5 cm" wait_for \
	status_true '.scope.bow_m[0] > 0.05 and .scenario_time_s > 9'
check_status "rod, overview: screenshot" 0 view --view overview \
	--frames 8 --screenshot "$TMP/rod.png" --print-state
keep_picture "$TMP/rod.png" endoview-rod
check "rod: no OpenGL error" ran_clean live
rect_of overview
read -r n share < <(share_of "$TMP/rod.png" "$(drawn rod_in=)" 'scope > 0')
echo "# rod: $n points inside the patient in view, $share of them green"
check "rod: the tube inside the patient is green where its points are" \
	float_test "$n >= 20 && $share >= 0.85"
read -r n share < <(share_of "$TMP/rod.png" "$(drawn rod_out=)" \
	'scope == 0 && lit > 0.5')
echo "# rod: $n points in the rig's pipe in view, $share of them dim"
check "rod: the tube in the rig's pipe is drawn, dimmer" \
	float_test "$n >= 3 && $share >= 0.85"
read -r moved at rest lumen < <(drawn 'span=0 ' |
	sed 's/[a-z_]*=//g; s/,/ /g' | awk '{ print $1, $2 "," $3, $4 "," $5, $6 }')
bow=$(sed -n 's/^state: bow_m=\([^,]*\),.*/\1/p' "$VIEW_OUT")
apart=$(awk -v a="$at" -v b="$rest" 'BEGIN { split(a, p, ","); split(b, q, ",")
	print sqrt((p[1] - q[1]) ^ 2 + (p[2] - q[2]) ^ 2) }')
echo "# rod: the sigmoid moved $moved m (the state: $bow), drawn $apart px from its rest"
check "rod: the sigmoid's centreline moved as far as the state says" \
	float_test "$moved > 0.04 && $moved > 0.9 * $bow && $moved < 1.1 * $bow && \
		    $apart > 2 * $lumen"
# (where it lay other parts of the moved sigmoid may pass: no test there;
# with the moved vertices not uploaded, none is drawn where it moved to).
# The share is the amber rim of the tube in the disc, so it follows the
# picture's moment: 0.054 to 0.092 on the optimised build (5.5 to 6.3 cm
# moved), 0.048 to 0.050 on the sanitizers' (5.6 cm)
r=$(awk -v l="$lumen" 'BEGIN { printf "%.0f", 1.4 * l }')
amber=$(png_value "$TMP/rod.png" "disc:$at,$r" amber)
echo "# rod: amber $amber round where the sigmoid moved to"
check "rod: the moved sigmoid is drawn where its nodes put it" \
	float_test "$amber > 0.03"
within=$(drawn rod_in_lumen=)
echo "# rod: $within of the tube's points inside the patient lie in the colon as drawn"
check "rod: the tube lies in the colon as drawn (moved by the nodes, not bowed)" \
	float_test "$within >= 0.9"
check "rod: the HUD names the model" grep -q '^hud: endosim .* rod model$' \
	"$VIEW_OUT"
check "rod: the HUD gives the sigmoid's loop as the state does" grep -q \
	"^hud: loop: sigmoid $(awk -v b="$bow" 'BEGIN { printf "%.1f", b * 100 }') cm" \
	"$VIEW_OUT"
check "rod: the HUD gives the wall along the tube" \
	grep -qE '^hud: tube on the wall: [1-9][0-9]* contacts?, [0-9.]+ N' "$VIEW_OUT"
check "rod: no loop warning below the daemon's loop threshold (20 cm)" \
	sh -c '! grep "^hud: LOOP" "$1"' _ "$VIEW_OUT"
stop_daemon

# --- the keyboard's hand; the daemon gone and back -----------------------
use_slot main
start_daemon "${STRAIGHT[@]}" || finish
(cd "$TMP" && endoview --socket "$SOCK" --shm-name "$SHM" \
	"${SMALL[@]}" >"$TMP/live.out" 2>&1) &
viewer=$!
# loaded N: the live viewer has loaded a colon N times.
loaded() { [ "$(grep -c "colon straight" "$TMP/live.out")" -ge "$1" ]; }
WAIT_S=20 check "live viewer: the colon is loaded" wait_for loaded 1
window=$(xdotool search --sync --name '^endoview$' | head -n 1)
xdotool windowfocus --sync "$window"
before=$(status_field .axes.insertion.position)
xdotool keydown Up
# held until the hand has carried the scope in 3 cm (at most WAIT_S)
wait_for status_true ".axes.insertion.position > $before + 0.03"
after=$(status_field .axes.insertion.position)
xdotool keyup Up
echo "# the Up key: insertion $before -> $after m"
check "the Up key inserts the scope (the simulated hand)" \
	float_test "$after > $before + 0.03"
# a drag up the image from its middle turns the up/down wheel up
before=$(status_field .axes.wheel_ud.position)
xdotool mousemove --window "$window" "$ENDO_CX" "$ENDO_CY" mousedown 1
for dy in 20 40 60 80 100; do
	xdotool mousemove --window "$window" "$ENDO_CX" $((ENDO_CY - dy))
	sleep 0.1
done
# held until the wheel has turned 0.3 rad (at most WAIT_S)
wait_for status_true ".axes.wheel_ud.position > $before + 0.3"
after=$(status_field .axes.wheel_ud.position)
xdotool mouseup 1
echo "# dragging up: wheel U/D $before -> $after rad"
check "a drag up the image steers the tip up" \
	float_test "$after > $before + 0.3"
# Z: hands off (endosimd's hand lets go of what it holds: test_grip)
xdotool key z
check "Z: hands off, sent to endosimd" \
	wait_for grep -q "hands off" "$TMP/live.out"
stop_daemon
check "the viewer sees the daemon gone" \
	wait_for grep -qE "is gone|no endosimd" "$TMP/live.out"
xdotool key p
check "P saves the picture" wait_for grep -q "saved endoview-" "$TMP/live.out"
picture=$(ls "$TMP"/endoview-*.png 2>/dev/null | head -n 1)
check "the picture shows the NO DAEMON banner" float_test \
	"$(png_value "$picture" "$ENDO" red) > 0.002"
start_daemon "${STRAIGHT[@]}" || finish
WAIT_S=20 check "the daemon back: its colon is fetched again" \
	wait_for loaded 2
# the window resized: the frames follow its events (endoview asks the X
# server nothing in a frame), so the next picture is the new size
rm -f "$TMP"/endoview-*.png
xdotool windowsize --sync "$window" 800 600
xdotool key p
check "resized to 800x600: the next picture is that size" \
	wait_for eval '[ "$(png_value "$(ls "$TMP"/endoview-*.png | head -n 1)" \
		rect:0,0,4000,4000 n)" = 480000 ]'
# P where a picture of that second is already there (placeholders for
# the next 30 s): written beside it, -2, the placeholder left empty.
# Then both views (V twice), a picture, the keys (H), another: with the
# keys asked for, the panel takes the overview's inset (800x600: the
# bottom 240 x 240) for them, the keys' amber names there, the overview's
# blue-grey ground gone. A picture after each key marks a frame drawn.
rm -f "$TMP"/endoview-*.png
now=$(date +%s)
for s in $(seq 0 30); do
	: >"$TMP/endoview-$(date -d "@$((now + s))" +%Y%m%d-%H%M%S).png"
done
# taken N: N pictures written (not the placeholders), the newest $SHOT
taken() {
	local shots
	shots=$(find "$TMP" -maxdepth 1 -name 'endoview-*.png' -size +0)
	[ "$(echo "$shots" | grep -c .)" -ge "$1" ] &&
		SHOT=$(ls -t $shots | head -n 1)
}
xdotool key v p
check "P in a second that has a picture: another beside it" \
	wait_for taken 1
check "... named -2, the first left as it was" eval \
	'case "$SHOT" in *-2.png) true ;; *) false ;; esac &&
	 [ -z "$(find "$TMP" -maxdepth 1 -size +0 \
		-name "endoview-*-[0-9][0-9][0-9][0-9][0-9][0-9].png")" ]'
xdotool key v p
wait_for taken 2
plain=$SHOT
xdotool key h p
wait_for taken 3
keys=$SHOT
INSET=rect:0,360,240,240
plain_amber=$(png_value "$plain" "$INSET" amber)
keys_amber=$(png_value "$keys" "$INSET" amber)
plain_mean=$(png_value "$plain" "$INSET" mean)
keys_mean=$(png_value "$keys" "$INSET" mean)
check "both views, the keys: amber names over the inset ($plain_amber -> $keys_amber)" \
	float_test "$keys_amber > $plain_amber + 0.0007"
check "... on black, not the overview (mean luma $plain_mean -> $keys_mean)" \
	float_test "$keys_mean < $plain_mean"
xdotool key q
wait "$viewer"
check "Q quits the viewer cleanly" test $? = 0

# --- the loop, at last ------------------------------------------------------
use_slot loop
WAIT_S=40 check "pushed into the splenic flexure: the wall holds the tip, the sigmoid bows 5 cm" \
	wait_for status_true '.scope.bow_m[0] > 0.05 and .haptics.contact'
check_status "overview, loop: screenshot" 0 view --view overview \
	--frames 8 --screenshot "$TMP/loop.png" --print-state
keep_picture "$TMP/loop.png" endoview-loop
check "loop: the HUD says it, beyond the paper model's 1 cm" \
	grep -q '^hud: LOOP: the sigmoid bows [0-9.]* cm$' "$VIEW_OUT"
check "the loop and the contact held through the screenshot" \
	status_true '.scope.bow_m[0] > 0.04 and .haptics.contact'
for what in amber red; do
	before=$(png_value "$TMP/plain.png" "$OVER" $what)
	after=$(png_value "$TMP/loop.png" "$OVER" $what)
	echo "# overview, $what: $before without, $after with a loop, contact"
	eval "$what=\$after; ${what}_before=\$before"
done
check "loop: the bowed sigmoid turns amber in the overview" \
	float_test "$amber > 0.003 && $amber > 3 * $amber_before"
check "contact: the contact point shows red in the overview" \
	float_test "$red > 0.0002 && $red_before == 0"
rect_of panel
check "loop: the HUD warns of it" float_test \
	"$(png_value "$TMP/loop.png" "rect:$X,$Y,$W,$H" amber) + \
	 $(png_value "$TMP/loop.png" "rect:$X,$Y,$W,$H" red) > 0.002"

if grep -qE "ERROR: (Address|Leak)Sanitizer|runtime error:" \
	"$TMP"/*.out "$VIEW_OUT" 2>/dev/null; then
	fail "sanitizer report in endoview's output"
fi
finish
