/* bench/reference.h - the benchmark's ground truth, independent of hrm.

   Composite Gauss-Legendre quadrature in long double. The nodes are found by
   Newton's method on the Legendre polynomial (three-term recurrence), so no
   table is copied from anywhere. Each scene splits its ray at the points
   where its integrand is not smooth (a shadow edge) or nearly so (the peak
   under a point light); on every piece the integrand is analytic, and an
   n-point rule on panels of width h converges like rho^(-2n), rho the
   Bernstein ellipse of the nearest complex singularity. The same integral at
   two panel widths (h and h/2) gives the stated accuracy estimate. */
#ifndef BENCH_REFERENCE_H
#define BENCH_REFERENCE_H

#include "hrm.h" /* HRM_CHANNELS */

#define REF_GL_POINTS 20      /* nodes per panel */
#define REF_PANEL 0.25L       /* coarse panel width, the fine one half of it;
                                 a scene may ask for narrower panels */
#define REF_MAX_POINTS 16     /* ray ends plus interior split points */

/* The integrand at s of a ray that starts at t0 (t0 for Tr(t0, s)). */
typedef void (*ref_integrand_fn)(const void *params, long double t0, long double s,
                                 long double out[HRM_CHANNELS]);

typedef struct ref_rule {
    long double x[REF_GL_POINTS]; /* nodes on [-1, 1] */
    long double w[REF_GL_POINTS]; /* weights, summing to 2 */
} ref_rule;

void ref_rule_init(ref_rule *rule);

/* Integral of f over [pts[0], pts[n-1]], pts sorted: each piece between
   consecutive points cut into equal panels no wider than h. */
void ref_integrate(const ref_rule *rule, ref_integrand_fn f, const void *params,
                   const long double *pts, int n, long double h, long double out[HRM_CHANNELS]);

/* max over channels of |a - b| / max(|a|, |b|) (0 where both vanish). */
long double ref_rel_diff(const long double *a, const long double *b);

#endif
