/* test_adaptive.c - tests of the adaptive methods of hrm.h: nested Simpson,
   Gauss-Kronrod G7/K15 (global and local), and the embedded Runge-Kutta
   pairs (Bogacki-Shampine, Dormand-Prince, Fehlberg, Cash-Karp, Verner).
   Their coefficient tables are checked in test_tables.c. adaptive_tests()
   runs every group.

   Every numerical check compares with a closed form and states its bound
   and the reason beside it. References are computed in double whatever
   HRM_REAL is.

   Tolerances: the adaptive methods control the error locally. hrm__ratio
   gives each step (or interval) the tolerance
       rtol * max(|increment|, share of the range * max(|y1|, scale))
   whose sum over the range is rtol * (|L| + max(|L|, scale)) <= 2 rtol |L|
   by construction, the scale being half a coarse estimate of the total
   (quadrature) or half the first step's increment (Runge-Kutta pairs). The
   local error estimates are themselves asymptotic (they estimate the
   lower-order solution's error). Hence the bound asserted on smooth
   scenes: achieved relative error <= 10 rtol. The ratio achieved / rtol is
   printed (NOTE) for every method.

   Under HRM_REAL=float rtol stops at 3e-5 (the library clips it at 100
   epsilons = 1.2e-5) and every bound gets the round-off floor of
   test_fixed.c, eps * (n + 16) * (1 + tau) relative, n being the number of
   accepted steps (each adds about eps to the sum and to tau). */
#include "common.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The rtol values of the accuracy tests: 1e-3 ... 1e-9 in double; under
   float down to 3e-5 (above the clip at 100 epsilons = 1.2e-5). The
   low-order methods (nested Simpson, order 4; Bogacki-Shampine, order 3)
   stop at 1e-7: at 1e-8 and 1e-9 they take 2e4 to 1.8e5 evaluations per
   solve, most of the suite's time budget (measured there: error/rtol
   below 1e-2, as at 1e-7). */
static int ad_rtols(double *r, hrm_method m)
{
    static const double dbl[] = { 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9 };
    static const double flt[] = { 1e-3, 1e-4, 3e-5 };
    const double *src = real_is_float() ? flt : dbl;
    int n = real_is_float() ? 3 : 7, i;
    if (!real_is_float() && (m == HRM_NESTED_SIMPSON || m == HRM_BOGACKI_SHAMPINE)) n = 5;
    for (i = 0; i < n; ++i) r[i] = src[i];
    return n;
}

/* ------------------------------------------------------------------------
   Scenes (common.h's scene, closed forms in exact_L)
   AD_HOM    homogeneous medium (sigma_t = 0.5, 0.75, 1.0 with three channels),
             single scattering of a directional light whose path in the
             medium grows along the ray (LIGHT_DIR): Li(s) = E exp(-sigma_t
             (d0 + k s)), L = sigma_s E e^{-sigma_t (d0 + k t0)}
             (1 - e^{-sigma_t (1+k) T}) / (sigma_t (1 + k)).
   AD_ABS    heterogeneous absorber sigma_a(s) = a + b sin(w s) (callback;
             no scattering), a = 0.1, 0.15, 0.2 with three channels, b = a/2,
             constant Le:  tau = a T + (b/w)(cos w t0 - cos w t1),
             Tr = e^{-tau}, L = Le (1 - Tr).
   AD_SHADOW AD_HOM's medium lit by a constant Li = E except in a sharp
             shadow [lo, hi) where Li = 0 (LIGHT_SHADOW):
             L = sigma_s E / sigma_t (1 - e^{-sigma_t (lo - t0)}
                 + e^{-sigma_t (hi - t0)} - e^{-sigma_t T}).
   ------------------------------------------------------------------------ */
enum { AD_HOM, AD_ABS, AD_SHADOW };

/* The defaults, with the absorber's a = 0.1 + 0.15 f (tau over T = 8:
   0.8 ... 1.6 with three channels). */
static void ad_scene_init(scene *sc)
{
    scene_init(sc);
    scene_set_sine(sc, 0.1, 0.15);
}

static problem ad_problem(scene *sc, int kind)
{
    problem p;
    if (kind == AD_ABS) {
        p = make_problem(sc, P_HET, 1, LIGHT_NONE);
        p.sigmas = SIGMA_A;
    } else {
        p = make_problem(sc, P_HOM, 0, kind == AD_HOM ? LIGHT_DIR : LIGHT_SHADOW);
    }
    return p;
}

static const char *ad_kind_name(int kind)
{
    return kind == AD_HOM ? "homogeneous" : kind == AD_ABS ? "absorber" : "shadow";
}

/* ------------------------------------------------------------------------
   The adaptive configurations
   ------------------------------------------------------------------------ */
typedef struct ad_cfg {
    hrm_method method;
    hrm_gk_mode gk;
    hrm_gk_rule rule;
    int cost;           /* new evaluations per step / split / Kronrod rule */
    const char *name;
} ad_cfg;

static const ad_cfg ad_cfgs[] = {
    { HRM_NESTED_SIMPSON, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 2, "nested-simpson" },
    { HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_RULE_DEFAULT, 15, "gk-global" },
    { HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_K7, 7, "gk-global-k7" },
    { HRM_GAUSS_KRONROD, HRM_GK_LOCAL, HRM_GK_RULE_DEFAULT, 15, "gk-local" },
    { HRM_BOGACKI_SHAMPINE, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 3, "bogacki-shampine" },
    { HRM_DORMAND_PRINCE, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 5, "dormand-prince" },
    { HRM_FEHLBERG, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 5, "fehlberg" },
    { HRM_CASH_KARP, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 5, "cash-karp" },
    { HRM_VERNER, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 6, "verner" },
};
#define AD_NCFG ((int)(sizeof ad_cfgs / sizeof ad_cfgs[0]))

static hrm_options ad_options(const ad_cfg *cfg, double rtol)
{
    hrm_options o = hrm_default_options(cfg->method);
    o.gk_mode = cfg->gk;
    o.gk_rule = cfg->rule;
    o.rtol = (hrm_real)rtol;
    o.max_evals = 1000000; /* the low-order methods need ~1e5 at rtol 1e-9 */
    return o;
}

/* The scenes' rays. */
static const double ad_hom_t0 = 0.5, ad_hom_t1 = 10.5;   /* sigma_t (1+k) T = 7.5 ... 15 */
static const double ad_abs_t0 = 0.5, ad_abs_t1 = 8.5;    /* 2.5 periods of sigma_a */
static const double ad_sh_t0 = 0.5, ad_sh_t1 = 4.5;      /* shadow [2.3137, 3.7071) */

static void ad_ray(int kind, double *t0, double *t1)
{
    *t0 = kind == AD_ABS ? ad_abs_t0 : kind == AD_HOM ? ad_hom_t0 : ad_sh_t0;
    *t1 = kind == AD_ABS ? ad_abs_t1 : kind == AD_HOM ? ad_hom_t1 : ad_sh_t1;
}

/* ========================================================================
   3. Accuracy on smooth closed-form scenes, rtol 1e-3 ... 1e-9
   ======================================================================== */

static void ad_accuracy_case(scene *sc, int kind, const ad_cfg *cfg, hrm_form form)
{
    problem p = ad_problem(sc, kind);
    double rt[8], t0, t1, ratios[8], tau;
    char line[256];
    int nr = ad_rtols(rt, cfg->method), i, pos = 0;
    ad_ray(kind, &t0, &t1);
    tau = max_tau(&p, t0, t1);
    for (i = 0; i < nr; ++i) {
        hrm_options o = ad_options(cfg, rt[i]);
        hrm_medium m = problem_medium(&p);
        hrm_result r;
        hrm_status st;
        double e, bound;
        o.form = form;
        st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r);
        e = rel_err_L(&p, t0, t1, &r);
        bound = 10 * rt[i] + fp_floor(r.stats.steps, tau);
        CHECK_INT(st, HRM_OK, "%s %s scene %s rtol %g: status", cfg->name,
                  form_name(form),
                  ad_kind_name(kind), rt[i]);
        /* 10 rtol: local control, summed tolerance <= 2 rtol |L| (top) */
        CHECK(e <= bound, "%s %s %s rtol %g: relative error %.3g > bound %.3g (evals %ld)",
              cfg->name, form_name(form),
              ad_kind_name(kind), rt[i], e, bound, r.stats.evals);
        if (kind == AD_ABS) {
            /* Tr = exp(-tau): tau is controlled with the same rtol (its
               error weighed by Tr), so |dTr|/Tr = |dtau| <= 10 rtol tau. In
               the RTE form Tr is marched itself: 10 rtol relative. */
            double et = rel_err_Tr(&p, t0, t1, r.Tr);
            double bt = 10 * rt[i] * (tau > 1 ? tau : 1) + fp_floor(r.stats.steps, tau);
            CHECK(et <= bt, "%s %s absorber rtol %g: Tr relative error %.3g > %.3g",
                  cfg->name, form_name(form), rt[i], et, bt);
        }
        ratios[i] = e / rt[i];
    }
    for (i = 0; i < nr; ++i)
        pos += snprintf(line + pos, sizeof line - (size_t)pos, " %.2g", ratios[i]);
    NOTE("%-16s %-13s %-11s error/rtol at rtol 1e-3..:%s", cfg->name,
         form_name(form),
         ad_kind_name(kind), line);
}

static void ad_accuracy(void)
{
    scene sc;
    int k, i;
    ad_scene_init(&sc);
    for (k = 0; k < 2; ++k) {
        int kind = k ? AD_ABS : AD_HOM;
        for (i = 0; i < AD_NCFG; ++i) ad_accuracy_case(&sc, kind, &ad_cfgs[i], HRM_FORM_OPTICAL_DEPTH);
    }
    /* The RTE form of the pairs on these non-stiff rays: the controlled
       steps keep h sigma_t well inside every pair's stability region. */
    for (k = 0; k < 2; ++k) {
        int kind = k ? AD_ABS : AD_HOM;
        for (i = 0; i < AD_NCFG; ++i)
            if (is_pair(ad_cfgs[i].method)) ad_accuracy_case(&sc, kind, &ad_cfgs[i], HRM_FORM_RTE);
    }
}

/* ========================================================================
   4. Evaluation counts: the per-step contract
   ======================================================================== */

