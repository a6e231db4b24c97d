/* hrm.h - higher-order ray marching for the radiative transfer equation.
   Version 0.1.0. Single-file C99 library; no dependencies but libm.

   ==========================================================================
   QUICK START
   ==========================================================================
   Define HRM_IMPLEMENTATION in exactly one C or C++ file before including
   this header; every other file includes it plainly.

   ---- quick start begin ----
   #define HRM_IMPLEMENTATION
   #include "hrm.h"
   #include <stdio.h>

   // In-scattered radiance toward the camera at distance t along the ray,
   // phase function and light transmittance included (the host's job).
   static void sun(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
       int c;
       (void)user; (void)t;
       for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)0.25;
   }

   int main(void) {
       hrm_medium fog = {0};            // zero: every term absent
       hrm_options opt = hrm_default_options(HRM_SIMPSON);
       hrm_result res;
       int c;
       fog.flags = HRM_MEDIUM_HOMOGENEOUS;
       for (c = 0; c < HRM_CHANNELS; ++c) {
           fog.const_sigma_a[c] = (hrm_real)0.1;
           fog.const_sigma_s[c] = (hrm_real)0.5;
       }
       fog.Li = sun;
       opt.steps = 16;
       if (hrm_solve(&fog, 0, 10, &opt, &res) < 0) return 1;
       // pixel = res.L + res.Tr * L_surface
       printf("L=%g Tr=%g samples=%ld\n", (double)res.L[0], (double)res.Tr[0],
              res.stats.evals);
       return 0;
   }
   ---- quick start end ----

   ==========================================================================
   DEFINITIONS
   ==========================================================================
   t        distance along the ray from its origin. A call integrates from
            t0 (the camera end) to t1 (a surface, or where the medium ends).
   sigma_a  absorption coefficient (1/length), sigma_s scattering coefficient,
   sigma_t  extinction sigma_a + sigma_s (unless given separately).
   tau      optical depth from t0: tau(t) = integral of sigma_t from t0 to t.
   Tr       transmittance exp(-tau). The result's Tr is Tr(t0, t1).
   Le       emitted radiance. The source is sigma_a*Le (Munoz 2014 eq. 1,
            pbrt-v4), or Le itself with HRM_EMISSION_PER_LENGTH (pbrt-v2,
            Cycles, where emission is already a per-length source).
   Li       in-scattered radiance toward the camera: phase function and the
            light's own transmittance already applied. hrm never looks
            inside it; the host computes it (shadow rays, photon map ...).
   S        source S(t) = sigma_a*Le + sigma_s*Li.
   L        radiance the medium adds: L = integral over [t0,t1] of Tr(t0,t)*S(t).
            The host composes  L_total = L + Tr * L_surface.
   sample / evaluation
            one evaluation of the source (Le and/or Li) at one distance t.
            This is the cost that matters (each Li is a shadow ray) and is
            counted in hrm_stats.evals. A solver evaluates the callbacks at
            most once per distinct abscissa.
   medium evaluation
            one evaluation of the medium's coefficients (sigma callbacks or
            the transmittance callback) at one abscissa: hrm_stats.medium_evals.
   step     one step of an IVP solver, one panel of Simpson's rule, one
            sample of Monte Carlo, one segment of the rectangle rule.

   ==========================================================================
   THE SCENE: hrm_medium
   ==========================================================================
   Every member is optional. A NULL callback is an absent term, and an absent
   term is never called and costs nothing:
     sigma_a, sigma_s  NULL: zero.     sigma_t  NULL: sigma_a + sigma_s.
     Le                NULL: no emission (and never called where sigma_a = 0
                       in every channel, unless HRM_EMISSION_PER_LENGTH).
     Li                NULL: no scattering (and never called where sigma_s = 0
                       in every channel).
     transmittance     closed-form Tr(ta, tb) of the eye ray. NULL: hrm
                       integrates sigma_t with the chosen method.
   Homogeneous media: set flags |= HRM_MEDIUM_HOMOGENEOUS and fill
   const_sigma_a / const_sigma_s. The sigma callbacks and the transmittance
   callback are then ignored, Tr is exp(-sigma_t*(tb-ta)) in closed form and
   no medium evaluation is ever made.
   Callbacks must return finite values; coefficients must also be >= 0 and a
   transmittance must lie in [0, 1]. Anything else stops the solve with
   HRM_ERR_CALLBACK_VALUE.

   ==========================================================================
   CONFIGURATION (define before including)
   ==========================================================================
   HRM_IMPLEMENTATION  compile the implementation into this file.
   HRM_STATIC          make every function static (private to one file).
   HRM_REAL            scalar type, double by default; float works too.
   HRM_CHANNELS        colour channels, 3 by default.
   HRM_ASSERT(x)       internal invariants only (never user input);
                       assert() by default.
   HRM_SQRT, HRM_EXP, HRM_EXPM1, HRM_LOG, HRM_LOG1P, HRM_POW, HRM_FABS,
   HRM_TAN, HRM_ATAN   math functions; by default the libm function that
                       matches sizeof(HRM_REAL) (expf for float, exp for
                       double).

   ==========================================================================
   ERRORS
   ==========================================================================
   Every call that can fail returns hrm_status: HRM_OK (0), a negative error
   (no usable answer: the result holds L = 0, Tr = 1 and the stats counted so
   far) or a positive warning (a usable estimate that missed what was asked;
   the result holds it). hrm_status_string() names each. Bad input never
   aborts, never crashes and never writes anything but the result.

   ==========================================================================
   THREAD SAFETY
   ==========================================================================
   hrm holds no global or static mutable state and never allocates. Calls
   are thread-safe and re-entrant: an Li callback may call hrm_transmittance
   (or hrm_solve) for its shadow ray. Randomness (Monte Carlo, jitter) comes
   from options.seed alone: the same inputs give the same answer.

   ==========================================================================
   ACCURACY AND COST   (N = options.steps; evaluations = source samples)
   ==========================================================================
   method               order  evaluations         notes
   HRM_RECTANGLE        2      N                   midpoint of each segment;
                        (1)                        with jitter, one random
                                                   offset per ray: order 1,
                                                   unbiased over seeds
   HRM_SIMPSON          4      2N + 1              N panels
   HRM_MONTE_CARLO      N^-1/2 N                   stratified: one sample per
                        (N^-3/2 stratified, smooth) segment
   HRM_EULER            1      N
   HRM_RK4              4      2N + 1              2 new per step (c = 1/2
                                                   shared by two stages)
   HRM_ADAMS_BASHFORTH  4      N + 3 (N >= 4)      4-step, started with 3 RK4
                                                   steps; 1 new per step
   Orders are for smooth integrands; a discontinuity (a sharp shadow) drags
   every fixed-step method down to first order.
   In a heterogeneous medium without a closed-form transmittance, the rule
   computes tau at its own nodes from the same sigma_t samples at its own
   order (no extra medium evaluations).

   Two forms for the IVP solvers (options.form):
   HRM_FORM_OPTICAL_DEPTH (default) state (tau, A), dtau/dt = sigma_t,
       dA/dt = exp(-tau)*S. Nothing feeds back, so it is stable at any step:
       L >= 0 and 0 <= Tr <= 1 however thick the medium (in Adams-Bashforth a
       positivity limiter keeps each increment's sign when every history
       value agrees on it; it is inactive on resolved problems).
   HRM_FORM_RTE  dL/dt = S - sigma_t*L (Munoz 2014 eq. 1) with Tr alongside,
       marched from t1 to t0 in the direction light travels. Explicit
       methods blow up once h*sigma_t passes their stability limit (2 for
       Euler, about 2.79 for RK4, 0.3 for Adams-Bashforth 4): kept so that
       the stiffness the papers report can be reproduced and measured.
   Neither form is accurate when one step spans many mean free paths; the
   optical-depth form only stays bounded there.

   ==========================================================================
   WHAT hrm DOES NOT DO
   ==========================================================================
   It does not trace rays, sample lights or evaluate phase functions: Li is
   the host's. It does not handle media whose coefficients depend on
   direction, nor multiple scattering beyond what the host puts into Li.

   LICENSE: MIT, see the end of this file.
*/
#ifndef HRM_H
#define HRM_H

