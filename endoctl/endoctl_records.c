/*
 * endoctl_records.c - `endoctl records check | rebuild`: the rig's records
 * (endosimd's SQLite database of its sessions) against the session files,
 * which are the truth (proto's RecordsCheck, on the read-only socket, and
 * RecordsRebuild, on the read-write one).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "endoctl/endoctl.h"

#define RECORDS_USAGE "endoctl records check | rebuild\n"

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

int ctl_cmd_records(struct ctl *ctl, int argc, char **argv)
{
	Endosim__RecordsCheck check = ENDOSIM__RECORDS_CHECK__INIT;
	Endosim__RecordsRebuild rebuild = ENDOSIM__RECORDS_REBUILD__INIT;
	Endosim__Request req = ENDOSIM__REQUEST__INIT;
	Endosim__Reply *rep;
	bool rebuilding;
	int r;

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
