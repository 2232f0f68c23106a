#!/bin/bash
# The tool in endoview's endoscopic image (issue 25), on a virtual screen
# (Xvfb, Mesa's llvmpipe), measured from its screenshots' pixels: the
# daemon on the simulated rig in a straight colon, the scope held 12 cm
# in, the hand holding the tool (`endoctl tool hand`) 15 mm out of the
# channel. No tool: nothing light and colourless in the image. A snare:
# its white sheath at 5 o'clock (the channel's place on the tip), and
# its steel loop, open, adding light grey pixels that the same snare
# closed (no loop) has not; the panel says which tool, how far out, the
# handle and the loop. The forceps: their blue sheath where the
# snare's was. Guided replay of a session recorded with the snare: the
# expert's snare a blue ghost where the channel is, the panel saying
# what the expert does, with no tool in the trainee's hand (and on the
# wire and in the shared memory). No run has an OpenGL error. States are
# waited for as the daemon publishes them. ENDOSIM_KEEP_SHOTS=DIR keeps
# the pictures.
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

start_xvfb || finish
HOLD="$TMP/hold.scn"
printf '%s\n' '0 insertion target 0.12 1.5' '60 end' >"$HOLD"
start_daemon --set "case.directory=$TOP/tests/cases" \
	--set case.name=straight --set haptics.model=paper \
	--scenario "$HOLD" || finish
ctl enable >/dev/null
WAIT_S=20 check "the scope held 12 cm in" \
	wait_for status_true '.axes.insertion.position > 0.115'

# shot NAME TOOL DEPTH_MM OPENING: the tool handed over and held, then a
# screenshot of the endoscopic view (1280x720) in $TMP/NAME.png, once the
# published tool says so; its regions in $IMAGE (the whole image circle's
# square) and $CHANNEL (a disc at 5 o'clock, 0.62 of the way out)
shot() {
	local x y w h
	ctl tool select "$2" >/dev/null &&
		ctl tool hand "$3" "$4" --for 10 >/dev/null || return 1
	wait_for status_true ".tool.kind == \"$2\" and
		(.tool.depth_m * 1000 - $3 | fabs) < 0.01 and
		(.tool.opening - $4 | fabs) < 0.001" || return 1
	view --view endo --size 1280x720 --frames 8 --print-state \
		--screenshot "$TMP/$1.png" || return 1
	cp "$VIEW_OUT" "$TMP/$1.out"
	read -r x y w h < <(view_rect endo)
	IMAGE="rect:$x,$y,$w,$h"
	CHANNEL=$(view_channel)
	[ -z "${ENDOSIM_KEEP_SHOTS:-}" ] ||
		cp "$TMP/$1.png" "$ENDOSIM_KEEP_SHOTS/tool-$1.png"
}

check "no tool: screenshot" shot none none 15 1
check "... the panel says none" eval '! grep -q "^hud: tool:" "$TMP/none.out"'
none_grey=$(png_value "$TMP/none.png" "$IMAGE" grey)
check "... nothing light and colourless (grey $none_grey)" \
	float_test "$none_grey < 0.001"
check "the snare open, 15 mm out: screenshot" shot open snare 15 1
keep_picture "$TMP/open.png" tool-snare
check "... the panel says it" grep -qx \
	'hud: tool: snare 15 mm, 15 mm out, handle 100 %, loop 15 mm' \
	"$TMP/open.out"
sheath=$(png_value "$TMP/open.png" "$CHANNEL" grey)
check "... its white sheath at 5 o'clock (grey $sheath there)" \
	float_test "$sheath > 0.5"
check "the snare closed: screenshot" shot closed snare 15 0
open_grey=$(png_value "$TMP/open.png" "$IMAGE" grey)
closed_grey=$(png_value "$TMP/closed.png" "$IMAGE" grey)
what="more grey ($open_grey) than closed ($closed_grey)"
check "... the open loop's steel: $what" \
	float_test "$open_grey > $closed_grey + 0.0005"
