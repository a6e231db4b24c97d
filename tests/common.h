/* common.h - what the files of hrm.h's test program share: precision
   helpers, Gauss-Legendre reference quadrature, the scene (coefficients of
   the media and lights, with call recording), its callbacks, problems (a
   medium built from a scene) with their closed forms, and solve helpers.
   Defined in common.c.

   The test program is one binary per configuration of tests/run.sh, linked
   from several translation units, each including hrm.h:
     main.c           runs every group, prints the summary (and holds the
                      harness's tally)
     test_tables.c    the implementation (HRM_IMPLEMENTATION) and the checks
                      of its private coefficient tables
     test_fixed.c     the interface and the fixed-step methods
     test_adaptive.c  the adaptive methods
     test_warp.c      the importance-sampling warps
     test_transmittance.c  the transmittance layer: tau in t under every
                      warp, decoupled sampling, the distance warp's reach
     test_breaks.c    breakpoints: bad lists, pieces, order regained
     common.c         the helpers below

   References are always computed in double, whatever HRM_REAL is. Nothing
   here is written to but the caller's own structs: the harness's tally is
   the only mutable global of the tests.

   Channels: every helper loops over HRM_CHANNELS. Channel c of a scene has
   its coefficients at the fraction f = c/HRM_CHANNELS of a fixed range
   (channel 0 is the same in every build; with three channels sigma_t is
   0.5, 0.75, 1.0), so no test assumes a channel count. */
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

#define NCH HRM_CHANNELS
#define PI 3.14159265358979323846

/* The entry points of the test files, each running its groups. */
void fixed_tests(void);
void table_tests(void);
void adaptive_tests(void);
void warp_tests(void);
void transmittance_tests(void);
void breaks_tests(void);
void exponential_tests(void);
void extremes_tests(void);
void bad_input_tests(void);

/* ------------------------------------------------------------------------
   Precision and small numerics
   ------------------------------------------------------------------------ */
int real_is_float(void);   /* HRM_REAL is float */
double real_eps(void);     /* FLT_EPSILON or DBL_EPSILON */
void spectrum_one(void *user, hrm_real t, hrm_real out[NCH]); /* 1 in every channel */

/* Round-off floor of a relative error after n steps (or samples) with
   optical depth tau: eps (n + 16) (1 + tau). Each step adds a relative
   error of about eps to the sum and to tau, and an error in tau is
   multiplied by tau in exp(-tau). Under double it stays far below the
   truncation bounds it is added to. */
double fp_floor(long n, double tau);

int verbose(void);         /* HRM_TEST_VERBOSE=1: print every error */
int finite_d(double x);    /* neither NaN nor infinite */

/* Least-squares slope of y against x (n points). */
double ls_slope(const double *x, const double *y, int n);

/* ------------------------------------------------------------------------
   Gauss-Legendre reference quadrature (in double)
   ------------------------------------------------------------------------ */
#define GL_MAX 10

/* Nodes x and weights w of the n-point rule on [-1, 1], 1 <= n <= GL_MAX
   (Newton's method on the Legendre recurrence, to round-off). */
void gl_rule(int n, double x[], double w[]);

typedef double (*real_fn)(const void *ctx, double s);

/* Composite n-point Gauss-Legendre over [a, b] in `panels` panels of
   f(ctx, s), or with square != 0 of (f(ctx, s) - centre)^2. */
double gl_integrate(real_fn f, const void *ctx, double a, double b, int panels, int n,
                    int square, double centre);

/* ------------------------------------------------------------------------
   The scene: user data of the callbacks, with call recording
   ------------------------------------------------------------------------ */
/* Lights, as Li(s) in units of E (or I):
     LIGHT_DIR     directional light whose path through the medium grows
                   along the ray: E exp(-sigma_t (d0 + k s)), sigma_t the
                   homogeneous one
     LIGHT_TAU     E exp(cexp tau_abs(s)), with the heterogeneous medium's
                   tau_abs (a closed form with it)
     LIGHT_CONST   E
     LIGHT_SHADOW  E except in a sharp shadow [lo, hi), where 0
     LIGHT_POINT   a point light D from the ray, projecting onto it at
                   delta, unattenuated: I / (D^2 + (s - delta)^2) */
enum { LIGHT_NONE, LIGHT_DIR, LIGHT_TAU, LIGHT_CONST, LIGHT_SHADOW, LIGHT_POINT };

/* The heterogeneous sigma_t(s): a + b sin(w s), or qc (s - q0)^2. */
enum { PROFILE_SINE, PROFILE_QUAD };

