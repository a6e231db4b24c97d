/* test_fixed.c - the tests of hrm.h's interface and of its fixed-step
   methods; fixed_tests() runs every group.

   Every numerical check compares with a closed form (or, for Monte Carlo
   variances, an independent high-accuracy quadrature in double) and states
   its bound and the reason for it beside the check. References are always
   computed in double, whatever HRM_REAL is. The scenes, their callbacks and
   closed forms are those of common.h.

   Notation in the comments: T = t1 - t0, h = T/N (step or segment),
   H = T/N (Simpson panel: nodes at H/2 spacing), lambda = a rate that bounds
   how fast the integrand changes (|f^(k)| <~ lambda^k |f|).

   Round-off: under HRM_REAL=float every bound gets the floor fp_floor(N,
   tau) = eps*(N + 16)*(1 + tau) relative (eps = FLT_EPSILON): each of the
   N steps adds a relative error of about eps to the sum and to tau, and an
   error in tau is multiplied by tau in exp(-tau). Under double that floor
   is below 1e-12 and never matters. Order fits use only the N whose error
   is well above round-off (> 1e-5 relative under float, > 1e-11 under
   double).

   The problems here: in the homogeneous medium Li is the directional light
   (LIGHT_DIR), in the heterogeneous one E e^{c tau_abs} (LIGHT_TAU), both
   with closed forms (see fixed_problem).

   Groups (in the order fixed_tests() runs them):
     test_names               status strings, method names, version
     test_defaults            options NULL / all-zero / hrm_default_options
     test_empty_interval      t0 == t1
     test_bad_input           exact error status, the error result, nothing
                              else written, caller's structs unchanged
     test_eval_counts         stats.evals / medium_evals / steps per method,
                              one call per abscissa, abscissae where stated
     test_eval_domain         no callback outside [t0, t1]
     test_absent_terms        absent or zero-coefficient terms never called
     test_closed_forms        every method against closed forms, both forms
     test_transmittance       hrm_transmittance against closed forms
     test_emission_convention sigma_a Le against HRM_EMISSION_PER_LENGTH
     test_reentrancy          Li calling hrm for its shadow ray
     test_orders              fitted orders of convergence
     test_monte_carlo         RMS rates, unbiasedness, seeds, sample laws
     test_thick               sigma_t T = 1e4: bounded, error shrinking
     test_rte_stiffness       RTE form: exact stability functions, blow-up
     test_rte_closed_form_tr  the RTE form reports a closed-form Tr

   HRM_TEST_VERBOSE=1 prints every measured error next to its bound. */
#include "common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------
   Local helpers
   ------------------------------------------------------------------------ */
/* Order fits keep only errors above this (well above round-off). */
static double fit_floor(void) { return real_is_float() ? 1e-5 : 1e-11; }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The deterministic fixed-step methods (all of them: the first
   N_METHODS_FIXED of every_method). */
static const hrm_method det_methods[] = { HRM_RECTANGLE, HRM_SIMPSON,
    HRM_EULER, HRM_RK4, HRM_ADAMS_BASHFORTH };
#define N_DET ((int)(sizeof det_methods / sizeof det_methods[0]))

/* This file's problems: le, li (the light of the medium: LIGHT_DIR when
   homogeneous, LIGHT_TAU when heterogeneous), tr (the transmittance
   callback). */
static problem fixed_problem(scene *sc, int kind, int le, int li, int tr)
{
    problem p = make_problem(sc, kind, le, li ? (kind == P_HOM ? LIGHT_DIR : LIGHT_TAU) : LIGHT_NONE);
    p.tr = tr;
    return p;
}

/* lambda: a rate bounding how fast the integrand changes */
static double problem_rate(const problem *p)
{
    double lam = 0;
    int c;
    for (c = 0; c < NCH; ++c) {
        double r;
        if (p->kind == P_HOM)
            r = sig_t_hom(p->sc, c) * (p->light ? 1.0 + p->sc->k : 1.0);
        else
            r = p->sc->a[c] + p->sc->b[c] + p->sc->w;
        if (r > lam) lam = r;
    }
    return lam;
}

/* Reference integrals of Tr(t0, s) S(s) over [a, b]: composite 5-point
   Gauss-Legendre in double over `panels` panels (error ~ (h lambda)^10 /
   1e6: round-off level here). */
typedef struct f_ctx {
    const problem *p;
    int c;
    double t0;
} f_ctx;

static double f_at(const void *ctx, double s)
{
    const f_ctx *x = (const f_ctx *)ctx;
    return exact_f(x->p, x->c, x->t0, s);
}

static double integrate_f(const problem *p, int c, double t0, double a, double b, int panels,
                          int square)
{
    f_ctx x;
    x.p = p;
    x.c = c;
    x.t0 = t0;
    return gl_integrate(f_at, &x, a, b, panels, 5, square, 0.0);
}

/* --- callbacks of this file (user = the scene) --- */

/* the directional light, its transmittance computed by a nested call of
   hrm through sc->shadow_ray */
static void shadow_Li(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    hrm_real tr[NCH];
    hrm_real dist = (hrm_real)(sc->d0 + sc->k * (double)t);
    hrm_status st;
    int c;
    sc->n_li++;
    touch(sc, t);
    if (sc->shadow_use_solve) {
        hrm_result r;
        hrm_options o = hrm_default_options(HRM_SIMPSON);
        o.steps = 4;
        st = hrm_solve(sc->shadow_ray, 0, dist, &o, &r);
        for (c = 0; c < NCH; ++c) tr[c] = r.Tr[c];
    } else {
        st = hrm_transmittance(sc->shadow_ray, 0, dist, NULL, tr, NULL);
    }
    if (st != HRM_OK) sc->shadow_bad_status++;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(sc->E[c] * (double)tr[c]);
}

/* callbacks that a homogeneous medium must never call */
static void never_spectrum(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_never++;
    (void)t;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)-1; /* would be an error */
}

static void never_transmittance(void *user, hrm_real ta, hrm_real tb, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_never++;
    (void)ta; (void)tb;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)2; /* would be an error */
}

/* step medium: sigma_s = 0 below t = 5, sigma_a = 0 above t = 6 (all
   channels); Le and Li record calls where their coefficient is zero. */
static void step_sigma_a(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_sa++;
    touch(sc, t);
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)((double)t > 6.0 ? 0.0 : 0.3);
}

static void step_sigma_s(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_ss++;
    touch(sc, t);
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)((double)t < 5.0 ? 0.0 : 0.4);
}

static void step_Le(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_le++;
    touch(sc, t);
    if ((double)t > 6.0) sc->le_where_sa0++;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)1;
}

static void step_Li(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_li++;
    touch(sc, t);
    if ((double)t < 5.0) sc->li_where_ss0++;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)1;
}

/* Leading relative truncation error of a deterministic method for an
   integrand whose k-th derivative is about lambda^k times itself:
     rectangle (midpoint)  (h lambda)^2 / 24   [exact for an exponential:
                           1 - x/sinh(x), x = h lambda/2]
     Simpson, N panels     (H lambda)^4 / 2880
     Euler                 h lambda / 2         [left/right rectangle rule;
                           RTE form: constant-source error (1-z)^N vs e^-zN]
     RK4                   (h lambda)^4 / 2880 in the optical-depth form
                           (Simpson with H = h); (h lambda)^4 / 120 in the
                           RTE form (R(z) - e^-z = z^5/120 per step)
     Adams-Bashforth 4     251/720 (h lambda)^4 (its error constant)   */
static double trunc_coeff(hrm_method m, hrm_form form, int *order)
{
    switch (m) {
    case HRM_RECTANGLE: *order = 2; return 1.0 / 24;
    case HRM_SIMPSON:   *order = 4; return 1.0 / 2880;
    case HRM_EULER:     *order = 1; return 0.5;
    case HRM_RK4:       *order = 4; return form == HRM_FORM_RTE ? 1.0 / 120 : 1.0 / 2880;
    case HRM_ADAMS_BASHFORTH: *order = 4; return 251.0 / 720;
    default:            *order = 0; return 1.0;
    }
}

static double trunc_bound(hrm_method m, hrm_form form, int n, double T, double lam)
{
    int p;
    double c = trunc_coeff(m, form, &p);
    return c * pow(T / n * lam, p);
}
/* Bound on the error of tau = integral of sigma_t = a + b sin(w s) over T
   when the method integrates it at its own nodes in the optical-depth form.
   Rigorous quadrature (Peano) bounds with |sigma_t^(k)| <= b w^k:
     midpoint T h^2 b w^2/24, Simpson T H^4 b w^4/2880, Euler (left or right
     sums) T h b w/2, RK4 on tau' = sigma_t(s) is Simpson with H = h;
     Adams-Bashforth 4: 251/720 T h^4 b w^4 (its error constant; doubled
     for the RK4 start and higher-order terms).
   In the RTE form Tr itself is marched (dTr/dt = -sigma_t Tr) and its
   relative error accumulates over the optical depth: C (h lambda)^p
   lambda T with the constants of trunc_coeff(). */
static double tau_error_bound(const scene *sc, hrm_method m, hrm_form form, int n,
                             double T, double lam)
{
    double h = T / n, b = 0, w = sc->w;
    int c;
    for (c = 0; c < NCH; ++c)
        if (sc->b[c] > b) b = sc->b[c];
    if (form == HRM_FORM_RTE && is_ivp(m)) {
        int p;
        double coef = trunc_coeff(m, form, &p);
        return coef * pow(h * lam, p) * lam * T;
    }
    switch (m) {
    case HRM_RECTANGLE: return T * h * h * b * w * w / 24;
    case HRM_SIMPSON:
    case HRM_RK4: return T * pow(h, 4) * b * pow(w, 4) / 2880;
    case HRM_EULER: return T * h * b * w / 2;
    default: return 2 * 251.0 / 720 * T * pow(h, 4) * b * pow(w, 4);
    }
}

/* Monte Carlo standard deviation of the estimate of channel c, relative to
   the exact L: uniform  Var = (T int f^2 - (int f)^2)/N;
   stratified (one uniform sample per segment)
   Var = sum_i (h int_i f^2 - (int_i f)^2). Reference quadrature in double. */
static double mc_rel_sigma(const problem *p, int c, double t0, double t1, int n,
                           int stratified)
{
    double T = t1 - t0, var = 0, L = exact_L(p, c, t0, t1);
    if (!stratified) {
        double i1 = integrate_f(p, c, t0, t0, t1, 400, 0);
        double i2 = integrate_f(p, c, t0, t0, t1, 400, 1);
        var = (T * i2 - i1 * i1) / n;
    } else {
        double h = T / n;
        int i;
        for (i = 0; i < n; ++i) {
            double a = t0 + i * h, b = a + h;
            double i1 = integrate_f(p, c, t0, a, b, 2, 0);
            double i2 = integrate_f(p, c, t0, a, b, 2, 1);
            double v = h * i2 - i1 * i1;
            var += v > 0 ? v : 0; /* round-off can make a tiny v negative */
        }
    }
    return sqrt(var) / L;
}
/* ========================================================================
   1. Every method against closed forms
   ======================================================================== */

/* Closed forms (per channel, sigma_t = sigma_a + sigma_s, T = t1 - t0):
   (a) homogeneous emission only:  L = Le sigma_a/sigma_t (1 - e^{-sigma_t T})
   (b) homogeneous single scattering of a directional light whose path length
       in the medium is d0 + k s:  Li(s) = E e^{-sigma_t (d0 + k s)},
       L = sigma_s E e^{-sigma_t (d0 + k t0)} (1 - e^{-sigma_t (1+k) T})
           / (sigma_t (1+k))
   (c) heterogeneous sigma_t(s) = a + b sin(w s), tau_abs(s) = a s +
       b (1 - cos w s)/w, Tr = exp(-(tau_abs(t1) - tau_abs(t0))):
       (c1) sigma_a = sigma_t, no scattering, constant Le: L = Le (1 - Tr)
       (c2) sigma_a = pa sigma_t, sigma_s = (1-pa) sigma_t, constant Le,
            Li(s) = E e^{c tau_abs(s)}:
            L = pa Le (1 - Tr) + (1-pa) E e^{c tau_abs(t0)} (1 - Tr^{1-c})/(1-c)
       (c3) = (c2) with the closed-form transmittance callback as well. */
typedef struct closed_case {
    const char *name;
    int kind, le, li, tr, absorber; /* absorber: sigma_a = sigma_t, no sigma_s */
    double T;
    double K; /* margin over the leading error term, see below */
} closed_case;

