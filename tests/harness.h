/* harness.h - the in-house test harness of hrm.h (no third-party framework:
   the library has no dependencies and neither do its tests).

   CHECK(cond, fmt, ...)              cond must hold
   CHECK_INT(got, want, fmt, ...)     integers equal (compared as long)
   CHECK_NEAR(got, want, tol, fmt, ...)  |got - want| <= tol (as double)
   CHECK_REL(got, want, rtol, fmt, ...)  |got - want| <= rtol * |want|
   RUN_GROUP(fn)                      run void fn(void) as the group "fn"
   NOTE(fmt, ...)                     an informational line (measured orders)
   harness_summary()                  prints the totals; its last line is
                                      exactly "N passed, N failed"; returns
                                      the process exit code (0: all passed)

   A failed check prints "FAIL file:line [group] message (details)". A NaN
   never passes a numerical check. Every function is static inline so that a
   file using only some of them compiles warning-free.

   The tally is one object for the whole test program, however many files
   include this header: it is declared here and defined in the one file that
   defines HARNESS_IMPLEMENTATION before including it (tests/main.c; a
   single-file program such as tests/linkage_user.cpp defines it itself). It
   is the only mutable global of the tests. */
#ifndef HRM_TEST_HARNESS_H
#define HRM_TEST_HARNESS_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#if defined(__GNUC__) || defined(__clang__)
#define HARNESS_PRINTF(fmt_index, first_arg) \
    __attribute__((format(printf, fmt_index, first_arg)))
#else
#define HARNESS_PRINTF(fmt_index, first_arg)
#endif

#define HARNESS_MAX_PRINTED_FAILURES 200

#ifdef __cplusplus
extern "C" {
#endif

typedef struct harness_state {
    long passed, failed;             /* all checks */
    long group_passed, group_failed; /* checks of the current group */
    long groups, groups_failed;
    const char *group;
} harness_state;

/* The test program's tally (see the top comment). C linkage, so that files
   compiled as C and as C++ share it. */
extern harness_state harness_tally;

#ifdef __cplusplus
}
#endif

static inline harness_state *harness_state_get(void) { return &harness_tally; }

static inline void harness_vreport(int ok, const char *file, int line,
                                   const char *fmt, va_list ap)
{
    harness_state *s = harness_state_get();
    if (ok) {
        s->passed++;
        s->group_passed++;
        return;
    }
    s->failed++;
    s->group_failed++;
    if (s->failed <= HARNESS_MAX_PRINTED_FAILURES) {
        printf("FAIL %s:%d [%s] ", file, line, s->group ? s->group : "-");
        vprintf(fmt, ap);
    } else if (s->failed == HARNESS_MAX_PRINTED_FAILURES + 1) {
        printf("FAIL ... further failures are counted but not printed\n");
    }
}

/* The detail line of a failed numerical check, after the message. */
static inline void harness_detail(const harness_state *s, const char *what,
                                  double got, double want, double tol)
{
    if (s->failed <= HARNESS_MAX_PRINTED_FAILURES)
        printf(" (%s: got %.17g, want %.17g, |diff| %.3g, bound %.3g)\n",
               what, got, want, fabs(got - want), tol);
}

HARNESS_PRINTF(4, 5)
static inline int harness_check(int ok, const char *file, int line,
                                const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    harness_vreport(ok, file, line, fmt, ap);
    va_end(ap);
    if (!ok && harness_state_get()->failed <= HARNESS_MAX_PRINTED_FAILURES)
        printf("\n");
    return ok;
}

HARNESS_PRINTF(5, 6)
static inline int harness_check_int(long got, long want, const char *file,
                                    int line, const char *fmt, ...)
{
    va_list ap;
    int ok = got == want;
    va_start(ap, fmt);
    harness_vreport(ok, file, line, fmt, ap);
    va_end(ap);
    if (!ok && harness_state_get()->failed <= HARNESS_MAX_PRINTED_FAILURES)
        printf(" (got %ld, want %ld)\n", got, want);
    return ok;
}

HARNESS_PRINTF(6, 7)
static inline int harness_check_near(double got, double want, double tol,
                                     const char *file, int line,
                                     const char *fmt, ...)
{
    va_list ap;
    int ok = fabs(got - want) <= tol; /* false for NaN */
    va_start(ap, fmt);
    harness_vreport(ok, file, line, fmt, ap);
    va_end(ap);
    if (!ok)
        harness_detail(harness_state_get(), "abs", got, want, tol);
    return ok;
}

HARNESS_PRINTF(6, 7)
static inline int harness_check_rel(double got, double want, double rtol,
                                    const char *file, int line,
                                    const char *fmt, ...)
{
    va_list ap;
    double tol = rtol * fabs(want);
    int ok = fabs(got - want) <= tol; /* false for NaN */
    va_start(ap, fmt);
    harness_vreport(ok, file, line, fmt, ap);
    va_end(ap);
    if (!ok)
        harness_detail(harness_state_get(), "rel", got, want, tol);
    return ok;
}

#define CHECK(cond, ...) \
    harness_check((cond) ? 1 : 0, __FILE__, __LINE__, __VA_ARGS__)
#define CHECK_INT(got, want, ...) \
    harness_check_int((long)(got), (long)(want), __FILE__, __LINE__, __VA_ARGS__)
#define CHECK_NEAR(got, want, tol, ...)                                      \
    harness_check_near((double)(got), (double)(want), (double)(tol),         \
                       __FILE__, __LINE__, __VA_ARGS__)
#define CHECK_REL(got, want, rtol, ...)                                      \
    harness_check_rel((double)(got), (double)(want), (double)(rtol),         \
                      __FILE__, __LINE__, __VA_ARGS__)

HARNESS_PRINTF(1, 2)
static inline void harness_note(const char *fmt, ...)
{
    va_list ap;
    printf("  note [%s] ", harness_state_get()->group ? harness_state_get()->group : "-");
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
}
#define NOTE(...) harness_note(__VA_ARGS__)

static inline void harness_run(const char *name, void (*fn)(void))
{
    harness_state *s = harness_state_get();
    s->group = name;
    s->group_passed = s->group_failed = 0;
    fn();
    s->groups++;
    if (s->group_failed) s->groups_failed++;
    printf("%s %-28s %ld checks, %ld failed\n", s->group_failed ? "FAIL" : "ok  ",
           name, s->group_passed + s->group_failed, s->group_failed);
    fflush(stdout);
    s->group = NULL;
}
#define RUN_GROUP(fn) harness_run(#fn, fn)

/* Prints the totals; the last line is exactly "N passed, N failed". */
static inline int harness_summary(void)
{
    harness_state *s = harness_state_get();
    if (s->groups)
        printf("%ld groups, %ld with failures\n", s->groups, s->groups_failed);
    printf("%ld passed, %ld failed\n", s->passed, s->failed);
    fflush(stdout);
    return s->failed ? 1 : 0;
}

#endif /* HRM_TEST_HARNESS_H */

/* The definition of the tally, in one file of the program only. */
#if defined(HARNESS_IMPLEMENTATION) && !defined(HRM_TEST_HARNESS_IMPLEMENTED)
#define HRM_TEST_HARNESS_IMPLEMENTED
#ifdef __cplusplus
extern "C" {
#endif
harness_state harness_tally;
#ifdef __cplusplus
}
#endif
#endif
