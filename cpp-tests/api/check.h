/* The checks of the C ABI tests: a failed condition is printed with its
 * place and the library's last error, and counted; main returns non-zero
 * when any failed. SENTINEL fills outputs that a failing call must leave
 * untouched. */
#ifndef LOOPSURF_TEST_CHECK_H
#define LOOPSURF_TEST_CHECK_H

#include <loopsurf.h>
#include <stdio.h>

static int failures = 0;
#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "%s:%d: FAILED: %s (last error: %s)\n", __FILE__, __LINE__, \
                    #cond, ls_last_error());                                          \
            failures++;                                                               \
        }                                                                             \
    } while (0)
#define EXPECT(call, status) CHECK((call) == (status))

static const double SENTINEL = -12345.678;

#endif
