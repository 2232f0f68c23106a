#!/bin/bash
# Guided replay through the running daemon (endoctl guide, the Guide
# request): a recorded session (session_synth: 20 s of the paper model's
# demo course on the normal case) played back through the simulated rig's
# motors with nobody's hand on it. Refused with a clear status on the
# read-only socket, while not ENABLED, for a damaged file and for a
# session of another case, and nothing changes; started, it follows the
# recording within 5 mm; stopped, it fades out and says why in the status
# and the journal; a session recorded while guided has its phases as
# events. (The guidance's behaviour, measured cycle for cycle: test_guide.)
. "$(dirname "$0")/../common.sh"

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
check_status "guide stop" 0 ctl guide stop
check "off, stopped" wait_for status_true \
	'.guide.phase == "off" and .guide.ended == "stopped"'
check "the journal says it ended, stopped" wait_for grep -q "guide: ended (stopped)" "$LOG"
check_status "guide resume (the path kept)" 0 ctl guide resume
check "guiding again" wait_for phase_is guiding
check_status "guide reset --to 2" 0 ctl guide reset --to 2
check "holding at 2 s of the recording" wait_for status_true \
	'.guide.phase == "holding" and .guide.time_s == 2'
ctl disable >/dev/null
check "disabled: the guidance ended at once" wait_for status_true \
	'.guide.phase == "off" and .guide.ended == "not-enabled"'
ctl session stop >/dev/null
ctl session export "$ID" --csv --events --out "$TMP/g.csv" >/dev/null
for p in moving guiding fading off holding; do
	check "the session's events: the guidance $p" \
		grep -q "guide: $p at" "$TMP/g.csv"
done
finish
