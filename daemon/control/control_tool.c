/*
 * control_tool.c - the tool the nurse hands over (the Tool request): the
 * name and the snare's size checked here, on the control thread, so that
 * a refusal lists the valid ones and nothing reaches the loop; the loop
 * selects it through its tool mailbox (loop_tool_command()) and answers
 * within a cycle or two. The reply is the status of the cycle that took
 * the command.
 */
#include <errno.h>
#include <stdio.h>

#include "base/log.h"
#include "control/control_private.h"
#include "model/tool.h"
#include "proto/names.h"

/* The selection asked for, or false with REP refused (the tools listed,
 * the snare's sizes said). */
static bool tool_of(struct control *c, const Endosim__Tool *t,
		    struct loop_tool_command *cmd, Endosim__Reply *rep)
{
	int kind = names_tool_find(t->select);
	double size = t->snare_m > 0 ? t->snare_m : c->cfg.tool.snare_size_m;

	if (kind < 0) {
		snprintf(c->refusal, sizeof(c->refusal), "tool: no tool "
			 "'%.63s': none, forceps, snare, needle or clip",
			 t->select);
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->refusal);
		return false;
	}
	if (kind == TOOL_SNARE &&
	    !(size >= TOOL_SNARE_MIN_M && size <= TOOL_SNARE_MAX_M)) {
		snprintf(c->refusal, sizeof(c->refusal), "tool: a snare of "
			 "%g mm: from %g to %g mm", size * 1e3,
			 TOOL_SNARE_MIN_M * 1e3, TOOL_SNARE_MAX_M * 1e3);
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE, c->refusal);
		return false;
	}
	*cmd = (struct loop_tool_command){ kind, kind == TOOL_SNARE ? size
								     : 0 };
	return true;
}

void control_on_tool(struct control *c, struct client *cl,
		     const Endosim__Request *req, Endosim__Reply *rep)
{
	struct loop_tool_command cmd;
	int r;

	if (!tool_of(c, req->tool, &cmd, rep)) {
		return;
	}
	r = loop_tool_command(c->deps.loop, &cmd, COMMAND_TIMEOUT_MS);
	if (r == -EINVAL) {
		refuse(rep, ENDOSIM__STATUS__STATUS_BAD_VALUE,
		       "tool: refused by the force loop");
		return;
	}
	if (r) {
		refuse(rep, ENDOSIM__STATUS__STATUS_TIMEOUT,
		       "the force loop did not take the command");
		return;
	}
	if (cmd.kind == TOOL_SNARE) {
		log_notice("tool: a %g mm snare handed over by uid %d",
			   cmd.snare_m * 1e3, (int)cl->uid);
	} else {
		log_notice("tool: %s handed over by uid %d",
			   names_tool((uint32_t)cmd.kind), (int)cl->uid);
	}
	control_await_state(c);
	control_build_status(c, rep);
}
