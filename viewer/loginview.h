/*
 * loginview.h - endoview's login screen (login.h) drawn over the views
 * while it asks who is training: the frame dimmed, a box in its middle
 * with "Who is training?", the name, the PIN as one dot a character, the
 * field with the focus outlined with a blinking caret, the last refusal
 * in red (a wrong name or PIN, the wait after wrong PINs in a row), and
 * the form's keys. A character beyond the font's printable ASCII shows
 * as one '?'.
 *
 * Main thread, with the GL context current (draw2d.h).
 */
#ifndef ENDOVIEW_LOGINVIEW_H
#define ENDOVIEW_LOGINVIEW_H

#include "viewer/draw2d.h"
#include "viewer/login.h"

/* Queues the screen of L (LOGIN_ASK; nothing else) into D, between
 * draw2d_begin() and draw2d_end(), over a W x H framebuffer; T_S (s) the
 * caret's blink. */
void loginview_draw(struct draw2d *d, const struct login *l, int w, int h,
		    double t_s);

#endif
