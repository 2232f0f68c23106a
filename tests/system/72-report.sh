#!/bin/bash
# The instructor's report (issue 8) rendered by a browser: a session file
# of a scripted colonoscopy on the polyps case (tests/tools/session_script:
# insertion with a sigmoid loop and excessive force, a fault, the cecum, a
# withdrawal of ~6.5 min), its report (tests/tools/session_report, the
# code of `endoctl session report`), rendered in headless Chromium: the
# screenshot is not blank (dark text, the red threshold lines), the
# rendered DOM holds the four plots with their episode bands, the
# unseen-mucosa map (its five polyps found) and the pain along the colon
# (no patient here: the force and the loop by segment, the sigmoid's
# loop), the trainee's name escaped, no script. The screenshot stays in
# $REPORT_SHOT (default $TMP/report.png) to be looked at.
. "$(dirname "$0")/../common.sh"

. "$(dirname "$0")/chrome_lib.sh"

need_chromium
SHOT=${REPORT_SHOT:-$TMP/report.png}
TRAINEE="Dr. <b>O'Brien</b> & Co"

check "session_script writes a session file" \
	"$TOOLS/session_script" "$CASES/polyps.case" "$TMP/s.endoses" "$TRAINEE"
check "session_report writes DIR/index.html" \
	sh -c '"$1" "$2" "$3" >"$4" && test -s "$3/index.html"' _ \
	"$TOOLS/session_report" "$TMP/s.endoses" "$TMP/report" "$TMP/metrics"
check "the recomputed metrics reach the cecum" \
	grep -q '^cecum_s=[0-9]' "$TMP/metrics"
check "the recomputed metrics find all 5 polyps" \
	grep -q '^polyps_seen=5$' "$TMP/metrics"

check_screenshot "$TMP/report/index.html" "$SHOT" 1280 2000 \
	"the plots' red marks"
keep_picture "$SHOT" session-report

chrome --dump-dom "file://$TMP/report/index.html" >"$TMP/dom.html"
check "the rendered DOM has the four plots, the mucosa map, along the colon" \
	test "$(grep -o '<svg class="plot"' "$TMP/dom.html" | wc -l)" -eq 6
check "... the map marks the case's five polyps, found" \
	test "$(grep -o '<title>polyp [0-9]: found</title>' "$TMP/dom.html" |
		wc -l)" -eq 5
for id in plot-force plot-torque plot-tip plot-bow; do
	check "the DOM has $id with a drawn series" \
		sh -c 'sed -n "/<figure id=\"$1\">/,/<\/figure>/p" "$2" |
			grep -q "<path class=\"series\" [^>]*d=\"M[0-9]"' \
		_ "$id" "$TMP/dom.html"
done
check "the DOM has the pain along the colon with its force bars" \
	sh -c 'sed -n "/<figure id=\"pain-along\">/,/<\/figure>/p" "$1" |
		grep -q "<title>sigmoid: peak insertion force (N) [0-9]"' \
	_ "$TMP/dom.html"
check "... and its table, the sigmoid looped (the scripted loop)" \
	sh -c 'grep -q "<table class=\"episodes\" id=\"pain-along-table\">" "$1" &&
		grep -qE "<th>sigmoid</th>(<td>[^<]*</td>){3}<td>[1-9][0-9.]* s</td>" "$1"' \
	_ "$TMP/dom.html"
check "the DOM has force episode bands" \
	grep -q '<rect class="band force"' "$TMP/dom.html"
check "the DOM has loop episode bands" \
	grep -q '<rect class="band loop"' "$TMP/dom.html"
check "the DOM marks the fault" grep -q 'class="event fault"' "$TMP/dom.html"
check "the DOM has the withdrawal marked good (>= 6 min)" \
	grep -q '<tr class="good"><th>Withdrawal time' "$TMP/dom.html"
check "the trainee's name is escaped" \
	grep -qF 'Dr. &lt;b&gt;O'"'"'Brien&lt;/b&gt; &amp; Co' "$TMP/dom.html"
check "the page has no script and no external asset" \
	sh -c "! grep -qiE '<script|src=|href=\"http' '$TMP/report/index.html'"
finish
