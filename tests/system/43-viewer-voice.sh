#!/bin/bash
# The patient reacts in endoview (issue 23), headless: the voice heard
# through OpenAL Soft's wave-file backend (ALSOFT_DRIVERS=wave, its file
# named in an ALSOFT_CONF of the test's) and measured with sox, and the
# panel's face, level and perforation seen in screenshots, on a virtual
# screen (Xvfb, Mesa's llvmpipe). The level is a replayed session file
# (session_synth --pain, --tear: the record's pain as chosen), so that it
# crosses its steps at known times of the replay's clock, which a
# headless replay runs by a fixed step per frame:
#
#    0-3 s  0; 3-4 s up to 6, held: a groan at 3.67 s (4 crossed); ow
#    (5.5, crossed at 3.92 s) when the interval of 4 s is over, at 7.67 s;
#    8.5-9 s up to 9, held: please stop (8.5, crossed at 8.83 s) at
#    11.67 s; 12.5 s the tip tears the sigmoid: the cry at once.
#
# The build's clips sound (RMS above silence); the viewer logs each clip
# with its time on the replay's clock and in the wave file; the file is
# silent before the groan, sounds in each clip, and is silent again
# between ow and please stop (a held level says nothing more). With the
# key U pressed at the start nothing is said and the file is silent over
# the groan and ow (--mute: the panel says muted from the first frame);
# without an audio device one line says
# so and the replay goes on. Live, on the daemon's own pain (the tip held
# into the wall until it tears), the patient groans, then cries out.
# In both views the panel above the overview says what it has room for
# (the patient's lines first) and counts the rest in a line, its text
# ending above the overview.
# ENDOSIM_KEEP_SHOTS=DIR keeps the pictures.
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

start_xvfb || finish
FILE="$TMP/pain.endoses"
SILENT=0.001 # RMS: the wave backend writes zeros while nothing plays
SOUND=0.02   # RMS of a clip speaking (the clips' own are 0.1 to 0.4)
TOL_S=0.05   # the replay's clock: a frame's step and the records' 1 ms

# wave_conf NAME: an OpenAL Soft configuration, $TMP/NAME.conf, that
# writes what is played into the wave file $TMP/NAME.wav
wave_conf() {
	printf '[general]\ndrivers = wave\n[wave]\nfile = %s\n' \
		"$TMP/$1.wav" >"$TMP/$1.conf"
}

# hear NAME ARGS...: endoview replaying $FILE headless into the wave
# file $TMP/NAME.wav, in a small window (what it draws is the screenshots'
# below; these runs are for their sound); its output in $TMP/NAME.out
hear() {
	local name=$1
	shift
	wave_conf "$name"
	ALSOFT_CONF="$TMP/$name.conf" ALSOFT_DRIVERS=wave \
		endoview --no-vsync --max-fps 60 --size 320x240 \
		--replay "$FILE" "$@" >"$TMP/$name.out" 2>&1
}

# rms NAME START LEN: the RMS amplitude of $TMP/NAME.wav from START s,
# LEN s long
rms() {
	sox "$TMP/$1.wav" -n trim "$2" "$3" stat 2>&1 |
		sed -n 's/^RMS  *amplitude: *//p'
}

# said NAME: the clips NAME's run logged, a line each: "CLIP T SOUND_T"
said() {
	local n='\([0-9.]*\)' re
	re="^endoview: voice: \([a-z]*\), pain [0-9.]*,"
	re+=" at $n s, $n s of sound\$"
	sed -n "s/$re/\1 \2 \3/p" "$TMP/$1.out"
}

# clip_at NAME CLIP T: NAME's run said CLIP once, at T s of the replay
clip_at() {
	said "$1" | awk -v c="$2" -v t="$3" -v tol="$TOL_S" '
		$1 == c { n++; d = $2 - t; ok = d < tol && d > -tol }
		END { exit !(n == 1 && ok) }'
}

# sound_t NAME CLIP: when NAME's wave file began CLIP (s)
sound_t() {
	said "$1" | awk -v c="$2" '$1 == c { print $3 }'
}

# quiet NAME START LEN / loud NAME START LEN: the wave file there
quiet() {
	local v
	v=$(rms "$@")
	echo "# $1.wav $2+$3 s: RMS $v" >&2
	float_test "$v < $SILENT"
}
loud() {
	local v
	v=$(rms "$@")
	echo "# $1.wav $2+$3 s: RMS $v" >&2
	float_test "$v > $SOUND"
}

# --- the clips -------------------------------------------------------------
for clip in groan ow hurts stop cry; do
	wav="$BUILD/voice/$clip.wav"
	check "the build spoke $clip.wav (sox: RMS above $SOUND, under 5 s)" \
		eval "float_test \"\$(sox '$wav' -n stat 2>&1 |
			sed -n 's/^RMS  *amplitude: *//p') > $SOUND &&
			\$(soxi -D '$wav') < 5\""
done

