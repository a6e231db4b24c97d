/* test_bad_input.c - the manual's BAD INPUT table, row by row.

   One table (bi_rows below) holds a row per class of bad input, or of
   extreme input that is valid: NaN, infinities, huge and denormal values
   in each argument and in each callback's output, negative coefficients
   and radiances, a transmittance above 1 or rising along the ray, step
   counts, tolerances and budgets out of range, unknown enumerators and
   flags, user warps that are not increasing, NULL pointers, breakpoint
   lists that are unsorted or out of range; and, for the other public
   functions, their own arguments.

   One table-driven test, bi_table, runs every row on every method of its
   set (bi_run_solve, bi_run_transmittance; bi_run_equi, bi_run_sphere and
   bi_run_name for the other functions). Each sets up a valid baseline (a
   heterogeneous medium through callbacks, or constants, or a closed-form
   transmittance, or a user warp; the ray [0.5, 6.5], where every value of
   the scene is of order 1; fixed-step methods take 8 steps, adaptive ones
   their defaults), checks that the call without the mutation returns
   HRM_OK (so that the row can fail), applies the one mutation, and calls
   the entry point with its result placed between canary bytes and
   prefilled with a pattern. It then checks
   - the exact status (a valid row may allow the adaptive methods a set of
     warnings: BI_UNRESOLVED);
   - an error's result: L = 0, Tr = 1 and error = -1 in every channel,
     njumps = 0 and jumps[] = 0;
   - its stats: all zero where the input is rejected before any callback
     (and then no callback was called), else the evaluations counted so
     far (no more than the callbacks made);
   - a callback's bad value: that it was returned, and that no callback of
     any kind was called after it (the manual: it "stops the solve"); for a
     value beyond the range, one factor of a product, that the callback
     was not called again (bi_stopped);
   - a valid row: L, Tr and error finite, L >= 0, 0 <= Tr <= 1, error -1
     (fixed-step) or >= 0 (adaptive);
   - the canaries around the result intact, medium and options unchanged;
   - hrm_transmittance with the same arguments: the same status where it
     reads what is mutated (HRM_OK where it does not, such as Le, Li or a
     warp on a finite ray), Tr = 1 on error, stats zero where rejected.

   The rows are the manual's table BAD INPUT, in its order. */
#include "common.h"

#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>


/* ------------------------------------------------------------------------
   The scene: callbacks that count their calls and return one bad value
   ------------------------------------------------------------------------ */
enum { CB_SA, CB_SS, CB_ST, CB_LE, CB_LI, CB_TR, CB_TOU, CB_DTDU, CB_UOT, CB_COUNT };

static const char *const bi_cb_name[CB_COUNT] = {"sigma_a", "sigma_s", "sigma_t", "Le",
                                                 "Li", "transmittance", "t_of_u", "dt_du",
                                                 "u_of_t"};

#define BI_T0 0.5
#define BI_T1 6.5

typedef struct bi_scene {
    long calls[CB_COUNT];
    long seq;          /* calls of every callback */
    int target;        /* the callback that returns the bad value, or -1 */
    long at_call;      /* which of its calls does (1: the first); 0: every
                          call, in every channel */
    hrm_real value;    /* the bad value (the last channel, or every one) */
    long poisoned;     /* seq of its first bad return, 0: none yet */
    long after;        /* calls of any callback after it */
    long after_cb[CB_COUNT]; /* of each callback */
    int tr_rising;     /* the transmittance rises along the ray */
    int warp_fold;     /* the user warp folds back inside the ray */
    int warp_reverse;  /* the user warp's u_of_t decreases: -sqrt(t) */
} bi_scene;

static void bi_scene_init(bi_scene *s)
{
    memset(s, 0, sizeof *s);
    s->target = -1;
}

static void bi_hit(bi_scene *s, int cb, hrm_real *out, int n)
{
    int c;
    s->calls[cb]++;
    s->seq++;
    if (s->poisoned && s->at_call) {
        s->after++;
        s->after_cb[cb]++;
    }
    if (cb != s->target || (s->at_call && s->calls[cb] != s->at_call)) return;
    if (!s->poisoned) s->poisoned = s->seq;
    if (s->at_call)
        out[n - 1] = s->value;
    else
        for (c = 0; c < n; ++c) out[c] = s->value;
}

/* sigma_t = (1 + f) (0.5 + 0.25 sin t), f = channel_frac(c); sigma_a is 0.4
   of it, sigma_s 0.6; Le = 1 + f; Li = 0.5 + 0.2 cos t. */
static double bi_st(int c, double t) { return (1 + channel_frac(c)) * (0.5 + 0.25 * sin(t)); }

static double bi_tau(int c, double ta, double tb)
{
    return (1 + channel_frac(c)) * (0.5 * (tb - ta) - 0.25 * (cos(tb) - cos(ta)));
}

static void bi_sigma(void *user, hrm_real t, hrm_real out[NCH], int cb, double part)
{
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(part * bi_st(c, (double)t));
    bi_hit((bi_scene *)user, cb, out, NCH);
}

static void bi_sigma_a(void *user, hrm_real t, hrm_real out[NCH]) { bi_sigma(user, t, out, CB_SA,
                       0.4); }
static void bi_sigma_s(void *user, hrm_real t, hrm_real out[NCH]) { bi_sigma(user, t, out, CB_SS,
                       0.6); }
static void bi_sigma_t(void *user, hrm_real t, hrm_real out[NCH]) { bi_sigma(user, t, out, CB_ST,
                       1.0); }

static void bi_Le(void *user, hrm_real t, hrm_real out[NCH])
{
    int c;
    (void)t;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(1 + channel_frac(c));
    bi_hit((bi_scene *)user, CB_LE, out, NCH);
}

static void bi_Li(void *user, hrm_real t, hrm_real out[NCH])
{
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(0.5 + 0.2 * cos((double)t));
    bi_hit((bi_scene *)user, CB_LI, out, NCH);
}

/* Tr(ta, tb) of the sigma_t above; rising: exp(-(1 + f) (7 - tb) / 2),
   which grows with tb (each value within [0, 1]). */
static void bi_transmittance(void *user, hrm_real ta, hrm_real tb, hrm_real out[NCH])
{
    bi_scene *s = (bi_scene *)user;
    int c;
    for (c = 0; c < NCH; ++c)
        out[c] = (hrm_real)(s->tr_rising ? exp(-(1 + channel_frac(c)) * (7.0 - (double)tb) / 2)
                                         : exp(-bi_tau(c, (double)ta, (double)tb)));
    bi_hit(s, CB_TR, out, NCH);
}

/* The user warp t = u^2, u = sqrt(t) (t >= 0); reversed, u = -sqrt(t),
   a map that decreases over the ray (t = u^2 still). Folded: t = u^2 + sin(6 pi
   (u - ua) / (ub - ua)), which keeps both ends but goes back and forth in
   between, with its true derivative (negative on about a third of it). */
static double bi_ua(void) { return sqrt(BI_T0); }
static double bi_ub(void) { return sqrt(BI_T1); }

static hrm_real bi_t_of_u(void *user, hrm_real u)
{
    bi_scene *s = (bi_scene *)user;
    double x = (double)u;
    double fold = s->warp_fold ? sin(6 * PI * (x - bi_ua()) / (bi_ub() - bi_ua())) : 0;
    hrm_real t = (hrm_real)(x * x + fold);
    bi_hit(s, CB_TOU, &t, 1);
    return t;
}

static hrm_real bi_dt_du(void *user, hrm_real u)
{
    bi_scene *s = (bi_scene *)user;
    double x = (double)u, k = 6 * PI / (bi_ub() - bi_ua());
    hrm_real j = (hrm_real)(2 * x + (s->warp_fold ? k * cos(k * (x - bi_ua())) : 0));
    bi_hit(s, CB_DTDU, &j, 1);
    return j;
}

static hrm_real bi_u_of_t(void *user, hrm_real t)
{
    bi_scene *s = (bi_scene *)user;
    hrm_real u = (hrm_real)((s->warp_reverse ? -1 : 1) * sqrt((double)t));
    bi_hit(s, CB_UOT, &u, 1);
    return u;
}

/* ------------------------------------------------------------------------
   The rows
   ------------------------------------------------------------------------ */
/* Entry points. */
enum {
    E_SOLVE,  /* hrm_solve, then hrm_transmittance with the same arguments */
    E_EQUI,   /* hrm_equiangular_warp */
    E_SPHERE, /* hrm_sphere_breaks */
    E_NAME    /* hrm_status_string, hrm_method_name, hrm_default_options */
};

/* Baselines of E_SOLVE. */
enum {
    V_AUTO,    /* by the callback poisoned: V_SIGMA_T for sigma_t, V_TR for
                  the transmittance, V_UWARP for the warp's; else V_CB */
    V_CB,      /* sigma_a, sigma_s, Le, Li (tau decoupled) */
    V_SIGMA_T, /* V_CB with sigma_t */
    V_TR,      /* V_CB with the closed-form transmittance */
    V_COUPLED, /* V_CB, tau coupled */
    V_RTE,     /* V_SIGMA_T, the RTE form */
    V_HOM,     /* constants, Le, Li */
    V_UWARP,   /* V_CB under the user warp */
    V_UWARP_BREAKS, /* V_UWARP with the breakpoints 1.5, 2.5, 3.5 */
    V_DIST,    /* V_CB under the distance warp */
    V_EMIT     /* Le alone, per unit length (HRM_EMISSION_PER_LENGTH): Tr = 1 */
};

/* Methods a row runs: every one, or a subset. */
enum { S_ALL, S_FIXED, S_ADAPTIVE, S_SIMPSON, S_RTE, S_NOFIT, S_DEFAULT };

/* What the checks expect of the result. */
enum {
    K_ARG,   /* an error before any callback: stats zero, nothing called */
    K_ENDS,  /* an error from the user warp's u_of_t at the ray's ends:
                stats zero, no other callback called */
    K_CB,    /* an error at a callback's value: stats so far, and nothing
                called after it */
    K_VALID  /* valid: the exact status, a finite estimate */
};