static void ad_eval_counts(void)
{
    static const double rts_d[] = { 1e-3, 1e-6 }, rts_f[] = { 1e-3, 1e-4 };
    const double *rts = real_is_float() ? rts_f : rts_d;
    scene sc;
    long any_rejected[AD_NCFG];
    int i, k, ri, n0;
    ad_scene_init(&sc);
    memset(any_rejected, 0, sizeof any_rejected);
    for (k = 0; k < 3; ++k) {
        int kind = k == 0 ? AD_HOM : k == 1 ? AD_ABS : AD_SHADOW;
        problem p = ad_problem(&sc, kind);
        double t0, t1;
        ad_ray(kind, &t0, &t1);
        for (i = 0; i < AD_NCFG; ++i) {
            const ad_cfg *cfg = &ad_cfgs[i];
            for (ri = 0; ri < 2; ++ri)
                for (n0 = 1; n0 <= 3; n0 += 2) {
                    hrm_options o = ad_options(cfg, rts[ri]);
                    /* one sigma evaluation per abscissa: the coupled
                       contract (decoupled counts: test_transmittance.c) */
                    o.tau_mode = HRM_TAU_COUPLED;
                    o.find_jumps = -1; /* one pass: the formulas below */
                    hrm_medium m = problem_medium(&p);
                    hrm_result r;
                    hrm_status st;
                    long calls, want, steps = -1;
                    char what[160];
                    if (is_pair(cfg->method) && n0 > 1) continue; /* steps ignored */
                    if (!is_pair(cfg->method)) o.steps = n0;
                    snprintf(what, sizeof what, "%s %s rtol %g steps %d", cfg->name,
                             ad_kind_name(kind),
                             rts[ri], o.steps);
                    scene_reset_counts(&sc);
                    st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r);
                    /* the counts hold whatever the outcome; the shadow's
                       statuses are ad_shadow's business (Bogacki-Shampine
                       may end at h_min there, see that group) */
                    if (kind == AD_SHADOW)
                        CHECK(st == HRM_OK || st == HRM_WARN_H_MIN, "%s: status %d", what, st);
                    else
                        CHECK_INT(st, HRM_OK, "%s: status", what);
                    calls = kind == AD_ABS ? sc.n_le : sc.n_li;
                    CHECK_INT(r.stats.evals, calls, "%s: stats.evals = source callback calls", what);
                    if (cfg->method == HRM_NESTED_SIMPSON) {
                        /* 2 panels + 1 initial samples, then 2 (its
                           quarter points) per interval, accepted or split;
                           every accepted interval is a step */
                        want = 2L * n0 + 1 + 2 * (r.stats.steps + r.stats.rejected);
                        steps = n0 + r.stats.rejected;
                    } else if (cfg->method == HRM_GAUSS_KRONROD) {
                        /* 7 or 15 per Kronrod rule: n0 initial intervals,
                           two halves per split (global: bisection; local:
                           both halves), and the ray's two ends */
                        want = (long)cfg->cost * (n0 + 2 * r.stats.rejected) + 2;
                        steps = n0 + r.stats.rejected;
                    } else {
                        /* the start sample, then at most `cost` new per
                           attempt, accepted or rejected (the c = 1 stage is
                           the next step's start; a retry after a rejection
                           reuses the nodes it shares with earlier ones) */
                        want = 1 + (long)cfg->cost * (r.stats.steps + r.stats.rejected);
                    }
                    if (is_pair(cfg->method) || real_is_float())
                        /* float: nodes closer than the resolution of t
                           share one evaluation too */
                        CHECK(r.stats.evals <= want && (r.stats.rejected > 0 || r.stats.evals == want),
                              "%s: evals %ld from steps %ld, rejected %ld: at most %ld, exactly without "
                              "a rejection", what, r.stats.evals, r.stats.steps, r.stats.rejected, want);
                    else
                        CHECK_INT(r.stats.evals, want, "%s: evals from steps %ld, rejected %ld",
                                  what, r.stats.steps, r.stats.rejected);
                    if (kind == AD_ABS && sc.log_n < LOG_CAP) {
                        /* no abscissa evaluated twice (the Le calls are logged) */
                        int a, b, twice = 0;
                        for (a = 0; a < sc.log_n && !twice; ++a)
                            for (b = a + 1; b < sc.log_n && !twice; ++b) twice = sc.log_le[a] == sc.log_le[b];
                        CHECK(!twice, "%s: no abscissa evaluated twice (%d logged)", what, sc.log_n);
                    }
                    if (steps >= 0)
                        CHECK_INT(r.stats.steps, steps, "%s: accepted intervals", what);
                    if (kind == AD_ABS) {
                        /* sigma_a once per abscissa, no other medium call */
                        CHECK_INT(r.stats.medium_evals, r.stats.evals, "%s: medium_evals", what);
                        CHECK_INT(sc.n_sa, r.stats.medium_evals, "%s: sigma_a calls", what);
                    } else {
                        CHECK_INT(r.stats.medium_evals, 0, "%s: homogeneous: no medium evaluation", what);
                    }
                    any_rejected[i] += r.stats.rejected;
                }
        }
    }
    /* the counts above were checked on solves that refined */
    for (i = 0; i < AD_NCFG; ++i)
        CHECK(any_rejected[i] > 0, "%s: the counts were checked with rejected steps / splits",
              ad_cfgs[i].name);
}

/* ========================================================================
   5. Limits: clipped rtol, h_min, budget, bad budget
   ======================================================================== */

/* Li stepping from 1 to 3 at *(double *)u (h_min at the ray's end), and
   the medium of that case (sigma_a 0.1, sigma_s 0.5) as callbacks. */
static void ad_step_li(void *u, hrm_real t, hrm_real out[NCH])
{
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)((double)t < *(const double *)u ? 1 : 3);
}

static void ad_step_sig(void *u, hrm_real t, hrm_real sa[NCH], hrm_real ss[NCH])
{
    int c;
    (void)u;
    (void)t;
    for (c = 0; c < NCH; ++c) {
        sa[c] = (hrm_real)0.1;
        ss[c] = (hrm_real)0.5;
    }
}

static void ad_limits(void)
{
    scene sc;
    problem hom, shadow;
    int i;
    double floor_rtol = 100 * real_eps();
    ad_scene_init(&sc);
    hom = ad_problem(&sc, AD_HOM);
    shadow = ad_problem(&sc, AD_SHADOW);

    /* rtol below 100 epsilons: raised to exactly that floor.
       (a) every method on a constant integrand (no extinction, emission
       per length: L = Le T), which every rule integrates exactly, so that
       nothing but the clip is reported; (b) the same solve at rtol = 100
       eps gives bit-identical results and counts, on (a) and, for the
       methods that reach 100 eps cheaply (K15 and the pairs of order >= 4),
       on the homogeneous scene. */
    for (i = 0; i < AD_NCFG; ++i) {
        const ad_cfg *cfg = &ad_cfgs[i];
        int v;
        for (v = 0; v < 2; ++v) {
            hrm_options o = ad_options(cfg, 1e-30);
            hrm_medium m = problem_medium(&hom);
            hrm_result r1, r2;
            hrm_status s1, s2;
            double t0 = 0.5, t1 = 2.5;
            int c, same = 1;
            if (v == 1 && (cfg->method == HRM_NESTED_SIMPSON || cfg->method == HRM_BOGACKI_SHAMPINE))
                continue; /* 2e5 evaluations at 2e-14 */
            if (v == 0) {
                m.Li = NULL;
                m.Le = const_Le;
                m.flags |= HRM_EMISSION_PER_LENGTH;
                for (c = 0; c < NCH; ++c) m.const_sigma_a[c] = m.const_sigma_s[c] = 0;
            }
            s1 = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r1);
            o.rtol = (hrm_real)floor_rtol;
            s2 = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r2);
            if (v == 0) {
                CHECK_INT(s1, HRM_WARN_RTOL_CLIPPED, "%s: rtol 1e-30, constant integrand", cfg->name);
                CHECK_INT(s2, HRM_OK, "%s: rtol 100 eps, constant integrand: not clipped", cfg->name);
                /* L = Le T: exact rules, round-off of a few steps' sums */
                for (c = 0; c < NCH; ++c)
                    CHECK_REL(r1.L[c], sc.le[c] * (t1 - t0), fp_floor(r1.stats.steps, 0),
                              "%s: clipped rtol: L = Le T, channel %d", cfg->name, c);
            } else {
                CHECK_INT(s1, s2 == HRM_OK ? HRM_WARN_RTOL_CLIPPED : s2,
                          "%s: rtol 1e-30: clipped (at 100 eps the status is %d)", cfg->name, s2);
                /* error: at 2e-14 the estimate is at round-off; bound 1e-12
                   (double) or 10 rtol (float, where the floor is 1.2e-5) */
                CHECK(rel_err_L(&hom, t0, t1, &r1) <= (real_is_float() ? 1.2e-4 : 1e-12),
                      "%s: clipped rtol: relative error %.3g", cfg->name,
                      rel_err_L(&hom, t0, t1, &r1));
            }
            for (c = 0; c < NCH; ++c) same &= r1.L[c] == r2.L[c] && r1.Tr[c] == r2.Tr[c];
            CHECK(same && r1.stats.evals == r2.stats.evals && r1.stats.steps == r2.stats.steps,
                  "%s %s: rtol 1e-30 solves exactly as rtol = 100 eps", cfg->name,
                  v ? "homogeneous" : "constant");
        }
    }

    /* h_min reached: a tolerance no step of at least h_min can meet (the
       shadow's jumps at rtol 1e-9, 1e-4 under float). The estimate is
       finite; every step refused at h_min is taken anyway, so the error is
       at most that of the two intervals (width < 2 h_min) holding an edge,
       each off by at most its width times the integrand's maximum
       sigma_s E times the sum of |weights| (1 for positive rules, 1.65 for
       Dormand-Prince's b), plus the controlled error elsewhere:
       4 * 1.7 h_min max f + 10 rtol L, with h_min = T/200 about 10% of L. */
    for (i = 0; i < AD_NCFG; ++i) {
        const ad_cfg *cfg = &ad_cfgs[i];
        double rtol = real_is_float() ? 1e-4 : 1e-9, t0, t1, hmin = 0.02;
        hrm_options o = ad_options(cfg, rtol);
        hrm_medium m = problem_medium(&shadow);
        hrm_result r;
        hrm_status st;
        double worst = 0;
        int c;
        ad_ray(AD_SHADOW, &t0, &t1);
        o.h_min = (hrm_real)hmin;
        o.find_jumps = -1; /* (a located edge would need no step below h_min) */
        st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r);
        CHECK_INT(st, HRM_WARN_H_MIN, "%s: h_min %g at rtol %g", cfg->name, hmin, rtol);
        CHECK(result_finite(&r), "%s: h_min: finite estimate", cfg->name);
        for (c = 0; c < NCH; ++c) {
            double x = exact_L(&shadow, c, t0, t1), f = sc.sig_s[c] * sc.E[c];
            double d = fabs((double)r.L[c] - x) / (4 * 1.7 * hmin * f + 10 * rtol * x);
            if (!(d <= worst)) worst = d;
        }
        CHECK(worst <= 1, "%s: h_min: error / (6.8 h_min max f + 10 rtol L) = %.3g", cfg->name, worst);
    }

    /* h_min at the ray's end: a jump of Li within h_min of t1 (h_min 1e-4
       on [0, 1], no jump search), the medium as constants and as sigma
       callbacks, without a warp and under the distance warp (h_min in u,
       the jump within 1.1 h_min of u's end). The pairs' last step may be
       stretched to the rest of the ray, up to 1.1 h_min, so that no
       sliver is left; refused there, it had been tried again the same
       until the budget ran out (Dormand-Prince, the jump at 0.9999:
       99 959 rejections, HRM_WARN_MAX_EVALS). Now taken as a step at
       h_min: at most a few hundred rejections, HRM_OK or HRM_WARN_H_MIN,
       L within the h_min bound above (4 * 1.7 h_min max f, a step of
       h_min in u being at most max dt/du = e^0.6 / 0.6 < 3.1 long in t
       under the distance warp, sigma_ref 0.6) plus 10 rtol. */
    for (i = 0; i < AD_NCFG; ++i) {
        const ad_cfg *cfg = &ad_cfgs[i];
        int j, c, cb, wd;
        if (!is_pair(cfg->method)) continue;
        for (cb = 0; cb < 2; ++cb)
            for (wd = 0; wd < 2; ++wd)
                for (j = 1; j <= 4; ++j) {
                    double rtol = real_is_float() ? 1e-4 : 1e-6, hmin = 1e-4, xj, x;
                    hrm_options o = ad_options(cfg, rtol);
                    hrm_medium m;
                    hrm_result r;
                    hrm_status st;
                    memset(&m, 0, sizeof m);
                    if (cb) {
                        m.sigma = ad_step_sig;
                    } else {
                        m.flags = HRM_MEDIUM_HOMOGENEOUS;
                        for (c = 0; c < NCH; ++c) {
                            m.const_sigma_a[c] = (hrm_real)0.1;
                            m.const_sigma_s[c] = (hrm_real)0.5;
                        }
                    }
                    /* without a warp 2.5e-5 j before t1; under the distance
                       warp (u = 1 - e^(-0.6 t)) 2.5e-5 j before u's end */
                    xj = wd ? -log(exp(-0.6) + 2.5e-5 * j) / 0.6 : 1 - 2.5e-5 * j;
                    m.Li = ad_step_li;
                    m.user = &xj;
                    o.h_min = (hrm_real)hmin;
                    o.find_jumps = -1;
                    if (wd) {
                        o.warp.kind = HRM_WARP_DISTANCE;
                        o.warp.sigma_ref = (hrm_real)0.6;
                    }
                    st = hrm_solve(&m, 0, 1, &o, &r);
                    CHECK(st == HRM_OK || st == HRM_WARN_H_MIN,
                          "%s, %s%s: a jump %g before the end, h_min %g: status %s", cfg->name,
                          cb ? "callbacks" : "constants", wd ? ", distance warp" : "", 1 - xj, hmin,
                          hrm_status_string(st));
                    CHECK(r.stats.rejected <= 400, "%s, %s%s: a jump %g before the end: %ld rejected steps",
                          cfg->name, cb ? "callbacks" : "constants", wd ? ", distance warp" : "", 1 - xj,
                          r.stats.rejected);
                    x = 0.5 / 0.6 * ((1 - exp(-0.6 * xj)) + 3 * (exp(-0.6 * xj) - exp(-0.6)));
                    for (c = 0; c < NCH; ++c)
                        CHECK_NEAR((double)r.L[c], x, 4 * 1.7 * hmin * (wd ? 3.1 : 1) * 3 * 0.5 + 10 * rtol * x,
                                   "%s, %s%s: a jump %g before the end: L", cfg->name,
                                   cb ? "callbacks" : "constants", wd ? ", distance warp" : "", 1 - xj);
                }
    }

    /* Budget. The solve without a budget takes N evaluations; every
       budget from one step's cost to N - 1 (up to 400) must give
       HRM_WARN_MAX_EVALS, a finite estimate and evals <= max_evals (the
       run is the same up to the first refused refinement, which a budget
       below N must meet). A budget well above N changes nothing. The
       shadow at rtol 1e-6 (3e-5 under float) needs N > 100 with every
       method and three channels or more; a single channel (the thinnest)
       may need fewer, so there rtol is halved while it stays above the
       clip at 100 eps until N > 150 (nested Simpson under float: N = 135
       at 3e-5, 179 at 1.5e-5). */
    for (i = 0; i < AD_NCFG; ++i) {
        const ad_cfg *cfg = &ad_cfgs[i];
        long budget, minimum = is_pair(cfg->method) ? cfg->cost + 1L
                             : cfg->method == HRM_GAUSS_KRONROD ? cfg->cost + 2L
                             : 4L * hrm_default_options(HRM_NESTED_SIMPSON).steps + 1; /* its first panels */
        long over = 0, badst = 0, unfinite = 0, miscount = 0, tried = 0, full_evals;
        double t0, t1, worst = 0, rtol = real_is_float() ? 3e-5 : 1e-6;
        hrm_options o = ad_options(cfg, rtol);
        hrm_medium m = problem_medium(&shadow);
        hrm_result full, r;
        hrm_status st;
        int c, same = 1;
        ad_ray(AD_SHADOW, &t0, &t1);
        /* one pass, so that a budget cuts the same run short (the jump
           search's budgets: test_breaks.c) */
        o.find_jumps = -1;
        st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &full);
        /* at least 100 evaluations (150 before nested Simpson returned its
           Richardson-corrected halves: it now solves the shadow at float's
           tightest rtol in about 105), so that the budgets below it span
           a decade above the method's minimum */
        while (st == HRM_OK && full.stats.evals <= 100 && rtol / 2 > floor_rtol) {
            rtol /= 2;
            o = ad_options(cfg, rtol);
            o.find_jumps = -1;
            st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &full);
        }
        CHECK_INT(st, HRM_OK, "%s: shadow at rtol %g without a budget", cfg->name, rtol);
        full_evals = full.stats.evals;
        CHECK(full_evals > 100, "%s: the unbudgeted solve takes %ld > 100 evaluations", cfg->name,
              full_evals);
        for (budget = minimum; budget < full_evals && budget <= 400; budget += budget < 40 ? 1 : 23) {
            double e;
            o.max_evals = budget;
            scene_reset_counts(&sc);
            st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r);
            tried++;
            badst += st != HRM_WARN_MAX_EVALS;
            over += r.stats.evals > budget;
            miscount += r.stats.evals != sc.n_li;
            unfinite += !result_finite(&r);
            e = rel_err_L(&shadow, t0, t1, &r);
            if (budget >= 200 && !(e <= worst)) worst = e;
        }
        CHECK_INT(badst, 0, "%s: %ld budgets from %ld to min(400, %ld): status HRM_WARN_MAX_EVALS",
                  cfg->name, tried, minimum, full_evals - 1);
        CHECK_INT(over, 0, "%s: stats.evals <= max_evals", cfg->name);
        CHECK_INT(miscount, 0, "%s: stats.evals = Li calls under a budget", cfg->name);
        CHECK_INT(unfinite, 0, "%s: finite estimates under a budget", cfg->name);
        /* a usable estimate: with 200 or more samples every method has
           bracketed both edges (measured error below 1%; one interval of
           width T/16 across an edge costs at most 1/16 of the range's
           share of L) */
        CHECK(worst <= 0.1, "%s: budget >= 200: relative error %.3g <= 0.1", cfg->name, worst);
        o.max_evals = 2 * full_evals + 1000;
        st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r);
        for (c = 0; c < NCH; ++c) same &= r.L[c] == full.L[c];
        CHECK(st == HRM_OK && same && r.stats.evals == full_evals,
              "%s: a budget never reached changes nothing", cfg->name);
    }

    /* A budget below one step's cost cannot be honoured: HRM_ERR_BAD_OPTION
       with the error result (L = 0, Tr = 1); one step's cost is accepted. */
    for (i = 0; i < AD_NCFG; ++i) {
        const ad_cfg *cfg = &ad_cfgs[i];
        int steps = is_pair(cfg->method) ? 0 : 3;
        long cost = is_pair(cfg->method) ? cfg->cost + 1L
                  : cfg->method == HRM_GAUSS_KRONROD ? (long)cfg->cost * steps + 2 : 4L * steps + 1;
        hrm_options o = ad_options(cfg, 1e-4);
        hrm_medium m = problem_medium(&hom);
        hrm_result r;
        hrm_status st;
        o.steps = steps;
        o.max_evals = cost - 1;
        st = hrm_solve(&m, (hrm_real)0.5, (hrm_real)4.5, &o, &r);
        CHECK_INT(st, HRM_ERR_BAD_OPTION, "%s: max_evals %ld, one below one step's cost",
                  cfg->name, cost - 1);
        CHECK(is_error_result(&r) && r.stats.evals == 0, "%s: bad budget: L = 0, Tr = 1, no evaluation",
              cfg->name);
        o.max_evals = cost;
        scene_reset_counts(&sc);
        st = hrm_solve(&m, (hrm_real)0.5, (hrm_real)4.5, &o, &r);
        CHECK(st == HRM_OK || st == HRM_WARN_MAX_EVALS, "%s: max_evals %ld = one step's cost: status %d",
              cfg->name, cost, st);
        CHECK(r.stats.evals <= cost && result_finite(&r), "%s: one step's budget: evals %ld <= %ld",
              cfg->name, r.stats.evals, cost);
    }
}

