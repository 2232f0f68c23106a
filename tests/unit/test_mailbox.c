/*
 * test_mailbox.c - how the control thread talks to the force loop
 * (mailbox.h): an answer answers its own request only, a box is taken
 * once a change, whole; and the patient's mailbox through the loop in
 * lockstep (loop.h): a turn, a press, a release applied at the next
 * cycle and answered 0; an unknown position or site, a force above
 * hand_max_n, an unknown command or a disabled patient answered -EINVAL
 * with nothing changed; a poster waiting on another thread gets its
 * answer from the cycle that took it.
 */
#include <errno.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "conf/cases.h"
#include "conf/config.h"
#include "loop/loop.h"
#include "loop/mailbox.h"
#include "rig/hand.h"
#include "rig/rig_sim.h"

#define PERIOD_NS 1000000ull

static void test_answer(void **state)
{
	struct mailbox_answer a = { 0 };
	uint32_t first, second;

	(void)state;
	first = mailbox_answer_next(&a);
	assert_int_equal(mailbox_answer_last(&a), -EINPROGRESS);
	mailbox_answer_set(&a, first, -EINVAL);
	assert_int_equal(mailbox_answer_last(&a), -EINVAL);
	assert_int_equal(mailbox_answer_wait(&a, first, 1), -EINVAL);
	second = mailbox_answer_next(&a);
	assert_int_not_equal(first, second);
	/* the first's answer is not the second's */
	assert_int_equal(mailbox_answer_last(&a), -EINPROGRESS);
	assert_int_equal(mailbox_answer_wait(&a, second, 5), -ETIMEDOUT);
	mailbox_answer_set(&a, second, 0);
	assert_int_equal(mailbox_answer_wait(&a, second, 5), 0);
}

static void test_box(void **state)
{
	struct mailbox_box b;
	double data = 0, in = 1.5, out = 0;

	(void)state;
	mailbox_box_init(&b, &data, sizeof(data));
	assert_false(mailbox_box_take(&b, &out));
	mailbox_box_put(&b, &in);
	assert_true(mailbox_box_take(&b, &out));
	assert_true(out == 1.5);
	assert_false(mailbox_box_take(&b, &out)); /* unchanged since */
	in = -2;
	mailbox_box_put(&b, &in);
	in = 3; /* the latest copy wins */
	mailbox_box_put(&b, &in);
	assert_true(mailbox_box_take(&b, &out));
	assert_true(out == 3);
}

/* The force loop in lockstep on the normal case (its sites llq and
 * umbilical), the patient ENABLED or not, turns of 0.5 s. */
struct rig_loop {
	struct config cfg;
	struct hand *hand;
	struct rig *rig;
	struct loop *loop;
	uint64_t now_ns;
};

static void rig_loop_create(struct rig_loop *r, bool patient)
{
	char err[512];
	struct colon *c;

	memset(r, 0, sizeof(*r));
	config_defaults(&r->cfg);
	r->cfg.haptics.model = HAPTICS_MODEL_PAPER;
	r->cfg.patient.enabled = patient;
	r->cfg.patient.turn_s = 0.5;
	snprintf(r->cfg.colon.file, sizeof(r->cfg.colon.file),
		 "config/cases/normal.case");
	c = cases_load(&r->cfg, NULL, err, sizeof(err));
	if (!c) {
		fail_msg("%s", err);
	}
	r->hand = hand_create(&r->cfg, NULL);
	r->rig = r->hand ? rig_sim_create(&r->cfg, r->hand) : NULL;
	r->loop = r->rig ? loop_create(&r->cfg, r->rig, NULL, c, 1) : NULL;
	assert_non_null(r->loop);
	r->now_ns = ENDOSIM_NS_PER_S;
}

static void rig_loop_destroy(struct rig_loop *r)
{
	loop_destroy(r->loop);
	r->rig->ops->destroy(r->rig);
	hand_destroy(r->hand);
}

static const struct endosim_patient_state *step(struct rig_loop *r)
{
	r->now_ns += PERIOD_NS;
	loop_step(r->loop, r->now_ns);
	return &loop_state(r->loop)->patient;
}

/* C posted, one cycle: its answer, the patient after it in *P. */
static int command(struct rig_loop *r, int op, int arg, double force_n,
		   const struct endosim_patient_state **p)
{
	const struct loop_patient_command c = { op, arg, force_n };

	loop_patient_post(r->loop, &c);
	assert_int_equal(loop_patient_answer(r->loop), -EINPROGRESS);
	*p = step(r);
	return loop_patient_answer(r->loop);
}

