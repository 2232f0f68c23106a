#!/bin/bash
# systemd integration: make install lays out binaries, configuration and the
# unit files; the unit scores an exposure of 1.0 or lower; the daemon tells
# the notify socket READY=1 and pings the watchdog while the loop runs.
. "$(dirname "$0")/../common.sh"

root="$TMP/root"
check "make install into a staging root" make -C "$TOP" --no-print-directory \
	BUILD="$BUILD" PREFIX="$root/usr" SYSCONFDIR="$root/etc" install
check "daemon in sbin" test -x "$root/usr/sbin/endosimd"
check "endoctl in bin" test -x "$root/usr/bin/endoctl"
check "configuration in etc/endosim" test -f "$root/etc/endosim/endosimd.conf"
check "the cases installed" test -f "$root/usr/share/endosim/cases/normal.case"
check "the installed configuration validates" \
	"$root/usr/sbin/endosimd" --check-config --config "$root/etc/endosim/endosimd.conf" \
	--set "case.directory=$root/usr/share/endosim/cases"
unit="$root/usr/lib/systemd/system/endosimd.service"
check "unit installed" test -f "$unit"
check "unit paths substituted" grep -q "^ExecStart=$root/usr/sbin/endosimd --config $root/etc/endosim/endosimd.conf$" "$unit"
check "sysusers.d and tmpfiles.d installed" test -f "$root/usr/lib/sysusers.d/endosim.conf" -a -f "$root/usr/lib/tmpfiles.d/endosim.conf"
check "udev rules installed where udev reads them" test -f "$root/etc/udev/rules.d/70-endosim.rules"
check "a second install keeps an edited configuration" sh -c "echo '; edited' >> '$root/etc/endosim/endosimd.conf' && make -C '$TOP' --no-print-directory BUILD='$BUILD' PREFIX='$root/usr' SYSCONFDIR='$root/etc' install >/dev/null && grep -q '; edited' '$root/etc/endosim/endosimd.conf'"
if command -v systemd-analyze >/dev/null; then
	check "systemd-analyze security: exposure 1.0 or lower" \
		systemd-analyze security --offline=true --threshold=10 "$unit"
	grep "Overall exposure" "$OUT" "$TMP/check.out" 2>/dev/null | sed 's/^.*:/# /'
else
	fail "systemd-analyze is missing (Debian package systemd)"
fi

# sd_notify: READY=1 once up, WATCHDOG=1 while the loop's heartbeat advances
notify="$TMP/notify.sock"
socat -u "UNIX-RECV:$notify" - >"$TMP/notify.log" 2>/dev/null &
listener=$!
wait_for test -S "$notify"
NOTIFY_SOCKET="$notify" WATCHDOG_USEC=200000 start_daemon || finish
sleep 0.6
check "READY=1 sent" grep -q "READY=1" "$TMP/notify.log"
check "watchdog pinged while the loop runs" test "$(grep -o WATCHDOG=1 "$TMP/notify.log" | wc -l)" -ge 2
stop_daemon
check "STOPPING=1 on SIGTERM" grep -q "STOPPING=1" "$TMP/notify.log"
kill "$listener" 2>/dev/null
finish