#define HRM_VERSION_MAJOR 0
#define HRM_VERSION_MINOR 1
#define HRM_VERSION_PATCH 0

#include <stdint.h>

#ifndef HRM_REAL
#define HRM_REAL double
#endif
#ifndef HRM_CHANNELS
#define HRM_CHANNELS 3
#endif
#ifdef HRM_STATIC
#define HRM_API static
#else
#define HRM_API extern
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef HRM_REAL hrm_real;

/* Status codes: one list, so the enum and the messages never drift apart. */
#define HRM__STATUS_LIST(X)                                                   \
    X(HRM_OK, 0, "ok")                                                        \
    X(HRM_WARN_MAX_EVALS, 1, "evaluation budget exhausted before the tolerance was met; best estimate returned") \
    X(HRM_WARN_H_MIN, 2, "minimum step reached before the tolerance was met; best estimate returned") \
    X(HRM_WARN_STORAGE, 3, "interval storage exhausted before the tolerance was met; best estimate returned") \
    X(HRM_WARN_RTOL_CLIPPED, 4, "rtol below 100 machine epsilons was raised to that floor") \
    X(HRM_WARN_ROUNDOFF, 5, "round-off prevents the requested tolerance; best estimate returned") \
    X(HRM_ERR_NULL_ARGUMENT, -1, "a required pointer argument is NULL")      \
    X(HRM_ERR_BAD_INTERVAL, -2, "t0 or t1 is not finite, or t1 < t0")       \
    X(HRM_ERR_BAD_STEPS, -3, "options.steps is negative")                    \
    X(HRM_ERR_BAD_METHOD, -4, "unknown method")                              \
    X(HRM_ERR_BAD_OPTION, -5, "an option is out of range (form, tolerances, step bounds, budget)") \
    X(HRM_ERR_BAD_MEDIUM, -6, "a constant coefficient of the medium is negative or not finite") \
    X(HRM_ERR_CALLBACK_VALUE, -7, "a callback returned NaN, an infinity, a negative coefficient or a transmittance outside [0,1]")

typedef enum hrm_status {
#define HRM__STATUS_ENUM(name, value, text) name = value,
    HRM__STATUS_LIST(HRM__STATUS_ENUM)
#undef HRM__STATUS_ENUM
    HRM_STATUS_END_ /* not a status */
} hrm_status;

/* Methods. HRM_METHOD_DEFAULT (0) lets hrm choose (currently HRM_SIMPSON). */
#define HRM__METHOD_LIST(X)                                                   \
    X(HRM_RECTANGLE, "rectangle")                                            \
    X(HRM_SIMPSON, "simpson")                                                \
    X(HRM_MONTE_CARLO, "monte-carlo")                                        \
    X(HRM_EULER, "euler")                                                    \
    X(HRM_RK4, "rk4")                                                        \
    X(HRM_ADAMS_BASHFORTH, "adams-bashforth")

typedef enum hrm_method {
    HRM_METHOD_DEFAULT = 0,
#define HRM__METHOD_ENUM(name, text) name,
    HRM__METHOD_LIST(HRM__METHOD_ENUM)
#undef HRM__METHOD_ENUM
    HRM_METHOD_COUNT /* one past the last method */
} hrm_method;

typedef enum hrm_form {
    HRM_FORM_DEFAULT = 0,      /* HRM_FORM_OPTICAL_DEPTH */
    HRM_FORM_OPTICAL_DEPTH,    /* (tau, A): stable at any step */
    HRM_FORM_RTE               /* dL/dt = S - sigma_t L: stiff, for study */
} hrm_form;

