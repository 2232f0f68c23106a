/*
 * state_text.h - a published state (struct endosim_state) as "key=value"
 * lines, one field a line, for tests and tools to compare: endoview
 * --print-state writes the state its last frame showed, session_synth the
 * truth it recorded. Numbers as %.9g, which a float reads back exactly, so
 * two states made from the same session record print the same text.
 *
 * Keys: cycle, stamp_ns, state, fault_bits, scenario_time_s, position,
 * velocity, hand, command, limited (4 axes, comma-separated), ramp,
 * depth_m, roll_rad, bend_rad (2), base_s_m, tip_s_m, turning_rad, tip,
 * dir, up (3), bow_m (4), spans, proxy, normal, f_static (3),
 * penetration_m, contact; the rod model's model, contacts, wall_n,
 * friction_n, trans_rod_n, tube_rod_nm, span_nodes (4), rod_point (its
 * points in use as "x,y,z" separated by ';'), rod_roll (as many, by ','),
 * rod_node (its nodes in use, as rod_point); with a tool in the working
 * channel, tool_kind, tool_depth_m, tool_opening, tool_pedal, tool_loop_m,
 * tool_tip, tool_loop_centre (3); what the tools left, tool in hand or
 * not: while any bleeds tool_bleeding and tool_bleed_at (3), with a clip
 * placed tool_clips and tool_clip_at (3), with a polyp cut and lying
 * tool_lying (each as "K:x,y,z", K its index, separated by ';'); with
 * guided replay's expert's tool shown, expert_kind, expert_depth_m,
 * expert_opening, expert_pedal, expert_loop_m, expert_tip (3); and, last,
 * tube: the 128 points as "x,y,z" separated by ';'.
 */
#ifndef ENDOSIM_STATE_TEXT_H
#define ENDOSIM_STATE_TEXT_H

#include <stdio.h>

#include "proto/endosim_shm.h"

/* Writes ST to F, each line prefixed with PREFIX (may be ""). */
void state_text_print(FILE *f, const char *prefix,
		      const struct endosim_state *st);

#endif
