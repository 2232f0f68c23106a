/*
 * endoctl_records.c - `endoctl records check | rebuild | backup FILE |
 * restore FILE`: the rig's records (endosimd's SQLite database of its
 * sessions) against the session files, which are the truth (proto's
 * RecordsCheck, on the read-only socket, and RecordsRebuild, on the
 * read-write one), and their backup (RecordsBackup, RecordsRestore, on
 * the read-write one; FILE made absolute here, endosimd opens it).
 */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "endoctl/endoctl.h"

#define RECORDS_USAGE \
	"endoctl records check | rebuild | backup FILE | restore FILE\n"

static void json_records(const Endosim__RecordsReply *m, bool rebuilt)
{
	struct json j;

	json_init(&j, stdout);
	json_object_begin(&j, NULL);
	json_string(&j, "database", m->database);
	json_bool(&j, "missing", m->missing);
	json_bool(&j, "damaged", m->damaged);
	json_uint(&j, "files", m->files);
	json_uint(&j, "rows", m->rows);
	json_uint(&j, "differ", m->differ);
	json_uint(&j, "written", m->written);
	json_bool(&j, "rebuilt", rebuilt);
	json_string(&j, "found", m->text);
	json_object_end(&j);
}

static void print_records(const Endosim__RecordsReply *m, bool rebuilt)
{
	fputs(m->text, stdout);
	printf("records %s: %llu session files, %llu sessions in the "
	       "database", m->database, (unsigned long long)m->files,
	       (unsigned long long)m->rows);
	if (m->differ) {
		printf(", %llu differ", (unsigned long long)m->differ);
	} else if (!m->missing && !m->damaged) {
		printf(": they agree");
	}
	if (rebuilt) {
		printf("; rebuilt: %llu sessions written",
		       (unsigned long long)m->written);
	}
	printf("\n");
}

/* FILE as an absolute path into OUT (SIZE): the daemon's working
 * directory is not ours. False when it does not fit. */
static bool absolute(const char *file, char *out, size_t size)
{
	char cwd[PATH_MAX];
	int n;

	if (file[0] == '/') {
		n = snprintf(out, size, "%s", file);
	} else if (getcwd(cwd, sizeof(cwd))) {
		n = snprintf(out, size, "%s/%s", cwd, file);
	} else {
		return false;
	}
	return n > 0 && (size_t)n < size;
}

/* `records backup FILE` and `records restore FILE`. */
static int backup_or_restore(struct ctl *ctl, bool backup, const char *file)
{
	Endosim__RecordsBackup b = ENDOSIM__RECORDS_BACKUP__INIT;
	Endosim__RecordsRestore rs = ENDOSIM__RECORDS_RESTORE__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	char path[PATH_MAX];
	int r;

	if (!absolute(file, path, sizeof(path))) {
		fprintf(stderr, "endoctl: %s: the path is too long\n", file);
		return EXIT_USAGE;
	}
	if (backup) {
		b.path = path;
		req.body_case = ENDOSIM__REQUEST__BODY_RECORDS_BACKUP;
		req.records_backup = &b;
	} else {
		rs.path = path;
		req.body_case = ENDOSIM__REQUEST__BODY_RECORDS_RESTORE;
		req.records_restore = &rs;
	}
	if ((r = ctl_transact(ctl, true, &req, &rep))) {
		return r;
	}
	if (ctl->json) {
		json_records(rep->records, false);
	} else if (backup) {
		fputs(rep->records->text, stdout);
	} else {
		printf("restored from %s\n", path);
		print_records(rep->records, false);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}

int ctl_cmd_records(struct ctl *ctl, int argc, char **argv)
{
	Endosim__RecordsCheck check = ENDOSIM__RECORDS_CHECK__INIT;
	Endosim__RecordsRebuild rebuild = ENDOSIM__RECORDS_REBUILD__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	bool rebuilding;
	int r;

	if (argc == 3 && (!strcmp(argv[1], "backup") ||
			  !strcmp(argv[1], "restore"))) {
		return backup_or_restore(ctl, !strcmp(argv[1], "backup"),
					 argv[2]);
	}
	if (argc != 2 || (strcmp(argv[1], "check") &&
			  strcmp(argv[1], "rebuild"))) {
		fputs("usage: " RECORDS_USAGE, stderr);
		return EXIT_USAGE;
	}
	rebuilding = !strcmp(argv[1], "rebuild");
	if (rebuilding) {
		req.body_case = ENDOSIM__REQUEST__BODY_RECORDS_REBUILD;
		req.records_rebuild = &rebuild;
	} else {
		req.body_case = ENDOSIM__REQUEST__BODY_RECORDS_CHECK;
		req.records_check = &check;
	}
	if ((r = ctl_transact(ctl, rebuilding, &req, &rep))) {
		return r;
	}
	if (ctl->json) {
		json_records(rep->records, rebuilding);
	} else {
		print_records(rep->records, rebuilding);
	}
	endosim__reply__free_unpacked(rep, NULL);
	return 0;
}