/* ========================================================================
   6. A sharp shadow (discontinuous Li)
   ======================================================================== */

/* The shadow's share of L in channel c: what missing it entirely costs. */
static double ad_shadow_share(const problem *p, int c, double t0, double t1)
{
    const scene *sc = p->sc;
    double st = sig_t_hom(sc, c);
    double dark = sc->sig_s[c] * sc->E[c] / st * (exp(-st * (sc->lo - t0)) - exp(-st * (sc->hi - t0)));
    return dark / exact_L(p, c, t0, t1);
}

/* No sampled error estimate sees an edge that no sample brackets: an edge
   in the gap between an interval's end and its first Gauss-Kronrod node,
   or between two stages of a long Runge-Kutta step, costs up to the
   shadow's share whatever rtol is. The shadow here (ray [0.5, 4.5],
   shadow [2.3137, 3.7071)) is bracketed by every method once rtol <= 1e-4;
   then a step across an edge, whose error does not halve with the step, is
   a "rough" step: at most 16 are accepted, each within rtol/16 of
   max(|L| so far, scale), adding at most rtol |L|; with the smooth steps'
   2 rtol |L| and the asymptotic estimates the bound is 10 rtol, as on
   smooth scenes (measured below 2 rtol here).
   The status is HRM_OK: "a jump costs a few refinements, not a descent to
   h_min" (hrm__rough's comment).
   Asserted: rtol <= 1e-4: error <= 10 rtol (under float 1e-4 only);
   rtol >= 1e-3: error <= the shadow's share + 10 rtol (a long step may
   skip the shadow, nothing worse); and the error falls at least 100 times
   from rtol 1e-2 to 1e-6 (double), unless it is below 1e-4 at 1e-2. */
static void ad_shadow(void)
{
    static const double rts[] = { 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8 };
    scene sc;
    problem p;
    int i, ri, c, nr = real_is_float() ? 3 : 7;
    double t0, t1, share = 0, tau;
    ad_scene_init(&sc);
    p = ad_problem(&sc, AD_SHADOW);
    ad_ray(AD_SHADOW, &t0, &t1);
    tau = max_tau(&p, t0, t1);
    for (c = 0; c < NCH; ++c)
        if (ad_shadow_share(&p, c, t0, t1) > share) share = ad_shadow_share(&p, c, t0, t1);
    for (i = 0; i < AD_NCFG; ++i) {
        const ad_cfg *cfg = &ad_cfgs[i];
        double e[7];
        char line[256];
        int pos = 0;
        for (ri = 0; ri < nr; ++ri) {
            hrm_options o = ad_options(cfg, rts[ri]);
            hrm_medium m = problem_medium(&p);
            hrm_result r;
            hrm_status st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r);
            double bound = 10 * rts[ri] + fp_floor(r.stats.steps, tau);
            if (rts[ri] > 1e-4) bound += share;
            e[ri] = rel_err_L(&p, t0, t1, &r);
            CHECK_INT(st, HRM_OK, "%s shadow rtol %g: status", cfg->name, rts[ri]);
            CHECK(e[ri] <= bound, "%s shadow rtol %g: relative error %.3g > %.3g (evals %ld)",
                  cfg->name, rts[ri], e[ri], bound, r.stats.evals);
            pos += snprintf(line + pos, sizeof line - (size_t)pos, " %.2g", e[ri] / rts[ri]);
        }
        /* (unless the answer at rtol 1e-2 is within 1e-4 already) */
        if (nr == 7)
            CHECK(e[4] * 100 <= e[0] || e[0] <= 1e-4, "%s shadow: error falls with rtol (%.3g at rtol 1e-2, %.3g "
                  "at 1e-6)", cfg->name, e[0], e[4]);
        NOTE("%-16s shadow error/rtol at rtol 1e-2..:%s", cfg->name, line);
    }
    NOTE("shadow share of L (the cost of missing it): %.3f", share);

    /* The blind spot, measured: the shadow's far edge 5e-5 past a dyadic
       point of the bisection (p = 2.625 from t0), inside the gap before
       the first K15 node of [2.625, 2.75]: no sample sees the sliver. */
    if (!real_is_float()) {
        hrm_options o = ad_options(&ad_cfgs[2], 1e-8);
        hrm_medium m;
        hrm_result r;
        hrm_status st;
        sc.lo = 1.66855;
        sc.hi = 3.12505;
        m = problem_medium(&p);
        st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &o, &r);
        NOTE("gk-global, shadow [1.66855, 3.12505), rtol 1e-8: status %d, relative error %.2g "
             "(an edge no node brackets)", st, rel_err_L(&p, t0, t1, &r));
    }
}

/* ========================================================================
   7. No evaluation outside [t0, t1]
   ======================================================================== */

static void ad_domain(void)
{
    scene sc;
    int i, k, f;
    ad_scene_init(&sc);
    for (k = 0; k < 3; ++k) {
        int kind = k == 0 ? AD_HOM : k == 1 ? AD_ABS : AD_SHADOW;
        problem p = ad_problem(&sc, kind);
        /* ends that are not representable: t0 + (t1 - t0) may round */
        double t0 = 0.1 * (k + 1), t1 = t0 + 3.3;
        hrm_real r0 = (hrm_real)t0, r1 = (hrm_real)t1;
        for (i = 0; i < AD_NCFG; ++i)
            for (f = 0; f < (is_pair(ad_cfgs[i].method) ? 3 : 2); ++f) {
                hrm_options o = ad_options(&ad_cfgs[i], 1e-5);
                hrm_medium m = problem_medium(&p);
                hrm_result r;
                hrm_status st;
                /* f: 0 coupled tau (the rule's nodes alone), 1 decoupled
                   (the transmittance layer samples sigma at both ends), 2
                   the RTE form */
                o.form = f == 2 ? HRM_FORM_RTE : HRM_FORM_OPTICAL_DEPTH;
                o.tau_mode = f == 1 ? HRM_TAU_DECOUPLED : HRM_TAU_COUPLED;
                scene_reset_counts(&sc);
                st = hrm_solve(&m, r0, r1, &o, &r);
                CHECK(st >= 0 && sc.tmin >= (double)r0 && sc.tmax <= (double)r1,
                      "%s %s scene %d: callbacks at t in [%.17g, %.17g], ray [%.17g, %.17g] "
                      "(status %d)", ad_cfgs[i].name, f == 2 ? "rte" : f ? "decoupled" : "coupled", kind,
                      sc.tmin, sc.tmax, (double)r0, (double)r1, st);
                /* every method samples both ends: nested Simpson's and the
                   pairs' nodes include them, Gauss-Kronrod samples them
                   once (its nodes are interior) */
                CHECK(sc.tmin == (double)r0 && sc.tmax == (double)r1,
                          "%s %s scene %d: both ends are sampled", ad_cfgs[i].name,
                          f == 2 ? "rte" : f ? "decoupled" : "coupled", kind);
            }
    }
}

/* ========================================================================
   8. hrm_transmittance with adaptive methods
   ======================================================================== */

/* Bound: tau is controlled with rtol relative to the scale of tau, so
   |dTr|/Tr = |dtau| <= 10 rtol tau (as in the accuracy group). */
