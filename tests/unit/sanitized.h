/*
 * sanitized.h - for the long lockstep tests: SANITIZED is 1 in the
 * AddressSanitizer/UBSan build (make asan-build: gcc's
 * __SANITIZE_ADDRESS__, clang's address_sanitizer feature), 0 in the
 * plain build. There a test checks memory and undefined behaviour, not
 * physics (the plain build checks the physics), and the same code paths
 * in fewer cycles catch the same errors: such a test runs shorter under
 * SANITIZED (shorter phases, fewer repeats, one case of several; never a
 * phase left out) and says what it leaves to the plain build, once, with
 * sanitized_leaves(). Include after stdio.h.
 */
#ifndef ENDOSIM_SANITIZED_H
#define ENDOSIM_SANITIZED_H

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SANITIZED 1
#endif
#endif
#ifndef SANITIZED
#define SANITIZED 0
#endif

/* Under SANITIZED, the line "# sanitized build: WHAT" (what this run
 * does instead of the plain build's, and what it leaves to it); nothing
 * in the plain build. */
static inline void sanitized_leaves(const char *what)
{
	if (SANITIZED) {
		printf("# sanitized build: %s\n", what);
	}
}

#endif