static void test_closed_forms(void)
{
    /* K: for (a) and (b) the integrand is a pure exponential of rate lambda
       and the leading term is the error itself (up to O(h lambda) relative),
       so a factor 2 covers the higher-order terms at h lambda <= 0.3.
       For (c) lambda = max(a + b) + w bounds every rate in the integrand
       sigma_t e^{-tau} (the size of sigma_t and the frequency of its sine),
       so C (h lambda)^p already over-estimates the error, tau's own
       quadrature error included: K = 1. (HRM_TEST_VERBOSE=1 prints the
       ratios: 0.5 for (a), (b); 0.001..0.4 for (c).) */
    static const closed_case cases[] = {
        { "(a) homogeneous emission", P_HOM, 1, 0, 0, 0, 6.0, 2.0 },
        { "(b) homogeneous directional light", P_HOM, 0, 1, 0, 0, 6.0, 2.0 },
        { "(a+b) homogeneous both", P_HOM, 1, 1, 0, 0, 6.0, 2.0 },
        { "(c1) heterogeneous absorbing", P_HET, 1, 0, 0, 1, 4.0, 1.0 },
        { "(c2) heterogeneous Le + Li", P_HET, 1, 1, 0, 0, 4.0, 1.0 },
        { "(c3) heterogeneous + Tr callback", P_HET, 1, 1, 1, 0, 4.0, 1.0 },
    };
    static const double t0s[] = { 0.0, 3.0 };
    const int N = 32;
    scene sc;
    int ci, ti, mi, fi, c;
    scene_init(&sc);
    for (ci = 0; ci < (int)(sizeof cases / sizeof cases[0]); ++ci) {
        const closed_case *cs = &cases[ci];
        problem p = fixed_problem(&sc, cs->kind, cs->le, cs->li, cs->tr);
        if (cs->absorber) p.sigmas = SIGMA_A;
        for (ti = 0; ti < 2; ++ti) {
            double t0 = t0s[ti], t1 = t0 + cs->T;
            double lam = problem_rate(&p), tau = max_tau(&p, t0, t1);
            /* Tr: closed form in the medium (homogeneous or the callback):
               only round-off, a few eps relative per unit of tau */
            double tr_exact_bound = 16 * real_eps() * (1.0 + tau);
            for (mi = 0; mi < N_DET; ++mi) {
                hrm_method m = det_methods[mi];
                for (fi = 0; fi < (is_ivp(m) ? 2 : 1); ++fi) {
                    hrm_form form = fi ? HRM_FORM_RTE : HRM_FORM_OPTICAL_DEPTH;
                    hrm_result r;
                    hrm_status st = solve(&p, t0, t1, m, N, form, &r);
                    double bound = cs->K * trunc_bound(m, form, N, cs->T, lam) + fp_floor(N, tau);
                    double eL = rel_err_L(&p, t0, t1, &r), eT = rel_err_Tr(&p, t0, t1, r.Tr);
                    /* Tr: closed form, or exp(-tau) with tau's quadrature
                       error (relative error of Tr = e^{d tau} - 1) */
                    double tbound = (cs->kind == P_HOM || cs->tr) ? tr_exact_bound :
                        expm1(tau_error_bound(&sc, m, form, N, cs->T, lam)) + fp_floor(N, tau);
                    CHECK_INT(st, HRM_OK, "%s t0=%g %s %s: status", cs->name, t0, hrm_method_name(m), form_name(form));
                    CHECK(eL <= bound, "%s t0=%g %s %s N=%d: rel error of L %.3g > bound %.3g",
                          cs->name, t0, hrm_method_name(m), form_name(form), N, eL, bound);
                    CHECK(eT <= tbound, "%s t0=%g %s %s N=%d: rel error of Tr %.3g > bound %.3g",
                          cs->name, t0, hrm_method_name(m), form_name(form), N, eT, tbound);
                    if (verbose())
                        NOTE("%-36s t0=%g %-15s %-13s L err %.2e / bound %.2e = %.3f  Tr err %.2e / %.2e",
                             cs->name, t0, hrm_method_name(m), form_name(form), eL, bound, eL / bound, eT, tbound);
                }
            }
            /* Monte Carlo, uniform and stratified: 5 standard deviations of
               the estimator with the exact Tr (variance from a reference
               quadrature); a fixed seed, so the outcome is reproducible and
               a correct estimator fails with probability < 1e-6. With sigma
               callbacks alone tau comes from the trapezoid rule between
               the sorted samples: its error, summed over spacings g_i, is
               sum g_i^3 max|sigma''|/12, whose mean for N uniform samples
               is T^3 max|sigma''|/(2 N^2); the bias allowance is twice that
               (stratified spacings, at most 2h, give less). */
            {
                int strat;
                double bias = 0;
                if (cs->kind == P_HET && !cs->tr)
                    for (c = 0; c < NCH; ++c) {
                        double bb = pow(cs->T, 3) * sc.b[c] * sc.w * sc.w / (256.0 * 256.0);
                        if (bb > bias) bias = bb;
                    }
                for (strat = 0; strat < 2; ++strat) {
                    hrm_options o = make_options(HRM_MONTE_CARLO, 256, HRM_FORM_DEFAULT);
                    hrm_result r;
                    hrm_status st;
                    o.stratified = strat;
                    o.seed = 12345u + (uint64_t)ci;
                    st = solve_opt(&p, t0, t1, &o, &r);
                    CHECK_INT(st, HRM_OK, "%s t0=%g monte-carlo: status", cs->name, t0);
                    for (c = 0; c < NCH; ++c) {
                        double x = exact_L(&p, c, t0, t1);
                        double sig = mc_rel_sigma(&p, c, t0, t1, 256, strat);
                        double e = fabs((double)r.L[c] - x) / x;
                        double bound = 5 * sig + bias + fp_floor(256, tau);
                        CHECK(e <= bound, "%s t0=%g monte-carlo%s ch %d: rel error %.3g > 5 sigma %.3g",
                              cs->name, t0, strat ? " stratified" : "", c, e, bound);
                        if (bias == 0)
                            CHECK_NEAR(r.Tr[c], exact_tr(&p, c, t0, t1), tr_exact_bound * exact_tr(&p, c, t0, t1),
                                       "%s t0=%g monte-carlo: Tr is the closed form", cs->name, t0);
                        else
                            CHECK_REL(r.Tr[c], exact_tr(&p, c, t0, t1), bias + fp_floor(256, tau),
                                      "%s t0=%g monte-carlo: Tr to the trapezoid's accuracy", cs->name, t0);
                        if (verbose() && c == 0)
                            NOTE("%-36s t0=%g monte-carlo%s: err %.2e = %.2f sigma",
                                 cs->name, t0, strat ? " strat" : "", e, e / sig);
                    }
                }
            }
        }
    }
}

/* ========================================================================
   2. Observed order of convergence
   ======================================================================== */

/* Fits the slope of log(error) against log(N) over nine N growing by
   sqrt(2) (a factor 16), keeping only errors above fit_floor(). The first
   N puts the method in its asymptotic regime: h lambda = 0.5, or 0.125 for
   Adams-Bashforth 4, whose large error constant (251/720) comes with large
   higher-order terms: at h lambda ~ 0.5 its error is not yet monotone in N,
   and in the heterogeneous medium the errors of tau and of A partly cancel
   at fourth order, so that the local slope creeps up to 4 (in a single
   channel: 3.3 at h lambda = 0.15, 3.8 at 0.05, 3.94 at 0.015).
   Bound: +-0.3 under double. There the higher-order terms at the coarsest N
   bias the slope by O(0.1); 0.3 keeps a clear gap to the neighbouring
   integer orders, so a method that lost (or gained) an order fails, and the
   kept points must span a decade of N at least.
   Under float the asymptotic regime of a fourth-order method lies near
   round-off (Simpson at h lambda = 0.5: 2e-5), so only errors > 1e-5 are
   kept, the grid starts at h lambda = 1 (Adams-Bashforth 4 at 0.25: before
   that its error curve bends, local slopes 3 to 5), the kept points
   must be 3 or more spanning a factor 2, and the bound is +-0.5 for the
   larger pre-asymptotic terms. Where fewer than 3 errors are above 1e-5
   (fourth-order methods in the heterogeneous medium) the float build
   notes it and leaves that order to the double builds. */
#define N_ORDER 9

static void order_grid(hrm_method m, double T, double lam, int ns[N_ORDER])
{
    double rho = m == HRM_ADAMS_BASHFORTH ? (real_is_float() ? 0.25 : 0.125)
                                          : real_is_float() ? 1.0 : 0.5;
    double n0 = ceil(T * lam / rho);
    int i;
    for (i = 0; i < N_ORDER; ++i) ns[i] = (int)floor(n0 * pow(2.0, i / 2.0) + 0.5);
}

/* tau: the optical depth, for the round-off floor of each point (a point
   within 4 fp_floor(N, tau) of round-off says nothing of the order). */
static void fit_order(const char *what, const int *ns, const double *err, int expected, double tau)
{
    double x[N_ORDER], y[N_ORDER], slope, tol = real_is_float() ? 0.5 : 0.3;
    double span_needed = real_is_float() ? 2.0 : 10.0;
    int i, n = 0, first = -1, last = -1;
    for (i = 0; i < N_ORDER; ++i) {
        if (err[i] > fit_floor() && err[i] > 4 * fp_floor(ns[i], tau)) {
            x[n] = log((double)ns[i]);
            y[n] = log(err[i]);
            ++n;
            if (first < 0) first = i;
            last = i;
        }
    }
    if (real_is_float() && !(n >= 3 && (double)ns[last] / ns[first] >= span_needed)) {
        NOTE("%-52s %d points above round-off in float: order left to double", what, n);
        return;
    }
    CHECK(n >= 3 && (double)ns[last] / ns[first] >= span_needed,
          "%s: %d errors above round-off, N = %d..%d (first error %.3g)", what, n,
          first >= 0 ? ns[first] : 0, last >= 0 ? ns[last] : 0, err[0]);
    if (n < 3) return;
    slope = -ls_slope(x, y, n);
    CHECK(fabs(slope - expected) <= tol, "%s: observed order %.3f, expected %d +- %.1f",
          what, slope, expected, tol);
    NOTE("%-52s order %.2f (N = %d..%d)", what, slope, ns[first], ns[last]);
}

static void test_orders(void)
{
    scene sc;
    int pi, mi, fi, i;
    scene_init(&sc);
    for (pi = 0; pi < 2; ++pi) {
        /* homogeneous: (b) over T = 6; heterogeneous: (c2) over T = 4
           starting at t0 = 1 */
        problem p = pi == 0 ? fixed_problem(&sc, P_HOM, 0, 1, 0)
                            : fixed_problem(&sc, P_HET, 1, 1, 0);
        double t0 = pi == 0 ? 0.0 : 1.0, t1 = pi == 0 ? 6.0 : 5.0;
        for (mi = 0; mi < N_DET; ++mi) {
            hrm_method m = det_methods[mi];
            for (fi = 0; fi < (is_ivp(m) ? 2 : 1); ++fi) {
                hrm_form form = fi ? HRM_FORM_RTE : HRM_FORM_OPTICAL_DEPTH;
                double eL[N_ORDER], eT[N_ORDER], eLc[N_ORDER], eTc[N_ORDER];
                int order, ns[N_ORDER];
                char what[160];
                trunc_coeff(m, form, &order);
                order_grid(m, t1 - t0, problem_rate(&p), ns);
                for (i = 0; i < N_ORDER; ++i) {
                    hrm_result r;
                    hrm_status st = solve(&p, t0, t1, m, ns[i], form, &r);
                    CHECK_INT(st, HRM_OK, "%s %s N=%d: status", hrm_method_name(m), form_name(form), ns[i]);
                    eL[i] = rel_err_L(&p, t0, t1, &r);
                    eT[i] = rel_err_Tr(&p, t0, t1, r.Tr);
                    eLc[i] = eTc[i] = 0;
                    if (pi == 1 && form == HRM_FORM_OPTICAL_DEPTH) {
                        /* decoupled tau (the layer): Tr within tau_tol =
                           0.01 N^-order absolutely (TRANSMITTANCE), so
                           relatively within that over Tr; round-off on top */
                        hrm_options oc = make_options(m, ns[i], form);
                        double tol = 0.01 * pow((double)ns[i], -(double)order), least = 1, eTd;
                        int c;
                        oc.tau_mode = HRM_TAU_DECOUPLED;
                        CHECK_INT(solve_opt(&p, t0, t1, &oc, &r), HRM_OK, "%s decoupled N=%d: status",
                                  hrm_method_name(m), ns[i]);
                        eTd = rel_err_Tr(&p, t0, t1, r.Tr);
                        for (c = 0; c < NCH; ++c)
                            if (exact_tr(&p, c, t0, t1) < least) least = exact_tr(&p, c, t0, t1);
                        CHECK_NEAR(eTd, 0, (tol > 64 * real_eps() ? tol : 64 * real_eps()) / least +
                                             fp_floor(ns[i], max_tau(&p, t0, t1)),
                                   "heterogeneous %s N=%d: decoupled Tr within tau_tol", hrm_method_name(m), ns[i]);
                        /* coupled tau (the default without a warp): the
                           rule's own order, below */
                        oc.tau_mode = HRM_TAU_COUPLED;
                        CHECK_INT(solve_opt(&p, t0, t1, &oc, &r), HRM_OK, "%s coupled N=%d: status",
                                  hrm_method_name(m), ns[i]);
                        eLc[i] = rel_err_L(&p, t0, t1, &r);
                        eTc[i] = rel_err_Tr(&p, t0, t1, r.Tr);
                    }
                    if (verbose())
                        NOTE("%s %s %s N=%d: L error %.3e Tr error %.3e (coupled: %.3e %.3e)",
                             pi ? "het" : "hom", hrm_method_name(m), form_name(form), ns[i], eL[i],
                             eT[i], eLc[i], eTc[i]);

                }
                snprintf(what, sizeof what, "%s %s, %s: L", pi ? "heterogeneous" : "homogeneous",
                         hrm_method_name(m), form_name(form));
                fit_order(what, ns, eL, order, max_tau(&p, t0, t1));
                if (pi == 1 && form == HRM_FORM_OPTICAL_DEPTH) {
                    /* coupled: tau integrated by the rule at its own nodes,
                       at its own order (Simpson stays fourth order), and L
                       with it */
                    snprintf(what, sizeof what, "heterogeneous %s, coupled: Tr", hrm_method_name(m));
                    fit_order(what, ns, eTc, order, max_tau(&p, t0, t1));
                    snprintf(what, sizeof what, "heterogeneous %s, coupled: L", hrm_method_name(m));
                    fit_order(what, ns, eLc, order, max_tau(&p, t0, t1));
                } else if (pi == 1) {
                    /* the RTE form integrates Tr in its own state */
                    snprintf(what, sizeof what, "heterogeneous %s, %s: Tr", hrm_method_name(m), form_name(form));
                    fit_order(what, ns, eT, order, max_tau(&p, t0, t1));
                }
            }
        }
    }
}