/* Medium flags. */
#define HRM_MEDIUM_HOMOGENEOUS   1u /* use const_sigma_a/_s, closed-form Tr */
#define HRM_EMISSION_PER_LENGTH  2u /* source is Le itself, not sigma_a*Le */

typedef void (*hrm_spectrum_fn)(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]);
typedef void (*hrm_transmittance_fn)(void *user, hrm_real ta, hrm_real tb,
                                     hrm_real out[HRM_CHANNELS]);

typedef struct hrm_medium {
    void *user;                        /* passed to every callback */
    hrm_spectrum_fn sigma_a, sigma_s;  /* NULL: zero */
    hrm_spectrum_fn sigma_t;           /* NULL: sigma_a + sigma_s */
    hrm_spectrum_fn Le, Li;            /* NULL: absent, never called */
    hrm_transmittance_fn transmittance;/* NULL: integrate sigma_t */
    unsigned flags;                    /* HRM_MEDIUM_*, HRM_EMISSION_* */
    hrm_real const_sigma_a[HRM_CHANNELS]; /* with HRM_MEDIUM_HOMOGENEOUS */
    hrm_real const_sigma_s[HRM_CHANNELS];
} hrm_medium;

typedef struct hrm_options {
    hrm_method method;  /* 0: HRM_METHOD_DEFAULT */
    int steps;          /* fixed-step methods: segments, panels, steps or
                           Monte Carlo samples. 0: 32. Typical values to start
                           with: 8-32 for Simpson/RK4 on smooth media,
                           64-256 for the rectangle rule. Negative: error. */
    hrm_form form;      /* IVP solvers only. 0: optical-depth form */
    uint64_t seed;      /* Monte Carlo and jitter; vary it per ray/pixel. */
    int jitter;         /* rectangle rule: nonzero offsets the ray's samples
                           by one random fraction of a segment per ray
                           (Gonterman's anti-banding jitter). 0: midpoints */
    int stratified;     /* Monte Carlo: nonzero takes one sample per segment */
} hrm_options;

typedef struct hrm_stats {
    long evals;         /* source (Le/Li) evaluations: one per abscissa */
    long medium_evals;  /* medium (sigma or transmittance) evaluations */
    long steps;         /* steps, panels, segments or samples taken */
    long rejected;      /* rejected adaptive steps (0 for fixed methods) */
} hrm_stats;

typedef struct hrm_result {
    hrm_real L[HRM_CHANNELS];   /* radiance added by the medium */
    hrm_real Tr[HRM_CHANNELS];  /* eye-ray transmittance Tr(t0, t1) */
    hrm_stats stats;
} hrm_result;

/* The defaults of `method`: what an all-zero hrm_options means, with the
   method set. */
HRM_API hrm_options hrm_default_options(hrm_method method);

/* Solve along one ray from t0 to t1 (t0 <= t1, both finite).
   medium, result: required.  options: NULL means all defaults.
   Returns HRM_OK, a warning (result holds the best estimate) or an error
   (result holds L = 0, Tr = 1, and the stats counted so far). */
HRM_API hrm_status hrm_solve(const hrm_medium *medium, hrm_real t0, hrm_real t1,
                             const hrm_options *options, hrm_result *result);

/* Eye-ray (or shadow-ray) transmittance Tr(t0, t1) alone: no source is
   evaluated. Closed form when the medium has one (no sigma evaluation for a
   homogeneous medium), else sigma_t integrated with options' method.
   Tr: required. stats: optional. On error Tr is 1 in every channel. */
HRM_API hrm_status hrm_transmittance(const hrm_medium *medium, hrm_real t0,
                                     hrm_real t1, const hrm_options *options,
                                     hrm_real Tr[HRM_CHANNELS], hrm_stats *stats);

HRM_API const char *hrm_method_name(hrm_method method); /* "?" if unknown */
HRM_API const char *hrm_status_string(hrm_status status); /* "unknown status" */
/* HRM_VERSION_MAJOR*10000 + MINOR*100 + PATCH of the compiled library. */
HRM_API int hrm_version(void);

#ifdef __cplusplus
}
#endif
#endif /* HRM_H */

/* ======================================================================== */
/*                             IMPLEMENTATION                               */
/* ======================================================================== */
#ifdef HRM_IMPLEMENTATION
#ifndef HRM__IMPLEMENTATION_DONE
#define HRM__IMPLEMENTATION_DONE

#include <math.h>
#include <float.h>
#include <string.h>

#ifndef HRM_ASSERT
#include <assert.h>
#define HRM_ASSERT(x) assert(x)
#endif

#if defined(HRM_STATIC) && (defined(__GNUC__) || defined(__clang__))
#define HRM__DEF __attribute__((unused)) static
#elif defined(HRM_STATIC)
#define HRM__DEF static
#else
#define HRM__DEF
#endif

#define HRM__R(x) ((hrm_real)(x))
#define HRM__IS_FLOAT (sizeof(hrm_real) == sizeof(float))
#define HRM__EPS (HRM__IS_FLOAT ? HRM__R(FLT_EPSILON) : HRM__R(DBL_EPSILON))
#define HRM__CH HRM_CHANNELS