static void ad_transmittance(void)
{
    static const double rts[] = { 1e-3, 1e-6, 1e-9 };
    scene sc;
    problem p;
    int i, ri, nr = real_is_float() ? 1 : 3, c;
    double t0, t1, tau;
    ad_scene_init(&sc);
    p = ad_problem(&sc, AD_ABS);
    ad_ray(AD_ABS, &t0, &t1);
    tau = max_tau(&p, t0, t1);
    for (i = 0; i < AD_NCFG; ++i) {
        const ad_cfg *cfg = &ad_cfgs[i];
        /* the low-order methods stop at 1e-6 (time; see ad_rtols) */
        int low = cfg->method == HRM_NESTED_SIMPSON || cfg->method == HRM_BOGACKI_SHAMPINE;
        for (ri = 0; ri < (low && nr > 2 ? 2 : nr); ++ri) {
            hrm_options o = ad_options(cfg, rts[ri]);
            hrm_medium m = problem_medium(&p);
            hrm_real Tr[NCH];
            hrm_stats stats;
            hrm_status st;
            double e, bound;
            scene_reset_counts(&sc);
            st = hrm_transmittance(&m, (hrm_real)t0, (hrm_real)t1, &o, Tr, &stats);
            e = rel_err_Tr(&p, t0, t1, Tr);
            bound = 10 * rts[ri] * (tau > 1 ? tau : 1) + fp_floor(stats.steps, tau);
            CHECK_INT(st, HRM_OK, "%s hrm_transmittance rtol %g: status", cfg->name, rts[ri]);
            CHECK(e <= bound, "%s hrm_transmittance rtol %g: Tr relative error %.3g > %.3g",
                  cfg->name, rts[ri], e, bound);
            CHECK_INT(sc.n_le, 0, "%s hrm_transmittance: no source evaluated", cfg->name);
            CHECK_INT(stats.evals, 0, "%s hrm_transmittance: stats.evals", cfg->name);
            CHECK_INT(stats.medium_evals, sc.n_sa, "%s hrm_transmittance: medium_evals = sigma calls",
                      cfg->name);
            for (c = 0; c < NCH; ++c)
                if (!((double)Tr[c] > 0 && (double)Tr[c] <= 1)) e = -1;
            CHECK(e >= 0, "%s hrm_transmittance: 0 < Tr <= 1", cfg->name);
        }
    }
}

/* ======================================================================== */

/* L over [0, 10] of a point light D from the ray at delta: Gauss-Legendre
   split at the peak, panels of width D/5 within 20 D of it (the Lorentzian
   is analytic there at scale D) and 0.01 outside: two resolutions agree to
   1e-13 here. */
static double ad_point_ref(const problem *p, int c, double D, double delta)
{
    double lo = delta - 20 * D > 0 ? delta - 20 * D : 0, hi = delta + 20 * D;
    return gl_exact_f(p, c, 0, 0, lo, (int)ceil(lo / 0.01) + 1) +
           (delta > lo ? gl_exact_f(p, c, 0, lo, delta, (int)ceil((delta - lo) / (D / 5))) : 0) +
           gl_exact_f(p, c, 0, delta, hi, 100) +
           gl_exact_f(p, c, 0, hi, 10, (int)ceil((10 - hi) / 0.01));
}

/* Verified tolerances, the error estimate, bounded budgets.
   1. A light 1e-3 from the ray whose peak lands near a first sample made
      the first estimate of the total 30-220x too large; the tolerance
      judged by half of it let Gauss-Kronrod (local), Dormand-Prince and
      Fehlberg return L 98-99% low with HRM_OK. The accepted estimates then
      add up to more than the tolerance allows: the solve is repeated at
      the scale found. A peak on a node of the first G3/K7 that its halves
      straddle left global Gauss-Kronrod 86% low, and a peak on the ray's
      start passed the pairs as a jump (Dormand-Prince 71% high): now the
      halves check that node's sample, and the pairs' rough steps are
      judged by both estimates. Now within 3 rtol (the bound on
      HRM_OK runs), or a warning. (Double only: the peak is 1e-3 wide,
      float resolves t near 1.3 to 1e-7.)
   2. result.error: -1 for the fixed-step methods; for the adaptive ones
      finite, >= 0, and at least a third of the error of these runs (the
      estimates are calibrated to the order returned, not bounds).
   3. Any budget: 0 <= L <= max(Li) (1 - Tr) (S / sigma_t is a weighted mean
      of Le and Li), whatever the status. */
/* A thin medium (sigma_a = 0.01, sigma_s = 0.04) lit by a point light 1e-3
   from the ray at delta, given as constants or (callbacks != 0) as the same
   constants through sigma_a/sigma_s callbacks (the sine profile with no
   amplitude: sigma_t = 0.05, sigma_a = 0.2 sigma_t). */
static problem ad_thin_light(scene *sc, double delta, int callbacks)
{
    problem p;
    int c;
    scene_init(sc);
    for (c = 0; c < NCH; ++c) {
        sc->sig_a[c] = 0.01;
        sc->sig_s[c] = 0.04;
        sc->I[c] = 1;
        sc->a[c] = 0.05;
        sc->b[c] = 0;
        sc->pa[c] = 0.2;
    }
    sc->profile = PROFILE_SINE;
    sc->D = 1e-3;
    sc->delta = delta;
    p = make_problem(sc, callbacks ? P_HET : P_HOM, 0, LIGHT_POINT);
    return p;
}

/* A budget is an anytime answer: with max_evals below what rtol 1e-10
   needs, nested Simpson and global Gauss-Kronrod spend the evaluations on
   the intervals with the largest estimates. Asserted for both: at most
   max_evals evaluations and L within the physical bound 0 <= L <=
   max(S/sigma_t) (1 - Tr). Against a uniform Simpson rule with as many
   samples (2N + 1 <= max_evals), on a point light 0.2 from the ray (a peak
   a fifth of the first pass's spacing wide): nested Simpson's error stays
   within 3x of the uniform rule's at every budget and within 3x of its
   own estimate when it warns (its first pass is as spread as the uniform
   rule's, then it concentrates on the peak). Measured, not asserted:
   Gauss-Kronrod's first 7 nodes can straddle that peak (error 0.74 at
   9-17 evaluations, uniform Simpson 0.2-0.27), and on a light 2 from the
   ray, smooth over the whole ray, nested Simpson at 17-33 evaluations is
   6-40x behind the uniform rule (its estimates of the coarse intervals
   are those of S2, pessimistic for the corrected sum), level from 49. */
static void ad_anytime(void)
{
    static const long budgets[] = { 9, 13, 17, 25, 33, 49, 65, 97, 129, 193 };
    int k, c, cb, mi, bi;
    for (k = 0; k < 2; ++k)
        for (cb = 0; cb < 2; ++cb) {
            scene sc;
            problem p;
            double ref[NCH], bound[NCH];
            p = ad_thin_light(&sc, 4.0, cb);
            sc.D = k == 0 ? 0.2 : 2;
            for (c = 0; c < NCH; ++c) {
                ref[c] = gl_exact_f(&p, c, 0, 0, 10, 1000);
                /* S / sigma_t <= max Li = I / D^2 (sigma_s Li / sigma_t) */
                bound[c] = sc.I[c] / (sc.D * sc.D) * (1 - exp(-max_tau(&p, 0, 10)));
            }
            for (mi = 0; mi < 2; ++mi)
                for (bi = 0; bi < (int)(sizeof budgets / sizeof budgets[0]); ++bi) {
                    hrm_options o = hrm_default_options(mi ? HRM_GAUSS_KRONROD : HRM_NESTED_SIMPSON);
                    hrm_options u = hrm_default_options(HRM_SIMPSON);
                    hrm_medium m = problem_medium(&p);
                    hrm_result r, ru;
                    hrm_status st;
                    double worst = 0, wu = 0, west = 0;
                    o.rtol = (hrm_real)(real_is_float() ? 1e-6 : 1e-10);
                    o.max_evals = budgets[bi];
                    u.steps = (int)((budgets[bi] - 1) / 2);
                    st = hrm_solve(&m, 0, 10, &o, &r);
                    hrm_solve(&m, 0, 10, &u, &ru);
                    if (st < 0) continue; /* below one step's cost: ad_limits */
                    for (c = 0; c < NCH; ++c) {
                        double e = fabs((double)r.L[c] - ref[c]) / ref[c];
                        double eu = fabs((double)ru.L[c] - ref[c]) / ref[c];
                        worst = e > worst ? e : worst;
                        wu = eu > wu ? eu : wu;
                        west = (double)r.error[c] / ref[c] > west ? (double)r.error[c] / ref[c] : west;
                        CHECK((double)r.L[c] >= 0 && (double)r.L[c] <= bound[c] * (1 + 1e-6),
                              "%s, budget %ld: L = %g within [0, %g]", hrm_method_name(o.method), budgets[bi],
                              (double)r.L[c], bound[c]);
                    }
                    CHECK(r.stats.evals <= budgets[bi], "%s, budget %ld: %ld evaluations",
                          hrm_method_name(o.method), budgets[bi], r.stats.evals);
                    if (k == 0 && mi == 0)
                        CHECK(worst <= 3 * wu + 64 * real_eps(),
                              "%s, %s, budget %ld: error %.3g within 3x uniform Simpson's %.3g (N = %d)",
                              hrm_method_name(o.method), cb ? "sigma callbacks" : "constants", budgets[bi],
                              worst, wu, u.steps);
                    if (st == HRM_WARN_MAX_EVALS && k == 0 && mi == 0)
                        CHECK(worst <= 3 * west + 64 * real_eps(),
                              "%s, budget %ld: error %.3g within 3x its estimate %.3g", hrm_method_name(o.method),
                              budgets[bi], worst, west);
                    if (cb == 0)
                        NOTE("light %g from the ray, %-14s budget %3ld: error %.2g (estimate %.2g), uniform Simpson %.2g",
                             sc.D, hrm_method_name(o.method), budgets[bi], worst, west, wu);
                }
        }
}

