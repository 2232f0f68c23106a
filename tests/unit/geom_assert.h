/*
 * geom_assert.h - assertions on numbers for the geometry unit tests
 * (cmocka 1.1.5 has none for floating point).
 */
#ifndef ENDOSIM_GEOM_ASSERT_H
#define ENDOSIM_GEOM_ASSERT_H

#include <math.h>

/* |A - B| <= TOL, printing both on failure. NaN fails. */
#define assert_near(a, b, tol)                                               \
	do {                                                                 \
		double a_ = (a), b_ = (b), t_ = (tol);                       \
		if (!(fabs(a_ - b_) <= t_)) {                                \
			print_error("%s = %.12g, %s = %.12g, |diff| %.3g > " \
				    "%.3g\n", #a, a_, #b, b_, fabs(a_ - b_), \
				    t_);                                     \
			fail();                                              \
		}                                                            \
	} while (0)

/* |A - B| <= TOL for three-vectors. */
#define assert_vec_near(a, b, tol)                     \
	do {                                           \
		for (int d_ = 0; d_ < 3; d_++) {       \
			assert_near((a)[d_], (b)[d_], tol); \
		}                                      \
	} while (0)

#endif