/* Values: a literal, or one that depends on HRM_REAL and the ray. */
enum {
    X_LIT,
    X_NAN,
    X_PINF,
    X_NINF,
    X_MAX,     /* the largest finite real */
    X_QMAX,    /* a quarter of it */
    X_IN_R,    /* R / 2 (ERRORS: R = largest / 1024 / (t1 - t0)) */
    X_OUT_R,   /* 4 R */
    X_DENORM   /* the smallest normal / 1024 */
};

/* Mutations. */
enum {
    MU_NONE,
    /* NULL pointers */
    MU_MEDIUM_NULL, MU_RESULT_NULL, MU_OPTIONS_NULL, MU_STATS_NULL, MU_NO_CALLBACKS,
    /* the interval */
    MU_T0, MU_T1, MU_T1_BELOW, MU_T_OVERFLOW, MU_T_FAR, MU_T_DENORM, MU_T_EMPTY,
    /* options */
    MU_METHOD, MU_STEPS, MU_FORM, MU_CONTROL, MU_GK_MODE, MU_GK_RULE, MU_TAU_MODE,
    MU_FIND_JUMPS, MU_EXPONENTIAL, MU_FIT_UNSUPPORTED, MU_RTOL, MU_ATOL, MU_H_MIN, MU_H_MAX,
    MU_H0, MU_H_MIN_ABOVE_MAX, MU_MAX_EVALS, MU_MAX_EVALS_MAX, MU_TAU_TOL, MU_JITTER,
    /* breakpoints (the baseline has 1.5, 2.5, 3.5) */
    MU_NBREAKS, MU_BREAKS_NULL, MU_BREAK_VALUE, MU_BREAKS_UNSORTED, MU_BREAKS_DUPLICATE,
    MU_BREAK_BELOW, MU_BREAK_ABOVE, MU_BREAKS_ENDS,
    /* warps */
    MU_WARP_KIND, MU_SIGMA_REF, MU_EQ_D, MU_EQ_DELTA, MU_EQ_ON_RAY, MU_UWARP_NULL,
    MU_UWARP_DECREASING, MU_WARP_EMPTY_RAY, MU_WARP_FOLD,
    /* the medium */
    MU_CONST_SA, MU_CONST_SS, MU_FLAGS, MU_FEATURE,
    /* callbacks' values */
    MU_POISON, MU_TR_RISING,
    /* hrm_equiangular_warp: origin (0,0,0), dir (1,0,0), light (3,1,0) */
    EQ_ORIGIN_NULL, EQ_DIR_NULL, EQ_LIGHT_NULL, EQ_WARP_NULL, EQ_DIR_ZERO, EQ_ORIGIN, EQ_DIR,
    EQ_LIGHT,
    /* hrm_sphere_breaks: origin (0,0,0), dir (1,0,0), light (5,4,0),
       sphere (5,2,0) radius 1, t in (0, 10) */
    SB_ORIGIN_NULL, SB_DIR_NULL, SB_LIGHT_NULL, SB_CENTER_NULL, SB_OUT_NULL, SB_COUNT_NULL,
    SB_RADIUS, SB_DIR_ZERO, SB_T0, SB_T1, SB_LIGHT, SB_CENTER,
    /* names */
    NM_STATUS, NM_METHOD, NM_DEFAULT_OPTIONS
};

typedef struct bi_row {
    const char *what;   /* the class and the example */
    int entry;          /* E_* */
    int mut;            /* MU_*, EQ_*, SB_*, NM_* */
    int cb;             /* MU_POISON: the callback (CB_*) */
    long at_call;       /* MU_POISON: its call that returns the value (0: every call) */
    int xk;             /* X_*: the value */
    double lit;         /* X_LIT: the value */
    int variant;        /* V_* */
    int set;            /* S_*: the methods */
    hrm_status want;    /* fixed-step methods (and every other entry point) */
    hrm_status want_ad; /* adaptive methods */
    unsigned also_ad;   /* K_VALID: other statuses allowed of adaptive
                           methods (bit s for status s >= 0) */
    int kind;           /* K_* */
    int tr;             /* T_*: what hrm_transmittance returns */
} bi_row;

/* hrm_transmittance's status for a row. */
enum {
    T_SAME, /* the row's status (a callback it calls fewer times than the
               row's call, or never: HRM_OK) */
    T_OK,   /* HRM_OK: it does not read what the row mutates */
    T_CLIP  /* HRM_WARN_RTOL_CLIPPED for adaptive methods, else HRM_OK */
};

#define BI_W(st) (1u << (st))

/* A row rejected before any callback, the same status for every method. */
#define BI_ARG(what, mut, xk, lit, set, st) \
    {what, E_SOLVE, mut, -1, 0, xk, lit, V_CB, set, st, st, 0, K_ARG, T_SAME}
/* The same with the homogeneous medium (its constants). */
#define BI_MED(what, mut, xk, lit, st) \
    {what, E_SOLVE, mut, -1, 0, xk, lit, V_HOM, S_ALL, st, st, 0, K_ARG, T_SAME}
/* A valid row: the status of fixed-step and of adaptive methods. */
#define BI_OK(what, mut, xk, lit, var, set, st, st_ad) \
    {what, E_SOLVE, mut, -1, 0, xk, lit, var, set, st, st_ad, 0, K_VALID, T_OK}
/* A valid row whose adaptive methods may also return the statuses of `also`. */
#define BI_OKW(what, mut, xk, lit, var, st_ad, also) \
    {what, E_SOLVE, mut, -1, 0, xk, lit, var, S_ALL, HRM_OK, st_ad, also, K_VALID, T_OK}
/* A callback returning the value at its call `at`. */
#define BI_CB(what, cb, at, xk, lit, var, set, st) \
    {what, E_SOLVE, MU_POISON, cb, at, xk, lit, var, set, st, st, 0, K_CB, T_SAME}
/* A callback returning a valid extreme value at every call, every channel. */
#define BI_CBOK(what, cb, xk, var, st_ad, also) \
    {what, E_SOLVE, MU_POISON, cb, 0, xk, 0, var, S_ALL, HRM_OK, st_ad, also, K_VALID, T_OK}
/* Another entry point (its own baseline and checks). */
#define BI_FN(what, entry, mut, xk, lit, st) \
    {what, entry, mut, -1, 0, xk, lit, V_CB, S_SIMPSON, st, st, 0, K_ARG, T_SAME}
/* The warnings of an integrand that no sample resolves (a layer at t0
   thinner than t's resolution there, or than h_min): which one depends on
   the method. */
#define BI_UNRESOLVED (BI_W(HRM_WARN_H_MIN) | BI_W(HRM_WARN_ROUNDOFF) | BI_W(HRM_WARN_TOLERANCE))

