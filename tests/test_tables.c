/* test_tables.c - the coefficient tables of hrm.h's adaptive methods: the
   Runge-Kutta tableaus (consistency and order conditions) and the
   Gauss-Kronrod G7/K15 nodes and weights (exactness, sharp degrees).
   table_tests() runs both groups.

   The tables are private to the implementation (static), so this is the
   file of the test program that compiles it: the one that defines
   HRM_IMPLEMENTATION (with HRM_STATIC every file compiles its own copy). */
#define HRM_IMPLEMENTATION
#include "common.h"

#include <float.h>
#include <math.h>

/* ========================================================================
   1. Runge-Kutta tableaus: consistency and order conditions
   ======================================================================== */

/* Bound on a sum of the library's coefficients against its rational value:
   1e-14 in double (each coefficient is a correctly rounded quotient and the
   magnitudes summed stay below 25: 25 * 2.2e-16 = 6e-15); under float each
   is rounded to 6e-8 relative, so 4 FLT_EPSILON times the magnitudes. */
static double ad_coef_tol(double magnitude)
{
    return real_is_float() ? 4 * (double)FLT_EPSILON * (magnitude + 1) : 1e-14;
}

/* The same for the products of the order conditions: 4 eps times the sum
   of the magnitudes of the products (each product and each addition
   rounds once). */
static double ad_prod_tol(double magnitude)
{
    return 4 * real_eps() * (magnitude + 1);
}