/* ========================================================================
   3. Monte Carlo and jitter: statistics over seeds
   ======================================================================== */

/* Jittered rectangle rule with offset u in [0,1): samples t0 + (i + u) h.
   Its error e(u) = h sum_i f(t0 + (i+u) h) - L has mean 0 over u (each
   segment's sample is uniform in the segment: unbiased), and variance
   int_0^1 e(u)^2 du, computed here by Gauss quadrature over u (5 points
   in each of 8 panels). */
typedef struct jitter_ctx {
    const problem *p;
    int c, n;
    double t0, h, L;
} jitter_ctx;

static double jitter_error(const void *ctx, double u)
{
    const jitter_ctx *x = (const jitter_ctx *)ctx;
    double sum = 0;
    int i;
    for (i = 0; i < x->n; ++i) sum += exact_f(x->p, x->c, x->t0, x->t0 + (i + u) * x->h);
    return sum * x->h - x->L;
}

static double jitter_rel_sigma(const problem *p, int c, double t0, double t1, int n)
{
    jitter_ctx x;
    x.p = p;
    x.c = c;
    x.n = n;
    x.t0 = t0;
    x.h = (t1 - t0) / n;
    x.L = exact_L(p, c, t0, t1);
    return sqrt(gl_integrate(jitter_error, &x, 0.0, 1.0, 8, 5, 1, 0.0)) / x.L;
}

/* Statistics of one randomized estimator over M seeds, channel 0 of (b).
   For each N: RMS relative error against the predicted standard deviation
   (+-15%: the sample RMS of M = 400 draws has a relative standard deviation
   sqrt((kurtosis - 1)/(4M)) <= 0.035 for these near-Gaussian or uniform
   errors, so 15% is over 4 of them), and the mean against the exact value
   (unbiased: |mean - L| <= 5 sigma/sqrt(M)). Then the slope of log RMS
   against log N over N = 16..1024: the slope's standard deviation is about
   0.035/sqrt(sum (log N - mean)^2) = 0.01, so +-0.1 is 10 of them and still
   far from any other rate. */
static void mc_statistics(const char *what, hrm_method m, int jitter, int stratified,
                          double expected_slope)
{
    enum { M = 400, NN = 7 };
    static const int ns[NN] = { 16, 32, 64, 128, 256, 512, 1024 };
    const double t0 = 0.0, t1 = 6.0;
    scene sc;
    problem p;
    double lx[NN], ly[NN], slope;
    int ni, s;
    scene_init(&sc);
    p = fixed_problem(&sc, P_HOM, 0, 1, 0);
    for (ni = 0; ni < NN; ++ni) {
        int n = ns[ni];
        double L = exact_L(&p, 0, t0, t1), sum = 0, sum2 = 0, mean, rms, pred;
        long bad = 0;
        hrm_options o = make_options(m, n, HRM_FORM_DEFAULT);
        o.jitter = jitter;
        o.stratified = stratified;
        for (s = 0; s < M; ++s) {
            hrm_result r;
            double e;
            o.seed = (uint64_t)(1000 + s);
            if (solve_opt(&p, t0, t1, &o, &r) != HRM_OK) bad++;
            e = ((double)r.L[0] - L) / L;
            sum += e;
            sum2 += e * e;
        }
        CHECK_INT(bad, 0, "%s N=%d: solves that failed", what, n);
        mean = sum / M;
        rms = sqrt(sum2 / M);
        pred = jitter ? jitter_rel_sigma(&p, 0, t0, t1, n)
                      : mc_rel_sigma(&p, 0, t0, t1, n, stratified);
        CHECK(fabs(rms / pred - 1) <= 0.15 + fp_floor(n, 4.5) / pred,
              "%s N=%d: RMS error %.4g vs predicted sigma %.4g (ratio %.3f)",
              what, n, rms, pred, rms / pred);
        CHECK(fabs(mean) <= 5 * pred / sqrt((double)M) + fp_floor(n, 4.5),
              "%s N=%d: mean error %.3g over %d seeds, 5 sigma/sqrt(M) = %.3g (biased?)",
              what, n, mean, M, 5 * pred / sqrt((double)M));
        if (verbose())
            NOTE("%s N=%4d rms %.3e predicted %.3e ratio %.3f mean %.2e", what, n, rms,
                 pred, rms / pred, mean);
        lx[ni] = log((double)n);
        ly[ni] = log(rms);
    }
    slope = ls_slope(lx, ly, NN);
    CHECK(fabs(slope - expected_slope) <= 0.1, "%s: RMS error ~ N^%.3f, expected N^%.1f +- 0.1",
          what, slope, expected_slope);
    NOTE("%-40s RMS ~ N^%.3f", what, slope);
}

/* Kolmogorov-Smirnov distance of n samples in [0, 1) from the uniform
   distribution (sorts x). */
static double ks_uniform(double *x, int n)
{
    double d = 0;
    int i;
    qsort(x, (size_t)n, sizeof x[0], cmp_double);
    for (i = 0; i < n; ++i) {
        double lo = x[i] - (double)i / n, hi = (double)(i + 1) / n - x[i];
        if (lo > d) d = lo;
        if (hi > d) d = hi;
    }
    return d;
}

/* The samples themselves: pooled over M seeds, uniform MC positions are
   uniform on [t0, t1]; stratified, the offset of each sample within its
   segment is uniform; jittered, the one offset per ray is uniform over
   seeds. Kolmogorov-Smirnov: P(sqrt(n) D > 2.2) < 2e-4 for a correct
   generator (fixed seeds: reproducible). This catches a biased sampler
   whose effect on a smooth integral is below the statistical bounds. */
static void mc_sample_distribution(void)
{
    enum { M = 400, N = 16 };
    double pool[M * N];
    const double t0 = 1.0, t1 = 5.0, h = (t1 - t0) / N;
    scene sc;
    problem p;
    int v, s, i;
    scene_init(&sc);
    p = fixed_problem(&sc, P_HOM, 1, 0, 0);
    for (v = 0; v < 3; ++v) {
        hrm_options o = make_options(v == 2 ? HRM_RECTANGLE : HRM_MONTE_CARLO, N, HRM_FORM_DEFAULT);
        int n = 0;
        double d;
        o.stratified = v == 1;
        o.jitter = v == 2;
        for (s = 0; s < M; ++s) {
            hrm_result r;
            o.seed = (uint64_t)(5000 + s);
            scene_reset_counts(&sc);
            solve_opt(&p, t0, t1, &o, &r);
            if (sc.log_n != N) continue; /* counted in test_eval_counts */
            qsort(sc.log_le, N, sizeof sc.log_le[0], cmp_double);
            if (v == 2) {
                pool[n++] = (sc.log_le[0] - t0) / h;
            } else {
                for (i = 0; i < N; ++i)
                    pool[n++] = v == 0 ? (sc.log_le[i] - t0) / (t1 - t0) : (sc.log_le[i] - t0) / h - i;
            }
        }
        d = ks_uniform(pool, n);
        CHECK(sqrt((double)n) * d <= 2.2 + 4 * real_eps() * N * sqrt((double)n),
              "%s: samples not uniform, KS sqrt(n) D = %.3f over %d samples",
              v == 0 ? "monte-carlo uniform" : v == 1 ? "monte-carlo stratified offsets" : "jitter offsets",
              sqrt((double)n) * d, n);
    }
}

static void test_monte_carlo(void)
{
    scene sc;
    problem p;
    int v;
    /* uniform: N^-1/2; stratified on a smooth integrand: the per-segment
       variance is h^2 f'^2/12, so the RMS is N^-3/2; jittered rectangle:
       one offset per ray, error h (u - 1/2)(f(t0) - f(t1)): N^-1 */
    mc_statistics("monte-carlo uniform", HRM_MONTE_CARLO, 0, 0, -0.5);
    mc_statistics("monte-carlo stratified", HRM_MONTE_CARLO, 0, 1, -1.5);
    mc_statistics("rectangle jittered", HRM_RECTANGLE, 1, 0, -1.0);
    mc_sample_distribution();

    /* same seed: identical result; other seed: different result */
    scene_init(&sc);
    p = fixed_problem(&sc, P_HOM, 1, 1, 0);
    for (v = 0; v < 3; ++v) {
        hrm_options o = make_options(v == 2 ? HRM_RECTANGLE : HRM_MONTE_CARLO, 16, HRM_FORM_DEFAULT);
        hrm_result r1, r2, r3;
        int c, same = 1, differ = 0;
        o.stratified = v == 1;
        o.jitter = v == 2;
        o.seed = 77;
        solve_opt(&p, 0, 6, &o, &r1);
        solve_opt(&p, 0, 6, &o, &r2);
        o.seed = 78;
        solve_opt(&p, 0, 6, &o, &r3);
        for (c = 0; c < NCH; ++c) {
            if (r1.L[c] != r2.L[c]) same = 0;
            if (r1.L[c] != r3.L[c]) differ = 1;
        }
        CHECK(same, "variant %d: the same seed gives the same L", v);
        CHECK(differ, "variant %d: seeds 77 and 78 give the same L", v);
    }
    /* without jitter the rectangle rule is deterministic: seed ignored */
    {
        hrm_options o = make_options(HRM_RECTANGLE, 16, HRM_FORM_DEFAULT);
        hrm_result r1, r2;
        int c, same = 1;
        o.seed = 1;
        solve_opt(&p, 0, 6, &o, &r1);
        o.seed = 999;
        solve_opt(&p, 0, 6, &o, &r2);
        for (c = 0; c < NCH; ++c)
            if (r1.L[c] != r2.L[c]) same = 0;
        CHECK(same, "rectangle without jitter does not depend on the seed");
    }
}

/* ========================================================================
   4. Exact evaluation counts
   ======================================================================== */

/* The contract's counts of abscissae (source evaluations) for N steps. */
static long expected_evals(hrm_method m, int n)
{
    switch (m) {
    case HRM_RECTANGLE: return n;
    case HRM_SIMPSON: return 2L * n + 1;
    case HRM_MONTE_CARLO: return n;
    case HRM_EULER: return n;
    case HRM_RK4: return 2L * n + 1;
    case HRM_ADAMS_BASHFORTH: return n >= 4 ? n + 3L : 2L * n + 1;
    default: return -1;
    }
}

/* Le's abscissae, sorted: no abscissa is evaluated twice, and where the
   contract fixes them, they are where it says. */
