#!/bin/bash
# endoview --replay: a session file played without the daemon, on a
# virtual screen of its own (Xvfb, Mesa's llvmpipe). The file is written
# by session_synth (the paper model's demo course on the normal case, by
# the force
# loop's own parts off line), which also prints the truth at a few times:
# the record's fields as the file holds them and the tube the daemon would
# have published. At those times the replay shows exactly the record's
# fields, and its tube, rebuilt by the kinematics from the record, lies on
# the published one; a playing replay runs its clock by a fixed step per
# frame in a headless run; the endoscopic image shows the lumen and the
# HUD its replay lines and timeline; a file cut short replays up to its
# last complete record; a file that is not a session and a missing one are
# refused with a reason; no run has an OpenGL error. Then a recording by
# the daemon itself (endoctl session start/stop) replays to the records
# that `endoctl session export --csv` lists (cycle, depth, tip, limited
# forces, contact, bows), and its rebuilt tube ends at the recorded tip
# (the daemon's own tube is not recorded: that comparison is the
# synthetic session's).
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

start_xvfb || finish
FILE="$TMP/demo.endoses"
TRUTH="$TMP/truth.txt"
TIMES=(3 12.5 24)
TUBE_TOL_M=0.00001 # a float's rounding of the recorded axes, through the arc

# replay ARGS...: endoview on a session file, headless; output in $VIEW_OUT.
replay() {
	endoview --no-vsync --size 640x480 --replay "$@" >"$VIEW_OUT" 2>&1
}

# shown KEY: a field of the state the last replay's last frame showed.
shown() {
	sed -n "s/^state: $1=//p" "$VIEW_OUT"
}

# fields FILE PREFIX: the state lines after PREFIX, less the tube.
fields() {
	sed -n "s/^$2//p" "$1" | grep -v '^tube='
}

# A finite number as %g prints it (awk's own test lets a NaN through: it
# compares false with everything, so it drops out of a maximum and never
# exceeds a bound).
NUMBER='^-?([0-9]+[.]?[0-9]*|[.][0-9]+)(e[-+]?[0-9]+)?$'

# point_gap A B N: the largest coordinate difference (m) between the
# points "x,y,z" (a line each) of files A and B; 1 unless both hold N
# points of finite numbers.
point_gap() {
	paste -d, "$1" "$2" | awk -F, -v n="$3" -v num="$NUMBER" '
		{ for (i = 1; i <= 6; i++) { bad = bad || $i !~ num }
		  for (i = 1; i <= 3; i++) { d = $i - $(i + 3);
			d = d < 0 ? -d : d; m = d > m ? d : m } }
		END { printf "%.3g\n", NR == n && !bad ? m : 1 }'
}

# tube_gap T [TRUTH]: the largest coordinate difference (m) between the
# tube shown and the truth's at T.
tube_gap() {
	point_gap <(shown tube | tr ';' '\n') \
		<(sed -n "s/^$1: tube=//p" "${2:-$TRUTH}" | tr ';' '\n') 128
}

ran_clean() {
	[ "$(view_field gl_errors)" = 0 ] &&
		[ "$(view_field daemon)" = replay ] &&
		[ "$(view_field colon)" = normal ]
}

# --- the daemon's recording, started ahead ---------------------------------
# It records 8.5 s of the demo's course (checked last, below) while the
# synthetic session's checks run, instead of the test waiting for it at
# the end: the simulated rig's clock counts the loop's cycles, so the
# course and its records are the same whenever the test looks.
mkdir -p "$TMP/sessions"
start_daemon --set "session.directory=$TMP/sessions" \
	--set haptics.model=paper \
	--scenario "$TOP/config/scenarios/demo-paper.scn" || finish
ctl enable >/dev/null
check "the daemon records a session" ctl session start --trainee Ada

# --- a synthetic session ---------------------------------------------------
at=()
for t in "${TIMES[@]}"; do
	at+=(--at "$t")
done
check_status "session_synth: 25 s of the paper demo on the normal case" 0 \
	"$TOOLS/session_synth" --set haptics.model=paper "${at[@]}" \
	"$CASES/normal.case" "$TOP/config/scenarios/demo-paper.scn" "$FILE" 25