static void ad_tableaus(void)
{
    /* sizes from the named arrays, and the order of b and of bh
       (b: the propagated solution). */
    static const struct { const char *name; int s, order_b, order_bh, cost; } info[5] = {
        { "bogacki-shampine", 4, 3, 2, 3 },
        { "dormand-prince", 7, 5, 4, 5 },
        { "fehlberg", 6, 4, 5, 5 },
        { "cash-karp", 6, 4, 5, 5 },
        { "verner", 8, 6, 5, 6 },
    };
    const hrm_real *named_a[5] = { hrm__bs_a, hrm__dp_a, hrm__rkf_a, hrm__ck_a, hrm__vr_a };
    const hrm_real *named_b[5] = { hrm__bs_b, hrm__dp_b, hrm__rkf_b, hrm__ck_b, hrm__vr_b };
    const hrm_real *named_bh[5] = { hrm__bs_bh, hrm__dp_bh, hrm__rkf_bh, hrm__ck_bh, hrm__vr_bh };
    const hrm_real *named_c[5] = { hrm__bs_c, hrm__dp_c, hrm__rkf_c, hrm__ck_c, hrm__vr_c };
    const size_t len_a[5] = { sizeof hrm__bs_a, sizeof hrm__dp_a, sizeof hrm__rkf_a,
                              sizeof hrm__ck_a, sizeof hrm__vr_a };
    const size_t len_c[5] = { sizeof hrm__bs_c, sizeof hrm__dp_c, sizeof hrm__rkf_c,
                              sizeof hrm__ck_c, sizeof hrm__vr_c };
    int p;
    for (p = 0; p < 5; ++p) {
        const hrm__tableau *tb = hrm__methods[HRM_BOGACKI_SHAMPINE + p].tb;
        int s = tb->s, i, j, l, w, q;
        double sum_b = 0, sum_bh = 0, mag_b = 0, mag_bh = 0, worst_row = 0, worst_mag = 0;
        /* the method table's row of HRM_BOGACKI_SHAMPINE + p is that pair */
        CHECK(hrm__methods[HRM_BOGACKI_SHAMPINE + p].family == HRM__PAIR,
              "%s: the method table's family is the embedded pairs", info[p].name);
        CHECK(tb->a == named_a[p] && tb->b == named_b[p] && tb->bh == named_bh[p] &&
              tb->c == named_c[p], "%s: the method table points at its own tables", info[p].name);
        CHECK_INT(s, info[p].s, "%s: stages", info[p].name);
        CHECK_INT(len_a[p], sizeof(hrm_real) * (size_t)(s * s), "%s: a is s x s", info[p].name);
        CHECK_INT(len_c[p], sizeof(hrm_real) * (size_t)s, "%s: c has s nodes", info[p].name);
        CHECK_INT(tb->order, info[p].order_b, "%s: order of the propagated solution", info[p].name);
        CHECK_INT(tb->k, info[p].order_b < info[p].order_bh ? info[p].order_b : info[p].order_bh,
                  "%s: error exponent k = the lower order", info[p].name);
        CHECK_INT(hrm__stage_cost(tb), info[p].cost,
                  "%s: new evaluations per step (distinct nonzero nodes)", info[p].name);
        CHECK((double)tb->c[0] == 0.0, "%s: c[0] = 0 (first stage at the step's start)", info[p].name);
        for (i = 0; i < s; ++i) {
            double row = 0, mag = 0;
            for (j = 0; j < s; ++j) {
                double aij = (double)tb->a[i * s + j];
                if (j >= i && aij != 0.0) worst_row = 1e300; /* explicit: strictly lower */
                row += aij;
                mag += fabs(aij);
            }
            row = fabs(row - (double)tb->c[i]);
            if (row > worst_row) worst_row = row;
            if (mag > worst_mag) worst_mag = mag;
            sum_b += (double)tb->b[i];
            sum_bh += (double)tb->bh[i];
            mag_b += fabs((double)tb->b[i]);
            mag_bh += fabs((double)tb->bh[i]);
        }
        CHECK_NEAR(worst_row, 0, ad_coef_tol(worst_mag),
                   "%s: a strictly lower, each row of a sums to c", info[p].name);
        CHECK_NEAR(sum_b, 1, ad_coef_tol(mag_b), "%s: sum of b = 1", info[p].name);
        CHECK_NEAR(sum_bh, 1, ad_coef_tol(mag_bh), "%s: sum of bh = 1", info[p].name);

        /* Order conditions of both weight sets, beyond the brief's sums:
           quadrature (bushy trees) sum w c^(q-1) = 1/q up to the order,
           and the other trees of orders 3 and 4. A wrong digit in any
           coefficient breaks one of them. */
        for (w = 0; w < 2; ++w) {
            const hrm_real *wt = w ? tb->bh : tb->b;
            int order = w ? info[p].order_bh : info[p].order_b;
            double worst = 0, mag = 0, m4 = 0;
            for (q = 1; q <= order; ++q) {
                double v = 0, m = 0;
                for (i = 0; i < s; ++i) {
                    double term = (double)wt[i] * pow((double)tb->c[i], q - 1);
                    v += term;
                    m += fabs(term);
                }
                if (fabs(v - 1.0 / q) > worst) worst = fabs(v - 1.0 / q);
                if (m > mag) mag = m;
            }
            if (order >= 3) {
                double t3 = 0, t4a = 0, t4b = 0, t4c = 0;
                for (i = 0; i < s; ++i)
                    for (j = 0; j < s; ++j) {
                        double wa = (double)wt[i] * (double)tb->a[i * s + j];
                        double cj = (double)tb->c[j];
                        t3 += wa * cj;                          /* 1/6 */
                        t4a += wa * (double)tb->c[i] * cj;      /* 1/8 */
                        t4b += wa * cj * cj;                    /* 1/12 */
                        m4 += fabs(wa);
                        for (l = 0; l < s; ++l) {               /* 1/24 */
                            t4c += wa * (double)tb->a[j * s + l] * (double)tb->c[l];
                            m4 += fabs(wa * (double)tb->a[j * s + l]);
                        }
                    }
                if (fabs(t3 - 1.0 / 6) > worst) worst = fabs(t3 - 1.0 / 6);
                if (order >= 4) {
                    if (fabs(t4a - 1.0 / 8) > worst) worst = fabs(t4a - 1.0 / 8);
                    if (fabs(t4b - 1.0 / 12) > worst) worst = fabs(t4b - 1.0 / 12);
                    if (fabs(t4c - 1.0 / 24) > worst) worst = fabs(t4c - 1.0 / 24);
                }
                if (m4 > mag) mag = m4;
            }
            CHECK_NEAR(worst, 0, ad_prod_tol(mag),
                       "%s: order conditions of %s (order %d) up to order %d", info[p].name,
                       w ? "bh" : "b", order, order < 4 ? order : 4);
        }
        /* the embedded solution differs: an error estimate that can vanish
           identically would accept every step */
        {
            double diff = 0;
            for (i = 0; i < s; ++i) diff += fabs((double)tb->b[i] - (double)tb->bh[i]);
            CHECK(diff > 1e-3, "%s: b and bh differ (sum |b - bh| = %g)", info[p].name, diff);
        }
    }
}

