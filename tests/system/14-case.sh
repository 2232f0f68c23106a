#!/bin/bash
# The colon and the endoscope: the daemon starts with the configured case,
# lists and loads cases (only while IDLE), serves the scene (endoctl scene
# export writes an OBJ that imports again), and the scope's tip follows the
# simulated hand into the colon, in the status and in shared memory.
. "$(dirname "$0")/../common.sh"

start_daemon || finish
check "starts with the normal case" test "$(status_field .case)" = normal
check_status "case list" 0 ctl case list
check "lists the four shipped cases, normal loaded" sh -c "grep -q '^\* normal ' '$OUT' &&
	grep -q '^  polyps ' '$OUT' && grep -q '^  redundant-sigmoid ' '$OUT' &&
	grep -q '^  tight-flexures ' '$OUT'"
check_status "case list in JSON" 0 ctl --json case list
check "JSON: loaded flag" test "$(jq -r '.cases[] | select(.loaded) | .name' "$OUT")" = normal

# loading, refusals
id1=$(status_field .scope.scene_id)
check_status "case load polyps" 0 ctl case load polyps
check "status shows the new case" test "$(status_field .case)" = polyps
check "the scene changed" test "$(status_field .scope.scene_id)" -gt "$id1"
check_status "an unknown case is refused" 1 ctl case load no-such-case
check "says which file" grep -q "no-such-case.case: cannot open" "$OUT"
check_status "a name with a path is refused" 1 ctl case load ../cases/normal
check_status "case load on the read-only socket is refused" 1 \
	"$ENDOCTL" --socket "$SOCK/status.sock" case load normal
check "as read-only" grep -q "read-only" "$OUT"
ctl enable >/dev/null
check_status "case load while ENABLED is refused" 1 ctl case load normal
check "saying why" grep -q "only while IDLE" "$OUT"
check "the case stays" test "$(status_field .case)" = polyps
ctl disable >/dev/null

# a broken case file: refused with its line, the daemon keeps its case
bad="$TMP/cases"
mkdir -p "$bad"
cp "$CASES"/*.case "$bad/"
printf '[case]\nname = broken\n[segment anal_canal]\nlength_m = -1\n' >"$bad/broken.case"
stop_daemon
start_daemon --set "case.directory=$bad" || finish
check_status "case list leaves the broken file out" 0 ctl case list
check "and says why, with its line" grep -qF \
	"broken.case:4: [segment anal_canal] length_m" "$OUT"
check_status "loading it is refused" 1 ctl case load broken
check "with file, line and key" grep -qF \
	"broken.case:4: [segment anal_canal] length_m: -1 is out of range" "$OUT"
check "the daemon keeps its case" test "$(status_field .case)" = normal

# the scene: chunked GetScene, export as OBJ, import again
check_status "scene info" 0 ctl --json scene info
tris=$(jq -r .triangles "$OUT")
verts=$(jq -r .vertices "$OUT")
check "a few hundred thousand triangles" test "$tris" -gt 200000
check_status "scene export" 0 ctl scene export "$TMP/colon.obj"
check "the OBJ has the mesh and the centreline polyline" sh -c \
	"grep -q '^o colon' '$TMP/colon.obj' && grep -q '^o centreline' '$TMP/colon.obj' && grep -q '^l ' '$TMP/colon.obj'"
check_status "the export imports" 0 "$TOOLS/obj_import" "$TMP/colon.obj"
check "with every triangle" grep -qx "triangles=$tris" "$OUT"
check "and every vertex" grep -qx "vertices=$verts" "$OUT"
check "named after the file" grep -qx "name=colon" "$OUT"
check_status "scene export on the read-only socket" 0 \
	"$ENDOCTL" --socket "$SOCK/status.sock" scene export "$TMP/ro.obj"

# the tip follows the simulated hand into the colon
check "tip at the anal verge" status_true '.scope.depth_m < 0.01'
ctl enable >/dev/null
ctl hand 20 0 0 0 --hold-ms 1500 >/dev/null
check "the tip advances with the insertion" wait_for status_true \
	'.scope.depth_m > 0.2 and .scope.tip_s_m > 0.1'
check "inserted length is the insertion axis" status_true \
	'(.scope.depth_m - .axes.insertion.position) | fabs < 0.01'
check "the tip is inside the body, above the anal verge" status_true \
	'.scope.tip[2] > 0.05'
"$TOOLS/shm_probe" "$SHM" --once >"$TMP/shm.txt"
# (the tube's points are floats, the tip doubles: within 10 um)
check "shared memory: the tube ends at the tip" awk -F'[=,]' \
	'/^scope.tip=/ { for (i = 2; i <= 4; i++) tip[i] = $i; t = 1 }
	 /^scope.tube_last=/ { for (i = 2; i <= 4; i++) last[i] = $i; l = 1 }
	 END { d = 0; for (i = 2; i <= 4; i++) d += (tip[i] - last[i]) ^ 2
	       exit !(t && l && d < 1e-10) }' "$TMP/shm.txt"
# (the rod model's tube: where the rod passes the anal verge, within 1 cm:
# pushed, the tube lags the carriage by its coupling's stretch, a few mm)
check "shared memory: and starts at the anal verge" awk -F'[=,]' \
	'/^scope.tube_first=/ { found = 1; bad = $2 * $2 + $3 * $3 + $4 * $4 > 1e-4 }
	 END { exit !found || bad }' "$TMP/shm.txt"
check "shared memory: two mobile segments" grep -qx "scope.spans=2" "$TMP/shm.txt"
ctl hand 0 0 3 0 --hold-ms 1000 >/dev/null
check "the up/down wheel bends the tip" wait_for status_true '.scope.bend_rad[0] > 0.2'
ctl disable >/dev/null
finish