static const bi_row bi_rows[] = {
    /* NULL pointers */
    BI_ARG("NULL: medium", MU_MEDIUM_NULL, X_LIT, 0, S_ALL, HRM_ERR_NULL_ARGUMENT),
    BI_ARG("NULL: result (hrm_transmittance: Tr; its stats zeroed)", MU_RESULT_NULL,
           X_LIT, 0, S_ALL, HRM_ERR_NULL_ARGUMENT),
    BI_OK("NULL: options means the defaults", MU_OPTIONS_NULL, X_LIT, 0, V_CB, S_DEFAULT, HRM_OK,
          HRM_OK),
    BI_OK("NULL: hrm_transmittance's stats is optional", MU_STATS_NULL, X_LIT, 0, V_CB, S_ALL,
          HRM_OK, HRM_OK),
    BI_OK("NULL: every callback of the medium (absent terms)", MU_NO_CALLBACKS, X_LIT, 0, V_CB,
          S_ALL, HRM_OK, HRM_OK),
    BI_ARG("NULL: breaks with nbreaks > 0", MU_BREAKS_NULL, X_LIT, 0, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("NULL: a user warp's t_of_u", MU_UWARP_NULL, X_LIT, 0, S_ALL, HRM_ERR_BAD_WARP),

    /* the interval */
    BI_ARG("t0 NaN", MU_T0, X_NAN, 0, S_ALL, HRM_ERR_BAD_INTERVAL),
    BI_ARG("t0 +inf", MU_T0, X_PINF, 0, S_ALL, HRM_ERR_BAD_INTERVAL),
    BI_ARG("t0 -inf", MU_T0, X_NINF, 0, S_ALL, HRM_ERR_BAD_INTERVAL),
    BI_ARG("t1 NaN", MU_T1, X_NAN, 0, S_ALL, HRM_ERR_BAD_INTERVAL),
    BI_ARG("t1 -inf", MU_T1, X_NINF, 0, S_ALL, HRM_ERR_BAD_INTERVAL),
    BI_ARG("t1 +inf without a warp", MU_T1, X_PINF, 0, S_ALL, HRM_ERR_BAD_INTERVAL),
    BI_OKW("t1 +inf under the distance warp (valid)", MU_T1, X_PINF, 0, V_DIST, HRM_OK,
           BI_UNRESOLVED),
    BI_ARG("t1 < t0", MU_T1_BELOW, X_LIT, 0, S_ALL, HRM_ERR_BAD_INTERVAL),
    BI_ARG("t1 - t0 overflows (t0 = -0.75 max, t1 = 0.75 max)", MU_T_OVERFLOW, X_LIT, 0, S_ALL,
           HRM_ERR_RANGE),
    {"t1 huge (max / 4): the coefficients beyond R", E_SOLVE, MU_T1, -1, 0, X_QMAX, 0, V_CB, S_ALL,
     HRM_ERR_RANGE, HRM_ERR_RANGE, 0, K_CB, T_SAME},
    BI_MED("t1 huge (max / 4), homogeneous: the constants beyond R", MU_T1, X_QMAX, 0,
           HRM_ERR_RANGE),
    BI_OKW("t0, t1 huge (1e30, 2e30)", MU_T_FAR, X_LIT, 0, V_CB, HRM_OK, BI_UNRESOLVED),
    BI_OK("t1 denormal (t0 = 0)", MU_T_DENORM, X_DENORM, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_OK("t1 = t0 (empty ray)", MU_T_EMPTY, X_LIT, 0, V_CB, S_ALL, HRM_OK, HRM_OK),

    /* enumerators and counts */
    BI_ARG("method unknown (999)", MU_METHOD, X_LIT, 999, S_SIMPSON, HRM_ERR_BAD_METHOD),
    BI_ARG("method negative (-1)", MU_METHOD, X_LIT, -1, S_SIMPSON, HRM_ERR_BAD_METHOD),
    BI_ARG("method HRM_METHOD_COUNT", MU_METHOD, X_LIT, HRM_METHOD_COUNT, S_SIMPSON,
           HRM_ERR_BAD_METHOD),
    BI_ARG("steps negative (-1)", MU_STEPS, X_LIT, -1, S_ALL, HRM_ERR_BAD_STEPS),
    BI_ARG("steps INT_MIN", MU_STEPS, X_LIT, -2147483648.0, S_ALL, HRM_ERR_BAD_STEPS),
    BI_OK("steps INT_MAX, adaptive (capped at 32, or ignored)", MU_STEPS, X_LIT, 2147483647.0, V_CB,
          S_ADAPTIVE, HRM_OK, HRM_OK),
    BI_OK("steps 65536, fixed-step (N steps: no cap)", MU_STEPS, X_LIT, 65536, V_CB, S_FIXED,
          HRM_OK, HRM_OK),
    BI_ARG("form unknown (3)", MU_FORM, X_LIT, 3, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("form negative (-1)", MU_FORM, X_LIT, -1, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("control unknown (4)", MU_CONTROL, X_LIT, 4, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("gk_mode unknown (3)", MU_GK_MODE, X_LIT, 3, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("gk_rule unknown (-1)", MU_GK_RULE, X_LIT, -1, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("tau_mode unknown (4)", MU_TAU_MODE, X_LIT, 4, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("tau_mode HRM_TAU_STREAM, adaptive method (no increasing nodes)", MU_TAU_MODE, X_LIT, 3,
           S_ADAPTIVE, HRM_ERR_BAD_OPTION),
    BI_ARG("find_jumps 2", MU_FIND_JUMPS, X_LIT, 2, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("find_jumps -2", MU_FIND_JUMPS, X_LIT, -2, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("exponential 3", MU_EXPONENTIAL, X_LIT, 3, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("exponential -1", MU_EXPONENTIAL, X_LIT, -1, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("exponential 1 with a rule that has no fit", MU_FIT_UNSUPPORTED, X_LIT, 1, S_NOFIT,
           HRM_ERR_BAD_OPTION),
    BI_OK("jitter, stratified any nonzero int (INT_MIN)", MU_JITTER, X_LIT, -2147483648.0, V_CB,
          S_ALL, HRM_OK, HRM_OK),

    /* tolerances, step bounds, budgets */
    BI_ARG("rtol negative", MU_RTOL, X_LIT, -1e-4, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("rtol NaN", MU_RTOL, X_NAN, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("rtol +inf", MU_RTOL, X_PINF, 0, S_ALL, HRM_ERR_BAD_OPTION),
    /* (at 100 eps a third-order pair may spend the budget first:
       Bogacki-Shampine, HRM_WARN_MAX_EVALS, which outranks the clip) */
    {"rtol denormal (raised to 100 eps)", E_SOLVE, MU_RTOL, -1, 0, X_DENORM, 0, V_CB, S_ALL, HRM_OK,
     HRM_WARN_RTOL_CLIPPED, BI_W(HRM_WARN_TOLERANCE) | BI_W(HRM_WARN_ROUNDOFF) | BI_W(HRM_WARN_MAX_EVALS), K_VALID,
     T_CLIP},
    BI_OK("rtol huge (max / 4)", MU_RTOL, X_QMAX, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_ARG("atol negative", MU_ATOL, X_LIT, -1e-9, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("atol NaN", MU_ATOL, X_NAN, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("atol -inf", MU_ATOL, X_NINF, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_OK("atol huge (max / 4)", MU_ATOL, X_QMAX, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_ARG("h_min negative", MU_H_MIN, X_LIT, -1e-3, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("h_min NaN", MU_H_MIN, X_NAN, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("h_max negative", MU_H_MAX, X_LIT, -1, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("h_max +inf", MU_H_MAX, X_PINF, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("h0 negative", MU_H0, X_LIT, -0.1, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("h0 NaN", MU_H0, X_NAN, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("h_min > h_max (0.5 > 0.25)", MU_H_MIN_ABOVE_MAX, X_LIT, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_OKW("h_min huge (max / 4: one step over the ray)", MU_H_MIN, X_QMAX, 0, V_CB, HRM_WARN_H_MIN,
           BI_W(HRM_OK)),
    BI_OK("h_max huge (max / 4: the whole ray)", MU_H_MAX, X_QMAX, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_OK("h0 huge (max / 4)", MU_H0, X_QMAX, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_OK("h_min, h0 denormal", MU_H0, X_DENORM, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_ARG("max_evals negative", MU_MAX_EVALS, X_LIT, -1, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("max_evals below one step (1)", MU_MAX_EVALS, X_LIT, 1, S_ADAPTIVE, HRM_ERR_BAD_OPTION),
    BI_OK("max_evals 1, fixed-step (ignored)", MU_MAX_EVALS, X_LIT, 1, V_CB, S_FIXED, HRM_OK,
          HRM_OK),
    BI_OK("max_evals LONG_MAX", MU_MAX_EVALS_MAX, X_LIT, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_ARG("tau_tol negative", MU_TAU_TOL, X_LIT, -1e-3, S_ALL, HRM_ERR_BAD_OPTION),
    BI_ARG("tau_tol NaN", MU_TAU_TOL, X_NAN, 0, S_ALL, HRM_ERR_BAD_OPTION),
    BI_OK("tau_tol huge (max / 4)", MU_TAU_TOL, X_QMAX, 0, V_CB, S_ALL, HRM_OK, HRM_OK),
    BI_OK("tau_tol denormal (raised to 64 eps)", MU_TAU_TOL, X_DENORM, 0, V_CB, S_ALL, HRM_OK,
          HRM_OK),

    /* breakpoints (the valid list: 1.5, 2.5, 3.5) */
    BI_ARG("nbreaks negative", MU_NBREAKS, X_LIT, -1, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("nbreaks above HRM_MAX_BREAKS", MU_NBREAKS, X_LIT, HRM_MAX_BREAKS + 1, S_ALL,
           HRM_ERR_BAD_BREAKS),
    BI_ARG("nbreaks INT_MAX (not the budget's HRM_ERR_BAD_OPTION)", MU_NBREAKS, X_LIT, 2147483647.0,
           S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("a breakpoint NaN", MU_BREAK_VALUE, X_NAN, 0, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("a breakpoint +inf", MU_BREAK_VALUE, X_PINF, 0, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("breakpoints unsorted", MU_BREAKS_UNSORTED, X_LIT, 0, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("breakpoints repeated", MU_BREAKS_DUPLICATE, X_LIT, 0, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("a breakpoint below t0", MU_BREAK_BELOW, X_LIT, 0, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_ARG("a breakpoint above t1", MU_BREAK_ABOVE, X_LIT, 0, S_ALL, HRM_ERR_BAD_BREAKS),
    BI_OK("breakpoints at t0 and t1 (valid)", MU_BREAKS_ENDS, X_LIT, 0, V_CB, S_ALL, HRM_OK,
          HRM_OK),

    /* warps */
    BI_ARG("warp kind unknown (17)", MU_WARP_KIND, X_LIT, 17, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("warp kind negative (-1)", MU_WARP_KIND, X_LIT, -1, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("distance warp: sigma_ref negative", MU_SIGMA_REF, X_LIT, -1, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("distance warp: sigma_ref NaN", MU_SIGMA_REF, X_NAN, 0, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("distance warp: sigma_ref +inf", MU_SIGMA_REF, X_PINF, 0, S_ALL, HRM_ERR_BAD_WARP),
    BI_OK("distance warp: sigma_ref huge (lowered)", MU_SIGMA_REF, X_QMAX, 0, V_DIST, S_ALL, HRM_OK,
          HRM_OK),
    BI_OK("distance warp: sigma_ref denormal (no warp)", MU_SIGMA_REF, X_DENORM, 0, V_DIST, S_ALL,
          HRM_OK, HRM_OK),
    BI_ARG("equiangular warp: D negative", MU_EQ_D, X_LIT, -1, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("equiangular warp: D NaN", MU_EQ_D, X_NAN, 0, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("equiangular warp: D +inf", MU_EQ_D, X_PINF, 0, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("equiangular warp: delta -inf", MU_EQ_DELTA, X_NINF, 0, S_ALL, HRM_ERR_BAD_WARP),
    BI_ARG("equiangular warp: delta NaN", MU_EQ_DELTA, X_NAN, 0, S_ALL, HRM_ERR_BAD_WARP),
    BI_OK("equiangular warp: D huge (max / 4: no warp)", MU_EQ_D, X_QMAX, 0, V_CB, S_ALL,
          HRM_OK, HRM_OK),
    BI_OK("equiangular warp: delta huge (max / 4: no warp)", MU_EQ_DELTA, X_QMAX, 0, V_CB, S_ALL,
          HRM_OK, HRM_OK),
    {"equiangular warp: D = 0, light on the ray", E_SOLVE, MU_EQ_ON_RAY, -1, 0, X_LIT, 0, V_CB,
     S_ALL, HRM_ERR_SINGULAR, HRM_ERR_SINGULAR, 0, K_ARG, T_OK},
    {"user warp: u_of_t decreasing", E_SOLVE, MU_UWARP_DECREASING, -1, 0, X_LIT, 0, V_UWARP, S_ALL,
     HRM_ERR_BAD_WARP, HRM_ERR_BAD_WARP, 0, K_ENDS, T_OK},
    BI_ARG("bad warp parameters on an empty ray", MU_WARP_EMPTY_RAY, X_NAN, 0, S_ALL,
           HRM_ERR_BAD_WARP),

    /* the medium's constants and flags */
    BI_MED("constant sigma_a negative", MU_CONST_SA, X_LIT, -0.1, HRM_ERR_BAD_MEDIUM),
    BI_MED("constant sigma_a NaN", MU_CONST_SA, X_NAN, 0, HRM_ERR_BAD_MEDIUM),
    BI_MED("constant sigma_s +inf", MU_CONST_SS, X_PINF, 0, HRM_ERR_BAD_MEDIUM),
    BI_MED("constant sigma_s -inf", MU_CONST_SS, X_NINF, 0, HRM_ERR_BAD_MEDIUM),
    BI_MED("constant sigma_a beyond R (largest finite)", MU_CONST_SA, X_MAX, 0, HRM_ERR_RANGE),
    BI_MED("constant sigma_s beyond R (4 R)", MU_CONST_SS, X_OUT_R, 0, HRM_ERR_RANGE),
    BI_OKW("constant sigma_a huge within R (R / 2)", MU_CONST_SA, X_IN_R, 0, V_HOM,
           HRM_WARN_ROUNDOFF,
           BI_UNRESOLVED),
    BI_OK("constant sigma_a denormal", MU_CONST_SA, X_DENORM, 0, V_HOM, S_ALL, HRM_OK, HRM_OK),
    BI_ARG("medium flags: an unknown bit", MU_FLAGS, X_LIT, 0, S_ALL,
           HRM_ERR_BAD_MEDIUM),
    BI_ARG("medium feature negative", MU_FEATURE, X_LIT, -0.1, S_ALL, HRM_ERR_BAD_MEDIUM),
    BI_ARG("medium feature NaN", MU_FEATURE, X_NAN, 0, S_ALL, HRM_ERR_BAD_MEDIUM),
    BI_ARG("medium feature +inf", MU_FEATURE, X_PINF, 0, S_ALL, HRM_ERR_BAD_MEDIUM),
    BI_OK("medium feature denormal (the scan capped)", MU_FEATURE, X_DENORM, 0, V_CB, S_ALL, HRM_OK,
          HRM_OK),
    BI_OK("medium feature huge (the default scan)", MU_FEATURE, X_MAX, 0, V_CB, S_ALL, HRM_OK, HRM_OK),

    /* the callbacks' values: at their second call (the first for the
       transmittance and u_of_t), in the last channel */
    BI_CB("sigma_a NaN", CB_SA, 2, X_NAN, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_a +inf", CB_SA, 2, X_PINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_a negative", CB_SA, 2, X_LIT, -0.5, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_a beyond R (largest finite)", CB_SA, 2, X_MAX, 0, V_AUTO, S_ALL, HRM_ERR_RANGE),
    BI_CB("sigma_a NaN, tau coupled", CB_SA, 2, X_NAN, 0, V_COUPLED, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_s -inf", CB_SS, 2, X_NINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_s negative (-1e-30)", CB_SS, 3, X_LIT, -1e-30, V_AUTO, S_ALL,
          HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_s beyond R (4 R)", CB_SS, 2, X_OUT_R, 0, V_AUTO, S_ALL, HRM_ERR_RANGE),
    BI_CB("sigma_t NaN", CB_ST, 2, X_NAN, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_t negative", CB_ST, 2, X_LIT, -2, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("sigma_t +inf, RTE form", CB_ST, 2, X_PINF, 0, V_RTE, S_RTE, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Le NaN", CB_LE, 2, X_NAN, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Le +inf", CB_LE, 2, X_PINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Le -inf", CB_LE, 2, X_NINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Le negative", CB_LE, 2, X_LIT, -1, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Le beyond R (largest finite)", CB_LE, 2, X_MAX, 0, V_AUTO, S_ALL, HRM_ERR_RANGE),
    BI_CB("Li NaN", CB_LI, 2, X_NAN, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Li +inf", CB_LI, 2, X_PINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Li negative", CB_LI, 2, X_LIT, -0.25, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("Li beyond R (4 R), homogeneous medium", CB_LI, 2, X_OUT_R, 0, V_HOM, S_ALL,
          HRM_ERR_RANGE),
    BI_CB("Li NaN, homogeneous medium", CB_LI, 2, X_NAN, 0, V_HOM, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("transmittance NaN", CB_TR, 1, X_NAN, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("transmittance above 1 (1.5)", CB_TR, 1, X_LIT, 1.5, V_AUTO, S_ALL,
          HRM_ERR_CALLBACK_VALUE),
    BI_CB("transmittance negative", CB_TR, 2, X_LIT, -0.25, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("transmittance +inf", CB_TR, 2, X_PINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    {"transmittance rising along the ray", E_SOLVE, MU_TR_RISING, CB_TR, 0, X_LIT, 0,
     V_TR, S_ALL, HRM_ERR_CALLBACK_VALUE, HRM_ERR_CALLBACK_VALUE, 0, K_CB, T_OK},
    BI_CB("t_of_u NaN", CB_TOU, 2, X_NAN, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("t_of_u -inf", CB_TOU, 2, X_NINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("dt_du negative", CB_DTDU, 2, X_LIT, -1, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("dt_du +inf", CB_DTDU, 2, X_PINF, 0, V_AUTO, S_ALL, HRM_ERR_CALLBACK_VALUE),
    BI_CB("dt_du beyond R (largest finite)", CB_DTDU, 2, X_MAX, 0, V_AUTO, S_ALL, HRM_ERR_RANGE),
    {"u_of_t NaN at t0", E_SOLVE, MU_POISON, CB_UOT, 1, X_NAN, 0, V_UWARP, S_ALL, HRM_ERR_BAD_WARP,
     HRM_ERR_BAD_WARP, 0, K_ENDS, T_SAME},
    BI_CB("u_of_t NaN at a breakpoint", CB_UOT, 3, X_NAN, 0, V_UWARP_BREAKS, S_ALL,
          HRM_ERR_CALLBACK_VALUE),
    {"user warp folding back inside the ray (dt_du < 0)", E_SOLVE, MU_WARP_FOLD, CB_DTDU, 0, X_LIT,
     0, V_UWARP, S_ALL, HRM_ERR_CALLBACK_VALUE, HRM_ERR_CALLBACK_VALUE, 0, K_CB, T_OK},
    BI_CBOK("sigma_a huge within R (R / 2, every call)", CB_SA, X_IN_R, V_CB, HRM_WARN_ROUNDOFF,
            BI_UNRESOLVED),
    BI_CBOK("sigma_s denormal (every call)", CB_SS, X_DENORM, V_CB, HRM_OK, 0),
    BI_CBOK("Le huge within R (R / 2, every call)", CB_LE, X_IN_R, V_CB, HRM_OK, 0),
    BI_CBOK("Le per length R / 2, no extinction (L = 3 R)", CB_LE, X_IN_R, V_EMIT, HRM_OK, 0),
    BI_CBOK("Li denormal (every call)", CB_LI, X_DENORM, V_CB, HRM_OK, 0),
    BI_CBOK("transmittance denormal (every call)", CB_TR, X_DENORM, V_TR, HRM_OK, 0),

    /* hrm_equiangular_warp (an error zeroes *warp) */
    BI_FN("hrm_equiangular_warp: origin NULL", E_EQUI, EQ_ORIGIN_NULL, X_LIT, 0,
          HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_equiangular_warp: dir NULL", E_EQUI, EQ_DIR_NULL, X_LIT, 0, HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_equiangular_warp: light NULL", E_EQUI, EQ_LIGHT_NULL, X_LIT, 0,
          HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_equiangular_warp: warp NULL", E_EQUI, EQ_WARP_NULL, X_LIT, 0, HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_equiangular_warp: dir zero", E_EQUI, EQ_DIR_ZERO, X_LIT, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_equiangular_warp: origin NaN", E_EQUI, EQ_ORIGIN, X_NAN, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_equiangular_warp: dir +inf", E_EQUI, EQ_DIR, X_PINF, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_equiangular_warp: light -inf", E_EQUI, EQ_LIGHT, X_NINF, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_equiangular_warp: light huge (max / 4)", E_EQUI, EQ_LIGHT, X_QMAX, 0,
          HRM_OK),
    BI_FN("hrm_equiangular_warp: light denormal", E_EQUI, EQ_LIGHT, X_DENORM, 0, HRM_OK),

    /* hrm_sphere_breaks (an error zeroes *count where count is given) */
    BI_FN("hrm_sphere_breaks: origin NULL", E_SPHERE, SB_ORIGIN_NULL, X_LIT, 0,
          HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_sphere_breaks: dir NULL", E_SPHERE, SB_DIR_NULL, X_LIT, 0, HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_sphere_breaks: light NULL", E_SPHERE, SB_LIGHT_NULL, X_LIT, 0,
          HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_sphere_breaks: center NULL", E_SPHERE, SB_CENTER_NULL, X_LIT, 0,
          HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_sphere_breaks: out NULL", E_SPHERE, SB_OUT_NULL, X_LIT, 0, HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_sphere_breaks: count NULL", E_SPHERE, SB_COUNT_NULL, X_LIT, 0,
          HRM_ERR_NULL_ARGUMENT),
    BI_FN("hrm_sphere_breaks: radius negative", E_SPHERE, SB_RADIUS, X_LIT, -1, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: radius NaN", E_SPHERE, SB_RADIUS, X_NAN, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: dir zero", E_SPHERE, SB_DIR_ZERO, X_LIT, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: t0 NaN", E_SPHERE, SB_T0, X_NAN, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: t1 < t0", E_SPHERE, SB_T1, X_LIT, -1, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: t1 NaN", E_SPHERE, SB_T1, X_NAN, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: t1 +inf (valid)", E_SPHERE, SB_T1, X_PINF, 0, HRM_OK),
    BI_FN("hrm_sphere_breaks: light NaN", E_SPHERE, SB_LIGHT, X_NAN, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: center +inf", E_SPHERE, SB_CENTER, X_PINF, 0, HRM_ERR_BAD_WARP),
    BI_FN("hrm_sphere_breaks: center huge (max / 4)", E_SPHERE, SB_CENTER, X_QMAX, 0,
          HRM_OK),

    /* names and defaults */
    BI_FN("hrm_status_string: unknown status (7)", E_NAME, NM_STATUS, X_LIT, 7, HRM_OK),
    BI_FN("hrm_status_string: unknown status (-12)", E_NAME, NM_STATUS, X_LIT, -12, HRM_OK),
    BI_FN("hrm_status_string: unknown status (INT_MIN)", E_NAME, NM_STATUS, X_LIT, -2147483648.0,
          HRM_OK),
    BI_FN("hrm_method_name: negative (-1)", E_NAME, NM_METHOD, X_LIT, -1, HRM_OK),
    BI_FN("hrm_method_name: HRM_METHOD_COUNT", E_NAME, NM_METHOD, X_LIT, HRM_METHOD_COUNT, HRM_OK),
    BI_FN("hrm_method_name: INT_MAX", E_NAME, NM_METHOD, X_LIT, 2147483647.0, HRM_OK),
    BI_FN("hrm_default_options: unknown method, then hrm_solve", E_NAME, NM_DEFAULT_OPTIONS, X_LIT,
          999, HRM_ERR_BAD_METHOD),
};

#define BI_NROWS ((int)(sizeof bi_rows / sizeof bi_rows[0]))

/* ------------------------------------------------------------------------
   Values, methods, setups
   ------------------------------------------------------------------------ */
static double bi_largest(void) { return real_is_float() ? (double)FLT_MAX : DBL_MAX; }

/* The range R of the manual's ERRORS for a ray of length T. */
static double bi_range(double T) { return bi_largest() / 1024 / (T > 1 ? T : 1); }

static double bi_value(const bi_row *row)
{
    switch (row->xk) {
    case X_NAN: return (double)NAN;
    case X_PINF: return (double)INFINITY;
    case X_NINF: return -(double)INFINITY;
    case X_MAX: return bi_largest();
    case X_QMAX: return bi_largest() / 4;
    case X_IN_R: return bi_range(BI_T1 - BI_T0) / 2;
    case X_OUT_R: return bi_range(BI_T1 - BI_T0) * 4;
    case X_DENORM: return (real_is_float() ? (double)FLT_MIN : DBL_MIN) / 1024;
    default: return row->lit;
    }
}

static int bi_in_set(int set, hrm_method m)
{
    switch (set) {
    case S_FIXED: return !is_adaptive(m);
    case S_ADAPTIVE: return is_adaptive(m);
    case S_SIMPSON: return m == HRM_SIMPSON;
    case S_DEFAULT: return m == HRM_NESTED_SIMPSON; /* what NULL and method 0 mean */
    case S_RTE: return is_ivp(m) || is_pair(m);
    case S_NOFIT: return m != HRM_SIMPSON && m != HRM_GAUSS_KRONROD && !is_pair(m);
    default: return 1;
    }
}

/* One call of hrm_solve / hrm_transmittance, with everything it reads. The
   options' breakpoints point into the setup itself: set up in place. */
typedef struct bi_setup {
    bi_scene sc;
    hrm_medium m;
    hrm_options o;
    hrm_real t0, t1;
    hrm_real breaks[HRM_MAX_BREAKS + 1];
    int medium_null, options_null, result_null, stats_null;
} bi_setup;

static int bi_variant(const bi_row *row)
{
    if (row->variant != V_AUTO) return row->variant;
    if (row->mut == MU_POISON && row->cb == CB_ST) return V_SIGMA_T;
    if (row->mut == MU_POISON && row->cb == CB_TR) return V_TR;
    if (row->mut == MU_POISON && (row->cb == CB_TOU || row->cb == CB_DTDU || row->cb == CB_UOT))
        return V_UWARP;
    return V_CB;
}

static void bi_baseline(bi_setup *s, int variant, hrm_method method)
{
    int c, i;
    memset(s, 0, sizeof *s);
    bi_scene_init(&s->sc);
    s->m.user = &s->sc;
    s->m.Le = bi_Le;
    s->m.Li = bi_Li;
    if (variant == V_EMIT) {
        s->m.Li = NULL;
        s->m.flags = HRM_EMISSION_PER_LENGTH;
    } else if (variant == V_HOM) {
        s->m.flags = HRM_MEDIUM_HOMOGENEOUS;
        for (c = 0; c < NCH; ++c) {
            s->m.const_sigma_a[c] = (hrm_real)(0.4 * 0.5 * (1 + channel_frac(c)));
            s->m.const_sigma_s[c] = (hrm_real)(0.6 * 0.5 * (1 + channel_frac(c)));
        }
    } else {
        s->m.sigma_a = bi_sigma_a;
        s->m.sigma_s = bi_sigma_s;
        if (variant == V_SIGMA_T || variant == V_RTE) s->m.sigma_t = bi_sigma_t;
        if (variant == V_TR) s->m.transmittance = bi_transmittance;
    }
    s->o = hrm_default_options(method);
    if (!is_adaptive(method)) s->o.steps = 8;
    if (variant == V_COUPLED) s->o.tau_mode = HRM_TAU_COUPLED;
    if (variant == V_RTE) s->o.form = HRM_FORM_RTE;
    if (variant == V_UWARP || variant == V_UWARP_BREAKS) {
        s->o.warp.kind = HRM_WARP_USER;
        s->o.warp.user = &s->sc;
        s->o.warp.t_of_u = bi_t_of_u;
        s->o.warp.dt_du = bi_dt_du;
        s->o.warp.u_of_t = bi_u_of_t;
    }
    if (variant == V_DIST) s->o.warp.kind = HRM_WARP_DISTANCE;
    for (i = 0; i <= HRM_MAX_BREAKS; ++i) s->breaks[i] = (hrm_real)(1.5 + i);
    s->o.breaks = s->breaks;
    s->o.nbreaks = variant == V_UWARP_BREAKS ? 3 : 0;
    s->t0 = (hrm_real)BI_T0;
    s->t1 = (hrm_real)BI_T1;
}

static void bi_mutate(bi_setup *s, const bi_row *row)
{
    double x = bi_value(row);
    hrm_real xr = (hrm_real)x;
    switch (row->mut) {
    case MU_MEDIUM_NULL: s->medium_null = 1; break;
    case MU_RESULT_NULL: s->result_null = 1; break;
    case MU_OPTIONS_NULL: s->options_null = 1; break;
    case MU_STATS_NULL: s->stats_null = 1; break;
    case MU_NO_CALLBACKS:
        s->m.sigma_a = s->m.sigma_s = s->m.sigma_t = s->m.Le = s->m.Li = NULL;
        s->m.transmittance = NULL;
        break;
    case MU_T0: s->t0 = xr; break;
    case MU_T1: s->t1 = xr; break;
    case MU_T1_BELOW: s->t1 = s->t0 - 1; break;
    case MU_T_OVERFLOW:
        s->t0 = (hrm_real)(-0.75 * bi_largest());
        s->t1 = (hrm_real)(0.75 * bi_largest());
        break;
    case MU_T_FAR:
        s->t0 = (hrm_real)1e30;
        s->t1 = (hrm_real)2e30;
        break;
    case MU_T_DENORM:
        s->t0 = 0;
        s->t1 = xr;
        break;
    case MU_T_EMPTY: s->t1 = s->t0; break;
    case MU_METHOD: s->o.method = (hrm_method)(int)x; break;
    case MU_STEPS: s->o.steps = (int)x; break;
    case MU_FORM: s->o.form = (hrm_form)(int)x; break;
    case MU_CONTROL: s->o.control = (hrm_control)(int)x; break;
    case MU_GK_MODE: s->o.gk_mode = (hrm_gk_mode)(int)x; break;
    case MU_GK_RULE: s->o.gk_rule = (hrm_gk_rule)(int)x; break;
    case MU_TAU_MODE: s->o.tau_mode = (hrm_tau_mode)(int)x; break;
    case MU_FIND_JUMPS: s->o.find_jumps = (int)x; break;
    case MU_EXPONENTIAL: s->o.exponential = (int)x; break;
    case MU_FIT_UNSUPPORTED: s->o.exponential = (int)x; break;
    case MU_JITTER:
        s->o.jitter = (int)x;
        s->o.stratified = (int)x;
        break;
    case MU_RTOL: s->o.rtol = xr; break;
    case MU_ATOL: s->o.atol = xr; break;
    case MU_H_MIN: s->o.h_min = xr; break;
    case MU_H_MAX: s->o.h_max = xr; break;
    case MU_H0:
        s->o.h0 = xr;
        if (row->xk == X_DENORM) s->o.h_min = xr;
        break;
    case MU_H_MIN_ABOVE_MAX:
        s->o.h_min = (hrm_real)0.5;
        s->o.h_max = (hrm_real)0.25;
        break;
    case MU_MAX_EVALS: s->o.max_evals = (long)x; break;
    case MU_MAX_EVALS_MAX: s->o.max_evals = LONG_MAX; break;
    case MU_TAU_TOL: s->o.tau_tol = xr; break;
    case MU_NBREAKS: s->o.nbreaks = (int)x; break;
    case MU_BREAKS_NULL:
        s->o.breaks = NULL;
        s->o.nbreaks = 3;
        break;
    case MU_BREAK_VALUE:
        s->o.nbreaks = 3;
        s->breaks[1] = xr;
        break;
    case MU_BREAKS_UNSORTED:
        s->o.nbreaks = 3;
        s->breaks[0] = (hrm_real)3;
        break;
    case MU_BREAKS_DUPLICATE:
        s->o.nbreaks = 3;
        s->breaks[2] = s->breaks[1];
        break;
    case MU_BREAK_BELOW:
        s->o.nbreaks = 3;
        s->breaks[0] = (hrm_real)0.25;
        break;
    case MU_BREAKS_ENDS:
        s->o.nbreaks = 2;
        s->breaks[0] = s->t0;
        s->breaks[1] = s->t1;
        break;
    case MU_BREAK_ABOVE:
        s->o.nbreaks = 3;
        s->breaks[2] = (hrm_real)7;
        break;
    case MU_WARP_KIND: s->o.warp.kind = (hrm_warp_kind)(int)x; break;
    case MU_SIGMA_REF:
        s->o.warp.kind = HRM_WARP_DISTANCE;
        s->o.warp.sigma_ref = xr;
        break;
    case MU_EQ_D:
        s->o.warp.kind = HRM_WARP_EQUIANGULAR;
        s->o.warp.delta = (hrm_real)3;
        s->o.warp.D = xr;
        break;
    case MU_EQ_DELTA:
        s->o.warp.kind = HRM_WARP_EQUIANGULAR;
        s->o.warp.delta = xr;
        s->o.warp.D = (hrm_real)1;
        break;
    case MU_EQ_ON_RAY:
        s->o.warp.kind = HRM_WARP_EQUIANGULAR;
        s->o.warp.delta = (hrm_real)3;
        s->o.warp.D = 0;
        break;
    case MU_UWARP_NULL:
        s->o.warp.kind = HRM_WARP_USER;
        s->o.warp.user = &s->sc;
        s->o.warp.t_of_u = NULL;
        s->o.warp.dt_du = bi_dt_du;
        s->o.warp.u_of_t = bi_u_of_t;
        break;
    case MU_UWARP_DECREASING: s->sc.warp_reverse = 1; break;
    case MU_WARP_EMPTY_RAY:
        s->o.warp.kind = HRM_WARP_DISTANCE;
        s->o.warp.sigma_ref = xr;
        s->t1 = s->t0;
        break;
    case MU_WARP_FOLD: s->sc.warp_fold = 1; break;
    case MU_CONST_SA: s->m.const_sigma_a[NCH - 1] = xr; break;
    case MU_CONST_SS: s->m.const_sigma_s[NCH - 1] = xr; break;
    case MU_FLAGS: s->m.flags |= 0x100u; break;
    case MU_FEATURE: s->m.feature = xr; break;
    case MU_POISON:
        s->sc.target = row->cb;
        s->sc.at_call = row->at_call;
        s->sc.value = xr;
        break;
    case MU_TR_RISING: s->sc.tr_rising = 1; break;
    default: break;
    }
}

/* ------------------------------------------------------------------------
   The checks
   ------------------------------------------------------------------------ */
#define BI_CANARY 0xA5
#define BI_PATTERN 0x5A

/* The result between canaries: the bytes around it must stay as they are. */
typedef struct bi_guard {
    unsigned char before[64];
    hrm_result r;
    unsigned char after[64];
} bi_guard;

typedef struct bi_tguard {
    unsigned char before[64];
    hrm_real Tr[NCH];
    unsigned char after[64];
    hrm_stats stats;
    unsigned char after_stats[64];
} bi_tguard;

static int bi_bytes_are(const unsigned char *p, size_t n, unsigned char v)
{
    size_t i;
    for (i = 0; i < n; ++i)
        if (p[i] != v) return 0;
    return 1;
}

static long bi_source_calls(const bi_scene *s) { return s->calls[CB_LE] + s->calls[CB_LI]; }

static long bi_medium_calls(const bi_scene *s)
{
    return s->calls[CB_SA] + s->calls[CB_SS] + s->calls[CB_ST] + s->calls[CB_TR];
}

static int bi_stats_zero(const hrm_stats *st)
{
    return st->evals == 0 && st->medium_evals == 0 && st->steps == 0 && st->rejected == 0;
}

/* The error result of hrm_solve: L = 0, Tr = 1, error = -1, no jump. */
static int bi_error_result(const hrm_result *r)
{
    int c, ok = r->njumps == 0;
    for (c = 0; c < NCH; ++c) ok &= r->L[c] == 0 && r->Tr[c] == 1 && r->error[c] == -1;
    for (c = 0; c < HRM_MAX_JUMPS; ++c) ok &= r->jumps[c] == 0;
    return ok;
}

/* A valid call's estimate: finite, L >= 0, 0 <= Tr <= 1, error -1
   (fixed-step) or finite and >= 0 (adaptive), 0 <= njumps <= HRM_MAX_JUMPS. */
static int bi_valid_result(const hrm_result *r, hrm_method m)
{
    int c, ok = r->njumps >= 0 && r->njumps <= HRM_MAX_JUMPS;
    for (c = 0; c < NCH; ++c) {
        double L = (double)r->L[c], Tr = (double)r->Tr[c], e = (double)r->error[c];
        ok &= finite_d(L) && L >= 0 && Tr >= 0 && Tr <= 1;
        ok &= is_adaptive(m) ? finite_d(e) && e >= 0 : e == -1;
    }
    return ok;
}

/* The solve stopped at the bad value: no callback called after it. A value
   beyond the range is one factor of a product (a coefficient or source
   times dt/du, a source's two terms) that is known only once the sample's
   other callbacks have returned (and the transmittance layer has sampled
   sigma up to it): there the callback itself is not called again. */
static int bi_stopped(const bi_scene *s, hrm_status st)
{
    return st == HRM_ERR_RANGE ? s->after_cb[s->target] == 0 : s->after == 0;
}

static hrm_status bi_call_solve(bi_setup *s, bi_guard *g)
{
    memset(g, BI_CANARY, sizeof *g);
    memset(&g->r, BI_PATTERN, sizeof g->r);
    return hrm_solve(s->medium_null ? NULL : &s->m, s->t0, s->t1, s->options_null ? NULL : &s->o,
                     s->result_null ? NULL : &g->r);
}

static hrm_status bi_call_tr(bi_setup *s, bi_tguard *g)
{
    memset(g, BI_CANARY, sizeof *g);
    memset(g->Tr, BI_PATTERN, sizeof g->Tr);
    memset(&g->stats, BI_PATTERN, sizeof g->stats);
    return hrm_transmittance(s->medium_null ? NULL : &s->m, s->t0, s->t1,
                             s->options_null ? NULL : &s->o, s->result_null ? NULL : g->Tr,
                             s->stats_null ? NULL : &g->stats);
}

/* The status a row expects of method m. */
static hrm_status bi_want(const bi_row *row, hrm_method m)
{
    return is_adaptive(m) ? row->want_ad : row->want;
}

/* hrm_solve for one row and method: the baseline, then the mutation. */
static void bi_run_solve(const bi_row *row, hrm_method m)
{
    const char *mn = hrm_method_name(m);
    int variant = bi_variant(row);
    hrm_status want = bi_want(row, m), st;
    bi_setup s;
    bi_guard g;
    unsigned char mb[sizeof(hrm_medium)], ob[sizeof(hrm_options)];
    long base_calls = 0;

    /* without the mutation: HRM_OK, and the poisoned callback is called */
    bi_baseline(&s, variant, m);
    st = bi_call_solve(&s, &g);
    CHECK_INT(st, HRM_OK, "%s, %s: the baseline without the mutation (%s)", row->what, mn,
              hrm_status_string(st));
    if (row->mut == MU_POISON || row->mut == MU_TR_RISING || row->mut == MU_WARP_FOLD)
        base_calls = s.sc.calls[row->cb];
    if (row->kind == K_CB && row->mut == MU_POISON)
        CHECK(base_calls >= row->at_call,
              "%s, %s: the baseline calls %s %ld times, the row poisons call %ld",
              row->what, mn, bi_cb_name[row->cb], base_calls, row->at_call);

    /* with it */
    bi_baseline(&s, variant, m);
    bi_mutate(&s, row);
    memcpy(mb, &s.m, sizeof mb);
    memcpy(ob, &s.o, sizeof ob);
    st = bi_call_solve(&s, &g);
    if (row->kind == K_VALID && is_adaptive(m) && st >= 0 && (row->also_ad & BI_W(st)))
        want = st; /* one of the statuses the row allows */
    if (row->kind == K_VALID && !is_adaptive(m) && want == HRM_OK && st == HRM_WARN_TOLERANCE)
        want = st; /* a fixed step's L past twice its physical bound (a ray
                      1e30 long, sigma R / 2): the bound, with a warning */
    CHECK_INT(st, want, "%s, %s: status %s", row->what, mn, hrm_status_string(st));
    CHECK(bi_bytes_are(g.before, sizeof g.before, BI_CANARY) &&
              bi_bytes_are(g.after, sizeof g.after, BI_CANARY),
          "%s, %s: the bytes around the result were written", row->what, mn);
    CHECK(memcmp(mb, &s.m, sizeof mb) == 0 && memcmp(ob, &s.o, sizeof ob) == 0,
          "%s, %s: the medium or the options were written", row->what, mn);
    if (s.result_null) {
        CHECK(bi_bytes_are((const unsigned char *)&g.r, sizeof g.r, BI_PATTERN) && s.sc.seq == 0,
              "%s, %s: no result, nothing written and no callback called (%ld calls)", row->what,
                                                                          mn,
              s.sc.seq);
        return;
    }
    if (row->kind == K_VALID) {
        CHECK(bi_valid_result(&g.r, m),
              "%s, %s: a finite estimate (L %g, Tr %g, error %g, njumps %d)", row->what, mn,
              (double)g.r.L[NCH - 1], (double)g.r.Tr[NCH - 1], (double)g.r.error[NCH - 1],
               g.r.njumps);
        return;
    }
    CHECK(bi_error_result(&g.r), "%s, %s: the error result (L %g, Tr %g, error %g, njumps %d)",
          row->what, mn, (double)g.r.L[NCH - 1], (double)g.r.Tr[NCH - 1],
          (double)g.r.error[NCH - 1], g.r.njumps);
    if (row->kind == K_ARG || row->kind == K_ENDS) {
        long other = s.sc.seq - s.sc.calls[CB_UOT];
        CHECK(bi_stats_zero(&g.r.stats) && other == 0 && (row->kind == K_ENDS || s.sc.seq == 0),
              "%s, %s: rejected before any evaluation (stats %ld %ld %ld %ld, %ld callback calls, "
              "%ld of u_of_t)", row->what, mn, g.r.stats.evals, g.r.stats.medium_evals,
              g.r.stats.steps, g.r.stats.rejected, s.sc.seq, s.sc.calls[CB_UOT]);
    } else {
        CHECK(g.r.stats.evals >= 0 && g.r.stats.evals <= bi_source_calls(&s.sc) &&
                  g.r.stats.medium_evals >= 0 && g.r.stats.medium_evals <= bi_medium_calls(&s.sc) &&
                  g.r.stats.steps >= 0 && g.r.stats.rejected >= 0,
              "%s, %s: the stats counted so far (evals %ld of %ld source calls, medium_evals %ld "
              "of %ld medium calls)", row->what, mn, g.r.stats.evals, bi_source_calls(&s.sc),
              g.r.stats.medium_evals, bi_medium_calls(&s.sc));
        if (row->mut == MU_POISON) {
            CHECK(s.sc.poisoned != 0, "%s, %s: the bad value was returned", row->what, mn);
            CHECK(bi_stopped(&s.sc, want),
                  "%s, %s: callbacks called after the bad value: %ld (%ld of %s)", row->what, mn,
                  s.sc.after, s.sc.after_cb[row->cb], bi_cb_name[row->cb]);
        }
    }
}

/* hrm_transmittance for one row and method: the status where it reads what
   the row mutates, HRM_OK where it does not. */
static void bi_run_transmittance(const bi_row *row, hrm_method m)
{
    const char *mn = hrm_method_name(m);
    int variant = bi_variant(row), c, ok = 1;
    hrm_status want = bi_want(row, m), st;
    bi_setup s;
    bi_tguard g;
    long base_calls = 0;

    bi_baseline(&s, variant, m);
    st = bi_call_tr(&s, &g);
    CHECK_INT(st, HRM_OK, "%s, %s: hrm_transmittance's baseline (%s)", row->what, mn,
              hrm_status_string(st));
    CHECK_INT(bi_source_calls(&s.sc), 0, "%s, %s: hrm_transmittance calls Le or Li", row->what, mn);
    if (row->cb >= 0) base_calls = s.sc.calls[row->cb];
    /* what hrm_transmittance does not read cannot be wrong for it: Le, Li,
       a warp on a finite ray (its parameters are still checked), and a
       callback it calls fewer times than the row's */
    if (row->tr == T_OK || (row->tr == T_CLIP && !is_adaptive(m)) ||
        (row->mut == MU_POISON && base_calls < (row->at_call ? row->at_call : 1)))
        want = HRM_OK;
    else if (row->tr == T_CLIP)
        want = HRM_WARN_RTOL_CLIPPED;
    bi_baseline(&s, variant, m);
    bi_mutate(&s, row);
    st = bi_call_tr(&s, &g);
    CHECK_INT(st, want, "%s, %s: hrm_transmittance's status %s", row->what, mn,
              hrm_status_string(st));
    CHECK(bi_bytes_are(g.before, sizeof g.before, BI_CANARY) &&
              bi_bytes_are(g.after, sizeof g.after, BI_CANARY) &&
              bi_bytes_are(g.after_stats, sizeof g.after_stats, BI_CANARY),
          "%s, %s: hrm_transmittance wrote around Tr or stats", row->what, mn);
    CHECK_INT(bi_source_calls(&s.sc), 0, "%s, %s: hrm_transmittance calls Le or Li", row->what, mn);
    if (s.stats_null)
        CHECK(bi_bytes_are((const unsigned char *)&g.stats, sizeof g.stats, BI_PATTERN),
              "%s, %s: hrm_transmittance without stats wrote them", row->what, mn);
    if (s.result_null) {
        /* no Tr: the stats given are the error's (zero) */
        CHECK(bi_stats_zero(&g.stats) && s.sc.seq == 0,
              "%s, %s: hrm_transmittance without Tr: stats zero, no callback called", row->what,
               mn);
        return;
    }
    for (c = 0; c < NCH; ++c) {
        double Tr = (double)g.Tr[c];
        ok &= want < 0 ? Tr == 1 : Tr >= 0 && Tr <= 1;
    }
    CHECK(ok, "%s, %s: hrm_transmittance's Tr (%g)", row->what, mn, (double)g.Tr[NCH - 1]);
    if (s.stats_null) return;
    CHECK(g.stats.evals == 0, "%s, %s: hrm_transmittance's stats.evals %ld", row->what, mn,
          g.stats.evals);
    if (want < 0 && (row->kind == K_ARG || row->kind == K_ENDS))
        CHECK(bi_stats_zero(&g.stats), "%s, %s: hrm_transmittance rejected before any evaluation",
              row->what, mn);
    if (want < 0 && row->mut == MU_POISON)
        CHECK(bi_stopped(&s.sc, want),
              "%s, %s: hrm_transmittance called callbacks after the bad value: %ld",
              row->what, mn, s.sc.after);
}

/* hrm_equiangular_warp: origin (0,0,0), dir (1,0,0), light (3,1,0). An
   error leaves the warp zeroed (HRM_WARP_NONE: "overwritten whole"). */
typedef struct bi_wguard {
    unsigned char before[64];
    hrm_warp w;
    unsigned char after[64];
} bi_wguard;

static void bi_run_equi(const bi_row *row)
{
    hrm_real origin[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, light[3] = {3, 1, 0};
    hrm_real x = (hrm_real)bi_value(row);
    bi_wguard g;
    hrm_status st;
    memset(&g, BI_CANARY, sizeof g);
    st = hrm_equiangular_warp(origin, dir, light, &g.w);
    CHECK(st == HRM_OK && g.w.kind == HRM_WARP_EQUIANGULAR && g.w.delta == 3 && g.w.D == 1,
          "%s: the baseline (%s, delta %g, D %g)", row->what, hrm_status_string(st),
          (double)g.w.delta, (double)g.w.D);
    if (row->mut == EQ_DIR_ZERO) dir[0] = 0;
    if (row->mut == EQ_ORIGIN) origin[1] = x;
    if (row->mut == EQ_DIR) dir[0] = x;
    if (row->mut == EQ_LIGHT) light[1] = x;
    memset(&g, BI_CANARY, sizeof g);
    memset(&g.w, BI_PATTERN, sizeof g.w);
    st = hrm_equiangular_warp(row->mut == EQ_ORIGIN_NULL ? NULL : origin,
                              row->mut == EQ_DIR_NULL ? NULL : dir,
                              row->mut == EQ_LIGHT_NULL ? NULL : light,
                              row->mut == EQ_WARP_NULL ? NULL : &g.w);
    CHECK_INT(st, row->want, "%s: status %s", row->what, hrm_status_string(st));
    CHECK(bi_bytes_are(g.before, sizeof g.before, BI_CANARY) &&
              bi_bytes_are(g.after, sizeof g.after, BI_CANARY),
          "%s: the bytes around the warp were written", row->what);
    if (row->mut == EQ_WARP_NULL) {
        CHECK(bi_bytes_are((const unsigned char *)&g.w, sizeof g.w, BI_PATTERN),
              "%s: warp NULL, yet written",
              row->what);
    } else if (row->want < 0) {
        CHECK(g.w.kind == HRM_WARP_NONE && g.w.sigma_ref == 0 && g.w.delta == 0 && g.w.D == 0 &&
                  g.w.user == NULL && g.w.t_of_u == NULL && g.w.dt_du == NULL && g.w.u_of_t == NULL,
              "%s: the warp zeroed on error (kind %d)", row->what, (int)g.w.kind);
    } else {
        /* the light (3, x, 0) from the x axis: delta 3, D |x| */
        /* (a denormal keeps fewer digits: sqrt(eps) relative) */
        CHECK(g.w.kind == HRM_WARP_EQUIANGULAR && g.w.delta == 3 &&
                  fabs((double)g.w.D - fabs((double)x)) <= sqrt(real_eps()) * fabs((double)x),
              "%s: delta 3 (got %g), D = %g (got %g)", row->what, (double)g.w.delta, (double)x,
              (double)g.w.D);
    }
}

/* hrm_sphere_breaks: origin (0,0,0), dir (1,0,0), light (5,4,0), sphere
   (5,2,0) of radius 1, t in (0, 10): two breakpoints. An error leaves
   *count 0 wherever count is given, out untouched. */
typedef struct bi_sguard {
    unsigned char before[64];
    hrm_real out[2];
    unsigned char after[64];
    int count;
    unsigned char after_count[64];
} bi_sguard;

static void bi_run_sphere(const bi_row *row)
{
    hrm_real origin[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, light[3] = {5, 4, 0}, center[3] = {5, 2, 0};
    hrm_real radius = 1, t0 = 0, t1 = 10, x = (hrm_real)bi_value(row);
    bi_sguard g;
    hrm_status st;
    memset(&g, BI_CANARY, sizeof g);
    st = hrm_sphere_breaks(origin, dir, light, center, radius, t0, t1, g.out, &g.count);
    CHECK(st == HRM_OK && g.count == 2 && g.out[0] > 0 && g.out[0] < g.out[1] && g.out[1] < 10,
          "%s: the baseline (%s, count %d)", row->what, hrm_status_string(st), g.count);
    if (row->mut == SB_RADIUS) radius = x;
    if (row->mut == SB_DIR_ZERO) dir[0] = 0;
    if (row->mut == SB_T0) t0 = x;
    if (row->mut == SB_T1) t1 = x;
    if (row->mut == SB_LIGHT) light[1] = x;
    if (row->mut == SB_CENTER) center[1] = x;
    memset(&g, BI_CANARY, sizeof g);
    memset(g.out, BI_PATTERN, sizeof g.out);
    memset(&g.count, BI_PATTERN, sizeof g.count);
    st = hrm_sphere_breaks(row->mut == SB_ORIGIN_NULL ? NULL : origin,
                           row->mut == SB_DIR_NULL ? NULL : dir,
                           row->mut == SB_LIGHT_NULL ? NULL : light,
                           row->mut == SB_CENTER_NULL ? NULL : center, radius, t0, t1,
                           row->mut == SB_OUT_NULL ? NULL : g.out,
                           row->mut == SB_COUNT_NULL ? NULL : &g.count);
    CHECK_INT(st, row->want, "%s: status %s", row->what, hrm_status_string(st));
    CHECK(bi_bytes_are(g.before, sizeof g.before, BI_CANARY) &&
              bi_bytes_are(g.after, sizeof g.after, BI_CANARY) &&
              bi_bytes_are(g.after_count, sizeof g.after_count, BI_CANARY),
          "%s: the bytes around out or count were written", row->what);
    if (row->want < 0) {
        CHECK(bi_bytes_are((const unsigned char *)g.out, sizeof g.out, BI_PATTERN),
              "%s: out written on error", row->what);
        if (row->mut == SB_COUNT_NULL)
            CHECK(bi_bytes_are((const unsigned char *)&g.count, sizeof g.count, BI_PATTERN),
                  "%s: count NULL, yet written", row->what);
        else
            CHECK(g.count == 0, "%s: *count 0 on error (got %d)", row->what, g.count);
    } else {
        int ok = g.count >= 0 && g.count <= 2, i;
        for (i = 0; ok && i < g.count; ++i)
            ok &= finite_d((double)g.out[i]) && g.out[i] > t0 &&
                  (i == 0 || g.out[i] > g.out[i - 1]);
        CHECK(ok, "%s: 0 to 2 ascending breakpoints in (t0, t1) (count %d)", row->what, g.count);
    }
}

static void bi_run_name(const bi_row *row)
{
    int v = (int)bi_value(row);
    if (row->mut == NM_STATUS) {
        CHECK(strcmp(hrm_status_string(HRM_ERR_RANGE), "unknown status") != 0 &&
                  strcmp(hrm_status_string(HRM_OK), "ok") == 0,
              "%s: the baseline names a known status", row->what);
        CHECK(strcmp(hrm_status_string((hrm_status)v), "unknown status") == 0, "%s: \"%s\"",
              row->what,
              hrm_status_string((hrm_status)v));
    } else if (row->mut == NM_METHOD) {
        CHECK(strcmp(hrm_method_name(HRM_SIMPSON), "simpson") == 0,
              "%s: the baseline names Simpson",
              row->what);
        CHECK(strcmp(hrm_method_name((hrm_method)v), "?") == 0, "%s: \"%s\"", row->what,
              hrm_method_name((hrm_method)v));
    } else {
        bi_setup s;
        bi_guard g;
        hrm_status st;
        bi_baseline(&s, V_CB, HRM_SIMPSON);
        s.o = hrm_default_options(HRM_SIMPSON);
        CHECK_INT(bi_call_solve(&s, &g), HRM_OK, "%s: the baseline", row->what);
        s.o = hrm_default_options((hrm_method)v);
        CHECK_INT((int)s.o.method, v, "%s: the method is kept", row->what);
        bi_scene_init(&s.sc);
        st = bi_call_solve(&s, &g);
        CHECK_INT(st, row->want, "%s: status %s", row->what, hrm_status_string(st));
        CHECK(bi_error_result(&g.r) && bi_stats_zero(&g.r.stats) && s.sc.seq == 0,
              "%s: the error result, nothing called", row->what);
    }
}

/* Every row, every method of its set. */
static void bi_table(void)
{
    int i, mi, n = 0;
    for (i = 0; i < BI_NROWS; ++i) {
        const bi_row *row = &bi_rows[i];
        if (row->entry == E_EQUI) {
            bi_run_equi(row);
        } else if (row->entry == E_SPHERE) {
            bi_run_sphere(row);
        } else if (row->entry == E_NAME) {
            bi_run_name(row);
        } else {
            for (mi = 0; mi < N_METHODS_ALL; ++mi) {
                hrm_method m = every_method[mi];
                if (!bi_in_set(row->set, m)) continue;
                bi_run_solve(row, m);
                bi_run_transmittance(row, m);
            }
        }
        ++n;
    }
    if (verbose()) NOTE("%d rows", n);
}

/* Two classes of bad input at once: the status is the one of the class
   the manual's BAD INPUT table lists first (the interval, the options, the
   breakpoints, the warp, the medium: the order hrm checks them in), for
   every method, hrm_solve and hrm_transmittance, with the error's result. */
static void bi_order_sig(void *user, hrm_real t, hrm_real sa[NCH], hrm_real ss[NCH])
{
    int c;
    (void)user;
    for (c = 0; c < NCH; ++c) {
        sa[c] = (hrm_real)(0.1 + 0.05 * (double)t);
        ss[c] = (hrm_real)0.3;
    }
}

static void bi_order(void)
{
    static const hrm_real unsorted[2] = {4, 2};
    enum { N_PAIRS = 6 };
    static const char *const what[N_PAIRS] = {
        "t1 < t0 and steps < 0", "steps < 0 and unsorted breakpoints", "rtol < 0 and unsorted breakpoints",
        "unsorted breakpoints and D < 0", "D < 0 and an unknown medium flag",
        "a negative constant and one beyond R"};
    static const hrm_status want[N_PAIRS] = {HRM_ERR_BAD_INTERVAL, HRM_ERR_BAD_STEPS, HRM_ERR_BAD_OPTION,
                                             HRM_ERR_BAD_BREAKS, HRM_ERR_BAD_WARP, HRM_ERR_BAD_MEDIUM};
    int k, mi, c;
    for (k = 0; k < N_PAIRS; ++k)
        for (mi = 0; mi < N_METHODS_ALL; ++mi) {
            hrm_medium m;
            hrm_options o = hrm_default_options(every_method[mi]);
            hrm_result r;
            hrm_real t0 = (hrm_real)0.5, t1 = (hrm_real)6.5, Tr[NCH];
            hrm_stats st;
            if (k == 5 && NCH < 2) continue; /* two channels needed */
            memset(&m, 0, sizeof m);
            m.sigma = bi_order_sig;
            m.Li = spectrum_one;
            o.warp.kind = HRM_WARP_EQUIANGULAR;
            o.warp.delta = 3;
            o.warp.D = 1;
            if (k == 0) {
                t1 = 0;
                o.steps = -1;
            }
            if (k == 1) o.steps = -1;
            if (k == 2) o.rtol = -1;
            if (k >= 1 && k <= 3) {
                o.breaks = unsorted;
                o.nbreaks = 2;
            }
            if (k == 3 || k == 4) o.warp.D = -1;
            if (k == 4) m.flags = 64u;
            if (k == 5) {
                m.sigma = NULL;
                m.flags = HRM_MEDIUM_HOMOGENEOUS;
                for (c = 0; c < NCH; ++c) m.const_sigma_a[c] = m.const_sigma_s[c] = (hrm_real)0.1;
                m.const_sigma_a[0] = real_is_float() ? (hrm_real)FLT_MAX : (hrm_real)DBL_MAX;
                m.const_sigma_a[1] = -1;
            }
            CHECK_INT(hrm_solve(&m, t0, t1, &o, &r), want[k], "%s, %s: hrm_solve's status", what[k],
                      hrm_method_name(every_method[mi]));
            CHECK(r.L[0] == 0 && r.Tr[0] == 1 && r.stats.evals == 0, "%s, %s: the error's result", what[k],
                  hrm_method_name(every_method[mi]));
            CHECK_INT(hrm_transmittance(&m, t0, t1, &o, Tr, &st), want[k], "%s, %s: hrm_transmittance's status",
                      what[k], hrm_method_name(every_method[mi]));
        }
}

/* options.workspace out of range: one byte short of hrm_workspace_size,
   not aligned to 16, NULL with a size: HRM_ERR_BAD_OPTION before any
   callback, the error's result, every method, both entry points; NULL
   with 0 (the stack) and exactly its size: valid. */
static void bi_workspace(void)
{
    unsigned char *mem = (unsigned char *)malloc(1 << 21), *ws;
    int mi, k;
    if (!mem) {
        CHECK(0, "workspace: no memory");
        return;
    }
    ws = mem + (16 - (size_t)((uintptr_t)mem % 16)) % 16;
    for (mi = 0; mi < N_METHODS_ALL; ++mi)
        for (k = 0; k < 5; ++k) {
            static const char *const what[5] = {"one byte short", "not on 16 bytes", "NULL with a size",
                                                "none", "exactly its size"};
            hrm_medium m;
            hrm_options o = hrm_default_options(every_method[mi]);
            hrm_result r;
            hrm_real Tr[NCH];
            hrm_stats st;
            size_t need = hrm_workspace_size(&o);
            hrm_status want = k < 3 ? HRM_ERR_BAD_OPTION : HRM_OK;
            memset(&m, 0, sizeof m);
            m.sigma = bi_order_sig;
            m.Li = spectrum_one;
            o.workspace = k == 3 ? NULL : k == 2 ? NULL : k == 1 ? ws + 8 : ws;
            o.workspace_size = k == 3 ? 0 : k == 0 ? need - 1 : need;
            CHECK(need > 0 && need % 16 == 0, "%s: hrm_workspace_size %lu, a multiple of 16",
                  hrm_method_name(every_method[mi]), (unsigned long)need);
            CHECK_INT(hrm_solve(&m, (hrm_real)0.5, (hrm_real)6.5, &o, &r), want, "%s, workspace %s: hrm_solve",
                      hrm_method_name(every_method[mi]), what[k]);
            if (k < 3)
                CHECK(r.L[0] == 0 && r.Tr[0] == 1 && r.stats.evals == 0 && r.stats.medium_evals == 0,
                      "%s, workspace %s: the error's result, no callback", hrm_method_name(every_method[mi]),
                      what[k]);
            CHECK_INT(hrm_transmittance(&m, (hrm_real)0.5, (hrm_real)6.5, &o, Tr, &st), want,
                      "%s, workspace %s: hrm_transmittance", hrm_method_name(every_method[mi]), what[k]);
        }
    free(mem);
}

void bad_input_tests(void)
{
    RUN_GROUP(bi_table);
    RUN_GROUP(bi_order);
    RUN_GROUP(bi_workspace);
}