static void check_abscissae(scene *sc, hrm_method m, const hrm_options *o, double t0,
                            double t1, const char *what)
{
    int n = o->steps, i, dup = 0, misplaced = 0;
    double h = (t1 - t0) / n, tol = 4 * real_eps() * (fabs(t0) + fabs(t1));
    qsort(sc->log_le, (size_t)sc->log_n, sizeof sc->log_le[0], cmp_double);
    for (i = 1; i < sc->log_n; ++i)
        if (!(sc->log_le[i] > sc->log_le[i - 1])) dup++;
    CHECK_INT(dup, 0, "%s: abscissae evaluated more than once", what);
    if (sc->log_n != (int)expected_evals(m, n)) return; /* reported elsewhere */
    for (i = 0; i < sc->log_n; ++i) {
        double t = sc->log_le[i];
        if (m == HRM_RECTANGLE && !o->jitter) {
            /* midpoint of each segment */
            if (fabs(t - (t0 + (i + 0.5) * h)) > tol) misplaced++;
        } else if (m == HRM_RECTANGLE) {
            /* one offset for the whole ray: equal spacing h, first sample
               in the first segment */
            if (fabs(t - sc->log_le[0] - i * h) > tol) misplaced++;
        } else if (m == HRM_SIMPSON) {
            /* panel ends and midpoints: t0 + i H/2 */
            if (fabs(t - (t0 + i * 0.5 * h)) > tol) misplaced++;
        } else if (m == HRM_MONTE_CARLO && o->stratified) {
            /* one sample in each segment [t0 + i h, t0 + (i+1) h] */
            if (t < t0 + i * h - tol || t > t0 + (i + 1) * h + tol) misplaced++;
        }
    }
    if (m == HRM_RECTANGLE && o->jitter)
        if (sc->log_le[0] < t0 - tol || sc->log_le[0] > t0 + h + tol) misplaced++;
    CHECK_INT(misplaced, 0, "%s: abscissae away from the contract's positions", what);
}

static void test_eval_counts(void)
{
    static const int ns[] = { 1, 2, 3, 4, 5, 8, 17 };
    scene sc;
    int mi, ni, fi, v;
    const double t0 = 1.0, t1 = 5.0;
    scene_init(&sc);
    for (v = 0; v < 4; ++v) {
        /* v = 0: homogeneous; 1: heterogeneous sigma callbacks; 2: with the
           transmittance callback; 3: as 1 with jitter / stratified MC.
           The source is present everywhere (sigma_a, sigma_s > 0). */
        problem p = fixed_problem(&sc, v == 0 ? P_HOM : P_HET, 1, 1, v == 2);
        for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
            hrm_method m = every_method[mi];
            if (v == 3 && m != HRM_RECTANGLE && m != HRM_MONTE_CARLO) continue;
            for (fi = 0; fi < (is_ivp(m) ? 2 : 1); ++fi) {
                hrm_form form = fi ? HRM_FORM_RTE : HRM_FORM_OPTICAL_DEPTH;
                for (ni = 0; ni < (int)(sizeof ns / sizeof ns[0]); ++ni) {
                    int n = ns[ni];
                    long ev = expected_evals(m, n);
                    hrm_options o = make_options(m, n, form);
                    hrm_medium med = problem_medium(&p);
                    hrm_result r;
                    hrm_status st;
                    char what[160];
                    snprintf(what, sizeof what, "%s %s %s N=%d",
                             v == 0 ? "homogeneous" : v == 1 ? "heterogeneous" :
                             v == 2 ? "transmittance callback" : "randomized",
                             hrm_method_name(m), form_name(form), n);
                    o.seed = 5;
                    /* one sigma evaluation per abscissa: the coupled
                       contract (decoupled counts: test_transmittance.c) */
                    o.tau_mode = HRM_TAU_COUPLED;
                    o.jitter = v == 3;
                    o.stratified = v == 3;
                    if (v == 0) { /* present but must be ignored */
                        med.sigma_a = never_spectrum;
                        med.sigma_s = never_spectrum;
                        med.sigma_t = never_spectrum;
                        med.transmittance = never_transmittance;
                    }
                    scene_reset_counts(&sc);
                    st = hrm_solve(&med, (hrm_real)t0, (hrm_real)t1, &o, &r);
                    /* (N = 1 or 2: L past twice its physical bound, or
                       the RTE form's Tr outside [0, 1]: a warning) */
                    CHECK(st == HRM_OK || st == HRM_WARN_TOLERANCE, "%s: status %d", what, (int)st);
                    CHECK_INT(r.stats.evals, ev, "%s: stats.evals", what);
                    CHECK_INT(r.stats.steps, n, "%s: stats.steps", what);
                    CHECK_INT(r.stats.rejected, 0, "%s: stats.rejected", what);
                    CHECK_INT(sc.n_le, ev, "%s: Le calls", what);
                    CHECK_INT(sc.n_li, ev, "%s: Li calls", what);
                    if (v == 0) {
                        CHECK_INT(r.stats.medium_evals, 0, "%s: stats.medium_evals", what);
                        CHECK_INT(sc.n_never, 0, "%s: sigma/transmittance callbacks called", what);
                    } else if (v == 2) {
                        /* one per abscissa, plus the final Tr(t0, t1) */
                        CHECK_INT(r.stats.medium_evals, ev + 1, "%s: stats.medium_evals", what);
                        /* Tr(t0, s) with the sigmas at each abscissa where
                           the form needs it (optical depth), and Tr(t0, t1) */
                        CHECK_INT(sc.n_tr, form == HRM_FORM_RTE ? 1 : r.stats.medium_evals,
                                  "%s: transmittance calls", what);
                        CHECK_INT(sc.n_sa, ev, "%s: sigma_a calls (once per abscissa)", what);
                        CHECK_INT(sc.n_ss, ev, "%s: sigma_s calls (once per abscissa)", what);
                    } else {
                        CHECK_INT(r.stats.medium_evals, ev, "%s: stats.medium_evals", what);
                        CHECK_INT(sc.n_sa, ev, "%s: sigma_a calls (once per abscissa)", what);
                        CHECK_INT(sc.n_ss, ev, "%s: sigma_s calls (once per abscissa)", what);
                    }
                    check_abscissae(&sc, m, &o, t0, t1, what);
                }
            }
        }
    }
}

/* ========================================================================
   5. Where callbacks are called
   ======================================================================== */

static void test_eval_domain(void)
{
    /* t0 = 0.17, t1 = 0.46: t0 + (t1 - t0) rounds above t1 in float and in
       double alike, so a last abscissa computed as t0 + T lies outside.
       Bounds are compared in hrm_real, where the solver works. */
    static const int ns[] = { 1, 3, 7, 13 };
    const hrm_real t0 = (hrm_real)0.17, t1 = (hrm_real)0.46;
    scene sc;
    int mi, ni, fi, s, v;
    scene_init(&sc);
    for (v = 0; v < 2; ++v) {
        problem p = fixed_problem(&sc, P_HET, 1, 1, v == 1);
        hrm_medium med = problem_medium(&p);
        med.sigma_t = het_sigma_t; /* given explicitly: its calls are recorded too */
        for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
            hrm_method m = every_method[mi];
            int randomized = m == HRM_MONTE_CARLO || m == HRM_RECTANGLE;
            for (fi = 0; fi < (is_ivp(m) ? 2 : 1); ++fi) {
                for (ni = 0; ni < 4; ++ni) {
                    long outside = 0, reversed = 0, bad = 0;
                    for (s = 0; s < (randomized ? 60 : 1); ++s) {
                        hrm_options o = make_options(m, ns[ni], fi ? HRM_FORM_RTE : HRM_FORM_OPTICAL_DEPTH);
                        hrm_result r;
                        o.seed = (uint64_t)(s * 7919 + 1);
                        o.jitter = s & 1;      /* rectangle: half jittered */
                        o.stratified = s & 1;  /* MC: half stratified */
                        scene_reset_counts(&sc);
                        if (hrm_solve(&med, t0, t1, &o, &r) != HRM_OK) bad++;
                        if (sc.tmin < (double)t0 || sc.tmax > (double)t1) outside++;
                        if (v == 1 && (sc.tr_amin < (double)t0 || sc.tr_bmax > (double)t1)) outside++;
                        reversed += sc.tr_reversed;
                    }
                    CHECK_INT(bad, 0, "%s N=%d: status", hrm_method_name(m), ns[ni]);
                    CHECK_INT(outside, 0, "%s %s%s N=%d: solves with a callback called outside [t0, t1]",
                              hrm_method_name(m), fi ? "rte " : "", v ? "(transmittance callback)" : "", ns[ni]);
                    CHECK_INT(reversed, 0, "%s N=%d: transmittance called with ta > tb", hrm_method_name(m), ns[ni]);
                }
            }
        }
    }
}

static void test_absent_terms(void)
{
    scene sc;
    hrm_medium med;
    hrm_result r;
    hrm_options o;
    int mi, fi, c;
    scene_init(&sc);
    for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
        hrm_method m = every_method[mi];
        for (fi = 0; fi < (is_ivp(m) ? 2 : 1); ++fi) {
            hrm_form form = fi ? HRM_FORM_RTE : HRM_FORM_OPTICAL_DEPTH;
            const char *fn = form_name(form);
            o = make_options(m, 16, form);
            o.seed = 3;

            /* step medium: Li never called where sigma_s = 0 (t < 5), Le
               never where sigma_a = 0 (t > 6) */
            med = zero_medium();
            med.user = &sc;
            med.sigma_a = step_sigma_a;
            med.sigma_s = step_sigma_s;
            med.Le = step_Le;
            med.Li = step_Li;
            scene_reset_counts(&sc);
            CHECK_INT(hrm_solve(&med, 3, 8, &o, &r), HRM_OK, "%s %s step medium: status", hrm_method_name(m), fn);
            CHECK_INT(sc.li_where_ss0, 0, "%s %s: Li called where sigma_s = 0", hrm_method_name(m), fn);
            CHECK_INT(sc.le_where_sa0, 0, "%s %s: Le called where sigma_a = 0", hrm_method_name(m), fn);
            CHECK(sc.n_li > 0 && sc.n_le > 0, "%s %s: Le and Li called where they matter", hrm_method_name(m), fn);
            /* per-length emission is a source wherever Le is given */
            med.flags = HRM_EMISSION_PER_LENGTH;
            scene_reset_counts(&sc);
            CHECK_INT(hrm_solve(&med, 3, 8, &o, &r), HRM_OK, "%s %s per length: status", hrm_method_name(m), fn);
            CHECK(sc.le_where_sa0 > 0, "%s %s per length: Le not called where sigma_a = 0", hrm_method_name(m), fn);
            CHECK_INT(sc.li_where_ss0, 0, "%s %s per length: Li called where sigma_s = 0", hrm_method_name(m), fn);

            /* sigma_s NULL: Li never called; sigma_a NULL: Le never called.
               With neither, no source: L = 0 exactly, no evaluation. */
            med = zero_medium();
            med.user = &sc;
            med.sigma_t = het_sigma_t;
            med.Le = const_Le;
            med.Li = light_Li(LIGHT_TAU);
            scene_reset_counts(&sc);
            CHECK_INT(hrm_solve(&med, 0, 4, &o, &r), HRM_OK, "%s %s no sigma_a/s: status", hrm_method_name(m), fn);
            CHECK_INT(sc.n_le + sc.n_li, 0, "%s %s: Le/Li called with sigma_a, sigma_s NULL", hrm_method_name(m), fn);
            CHECK_INT(r.stats.evals, 0, "%s %s: evals with no source", hrm_method_name(m), fn);
            for (c = 0; c < NCH; ++c)
                CHECK(r.L[c] == 0, "%s %s: L = 0 without a source (got %g)", hrm_method_name(m), fn, (double)r.L[c]);

            /* homogeneous with const_sigma_s = 0: Li never called;
               const_sigma_a = 0: Le never called */
            med = zero_medium();
            med.user = &sc;
            med.flags = HRM_MEDIUM_HOMOGENEOUS;
            med.Le = const_Le;
            med.Li = light_Li(LIGHT_DIR);
            for (c = 0; c < NCH; ++c) med.const_sigma_a[c] = (hrm_real)0.5;
            scene_reset_counts(&sc);
            CHECK_INT(hrm_solve(&med, 0, 4, &o, &r), HRM_OK, "%s %s: status", hrm_method_name(m), fn);
            CHECK_INT(sc.n_li, 0, "%s %s: Li called in a medium with sigma_s = 0", hrm_method_name(m), fn);
            CHECK_INT(sc.n_le, r.stats.evals, "%s %s: Le calls = evals", hrm_method_name(m), fn);
            for (c = 0; c < NCH; ++c) {
                med.const_sigma_a[c] = 0;
                med.const_sigma_s[c] = (hrm_real)0.5;
            }
            scene_reset_counts(&sc);
            CHECK_INT(hrm_solve(&med, 0, 4, &o, &r), HRM_OK, "%s %s: status", hrm_method_name(m), fn);
            CHECK_INT(sc.n_le, 0, "%s %s: Le called in a medium with sigma_a = 0", hrm_method_name(m), fn);
            CHECK_INT(sc.n_li, r.stats.evals, "%s %s: Li calls = evals", hrm_method_name(m), fn);

            /* an empty medium: nothing to evaluate, L = 0, Tr = 1 */
            med = zero_medium();
            scene_reset_counts(&sc);
            CHECK_INT(hrm_solve(&med, 0, 4, &o, &r), HRM_OK, "%s %s empty medium: status", hrm_method_name(m), fn);
            CHECK_INT(r.stats.evals, 0, "%s %s empty medium: evals", hrm_method_name(m), fn);
            for (c = 0; c < NCH; ++c)
                CHECK(r.L[c] == 0 && r.Tr[c] == 1, "%s %s empty medium: L = %g, Tr = %g", hrm_method_name(m), fn,
                      (double)r.L[c], (double)r.Tr[c]);
        }
    }
}