cp "$OUT" "$TRUTH"

# --- (a) the states shown are the records --------------------------------
for t in "${TIMES[@]}"; do
	check_status "replay paused at $t s: draws and exits 0" 0 \
		replay "$FILE" --seek "$t" --paused --frames 6 \
		--screenshot "$TMP/at-$t.png" --print-state
	check "at $t s: the colon from the file's case, no OpenGL error" \
		ran_clean
	check "at $t s: every field shown is the record's (cycle $(shown cycle))" \
		diff <(fields "$VIEW_OUT" 'state: ') <(fields "$TRUTH" "$t: ")
	gap=$(tube_gap "$t")
	echo "# at $t s: the tube by the kinematics within $gap m of the published"
	check "at $t s: the rebuilt tube lies on the daemon's published tube" \
		float_test "$gap < $TUBE_TOL_M"
done
check "the course moves: deeper at 24 s than at 3 s" float_test \
	"$(fields "$TRUTH" '24: ' | sed -n 's/^depth_m=//p') > \
	 $(fields "$TRUTH" '3: ' | sed -n 's/^depth_m=//p') + 0.2"

# playing: 30 frames of 1/60 s at x2 from 10 s reach 11 s, cycle 11000
# (the first record is cycle 0, as the daemon's first cycle)
check_status "replay playing at x2 from 10 s, 31 frames" 0 \
	replay "$FILE" --seek 10 --speed 2 --frames 31 --print-state
check "playing: the clock ran 1 s in 30 headless frames (cycle 11000)" \
	eval '[ "$(shown cycle)" = 11000 ] && ran_clean'

# --- (b) what it looks like ---------------------------------------------
SHOT="$TMP/at-12.5.png"
keep_picture "$SHOT" endoview-replay
replay "$FILE" --seek 12.5 --paused --frames 2
read -r X Y W H < <(view_rect endo)
# the lumen somewhere in the image: its darkest sixteenth against its
# brightest
read -r dark bright < <(for i in 0 1 2 3; do for j in 0 1 2 3; do
	png_value "$SHOT" "rect:$((X + i * W / 4)),$((Y + j * H / 4)),$((W / 4)),$((H / 4))" mean
done; done | sort -g | sed -n '1p;$p' | tr '\n' ' ')
echo "# at 12.5 s: mean luma $dark in the image's darkest sixteenth, $bright in its brightest"
check "the endoscopic image: a dark lumen amid lit walls" \
	float_test "$dark < 0.4 * $bright && $bright > 60"
read -r TX TY TW TH < <(view_rect timeline)
read -r PX PY PW PH < <(view_rect panel)
lines="rect:$TX,$((PY + TH)),$TW,$((TY - PY - TH))"
check "the HUD: the replay's lines (amber REPLAY) above the timeline" \
	float_test "$(png_value "$SHOT" "$lines" amber) > 0.005 && \
		    $(png_value "$SHOT" "$lines" lit) > 0.03"
left=$(png_value "$SHOT" "rect:$TX,$TY,$((TW * 45 / 100)),$TH" lit)
right=$(png_value "$SHOT" "rect:$((TX + TW * 55 / 100)),$TY,$((TW * 45 / 100)),$TH" lit)
echo "# the timeline at 12.5 of 25 s: lit $left before the middle, $right after"
check "the timeline: filled up to the middle, at 12.5 s of 25" \
	float_test "$left > 0.3 && $right < 0.2"
check_status "overview and both views: draw and exit 0" 0 \
	replay "$FILE" --seek 12.5 --paused --view both --frames 8 \
	--size 1280x720 --screenshot "$TMP/both.png"
keep_picture "$TMP/both.png" endoview
check "both views: no OpenGL error" ran_clean
read -r X Y W H < <(view_rect overview)
check "both views: the scope's green in the overview" float_test \
	"$(png_value "$TMP/both.png" "rect:$X,$Y,$W,$H" scope) > 0.001"

