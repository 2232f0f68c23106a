-- centre-roles.sql - who sees what in a training centre's PostgreSQL
-- (docs/INSTRUCTOR.md, "Who sees what"): the rules of the rigs' logins (a
-- trainee their own sessions, an instructor their groups' trainees', only
-- an administrator deletes) held by the database itself, with roles,
-- grants and row-level security, whatever client a person connects with.
--
-- Run it as the server's superuser in the centre's database, once the
-- first rig has connected (endosimd makes `sessions` and the people's
-- tables then), and again after an upgrade (it changes nothing twice):
--
--   sudo -u postgres psql -d endosim -f /usr/share/endosim/centre-roles.sql
--
-- The rigs' role owns the tables and writes them; as their owner it is
-- not bound by the policies (keep its password on the rigs). The people
-- (endosim_people, endosim_groups, endosim_members, endosim_courses) come
-- from the rigs: a user or group made on any rig of the centre is there,
-- with their role at the rigs. Everyone else reads through three roles,
-- each granted to a person's own login, a PostgreSQL role named as the
-- person is at the rigs:
--
--   endosim_trainee      the sessions whose trainee is their person
--   endosim_instructor   those of the trainees of the groups they manage
--   endosim_admin        every session; deletes them; reads the people
--                        (not their PINs' hashes) and the changes' log
--
-- A person sees what both their role at the rigs and the centre's grant
-- allow: an instructor at the rigs with a login granted endosim_trainee
-- sees their own sessions only.
--
--   CREATE ROLE "Dr Ives" LOGIN IN ROLE endosim_instructor;
--   \password "Dr Ives"
--
-- Their passwords are PostgreSQL's own (SCRAM verifiers, never in clear);
-- they read with `endoctl trainee list --centre
-- "postgresql://centre/endosim?user=Dr%20Ives"` and the password in their
-- ~/.pgpass.

DO $$
DECLARE
	r text;
BEGIN
	FOREACH r IN ARRAY ARRAY['endosim_trainee', 'endosim_instructor',
				 'endosim_admin'] LOOP
		IF NOT EXISTS (SELECT 1 FROM pg_roles WHERE rolname = r) THEN
			EXECUTE format('CREATE ROLE %I NOLOGIN', r);
		END IF;
	END LOOP;
END
$$;

-- Whether the person logged in sees the sessions of TRAINEE. It reads the
-- people as the function's owner: no one else needs to.
CREATE OR REPLACE FUNCTION endosim_sees(trainee text) RETURNS boolean
	LANGUAGE sql STABLE SECURITY DEFINER
	SET search_path = public, pg_temp
AS $$
	SELECT EXISTS (
		SELECT 1 FROM endosim_people p
		WHERE p.name = session_user::text AND (
			(p.role = 'administrator' AND pg_has_role(session_user,
				'endosim_admin', 'MEMBER')) OR
			(p.role = 'trainee' AND p.name = $1) OR
			(p.role = 'instructor' AND pg_has_role(session_user,
				'endosim_instructor', 'MEMBER') AND EXISTS (
				SELECT 1 FROM endosim_groups g
				JOIN endosim_members m ON m.group_name = g.name
				WHERE g.instructor = p.name
				  AND m.trainee = $1))))
$$;
REVOKE ALL ON FUNCTION endosim_sees(text) FROM PUBLIC;
GRANT EXECUTE ON FUNCTION endosim_sees(text)
	TO endosim_trainee, endosim_instructor, endosim_admin;

-- the people are the rigs' to change; an administrator reads them
REVOKE ALL ON endosim_people, endosim_groups, endosim_members,
	endosim_courses, endosim_changes FROM PUBLIC, endosim_trainee,
	endosim_instructor, endosim_admin;
GRANT SELECT (name, role) ON endosim_people TO endosim_admin;
GRANT SELECT ON endosim_groups, endosim_members, endosim_courses,
	endosim_changes TO endosim_admin;

ALTER TABLE sessions ENABLE ROW LEVEL SECURITY;
REVOKE ALL ON sessions FROM PUBLIC;
GRANT SELECT ON sessions
	TO endosim_trainee, endosim_instructor, endosim_admin;
GRANT DELETE ON sessions TO endosim_admin;
DROP POLICY IF EXISTS sessions_seen ON sessions;
CREATE POLICY sessions_seen ON sessions FOR SELECT
	TO endosim_trainee, endosim_instructor, endosim_admin
	USING (endosim_sees(trainee));
DROP POLICY IF EXISTS sessions_deleted ON sessions;
CREATE POLICY sessions_deleted ON sessions FOR DELETE TO endosim_admin
	USING (endosim_sees(trainee));