/* ========================================================================
   6. Thick media and the stiffness of the RTE form
   ======================================================================== */

static void test_thick(void)
{
    scene sc;
    int mi, n, c, s;
    scene_init(&sc);
    /* sigma_t T = 1e4 (sigma_t = 1000 over T = 10), homogeneous and
       heterogeneous (sigma_t = 1000 (1 + 0.5 sin 2s) over T = 10). In the
       optical-depth form every method must stay bounded however few the
       steps: finite L >= 0 and 0 <= Tr <= 1. */
    for (c = 0; c < NCH; ++c) {
        sc.sig_a[c] = 400.0 + 100.0 * c / NCH;
        sc.sig_s[c] = 1000.0 - sc.sig_a[c];
        sc.a[c] = 1000.0;
        sc.b[c] = 500.0;
    }
    sc.cexp = 0; /* heterogeneous Li = E (e^{c tau} would overflow) */
    for (s = 0; s < 2; ++s) {
        problem p = fixed_problem(&sc, s == 0 ? P_HOM : P_HET, 1, 1, 0);
        for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
            hrm_method m = every_method[mi];
            long unbounded = 0, bad = 0;
            for (n = 1; n <= 16; ++n) {
                int variant;
                for (variant = 0; variant < 2; ++variant) {
                    hrm_options o = make_options(m, n, HRM_FORM_OPTICAL_DEPTH);
                    hrm_result r;
                    o.seed = (uint64_t)n;
                    o.jitter = variant;
                    o.stratified = variant;
                    hrm_status st = solve_opt(&p, 0, 10, &o, &r);
                    /* a step count too coarse for the medium: L past twice
                       its physical bound, the bound with
                       HRM_WARN_TOLERANCE (hrm__finish) */
                    if (st != HRM_OK && st != HRM_WARN_TOLERANCE) bad++;
                    for (c = 0; c < NCH; ++c) {
                        double L = (double)r.L[c], Tr = (double)r.Tr[c];
                        if (!(finite_d(L) && L >= 0 && Tr >= 0 && Tr <= 1)) {
                            if (unbounded == 0)
                                NOTE("%s N=%d: L = %g, Tr = %g", hrm_method_name(m), n, L, Tr);
                            unbounded++;
                        }
                    }
                }
            }
            CHECK_INT(bad, 0, "thick %s %s: solves that returned neither HRM_OK nor HRM_WARN_TOLERANCE", s ? "heterogeneous" : "homogeneous", hrm_method_name(m));
            CHECK_INT(unbounded, 0, "thick %s %s N=1..16: channels with L < 0, L not finite or Tr outside [0,1]",
                      s ? "heterogeneous" : "homogeneous", hrm_method_name(m));
        }
    }
    /* The error shrinks as N grows: homogeneous (a+b), N = 16, 64, ...,
       65536 (h sigma_t from 625 down to 0.15). For the rules with positive
       weights each error must not exceed the previous one: for an
       exponential integrand of rate lambda their ratio to the exact value
       is x/sinh x (midpoint, x = h lambda/2), y/(1 - e^{-y}) (Euler,
       y = h lambda), (x/3)(1 + 4e^{-x} + e^{-2x})/(1 - e^{-2x}) (Simpson,
       and RK4 here, x = H lambda/2), each monotone in h, and the two
       exponentials of (a+b) err the same way. Adams-Bashforth 4 is not
       monotone while h lambda > 0.25 (see the order test), so for it only
       the last error must be below the first. At N = 65536 every method
       must be in its asymptotic regime: within twice its leading error
       term (as in group 1), lambda = 1.5 sigma_t (the light's rate). The
       round-off floor counts only the first 30 optical depths, where the
       integrand is not negligible. */
    {
        problem p = fixed_problem(&sc, P_HOM, 1, 1, 0);
        double lam = problem_rate(&p);
        for (mi = 0; mi < N_DET; ++mi) {
            hrm_method m = det_methods[mi];
            double prev = 1e300, first = -1, e = 0;
            long grew = 0;
            for (n = 16; n <= 65536; n *= 4) {
                hrm_result r;
                /* from the first N whose rule stays within twice the
                   physical bound (coarser: the bound itself, exact here,
                   with HRM_WARN_TOLERANCE) */
                if (solve(&p, 0, 10, m, n, HRM_FORM_OPTICAL_DEPTH, &r) != HRM_OK) continue;
                e = rel_err_L(&p, 0, 10, &r);
                if (first < 0) first = e;
                if (verbose()) NOTE("thick %s N=%d: rel error %.3g", hrm_method_name(m), n, e);
                if (!(e <= prev * (1 + 1e-9)) && m != HRM_ADAMS_BASHFORTH) {
                    NOTE("thick %s: rel. deviation %.6g at N=%d after %.6g", hrm_method_name(m), e, n, prev);
                    grew++;
                }
                prev = e;
            }
            CHECK_INT(grew, 0, "thick %s: the error grew with N", hrm_method_name(m));
            CHECK(e < first, "thick %s: error %.3g at N=65536 not below %.3g at N=16", hrm_method_name(m), e, first);
            {
                double bound = 2 * trunc_bound(m, HRM_FORM_OPTICAL_DEPTH, 65536, 10, lam) +
                               fp_floor(65536 * 30 / 10000, 30);
                CHECK(e <= bound, "thick %s N=65536: rel error %.3g > bound %.3g", hrm_method_name(m), e, bound);
            }
        }
    }
}

/* The RTE form marches L, and Tr alongside (dTr/dt = -sigma_t Tr) where Tr
   has to be integrated. Where the medium has a closed form, the manual says
   what Tr is: "Homogeneous media: ... Tr is exp(-sigma_t*(tb-ta)) in closed
   form", and a transmittance callback is "closed-form Tr(ta, tb) of the eye
   ray. NULL: hrm integrates sigma_t", counted as one more medium
   evaluation. The form changes how L is computed, not what a closed form
   is: the result's Tr must be the closed form in the RTE form too (also
   where the march blows up: Tr stays in [0, 1]). */
static void test_rte_closed_form_tr(void)
{
    scene sc;
    int mi, v, c;
    scene_init(&sc);
    for (v = 0; v < 2; ++v) {
        problem p = fixed_problem(&sc, v == 0 ? P_HOM : P_HET, 1, 1, v == 1);
        for (mi = 0; mi < N_DET; ++mi) {
            hrm_method m = det_methods[mi];
            hrm_result r;
            double tau = max_tau(&p, 1, 5);
            long ev = expected_evals(m, 8);
            int ok = 1;
            if (!is_ivp(m)) continue;
            scene_reset_counts(&sc);
            CHECK_INT(solve(&p, 1, 5, m, 8, HRM_FORM_RTE, &r), HRM_OK, "%s: status", hrm_method_name(m));
            for (c = 0; c < NCH; ++c)
                if (!(fabs((double)r.Tr[c] - exact_tr(&p, c, 1, 5)) <=
                      16 * real_eps() * (1 + tau) * exact_tr(&p, c, 1, 5)))
                    ok = 0;
            CHECK(ok, "%s rte, %s: Tr = %.9g, closed form %.9g", hrm_method_name(m),
                  v ? "transmittance callback" : "homogeneous", (double)r.Tr[0], exact_tr(&p, 0, 1, 5));
            if (v == 1) {
                CHECK_INT(r.stats.medium_evals, ev + 1, "%s rte, transmittance callback: medium_evals", hrm_method_name(m));
                CHECK_INT(sc.n_tr, 1, "%s rte, transmittance callback: Tr(t0, t1) called once", hrm_method_name(m));
            }
        }
    }
    /* Euler, h sigma_t = 4, 20 steps: L blows up as it should; Tr is
       e^{-80}, not (1 - 4)^20 */
    {
        problem p = fixed_problem(&sc, P_HOM, 1, 0, 0);
        hrm_result r;
        for (c = 0; c < NCH; ++c) {
            sc.sig_a[c] = 1.0;
            sc.sig_s[c] = 0.0;
        }
        solve(&p, 0, 80, HRM_EULER, 20, HRM_FORM_RTE, &r);
        CHECK(r.Tr[0] >= 0 && r.Tr[0] <= 1, "euler rte h sigma_t = 4: Tr = %g outside [0, 1]", (double)r.Tr[0]);
    }
}

/* RTE form, homogeneous, constant source S = sigma_a Le (sigma_a = sigma_t
   = 1, Le = 1, no scattering). Marched from t1 with L = 0, a one-step
   method multiplies the deviation from the fixed point S/sigma_t by its
   stability function R(z), z = h sigma_t, every step, so exactly
   L_N = (S/sigma_t)(1 - R(z)^N): Euler R = 1 - z, RK4
   R = 1 - z + z^2/2 - z^3/6 + z^4/24. Checked to round-off (16 eps N
   relative to the largest term: N roundings of R, and an error of eps z in
   h amplified N |R'(z)/R| z <= 4.4 N times), and the blow-up measured from the growth of the
   error with N at fixed h. */