# --- (c) a file cut short ------------------------------------------------
size=$(stat -c %s "$FILE")
cp "$FILE" "$TMP/cut.endoses"
# the END frame and part of the last record (500 bytes a frame) go
truncate -s $((size - 200)) "$TMP/cut.endoses"
check_status "a file cut mid-record replays" 0 \
	replay "$TMP/cut.endoses" --seek 1000 --paused --frames 3 --print-state
records=$(sed -n 's/.* records=\([0-9]*\).*/\1/p' "$VIEW_OUT")
check "cut: up to its last complete record, cycle 24999 (of 0-25000)" \
	eval '[ "$(shown cycle)" = 24999 ] && [ "$records" = 25000 ] && ran_clean'
check "cut: the bytes after it are said to be ignored" \
	grep -q 'replay t=.* bytes_ignored=[1-9]' "$VIEW_OUT"

# --- (d) not a session -----------------------------------------------------
check_status "a file that is not a session: refused, exit 1" 1 \
	replay "$TOP/README.md" --frames 2
check "not a session: says so" grep -q 'README.md: not a session file' \
	"$VIEW_OUT"
check_status "a missing file: refused, exit 1" 1 \
	replay "$TMP/none.endoses" --frames 2
check "missing: says so" grep -q 'none.endoses: No such file' "$VIEW_OUT"
head -c 8 "$FILE" >"$TMP/magic.endoses"
check_status "the magic alone: refused, exit 1" 1 \
	replay "$TMP/magic.endoses" --frames 2
check_status "a bad --speed: usage, exit 2" 2 \
	replay "$FILE" --speed fast

# --- (e) the rod model ----------------------------------------------------
# A session of the rod model (session_synth --set haptics.model=rod): the
# state shown is the record at its time with the SHAPE at or before it
# (the tube's points and roll, the colon's nodes, each span's loop size
# from them), exactly as the file holds them; at a SHAPE's cycle (every
# 33rd: 3.003 s and 9.999 s) the tube drawn from the rod's points lies on
# the one the daemon published, within the cycle's motion: the loop
# publishes the tube of its pose, made before the rod's step, and the
# rod's points after it (30 um at the course's 3 cm/s).
ROD="$TMP/rod.endoses"
ROD_TUBE_TOL_M=0.0001 # a cycle at 10 cm/s
ROD_TRUTH="$TMP/rod-truth.txt"
check_status "session_synth: 10 s of the demo in the rod model" 0 \
	"$TOOLS/session_synth" --set haptics.model=rod --at 3.003 --at 3.02 \
	--at 9.999 "$CASES/normal.case" "$TOP/config/scenarios/demo.scn" \
	"$ROD" 10
cp "$OUT" "$ROD_TRUTH"
for t in 3.003 3.02 9.999; do
	check_status "rod: replay paused at $t s" 0 \
		replay "$ROD" --seek "$t" --paused --frames 3 --print-state
	shown rod_point >"$TMP/rod-$t.txt"
	check "rod at $t s: every field shown is the file's, the rod's shape too ($(tr ';' '\n' <"$TMP/rod-$t.txt" | wc -l) points)" \
		eval 'ran_clean && [ "$(shown model)" = 1 ] &&
		      diff <(fields "$VIEW_OUT" "state: ") <(fields "$ROD_TRUTH" "$t: ")'
	if [ "$t" != 3.02 ]; then
		gap=$(tube_gap "$t" "$ROD_TRUTH")
		echo "# rod at $t s: the tube from the rod's points within $gap m of the published"
		check "rod at $t s: the tube drawn from the rod's points lies on the daemon's" \
			float_test "$gap < $ROD_TUBE_TOL_M"
	fi
done
check "rod at 3.02 s: the shape of 3.003 s (cycle 3003, the SHAPE before)" \
	cmp "$TMP/rod-3.003.txt" "$TMP/rod-3.02.txt"
check "rod: the tube moves (3.003 s and 9.999 s differ)" \
	eval '! cmp -s "$TMP/rod-3.003.txt" "$TMP/rod-9.999.txt"'

