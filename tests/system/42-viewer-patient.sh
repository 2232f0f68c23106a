#!/bin/bash
# The patient in endoview (issue 22), on a virtual screen (Xvfb, Mesa's
# llvmpipe), measured from its screenshots' pixels, each daemon with
# [patient] enabled in a straight colon (tests/cases/straight.case), the
# scope held 30 cm in, in the sigmoid: the gas's lumen (the same lumen
# insufflated at 15 mmHg and collapsed to half its width: the open
# lumen's dark middle larger; held air, the viewer's key 1, opens it
# again), a fluid pool seen from above (its dull yellow in the image) and
# from under its surface (the image murky yellow), the lens smeared red by
# the tip pressed into the wall and clear after the water jet (measured
# below the red banner of the perforation that the tip, held there,
# may make). The patient
# panel says the position, the gas, the hand and the valves, and the keys
# T and N turn the patient and put the assistant's hand on the case's
# first site. No run has an OpenGL error. States are waited for as the
# daemon publishes them (the simulated rig's clock counts the loop's
# cycles), never slept for. ENDOSIM_KEEP_SHOTS=DIR keeps the pictures.
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

start_xvfb || finish
SMALL=(--size 640x480)
HOLD="$TMP/hold.scn"
printf '%s\n' '0 insertion target 0.30 1.5' '60 end' >"$HOLD"
# the straight colon and its variants, in a case directory of the test's
mkdir -p "$TMP/cases"
cp "$TOP/tests/cases/straight.case" "$TMP/cases/"
# variant NAME FLUID_M3: the straight colon with FLUID_M3 in the sigmoid
# (the tip's segment) and two of the assistant's sites
variant() {
	awk -v name="$1" -v fluid="$2" '
		/^name = / { print "name = " name; next }
		{ print }
		/^\[segment sigmoid\]/ { print "fluid_m3 = " fluid }
		END { print "[site llq]"; print "position_m = 0.05 -0.20 0.20"
		      print "[site umbilical]"
		      print "position_m = -0.05 -0.23 0.35" }' \
		"$TOP/tests/cases/straight.case" >"$TMP/cases/$1.case"
}
variant pool 30e-6  # a shallow pool beside the tip
variant deep 290e-6 # over the tip (half the lumen: the most a case may hold)
PATIENT=(--set "case.directory=$TMP/cases" --set haptics.model=paper
	 --set patient.enabled=yes)

# --- the courses, started ahead (as in 40-viewer), each holding its state -----
use_slot gas
start_daemon "${PATIENT[@]}" --set case.name=straight --scenario "$HOLD" ||
	finish
ctl enable >/dev/null
use_slot pool
start_daemon "${PATIENT[@]}" --set case.name=pool --scenario "$HOLD" ||
	finish
ctl enable >/dev/null
use_slot deep
start_daemon "${PATIENT[@]}" --set case.name=deep --scenario "$HOLD" ||
	finish
ctl enable >/dev/null
# the tip steered up into the wall from 2 s (it smears the lens), back
# into the lumen from 8 s
use_slot lens
printf '%s\n' '0 insertion target 0.30 1.5' '2 wheel_ud target 0.6 1.0' \
	'8 wheel_ud target 0 1.0' '60 end' >"$TMP/lens.scn"
start_daemon "${PATIENT[@]}" --set case.name=straight \
	--scenario "$TMP/lens.scn" || finish
ctl enable >/dev/null

# p_true JQ: the jq expression over the status' patient is true
p_true() {
	status_true ".patient | $1"
}