static void test_rte_stiffness(void)
{
    scene sc;
    problem p;
    int c, v;
    scene_init(&sc);
    for (c = 0; c < NCH; ++c) {
        sc.sig_a[c] = 1.0;
        sc.sig_s[c] = 0.0;
        sc.le[c] = 1.0;
    }
    p = fixed_problem(&sc, P_HOM, 1, 0, 0);
    for (v = 0; v < 4; ++v) {
        /* Euler z = 4 (|R| = 3), z = 0.5; RK4 z = 3 (R = 1.375, beyond
           2.785), z = 2.6 (R = 0.755, inside) */
        hrm_method m = v < 2 ? HRM_EULER : HRM_RK4;
        double z = v == 0 ? 4.0 : v == 1 ? 0.5 : v == 2 ? 3.0 : 2.6;
        double R = m == HRM_EULER ? 1 - z : 1 - z + z * z / 2 - z * z * z / 6 + z * z * z * z / 24;
        double lx[11], ly[11], slope;
        int n, k = 0;
        for (n = 20; n <= 30; ++n) {
            hrm_result r;
            double T = z * n, pred = 1 - pow(R, n), exact = -expm1(-T);
            hrm_status st = solve(&p, 0, T, m, n, HRM_FORM_RTE, &r);
            CHECK(st >= 0, "%s rte z=%g N=%d: status %d", hrm_method_name(m), z, n, (int)st);
            CHECK_NEAR(r.L[0], pred, 16 * real_eps() * n * (1 + fabs(pow(R, n))),
                       "%s rte z=%g N=%d: L = (1 - R^N) S/sigma_t", hrm_method_name(m), z, n);
            lx[k] = n;
            ly[k] = log(fabs((double)r.L[0] - exact));
            ++k;
        }
        slope = ls_slope(lx, ly, k);
        if (fabs(R) > 1) {
            /* |error| ~ |R|^N: slope log|R| (0.01: the fit is exact up to
               |R|^-N and round-off) */
            CHECK_NEAR(slope, log(fabs(R)), 0.01, "%s rte z=%g: log|error| grows by log|R| per step",
                       hrm_method_name(m), z);
            NOTE("%s rte h*sigma_t=%g: |L - exact| grows by %.4f per step (|R(z)| = %g)", hrm_method_name(m), z,
                 exp(slope), fabs(R));
        } else {
            /* stable: |L - exact| <= |R|^N + e^{-zN}, tiny here */
            CHECK(fabs(exp(ly[k - 1])) <= pow(fabs(R), 30) + exp(-z * 30) + 4 * real_eps() * 30,
                  "%s rte z=%g: bounded", hrm_method_name(m), z);
        }
    }
    /* Adams-Bashforth 4: stable interval (-0.3, 0). At z = 0.5 the
       dominant root of zeta^4 - zeta^3 = -z (55 zeta^3 - 59 zeta^2 +
       37 zeta - 9)/24 is -1.43730 (next 0.619, so after 20 steps it
       dominates to 1e-7): the error grows by 1.4373 per step (+-0.005).
       At z = 0.2 the roots are inside the unit circle (0.819): bounded. */
    {
        double lx[21], ly[21], slope;
        int n, k = 0;
        for (n = 30; n <= 50; ++n) {
            hrm_result r;
            double T = 0.5 * n;
            solve(&p, 0, T, HRM_ADAMS_BASHFORTH, n, HRM_FORM_RTE, &r);
            lx[k] = n;
            ly[k] = log(fabs((double)r.L[0] + expm1(-T)));
            ++k;
        }
        slope = ls_slope(lx, ly, k);
        CHECK_NEAR(exp(slope), 1.4373033, 0.005, "adams-bashforth rte z=0.5: growth factor per step");
        NOTE("adams-bashforth rte h*sigma_t=0.5: |L - exact| grows by %.4f per step (root 1.4373)", exp(slope));
        for (n = 30; n <= 50; n += 20) {
            hrm_result r;
            double T = 0.2 * n;
            solve(&p, 0, T, HRM_ADAMS_BASHFORTH, n, HRM_FORM_RTE, &r);
            /* stable: fourth-order accurate, rel error <= 251/720 z^4 x 2 */
            CHECK_REL(r.L[0], -expm1(-T), 2 * 251.0 / 720 * pow(0.2, 4) + fp_floor(n, T),
                      "adams-bashforth rte z=0.2 N=%d: stable and accurate", n);
        }
    }
    /* The optical-depth form at the same steps stays bounded: the
       integrand Tr S is at most S = 1, and no weight of these rules exceeds
       (55 + 59 + 37 + 9)/24 < 7 times h, so 0 <= L <= 7 S T, where the RTE
       form above reached 3^30. */
    for (v = 0; v < 3; ++v) {
        hrm_method m = v == 0 ? HRM_EULER : v == 1 ? HRM_RK4 : HRM_ADAMS_BASHFORTH;
        hrm_result r;
        solve(&p, 0, 4.0 * 30, m, 30, HRM_FORM_OPTICAL_DEPTH, &r);
        CHECK(finite_d((double)r.L[0]) && r.L[0] >= 0 && (double)r.L[0] <= 7 * 4.0 * 30,
              "%s optical-depth z=4: bounded (L = %g)", hrm_method_name(m), (double)r.L[0]);
    }
}

/* ========================================================================
   7. Bad input: exact status, the defined result, nothing else written
   ======================================================================== */

typedef struct guarded_result {
    unsigned char before[32];
    hrm_result r;
    unsigned char after[32];
} guarded_result;

static void guarded_fill(guarded_result *g)
{
    int c;
    memset(g, 0xA5, sizeof *g);
    for (c = 0; c < NCH; ++c) {
        g->r.L[c] = (hrm_real)7;
        g->r.Tr[c] = (hrm_real)-3;
    }
}

static int guards_intact(const guarded_result *g)
{
    size_t i;
    for (i = 0; i < sizeof g->before; ++i)
        if (g->before[i] != 0xA5 || g->after[i] != 0xA5) return 0;
    return 1;
}

/* The error result: L = 0 and Tr = 1 in every channel. */
static void check_error_result(const guarded_result *g, const char *what, int argument_error)
{
    int c, ok = 1;
    for (c = 0; c < NCH; ++c)
        if (!(g->r.L[c] == 0 && g->r.Tr[c] == 1)) ok = 0;
    CHECK(ok, "%s: error result L = 0, Tr = 1 (got L[0] = %g, Tr[0] = %g)", what,
          (double)g->r.L[0], (double)g->r.Tr[0]);
    CHECK(guards_intact(g), "%s: bytes around the result were written", what);
    if (argument_error) /* rejected before any evaluation: stats all zero */
        CHECK(g->r.stats.evals == 0 && g->r.stats.medium_evals == 0 && g->r.stats.steps == 0 &&
              g->r.stats.rejected == 0,
              "%s: stats of a rejected call (evals %ld, medium_evals %ld, steps %ld)", what,
              g->r.stats.evals, g->r.stats.medium_evals, g->r.stats.steps);
}

static void expect_solve_error(const hrm_medium *m, hrm_real t0, hrm_real t1,
                               const hrm_options *o, hrm_status want, const char *what,
                               int argument_error)
{
    guarded_result g;
    hrm_status st;
    unsigned char mb[sizeof(hrm_medium)], ob[sizeof(hrm_options)];
    scene *sc = m ? (scene *)m->user : NULL;
    if (m) memcpy(mb, m, sizeof mb);
    if (o) memcpy(ob, o, sizeof ob);
    if (sc) scene_reset_counts(sc);
    guarded_fill(&g);
    st = hrm_solve(m, t0, t1, o, &g.r);
    CHECK_INT(st, want, "%s: status (%s)", what, hrm_status_string(st));
    check_error_result(&g, what, argument_error);
    if (sc && argument_error)
        CHECK_INT(sc->n_sa + sc->n_ss + sc->n_st + sc->n_le + sc->n_li + sc->n_tr + sc->n_never, 0,
                  "%s: callbacks called for a rejected call", what);
    if (m) CHECK(memcmp(mb, m, sizeof mb) == 0, "%s: the medium was modified", what);
    if (o) CHECK(memcmp(ob, o, sizeof ob) == 0, "%s: the options were modified", what);
    /* hrm_transmittance rejects the same arguments the same way */
    {
        hrm_real tr[NCH + 4];
        hrm_stats stats;
        int c, ok = 1;
        for (c = 0; c < NCH + 4; ++c) tr[c] = (hrm_real)-5;
        memset(&stats, 0x5A, sizeof stats);
        st = hrm_transmittance(m, t0, t1, o, tr, &stats);
        if (want != HRM_ERR_CALLBACK_VALUE || (sc && sc->poison != POISON_LE && sc->poison != POISON_LI)) {
            CHECK_INT(st, want, "%s: hrm_transmittance status", what);
            for (c = 0; c < NCH; ++c)
                if (tr[c] != 1) ok = 0;
            CHECK(ok, "%s: hrm_transmittance error result Tr = 1 (got %g)", what, (double)tr[0]);
        } else { /* a bad Le/Li is never called by hrm_transmittance */
            CHECK_INT(st, HRM_OK, "%s: hrm_transmittance does not call Le/Li", what);
        }
        for (c = NCH; c < NCH + 4; ++c)
            if (tr[c] != (hrm_real)-5) ok = 0;
        CHECK(ok, "%s: hrm_transmittance wrote past Tr[HRM_CHANNELS]", what);
    }
}

static void test_bad_input(void)
{
    scene sc;
    problem ph, pt;
    hrm_medium hom, het, med;
    hrm_options o = make_options(HRM_SIMPSON, 8, HRM_FORM_DEFAULT);
    const hrm_real nan_r = (hrm_real)NAN, inf_r = (hrm_real)INFINITY;
    int mi, c;
    guarded_result g;
    hrm_real tr[NCH];
    scene_init(&sc);
    ph = fixed_problem(&sc, P_HOM, 1, 1, 0);
    pt = fixed_problem(&sc, P_HET, 1, 1, 1);
    hom = problem_medium(&ph);
    het = problem_medium(&pt);
    het.sigma_t = het_sigma_t;

    /* NULL arguments */
    expect_solve_error(NULL, 0, 1, &o, HRM_ERR_NULL_ARGUMENT, "medium NULL", 1);
    expect_solve_error(NULL, 0, 1, NULL, HRM_ERR_NULL_ARGUMENT, "medium and options NULL", 1);
    scene_reset_counts(&sc);
    CHECK_INT(hrm_solve(&het, 0, 1, &o, NULL), HRM_ERR_NULL_ARGUMENT, "result NULL");
    CHECK_INT(hrm_solve(NULL, 0, 1, &o, NULL), HRM_ERR_NULL_ARGUMENT, "medium and result NULL");
    CHECK_INT(sc.n_sa + sc.n_le + sc.n_li + sc.n_tr, 0, "result NULL: no callback called");
    CHECK_INT(hrm_transmittance(&het, 0, 1, &o, NULL, NULL), HRM_ERR_NULL_ARGUMENT,
              "hrm_transmittance Tr NULL");
    for (c = 0; c < NCH; ++c) tr[c] = (hrm_real)-5;
    CHECK_INT(hrm_transmittance(NULL, 0, 1, &o, tr, NULL), HRM_ERR_NULL_ARGUMENT,
              "hrm_transmittance medium NULL");
    CHECK(tr[0] == 1, "hrm_transmittance medium NULL: Tr = 1");

    /* interval */
    expect_solve_error(&het, nan_r, 1, &o, HRM_ERR_BAD_INTERVAL, "t0 NaN", 1);
    expect_solve_error(&het, 0, nan_r, &o, HRM_ERR_BAD_INTERVAL, "t1 NaN", 1);
    expect_solve_error(&het, -inf_r, 1, &o, HRM_ERR_BAD_INTERVAL, "t0 -inf", 1);
    expect_solve_error(&het, inf_r, inf_r, &o, HRM_ERR_BAD_INTERVAL, "t0 = t1 = +inf", 1);
    expect_solve_error(&het, 0, inf_r, &o, HRM_ERR_BAD_INTERVAL, "t1 +inf", 1);
    expect_solve_error(&het, 0, -inf_r, &o, HRM_ERR_BAD_INTERVAL, "t1 -inf", 1);
    expect_solve_error(&het, 2, 1, &o, HRM_ERR_BAD_INTERVAL, "t1 < t0", 1);
    expect_solve_error(&hom, 2, 1, &o, HRM_ERR_BAD_INTERVAL, "t1 < t0 homogeneous", 1);
    expect_solve_error(&het, nan_r, 1, NULL, HRM_ERR_BAD_INTERVAL, "t0 NaN, options NULL", 1);

    /* options */
    o.steps = -1;
    expect_solve_error(&het, 0, 1, &o, HRM_ERR_BAD_STEPS, "steps -1", 1);
    o.steps = -2147483647 - 1;
    expect_solve_error(&hom, 0, 1, &o, HRM_ERR_BAD_STEPS, "steps INT_MIN", 1);
    o.steps = 8;
    o.method = (hrm_method)999;
    expect_solve_error(&het, 0, 1, &o, HRM_ERR_BAD_METHOD, "method 999", 1);
    o.method = HRM_METHOD_COUNT;
    expect_solve_error(&hom, 0, 1, &o, HRM_ERR_BAD_METHOD, "method HRM_METHOD_COUNT", 1);
    o.method = HRM_RK4;
    o.form = (hrm_form)999;
    expect_solve_error(&het, 0, 1, &o, HRM_ERR_BAD_OPTION, "form 999", 1);
    o.form = (hrm_form)(HRM_FORM_RTE + 1);
    expect_solve_error(&hom, 0, 1, &o, HRM_ERR_BAD_OPTION, "form HRM_FORM_RTE + 1", 1);
    o = make_options(HRM_SIMPSON, 8, HRM_FORM_DEFAULT);

    /* homogeneous constants */
    for (c = 0; c < 4; ++c) {
        med = hom;
        med.sigma_a = never_spectrum; /* ignored, and must not mask the error */
        if (c == 0) med.const_sigma_a[NCH - 1] = (hrm_real)-0.1;
        if (c == 1) med.const_sigma_s[0] = (hrm_real)-1e-30;
        if (c == 2) med.const_sigma_a[0] = nan_r;
        if (c == 3) med.const_sigma_s[NCH - 1] = inf_r;
        expect_solve_error(&med, 0, 1, &o, HRM_ERR_BAD_MEDIUM,
                           c == 0 ? "const_sigma_a < 0" : c == 1 ? "const_sigma_s < 0" :
                           c == 2 ? "const_sigma_a NaN" : "const_sigma_s inf", 1);
    }
    /* without HRM_MEDIUM_HOMOGENEOUS the constants are not used */
    med = het;
    med.const_sigma_a[0] = (hrm_real)-1;
    med.const_sigma_s[0] = nan_r;
    guarded_fill(&g);
    CHECK_INT(hrm_solve(&med, 0, 1, &o, &g.r), HRM_OK, "negative constants without the flag are ignored");

    /* callback values: NaN, infinities, negative coefficients, a
       transmittance outside [0, 1]: HRM_ERR_CALLBACK_VALUE, every method */
    {
        static const struct { int which; double value; const char *what; } bad[] = {
            { POISON_SA, -0.5, "sigma_a < 0" },  { POISON_SA, (double)NAN, "sigma_a NaN" },
            { POISON_SS, -1e-3, "sigma_s < 0" }, { POISON_SS, (double)INFINITY, "sigma_s inf" },
            { POISON_ST, -2, "sigma_t < 0" },    { POISON_ST, (double)NAN, "sigma_t NaN" },
            { POISON_LE, (double)NAN, "Le NaN" }, { POISON_LE, (double)-INFINITY, "Le -inf" },
            { POISON_LI, (double)INFINITY, "Li inf" }, { POISON_LI, (double)NAN, "Li NaN" },
            { POISON_TR, 1.5, "transmittance 1.5" }, { POISON_TR, -0.25, "transmittance -0.25" },
            { POISON_TR, (double)NAN, "transmittance NaN" },
        };
        int bi;
        for (bi = 0; bi < (int)(sizeof bad / sizeof bad[0]); ++bi) {
            for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
                char what[160];
                hrm_options ob = make_options(every_method[mi], 6, HRM_FORM_DEFAULT);
                med = het;
                /* sigma_t given only where it is the poisoned one: else
                   sigma_t = sigma_a + sigma_s, so that hrm_transmittance
                   needs the poisoned coefficient too */
                if (bad[bi].which != POISON_TR) med.transmittance = NULL;
                if (bad[bi].which != POISON_ST) med.sigma_t = NULL;
                sc.poison = bad[bi].which;
                sc.poison_value = bad[bi].value;
                snprintf(what, sizeof what, "%s, %s", bad[bi].what, hrm_method_name(every_method[mi]));
                expect_solve_error(&med, 0, 2, &ob, HRM_ERR_CALLBACK_VALUE, what, 0);
            }
        }
        sc.poison = POISON_NONE;
    }

    /* a valid call leaves medium and options untouched as well */
    {
        unsigned char mb[sizeof(hrm_medium)], ob[sizeof(hrm_options)];
        hrm_options ov = make_options(HRM_MONTE_CARLO, 8, HRM_FORM_DEFAULT);
        ov.seed = 42;
        ov.stratified = 1;
        memcpy(mb, &het, sizeof mb);
        memcpy(ob, &ov, sizeof ob);
        guarded_fill(&g);
        CHECK_INT(hrm_solve(&het, 0, 2, &ov, &g.r), HRM_OK, "valid call: status");
        CHECK(memcmp(mb, &het, sizeof mb) == 0 && memcmp(ob, &ov, sizeof ob) == 0,
              "valid call: medium and options unchanged");
        CHECK(guards_intact(&g), "valid call: bytes around the result untouched");
    }
}