# --- the session: the level as chosen ----------------------------------------
printf '%s\n' '0 insertion target 0.30 1.5' '60 end' >"$TMP/hold.scn"
check_status "session_synth: 14.5 s, the pain and the tear as chosen" 0 \
	"$TOOLS/session_synth" --set haptics.model=paper --pain 0:0 \
	--pain 3:0 --pain 4:6 --pain 8.5:6 --pain 9:9 --tear 12.5:2 \
	"$TOP/tests/cases/straight.case" "$TMP/hold.scn" "$FILE" 14.5

# --- the runs that take their time, at once ----------------------------------
# Each paced in real time (the wave file is written as time passes): the
# replay heard (14.5 s), muted (--mute, 2 s; by the key U, 8.3 s) and the
# daemon's live pain (15 s), each with its own wave file and output, all
# started here and checked once done: the checks read the replay's clock
# and the logged sound times, not the wall clock. The key's run first and
# alone: its window must be the only one xdotool finds. The key U,
# pressed as the window opens (before the first frame's events are read):
# muted from the replay's start. Then the live viewer, which must be up
# before the daemon's patient hurts, and the replays.
wave_conf key
(ALSOFT_CONF="$TMP/key.conf" ALSOFT_DRIVERS=wave endoview --no-vsync \
	--max-fps 60 --size 320x240 --replay "$FILE" --frames 500 \
	>"$TMP/key.out" 2>&1) &
KEYED=$!
window=$(xdotool search --sync --name '^endoview$' | head -n 1)
xdotool key --window "$window" u
# live: the daemon on the simulated rig with the patient, the scope 30 cm
# in, the tip steered up into the sigmoid's wall from 8 s (the viewer is
# up long before) and held there: the pain rises past 4 and the tip tears
# the wall. The viewer, live, groans first and cries out at the tear.
printf '%s\n' '0 insertion target 0.30 1.5' '8 wheel_ud target 0.6 1.0' \
	'60 end' >"$TMP/wall.scn"
start_daemon --set patient.enabled=yes --set haptics.model=paper \
	--set "case.directory=$TOP/tests/cases" --set case.name=straight \
	--scenario "$TMP/wall.scn" || finish
ctl enable >/dev/null
wave_conf live
(ALSOFT_CONF="$TMP/live.conf" ALSOFT_DRIVERS=wave endoview --socket "$SOCK" \
	--shm-name "$SHM" --no-vsync --max-fps 30 --size 320x240 \
	--frames 450 >"$TMP/live.out" 2>&1) & # 15 s at least
VIEWER=$!
hear voice --frames 870 &
HEARD=$!
# --mute: muted from the start, the panel says so (the silence itself is
# the key's run's: the same muting, over the groan and ow); in a window
# whose panel has room for the voice's line, the patient's last
hear mute --mute --size 640x480 --frames 120 --print-state &
MUTED=$!

# --- no audio device ---------------------------------------------------------
check_status "no audio device: the replay runs" 0 env ALSOFT_DRIVERS=none \
	"$ENDOVIEW" --no-vsync --size 640x480 --replay "$FILE" --seek 3 \
	--frames 60 --print-state
check "... one line says so" eval \
	'[ "$(grep -c "no sound (no audio device): the patient is silent" \
		"$OUT")" = 1 ]'
check "... the panel too" grep -q '^hud: no sound: no audio device$' "$OUT"

# --- the panel: pain high, then the perforation ------------------------------
# look NAME SEEK: a screenshot of the paused replay at SEEK s into
# $TMP/NAME.png; the image's top strip (a banner's) as $TOP_STRIP
look() {
	local x y w h
	endoview --no-vsync --size 1280x720 --replay "$FILE" --paused \
		--seek "$2" --frames 8 --screenshot "$TMP/$1.png" \
		--print-state >"$VIEW_OUT" 2>&1 || return 1
	read -r x y w h < <(view_rect endo)
	TOP_STRIP="rect:$x,$y,$w,$((h / 12))"
	[ -z "${ENDOSIM_KEEP_SHOTS:-}" ] ||
		cp "$TMP/$1.png" "$ENDOSIM_KEEP_SHOTS/voice-$1.png"
	case $1 in
	pain) keep_picture "$TMP/pain.png" patient-pain ;;
	torn) keep_picture "$TMP/torn.png" patient-perforation ;;
	esac
}
check "pain high (11 s): screenshot" look pain 11
check "... the panel: the level, crying out, the cause and place" \
	grep -q '^hud: pain 9\.0 crying out: looping, sigmoid$' "$VIEW_OUT"
check "... the vital signs" \
	grep -q '^hud: HR 106/min  SpO2 97 %  moderate sedation$' "$VIEW_OUT"
pain_red=$(png_value "$TMP/pain.png" "$TOP_STRIP" red)
check "... no perforation: no line, no banner (red $pain_red)" eval \
	'! grep -q PERFORAT "$VIEW_OUT" && float_test "$pain_red < 0.05"'
check "perforated (14 s): screenshot" look torn 14
check "... the panel says it" grep -q '^hud: PERFORATED: sigmoid$' \
	"$VIEW_OUT"