# shot NAME: a screenshot of this slot's daemon into $TMP/NAME.png, the
# state and the panel's lines printed (--print-state); the image's view
# and its middle (a disc of a quarter of its side) as $ENDO and $MIDDLE,
# the view below a perforation's banner (its top eighth) as $BELOW
shot() {
	local x y w h
	view "${SMALL[@]}" --frames 12 --screenshot "$TMP/$1.png" --print-state
	read -r x y w h < <(view_rect endo)
	ENDO="rect:$x,$y,$w,$h"
	BELOW="rect:$x,$((y + h / 8)),$w,$((h - h / 8))"
	MIDDLE="disc:$((x + w / 2)),$((y + h / 2)),$((w / 4))"
	[ -z "${ENDOSIM_KEEP_SHOTS:-}" ] ||
		cp "$TMP/$1.png" "$ENDOSIM_KEEP_SHOTS/patient-$1.png"
	case $1 in
	open) keep_picture "$TMP/open.png" patient-insufflated ;;
	collapsed) keep_picture "$TMP/collapsed.png" patient-collapsed ;;
	pool) keep_picture "$TMP/pool.png" patient-pool ;;
	under) keep_picture "$TMP/under.png" patient-under ;;
	smeared) keep_picture "$TMP/smeared.png" patient-smeared ;;
	washed) keep_picture "$TMP/washed.png" patient-washed ;;
	esac
}

# clean: the last run drew its frames live, without an OpenGL error
clean() {
	[ "$(view_field gl_errors)" = 0 ] && [ "$(view_field daemon)" = live ]
}

# take NAME WHAT: the screenshot NAME (shot) of WHAT, drawn clean (checks)
take() {
	check_status "$2: screenshot" 0 shot "$1"
	check "... live, no OpenGL error" clean
}

# value NAME REGION KEY: png_stats' KEY of REGION in the screenshot NAME,
# said as a comment (on stderr)
value() {
	local v
	v=$(png_value "$TMP/$1.png" "$2" "$3")
	echo "# $1: $3 $v in ${2%%:*}" >&2
	echo "$v"
}

# quit_viewer: Q to the live viewer; it is gone
quit_viewer() {
	xdotool key q
	wait "$VIEWER"
}

# said RE: the last run's panel has a line starting with RE (grep -E)
said() {
	grep -qE "^hud: $1" "$VIEW_OUT"
}

# --- the gas: insufflated -----------------------------------------------------
use_slot gas
check "gas: the scope goes in 30 cm, the gas at 15 mmHg" wait_for status_true \
	'.axes.insertion.position > 0.29 and
	 (.patient.pressure_pa / 133.322 | . > 14 and . < 16)'
take open "insufflated"
check "the panel: left lateral, the gas, no hand, no valve" eval \
	'said "patient left lateral$" && said "gas 1[45]\.[0-9] mmHg, " &&
	 said "hand off; valves none$"'
open_lit=$(value open "$MIDDLE" lit)
# the gas absorbed fast (live) until the sigmoid is half its width, then
# held there: no absorption, no leak below 20 mmHg. A watcher of its own
# stops the absorption as soon as the width is reached, while the pool's
# section runs: the absorption takes seconds of the daemon's clock.
ctl set patient.absorb_air_per_s 0.3 >/dev/null
(wait_for p_true '.factor[2] < 0.55' &&
	ctl set patient.absorb_air_per_s 0 >/dev/null) &
ABSORBED=$!

# --- a pool beside the tip; the keys T and N ----------------------------------
use_slot pool
check "pool: the scope 30 cm in, above the surface" wait_for status_true \
	'.axes.insertion.position > 0.29 and (.patient.tip_in_fluid | not)
	 and .patient.fluid_m3[2] > 2.9e-5'
take pool "pool"
pool_yellow=$(value pool "$ENDO" yellow)
dry_yellow=$(value open "$ENDO" yellow)
check "the pool's surface in the image (its yellow, 2 % more than dry)" \
	float_test "$pool_yellow > $dry_yellow + 0.02"
live_view pool "${SMALL[@]}"
xdotool key t
check "the key T: the patient turns to supine" \
	wait_for p_true '.position == "supine" and .turning'
xdotool key n
check "the key N: the assistant's hand on llq (the case's first site)" \
	wait_for p_true '.site == "llq" and .hand_n > 0'
quit_viewer
take turning turning
check "the panel says the turn (or supine, once turned) and the hand" eval \
	'(said "turning to supine, [0-9]+ %$" || said "patient supine$") &&
	 said "hand on llq, 20 N; valves none$"'
