# pg_lib.sh - a PostgreSQL cluster of a test's own, for the tests of a
# centre's records (80-centre, 83-centre-roles): initdb and pg_ctl in the
# test's temporary directory, as an unprivileged user (nobody when we are
# root), on a private Unix socket, passwords required; the superuser
# admin, a role rig (password rig-secret, in a libpq password file
# $PGPASSFILE) owning the database endosim. The test is skipped (never
# passed) where Debian's postgresql is not installed. Sourced after
# common.sh; pg_make checks that the cluster came up.

PGBIN=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1)
for p in initdb pg_ctl postgres; do
	if [ ! -x "$PGBIN/$p" ]; then
		skip "a centre's PostgreSQL: no PostgreSQL server here \
(${PGBIN:-/usr/lib/postgresql/VERSION/bin}/$p: Debian's postgresql)"
		tally
	fi
done
if ! command -v psql >/dev/null || ! command -v sqlite3 >/dev/null; then
	skip "a centre's PostgreSQL: no psql or sqlite3 program here"
	tally
fi

# the server runs as an unprivileged user: nobody when we are root
PGDIR="$TMP/pg"
PGSOCK="$PGDIR/run"
as_pg() { "$@"; }
if [ "$(id -u)" = 0 ]; then
	as_pg() { runuser -u nobody -- "$@"; }
	chmod 711 "$TMP"
fi
mkdir -p "$PGSOCK" && chmod 700 "$PGDIR"
[ "$(id -u)" = 0 ] && chown -R nobody "$PGDIR"

printf 'admin-secret\n' >"$TMP/adminpw"
[ "$(id -u)" = 0 ] && chown nobody "$TMP/adminpw"
export PGPASSFILE="$TMP/pgpass"
printf '*:*:*:admin:admin-secret\n*:*:endosim:rig:rig-secret\n' >"$PGPASSFILE"
chmod 600 "$PGPASSFILE"
URL="postgresql:///endosim?host=$PGSOCK&user=rig"

pg_start() {
	as_pg "$PGBIN/pg_ctl" -D "$PGDIR/data" -l "$PGDIR/log" -w -s \
		-o "-k $PGSOCK -c listen_addresses= -c fsync=off" start
}
pg_stop() { as_pg "$PGBIN/pg_ctl" -D "$PGDIR/data" -m fast -w -s stop; }
trap 'pg_stop >/dev/null 2>&1; cleanup' EXIT
# admin SQL: as the cluster's superuser; sql SQL: as a rig, in endosim
admin() { psql -X -q -At -v ON_ERROR_STOP=1 \
	"host=$PGSOCK user=admin dbname=postgres" -c "$1"; }
sql() { psql -X -q -At -v ON_ERROR_STOP=1 "$URL" -c "$1"; }
# centre ARGS: psql as the superuser in the centre's database
centre() { psql -X -q -At -v ON_ERROR_STOP=1 \
	"host=$PGSOCK user=admin dbname=endosim" "$@"; }
# as LOGIN SQL: a query with the credentials of the login LOGIN
as() { psql -X -q -At -v ON_ERROR_STOP=1 \
	"host=$PGSOCK user='$1' dbname=endosim" -c "$2"; }
# login NAME GROUPROLE: the centre's login of the person NAME (a role of
# that name in GROUPROLE), its password in the password file
login() {
	centre -c "CREATE ROLE \"$1\" LOGIN PASSWORD '$1-pw' IN ROLE $2" &&
		printf '*:*:endosim:%s:%s-pw\n' "$1" "$1" >>"$PGPASSFILE"
}

# pg_make: the cluster made and started, the rigs' role and database
pg_make() {
	check "the cluster made (initdb, passwords required)" as_pg \
		"$PGBIN/initdb" -D "$PGDIR/data" -U admin \
		--pwfile="$TMP/adminpw" --auth-local=scram-sha-256 \
		--auth-host=scram-sha-256 -E UTF8 --locale=C.UTF-8 --no-sync
	check "the server started on a private socket" pg_start
	check "the rigs' role and the centre's database" eval \
		"admin \"CREATE ROLE rig LOGIN PASSWORD 'rig-secret'\" &&
		 admin 'CREATE DATABASE endosim OWNER rig'"
}