/* The libm function matching the scalar type; the branch is a constant. */
#define HRM__MATH1(fn, x) (HRM__IS_FLOAT ? (hrm_real)fn##f((float)(x)) : (hrm_real)fn((double)(x)))
#ifndef HRM_SQRT
#define HRM_SQRT(x) HRM__MATH1(sqrt, x)
#endif
#ifndef HRM_EXP
#define HRM_EXP(x) HRM__MATH1(exp, x)
#endif
#ifndef HRM_EXPM1
#define HRM_EXPM1(x) HRM__MATH1(expm1, x)
#endif
#ifndef HRM_LOG
#define HRM_LOG(x) HRM__MATH1(log, x)
#endif
#ifndef HRM_LOG1P
#define HRM_LOG1P(x) HRM__MATH1(log1p, x)
#endif
#ifndef HRM_FABS
#define HRM_FABS(x) HRM__MATH1(fabs, x)
#endif
#ifndef HRM_TAN
#define HRM_TAN(x) HRM__MATH1(tan, x)
#endif
#ifndef HRM_ATAN
#define HRM_ATAN(x) HRM__MATH1(atan, x)
#endif
#ifndef HRM_POW
#define HRM_POW(x, y) (HRM__IS_FLOAT ? (hrm_real)powf((float)(x), (float)(y)) \
                                     : (hrm_real)pow((double)(x), (double)(y)))
#endif

/* Finite test without <math.h> classification macros (C and C++ alike):
   x - x is 0 for finite x and NaN for infinities and NaN. */
#define HRM__FINITE(x) ((x) - (x) == 0)

/* ---------------------------------------------------------------------- */
/* Shared machinery: the solve context, evaluation of one abscissa, stats  */
/* ---------------------------------------------------------------------- */

/* One evaluated abscissa. The solvers integrate over a parameter p with
   s = t0 + off(p) (the identity, or a warp); gs and gq are already multiplied
   by ds/dp, so every rule below works in p alone. */
typedef struct hrm__pt {
    hrm_real p, off;
    hrm_real gs[HRM__CH];  /* sigma_t(s) * ds/dp */
    hrm_real gq[HRM__CH];  /* S(s) * ds/dp */
    hrm_real tau[HRM__CH]; /* tau(t0, s), when the medium has a closed form */
} hrm__pt;

typedef struct hrm__ctx {
    const hrm_medium *m;
    hrm_real t0, t1, T;    /* T = t1 - t0 */
    hrm_real pa, pb;       /* parameter range, s(pa) = t0, s(pb) = t1 */
    int homog;             /* constant coefficients */
    int closed;            /* tau at any abscissa in closed form */
    int need_st;           /* sigma_t samples needed */
    int use_le, use_li;    /* source terms present */
    int per_length;        /* HRM_EMISSION_PER_LENGTH */
    int rte;               /* HRM_FORM_RTE */
    hrm_real sa[HRM__CH], ss[HRM__CH], st[HRM__CH]; /* constants (homog) */
    hrm_status status;     /* first callback failure, else HRM_OK */
    uint64_t rng;
    hrm_stats stats;
} hrm__ctx;

static void hrm__fill(hrm_real *v, int n, hrm_real x)
{
    int i;
    for (i = 0; i < n; ++i) v[i] = x;
}

/* Validate callback output. kind 0: finite, 1: coefficient (>= 0),
   2: transmittance ([0, 1]). A failure is recorded once and the values are
   zeroed so that the arithmetic in flight stays harmless until the driver
   notices and stops. */
static void hrm__check(hrm__ctx *c, hrm_real *v, int kind)
{
    int i;
    for (i = 0; i < HRM__CH; ++i) {
        int ok = HRM__FINITE(v[i]) && (kind == 0 || v[i] >= 0) &&
                 (kind != 2 || v[i] <= 1);
        if (!ok) {
            if (c->status == HRM_OK) c->status = HRM_ERR_CALLBACK_VALUE;
            v[i] = 0;
        }
    }
}

/* The change of variable p -> s. Without a warp p is the distance from t0,
   which keeps full precision for short rays far from the origin. */
static void hrm__map(const hrm__ctx *c, hrm_real p, hrm_real *off, hrm_real *J)
{
    *off = p < c->T ? p : c->T;
    *J = 1;
}

static hrm_real hrm__abscissa(const hrm__ctx *c, hrm_real off)
{
    hrm_real s = c->t0 + off;
    return s < c->t1 ? s : c->t1; /* t0 + (t1 - t0) may round past t1 */
}

/* Evaluate the medium and the source at parameter p: every callback at most
   once, absent terms never. */
static void hrm__eval(hrm__ctx *c, hrm_real p, hrm__pt *pt)
{
    const hrm_medium *m = c->m;
    hrm_real sa[HRM__CH], ss[HRM__CH], st[HRM__CH], v[HRM__CH], q[HRM__CH];
    hrm_real J, s;
    int i, em = 0, sc = 0;

    hrm__map(c, p, &pt->off, &J);
    pt->p = p;
    s = hrm__abscissa(c, pt->off);
    if (c->homog) {
        memcpy(sa, c->sa, sizeof sa);
        memcpy(ss, c->ss, sizeof ss);
        memcpy(st, c->st, sizeof st);
        if (c->closed)
            for (i = 0; i < HRM__CH; ++i) pt->tau[i] = c->st[i] * pt->off;
    } else {
        int medium = 0;
        int derive_st = c->need_st && !m->sigma_t;
        hrm__fill(sa, HRM__CH, 0);
        hrm__fill(ss, HRM__CH, 0);
        hrm__fill(st, HRM__CH, 0);
        if (m->sigma_a && ((c->use_le && !c->per_length) || derive_st)) {
            m->sigma_a(m->user, s, sa);
            hrm__check(c, sa, 1);
            medium = 1;
        }
        if (m->sigma_s && (c->use_li || derive_st)) {
            m->sigma_s(m->user, s, ss);
            hrm__check(c, ss, 1);
            medium = 1;
        }
        if (c->need_st) {
            if (m->sigma_t) {
                m->sigma_t(m->user, s, st);
                hrm__check(c, st, 1);
                medium = 1;
            } else {
                for (i = 0; i < HRM__CH; ++i) st[i] = sa[i] + ss[i];
            }
        }
        if (c->closed) {
            m->transmittance(m->user, c->t0, s, v);
            hrm__check(c, v, 2);
            for (i = 0; i < HRM__CH; ++i) pt->tau[i] = -HRM_LOG(v[i]);
            medium = 1;
        }
        c->stats.medium_evals += medium;
    }

    /* A term whose coefficient vanishes in every channel is not called:
       no shadow ray where nothing scatters. */
    for (i = 0; i < HRM__CH; ++i) {
        em |= c->per_length || sa[i] > 0;
        sc |= ss[i] > 0;
        q[i] = 0;
    }
    em &= c->use_le;
    sc &= c->use_li;
    if (em) {
        m->Le(m->user, s, v);
        hrm__check(c, v, 0);
        for (i = 0; i < HRM__CH; ++i) q[i] += (c->per_length ? v[i] : sa[i] * v[i]);
    }
    if (sc) {
        m->Li(m->user, s, v);
        hrm__check(c, v, 0);
        for (i = 0; i < HRM__CH; ++i) q[i] += ss[i] * v[i];
    }
    c->stats.evals += em | sc;
    for (i = 0; i < HRM__CH; ++i) {
        pt->gq[i] = q[i] * J;
        pt->gs[i] = st[i] * J;
    }
}

