/*
 * text.h - small helpers for the line-based files people write (case
 * files, course files).
 *
 * No allocation, no state: any thread, the force loop included.
 */
#ifndef ENDOSIM_TEXT_H
#define ENDOSIM_TEXT_H

/* S without its leading and trailing white space: the trailing is cut
 * off in place (S is written), the result points into S. */
char *text_trim(char *s);

#endif
