#!/bin/bash
# A replayed session shows the tool (issue 25): a snare handed over and
# pushed out with its handle part open (`endoctl tool hand`) while a
# session records; endoview --replay of that file, paused at its end (the
# tool held there, the scope still), shows the tool where the daemon
# published it live: its kind, depth and opening as recorded, its tip and
# the snare's loop (its diameter and centre, which the file does not
# hold: the model puts them on the recorded tip, tool.h) within a float's
# rounding of the recorded pose, with the channel where the recorded
# configuration put it.
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

start_xvfb || finish
# the channel at 3 o'clock, not the default 5: the replay takes the file's
start_daemon --set tool.channel_angle_deg=90 || finish
TOL_M=0.00001 # a float's rounding of the recorded tip, dir and up

# live KEY: the tool's field as the daemon publishes it now (shm_probe)
live() {
	"$TOOLS/shm_probe" "$SHM" --once | sed -n "s/^tool.$1=//p"
}

# replay ARGS...: endoview on a session file, headless; output in $VIEW_OUT
replay() {
	endoview --no-vsync --size 640x480 --replay "$@" >"$VIEW_OUT" 2>&1
}

# shown KEY: a field of the state the replay's last frame showed
shown() {
	sed -n "s/^state: $1=//p" "$VIEW_OUT"
}

# near A B: the points "x,y,z" A and B within TOL_M in each coordinate
near() {
	echo "$1 ~ $2"
	awk -v a="$1" -v b="$2" -v tol="$TOL_M" 'BEGIN {
		n = split(a, p, ","); m = split(b, q, ",")
		if (n != 3 || m != 3) exit 1
		for (i = 1; i <= 3; i++) {
			d = p[i] - q[i]; d = d < 0 ? -d : d
			if (!(d <= tol)) exit 1
		}
	}'
}

same() {
	echo "$1 = $2"
	awk -v a="$1" -v b="$2" -v tol="$TOL_M" 'BEGIN {
		d = a - b; d = d < 0 ? -d : d; exit !(a != "" && d <= tol) }'
}

check_status "a 20 mm snare handed over" 0 ctl tool select snare --size 20
ID=$(ctl --json session start --trainee replay-tool | jq -r .id)
check "a session recording" [ -n "$ID" ]
ctl tool hand 8 0.6 --pedal --for 10 >/dev/null
check "the snare out 8 mm, the handle 0.6 open, the pedal down" \
	wait_for [ "$(live pedal)" = 1 ]
sleep 1.5
TIP=$(live tip)
CENTRE=$(live loop_centre)
LOOP=$(live loop_m)
DEPTH=$(live depth_m)
check "live: the loop open (the daemon's)" awk -v l="$LOOP" \
	'BEGIN { exit !(l > 0.005) }'
ctl tool hand 8 0.6 --for 0.05 >/dev/null # the pedal up, the tool held
sleep 0.5
check_status "session stop" 0 ctl session stop
FILE="$TMP/sessions/$ID.endoses"
check "the file is there" test -s "$FILE"

check_status "replay paused at its end" 0 replay "$FILE" --paused \
	--seek 1000 --frames 3 --print-state
check "replay: the snare (kind 2)" [ "$(shown tool_kind)" = 2 ]
check "replay: its depth as recorded" same "$(shown tool_depth_m)" "$DEPTH"
check "replay: the handle as recorded" same "$(shown tool_opening)" 0.6
check "replay: the tool's tip where the daemon had it" \
	near "$(shown tool_tip)" "$TIP"
check "replay: the loop's diameter the daemon's" \
	same "$(shown tool_loop_m)" "$LOOP"
check "replay: the loop's centre the daemon's" \
	near "$(shown tool_loop_centre)" "$CENTRE"

finish
