# chrome_lib.sh - headless Chromium for the system tests that render an
# instructor's page (72-report, 76-trainee); sourced after common.sh. The
# browser's profile and caches stay in the test's directory.

CHROMIUM=$(command -v chromium || command -v chromium-browser || true)

# need_chromium: without a Chromium, a failed check and the test's end.
need_chromium() {
	if [ -z "$CHROMIUM" ]; then
		fail "chromium is installed (Debian package chromium; make deps-test)"
		finish
	fi
}

# chrome ARGS...: headless Chromium, its complaints in $TMP/chromium.log.
chrome() {
	HOME="$TMP" "$CHROMIUM" --headless --no-sandbox --disable-gpu \
		--user-data-dir="$TMP/chromium" --hide-scrollbars "$@" \
		2>>"$TMP/chromium.log"
}

# check_screenshot PAGE SHOT WIDTH HEIGHT RED_WHAT: the page at PAGE (a
# file) rendered into SHOT (a PNG) at WIDTH x HEIGHT px is not blank: it
# has dark text, and red pixels (RED_WHAT says what makes them).
check_screenshot() {
	local page=$1 shot=$2 w=$3 h=$4 what=$5 lit red
	check "headless Chromium renders a screenshot" \
		chrome --screenshot="$shot" --window-size="$w,$h" "file://$page"
	[ -s "$shot" ] || return
	read -r _ _ _ lit red _ < <("$TOOLS/png_stats" "$shot" rect:0,0,$w,$h)
	lit=${lit#lit=}
	red=${red#red=}
	check "the screenshot has text (dark pixels: lit $lit < 0.999)" \
		awk -v v="$lit" 'BEGIN { exit !(v < 0.999) }'
	check "the screenshot has $what (red $red > 0.00005)" \
		awk -v v="$red" 'BEGIN { exit !(v > 0.00005) }'
}