# --- a recording by the daemon ------------------------------------------
# csv_state CYCLE: from `endoctl session export --csv`, the fields of the
# record of CYCLE named as --print-state names them.
csv_state() {
	awk -F, -v cycle="$1" '
		NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
		$col["cycle"] == cycle {
			v = "cycle=" $col["cycle"] "\ndepth_m=" $col["depth_m"]
			v = v "\ntip_s_m=" $col["tip_s_m"] "\ntip=" $col["tip_x_m"]
			v = v "," $col["tip_y_m"] "," $col["tip_z_m"] "\nlimited="
			v = v $col["insertion_limited_n"] "," $col["roll_limited_nm"]
			v = v "," $col["wheel_ud_limited_nm"] ","
			v = v $col["wheel_lr_limited_nm"] "\ncontact=" $col["contact"]
			v = v "\nbow_m=" $col["bow0_m"] "," $col["bow1_m"] ","
			v = v $col["bow2_m"] "," $col["bow3_m"]
			print v }' "$TMP/export.csv"
}

# same_numbers A B: the key=value lines of A and B hold the same keys and
# finite numbers within the CSV's 7 digits.
same_numbers() {
	paste -d= "$1" "$2" | awk -F= -v num="$NUMBER" '
		{ if ($1 != $3) bad = 1; n = split($2, a, ","); split($4, b, ",")
		  for (i = 1; i <= n; i++) { d = a[i] - b[i]; d = d < 0 ? -d : d
			m = a[i] < 0 ? -a[i] : a[i]
			if (a[i] !~ num || b[i] !~ num || d > 1e-6 * m + 1e-9)
				bad = 1 } }
		END { exit bad || NR == 0 }'
}

WAIT_S=15
check "8 s of the demo's course recorded" \
	wait_for status_true '.scenario_time_s > 8.5'
WAIT_S=5
check "the session stops" ctl session stop
REC=$(ls "$TMP"/sessions/*.endoses 2>/dev/null | head -n 1)
ctl session export 1 --csv >"$TMP/export.csv"
t0=$(awk -F, 'NR == 2 { print $1 }' "$TMP/export.csv")
for t in 2 7.5; do
	# the record at t s (the last at or before it) and where the replay
	# seeks: midway between it and the next record. The CSV's times are to
	# the microsecond and the records' stamps a period apart give or take
	# the loop's wake-up jitter, so a stamp can lie within a microsecond of
	# t itself (a third of them did in some runs), where the CSV cannot
	# tell which side the replay's nanoseconds put it; half a period from
	# either record it can.
	read -r want seek < <(awk -F, -v t="$t" -v t0="$t0" '
		NR > 1 && $1 <= t0 + t + 5e-7 { c = $2; at = $1; next }
		NR > 1 && c != "" { printf "%s %.7f\n", c, (at + $1) / 2 - t0; exit }' \
		"$TMP/export.csv")
	check_status "the daemon's recording replayed at $t s (sought at ${seek:-?} s)" 0 \
		replay "${REC:-none}" --seek "${seek:-$t}" --paused --frames 4 \
		--screenshot "$TMP/rec-$t.png" --print-state
	check "at $t s: the record at that time (cycle $want), no OpenGL error" \
		eval '[ "$(shown cycle)" = "$want" ] && ran_clean'
	csv_state "$want" >"$TMP/csv.txt"
	for k in cycle depth_m tip_s_m tip limited contact bow_m; do
		echo "$k=$(shown "$k")"
	done >"$TMP/shown.txt"
	check "at $t s: depth, tip, limited forces, contact, bows as exported" \
		same_numbers "$TMP/shown.txt" "$TMP/csv.txt"
	gap=$(point_gap <(shown tube | tr ';' '\n' | tail -n 1) \
		<(shown tip) 1)
	check "at $t s: the rebuilt tube ends at the recorded tip ($gap m)" \
		float_test "$gap < $TUBE_TOL_M"
done
check "the recording's trainee and case in the HUD's replay line" \
	float_test "$(png_value "$TMP/rec-7.5.png" "$lines" amber) > 0.005"

finish