check "the forceps: screenshot" shot forceps forceps 15 1
blue=$(png_value "$TMP/forceps.png" "$CHANNEL" mean)
forceps_grey=$(png_value "$TMP/forceps.png" "$CHANNEL" grey)
what="grey $forceps_grey, luma $blue"
check "... their blue sheath at 5 o'clock, not white ($what)" \
	float_test "$forceps_grey < 0.2 && $blue > 40"

# Guided replay's expert's tool (daemon/rig/guide.h): a session recorded
# with the snare 15 mm out, the handle 60 % open and the pedal down (2 s
# of the scenario's clock), then guided at a quarter of its speed with no
# tool in the trainee's hand: the expert's snare on the wire and in the
# shared memory as recorded; drawn as a translucent ghost of its own blue
# where the channel is (not the trainee's snare's white, nor her forceps'
# blue), the panel saying what the expert does.
check_status "a snare for the expert" 0 ctl tool select snare
ctl tool hand 15 0.6 --pedal --for 10 >/dev/null
wait_for status_true '.tool.pedal and (.tool.opening - 0.6 | fabs) < 0.001'
EXPERT=$(ctl --json session start --trainee expert | jq -r .id)
T0=$(status_field .scenario_time_s)
check "the expert's session recorded for 2 s" wait_for status_true \
	".scenario_time_s > $T0 + 2"
check_status "... stopped" 0 ctl session stop
ctl tool hand 15 0.6 --for 0.01 >/dev/null
ctl tool select none >/dev/null
check_status "guided along it at 0.25x, no tool in hand" 0 \
	ctl guide start "$EXPERT" --speed 0.25
check "the wire: the expert's snare, out, the handle, the pedal" \
	wait_for status_true '.guide.phase == "guiding" and
	.tool.kind == "none" and .guide.expert_kind == "snare" and
	(.guide.expert_depth_m - 0.015 | fabs) < 1e-6 and
	(.guide.expert_opening - 0.6 | fabs) < 1e-6 and .guide.expert_pedal'
"$TOOLS/shm_probe" "$SHM" --once >"$TMP/probe.out"
check "the shared memory: the same" eval \
	"grep -qx 'guide.expert_kind=snare' $TMP/probe.out &&
	 grep -qx 'guide.expert_opening=0.600000024' $TMP/probe.out &&
	 grep -qx 'guide.expert_pedal=1' $TMP/probe.out"
check "the expert's ghost: screenshot" eval \
	'view --view endo --size 1280x720 --frames 8 --print-state \
	 --screenshot "$TMP/ghost.png" && cp "$VIEW_OUT" "$TMP/ghost.out"'
keep_picture "$TMP/ghost.png" tool-ghost
check "... the frame showed the expert's snare" \
	grep -qx 'state: expert_kind=2' "$TMP/ghost.out"
check "... the panel says what the expert does" grep -qx \
	'hud: expert: snare 15 mm, 15 mm out, handle 60 %, loop 9 mm, pedal down' \
	"$TMP/ghost.out"
check "... and no tool of the trainee's" eval \
	'! grep -q "^hud: tool:" "$TMP/ghost.out"'
ghost=$(png_value "$TMP/ghost.png" "$CHANNEL" ghost)
open_ghost=$(png_value "$TMP/open.png" "$CHANNEL" ghost)
forceps_ghost=$(png_value "$TMP/forceps.png" "$CHANNEL" ghost)
what="$ghost there; her snare's $open_ghost, her forceps' $forceps_ghost"
check "... its ghost's blue at 5 o'clock ($what)" \
	float_test "$ghost > 0.3 && $open_ghost < 0.01 && $forceps_ghost < 0.01"
ctl guide stop >/dev/null

check "no run had an OpenGL error" eval \
	'! grep -h "^endoview: frames=" "$TMP"/*.out | grep -qv " gl_errors=0 "'
finish
