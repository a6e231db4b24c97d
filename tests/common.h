/* common.h - what the files of hrm.h's test program share.

   The test program is one binary per configuration of tests/run.sh, linked
   from several translation units, each including hrm.h:
     main.c           runs every group, prints the summary (and holds the
                      harness's tally)
     test_tables.c    the implementation (HRM_IMPLEMENTATION) and the checks
                      of its private coefficient tables
     test_fixed.c     the interface and the fixed-step methods
     test_adaptive.c  the adaptive methods
     test_warp.c      the importance-sampling warps */
#ifndef HRM_TEST_COMMON_H
#define HRM_TEST_COMMON_H

/* HRM_STATIC makes every function of hrm.h private to the file that
   compiles it, so each file of the program then needs its own copy of the
   implementation (and the build checks that the copies do not collide). */
#if defined(HRM_STATIC) && !defined(HRM_IMPLEMENTATION)
#define HRM_IMPLEMENTATION
#endif
#include "hrm.h"
#include "harness.h"

/* The entry points of the test files, each running its groups. */
void fixed_tests(void);
void table_tests(void);
void adaptive_tests(void);
void warp_tests(void);

#endif /* HRM_TEST_COMMON_H */
