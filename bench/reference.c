/* bench/reference.c - composite Gauss-Legendre in long double (reference.h). */
#include "reference.h"

#include <float.h>
#include <math.h>

/* P_n(x) and P_n'(x) by the recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}. */
static void ref_legendre(int n, long double x, long double *p, long double *dp)
{
    long double p0 = 1, p1 = x;
    int k;
    for (k = 1; k < n; ++k) {
        long double p2 = ((2 * k + 1) * x * p1 - k * p0) / (k + 1);
        p0 = p1;
        p1 = p2;
    }
    *p = p1;
    *dp = n * (x * p1 - p0) / (x * x - 1);
}

void ref_rule_init(ref_rule *rule)
{
    const long double pi = 3.141592653589793238462643383279502884L;
    int i, it;
    for (i = 0; i < REF_GL_POINTS; ++i) {
        /* The usual starting guess, close enough for quadratic convergence. */
        long double x = cosl(pi * (i + 0.75L) / (REF_GL_POINTS + 0.5L));
        long double p, dp;
        for (it = 0; it < 100; ++it) {
            long double dx;
            ref_legendre(REF_GL_POINTS, x, &p, &dp);
            dx = p / dp;
            x -= dx;
            if (fabsl(dx) <= 2 * LDBL_EPSILON) break;
        }
        ref_legendre(REF_GL_POINTS, x, &p, &dp);
        rule->x[i] = x;
        rule->w[i] = 2 / ((1 - x * x) * dp * dp);
    }
}

void ref_integrate(const ref_rule *rule, ref_integrand_fn f, const void *params,
                   const long double *pts, int n, long double h, long double out[HRM_CHANNELS])
{
    long double v[HRM_CHANNELS];
    int j, k, i, c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = 0;
    for (j = 0; j + 1 < n; ++j) {
        long double a = pts[j], b = pts[j + 1];
        int panels = (int)ceill((b - a) / h);
        if (panels < 1) panels = 1;
        for (k = 0; k < panels; ++k) {
            long double pa = a + (b - a) * k / panels;
            long double pb = k + 1 == panels ? b : a + (b - a) * (k + 1) / panels;
            long double mid = (pa + pb) / 2, half = (pb - pa) / 2;
            for (i = 0; i < REF_GL_POINTS; ++i) {
                f(params, pts[0], mid + half * rule->x[i], v);
                for (c = 0; c < HRM_CHANNELS; ++c) out[c] += half * rule->w[i] * v[c];
            }
        }
    }
}

long double ref_rel_diff(const long double *a, const long double *b)
{
    long double worst = 0;
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) {
        long double den = fabsl(a[c]) > fabsl(b[c]) ? fabsl(a[c]) : fabsl(b[c]);
        long double e = den > 0 ? fabsl(a[c] - b[c]) / den : 0;
        if (!(e <= worst)) worst = e; /* NaN propagates */
    }
    return worst;
}