/* Closed-form Tr(t0, t1): no callback for a homogeneous medium, one
   transmittance call otherwise. */
static void hrm__closed_tr(hrm__ctx *c, hrm_real Tr[HRM__CH])
{
    int i;
    if (c->homog) {
        for (i = 0; i < HRM__CH; ++i) Tr[i] = HRM_EXP(-c->st[i] * c->T);
        return;
    }
    c->m->transmittance(c->m->user, c->t0, c->t1, Tr);
    hrm__check(c, Tr, 2);
    c->stats.medium_evals++;
}

/* splitmix64 (Steele, Lea, Flood 2014): the generator's state lives in the
   call, so results depend on options.seed alone. */
static uint64_t hrm__next(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1), exactly representable in hrm_real (never rounds to 1). */
static hrm_real hrm__uniform(uint64_t *state)
{
    uint64_t x = hrm__next(state);
    if (HRM__IS_FLOAT) return (hrm_real)((float)(x >> 40) * (1.0f / 16777216.0f));
    return (hrm_real)((double)(x >> 11) * (1.0 / 9007199254740992.0));
}

/* ---------------------------------------------------------------------- */
/* Fixed-step quadrature                                                   */
/* ---------------------------------------------------------------------- */

/* The rectangle rule and Monte Carlo: N increasing nodes of equal weight
   (pb - pa)/N. Without a closed form, tau at each node comes from the same
   sigma_t samples by the trapezoid rule between consecutive nodes (a
   constant one-sided piece before the first and after the last): second
   order, as the midpoint rule itself. kind: 0 rectangle, 1 stratified,
   2 uniform Monte Carlo. Uniform samples are generated already sorted
   (the minimum of n uniforms is 1 - U^(1/n), and the rest are uniform
   above it), so tau accumulates without storing them. */
static void hrm__nodes(hrm__ctx *c, int N, int kind, hrm_real xi,
                       hrm_real L[HRM__CH], hrm_real tau[HRM__CH])
{
    hrm_real w = (c->pb - c->pa) / (hrm_real)N, x = 0, prev_p = c->pa;
    hrm_real prev_gs[HRM__CH];
    hrm__pt pt;
    int k, i;

    hrm__fill(prev_gs, HRM__CH, 0);
    for (k = 0; k < N; ++k) {
        hrm_real p;
        if (kind == 2) {
            hrm_real u = 1 - hrm__uniform(&c->rng); /* (0, 1] */
            x += (1 - x) * -HRM_EXPM1(HRM_LOG(u) / (hrm_real)(N - k));
            p = c->pa + (c->pb - c->pa) * x;
        } else {
            if (kind == 1) xi = hrm__uniform(&c->rng);
            p = c->pa + (c->pb - c->pa) * (((hrm_real)k + xi) / (hrm_real)N);
        }
        hrm__eval(c, p, &pt);
        for (i = 0; i < HRM__CH; ++i) {
            if (c->closed) {
                tau[i] = pt.tau[i];
            } else {
                hrm_real mean = k ? (prev_gs[i] + pt.gs[i]) / 2 : pt.gs[i];
                tau[i] += mean * (p - prev_p);
                prev_gs[i] = pt.gs[i];
            }
            L[i] += w * HRM_EXP(-tau[i]) * pt.gq[i];
        }
        prev_p = p;
        if (c->status != HRM_OK) return;
    }
    if (!c->closed)
        for (i = 0; i < HRM__CH; ++i) tau[i] += prev_gs[i] * (c->pb - prev_p);
}

/* Composite Simpson over N panels. Without a closed form, tau at the panel
   ends comes from Simpson's rule on the sigma_t samples, and at each panel's
   midpoint from the integral of the same parabola over the panel's first
   half, H/24 (5 f_a + 8 f_m - f_b): fourth order overall, no extra samples.
   tau is nondecreasing, so the midpoint value is kept between its
   neighbours (a thick, sharply varying medium could otherwise overshoot). */