static void test_patient_commands(void **state)
{
	const struct endosim_patient_state *p;
	struct rig_loop r;

	(void)state;
	rig_loop_create(&r, true);
	p = step(&r);
	assert_true(p->enabled);
	assert_int_equal(p->position, ENDOSIM_POSITION_LEFT_LATERAL);
	assert_int_equal(command(&r, LOOP_PATIENT_TURN,
				 ENDOSIM_POSITION_SUPINE, 0, &p), 0);
	assert_int_equal(p->position, ENDOSIM_POSITION_SUPINE);
	assert_true(p->turning && p->turn < 0.01);
	for (int k = 0; k < 500; k++) {
		p = step(&r);
	}
	assert_false(p->turning);
	assert_true(p->down[1] > 0.999); /* supine: towards the back */
	/* no such position: nothing changes */
	assert_int_equal(command(&r, LOOP_PATIENT_TURN, 4, 0, &p), -EINVAL);
	assert_int_equal(p->position, ENDOSIM_POSITION_SUPINE);
	assert_false(p->turning);
	/* the hand: the default force, another site and force */
	assert_int_equal(command(&r, LOOP_PATIENT_PRESS, 0, 0, &p), 0);
	assert_int_equal(p->hand_site, 0);
	assert_true(p->hand_n == r.cfg.patient.hand_n);
	assert_int_equal(command(&r, LOOP_PATIENT_PRESS, 1, 30, &p), 0);
	assert_int_equal(p->hand_site, 1);
	assert_true(p->hand_n == 30);
	/* no such site, too strong: nothing changes */
	assert_int_equal(command(&r, LOOP_PATIENT_PRESS, 2, 0, &p), -EINVAL);
	assert_int_equal(command(&r, LOOP_PATIENT_PRESS, -1, 0, &p), -EINVAL);
	assert_int_equal(command(&r, LOOP_PATIENT_PRESS, 0,
				 r.cfg.patient.hand_max_n + 10, &p), -EINVAL);
	assert_int_equal(p->hand_site, 1);
	assert_true(p->hand_n == 30);
	assert_int_equal(command(&r, LOOP_PATIENT_RELEASE, 0, 0, &p), 0);
	assert_int_equal(p->hand_site, -1);
	assert_true(p->hand_n == 0);
	assert_int_equal(command(&r, 99, 0, 0, &p), -EINVAL);
	rig_loop_destroy(&r);
}

static void test_patient_disabled(void **state)
{
	const struct endosim_patient_state *p;
	struct rig_loop r;

	(void)state;
	rig_loop_create(&r, false);
	assert_int_equal(command(&r, LOOP_PATIENT_TURN,
				 ENDOSIM_POSITION_PRONE, 0, &p), -EINVAL);
	assert_int_equal(command(&r, LOOP_PATIENT_PRESS, 0, 0, &p), -EINVAL);
	assert_false(p->enabled);
	assert_int_equal(p->hand_site, -1);
	rig_loop_destroy(&r);
}

struct poster {
	struct loop *loop;
	_Atomic int result;
	_Atomic bool done;
};

static void *post_prone(void *arg)
{
	struct poster *ps = arg;
	const struct loop_patient_command c = {
		LOOP_PATIENT_TURN, ENDOSIM_POSITION_PRONE, 0,
	};

	ps->result = loop_patient_command(ps->loop, &c, 5000);
	ps->done = true;
	return NULL;
}

/* The daemon's way: the control thread posts and waits, the loop answers
 * within a cycle. */
static void test_patient_command_waits(void **state)
{
	struct poster ps = { 0 };
	struct rig_loop r;
	pthread_t t;
	int cycles = 0;

	(void)state;
	rig_loop_create(&r, true);
	ps.loop = r.loop;
	ps.result = 1;
	assert_int_equal(pthread_create(&t, NULL, post_prone, &ps), 0);
	while (!ps.done && cycles < 100000) {
		step(&r);
		cycles++;
	}
	pthread_join(t, NULL);
	assert_int_equal(ps.result, 0);
	assert_int_equal(loop_state(r.loop)->patient.position,
			 ENDOSIM_POSITION_PRONE);
	rig_loop_destroy(&r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_answer),
		cmocka_unit_test(test_box),
		cmocka_unit_test(test_patient_commands),
		cmocka_unit_test(test_patient_disabled),
		cmocka_unit_test(test_patient_command_waits),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
