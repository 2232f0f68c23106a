-- centre-roles.sql - who sees what in a training centre's PostgreSQL
-- (README.md, "Who sees what"): the rules of the rigs' logins (a trainee
-- their own sessions, an instructor their groups' trainees', only an
-- administrator deletes) held by the database itself, with roles, grants
-- and row-level security, whatever client a person connects with.
--
-- Run it as the server's superuser in the centre's database, once the
-- first rig has made its table (endosimd makes `sessions` on its first
-- connection), and again after an upgrade (it changes nothing twice):
--
--   sudo -u postgres psql -d endosim -f /usr/share/endosim/centre-roles.sql
--
-- The rigs' role owns `sessions` and writes it; as its owner it is not
-- bound by the policies (keep its password on the rigs). Everyone else
-- reads through three roles, each granted to a person's own login:
--
--   endosim_trainee      the sessions whose trainee is their person
--   endosim_instructor   those of the trainees of the groups they manage
--   endosim_admin        every session; deletes them; keeps the people,
--                        groups, members and courses below
--
-- A person: a login role in one of them, and their row in endosim_people
-- (the role there decides what they see: the two must agree):
--
--   CREATE ROLE ann LOGIN IN ROLE endosim_trainee;  -- then \password ann
--   INSERT INTO endosim_people VALUES ('ann', 'Ann', 'trainee');
--   INSERT INTO endosim_groups VALUES ('2026', 'Dr Ives');
--   INSERT INTO endosim_members VALUES ('2026', 'Ann');
--
-- Their passwords are PostgreSQL's own (SCRAM verifiers, never in clear);
-- they read with `endoctl trainee list --centre
-- "postgresql://centre/endosim?user=ann"` and the password in their
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

CREATE TABLE IF NOT EXISTS endosim_people (
	login name PRIMARY KEY,         -- the role they log in as
	person text NOT NULL UNIQUE,    -- their name in the sessions and groups
	role text NOT NULL
		CHECK (role IN ('trainee', 'instructor', 'administrator')));
CREATE TABLE IF NOT EXISTS endosim_groups (
	name text PRIMARY KEY,          -- a year's intake
	instructor text NOT NULL);      -- the person who manages it
CREATE TABLE IF NOT EXISTS endosim_members (
	group_name text NOT NULL
		REFERENCES endosim_groups (name) ON DELETE CASCADE,
	trainee text NOT NULL,
	PRIMARY KEY (group_name, trainee));
CREATE TABLE IF NOT EXISTS endosim_courses (
	group_name text NOT NULL
		REFERENCES endosim_groups (name) ON DELETE CASCADE,
	course text NOT NULL,
	PRIMARY KEY (group_name, course));

-- Whether the person logged in sees the sessions of TRAINEE. It reads the
-- tables above as their owner: no one else needs to read them.
CREATE OR REPLACE FUNCTION endosim_sees(trainee text) RETURNS boolean
	LANGUAGE sql STABLE SECURITY DEFINER
	SET search_path = public, pg_temp
AS $$
	SELECT EXISTS (
		SELECT 1 FROM endosim_people p
		WHERE p.login = session_user AND (
			p.role = 'administrator' OR
			(p.role = 'trainee' AND p.person = $1) OR
			(p.role = 'instructor' AND EXISTS (
				SELECT 1 FROM endosim_groups g
				JOIN endosim_members m ON m.group_name = g.name
				WHERE g.instructor = p.person
				  AND m.trainee = $1))))
$$;
REVOKE ALL ON FUNCTION endosim_sees(text) FROM PUBLIC;
GRANT EXECUTE ON FUNCTION endosim_sees(text)
	TO endosim_trainee, endosim_instructor, endosim_admin;

REVOKE ALL ON endosim_people, endosim_groups, endosim_members,
	endosim_courses FROM PUBLIC;
GRANT SELECT, INSERT, UPDATE, DELETE ON endosim_people, endosim_groups,
	endosim_members, endosim_courses TO endosim_admin;

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