static void ad_verified(void)
{
    static const struct { hrm_method m; hrm_gk_mode gk; hrm_gk_rule rule; double delta, rtol; } cases[] = {
        { HRM_GAUSS_KRONROD, HRM_GK_LOCAL, HRM_GK_RULE_DEFAULT, 1.29234, 1e-4 },
        { HRM_DORMAND_PRINCE, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 1.00475, 1e-3 },
        { HRM_FEHLBERG, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 1.15933, 1e-3 },
        /* the peak on a node of the first G3/K7 (5 - 5 sqrt(3/5)) and of
           the first G7/K15 (5 + 5 x_1, x_1 = -0.949107912342758...) */
        { HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_K7, 1.1270166537925831, 1e-2 },
        { HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_K7, 1.1270166537925831, 1e-3 },
        { HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_RULE_DEFAULT, 0.2544604382862074, 1e-2 },
        /* the peak on the ray's start: the first node of every step */
        { HRM_DORMAND_PRINCE, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 0, 1e-2 },
        { HRM_CASH_KARP, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 0, 1e-2 },
        { HRM_VERNER, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 0, 1e-2 },
    };
    static const char *const how[2] = {"constants", "sigma callbacks"};
    scene sc;
    problem p;
    int i, c, mi, cb;
    for (cb = 0; cb < 2; ++cb)
        for (i = 0; i < (int)(sizeof cases / sizeof cases[0]) && !real_is_float(); ++i) {
            hrm_options o = hrm_default_options(cases[i].m);
            hrm_medium m;
            hrm_result r;
            hrm_status st;
            p = ad_thin_light(&sc, cases[i].delta, cb);
            m = problem_medium(&p);
            o.rtol = (hrm_real)cases[i].rtol;
            if (cases[i].gk) o.gk_mode = cases[i].gk;
            o.gk_rule = cases[i].rule;
            st = hrm_solve(&m, 0, 10, &o, &r);
            CHECK(st == HRM_OK || st == HRM_WARN_TOLERANCE, "%s, %s, light at %g: status %d",
                  hrm_method_name(cases[i].m), how[cb], cases[i].delta, st);
            for (c = 0; c < NCH; ++c) {
                double ref = ad_point_ref(&p, c, sc.D, sc.delta), e = fabs((double)r.L[c] - ref);
                if (st == HRM_OK)
                    CHECK_NEAR(e / ref, 0, 3 * cases[i].rtol, "%s, %s, light 1e-3 from the ray at %g, rtol %g: L",
                               hrm_method_name(cases[i].m), how[cb], cases[i].delta, cases[i].rtol);
                CHECK(e <= 3 * (double)r.error[c] + 1e-12 * ref,
                      "%s, %s, light at %g: the error %.3g within 3x the estimate %.3g", hrm_method_name(cases[i].m),
                      how[cb], cases[i].delta, e, (double)r.error[c]);
                if (cb == 0 && c == 0)
                    NOTE("%s%s, light 1e-3 from the ray at %g, rtol %g: status %d, error/rtol %.2g, %ld evaluations",
                         hrm_method_name(cases[i].m), cases[i].gk == HRM_GK_LOCAL ? " (local)"
                         : cases[i].rule == HRM_GK_K7 ? " (G3/K7)" : "", cases[i].delta, cases[i].rtol, st,
                         e / ref / cases[i].rtol, r.stats.evals);
            }
        }
    /* 4. Far from the origin (t0 = 1e8, double: t resolves 1.5e-8), a light
       1e-3 from the ray cannot be integrated to rtol 1e-8: the integrand
       the callbacks see jitters at 1e-5 of itself. The pairs spent their
       100 000 evaluations there and ended 56-95% wrong; they now stop at
       the resolution of t with HRM_WARN_ROUNDOFF, within 1e-4 (measured
       1e-6..1e-5) and a few hundred evaluations. Every adaptive method:
       no step below t's resolution, so no abscissa is evaluated twice
       (the Li calls are logged). */
    for (cb = 0; cb < 2; ++cb)
        for (mi = 0; mi < N_METHODS_ALL && !real_is_float(); ++mi) {
            hrm_method meth = every_method[mi];
            hrm_options o = hrm_default_options(meth);
            hrm_medium m;
            hrm_result r;
            hrm_status st;
            int g;
            if (!is_adaptive(meth)) continue;
            for (g = 0; g < (meth == HRM_GAUSS_KRONROD ? 2 : 1); ++g) {
                const char *name = g ? "gauss-kronrod (local)" : hrm_method_name(meth);
                p = ad_thin_light(&sc, 1e8 + 3.7, cb);
                m = problem_medium(&p);
                o.rtol = (hrm_real)1e-8;
                o.gk_mode = g ? HRM_GK_LOCAL : HRM_GK_DEFAULT;
                scene_reset_counts(&sc);
                st = hrm_solve(&m, (hrm_real)1e8, (hrm_real)(1e8 + 10), &o, &r);
                CHECK_INT(log_repeats(sc.log_li, sc.log_li_n), 0,
                          "%s, %s, t0 = 1e8: abscissae evaluated twice (of %d)", name, how[cb], sc.log_li_n);
                /* every step or interval taken has a node of its own: none
                   is below the resolution of t (the memo would hide its
                   repeated nodes from the count above) */
                CHECK(r.stats.steps <= sc.log_li_n, "%s, %s, t0 = 1e8: %ld steps for %d distinct abscissae",
                      name, how[cb], r.stats.steps, sc.log_li_n);
                if (st != HRM_WARN_ROUNDOFF) NOTE("%s, %s, t0 = 1e8, rtol 1e-8: status %d, evals %ld, error %.2g",
                                                 name, how[cb], st, r.stats.evals,
                                                 fabs((double)r.error[0]));
            }
            if (!is_pair(meth)) continue;
            o.gk_mode = HRM_GK_DEFAULT;
            scene_reset_counts(&sc);
            st = hrm_solve(&m, (hrm_real)1e8, (hrm_real)(1e8 + 10), &o, &r);
            CHECK_INT(st, HRM_WARN_ROUNDOFF, "%s, %s, t0 = 1e8, rtol 1e-8: status", hrm_method_name(meth), how[cb]);
            CHECK(r.stats.evals < 10000, "%s, %s, t0 = 1e8: %ld evaluations", hrm_method_name(meth), how[cb],
                  r.stats.evals);
            for (c = 0; c < NCH; ++c) {
                double ref = gl_exact_f(&p, c, 1e8, 1e8, 1e8 + 3.6, 400) +
                             gl_exact_f(&p, c, 1e8, 1e8 + 3.6, 1e8 + 3.7, 2000) +
                             gl_exact_f(&p, c, 1e8, 1e8 + 3.7, 1e8 + 3.8, 2000) +
                             gl_exact_f(&p, c, 1e8, 1e8 + 3.8, 1e8 + 10, 700);
                CHECK_REL((double)r.L[c], ref, 1e-4, "%s, %s, t0 = 1e8: L within 1e-4", hrm_method_name(meth),
                          how[cb]);
            }
        }
    /* 2 and 3 with Li = 1 (S / sigma_t = albedo), the medium as constants
       and as the same constants through sigma callbacks (then tau comes
       from the transmittance layer) */
    for (cb = 0; cb < 2; ++cb) {
        scene_init(&sc);
        for (c = 0; c < NCH; ++c) {
            sc.a[c] = sig_t_hom(&sc, c);
            sc.b[c] = 0;
            sc.pa[c] = sc.sig_a[c] / sc.a[c];
        }
        sc.profile = PROFILE_SINE;
        p = make_problem(&sc, cb ? P_HET : P_HOM, 0, LIGHT_CONST);
        for (mi = 0; mi < N_METHODS_ALL; ++mi) {
            hrm_method meth = every_method[mi];
            long budget;
            for (budget = 4; budget <= (is_adaptive(meth) ? 40 : 4); ++budget) {
                hrm_options o = hrm_default_options(meth);
                hrm_medium m = problem_medium(&p);
                hrm_result r;
                hrm_status st;
                o.rtol = (hrm_real)1e-6;
                o.max_evals = budget;
                st = hrm_solve(&m, 0, 10 * (1 + (double)budget), &o, &r);
                if (st < 0) {
                    CHECK_INT(st, HRM_ERR_BAD_OPTION, "%s budget %ld: below one step", hrm_method_name(meth), budget);
                    continue;
                }
                for (c = 0; c < NCH; ++c) {
                    /* max(Li)(1 - Tr); with constants sigma_t is known at
                       every sample and the bound is S / sigma_t = albedo Li
                       (with sigma_s callbacks and no Le, sigma_a is never
                       called: max(Li) is what is known) */
                    double albedo = cb ? 1 : sc.sig_s[c] / (sc.sig_a[c] + sc.sig_s[c]);
                    double top = albedo * sc.E[c] * (1 - (double)r.Tr[c]);
                    if (!is_adaptive(meth)) {
                        CHECK((double)r.error[c] == -1, "%s: no error estimate: -1", hrm_method_name(meth));
                        continue;
                    }
                    CHECK(finite_d((double)r.error[c]) && r.error[c] >= 0,
                          "%s, %s, budget %ld: error estimate finite, >= 0", hrm_method_name(meth), how[cb], budget);
                    CHECK(r.L[c] >= 0 && (double)r.L[c] <= top * (1 + 64 * real_eps()),
                          "%s, %s, budget %ld, status %d: 0 <= L %.6g <= max(S / sigma_t)(1 - Tr) %.6g",
                          hrm_method_name(meth), how[cb], budget, st, (double)r.L[c], top);
                }
            }
        }
    }
}

/* ========================================================================
   options.workspace: the deep storage in the caller's memory gives every
   method the same answer, bit for bit, as the stack: L, Tr, the error
   estimate, the stats and the jumps, on a smooth ray, on a hard one (a
   shadow, a light 0.05 from the ray, rtol 1e-9: nested Simpson and
   global Gauss-Kronrod fill their storage and finish left to right), on
   constants and sigma callbacks (the transmittance layer), without and
   with the equiangular warp and an exponential fit; also with a shadow
   ray solved inside Li in the rest of the same workspace. (Bad
   workspaces: tests/test_bad_input.c.)
   ======================================================================== */
typedef struct ad_ws_scene {
    int hard;
    void *inner_ws;     /* Li's shadow ray: its workspace (or NULL) */
    size_t inner_size;
    int nested;         /* Li solves a shadow ray */
} ad_ws_scene;

static void ad_ws_sig(void *u, hrm_real t, hrm_real sa[NCH], hrm_real ss[NCH])
{
    int c;
    (void)u;
    for (c = 0; c < NCH; ++c) {
        sa[c] = (hrm_real)(0.1 + 0.05 * sin(0.9 * (double)t + c));
        ss[c] = (hrm_real)(0.4 + 0.1 * cos(0.7 * (double)t));
    }
}

static void ad_ws_li(void *u, hrm_real t, hrm_real out[NCH])
{
    const ad_ws_scene *s = (const ad_ws_scene *)u;
    double x = (double)t - 2.5, v = 1 / (x * x + (s->hard ? 0.0025 : 1.0));
    int c;
    if (s->hard && (double)t > 3.1 && (double)t < 3.9) v = 0; /* a shadow */
    if (s->nested) {
        /* a shadow ray through the same medium, in the outer workspace's
           rest when there is one */
        hrm_medium m;
        hrm_options o = hrm_default_options(HRM_SIMPSON);
        hrm_real Tr[NCH];
        memset(&m, 0, sizeof m);
        m.sigma = ad_ws_sig;
        o.steps = 8;
        o.tau_mode = HRM_TAU_DECOUPLED;
        o.workspace = s->inner_ws;
        o.workspace_size = s->inner_size;
        if (hrm_transmittance(&m, t, t + 1, &o, Tr, NULL) == HRM_OK) v *= (double)Tr[0];
        else v = -1; /* a callback error: the test sees it */
    }
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)v;
}

static void ad_ws_kink(void *u, hrm_real t, hrm_real sa[NCH], hrm_real ss[NCH])
{
    double v = sin(10 * (double)t);
    int c;
    (void)u;
    for (c = 0; c < NCH; ++c) {
        sa[c] = (hrm_real)(v > 0 ? 0.12 * v : 0);
        ss[c] = (hrm_real)(v > 0 ? 0.18 * v : 0);
    }
}

static void ad_ws_one(void *u, hrm_real t, hrm_real out[NCH])
{
    int c;
    (void)u;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(1 + 0.5 * sin(0.3 * (double)t));
}

/* a and b the same answer, stats and jumps; more_medium: a's medium
   evaluations may exceed b's */
static int ad_ws_same(const hrm_result *a, const hrm_result *b, int more_medium)
{
    int c, k, same = a->stats.evals == b->stats.evals &&
                     (more_medium ? a->stats.medium_evals >= b->stats.medium_evals
                                  : a->stats.medium_evals == b->stats.medium_evals) &&
                     a->stats.steps == b->stats.steps && a->stats.rejected == b->stats.rejected &&
                     a->njumps == b->njumps;
    for (c = 0; c < NCH; ++c)
        same &= a->L[c] == b->L[c] && a->Tr[c] == b->Tr[c] && a->error[c] == b->error[c];
    for (k = 0; k < a->njumps && k < HRM_MAX_JUMPS; ++k) same &= a->jumps[k] == b->jumps[k];
    return same;
}

/* The solve of m on [0, 6] with options o on the stack (*plain) and in
   the workspace ws (*in_ws; with nested, Li's shadow ray in the rest of
   it), the workspace painted first so that nothing is read before it is
   written: -1 where o is not this method's option, else whether the two
   answers, stats and jumps are the same. */
static int ad_ws_compare(const hrm_medium *m, hrm_options o, ad_ws_scene *sc, unsigned char *ws, int nested,
                         hrm_status st[2], hrm_result *plain, hrm_result *in_ws)
{
    size_t need;
    st[0] = hrm_solve(m, 0, 6, &o, plain);
    if (st[0] == HRM_ERR_BAD_OPTION) return -1;
    need = hrm_workspace_size(&o);
    o.workspace = ws;
    o.workspace_size = need;
    if (nested) {
        hrm_options io = hrm_default_options(HRM_SIMPSON);
        io.steps = 8;
        io.tau_mode = HRM_TAU_DECOUPLED;
        sc->inner_ws = ws + need;
        sc->inner_size = hrm_workspace_size(&io);
        o.workspace_size = need + sc->inner_size;
    }
    memset(ws, 0xA5, o.workspace_size);
    st[1] = hrm_solve(m, 0, 6, &o, in_ws);
    return st[0] == st[1] && ad_ws_same(plain, in_ws, 0);
}