static void hrm__simpson(hrm__ctx *c, int N, hrm_real L[HRM__CH], hrm_real tau[HRM__CH])
{
    hrm__pt a, mid, b;
    hrm_real ea[HRM__CH]; /* exp(-tau) * gq at the panel's left end */
    hrm_real span = c->pb - c->pa;
    int k, i;

    hrm__eval(c, c->pa, &a);
    for (i = 0; i < HRM__CH; ++i) {
        tau[i] = c->closed ? a.tau[i] : 0;
        ea[i] = HRM_EXP(-tau[i]) * a.gq[i];
    }
    for (k = 0; k < N; ++k) {
        hrm_real pl = c->pa + span * ((hrm_real)k / (hrm_real)N);
        hrm_real pr = k + 1 == N ? c->pb : c->pa + span * ((hrm_real)(k + 1) / (hrm_real)N);
        hrm_real H = pr - pl;
        hrm__eval(c, pl + H / 2, &mid);
        hrm__eval(c, pr, &b);
        for (i = 0; i < HRM__CH; ++i) {
            hrm_real tm, tb, eb;
            if (c->closed) {
                tm = mid.tau[i];
                tb = b.tau[i];
            } else {
                tb = tau[i] + H / 6 * (a.gs[i] + 4 * mid.gs[i] + b.gs[i]);
                tm = tau[i] + H / 24 * (5 * a.gs[i] + 8 * mid.gs[i] - b.gs[i]);
                if (tb < tau[i]) tb = tau[i];
                if (tm < tau[i]) tm = tau[i];
                if (tm > tb) tm = tb;
            }
            eb = HRM_EXP(-tb) * b.gq[i];
            L[i] += H / 6 * (ea[i] + 4 * HRM_EXP(-tm) * mid.gq[i] + eb);
            ea[i] = eb;
            tau[i] = tb;
        }
        a = b;
        if (c->status != HRM_OK) return;
    }
}

/* ---------------------------------------------------------------------- */
/* IVP steppers                                                            */
/* ---------------------------------------------------------------------- */

#define HRM__MAX_STAGES 8
#define HRM__NY (2 * HRM__CH)

/* An explicit Runge-Kutta method: stages s, row-major a (s x s, strictly
   lower), weights b, nodes c; e = b - b_hat for embedded pairs. */
typedef struct hrm__tableau {
    int s, order;
    const hrm_real *a, *b, *c, *e;
} hrm__tableau;

/* Euler (1768). */
static const hrm_real hrm__euler_a[] = {0};
static const hrm_real hrm__euler_b[] = {1};
static const hrm_real hrm__euler_c[] = {0};
static const hrm__tableau hrm__euler = {1, 1, hrm__euler_a, hrm__euler_b, hrm__euler_c, 0};

/* Classical Runge-Kutta (Kutta 1901). */
static const hrm_real hrm__rk4_a[] = {
    0, 0, 0, 0,
    0.5, 0, 0, 0,
    0, 0.5, 0, 0,
    0, 0, 1, 0};
static const hrm_real hrm__rk4_b[] = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
static const hrm_real hrm__rk4_c[] = {0, 0.5, 0.5, 1};
static const hrm__tableau hrm__rk4 = {4, 4, hrm__rk4_a, hrm__rk4_b, hrm__rk4_c, 0};

/* Adams-Bashforth 4-step (Bashforth & Adams 1883), newest value first. */
static const hrm_real hrm__ab4_beta[4] = {55.0 / 24, -59.0 / 24, 37.0 / 24, -9.0 / 24};

/* The right-hand side of either form at one evaluated abscissa.
   Optical depth: y = (tau, A), tau' = sigma_t, A' = exp(-tau) S.
   RTE (marched from t1 toward t0): y = (Tr, L), Tr' = sigma_t Tr,
   L' = sigma_t L - S, in p, so that stepping toward t0 gives Munoz eq. 1. */
static void hrm__deriv(const hrm__ctx *c, const hrm__pt *pt, const hrm_real *y, hrm_real *k)
{
    int i;
    for (i = 0; i < HRM__CH; ++i) {
        if (c->rte) {
            k[i] = pt->gs[i] * y[i];
            k[HRM__CH + i] = pt->gs[i] * y[HRM__CH + i] - pt->gq[i];
        } else {
            k[i] = pt->gs[i];
            k[HRM__CH + i] = HRM_EXP(-(c->closed ? pt->tau[i] : y[i])) * pt->gq[i];
        }
    }
}

/* One explicit RK step from p to p_end = p + h. start holds the sample at p
   (and becomes the sample at p_end when the tableau has a node c = 1, so the
   next step does not evaluate it again: *have_start says whether it did).
   Stages sharing a node share one evaluation. err (optional) receives
   h * sum e_i k_i. */
static void hrm__rk_step(hrm__ctx *c, const hrm__tableau *tb, hrm__pt *start,
                         int *have_start, hrm_real p, hrm_real p_end,
                         const hrm_real *y, hrm_real *ynew, hrm_real *err)
{
    hrm__pt pts[HRM__MAX_STAGES];
    const hrm__pt *sp[HRM__MAX_STAGES];
    hrm_real k[HRM__MAX_STAGES][HRM__NY], Y[HRM__NY];
    hrm_real h = p_end - p;
    int i, j, n, end_stage = -1;

    HRM_ASSERT(tb->s <= HRM__MAX_STAGES);
    if (!*have_start) hrm__eval(c, p, start);
    for (i = 0; i < tb->s; ++i) {
        hrm_real ci = tb->c[i];
        sp[i] = 0;
        if (ci == 0) sp[i] = start;
        for (j = 0; j < i && !sp[i]; ++j)
            if (tb->c[j] == ci) sp[i] = sp[j];
        if (!sp[i]) {
            hrm__eval(c, ci == 1 ? p_end : p + ci * h, &pts[i]);
            sp[i] = &pts[i];
            if (ci == 1) end_stage = i;
        }
        for (n = 0; n < HRM__NY; ++n) {
            hrm_real acc = 0;
            for (j = 0; j < i; ++j) acc += tb->a[i * tb->s + j] * k[j][n];
            Y[n] = y[n] + h * acc;
        }
        /* tau never decreases along the march: keep stage values at or
           above the step's start, whatever signs the tableau's a hold. */
        if (!c->rte)
            for (n = 0; n < HRM__CH; ++n)
                if (Y[n] < y[n]) Y[n] = y[n];
        hrm__deriv(c, sp[i], Y, k[i]);
    }
    for (n = 0; n < HRM__NY; ++n) {
        hrm_real acc = 0, eacc = 0;
        for (i = 0; i < tb->s; ++i) {
            acc += tb->b[i] * k[i][n];
            if (err) eacc += tb->e[i] * k[i][n];
        }
        ynew[n] = y[n] + h * acc;
        if (err) err[n] = h * eacc;
    }
    *have_start = end_stage >= 0;
    if (end_stage >= 0) *start = pts[end_stage];
}