/* Which callback returns poison_value (test of HRM_ERR_CALLBACK_VALUE). */
enum { POISON_NONE, POISON_SA, POISON_SS, POISON_ST, POISON_LE, POISON_LI, POISON_TR };

#define LOG_CAP 8192

typedef struct scene {
    /* homogeneous medium */
    double sig_a[NCH], sig_s[NCH];
    /* heterogeneous medium: sigma_t(s) of the profile, sigma_a = pa
       sigma_t, sigma_s = (1 - pa) sigma_t */
    int profile;
    double a[NCH], b[NCH], w;   /* PROFILE_SINE */
    double q0, qc[NCH];         /* PROFILE_QUAD */
    double pa[NCH];
    /* sources */
    double le[NCH];             /* constant Le */
    double E[NCH], d0, k;       /* LIGHT_DIR, LIGHT_TAU, LIGHT_CONST, LIGHT_SHADOW */
    double cexp;                /* LIGHT_TAU */
    double lo, hi;              /* LIGHT_SHADOW */
    double I[NCH], delta, D;    /* LIGHT_POINT */
    /* bad values injected by the callbacks */
    int poison;                 /* which callback: POISON_* */
    double poison_value;
    /* recording */
    long n_sa, n_ss, n_st, n_le, n_li, n_tr;
    long n_one;                 /* calls of het_sigma (both coefficients) */
    long n_never;               /* calls of callbacks that must not be called */
    double tmin, tmax;          /* over every spectrum callback */
    double tr_amin, tr_bmax;    /* over the transmittance callback (ta, tb) */
    long tr_reversed;           /* transmittance calls with ta > tb */
    long li_where_ss0, le_where_sa0; /* calls where the term is zero */
    double log_le[LOG_CAP];     /* the t of every Le call */
    int log_n;
    double log_li[LOG_CAP];     /* the t of every Li call */
    int log_li_n;
    /* re-entrancy: the light's transmittance by a nested call of hrm */
    hrm_medium *shadow_ray;     /* medium of the nested rays */
    int shadow_use_solve;       /* 0: hrm_transmittance, 1: hrm_solve */
    long shadow_bad_status;
} scene;

/* The position of channel c in the scenes' ranges: c / HRM_CHANNELS. */
double channel_frac(int c);

/* Every coefficient at its default (channel c at f = channel_frac(c)):
   homogeneous sigma_a = 0.2 + 0.3 f, sigma_s = 0.3 + 0.45 f (sigma_t 0.5
   ... 1.0); heterogeneous sine with a = 0.6 + 0.9 f, b = a/2, w = 2,
   pa = 0.3 + 0.6 f, quad q0 = 0, qc = 0.1 + 0.1 f; Le = 1 + 1.5 f;
   E = 2 - 0.9 f, d0 = k = cexp = 0.5; shadow [2.3137, 3.7071); I = 1 + f,
   delta = 3, D = 1. No poison, counts reset. */
void scene_init(scene *sc);

/* The sine profile with a = a0 + a1 f, b = a/2. */
void scene_set_sine(scene *sc, double a0, double a1);

void scene_reset_counts(scene *sc);
void touch(scene *sc, hrm_real t); /* records t in [tmin, tmax] */

double sig_t_hom(const scene *sc, int c);
double sig_t_het(const scene *sc, int c, double s);
double tau_abs(const scene *sc, int c, double s);               /* int_0^s sigma_t */
double tau_het(const scene *sc, int c, double ta, double tb);   /* int_ta^tb sigma_t */
double light_value(const scene *sc, int light, int c, double s);

/* Callbacks (user = the scene). Each counts its calls and records t. */
void het_sigma_a(void *user, hrm_real t, hrm_real out[NCH]);   /* pa sigma_t */
void het_sigma_s(void *user, hrm_real t, hrm_real out[NCH]);   /* (1 - pa) sigma_t */
void het_sigma_t(void *user, hrm_real t, hrm_real out[NCH]);
void het_absorber(void *user, hrm_real t, hrm_real out[NCH]);  /* sigma_a = sigma_t, counted as sigma_a */
void het_sigma(void *user, hrm_real t, hrm_real sa[NCH], hrm_real ss[NCH]); /* both, one call */
void het_transmittance(void *user, hrm_real ta, hrm_real tb, hrm_real out[NCH]);
void const_Le(void *user, hrm_real t, hrm_real out[NCH]);      /* logs t in log_le */
/* Abscissae logged twice or more (the log of Le or Li calls). */
long log_repeats(const double *log, int n);
hrm_spectrum_fn light_Li(int light);                           /* the Li callback of a light */