/* ========================================================================
   2. Gauss-Kronrod tables
   ======================================================================== */

/* P_k(x) by the three-term recurrence. */
static double ad_legendre(int k, double x)
{
    double p0 = 1, p1 = x;
    int q;
    if (k == 0) return 1;
    for (q = 1; q < k; ++q) {
        double p2 = ((2 * q + 1) * x * p1 - q * p0) / (q + 1);
        p0 = p1;
        p1 = p2;
    }
    return p1;
}

/* Four rows of Legendre coefficients at the n nodes x (rows[r * n + j]),
   row r that of degree deg[r]: applied to P_k at the nodes, it gives 1
   for k = deg[r] and 0 for every other k < n, within bound; the worst
   miss into *worst. */
static void ad_legendre_rows(const hrm_real *rows, int n, const double *x, const int deg[4], double bound,
                             const char *name, double *worst)
{
    int r, k, j;
    for (r = 0; r < 4; ++r)
        for (k = 0; k < n; ++k) {
            double v = 0;
            for (j = 0; j < n; ++j) v += (double)rows[r * n + j] * ad_legendre(k, x[j]);
            v = fabs(v - (k == deg[r] ? 1 : 0));
            CHECK(v <= bound, "%s Legendre row %d on P_%d: off by %.3g", name, r, k, v);
            if (v > *worst) *worst = v;
        }
}

/* integral of x^k over [-1, x] */
static double ad_mono_int(int k, double x)
{
    return (pow(x, k + 1) - pow(-1.0, k + 1)) / (k + 1);
}