static void ad_workspace(void)
{
    unsigned char *mem = (unsigned char *)malloc(1 << 22), *ws;
    int mi, cb, hard, w, e, nested, diff = 0, runs = 0;
    size_t need;
    if (!mem) {
        CHECK(0, "workspace test: no memory");
        return;
    }
    ws = mem + (16 - (size_t)((uintptr_t)mem % 16)) % 16;
    CHECK(hrm_workspace_size(NULL) > 0 && hrm_workspace_size(NULL) % 16 == 0,
          "hrm_workspace_size(NULL) = %lu: positive, a multiple of 16", (unsigned long)hrm_workspace_size(NULL));
    for (mi = 0; mi < N_METHODS_ALL; ++mi)
        for (cb = 0; cb < 2; ++cb)
            for (hard = 0; hard < 2; ++hard)
                for (w = 0; w < 2; ++w)
                    for (e = 0; e < 2; ++e)
                        for (nested = 0; nested < 2; ++nested) {
                            ad_ws_scene sc;
                            hrm_medium m;
                            hrm_options o = hrm_default_options(every_method[mi]);
                            hrm_result plain, in_ws;
                            hrm_status st[2];
                            int c, same;
                            memset(&sc, 0, sizeof sc);
                            memset(&m, 0, sizeof m);
                            sc.hard = hard;
                            sc.nested = nested;
                            m.user = &sc;
                            m.Li = ad_ws_li;
                            if (cb) {
                                m.sigma = ad_ws_sig;
                            } else {
                                m.flags = HRM_MEDIUM_HOMOGENEOUS;
                                for (c = 0; c < NCH; ++c) {
                                    m.const_sigma_a[c] = (hrm_real)0.1;
                                    m.const_sigma_s[c] = (hrm_real)0.4;
                                }
                            }
                            if (!is_adaptive(every_method[mi])) o.steps = 16;
                            else o.rtol = (hrm_real)(hard ? (real_is_float() ? 1e-5 : 1e-9) : 1e-3);
                            if (w) {
                                o.warp.kind = HRM_WARP_EQUIANGULAR;
                                o.warp.delta = (hrm_real)2.5;
                                o.warp.D = (hrm_real)(hard ? 0.05 : 1);
                            }
                            o.exponential = e;
                            same = ad_ws_compare(&m, o, &sc, ws, nested, st, &plain, &in_ws);
                            if (same < 0) continue; /* not this method's option */
                            ++runs;
                            if (!same) {
                                ++diff;
                                CHECK(0, "%s, %s, %s, warp %d, exp %d, nested %d: the workspace changed the answer "
                                      "(status %d/%d, L %.17g/%.17g, evals %ld/%ld)",
                                      hrm_method_name(every_method[mi]), cb ? "sigma" : "const",
                                      hard ? "hard" : "smooth", w, e, nested, st[0], st[1], (double)plain.L[0],
                                      (double)in_ws.L[0], plain.stats.evals, in_ws.stats.evals);
                            }
                        }
    CHECK(runs >= 300 && diff == 0, "workspace: %d solves identical to the stack's, %d differ", runs - diff, diff);
    {
        /* Breakpoints: without a workspace a ray of at most 8 pieces
           keeps the pieces' tables in a frame of 8, a longer one in a
           frame for every breakpoint the options may give; a workspace
           holds the latter. 3, 7 (8 pieces), 8 and 12 breakpoints over
           [0, 6], every method, sigma callbacks, the hard Li: the same
           answers, stats and jumps on the stack as in the workspace. */
        static const int counts[4] = {3, 7, 8, 12};
        hrm_real brk[12];
        int runs_b = 0, diff_b = 0, k, q;
        for (mi = 0; mi < N_METHODS_ALL; ++mi)
            for (q = 0; q < 4; ++q) {
                ad_ws_scene sc;
                hrm_medium m;
                hrm_options o = hrm_default_options(every_method[mi]);
                hrm_result plain, in_ws;
                hrm_status st[2];
                int same;
                if (counts[q] > HRM_MAX_BREAKS) continue;
                memset(&sc, 0, sizeof sc);
                memset(&m, 0, sizeof m);
                sc.hard = 1;
                m.user = &sc;
                m.Li = ad_ws_li;
                m.sigma = ad_ws_sig;
                for (k = 0; k < counts[q]; ++k) brk[k] = (hrm_real)(6.0 * (k + 1) / (counts[q] + 1) + 0.01);
                o.breaks = brk;
                o.nbreaks = counts[q];
                if (!is_adaptive(every_method[mi])) o.steps = 32;
                else o.rtol = (hrm_real)1e-4;
                same = ad_ws_compare(&m, o, &sc, ws, 0, st, &plain, &in_ws);
                if (same < 0) continue;
                ++runs_b;
                if (!same) {
                    ++diff_b;
                    CHECK(0, "%s, %d breakpoints: the workspace changed the answer (status %d/%d, L %.17g/%.17g)",
                          hrm_method_name(every_method[mi]), counts[q], st[0], st[1], (double)plain.L[0],
                          (double)in_ws.L[0]);
                }
            }
        /* (every method at the four counts: 56 solves, 48 at least) */
        CHECK(runs_b >= 4 * 12 && diff_b == 0,
              "workspace, 3-12 breakpoints: %d solves identical to the stack's, %d differ", runs_b - diff_b, diff_b);
    }
    {
        /* A ray of more transmittance panels than the stack's table holds
           (32; a workspace's 128): sigma = 0.3 max(0, sin 10 t) over 8,
           25 kinks, far more than 32 panels, which the worst-first rules
           ask for behind the march (2 of the 3 solves march some again). The stack marches the forgotten ones again
           from a checkpoint, to the same values: the same answer, evals
           and steps; only the medium evaluations may differ (more on the
           stack). */
        static const hrm_method ms[3] = {HRM_NESTED_SIMPSON, HRM_GAUSS_KRONROD, HRM_DORMAND_PRINCE};
        int k, re = 0;
        for (k = 0; k < 3; ++k) {
            hrm_medium m;
            hrm_options o = hrm_default_options(ms[k]);
            hrm_result plain, in_ws;
            hrm_status s1, s2;
            memset(&m, 0, sizeof m);
            m.sigma = ad_ws_kink;
            m.Li = ad_ws_one;
            o.rtol = (hrm_real)(real_is_float() ? 1e-3 : 1e-4);
            s1 = hrm_solve(&m, 0, 8, &o, &plain);
            o.workspace = ws;
            o.workspace_size = hrm_workspace_size(&o);
            s2 = hrm_solve(&m, 0, 8, &o, &in_ws);
            CHECK(s1 >= 0 && s1 == s2 && ad_ws_same(&plain, &in_ws, 1), "kinked medium, %s: the stack's table (32 panels) and a workspace's give the same "
                  "answer (status %d/%d, L %.17g/%.17g, evals %ld/%ld, medium evaluations %ld/%ld)",
                  hrm_method_name(ms[k]), s1, s2, (double)plain.L[0], (double)in_ws.L[0], plain.stats.evals,
                  in_ws.stats.evals, plain.stats.medium_evals, in_ws.stats.medium_evals);
            re += plain.stats.medium_evals > in_ws.stats.medium_evals;
        }
        if (verbose()) NOTE("kinked medium: %d of 3 solves marched forgotten panels again on the stack", re);
    }
    {
        /* the workspace is used, and not one byte past its size */
        hrm_medium m;
        hrm_options o = hrm_default_options(HRM_NESTED_SIMPSON);
        hrm_result r;
        ad_ws_scene sc;
        size_t k, used = 0, past = 0;
        memset(&sc, 0, sizeof sc);
        memset(&m, 0, sizeof m);
        sc.hard = 1;
        m.user = &sc;
        m.sigma = ad_ws_sig;
        m.Li = ad_ws_li;
        o.rtol = (hrm_real)(real_is_float() ? 1e-5 : 1e-9);
        need = hrm_workspace_size(&o);
        CHECK(need > 0 && need % 16 == 0, "nested Simpson's workspace: %lu bytes, a multiple of 16",
              (unsigned long)need);
        o.workspace = ws;
        o.workspace_size = need;
        memset(ws, 0xA5, need + 256);
        CHECK(hrm_solve(&m, 0, 6, &o, &r) >= 0, "a workspace of exactly its size, a hard ray: solved");
        for (k = 0; k < need; ++k) used += ws[k] != 0xA5;
        for (k = need; k < need + 256; ++k) past += ws[k] != 0xA5;
        /* (an eighth of it, or of 64 KiB: nested Simpson's size covers
           the shadow-ray estimator's too, which sets it where
           HRM_SHADOW_PANELS is a few hundred) */
        CHECK(used > (need < 65536 ? need : 65536) / 8, "the workspace used: %lu of %lu bytes written",
              (unsigned long)used, (unsigned long)need);
        CHECK(past == 0, "nothing written past the workspace's size (%lu bytes)", (unsigned long)past);
    }
    {
        /* hrm_transmittance without a method (the shadow-ray estimator):
           its panels, context and pieces' tables in a workspace of
           hrm_workspace_size's bytes for those options, the same Tr and
           stats as on the stack, nothing written past the size; a smooth
           ray and a hard one (tr_tol 1e-9: its panels fill), without and
           with breakpoints and a cut-off */
        static const hrm_real brk[2] = {(hrm_real)1.5, (hrm_real)4};
        int hv, b, cut, same = 0, n = 0, past = 0, used = 1;
        size_t wrote[2][2][2];
        for (hv = 0; hv < 2; ++hv)
            for (b = 0; b < 2; ++b)
                for (cut = 0; cut < 2; ++cut) {
                    hrm_medium m;
                    hrm_options o;
                    hrm_real T1[NCH], T2[NCH];
                    hrm_stats s1, s2;
                    hrm_status st1, st2;
                    size_t k, u = 0;
                    int c, eq;
                    memset(&m, 0, sizeof m);
                    memset(&o, 0, sizeof o);
                    m.sigma = hv ? ad_ws_kink : ad_ws_sig;
                    o.tr_tol = (hrm_real)(hv ? 1e-9 : 0);
                    o.breaks = b ? brk : NULL;
                    o.nbreaks = b ? 2 : 0;
                    o.cutoff = (hrm_real)(cut ? 0.2 : 0);
                    st1 = hrm_transmittance(&m, 0, 6, &o, T1, &s1);
                    need = hrm_workspace_size(&o);
                    o.workspace = ws;
                    o.workspace_size = need;
                    memset(ws, 0xA5, need + 256);
                    st2 = hrm_transmittance(&m, 0, 6, &o, T2, &s2);
                    eq = st1 >= 0 && st1 == st2 && s1.evals == s2.evals && s1.medium_evals == s2.medium_evals &&
                         s1.steps == s2.steps && s1.rejected == s2.rejected && s1.t_cut == s2.t_cut;
                    for (c = 0; c < NCH; ++c) eq &= T1[c] == T2[c];
                    CHECK(eq, "estimator, %s, %d breaks, cut-off %d: the workspace's Tr and stats the stack's "
                          "(status %d/%d, Tr %.17g/%.17g, lookups %ld/%ld)", hv ? "hard" : "smooth", 2 * b, cut,
                          st1, st2, (double)T1[0], (double)T2[0], s1.medium_evals, s2.medium_evals);
                    same += eq;
                    ++n;
                    for (k = 0; k < need; ++k) u += ws[k] != 0xA5;
                    for (k = need; k < need + 256; ++k) past += ws[k] != 0xA5;
                    wrote[hv][b][cut] = u;
                }
        /* the panels there: the hard ray fills them (16 at least, the
           least HRM_SHADOW_PANELS), the smooth one takes a few, 5 samples
           each; so the hard ray writes 8 panels' samples more (the
           context and the pieces' tables, all that the workspace held
           before, are the same for both) */
        for (b = 0; b < 2; ++b)
            for (cut = 0; cut < 2; ++cut)
                used &= wrote[1][b][cut] >= wrote[0][b][cut] + 8 * 5 * NCH * sizeof(hrm_real);
        CHECK(same == n && used && past == 0, "estimator: %d of %d answers the stack's, its panels in the workspace "
              "(%d), %d bytes past it", same, n, used, past);
    }
    free(mem);
}

