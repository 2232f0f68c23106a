# viewer_lib.sh - for the tests, the demo and the benchmark that run
# endoview (source it after common.sh): a virtual screen of their own
# (Xvfb, stopped with the daemon on exit), endoview on the test's daemon,
# and what endoview prints when it exits:
#
#   endoview: frames=N ... gl_errors=N daemon=live|stale|none colon=NAME
#   endoview: layout endo=X,Y,W,H overview=X,Y,W,H panel=X,Y,W,H
#
# (rectangles in the screenshot's pixels, top-left origin; W = 0: not shown).

ENDOVIEW="$BUILD/endoview"
PNG_STATS="$TOOLS/png_stats"
VIEW_OUT="$TMP/endoview.out"
XVFB_PID=""

# start_xvfb [WxH]: an X server of our own on a display it chose itself
# (-displayfd: the first free one, taken atomically by its lock file, so
# that tests running at once never share one); exports DISPLAY.
start_xvfb() {
	local size=${1:-1920x1080} n=""
	Xvfb -displayfd 3 -screen 0 "${size}x24" -nolisten tcp -noreset \
		3>"$TMP/xvfb.display" >"$TMP/xvfb.log" 2>&1 &
	XVFB_PID=$!
	if wait_for grep -q '^[0-9]' "$TMP/xvfb.display"; then
		n=$(head -n 1 "$TMP/xvfb.display")
		export DISPLAY=":$n"
		return 0
	fi
	kill "$XVFB_PID" 2>/dev/null
	wait "$XVFB_PID" 2>/dev/null
	XVFB_PID=""
	echo "# no display for Xvfb; its log:"
	sed 's/^/#   /' "$TMP/xvfb.log"
	return 1
}

stop_xvfb() {
	if [ -n "$XVFB_PID" ]; then
		kill "$XVFB_PID" 2>/dev/null
		wait "$XVFB_PID" 2>/dev/null
		XVFB_PID=""
	fi
}
trap 'stop_xvfb; cleanup' EXIT

# endoview ARGS...: the viewer. In the sanitizer build without leak
# checks: Mesa's drivers, unloaded as the viewer exits, leave allocations
# that LeakSanitizer can neither name nor be told to ignore (the other
# checks stay on, and the viewer's modules that need no window are leak
# checked by their unit tests).
endoview() {
	ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
		"$ENDOVIEW" "$@"
}

# view ARGS...: endoview on this test's daemon (whether it runs or not),
# in the foreground; its output in $VIEW_OUT.
view() {
	endoview --socket "$SOCK" --shm-name "$SHM" --no-vsync "$@" \
		>"$VIEW_OUT" 2>&1
}

# live_view COLON ARGS...: endoview on this test's daemon in a window of
# its own, in the background (its pid in $VIEWER, its output in
# $TMP/live.out, run in $TMP, where P saves), once it has loaded COLON
# (a check), with the keyboard's focus: xdotool's keys go to it.
VIEWER=""
live_view() {
	local colon=$1 window
	shift
	(cd "$TMP" && endoview --socket "$SOCK" --shm-name "$SHM" "$@" \
		>"$TMP/live.out" 2>&1) &
	VIEWER=$!
	WAIT_S=20 check "live viewer: the colon is loaded" \
		wait_for grep -q "colon $colon" "$TMP/live.out"
	window=$(xdotool search --sync --name '^endoview$' | head -n 1)
	xdotool windowfocus --sync "$window"
}

# view_field KEY: a value of endoview's closing line ("frames", "fps", ...).
view_field() {
	grep '^endoview: frames=' "$VIEW_OUT" | tr ' ' '\n' | sed -n "s/^$1=//p"
}

# view_rect NAME: "X Y W H" of the view NAME (endo, overview, panel).
view_rect() {
	grep '^endoview: layout' "$VIEW_OUT" | tr ' ' '\n' |
		sed -n "s/^$1=//p" | tr ',' ' '
}

# view_channel: the region where the working channel's tools show in the
# endoscopic view of $VIEW_OUT's layout: a disc at 5 o'clock (the
# channel's default clock), 0.62 of the way out, a twelfth of the view's
# width across.
view_channel() {
	local x y w h
	read -r x y w h < <(view_rect endo)
	awk -v cx=$((x + w / 2)) -v cy=$((y + h / 2)) -v r=$((w / 2)) 'BEGIN {
		a = 150 * atan2(0, -1) / 180
		printf "disc:%d,%d,%d\n", cx + 0.62 * r * sin(a),
			cy - 0.62 * r * cos(a), r / 12 }'
}

# png_changed FILE OTHER REGION: the share of REGION's pixels that differ
# between two pictures (png_stats --diff).
png_changed() {
	"$PNG_STATS" "$1" --diff "$2" "$3" | sed -n 's/.* changed=\([^ ]*\).*/\1/p'
}

# png_value FILE REGION KEY: one statistic of png_stats.
png_value() {
	"$PNG_STATS" "$1" "$2" | sed -n "s/.* $3=\([^ ]*\).*/\1/p"
}

# float_test EXPR: awk's verdict on a comparison of numbers.
float_test() {
	awk "BEGIN { exit !($1) }"
}

# hold_scope READY ARGS...: the daemon (ARGS its own) on the simulated
# rig, enabled, pushing the scope 60 cm in and holding it there, once
# the status makes READY true (the benchmarks' fixed view).
HOLD_AT='.axes.insertion.position > 0.59'
hold_scope() {
	local ready=$1
	shift
	printf '%s\n' '0 insertion target 0.60 2' >"$TMP/hold.scn"
	start_daemon "$@" --scenario "$TMP/hold.scn" || return 1
	ctl enable >/dev/null
	wait_for status_true "$ready"
}