static void ad_gk_tables(void)
{
    double x[15], wk[15], wg[15], worst_k = 0, worst_g = 0, worst_tau = 0;
    double sharp_k, sharp_g, tol_rule, tol_tau;
    int j, k, l, ascending = 1, symmetric = 1, gauss_nodes = 0;
    for (j = 0; j < 15; ++j) {
        x[j] = (double)hrm__gk_x[j];
        wk[j] = (double)hrm__gk_wk[j];
        wg[j] = (double)hrm__gk_wg[j];
        gauss_nodes += wg[j] != 0.0;
    }
    for (j = 0; j < 15; ++j) {
        if (j && !(x[j] > x[j - 1])) ascending = 0;
        if (x[j] != -x[14 - j] || wk[j] != wk[14 - j] || wg[j] != wg[14 - j]) symmetric = 0;
    }
    CHECK(ascending && x[0] > -1 && x[14] < 1, "K15 nodes ascending inside (-1, 1)");
    CHECK(symmetric, "K15 nodes and weights symmetric about 0");
    CHECK_INT(gauss_nodes, 7, "G7 weights nonzero on exactly 7 nodes");
    CHECK(x[7] == 0.0 && wg[7] != 0.0, "the centre is a Gauss node");
    /* Exactness: K15 has degree 3*7+1 = 22, G7 degree 2*7-1 = 13. Bound:
       double 1e-14 (two ulps of a sum of 15 positive terms <= 2); float:
       nodes and weights rounded to 6e-8, x^k magnifies a node's error k
       times: 4 (k+1) FLT_EPSILON * 2. */
    for (k = 0; k <= 22; ++k) {
        double sk = 0, sg = 0, want = (k % 2) ? 0.0 : 2.0 / (k + 1);
        for (j = 0; j < 15; ++j) {
            sk += wk[j] * pow(x[j], k);
            sg += wg[j] * pow(x[j], k);
        }
        if (fabs(sk - want) > worst_k) worst_k = fabs(sk - want);
        if (k <= 13 && fabs(sg - want) > worst_g) worst_g = fabs(sg - want);
    }
    tol_rule = real_is_float() ? 8 * 23 * (double)FLT_EPSILON : 1e-14;
    CHECK_NEAR(worst_k, 0, tol_rule, "K15 integrates x^k exactly on [-1, 1] for k <= 22");
    CHECK_NEAR(worst_g, 0, tol_rule, "G7 integrates x^k exactly on [-1, 1] for k <= 13");
    /* ... and no further (the degrees are sharp): the first even power past
       each degree has an error of order 1e-4 (K15, x^24) and 1e-2 (G7,
       x^14), far above either precision's bound. */
    sharp_k = sharp_g = 0;
    for (j = 0; j < 15; ++j) {
        sharp_k += wk[j] * pow(x[j], 24);
        sharp_g += wg[j] * pow(x[j], 14);
    }
    sharp_k = fabs(sharp_k - 2.0 / 25);
    sharp_g = fabs(sharp_g - 2.0 / 15);
    if (!real_is_float()) { /* float's bound is above K15's x^24 error */
        CHECK(sharp_k > 100 * tol_rule, "K15 is not exact for x^24 (error %.3g)", sharp_k);
        CHECK(sharp_g > 100 * tol_rule, "G7 is not exact for x^14 (error %.3g)", sharp_g);
    }
    NOTE("exactness: worst K15 error %.3g (k <= 22), G7 %.3g (k <= 13)", worst_k, worst_g);
    NOTE("K15 error on x^24: %.3g; G7 error on x^14: %.3g", sharp_k, sharp_g);

    /* hrm__gk_tau row j integrates the degree-14 interpolant from -1 to
       node j: exact for x^k, k <= 14. Bound: double 1e-13 (coefficients
       given to 18 digits, 15 terms of magnitude <= 0.25, x^14 at most 1);
       float: 15 terms each rounded to 6e-8, node errors magnified 14 times:
       4 * 15 * 15 FLT_EPSILON. */
    for (j = 0; j < 15; ++j)
        for (k = 0; k <= 14; ++k) {
            double v = 0;
            for (l = 0; l < 15; ++l) v += (double)hrm__gk_tau[j * 15 + l] * pow(x[l], k);
            v = fabs(v - ad_mono_int(k, x[j]));
            if (v > worst_tau) worst_tau = v;
        }
    tol_tau = real_is_float() ? 4 * 15 * 15 * (double)FLT_EPSILON : 1e-13;
    CHECK_NEAR(worst_tau, 0, tol_tau,
               "hrm__gk_tau row j integrates x^k from -1 to node j exactly, k <= 14");
    /* the last row is the whole K15 rule's integral only up to x[14] < 1:
       it is not the Kronrod weights (no accidental copy) */
    {
        double d = 0;
        for (l = 0; l < 15; ++l) d += fabs((double)hrm__gk_tau[14 * 15 + l] - wk[l]);
        CHECK(d > 1e-3, "the last tau row differs from the K15 weights (sum |diff| = %g)", d);
    }
    /* The Legendre rows (hrm__gk_leg, hrm__k7_leg: the kink test,
       hrm__gk_tail): applied to P_m at a pair's nodes, row r gives 1 for
       its degree and 0 for every other m < n (the interpolant of P_m is
       P_m). Bound: double 1e-13 (entries to 21 digits, n terms of
       magnitude <= 1); float: n terms each rounded to FLT_EPSILON, node
       errors magnified n times: 4 n n FLT_EPSILON. */
    {
        static const int deg15[4] = {14, 13, 10, 9}, deg7[4] = {6, 5, 4, 3};
        const hrm__gk_pair *pr[2] = {&hrm__k15, &hrm__k7};
        double worst_leg = 0, xn[15];
        int p;
        for (p = 0; p < 2; ++p) {
            int n = pr[p]->n;
            for (l = 0; l < n; ++l) xn[l] = (double)pr[p]->x[l];
            ad_legendre_rows(pr[p]->leg, n, xn, p ? deg7 : deg15,
                             real_is_float() ? 4.0 * n * n * (double)FLT_EPSILON : 1e-13, p ? "K7" : "K15",
                             &worst_leg);
        }
        NOTE("Legendre rows of K15 and K7: worst %.3g", worst_leg);
    }
}

/* The pairs' Legendre rows (hrm__nodes_info.leg, set in the caller's array by
   hrm__nodes_legendre from each tableau's distinct nodes through
   hrm__legendre_inverse, the exponential fits' inverse: the kink test,
   hrm__pair_tail): rows m - 1 .. m - 4, checked as the Gauss-Kronrod
   rows above on P_k at the nodes 2 c - 1. Bound: m terms of magnitude at
   most 4 (the largest entry, 2.65) each to a few epsilons: double 1e-13;
   float 64 m FLT_EPSILON 4. Bogacki-Shampine (4 nodes) has none. */