/* ========================================================================
   9. An Li whose slope jumps: nested Simpson's estimate where its samples
   do not resolve the integrand
   A host's shadow ray of a few fixed steps makes Li's slope jump wherever
   one of its nodes crosses a cloud's edge (make render's cloud: 5 times
   steeper twice within 0.01). Here Li = e^-g, g piecewise linear, 0 up to
   the first knot, then of slope s[1], s[2], ... (scenes of a random
   search), sigma_t constant (albedo 0.9) over [0, 1]; L in closed form,
   piece by piece. Scenes 0-2: one kink just past the dyadic point 3/8 of
   the bisection: the interval after it has one sample before the kink
   and four on an exponential they do not resolve, whose S2 - S1 fell 8
   times twice by chance; trusted (hrm__wf_trust), the answer was 6.6-10.5
   rtol off with HRM_OK at rtol 1e-4 without a warp. Scenes 3-4: two and
   three kinks, Li falling 13 times between two neighbouring samples of a
   first interval whose S2 - S1 agreed by chance (7.7 and 6.4 rtol off at
   rtol 1e-3 with 17 samples). Scene 5: three kinks, Li falling 8-fold
   and more between neighbouring nodes of Gauss-Kronrod's first K15
   interval, |K - G| 1.1e-6 (85 rtol off with HRM_OK at rtol 1e-4; K15 and
   K7, global and local: 8 of their 72 solves silent before
   hrm__gap_miss). Asserted over rtol 1e-2..1e-4, the medium as constants,
   as callbacks and (without a fit; in double) as callbacks with tau
   coupled, no warp, the distance warp and an equiangular warp
   towards the first kink: no answer beyond 3 rtol with HRM_OK (the bound
   that calls an answer silent), nested Simpson on every scene and
   Gauss-Kronrod's four forms on scene 5, with and without an exponential
   fit (whose test is on the fitted values, as below), and on scene 14:
   one kink inside an interval, whose halves' |K - G| fell 4 times twice
   by chance and were trusted (K15 27 and K7 3.4 rtol off with HRM_OK at
   rtol 1e-4, with and without a fit, before the halves kept a quarter of
   the parent's miss, hrm__wf_trust). Scenes 15-17, nested Simpson at
   rtol 1e-4, 3e-5 and 1e-5: a mild kink (the slope 22% steeper) just
   before a sample, the halves' S2 - S1 resolved and falling 8.3 times,
   one half holding it all (3.4-19 rtol off with HRM_OK at rtol 1e-5, 6.4
   in float at 3e-5, before such a fall had to reach 1/16:
   hrm__wf_trust). Scenes 6-9: a kink or two, Li
   falling 20 times and more between neighbouring nodes of a pair's step
   (Dormand-Prince at rtol 1e-2: one or two steps over the ray, 11
   evaluations, 17-19 rtol off with HRM_OK before hrm__gap_miss counted
   such a gap): every pair asserted there. Scenes 10-13: the same for the
   pairs with an exponential fit, whose fitted values (Tr's decay divided
   out) fall 8 times between neighbouring nodes (Dormand-Prince 16-21
   rtol off with HRM_OK, Cash-Karp 15, before hrm__gap_miss read them): every
   fitted pair asserted there. Not asserted, printed: the
   other forms' silent answers on the other scenes (Gauss-Kronrod's: a
   kink inside a resolved interval makes |K - G| fall 4 times a split,
   second order, which its trust in the halves, a fall of 4 twice, can
   take for the asymptotic rate). Gauss-Kronrod's eight forms are asserted
   on every scene since its nodes' Legendre coefficients that stop
   falling count as a miss (hrm__gk_tail; before it, 34 of the asserted
   solves without a fit silent, the worst 436 rtol off, on scene 18 and
   elsewhere; with a fit, 4 on scenes 4 and 8, 3.4 and 5.8 rtol); scene
   18, nested Simpson and those eight at rtol 1e-4, 2.34e-5 and
   1e-5: the worst of bench/sweep.c's kinks for them, one K15 over the
   ray accepted with |K - G| 1e-5 of K, 186 rtol off with HRM_OK at rtol
   2.34e-5 (K7 under the equiangular warp: 8 rtol off before a flagged
   interval's |K - G| was kept from the halves' trust). Scene 19, nested
   Simpson at rtol 1e-2, 2.64e-3 and 1e-3: the sweep's one silent answer
   for it, Li falling 1172 times over one of its first panels behind two
   slope jumps, no two samples 8 times apart in the bulk of the light
   (3.9 rtol off with HRM_OK at 2.64e-3 before neighbours 6 times apart
   counted, hrm__gap_miss). Scenes 20-22, every form at the sweep's rtol
   and two beside it (3.1486e-4, 1e-3, 1e-4; 1.2422e-2, 3e-3, 3e-2;
   2.9093e-4, 1e-3, 1e-4): the sweep's worst for Dormand-Prince (a mild
   kink, slope 2.64, at 0.62 of a step in its widest gap between nodes, 0.3
   to 0.8: 22 rtol off, estimate 0.63 rtol), Cash-Karp (6.5 rtol) and
   Verner (8.5), HRM_OK, before the pairs' nodes' Legendre coefficients
   that stop falling counted as a miss (hrm__pair_tail); with it every
   plain pair is asserted on scenes 20-22 too.
   ======================================================================== */
typedef struct ad_kink_scene {
    test_fog fog;      /* sigma_t, and sigma_s 0.9 of it (fog_medium) */
    int nk;
    double k[3], s[4]; /* knots, g's slope on each piece (s[0] = 0) */
} ad_kink_scene;

/* g at t, and L over [0, 1] */
static double ad_kink_g(const ad_kink_scene *p, double t)
{
    double g = 0;
    int i;
    for (i = 0; i < p->nk && t > p->k[i]; ++i) g += (p->s[i + 1] - p->s[i]) * (t - p->k[i]);
    return g;
}

static double ad_kink_L(const ad_kink_scene *p)
{
    double L = 0, a = 0;
    int i;
    for (i = 0; i <= p->nk; ++i) {
        double b = i < p->nk ? p->k[i] : 1, r = p->fog.st + p->s[i];
        /* sigma_s e^-(sigma_t t + g(t)) over [a, b], g linear there */
        L += p->fog.ss * exp(-p->fog.st * a - ad_kink_g(p, a)) * -expm1(-r * (b - a)) / r;
        a = b;
    }
    return L;
}

static void ad_kink_li(void *u, hrm_real t, hrm_real out[NCH])
{
    double v = exp(-ad_kink_g((const ad_kink_scene *)u, (double)t));
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)v;
}

/* One solve of scene p: form v (0 nested Simpson, 1-4 Gauss-Kronrod K15,
   K7, local K15, local K7, 5-9 the pairs: Dormand-Prince, Fehlberg,
   Cash-Karp, Verner, Bogacki-Shampine; 10-14 the same with an exponential
   fit; 15-18 Gauss-Kronrod's four with one), the medium as constants (med
   0), callbacks (1) or callbacks with tau coupled (2: the pairs' stage
   values of tau), warp w (0 none, 1 distance, 2 equiangular towards the
   first kink); its status, and its error over rtol into *e. */
static hrm_status ad_kink_solve(const ad_kink_scene *p, int v, double rtol, int med, int w, double *e)
{
    static const hrm_method pairs[5] = {HRM_DORMAND_PRINCE, HRM_FEHLBERG, HRM_CASH_KARP, HRM_VERNER,
                                        HRM_BOGACKI_SHAMPINE};
    hrm_method method = v >= 5 && v < 15 ? pairs[(v - 5) % 5] : v ? HRM_GAUSS_KRONROD : HRM_NESTED_SIMPSON;
    hrm_medium m = fog_medium((void *)p, ad_kink_li, med);
    hrm_options o = warp_options(method, rtol, w, p->k[0], 0.2);
    hrm_result r;
    hrm_status st;
    if (med == 2) o.tau_mode = HRM_TAU_COUPLED;
    if (v == 2 || v == 4 || v == 16 || v == 18) o.gk_rule = HRM_GK_K7;
    if (v == 3 || v == 4 || v >= 17) o.gk_mode = HRM_GK_LOCAL;
    if (v >= 10) o.exponential = 1;
    st = hrm_solve(&m, 0, 1, &o, &r);
    *e = fabs((double)r.L[0] - ad_kink_L(p)) / (rtol * ad_kink_L(p));
    return st;
}

static void ad_kink(void)
{
    static const ad_kink_scene scenes[23] = {{{1.48, 0.9 * 1.48}, 1, {0.3776}, {0, 53.1}},
                                            {{1.158, 0.9 * 1.158}, 1, {0.3765}, {0, 52.9}},
                                            {{0.798, 0.9 * 0.798}, 1, {0.3777}, {0, 48.3}},
                                            {{3.341, 0.9 * 3.341}, 2, {0.2766, 0.4078}, {0, 10.7, 38.0}},
                                            {{0.925, 0.9 * 0.925}, 3, {0.2617, 0.3218, 0.3522}, {0, 27.4, 76.8, 106.1}},
                                            {{3.111, 0.9 * 3.111}, 3, {0.3331, 0.3985, 0.4144}, {0, 8.8, 29.4, 47.8}},
                                            {{0.615, 0.9 * 0.615}, 1, {0.3277}, {0, 54.4}},
                                            {{1.394, 0.9 * 1.394}, 1, {0.4364}, {0, 56.7}},
                                            {{0.644, 0.9 * 0.644}, 2, {0.3075, 0.3943}, {0, 33.2, 85.9}},
                                            {{1.417, 0.9 * 1.417}, 2, {0.3259, 0.3333}, {0, 17.1, 57.3}},
                                            {{4.458, 0.9 * 4.458}, 2, {0.3012, 0.3829}, {0, 37.3, 87.0}},
                                            {{1.011, 0.9 * 1.011}, 1, {0.3289}, {0, 59.6}},
                                            {{0.849, 0.9 * 0.849}, 2, {0.4350, 0.4740}, {0, 57.0, 103.9}},
                                            {{0.957, 0.9 * 0.957}, 2, {0.3151, 0.4618}, {0, 43.2, 69.6}},
                                            {{0.691, 0.9 * 0.691}, 1, {0.2932}, {0, 59.2}},
                                            {{2.146, 0.9 * 2.146}, 2, {0.2491, 0.2966}, {0, 28.9, 36.9}},
                                            {{4.028, 0.9 * 4.028}, 3, {0.2358, 0.2502, 0.3465}, {0, 14.6, 50.6, 101.6}},
                                            {{2.943, 0.9 * 2.943}, 2, {0.2286, 0.2502}, {0, 5.8, 45.7}},
                                            {{3.088, 0.9 * 3.088}, 1, {0.362589}, {0, 9.2993}},
                                            {{2.3351, 0.9 * 2.3351}, 2, {0.275514, 0.410376}, {0, 12.9182, 49.1404}},
                                            {{2.9701, 0.9 * 2.9701}, 1, {0.408059}, {0, 2.6351}},
                                            {{2.4317, 0.9 * 2.4317}, 1, {0.308758}, {0, 24.5866}},
                                            {{3.5128, 0.9 * 3.5128}, 3, {0.214233, 0.395494, 0.465838},
                                             {0, 40.6399, 45.5543, 81.4119}}};
    static const char *const names[19] = {"nested-simpson", "gk K15", "gk K7", "gk local K15", "gk local K7",
                                          "dormand-prince", "fehlberg", "cash-karp", "verner", "bogacki-shampine",
                                          "dormand-prince fit", "fehlberg fit", "cash-karp fit", "verner fit",
                                          "bogacki-shampine fit", "gk K15 fit", "gk K7 fit", "gk local K15 fit",
                                          "gk local K7 fit"};
    static const double rts[3] = {1e-2, 1e-3, 1e-4}, tight[3] = {1e-4, 3e-5, 1e-5}, gk[3] = {1e-4, 2.34e-5, 1e-5},
                        ns[3] = {1e-2, 2.64e-3, 1e-3},
                        sweep[3][3] = {{3.1486e-4, 1e-3, 1e-4}, {1.2422e-2, 3e-3, 3e-2}, {2.9093e-4, 1e-3, 1e-4}};
    static const char *const meds[3] = {"constants", "callbacks", "coupled tau"};
    int i, v, k, silent = 0, other_silent = 0, other_runs = 0, runs = 0, ok = 0, within = 0, fc_silent = 0;
    double worst = 0;
    for (i = 0; i < 23; ++i)
        for (v = 0; v < (i < 15 || i == 18 || i >= 20 ? 19 : 1); ++v)
            for (k = 0; k < 27; ++k) {
                /* rtol k / 9, medium k / 3 % 3, warp k % 3 */
                int ri = k / 9, med = k / 3 % 3, w = k % 3;
                const double *rt = i < 15 ? rts : i < 18 ? tight : i == 18 ? gk : i == 19 ? ns : sweep[i - 20];
                double e;
                hrm_status st;
                if (med == 2 && v >= 10) continue; /* a fit takes tau decoupled (HRM_ERR_BAD_OPTION) */
                if (i == 18 && v >= 5 && v <= 14) continue; /* Gauss-Kronrod's scene */
                st = ad_kink_solve(&scenes[i], v, rt[ri], med, w, &e);
                CHECK(st >= 0, "kink %d, %s, rtol %g, %s, warp %d: status %d", i, names[v], rt[ri], meds[med],
                      w, st);
                if (v >= 5 && v <= 14 && !(v <= 9 ? (i >= 6 && i <= 9) || i >= 20 : i >= 10 && i <= 13)) {
                    /* (not asserted) */
                    other_runs++;
                    other_silent += st == HRM_OK && e > 3;
                    continue;
                }
                if (med == 2 && sizeof(hrm_real) < sizeof(double)) {
                    /* (float with tau coupled, not asserted: Verner on scene 6
                       at rtol 1e-4, its step across the kink 3.4 rtol off,
                       its embedded estimate 0.1 rtol, Li falling only 1.5
                       times between its nodes: HRM_OK) */
                    fc_silent += st == HRM_OK && e > 3;
                    continue;
                }
                runs++;
                ok += st == HRM_OK;
                within += st != HRM_OK && e <= 1;
                if (st == HRM_OK && e > worst) worst = e;
                if (st == HRM_OK) silent += e > 3;
                CHECK(st != HRM_OK || e <= 3, "kink %d, %s, rtol %g, %s, warp %d: HRM_OK %.2f rtol off", i, names[v],
                      rt[ri], meds[med], w, e);
            }
    NOTE("an Li whose slope jumps: worst HRM_OK answer %.2f rtol, %d beyond 3 (asserted); %d of %d HRM_OK, "
         "%d warnings within rtol", worst, silent, ok, runs, within);
    NOTE("float with tau coupled (not asserted): %d solves silent", fc_silent);
    /* A test of HRM_OK's answers that warnings everywhere would pass: on these
       scenes the solver reaches the tolerance (all 5346 asserted solves
       HRM_OK in double, 4068 of 4140 in float), so 9 in 10 must be HRM_OK. */
    CHECK(ok * 10 >= runs * 9, "an Li whose slope jumps: only %d of %d solves HRM_OK", ok, runs);
    NOTE("the pairs on the other scenes (not asserted): %d of %d solves silent", other_silent,
         other_runs);
}