/* ========================================================================
   Defaults, empty intervals, hrm_transmittance
   ======================================================================== */

static void test_defaults(void)
{
    scene sc;
    problem p;
    hrm_medium med;
    hrm_options zero, nested, d;
    hrm_result rn, rz, rs, rd;
    int mi;
    scene_init(&sc);
    p = fixed_problem(&sc, P_HET, 1, 1, 0);
    med = problem_medium(&p);
    memset(&zero, 0, sizeof zero);
    nested = zero;
    nested.method = HRM_NESTED_SIMPSON;
    nested.rtol = (hrm_real)1e-3;
    d = hrm_default_options(HRM_METHOD_DEFAULT);
    CHECK_INT(hrm_solve(&med, 1, 5, NULL, &rn), HRM_OK, "options NULL: status");
    CHECK_INT(hrm_solve(&med, 1, 5, &zero, &rz), HRM_OK, "all-zero options: status");
    CHECK_INT(hrm_solve(&med, 1, 5, &nested, &rs), HRM_OK, "nested Simpson, rtol 1e-3: status");
    CHECK_INT(hrm_solve(&med, 1, 5, &d, &rd), HRM_OK, "hrm_default_options(DEFAULT): status");
    /* the default method is nested Simpson at rtol 1e-3 (what make
       render's three scenes pick: the manual's DEFAULTS) */
    CHECK_INT(d.method, HRM_METHOD_DEFAULT, "hrm_default_options(HRM_METHOD_DEFAULT) keeps method 0");
    CHECK(d.steps == hrm_default_options(HRM_NESTED_SIMPSON).steps &&
              d.tau_mode == hrm_default_options(HRM_NESTED_SIMPSON).tau_mode,
          "the default method's options: nested Simpson's");
    CHECK(d.rtol == (hrm_real)1e-3, "the default rtol: 1e-3");
    CHECK(same_result(&rn, &rz), "options NULL and all-zero options agree bit for bit");
    CHECK(same_result(&rn, &rs), "options NULL and nested Simpson at rtol 1e-3 agree bit for bit");
    CHECK(same_result(&rn, &rd), "options NULL and hrm_default_options(HRM_METHOD_DEFAULT) agree");
    /* hrm_default_options(m) = all-zero with the method set; form 0 is the
       optical-depth form */
    for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
        hrm_method m = every_method[mi];
        hrm_options a = hrm_default_options(m), b = zero, f = zero;
        hrm_result ra, rb, rf;
        b.method = m;
        b.seed = a.seed; /* whatever default seed it picks, the same */
        f = b;
        f.form = HRM_FORM_OPTICAL_DEPTH;
        CHECK_INT(a.method, m, "hrm_default_options(%s).method", hrm_method_name(m));
        CHECK_INT(a.steps == 0 || a.steps == 32, 1, "hrm_default_options(%s).steps is the default", hrm_method_name(m));
        CHECK(a.jitter == 0 && a.stratified == 0 &&
              (a.form == HRM_FORM_DEFAULT || a.form == HRM_FORM_OPTICAL_DEPTH),
              "hrm_default_options(%s): no jitter, no stratification, optical-depth form", hrm_method_name(m));
        hrm_solve(&med, 1, 5, &a, &ra);
        hrm_solve(&med, 1, 5, &b, &rb);
        hrm_solve(&med, 1, 5, &f, &rf);
        CHECK(same_result(&ra, &rb), "%s: hrm_default_options = zero options with the method", hrm_method_name(m));
        CHECK(same_result(&rb, &rf), "%s: form 0 = HRM_FORM_OPTICAL_DEPTH", hrm_method_name(m));
        CHECK_INT(rb.stats.steps, 32, "%s: steps 0 means 32", hrm_method_name(m));
    }
}

static void test_empty_interval(void)
{
    scene sc;
    int v, mi, fi, c;
    scene_init(&sc);
    for (v = 0; v < 3; ++v) {
        problem p = fixed_problem(&sc, v == 0 ? P_HOM : P_HET, 1, 1, v == 2);
        hrm_medium med = problem_medium(&p);
        for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
            for (fi = 0; fi < 2; ++fi) {
                hrm_options o = make_options(every_method[mi], 8, fi ? HRM_FORM_RTE : HRM_FORM_OPTICAL_DEPTH);
                hrm_result r;
                hrm_real tr[NCH];
                hrm_stats stats;
                int ok = 1;
                if (fi && !is_ivp(every_method[mi])) continue;
                scene_reset_counts(&sc);
                CHECK_INT(hrm_solve(&med, (hrm_real)2.5, (hrm_real)2.5, &o, &r), HRM_OK,
                          "t0 = t1 %s: status", hrm_method_name(every_method[mi]));
                for (c = 0; c < NCH; ++c)
                    if (!(r.L[c] == 0 && r.Tr[c] == 1)) ok = 0;
                CHECK(ok, "t0 = t1 %s: L = 0, Tr = 1 (got %g, %g)", hrm_method_name(every_method[mi]),
                      (double)r.L[0], (double)r.Tr[0]);
                CHECK_INT(r.stats.evals, 0, "t0 = t1 %s: evals", hrm_method_name(every_method[mi]));
                CHECK_INT(sc.n_le + sc.n_li, 0, "t0 = t1 %s: Le/Li calls", hrm_method_name(every_method[mi]));
                CHECK_INT(hrm_transmittance(&med, (hrm_real)2.5, (hrm_real)2.5, &o, tr, &stats), HRM_OK,
                          "hrm_transmittance t0 = t1: status");
                CHECK(tr[0] == 1, "hrm_transmittance t0 = t1: Tr = 1");
            }
        }
    }
}

static void test_transmittance(void)
{
    scene sc;
    problem ph, pe, pt;
    hrm_medium hom, het, htr;
    int mi, c, k;
    scene_init(&sc);
    ph = fixed_problem(&sc, P_HOM, 1, 1, 0);
    pe = fixed_problem(&sc, P_HET, 1, 1, 0);
    pt = fixed_problem(&sc, P_HET, 1, 1, 1);
    hom = problem_medium(&ph);
    hom.sigma_a = never_spectrum; /* ignored: homogeneous */
    hom.transmittance = never_transmittance;
    het = problem_medium(&pe);
    htr = problem_medium(&pt);
    for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
        hrm_method m = every_method[mi];
        hrm_options o = make_options(m, 32, HRM_FORM_DEFAULT);
        for (k = 0; k < 2; ++k) {
            double t0 = k ? 3.0 : 0.0, t1 = t0 + 4.0;
            hrm_real tr[NCH];
            hrm_stats stats;
            /* homogeneous: exp(-sigma_t T) in closed form, no callback,
               stats optional; round-off only (16 eps (1 + tau)) */
            scene_reset_counts(&sc);
            CHECK_INT(hrm_transmittance(&hom, (hrm_real)t0, (hrm_real)t1, &o, tr, NULL), HRM_OK,
                      "homogeneous %s: status (stats NULL)", hrm_method_name(m));
            for (c = 0; c < NCH; ++c) {
                double x = exp(-sig_t_hom(&sc, c) * 4.0);
                CHECK_REL(tr[c], x, 16 * real_eps() * (1 + sig_t_hom(&sc, c) * 4.0),
                          "homogeneous %s: Tr = exp(-sigma_t T)", hrm_method_name(m));
            }
            CHECK_INT(sc.n_never + sc.n_le + sc.n_li, 0, "homogeneous %s: callbacks called", hrm_method_name(m));
            memset(&stats, 0x5A, sizeof stats);
            hrm_transmittance(&hom, (hrm_real)t0, (hrm_real)t1, &o, tr, &stats);
            CHECK(stats.evals == 0 && stats.medium_evals == 0,
                  "homogeneous %s: stats evals %ld medium_evals %ld", hrm_method_name(m), stats.evals,
                  stats.medium_evals);

            /* transmittance callback: its value, to round-off */
            scene_reset_counts(&sc);
            CHECK_INT(hrm_transmittance(&htr, (hrm_real)t0, (hrm_real)t1, &o, tr, &stats), HRM_OK,
                      "callback %s: status", hrm_method_name(m));
            for (c = 0; c < NCH; ++c)
                CHECK_REL(tr[c], exact_tr(&pt, c, t0, t1), 16 * real_eps() * (1 + exact_tau(&pt, c, t0, t1)),
                          "callback %s: Tr from the callback", hrm_method_name(m));
            CHECK_INT(sc.n_le + sc.n_li, 0, "callback %s: Le/Li called", hrm_method_name(m));
            CHECK_INT(stats.evals, 0, "callback %s: stats.evals", hrm_method_name(m));

            /* sigma callbacks: tau integrated by the method (deterministic
               ones; Monte Carlo's estimate is random), per channel, with the
               bounds of tau_error_bound(); Tr's relative error is then at
               most e^{d tau} - 1. */
            scene_reset_counts(&sc);
            CHECK_INT(hrm_transmittance(&het, (hrm_real)t0, (hrm_real)t1, &o, tr, &stats), HRM_OK,
                      "sigma callbacks %s: status", hrm_method_name(m));
            CHECK_INT(sc.n_le + sc.n_li, 0, "sigma callbacks %s: Le/Li called", hrm_method_name(m));
            CHECK_INT(stats.evals, 0, "sigma callbacks %s: stats.evals", hrm_method_name(m));
            CHECK(stats.medium_evals > 0, "sigma callbacks %s: medium_evals counted", hrm_method_name(m));
            if (m != HRM_MONTE_CARLO) {
                for (c = 0; c < NCH; ++c) {
                    double dtau = tau_error_bound(&sc, m, HRM_FORM_OPTICAL_DEPTH, 32, 4.0, 0), x;
                    x = exact_tr(&pe, c, t0, t1);
                    CHECK_REL(tr[c], x, expm1(dtau) + fp_floor(32, exact_tau(&pe, c, t0, t1)),
                              "sigma callbacks %s t0=%g ch %d: Tr to the rule's accuracy", hrm_method_name(m), t0, c);
                }
            }
        }
    }
}

