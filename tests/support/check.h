/* A tiny test harness: CHECK macros record failures with expected vs seen;
 * RUN(fn) runs one test function and prints its name and verdict. */
#ifndef PELT_CHECK_H
#define PELT_CHECK_H

#include <math.h>
#include <stdio.h>

extern int check_failures;
extern const char *check_current;

#define CHECK(cond)                                                            \
    do {                                                                       \
        if (!(cond)) {                                                         \
            check_failures++;                                                  \
            fprintf(stderr, "  FAIL %s:%d in %s: %s\n", __FILE__, __LINE__,    \
                    check_current, #cond);                                     \
        }                                                                      \
    } while (0)

#define CHECK_NEAR(seen, expected, tol)                                        \
    do {                                                                       \
        double s_ = (double)(seen), e_ = (double)(expected);                   \
        if (!(fabs(s_ - e_) <= (double)(tol))) {                               \
            check_failures++;                                                  \
            fprintf(stderr,                                                    \
                    "  FAIL %s:%d in %s: %s = %.9g, expected %.9g (tol %g)\n", \
                    __FILE__, __LINE__, check_current, #seen, s_, e_,          \
                    (double)(tol));                                            \
        }                                                                      \
    } while (0)

#define RUN(fn)                                                                \
    do {                                                                       \
        int before_ = check_failures;                                          \
        check_current = #fn;                                                   \
        fn();                                                                  \
        printf("%s %s\n", check_failures == before_ ? "ok  " : "FAIL", #fn);   \
        fflush(stdout);                                                        \
    } while (0)

/* Prints the summary line and returns the process exit code. */
int check_summary(void);

/* The exit code CTest reads as SKIPPED (SKIP_RETURN_CODE in
 * tests/CMakeLists.txt): for a test that cannot run here, never a pass. */
#define CHECK_SKIP_CODE 77

/* Prints "SKIPPED: reason" and returns CHECK_SKIP_CODE. */
int check_skip(const char *reason);

#endif
