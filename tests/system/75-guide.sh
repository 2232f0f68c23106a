#!/bin/bash
# Guided replay through the running daemon (endoctl guide, the Guide
# request): a recorded session (session_synth: 20 s of the paper model's
# demo course on the normal case) played back through the simulated rig's
# motors with nobody's hand on it. Refused with a clear status on the
# read-only socket, while not ENABLED, for a damaged file and for a
# session of another case, and nothing changes; started, it follows the
# recording within 5 mm; stopped, it fades out and says why in the status
# and the journal; a session recorded while guided has its phases as
# events; a session recorded without a tool shows no expert's tool (on
# the wire, the HUD, the picture; one with a tool: 44-viewer-tool); the
# trainee's take-over (the viewer's key) fades it out; its
# report compares it with the expert's (--reference). (The
# guidance's behaviour, measured cycle for cycle: test_guide.)
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

SESS="$TMP/sessions"
mkdir -p "$SESS"
"$TOOLS/session_synth" --set haptics.model=paper "$CASES/normal.case" \
	"$TOP/config/scenarios/demo-paper.scn" "$SESS/1.endoses" 20 \
	>/dev/null || fail "session_synth: the recording to guide along"
"$TOOLS/session_synth" --set haptics.model=paper \
	"$CASES/redundant-sigmoid.case" "$TOP/config/scenarios/demo-paper.scn" \
	"$SESS/2.endoses" 2 >/dev/null || fail "session_synth: another case's"
head -c 4000 "$SESS/1.endoses" >"$TMP/cut.endoses"
printf 'ENDOSES1 but nothing after it' >"$TMP/junk.endoses"

start_daemon --set haptics.model=paper || finish

phase_is() {
	status_true ".guide.phase == \"$1\""
}

check_status "not ENABLED: refused (1)" 1 ctl guide start 1
check "... saying to enable first" grep -q "not ENABLED: enable first" "$OUT"
ctl enable >/dev/null
wait_for status_true '.ramp == 1'
check_status "the read-only socket: refused (1)" 1 \
	"$ENDOCTL" --socket "$SOCK/status.sock" guide start 1
check "... as read-only" grep -q "read-only" "$OUT"
check_status "a file that is not a session: refused (1)" 1 \
	ctl guide start "$TMP/junk.endoses"
check "... saying so" grep -q "not a session file" "$OUT"
check_status "a session of another case: refused (1)" 1 ctl guide start 2
check "... naming both cases" grep -q "recorded on case 'redundant-sigmoid', the loaded case is 'normal'" "$OUT"
check_status "a speed beyond 2x: refused (1)" 1 \
	ctl guide start 1 --speed 3
check "nothing changed: off, no session" \
	status_true '.guide.phase == "off" and .guide.source_id == 0'

ID=$(ctl --json session start --trainee guided | jq -r .id)
check_status "guide start 1" 0 ctl guide start 1
check "... the status says it moves to the path or guides" \
	grep -qE "guide: (moving|guiding), session 1" "$OUT"
check "guiding" wait_for phase_is guiding
check "4 s into the recording" wait_for status_true '.guide.time_s > 4'
within_5mm() {
	status_true '.guide.error[0] | (if . < 0 then -. else . end) < 0.005'
}
check "the insertion within 5 mm of the recording's" within_5mm
check "the journal names the session" grep -q "guide: session 1 from 0.00 s at 1.00x" "$LOG"
# endoview: GUIDED on the HUD with the session, its time and the error;
# the reference scope drawn as a ghost in the overview
if start_xvfb; then
	check_status "endoview while guided" 0 view --view both --size 960x540 \
		--frames 20 --print-state --screenshot "$TMP/guided.png"
	check "the HUD says GUIDED" grep -q '^hud: GUIDED$' "$VIEW_OUT"
	check "... the session, its time and speed" \
		grep -qE '^hud: session 1  [0-9.]+ / 20.0 s  x1.00$' "$VIEW_OUT"
	check "... how far off the path" \
		grep -qE '^hud: off the path: ins [-+][0-9.]+ mm' "$VIEW_OUT"
	check "the picture was written" test -s "$TMP/guided.png"
	ghost=$(png_value "$TMP/guided.png" "$(view_channel)" ghost)
	check "a session recorded without a tool: no expert's tool shown (its blue $ghost)" \
		eval "status_true '.guide.expert_kind == \"none\"' &&
		      ! grep -q '^hud: expert:' $VIEW_OUT &&
		      float_test '$ghost < 0.01'"
	[ -z "${ENDOSIM_KEEP_SHOTS:-}" ] ||
		cp "$TMP/guided.png" "$ENDOSIM_KEEP_SHOTS/guided.png"
else
	skip "endoview while guided" "no Xvfb here"
fi
check_status "guide stop" 0 ctl guide stop
check "off, stopped" wait_for status_true \
	'.guide.phase == "off" and .guide.ended == "stopped"'
check "the journal says it ended, stopped" wait_for grep -q "guide: ended (stopped)" "$LOG"
check_status "guide resume (the path kept)" 0 ctl guide resume
check "guiding again" wait_for phase_is guiding
check_status "guide takeover (the viewer's key)" 0 ctl guide takeover
check "faded out, taken over" wait_for status_true \
	'.guide.phase == "taken-over" and .guide.takeovers == 1 and
	 (.guide.force | all(. == 0))'
if [ -n "${DISPLAY:-}" ]; then
	view --view endo --size 640x360 --frames 5 --print-state
	check "the HUD says TAKEN OVER, and the keys" eval \
		"grep -q '^hud: TAKEN OVER$' $VIEW_OUT &&
		 grep -q '^hud: F: follow again, B: back to the path$' $VIEW_OUT"
fi
check_status "a second take-over: refused (1)" 1 ctl guide takeover
check "... nothing to take over from" grep -q "nothing to take over" "$OUT"
check_status "guide reset --to 2" 0 ctl guide reset --to 2
check "holding at 2 s of the recording" wait_for status_true \
	'.guide.phase == "holding" and .guide.time_s == 2'
check_status "a scenario as the reference (its hand's targets)" 0 \
	ctl guide start "$TOP/config/scenarios/demo-paper.scn" --from 3
check "... guiding along it" wait_for status_true \
	'.guide.phase == "guiding" and .guide.source_id == 0 and
	 .guide.length_s > 80'
ctl disable >/dev/null
check "disabled: the guidance ended at once" wait_for status_true \
	'.guide.phase == "off" and .guide.ended == "not-enabled"'
ctl session stop >/dev/null
ctl session export "$ID" --csv --events --out "$TMP/g.csv" >/dev/null
for p in moving guiding fading taken-over off holding; do
	check "the session's events: the guidance $p" \
		grep -q "guide: $p at" "$TMP/g.csv"
done
check_status "the guided session's report against the expert's" 0 \
	ctl session report "$ID" --out "$TMP/report" --reference 1
check "... its comparison: the reference named, its curves along the colon" \
	eval "grep -q 'Compared with the reference: session 1 ' $TMP/report/index.html &&
	      grep -q 'id=\"compare-force\"' $TMP/report/index.html"
check_status "a reference that is not a session: refused (1)" 1 \
	ctl session report "$ID" --out "$TMP/report2" --reference "$TMP/junk.endoses"
finish