/* Emission that ends just past a point where the adaptive quadratures
   bisect the ray (B = d + delta, d a dyadic point of [0, 10]): no node of
   the half right of d lies before B until that half is narrower than
   delta over 0.0043 (K15's first node; 0.025 for K7), so unless the
   source sampled at d is compared with the half's nodes, the sliver [d,
   B) is in no node at any depth (local Gauss-Kronrod at rtol 1e-4: 7
   rtol off with HRM_OK). And a thin emitting layer at the camera or at
   the surface, 0.005 to 0.04 of the ray, before Gauss-Kronrod's first
   node or past its last: seen only by the samples at the ray's ends.
   Closed form: L = sigma_a / sigma_t Le (e^-(sigma_t A) - e^-(sigma_t B)),
   emission on [A, B) alone (B capped at the ray's end), no Li. */
typedef struct ad_sliver_scene {
    test_fog fog; /* (first: fog_medium's user) */
    double a, b, le;
} ad_sliver_scene;

static void ad_sliver_le(void *u, hrm_real t, hrm_real out[NCH])
{
    const ad_sliver_scene *p = (const ad_sliver_scene *)u;
    double v = (double)t >= p->a && (double)t < p->b ? p->le : 0;
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)v;
}

static void ad_sliver(void)
{
    /* where: past 5, 2.5 or 7.5 by delta; at the camera, at the surface,
       delta wide */
    static const double ds[3] = {5, 2.5, 7.5}, deltas[3][3] = {{2e-4, 1e-3, 4e-3}, {5e-3, 2e-2, 4e-2}},
                        rts[2] = {1e-3, 1e-4};
    static const char *const names[5] = {"gk local K15", "gk local K7", "gk K15", "gk K7", "nested-simpson"};
    static const char *const where[5] = {"past 5", "past 2.5", "past 7.5", "at the camera", "at the surface"};
    int i, j, v, k, runs = 0, ok = 0, silent = 0;
    double worst = 0;
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 3; ++j)
            for (v = 0; v < 5; ++v)
                for (k = 0; k < 12; ++k) {
                    /* rtol k / 6, medium k / 3 % 2 (constants, a sigma
                       callback), warp k % 3 (none, distance, equiangular
                       towards a light 0.5 from the emission's end) */
                    ad_sliver_scene p;
                    hrm_medium m;
                    hrm_options o = hrm_default_options(v < 4 ? HRM_GAUSS_KRONROD : HRM_NESTED_SIMPSON);
                    hrm_result r;
                    hrm_status st;
                    double rtol = rts[k / 6], delta = deltas[i >= 3][j], L, e;
                    p.fog.st = 0.3;
                    p.fog.ss = 0.2;
                    p.a = i < 3 ? 0.5 : i == 3 ? 0 : 10 - delta;
                    p.b = i < 3 ? ds[i] + delta : i == 3 ? delta : 11;
                    p.le = 2;
                    m = fog_medium(&p, NULL, k / 3 % 2);
                    m.Le = ad_sliver_le;
                    o.rtol = (hrm_real)rtol;
                    if (v < 2) o.gk_mode = HRM_GK_LOCAL;
                    if (v == 1 || v == 3) o.gk_rule = HRM_GK_K7;
                    if (k % 3 == 1) o.warp.kind = HRM_WARP_DISTANCE;
                    if (k % 3 == 2) {
                        o.warp.kind = HRM_WARP_EQUIANGULAR;
                        o.warp.delta = (hrm_real)(p.b < 10 ? p.b : p.a);
                        o.warp.D = (hrm_real)0.5;
                    }
                    st = hrm_solve(&m, 0, 10, &o, &r);
                    L = 0.1 / 0.3 * p.le * (exp(-0.3 * p.a) - exp(-0.3 * (p.b < 10 ? p.b : 10)));
                    e = fabs((double)r.L[0] - L) / (rtol * L);
                    CHECK(st >= 0, "emission %s by %g, %s, rtol %g, medium %d, warp %d: status %d", where[i], delta,
                          names[v], rtol, k / 3 % 2, k % 3, st);
                    CHECK(st != HRM_OK || e <= 3, "emission %s by %g, %s, rtol %g, medium %d, warp %d: HRM_OK "
                          "%.2f rtol off", where[i], delta, names[v], rtol, k / 3 % 2, k % 3, e);
                    runs++;
                    ok += st == HRM_OK;
                    silent += st == HRM_OK && e > 3;
                    if (st == HRM_OK && e > worst) worst = e;
                    if (verbose() && st != HRM_OK)
                        printf("    sliver %s by %g, %s, rtol %g, medium %d, warp %d: status %d, %.2f rtol\n",
                               where[i], delta, names[v], rtol, k / 3 % 2, k % 3, st, e);
                }
    NOTE("emission ending past a bisection point or a thin layer at an end: worst HRM_OK answer %.2f rtol, %d "
         "beyond 3; %d of %d HRM_OK", worst, silent, ok, runs);
    /* (a test that warnings everywhere would pass is none: in double the
       solvers reach these tolerances, 864 of the 900 solves HRM_OK; in
       float local Gauss-Kronrod and nested Simpson bisect towards a
       layer's edge until h_min, 64 epsilons of the ray, whose slice of
       the layer is more than rtol 1e-4, and the 0.005 layer at t = 10
       is placed to 2 ulps of t: HRM_WARN_H_MIN and HRM_WARN_ROUNDOFF,
       627 HRM_OK) */
    if (!real_is_float())
        CHECK(ok * 10 >= runs * 9, "emission past a bisection point or at an end: only %d of %d solves HRM_OK", ok,
              runs);
}

/* A point light behind a dense front at the camera: sigma_t k_c (0.138
   + 16.7 exp(-(t / 0.45)^2)) (k_c = 1 - c / 10, the front 6.7 optical
   depths), albedo 0.63, Li = 0.485 / (0.43^2 + (t - 17)^2) on [0, 19.88]
   (L about 1.1e-3, half of it from the front, where Li is 1.7e-3). The
   light's warp squeezes the front into 2e-4 of u; Bogacki-Shampine's
   steps about the light's foot and the ray's end missed 2-9 times its
   calibrated estimate at rtol 1e-4 (3.8 rtol off with HRM_OK; found by
   a random search of dense fronts under lights' warps). Every pair, no
   warp and the equiangular one, sigma as one callback, as sigma_a and
   sigma_s, and with the exact Tr as the host's callback: HRM_OK within 3
   rtol. Reference: 4000 panels of 8-point Gauss-Legendre with tau in
   closed form (the integrand's narrowest scale 0.43, a panel 0.005). */
typedef struct ad_front {
    int cb; /* counted calls */
} ad_front;

static double ad_front_tau(double t)
{
    return 0.138 * t + 16.7 * 0.45 * 0.886226925452758 * erf(t / 0.45);
}

static double ad_front_k(int c) { return 1 - 0.1 * (double)(c % 8); }

static void ad_front_sigma(void *u, hrm_real t, hrm_real sa[NCH], hrm_real ss[NCH])
{
    double x = (double)t / 0.45, v = 0.138 + 16.7 * exp(-x * x);
    int c;
    ((ad_front *)u)->cb++;
    for (c = 0; c < NCH; ++c) {
        sa[c] = (hrm_real)(0.37 * ad_front_k(c) * v);
        ss[c] = (hrm_real)(0.63 * ad_front_k(c) * v);
    }
}

static void ad_front_sa(void *u, hrm_real t, hrm_real out[NCH])
{
    hrm_real ss[NCH];
    ad_front_sigma(u, t, out, ss);
}

static void ad_front_ss(void *u, hrm_real t, hrm_real out[NCH])
{
    hrm_real sa[NCH];
    ad_front_sigma(u, t, sa, out);
}

static void ad_front_tr(void *u, hrm_real ta, hrm_real tb, hrm_real out[NCH])
{
    double d = ad_front_tau((double)tb) - ad_front_tau((double)ta);
    int c;
    (void)u;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)exp(-ad_front_k(c) * d);
}

static void ad_front_li(void *u, hrm_real t, hrm_real out[NCH])
{
    double d = (double)t - 17;
    int c;
    (void)u;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(0.485 / (0.43 * 0.43 + d * d));
}

typedef struct ad_front_ref {
    int c;
} ad_front_ref;

static double ad_front_integrand(const void *ctx, double t)
{
    int c = ((const ad_front_ref *)ctx)->c;
    double x = t / 0.45, d = t - 17, k = ad_front_k(c);
    return 0.63 * k * (0.138 + 16.7 * exp(-x * x)) * 0.485 / (0.43 * 0.43 + d * d) * exp(-k * ad_front_tau(t));
}

static void ad_pair_front(void)
{
    static const double rts[2] = {1e-3, 1e-4};
    double ref[NCH], worst = 0;
    int mi, form, w, k, c, runs = 0, ok = 0;
    for (c = 0; c < NCH; ++c) {
        ad_front_ref x;
        x.c = c;
        ref[c] = gl_integrate(ad_front_integrand, &x, 0, 19.88, 4000, 8, 0, 0);
    }
    for (mi = 0; mi < N_METHODS_ALL; ++mi) {
        if (!is_pair(every_method[mi])) continue;
        for (form = 0; form < 3; ++form)
            for (w = 0; w < 2; ++w)
                for (k = 0; k < 2; ++k) {
                    ad_front u;
                    hrm_medium m;
                    hrm_options o = hrm_default_options(every_method[mi]);
                    hrm_result r;
                    hrm_status st;
                    memset(&m, 0, sizeof m);
                    u.cb = 0;
                    m.user = &u;
                    m.sigma = form == 1 ? NULL : ad_front_sigma;
                    m.sigma_a = form == 1 ? ad_front_sa : NULL;
                    m.sigma_s = form == 1 ? ad_front_ss : NULL;
                    m.transmittance = form == 2 ? ad_front_tr : NULL;
                    m.Li = ad_front_li;
                    o.rtol = (hrm_real)rts[k];
                    if (w) {
                        o.warp.kind = HRM_WARP_EQUIANGULAR;
                        o.warp.delta = 17;
                        o.warp.D = (hrm_real)0.43;
                    }
                    st = hrm_solve(&m, 0, (hrm_real)19.88, &o, &r);
                    CHECK(st >= 0, "front and light, %s, form %d, warp %d, rtol %g: status %d",
                          hrm_method_name(every_method[mi]), form, w, rts[k], st);
                    runs++;
                    ok += st == HRM_OK;
                    for (c = 0; c < NCH; ++c) {
                        double e = fabs((double)r.L[c] - ref[c]) / (rts[k] * ref[c]);
                        CHECK(st != HRM_OK || e <= 3, "front and light, %s, form %d, warp %d, rtol %g, channel %d: "
                              "HRM_OK %.2f rtol off", hrm_method_name(every_method[mi]), form, w, rts[k], c, e);
                        if (st == HRM_OK && e > worst) worst = e;
                        if (verbose() && e > 1)
                            printf("    front and light, %s, form %d, warp %d, rtol %g, channel %d: status %d, %.2f "
                                   "rtol, %ld evaluations\n", hrm_method_name(every_method[mi]), form, w, rts[k], c,
                                   st, e, r.stats.evals);
                    }
                }
    }
    NOTE("a light behind a dense front, the pairs: worst HRM_OK answer %.2f rtol; %d of %d HRM_OK", worst, ok, runs);
    /* (not passed by warning: every solve HRM_OK in double; in float the
       pairs under the warp at rtol 1e-4 end 1-7 rtol off and say so,
       HRM_WARN_TOLERANCE, 18 of the 60) */
    CHECK(ok >= (real_is_float() ? runs * 2 / 3 : runs), "a light behind a dense front: %d of %d solves HRM_OK", ok,
          runs);
}

void adaptive_tests(void)
{
    RUN_GROUP(ad_accuracy);
    RUN_GROUP(ad_eval_counts);
    RUN_GROUP(ad_limits);
    RUN_GROUP(ad_shadow);
    RUN_GROUP(ad_domain);
    RUN_GROUP(ad_transmittance);
    RUN_GROUP(ad_verified);
    RUN_GROUP(ad_anytime);
    RUN_GROUP(ad_workspace);
    RUN_GROUP(ad_kink);
    RUN_GROUP(ad_sliver);
    RUN_GROUP(ad_pair_front);
}