/* ========================================================================
   8. Emission convention
   ======================================================================== */

static void test_emission_convention(void)
{
    scene sc;
    problem p, q;
    int mi, c;
    scene_init(&sc);
    p = fixed_problem(&sc, P_HOM, 1, 0, 0);
    q = p;
    q.flags = HRM_EMISSION_PER_LENGTH;
    for (mi = 0; mi < N_METHODS_FIXED; ++mi) {
        hrm_method m = every_method[mi];
        hrm_options o = make_options(m, 64, HRM_FORM_DEFAULT);
        hrm_result r1, r2;
        o.seed = 9;
        solve_opt(&p, 0, 6, &o, &r1);
        solve_opt(&q, 0, 6, &o, &r2);
        for (c = 0; c < NCH; ++c) {
            /* same nodes, same weights: the results differ by the factor
               sigma_a alone (a few roundings: 8 eps) */
            CHECK_REL((double)r1.L[c] / (double)r2.L[c], sc.sig_a[c], 8 * real_eps(),
                      "%s ch %d: L(sigma_a Le) / L(Le per length) = sigma_a", hrm_method_name(m), c);
            CHECK(r1.Tr[c] == r2.Tr[c], "%s: Tr does not depend on the emission convention", hrm_method_name(m));
            if (m != HRM_MONTE_CARLO) {
                /* closed forms Le sigma_a/sigma_t (1 - e^{-sigma_t T}) and
                   Le/sigma_t (1 - e^{-sigma_t T}), bound as in group 1 */
                double bound = 2 * trunc_bound(m, HRM_FORM_DEFAULT, 64, 6, problem_rate(&p)) +
                               fp_floor(64, 6);
                CHECK_REL(r1.L[c], exact_L(&p, c, 0, 6), bound, "%s: source sigma_a Le", hrm_method_name(m));
                CHECK_REL(r2.L[c], exact_L(&q, c, 0, 6), bound, "%s: source Le (per length)", hrm_method_name(m));
            }
        }
    }
    /* per length in a purely scattering medium: Le is the source although
       sigma_a = 0: L = Le/sigma_t (1 - e^{-sigma_t T}) */
    {
        hrm_medium med = zero_medium();
        hrm_result r;
        hrm_options o = make_options(HRM_SIMPSON, 64, HRM_FORM_DEFAULT);
        med.user = &sc;
        med.flags = HRM_MEDIUM_HOMOGENEOUS | HRM_EMISSION_PER_LENGTH;
        med.Le = const_Le;
        for (c = 0; c < NCH; ++c) med.const_sigma_s[c] = (hrm_real)0.5;
        scene_reset_counts(&sc);
        CHECK_INT(hrm_solve(&med, 0, 6, &o, &r), HRM_OK, "per length, sigma_a = 0: status");
        CHECK_INT(sc.n_le, 129, "per length, sigma_a = 0: Le called at every node");
        for (c = 0; c < NCH; ++c)
            /* Simpson H = 6/64, lambda = 0.5: 2 (H lambda)^4/2880 = 3e-8 */
            CHECK_REL(r.L[c], sc.le[c] / 0.5 * -expm1(-0.5 * 6), 2 * pow(6.0 / 64 * 0.5, 4) / 2880 + fp_floor(64, 3),
                      "per length, sigma_a = 0: L = Le/sigma_t (1 - e^{-sigma_t T})");
    }
}

/* ========================================================================
   9. Re-entrancy: Li calls hrm for its shadow ray
   ======================================================================== */

static void test_reentrancy(void)
{
    scene sc;
    problem p;
    hrm_medium outer, light;
    int v, c;
    scene_init(&sc);
    /* the light's medium: the same homogeneous medium, so Li(s) =
       E exp(-sigma_t (d0 + k s)) and the closed form (b) holds */
    p = fixed_problem(&sc, P_HOM, 0, 1, 0);
    light = problem_medium(&p);
    light.Li = NULL;
    outer = problem_medium(&p);
    outer.Li = shadow_Li;
    sc.shadow_ray = &light;
    for (v = 0; v < 2; ++v) {
        hrm_options o = make_options(v ? HRM_RK4 : HRM_SIMPSON, 32, HRM_FORM_DEFAULT);
        hrm_result r;
        double bound = 2 * trunc_bound(o.method, HRM_FORM_DEFAULT, 32, 6, problem_rate(&p)) +
                       fp_floor(32, 6);
        sc.shadow_use_solve = v;
        scene_reset_counts(&sc);
        CHECK_INT(hrm_solve(&outer, 0, 6, &o, &r), HRM_OK,
                  "nested %s: status", v ? "hrm_solve" : "hrm_transmittance");
        CHECK_INT(sc.shadow_bad_status, 0, "nested %s: inner status", v ? "hrm_solve" : "hrm_transmittance");
        CHECK_INT(sc.n_li, r.stats.evals, "nested: Li calls");
        for (c = 0; c < NCH; ++c)
            /* Simpson/RK4 at N = 32, lambda = 1.5 sigma_t: as in group 1 */
            CHECK_REL(r.L[c], exact_L(&p, c, 0, 6), bound,
                      "nested %s: L matches closed form (b)", v ? "hrm_solve" : "hrm_transmittance");
    }
    sc.shadow_ray = NULL;
}

/* ========================================================================
   10. Names and version
   ======================================================================== */

static void test_names(void)
{
    static const hrm_status statuses[] = {
        HRM_OK, HRM_WARN_MAX_EVALS, HRM_WARN_H_MIN, HRM_WARN_STORAGE, HRM_WARN_RTOL_CLIPPED,
        HRM_WARN_ROUNDOFF, HRM_ERR_NULL_ARGUMENT, HRM_ERR_BAD_INTERVAL, HRM_ERR_BAD_STEPS,
        HRM_ERR_BAD_METHOD, HRM_ERR_BAD_OPTION, HRM_ERR_BAD_MEDIUM, HRM_ERR_CALLBACK_VALUE
    };
    static const char *const method_names[] = { "rectangle", "simpson", "monte-carlo",
                                                "euler", "rk4", "adams-bashforth" };
    const int ns = (int)(sizeof statuses / sizeof statuses[0]);
    const char *unknown;
    int i, j;
    CHECK_INT(HRM_OK, 0, "HRM_OK is 0");
    for (i = 0; i < ns; ++i) {
        const char *s = hrm_status_string(statuses[i]);
        CHECK(s != NULL && s[0] != 0, "status %d: a non-empty string", (int)statuses[i]);
        if (!s) continue;
        for (j = 0; j < i; ++j) {
            const char *t = hrm_status_string(statuses[j]);
            CHECK(t == NULL || strcmp(s, t) != 0, "statuses %d and %d share the string \"%s\"",
                  (int)statuses[i], (int)statuses[j], s);
        }
    }
    unknown = hrm_status_string((hrm_status)42);
    CHECK(unknown != NULL && strcmp(unknown, "unknown status") == 0, "unknown status 42: \"unknown status\"");
    unknown = hrm_status_string((hrm_status)-99);
    CHECK(unknown != NULL && strcmp(unknown, "unknown status") == 0, "unknown status -99: \"unknown status\"");
    CHECK(strcmp(hrm_status_string(HRM_OK), "ok") == 0, "HRM_OK is \"ok\"");

    /* every method has its own non-empty name */
    for (i = 1; i < (int)HRM_METHOD_COUNT; ++i) {
        const char *s = hrm_method_name((hrm_method)i);
        CHECK(s != NULL && s[0] != 0 && strcmp(s, "?") != 0, "method %d has a name", i);
        for (j = 1; j < i; ++j)
            CHECK(s && strcmp(s, hrm_method_name((hrm_method)j)) != 0, "methods %d and %d share a name", i, j);
    }
    /* and the fixed-step ones the names the header lists */
    for (i = 0; i < N_METHODS_FIXED; ++i) {
        const char *s = hrm_method_name(every_method[i]);
        CHECK(s != NULL && strcmp(s, method_names[i]) == 0, "method %d is \"%s\" (got \"%s\")",
              (int)every_method[i], method_names[i], s ? s : "(null)");
    }
    unknown = hrm_method_name(HRM_METHOD_COUNT);
    CHECK(unknown != NULL && strcmp(unknown, "?") == 0, "HRM_METHOD_COUNT: \"?\"");
    unknown = hrm_method_name((hrm_method)999);
    CHECK(unknown != NULL && strcmp(unknown, "?") == 0, "method 999: \"?\"");

    CHECK_INT(hrm_version(), HRM_VERSION_MAJOR * 10000 + HRM_VERSION_MINOR * 100 + HRM_VERSION_PATCH,
              "hrm_version()");
    CHECK_INT(hrm_version(), 100, "version 0.1.0 as the top comment says");
}


/* What N says, in sigma too: without a warp a fixed-step method takes tau
   from its own nodes (coupled, its default there), so that with the
   medium as one callback (medium.sigma) it makes one medium evaluation
   per node: N (rectangle, Monte Carlo, Euler, the analytic march), 2N + 1
   (Simpson, RK4), N + 3 (Adams-Bashforth) - the bounds N + 4 and
   2N + 5 with room for none; under a warp the layer (decoupled) is its
   default, and asked for without one it still is what it says. The
   sigma callbacks are counted by the scene. */
static void test_sigma_cost(void)
{
    static const int ns[3] = {8, 32, 128};
    int mi, k, bad = 0, cases = 0;
    for (mi = 0; mi < N_METHODS_ALL; ++mi) {
        hrm_method m = every_method[mi];
        if (is_adaptive(m)) continue;
        for (k = 0; k < 3; ++k) {
            scene sc;
            problem p;
            hrm_options o = hrm_default_options(m);
            hrm_result r;
            long want;
            int n = ns[k];
            scene_init(&sc);
            p = make_problem(&sc, P_HET, 1, LIGHT_DIR);
            p.sigmas = SIGMA_ONE;
            o.steps = n;
            want = m == HRM_SIMPSON || m == HRM_RK4 ? 2L * n + 1 : m == HRM_ADAMS_BASHFORTH ? n + 3L : n;
            CHECK_INT(solve_opt(&p, 0.5, 6.5, &o, &r), HRM_OK, "%s N=%d: status", hrm_method_name(m), n);
            cases++;
            if (r.stats.medium_evals != want || sc.n_one != want) {
                bad++;
                NOTE("%s N=%d: %ld medium evaluations (%ld calls), want %ld", hrm_method_name(m), n,
                     r.stats.medium_evals, sc.n_one, want);
            }
        }
    }
    CHECK_INT(bad, 0, "fixed-step methods without a warp: N, 2N + 1 or N + 3 medium evaluations (%d solves)",
              cases);
    {
        /* the layer, asked for, and under a warp by default */
        scene sc;
        problem p;
        hrm_options o = hrm_default_options(HRM_RECTANGLE);
        hrm_result r;
        scene_init(&sc);
        p = make_problem(&sc, P_HET, 1, LIGHT_DIR);
        p.sigmas = SIGMA_ONE;
        o.steps = 8;
        o.tau_mode = HRM_TAU_DECOUPLED;
        CHECK_INT(solve_opt(&p, 0.5, 6.5, &o, &r), HRM_OK, "decoupled: status");
        CHECK(r.stats.medium_evals > 8, "rectangle N = 8, tau decoupled: the layer's samples too (%ld)",
              r.stats.medium_evals);
        o.tau_mode = HRM_TAU_DEFAULT;
        o.warp.kind = HRM_WARP_DISTANCE;
        CHECK_INT(solve_opt(&p, 0.5, 6.5, &o, &r), HRM_OK, "distance warp: status");
        CHECK(r.stats.medium_evals > 8, "rectangle N = 8 under a warp: the layer by default (%ld)",
              r.stats.medium_evals);
    }
}

void fixed_tests(void)
{
    RUN_GROUP(test_names);
    RUN_GROUP(test_defaults);
    RUN_GROUP(test_empty_interval);
    RUN_GROUP(test_bad_input);
    RUN_GROUP(test_eval_counts);
    RUN_GROUP(test_eval_domain);
    RUN_GROUP(test_absent_terms);
    RUN_GROUP(test_closed_forms);
    RUN_GROUP(test_transmittance);
    RUN_GROUP(test_emission_convention);
    RUN_GROUP(test_reentrancy);
    RUN_GROUP(test_orders);
    RUN_GROUP(test_sigma_cost);
    RUN_GROUP(test_monte_carlo);
    RUN_GROUP(test_thick);
    RUN_GROUP(test_rte_stiffness);
    RUN_GROUP(test_rte_closed_form_tr);
}
