#!/bin/bash
# viewer.sh - endoview's frame times on this machine (make bench runs it;
# figures, not verdicts). On a virtual screen (Xvfb; Mesa's llvmpipe
# unless a GPU is there), with vsync off, the daemon on the simulated rig
# holding the scope 60 cm in the default case: for each window size and
# each mesh (the default resolution, and ~2 million triangles), the frame
# rate and the frame time (p50, p99) of the endoscopic view (endo: its
# image drawn at the scale endoview takes on this renderer and scaled up,
# viewer/imagescale.h; endo-full: at its size) and of the overview next
# to an empty frame (clear and swap only) measured in the
# same run, and the age of the state each frame shows (the swap's time less
# the state's publish_ns, p50, p99). Then the patient's (issue 22): the
# default case with a little fluid in the rectum, the sigmoid and the
# descending colon, the tip under the sigmoid's surface and pressed into
# its wall, so that every pixel of the endoscopic view goes through the
# liquid and the lens is both smeared and murky (endo.h, lensfx.h).
#
#   VIEWER_FRAMES   frames per run (default 150)
set -u
. "$(dirname "$0")/../common.sh"
. "$TOP/tests/viewer_lib.sh"

FRAMES=${VIEWER_FRAMES:-150}
SIZES="1280x720 640x480"

# measure VIEW SIZE: one run; prints its row.
measure() {
	local view=$1 size=$2 fps p50 p99 a50 a99 tris ratio args
	args=(--view "$view")
	[ "$view" = endo-full ] && args=(--view endo --image-scale 1)
	if ! view "${args[@]}" --size "$size" --frames "$FRAMES"; then
		echo "  $view $size: endoview failed:"
		sed 's/^/    /' "$VIEW_OUT"
		return 1
	fi
	fps=$(view_field fps)
	p50=$(view_field frame_ms_p50)
	p99=$(view_field frame_ms_p99)
	a50=$(view_field age_ms_p50)
	a99=$(view_field age_ms_p99)
	tris=$(view_field triangles)
	[ "$view" = empty ] && EMPTY=$p50
	ratio=$(awk -v a="$p50" -v b="$EMPTY" \
		'BEGIN { printf "%.2f", (b > 0 ? a / b : 0) }')
	printf '  %-9s %-9s %7.1f %8.2f %8.2f %7s %9.2f %8.2f %9d\n' \
		"$view" "$size" "$fps" "$p50" "$p99" "${ratio}x" "$a50" "$a99" \
		"$tris"
}

# mesh NAME ARGS...: the daemon with the colon at that resolution, every
# view ($VIEWS) at every size, once the status makes $READY true.
VIEWS="empty endo endo-full overview"
READY=$HOLD_AT
mesh() {
	local name=$1
	shift
	hold_scope "$READY" "$@" || return 1
	echo "colon: $name, $(ctl --json scene info 2>/dev/null |
		jq -r '"\(.triangles) triangles"' 2>/dev/null)"
	printf '  %-9s %-9s %7s %8s %8s %7s %9s %8s %9s\n' view size fps \
		"p50 ms" "p99 ms" "/empty" "age p50" "age p99" triangles
	for size in $SIZES; do
		for view in $VIEWS; do
			measure "$view" "$size"
		done
	done
	# where the endoscopic frame's time goes, each pass finished
	view --view endo --size 1280x720 --frames "$FRAMES" --pass-times &&
		echo "  endo 1280x720 by pass, p50/p99 ms (each finished:" \
			"the frame is slower so):" &&
		sed -n 's/^endoview: passes_ms /    /p' "$VIEW_OUT"
	stop_daemon
}

echo "=== endoview: frame times, ${FRAMES} frames a run, vsync off ==="
start_xvfb 1920x1080 || exit 1
view --view empty --size 320x240 --frames 1 >/dev/null 2>&1
echo "renderer: $(sed -n 's/^endoview: OpenGL //p' "$VIEW_OUT"), $(nproc) CPUs"
view --view endo --size 320x240 --frames 1 >/dev/null 2>&1
echo "endo: the image at $(sed -n 's/^endoview: the endoscopic image drawn at \([0-9]*\) %.*/\1 %/p' \
	"$VIEW_OUT" | grep . || echo "100 %") of its size, scaled up;" \
	"endo-full: at its size (--image-scale 1)"
mesh "default case, default resolution"
mesh "default case at ~2 million triangles" \
	--set case.ring_vertices=672 --set case.step_m=0.001
mkdir -p "$TMP/cases"
awk '{ print } /^\[segment (rectum|sigmoid|descending)\]/ {
	print "fluid_m3 = 20e-6" }' "$CASES/normal.case" |
	sed 's/^name = normal$/name = pool/' >"$TMP/cases/pool.case"
VIEWS="empty endo endo-full"
READY="$READY and .patient.tip_in_fluid and .patient.lens_smear > 0.5 and
       .patient.lens_murk > 0.5"
mesh "default case, default resolution, the patient: the tip in a pool, \
the lens smeared and murky" --set patient.enabled=yes \
	--set "case.directory=$TMP/cases" --set case.name=pool
echo "(frame: swap to swap; age: the state's publish_ns to the swap that"
echo " shows it; /empty: the frame's p50 over the empty frame's at that size)"