/* Fixed-step IVP driver: Euler, RK4 and Adams-Bashforth 4 (three RK4 steps
   to start, then one new evaluation per step). The optical-depth form
   marches from t0 to t1, the RTE form from t1 to t0. */
static void hrm__ivp_fixed(hrm__ctx *c, const hrm__tableau *tb, int ab4, int N,
                           hrm_real y[HRM__NY])
{
    hrm_real from = c->rte ? c->pb : c->pa, to = c->rte ? c->pa : c->pb;
    hrm_real f[4][HRM__NY]; /* Adams-Bashforth history, f[n % 4] = f_n */
    hrm__pt start;
    int have = 0, n, i, j;

    for (i = 0; i < HRM__CH; ++i) {
        y[i] = c->rte ? 1 : 0;
        y[HRM__CH + i] = 0;
    }
    for (n = 0; n < N; ++n) {
        hrm_real p = from + (to - from) * ((hrm_real)n / (hrm_real)N);
        hrm_real q = n + 1 == N ? to : from + (to - from) * ((hrm_real)(n + 1) / (hrm_real)N);
        hrm_real h = q - p;
        if (!ab4 || n < 3) {
            if (ab4) {
                if (!have) hrm__eval(c, p, &start);
                have = 1;
                hrm__deriv(c, &start, y, f[n % 4]);
            }
            hrm__rk_step(c, tb, &start, &have, p, q, y, y, 0);
        } else {
            if (!have) hrm__eval(c, p, &start);
            have = 0;
            hrm__deriv(c, &start, y, f[n % 4]);
            for (i = 0; i < HRM__NY; ++i) {
                hrm_real inc = 0;
                int pos = 1, neg = 1;
                for (j = 0; j < 4; ++j) {
                    hrm_real hf = h * f[(n - j) % 4][i];
                    inc += hrm__ab4_beta[j] * hf;
                    pos &= hf >= 0;
                    neg &= hf <= 0;
                }
                /* Positivity limiter (optical-depth form): when every history
                   value agrees on the increment's sign, so does the
                   increment. Extrapolating a sharply decaying exp(-tau) S
                   can otherwise go negative in thick media. */
                if (!c->rte && ((pos && inc < 0) || (neg && inc > 0))) inc = 0;
                y[i] += inc;
            }
        }
        c->stats.steps++;
        if (c->status != HRM_OK) return;
    }
}

/* ---------------------------------------------------------------------- */
/* Dispatcher and public functions                                         */
/* ---------------------------------------------------------------------- */

HRM__DEF const char *hrm_status_string(hrm_status status)
{
    switch (status) {
#define HRM__STATUS_CASE(name, value, text) case name: return text;
        HRM__STATUS_LIST(HRM__STATUS_CASE)
#undef HRM__STATUS_CASE
    default: return "unknown status";
    }
}

HRM__DEF const char *hrm_method_name(hrm_method method)
{
    switch (method) {
    case HRM_METHOD_DEFAULT: return "default";
#define HRM__METHOD_CASE(name, text) case name: return text;
        HRM__METHOD_LIST(HRM__METHOD_CASE)
#undef HRM__METHOD_CASE
    default: return "?";
    }
}

HRM__DEF int hrm_version(void)
{
    return HRM_VERSION_MAJOR * 10000 + HRM_VERSION_MINOR * 100 + HRM_VERSION_PATCH;
}

HRM__DEF hrm_options hrm_default_options(hrm_method method)
{
    hrm_options o;
    memset(&o, 0, sizeof o);
    o.method = method == HRM_METHOD_DEFAULT ? HRM_SIMPSON : method;
    o.steps = 32;
    o.form = HRM_FORM_OPTICAL_DEPTH;
    return o;
}

/* Resolve zeros to defaults; validate. */
static hrm_status hrm__resolve(const hrm_options *in, hrm_options *o)
{
    hrm_options d = hrm_default_options(in ? in->method : HRM_METHOD_DEFAULT);
    if (!in) {
        *o = d;
        return HRM_OK;
    }
    *o = *in;
    if ((int)o->method < 0 || (int)o->method >= (int)HRM_METHOD_COUNT) return HRM_ERR_BAD_METHOD;
    if (o->method == HRM_METHOD_DEFAULT) o->method = d.method;
    if (o->steps < 0) return HRM_ERR_BAD_STEPS;
    if (o->steps == 0) o->steps = d.steps;
    if ((int)o->form < 0 || (int)o->form > (int)HRM_FORM_RTE) return HRM_ERR_BAD_OPTION;
    if (o->form == HRM_FORM_DEFAULT) o->form = HRM_FORM_OPTICAL_DEPTH;
    return HRM_OK;
}

/* The one solve behind hrm_solve and hrm_transmittance (tr_only: no
   source, so only sigma_t is integrated). */
