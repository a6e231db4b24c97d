/* main.c - the test program of hrm.h: runs every group of every test file
   and ends with the harness's line "N passed, N failed"; the exit code is
   0 only if every check passed.

   Set HRM_TEST_VERBOSE=1 in the environment to print every measured error
   next to its bound. */
#define HARNESS_IMPLEMENTATION /* the one definition of the tally */
#include "common.h"

int main(void)
{
    fixed_tests();
    table_tests();
    adaptive_tests();
    warp_tests();
    transmittance_tests();
    breaks_tests();
    exponential_tests();
    extremes_tests();
    bad_input_tests();
    return harness_summary();
}