torn_red=$(png_value "$TMP/torn.png" "$TOP_STRIP" red)
check "... the red banner across the image's top (red $torn_red)" \
	float_test "$torn_red > 0.5"
check "... the panel has room for all it says" \
	grep -q '^panel: hidden=0 ' "$VIEW_OUT"

# both SIZE: the paused replay at 14 s in both views at SIZE: the panel
# above the overview says less than the endoscopic view's (the patient's
# first, the perforation and the pain among it); its text, footer last,
# ends above the overview, and a line counts what had no room. The
# overview's top left (clear of the colon here) has no text ($BAND_LIT)
both() {
	local x y w h
	endoview --no-vsync --size "$1" --replay "$FILE" --paused --seek 14 \
		--view both --frames 4 --print-state \
		--screenshot "$TMP/both.png" >"$VIEW_OUT" 2>&1 || return 1
	read -r x y w h < <(view_rect overview)
	END_PX=$(sed -n 's/^panel: .* end_px=\([0-9]*\)$/\1/p' "$VIEW_OUT")
	HIDDEN=$(sed -n 's/^panel: hidden=\([0-9]*\) .*/\1/p' "$VIEW_OUT")
	OVERVIEW_Y=$y
	BAND_LIT=$(png_value "$TMP/both.png" \
		"rect:$x,$y,$((w / 3)),$((h / 12))" lit)
	grep -q '^hud: PERFORATED: sigmoid$' "$VIEW_OUT" &&
		grep -q '^hud: pain ' "$VIEW_OUT"
}
for size in 1280x720 960x540; do
	check "both views at $size, perforated: the panel says it and the pain" \
		both "$size"
	check "... its text ends (at $END_PX px) above the overview (from $OVERVIEW_Y)" \
		test "${END_PX:-999999}" -le "$OVERVIEW_Y"
	check "... a line counts the $HIDDEN with no room" eval \
		'[ "${HIDDEN:-0}" -gt 0 ] &&
		 grep -q "^hud: + $HIDDEN more lines: no room here$" "$VIEW_OUT"'
	check "... no text over the overview's top left (lit $BAND_LIT)" \
		float_test "$BAND_LIT < 0.002"
done

# --- heard -------------------------------------------------------------------
check_status "the replay, heard through the wave backend" 0 wait "$HEARD"
check "... each clip once, at its time: groan 3.67 s" clip_at voice groan 3.67
check "... ow when the interval is over, 7.67 s" clip_at voice ow 7.67
check "... please stop, 11.67 s" clip_at voice stop 11.67
check "... the cry at the tear, 12.5 s" clip_at voice cry 12.5
check "... nothing else (that hurts: crossed within the interval)" \
	eval '[ "$(said voice | wc -l)" = 4 ]'
groan=$(sound_t voice groan)
ow=$(sound_t voice ow)
stop=$(sound_t voice stop)
cry=$(sound_t voice cry)
check "the wave file: silent before the groan" \
	quiet voice 0 "$(awk -v t="$groan" 'BEGIN { print t - 0.1 }')"
check "... the groan sounds" loud voice "$groan" 0.6
check "... ow sounds" loud voice "$ow" 0.5
check "... silent while the level is held, until please stop" \
	quiet voice "$(awk -v t="$ow" 'BEGIN { print t + 1.0 }')" \
	"$(awk -v a="$ow" -v b="$stop" 'BEGIN { print b - a - 1.1 }')"
check "... please stop sounds" loud voice "$stop" 0.5
check "... the cry sounds" loud voice "$cry" 0.5

# --- muted -------------------------------------------------------------------
check_status "--mute: the replay's first 2 s" 0 wait "$MUTED"
check "... the panel says so" grep -q '^hud: voice muted (U: on)$' \
	"$TMP/mute.out"
wait "$KEYED"
check "the key U: muted" grep -q '^endoview: voice muted$' "$TMP/key.out"
check "... nothing said to 8.3 s (groan and ow due)" \
	eval '[ -z "$(said key)" ]'
check "... the wave file silent" quiet key 0 8

# --- live: the daemon's own pain ----------------------------------------------
WAIT_S=40 check "live: the tip tears the sigmoid (the daemon's perforation)" \
	wait_for status_true '.patient.torn_segment == 2'
wait "$VIEWER"
check "... endoview groaned first" eval \
	'[ "$(said live | head -n 1 | cut -d" " -f1)" = groan ]'
check "... and cried out at the tear" eval '[ -n "$(sound_t live cry)" ]'
groan=$(sound_t live groan)
cry=$(sound_t live cry)
check "... the wave file: silent before the groan" \
	quiet live 0 "$(awk -v t="$groan" 'BEGIN { print t - 0.1 }')"
check "... the groan sounds" loud live "$groan" 0.3
check "... the cry sounds" loud live "$cry" 0.5

check "no run had an OpenGL error" eval \
	'! grep -h "^endoview: frames=" "$TMP"/*.out "$VIEW_OUT" |
		grep -qv " gl_errors=0 "'

finish