static hrm_status hrm__run(const hrm_medium *m, hrm_real t0, hrm_real t1,
                           const hrm_options *in, int tr_only,
                           hrm_real L[HRM__CH], hrm_real Tr[HRM__CH], hrm_stats *stats)
{
    hrm__ctx c;
    hrm_options o;
    hrm_real tau[HRM__CH], y[HRM__NY];
    hrm_status st;
    int i, ivp = 0;

    memset(&c, 0, sizeof c);
    memset(stats, 0, sizeof *stats);
    hrm__fill(L, HRM__CH, 0);
    hrm__fill(Tr, HRM__CH, 1);
    hrm__fill(tau, HRM__CH, 0);
    if (!HRM__FINITE(t0) || !HRM__FINITE(t1) || t1 < t0) return HRM_ERR_BAD_INTERVAL;
    st = hrm__resolve(in, &o);
    if (st != HRM_OK) return st;

    c.m = m;
    c.t0 = t0;
    c.t1 = t1;
    c.T = t1 - t0;
    c.pa = 0;
    c.pb = c.T;
    c.rng = o.seed;
    c.homog = (m->flags & HRM_MEDIUM_HOMOGENEOUS) != 0;
    c.per_length = (m->flags & HRM_EMISSION_PER_LENGTH) != 0;
    c.rte = o.form == HRM_FORM_RTE &&
            (o.method == HRM_EULER || o.method == HRM_RK4 || o.method == HRM_ADAMS_BASHFORTH);
    if (c.homog) {
        for (i = 0; i < HRM__CH; ++i) {
            c.sa[i] = m->const_sigma_a[i];
            c.ss[i] = m->const_sigma_s[i];
            if (!(HRM__FINITE(c.sa[i]) && HRM__FINITE(c.ss[i]) && c.sa[i] >= 0 && c.ss[i] >= 0))
                return HRM_ERR_BAD_MEDIUM;
            c.st[i] = c.sa[i] + c.ss[i];
            if (!HRM__FINITE(c.st[i])) return HRM_ERR_BAD_MEDIUM;
        }
    }
    c.use_le = !tr_only && m->Le && (c.per_length || c.homog || m->sigma_a);
    c.use_li = !tr_only && m->Li && (c.homog || m->sigma_s);
    /* The RTE form integrates Tr itself, so it takes sigma_t samples even
       where a closed form exists. */
    c.closed = c.homog || (m->transmittance && !c.rte);
    c.need_st = !c.closed || c.rte;

    if (t0 == t1) return HRM_OK;
    if (!c.use_le && !c.use_li && c.closed) {
        /* Nothing to integrate: only the closed-form Tr. */
        hrm__closed_tr(&c, Tr);
        *stats = c.stats;
        if (c.status != HRM_OK) {
            hrm__fill(Tr, HRM__CH, 1);
            return c.status;
        }
        return HRM_OK;
    }

    switch (o.method) {
    case HRM_RECTANGLE:
        hrm__nodes(&c, o.steps, 0, o.jitter ? hrm__uniform(&c.rng) : HRM__R(0.5), L, tau);
        c.stats.steps = o.steps;
        break;
    case HRM_MONTE_CARLO:
        hrm__nodes(&c, o.steps, o.stratified ? 1 : 2, 0, L, tau);
        c.stats.steps = o.steps;
        break;
    case HRM_SIMPSON:
        hrm__simpson(&c, o.steps, L, tau);
        c.stats.steps = o.steps;
        break;
    case HRM_EULER:
    case HRM_RK4:
    case HRM_ADAMS_BASHFORTH:
        hrm__ivp_fixed(&c, o.method == HRM_EULER ? &hrm__euler : &hrm__rk4,
                       o.method == HRM_ADAMS_BASHFORTH, o.steps, y);
        ivp = 1;
        break;
    default:
        return HRM_ERR_BAD_METHOD;
    }

    if (ivp) {
        for (i = 0; i < HRM__CH; ++i) {
            L[i] = y[HRM__CH + i];
            tau[i] = y[i];
        }
    }
    if (c.rte) {
        for (i = 0; i < HRM__CH; ++i) Tr[i] = tau[i]; /* y holds (Tr, L) */
    } else if (c.closed) {
        hrm__closed_tr(&c, Tr);
    } else {
        for (i = 0; i < HRM__CH; ++i) Tr[i] = HRM_EXP(-tau[i]);
    }
    *stats = c.stats;
    if (c.status != HRM_OK) {
        hrm__fill(L, HRM__CH, 0);
        hrm__fill(Tr, HRM__CH, 1);
        return c.status;
    }
    return HRM_OK;
}

HRM__DEF hrm_status hrm_solve(const hrm_medium *medium, hrm_real t0, hrm_real t1,
                              const hrm_options *options, hrm_result *result)
{
    hrm_result r;
    hrm_status st;
    if (!result) return HRM_ERR_NULL_ARGUMENT;
    if (!medium) {
        memset(result, 0, sizeof *result);
        hrm__fill(result->Tr, HRM__CH, 1);
        return HRM_ERR_NULL_ARGUMENT;
    }
    /* Work on a local copy: result may alias nothing we read, and a failed
       solve leaves exactly the defined error result. */
    st = hrm__run(medium, t0, t1, options, 0, r.L, r.Tr, &r.stats);
    *result = r;
    return st;
}

HRM__DEF hrm_status hrm_transmittance(const hrm_medium *medium, hrm_real t0,
                                      hrm_real t1, const hrm_options *options,
                                      hrm_real Tr[HRM_CHANNELS], hrm_stats *stats)
{
    hrm_real L[HRM__CH], out[HRM__CH];
    hrm_stats s;
    hrm_status st;
    if (!Tr) return HRM_ERR_NULL_ARGUMENT;
    if (!medium) {
        hrm__fill(Tr, HRM__CH, 1);
        if (stats) memset(stats, 0, sizeof *stats);
        return HRM_ERR_NULL_ARGUMENT;
    }
    st = hrm__run(medium, t0, t1, options, 1, L, out, &s);
    memcpy(Tr, out, sizeof out);
    if (stats) *stats = s;
    return st;
}

#endif /* HRM__IMPLEMENTATION_DONE */
#endif /* HRM_IMPLEMENTATION */

/*
------------------------------------------------------------------------------
MIT License

Copyright (c) 2026 the hrm.h authors

Permission is hereby granted, free of charge, to any person obtaining a copy
of this software and associated documentation files (the "Software"), to deal
in the Software without restriction, including without limitation the rights
to use, copy, modify, merge, publish, distribute, sublicense, and/or sell
copies of the Software, and to permit persons to whom the Software is
furnished to do so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in
all copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
------------------------------------------------------------------------------
*/