# the panel at the size where it draws the figure and the gauge (1280x720),
# for the docs (docs/TRAINEE.md): the same moment, one run more
view --size 1280x720 --frames 12 --screenshot "$TMP/panel.png"
keep_picture "$TMP/panel.png" patient-panel

# --- the gas again: collapsed, opened again by the key 1 ----------------------
use_slot gas
check "the gas absorbed: the sigmoid at half its width" wait "$ABSORBED"
take collapsed "collapsed"
check "... the state held through the screenshot" p_true \
	'.factor[2] < 0.55 and .factor[2] > 0.35'
collapsed_lit=$(value collapsed "$MIDDLE" lit)
check "the open lumen's dark middle is larger (its lit share 0.15 lower)" \
	float_test "$open_lit + 0.15 < $collapsed_lit"
# the air valve held on the viewer's key 1 opens it again: a fast pump
# that stops at 15 mmHg (an insufflator's relief, the gauge's mark)
ctl set patient.pump_m3_per_s 1e-3 >/dev/null
ctl set patient.relief_pa 2000 >/dev/null
live_view straight "${SMALL[@]}"
xdotool keydown 1
check "the key 1 held: the air valve published" \
	wait_for p_true '.valves == "air"'
check "... the sigmoid opens again (its width 0.9 of the case's)" \
	wait_for p_true '.factor[2] > 0.9'
check "... the gas up to the relief's 15 mmHg, where the pump stops" \
	wait_for p_true '.pressure_pa > 1990 and .valves == "air"'
check "... and no further while the key is held" p_true '.pressure_pa < 2010'
xdotool keyup 1
check "the key let go: the valve released" wait_for p_true '.valves == "none"'
quit_viewer
take reopened "opened again"
check "the panel's gas gives the relief" \
	said "gas 1[45]\.[0-9] mmHg, .*, relief 15"
again_lit=$(value reopened "$MIDDLE" lit)
check "... the dark middle as large as before (within 0.1)" \
	float_test "$again_lit < $open_lit + 0.1"

# --- under the surface --------------------------------------------------------
use_slot deep
check "deep: the tip under the surface, the lens murky" wait_for \
	p_true '.tip_in_fluid and .lens_murk > 0.9'
take under "under the surface"
under=$(value under "$ENDO" yellow)
check "the image is the murky liquid (its yellow over half of it)" \
	float_test "$under > 0.5"

# --- the lens: smeared on the wall, washed by the water jet -------------------
use_slot lens
check "lens: pressed into the wall and back in the lumen, smeared" \
	wait_for status_true '.scenario_time_s > 10 and
	 .axes.wheel_ud.position < 0.05 and .patient.lens_smear > 0.3'
take smeared "smeared"
check "the panel gives the lens" said "lens: smear [0-9]+ %"
# --pass-times: each pass of the frame timed; the lens's drawn (> 50 us)
view "${SMALL[@]}" --frames 12 --pass-times
passes=$(sed -n 's/^endoview: passes_ms //p' "$VIEW_OUT")
echo "# passes (p50/p99 ms): $passes"
check "--pass-times: seven passes, the lens's among them" eval \
	'[ "$(echo "$passes" | grep -oE "[a-z]+=[0-9.]+/[0-9.]+" | wc -l)" = 7 ] &&
	 float_test "$(echo "$passes" | sed -n "s/.*lens=\([0-9.]*\)\/.*/\1/p") > 0.05"'
check_status "the water jet (endoctl patient valve water on)" 0 \
	ctl patient valve water on --for 10
check "... the lens clears" wait_for p_true '.lens_smear < 0.01'
check_status "... and the jet stops" 0 ctl patient valve water off
check "the valve released" wait_for p_true '.valves == "none"'
take washed "washed"
smeared=$(value smeared "$BELOW" red)
washed=$(value washed "$BELOW" red)
check "the smear is red over the image (10 % of it), gone once washed" \
	float_test "$smeared > 0.1 && $washed < 0.01"
smeared=$(value smeared "$MIDDLE" lit)
washed=$(value washed "$MIDDLE" lit)
check "the smear veils the dark lumen; washed, it shows again" \
	float_test "$washed + 0.2 < $smeared"

finish