static void ad_pair_legendre(void)
{
    static const int want_m[5] = {4, 6, 6, 6, 7}; /* distinct nodes */
    double worst = 0, biggest = 0;
    int p;
    for (p = 0; p < 5; ++p) {
        const hrm__tableau *tb = hrm__methods[HRM_BOGACKI_SHAMPINE + p].tb;
        const char *name = hrm_method_name((hrm_method)(HRM_BOGACKI_SHAMPINE + p));
        hrm__nodes_info ni;
        hrm_real leg[4 * HRM__MAX_STAGES];
        double x[HRM__MAX_STAGES];
        int deg[4], j, m;
        hrm__nodes_init(tb, &ni);
        hrm__nodes_legendre(&ni, leg);
        m = ni.m;
        CHECK_INT(m, want_m[p], "%s: distinct nodes", name);
        if (m < 6) continue;
        for (j = 0; j < 4; ++j) deg[j] = m - 1 - j;
        for (j = 0; j < m; ++j) x[j] = 2 * (double)ni.c[j] - 1;
        for (j = 0; j < 4 * m; ++j)
            if (fabs((double)ni.leg[j]) > biggest) biggest = fabs((double)ni.leg[j]);
        ad_legendre_rows(ni.leg, m, x, deg, real_is_float() ? 64.0 * m * 4 * (double)FLT_EPSILON : 1e-13, name,
                         &worst);
    }
    CHECK(biggest <= 4, "the pairs' Legendre rows: largest entry %.3g (the bound above assumes 4)", biggest);
    NOTE("the pairs' Legendre rows: worst %.3g, largest entry %.3g", worst, biggest);
}

/* ======================================================================== */

/* The pairs' step limit in the RTE form (hrm__tableau.zmax): the
   stability function R(-z) = 1 - z b^T (I + z A)^-1 1 of each explicit
   tableau, by forward substitution in double from its own coefficients,
   lies in [0, 1] at every z in [0, zmax] on a grid of 1/1024 (Tr and L
   decay monotonically over a step, as the exact solution does), and
   leaves it by the next 1/64 past zmax (the limit is the largest such
   multiple of 1/64, not a smaller one). */
static double ad_stability(const hrm__tableau *tb, double z)
{
    double g[16], R = 1;
    int i, j;
    for (i = 0; i < tb->s; ++i) {
        double acc = 0;
        for (j = 0; j < i; ++j) acc += (double)tb->a[i * tb->s + j] * g[j];
        g[i] = 1 - z * acc;
        R -= z * (double)tb->b[i] * g[i];
    }
    return R;
}

static void ad_step_limit(void)
{
    int p;
    for (p = 0; p < 5; ++p) {
        const hrm__tableau *tb = hrm__methods[HRM_BOGACKI_SHAMPINE + p].tb;
        const char *name = hrm_method_name((hrm_method)(HRM_BOGACKI_SHAMPINE + p));
        double zmax = (double)tb->zmax, z, worst = 0, past = 0;
        int k, inside = 1, leaves = 0;
        CHECK(zmax > 1 && zmax * 64 == floor(zmax * 64), "%s: zmax %.6g a multiple of 1/64 above 1", name, zmax);
        for (k = 0; k <= (int)(zmax * 1024); ++k) {
            double R = ad_stability(tb, k / 1024.0);
            if (!(R >= 0 && R <= 1)) {
                inside = 0;
                worst = R;
            }
        }
        for (z = zmax + 1 / 1024.0; z <= zmax + 1 / 64.0 + 1e-12; z += 1 / 1024.0) {
            double R = ad_stability(tb, z);
            if (!(R >= 0 && R <= 1)) {
                leaves = 1;
                past = R;
                break;
            }
        }
        CHECK(inside, "%s: R(-z) in [0, 1] on [0, %.6g] (%.6g)", name, zmax, worst);
        CHECK(leaves, "%s: R(-z) leaves [0, 1] within 1/64 past %.6g (%.6g)", name, zmax, past);
    }
}

void table_tests(void)
{
    RUN_GROUP(ad_tableaus);
    RUN_GROUP(ad_gk_tables);
    RUN_GROUP(ad_pair_legendre);
    RUN_GROUP(ad_step_limit);
}