/* ------------------------------------------------------------------------
   Problems: a medium built from a scene, with its closed forms
   ------------------------------------------------------------------------ */
enum { P_HOM, P_HET };

/* The coefficient callbacks of a heterogeneous medium. */
enum {
    SIGMA_AS, /* sigma_a and sigma_s */
    SIGMA_A,  /* an absorber: sigma_a = sigma_t (het_absorber), no scattering */
    SIGMA_TS, /* sigma_t and sigma_s (hrm derives sigma_a) */
    SIGMA_ONE /* both from one call (medium.sigma), counted in n_one */
};

typedef struct problem {
    scene *sc;
    int kind;          /* P_HOM (constants, closed-form Tr) or P_HET */
    int le;            /* constant Le present */
    int light;         /* LIGHT_NONE or the Li */
    int tr;            /* P_HET: the closed-form transmittance callback */
    int sigmas;        /* P_HET: SIGMA_* */
    unsigned flags;    /* extra medium flags (HRM_EMISSION_PER_LENGTH) */
} problem;

problem make_problem(scene *sc, int kind, int le, int light); /* tr = 0, SIGMA_AS */
hrm_medium zero_medium(void);
hrm_medium problem_medium(const problem *p);

/* Closed forms (per channel c; exact_L is NaN where there is none). */
double exact_tau(const problem *p, int c, double t0, double t1);
double exact_tr(const problem *p, int c, double t0, double s);
double exact_S(const problem *p, int c, double s);              /* the source */
double exact_f(const problem *p, int c, double t0, double s);   /* Tr(t0, s) S(s) */
double exact_L(const problem *p, int c, double t0, double t1);  /* t1 may be +inf */
double max_tau(const problem *p, double t0, double t1);         /* over channels */

/* Max over channels of |L - exact| / |exact| (NaN propagates), and the
   same for Tr. */
double rel_err_L(const problem *p, double t0, double t1, const hrm_result *r);
double rel_err_Tr(const problem *p, double t0, double t1, const hrm_real *Tr);

/* The integral of exact_f (Tr(t0, s) S(s), channel c) over [a, b] by
   composite 10-point Gauss-Legendre in `panels` panels: the reference of
   scenes whose L has no closed form. */
double gl_exact_f(const problem *p, int c, double t0, double a, double b, int panels);

/* ------------------------------------------------------------------------
   Methods, options, solving, results
   ------------------------------------------------------------------------ */
/* Every method in hrm's order: the six fixed-step ones first. */
#define N_METHODS_ALL 14
#define N_METHODS_FIXED 6
extern const hrm_method every_method[N_METHODS_ALL];

int is_ivp(hrm_method m);       /* Euler, RK4, Adams-Bashforth 4 */
int is_adaptive(hrm_method m);  /* nested Simpson and after */
int is_pair(hrm_method m);      /* the embedded Runge-Kutta pairs */
const char *form_name(hrm_form f);

hrm_options make_options(hrm_method m, int steps, hrm_form form);
/* method m's defaults at rtol under warp w: 0 none, 1 distance, 2 the
   equiangular warp of a light D from the ray at its foot delta */
hrm_options warp_options(hrm_method m, double rtol, int w, double delta, double D);
hrm_status solve_opt(const problem *p, double t0, double t1, const hrm_options *o,
                     hrm_result *r);
hrm_status solve(const problem *p, double t0, double t1, hrm_method m, int n, hrm_form form,
                 hrm_result *r);

int result_finite(const hrm_result *r);   /* L and Tr finite */
int is_error_result(const hrm_result *r); /* L = 0, Tr = 1 in every channel */
/* The same L, Tr, evals and steps (bit for bit); same_result: and the same
   medium_evals too. */
int same_solve(const hrm_result *a, const hrm_result *b);
int same_result(const hrm_result *a, const hrm_result *b);

/* Homogeneous fog, sigma_t st and sigma_s ss in every channel: the first
   member of a scene's user data where the medium is given to hrm either
   way. fog_medium: as constants (cb 0) or as one sigma callback (cb 1,
   fog_sigma), Li li, user the scene. */
typedef struct test_fog {
    double st, ss;
} test_fog;
void fog_sigma(void *user, hrm_real t, hrm_real sa[HRM_CHANNELS], hrm_real ss[HRM_CHANNELS]);
hrm_medium fog_medium(void *user, hrm_spectrum_fn li, int cb);

#endif /* HRM_TEST_COMMON_H */
