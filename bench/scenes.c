/* bench/scenes.c - the benchmark's scenes (scenes.h), each a set of
   callbacks for hrm and a long double integrand for its reference, and the
   generic wrappers: counting, a homogeneous medium given as sigma
   callbacks, and the ~500 ns Li of the overhead table. */
#include "scenes.h"

#include <math.h>
#include <string.h>

#define LD(x) ((long double)(x)) /* parameters are doubles: what hrm sees */

/* ------------------------------------------------------------------------ */
/* Generic wrappers                                                         */
/* ------------------------------------------------------------------------ */

void bench_count(void *user, unsigned which, hrm_real t)
{
    bench_counts *n = &((bench_calls *)user)->n;
    switch (which) {
    case BENCH_CB_SIGMA_A: n->sigma_a++; break;
    case BENCH_CB_SIGMA_S: n->sigma_s++; break;
    case BENCH_CB_TR: n->tr++; break;
    case BENCH_CB_LE: n->le++; break;
    default: n->li++; break;
    }
    if (which & (BENCH_CB_LE | BENCH_CB_LI)) { /* a source callback closes the run */
        n->run = 0;
        return;
    }
    if (!n->run || (n->run & which) || n->run_t != (double)t) {
        n->medium++;
        n->run = 0;
        n->run_t = (double)t;
    }
    n->run |= which;
}

static void bench_const_sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const bench_calls *calls = (const bench_calls *)user;
    int c;
    bench_count(user, BENCH_CB_SIGMA_A, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)calls->const_sigma_a[c];
}

static void bench_const_sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const bench_calls *calls = (const bench_calls *)user;
    int c;
    bench_count(user, BENCH_CB_SIGMA_S, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)calls->const_sigma_s[c];
}

int bench_medium_build(const bench_scene *sc, bench_medium_id how, hrm_medium *m,
                       bench_calls *calls)
{
    int c;
    memset(m, 0, sizeof *m);
    memset(calls, 0, sizeof *calls);
    sc->build(sc->params, m);
    calls->params = sc->params;
    m->user = calls;
    if (!(m->flags & HRM_MEDIUM_HOMOGENEOUS)) return how == BENCH_MEDIUM_SIGMA;
    if (how == BENCH_MEDIUM_CONST) return 1;
    /* The same constants, through callbacks: hrm integrates tau itself. */
    for (c = 0; c < 3; ++c) {
        calls->const_sigma_a[c] = (double)m->const_sigma_a[c];
        calls->const_sigma_s[c] = (double)m->const_sigma_s[c];
        m->const_sigma_a[c] = m->const_sigma_s[c] = 0;
    }
    m->flags &= ~HRM_MEDIUM_HOMOGENEOUS;
    m->sigma_a = bench_const_sigma_a;
    m->sigma_s = bench_const_sigma_s;
    return 1;
}

double bench_busy(long iters, double x)
{
    long i;
    for (i = 0; i < iters; ++i) x = x * 0.96875 + 0.015625; /* each step needs the last */
    return x;
}

static void bench_busy_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const bench_calls *calls = (const bench_calls *)user;
    double x;
    calls->inner_li(user, t, out); /* counts the call */
    x = bench_busy(calls->busy_iters, 0.25 + (double)t);
    /* x lies in (0, 1 + t): 1e-300 x is far below an ulp of any Li here, but
       the compiler cannot know, so the work stays. */
    out[0] += (hrm_real)(x * 1e-300);
}

void bench_medium_busy_li(hrm_medium *m, bench_calls *calls, long iters)
{
    if (!m->Li) return;
    calls->inner_li = m->Li;
    calls->busy_iters = iters;
    m->Li = bench_busy_li;
}

static void bench_print_vec(FILE *out, const char *name, const double v[3])
{
    fprintf(out, "%s = (%g, %g, %g)", name, v[0], v[1], v[2]);
}

/* ------------------------------------------------------------------------ */
/* directional: homogeneous medium under a directional light. The light's   */
/* path through the medium to x(s) is d0 + k s long, so                     */
/* Li(s) = E p exp(-sigma_t (d0 + k s)), and L has a closed form.           */
/* ------------------------------------------------------------------------ */

typedef struct directional_params {
    double sigma_a[3], sigma_s[3];
    double E[3];        /* irradiance at the medium's boundary */
    double d0, k;       /* light path length d0 + k s */
} directional_params;

static const directional_params directional_scene = {
    {0.02, 0.05, 0.10}, {0.10, 0.20, 0.40}, {3.0, 2.5, 2.0}, 1.0, 0.5};

static void directional_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const directional_params *p = BENCH_PARAMS(directional_params, user);
    double s = (double)t;
    int c;
    bench_count(user, BENCH_CB_LI, t);
    for (c = 0; c < 3; ++c) {
        double st = p->sigma_a[c] + p->sigma_s[c];
        out[c] = (hrm_real)(p->E[c] * BENCH_PHASE * exp(-st * (p->d0 + p->k * s)));
    }
}

static void directional_build(const void *params, hrm_medium *m)
{
    const directional_params *p = (const directional_params *)params;
    int c;
    m->flags = HRM_MEDIUM_HOMOGENEOUS;
    for (c = 0; c < 3; ++c) {
        m->const_sigma_a[c] = (hrm_real)p->sigma_a[c];
        m->const_sigma_s[c] = (hrm_real)p->sigma_s[c];
    }
    m->Li = directional_li;
}

static void directional_integrand(const void *params, long double t0, long double s,
                                  long double out[HRM_CHANNELS])
{
    const directional_params *p = (const directional_params *)params;
    int c;
    for (c = 0; c < 3; ++c) {
        long double st = LD(p->sigma_a[c]) + LD(p->sigma_s[c]);
        long double li = LD(p->E[c]) * BENCH_PHASE_L * expl(-st * (LD(p->d0) + LD(p->k) * s));
        out[c] = expl(-st * (s - t0)) * LD(p->sigma_s[c]) * li;
    }
}

/* L = sigma_s E p exp(-sigma_t (d0 + k t0)) (1 - exp(-sigma_t (1 + k) T)) / (sigma_t (1 + k)) */
static void directional_closed(const void *params, long double t0, long double t1,
                               long double L[HRM_CHANNELS])
{
    const directional_params *p = (const directional_params *)params;
    int c;
    for (c = 0; c < 3; ++c) {
        long double st = LD(p->sigma_a[c]) + LD(p->sigma_s[c]);
        long double rate = st * (1 + LD(p->k));
        L[c] = LD(p->sigma_s[c]) * LD(p->E[c]) * BENCH_PHASE_L *
               expl(-st * (LD(p->d0) + LD(p->k) * t0)) * -expm1l(-rate * (t1 - t0)) / rate;
    }
}

static void directional_print(FILE *out, const void *params)
{
    const directional_params *p = (const directional_params *)params;
    fprintf(out, "  homogeneous: ");
    bench_print_vec(out, "sigma_a", p->sigma_a);
    fprintf(out, ", ");
    bench_print_vec(out, "sigma_s", p->sigma_s);
    fprintf(out, "\n  Li(s) = E p exp(-sigma_t (d0 + k s)), p = 1/(4 pi), ");
    bench_print_vec(out, "E", p->E);
    fprintf(out, ", d0 = %g, k = %g\n", p->d0, p->k);
}

/* ------------------------------------------------------------------------ */
/* point: homogeneous medium, isotropic point light of intensity I at       */
/* (delta, D, 0): distance D from the ray, projecting at s = delta.         */
/* Li(s) = p I exp(-sigma_t r) / r^2, r = sqrt((s - delta)^2 + D^2).        */
/* ------------------------------------------------------------------------ */

typedef struct point_params {
    double sigma_a[3], sigma_s[3];
    double I[3];        /* radiant intensity */
    double delta, D;
} point_params;

static const point_params point_scene = {
    {0.02, 0.05, 0.10}, {0.10, 0.20, 0.40}, {10.0, 8.0, 6.0}, 4.0, 0.5};

static void point_li_unshadowed(const point_params *p, double s, hrm_real out[HRM_CHANNELS])
{
    double r2 = (s - p->delta) * (s - p->delta) + p->D * p->D, r = sqrt(r2);
    int c;
    for (c = 0; c < 3; ++c) {
        double st = p->sigma_a[c] + p->sigma_s[c];
        out[c] = (hrm_real)(BENCH_PHASE * p->I[c] * exp(-st * r) / r2);
    }
}

static void point_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    bench_count(user, BENCH_CB_LI, t);
    point_li_unshadowed(BENCH_PARAMS(point_params, user), (double)t, out);
}

static void point_build_with(const point_params *p, hrm_medium *m, hrm_spectrum_fn li)
{
    int c;
    m->flags = HRM_MEDIUM_HOMOGENEOUS;
    for (c = 0; c < 3; ++c) {
        m->const_sigma_a[c] = (hrm_real)p->sigma_a[c];
        m->const_sigma_s[c] = (hrm_real)p->sigma_s[c];
    }
    m->Li = li;
}

static void point_build(const void *params, hrm_medium *m)
{
    point_build_with((const point_params *)params, m, point_li);
}

static void point_integrand_of(const point_params *p, long double t0, long double s,
                               long double out[HRM_CHANNELS])
{
    long double x = s - LD(p->delta);
    long double r2 = x * x + LD(p->D) * LD(p->D), r = sqrtl(r2);
    int c;
    for (c = 0; c < 3; ++c) {
        long double st = LD(p->sigma_a[c]) + LD(p->sigma_s[c]);
        long double li = BENCH_PHASE_L * LD(p->I[c]) * expl(-st * r) / r2;
        out[c] = expl(-st * (s - t0)) * LD(p->sigma_s[c]) * li;
    }
}

static void point_integrand(const void *params, long double t0, long double s,
                            long double out[HRM_CHANNELS])
{
    point_integrand_of((const point_params *)params, t0, s, out);
}

/* The peak: its poles s = delta +- iD are D from the split point. */
static int point_split(const void *params, long double out[], int max)
{
    const point_params *p = (const point_params *)params;
    if (max < 1) return 0;
    out[0] = LD(p->delta);
    return 1;
}

static void point_print_light(FILE *out, const point_params *p)
{
    fprintf(out, "  homogeneous: ");
    bench_print_vec(out, "sigma_a", p->sigma_a);
    fprintf(out, ", ");
    bench_print_vec(out, "sigma_s", p->sigma_s);
    fprintf(out, "\n  Li(s) = p I exp(-sigma_t r) / r^2, r = sqrt((s - delta)^2 + D^2), "
                 "p = 1/(4 pi), ");
    bench_print_vec(out, "I", p->I);
    fprintf(out, ", delta = %g, D = %g\n", p->delta, p->D);
}

static void point_print(FILE *out, const void *params)
{
    point_print_light(out, (const point_params *)params);
}

static int point_light(const void *params, double pos[3])
{
    const point_params *p = (const point_params *)params;
    pos[0] = p->delta;
    pos[1] = p->D;
    pos[2] = 0;
    return 1;
}

/* thin: the point scene in an optically thin medium, sigma_t T ~ 1e-3
   (air lit by a lamp): Tr ~ 1 and the 1/r^2 peak is all there is. */
static const point_params thin_scene = {
    {2e-5, 3e-5, 4e-5}, {6e-5, 7e-5, 8e-5}, {10.0, 8.0, 6.0}, 6.0, 0.3};

/* ------------------------------------------------------------------------ */
/* occluder: the point light with an opaque sphere between it and the ray.  */
/* Li = 0 where the segment from x(s) to the light meets the sphere.        */
/* ------------------------------------------------------------------------ */

typedef struct occluder_params {
    point_params light;
    double centre[3], radius;
} occluder_params;

/* Centre halfway between the light (4, 0.5, 0) and its projection (4, 0, 0). */
static const occluder_params occluder_scene = {
    {{0.02, 0.05, 0.10}, {0.10, 0.20, 0.40}, {10.0, 8.0, 6.0}, 4.0, 0.5},
    {4.0, 0.25, 0.0}, 0.12};

/* Does the segment from x(s) to the light miss the sphere? (double, for hrm) */
static int occluder_visible(const occluder_params *p, double s)
{
    double a[3], d[3], dd = 0, fd = 0, u, dist2 = 0;
    int i;
    a[0] = s;
    a[1] = a[2] = 0;
    d[0] = p->light.delta - s;
    d[1] = p->light.D;
    d[2] = 0;
    for (i = 0; i < 3; ++i) {
        dd += d[i] * d[i];
        fd += (p->centre[i] - a[i]) * d[i];
    }
    u = fd / dd; /* closest point of the segment to the centre */
    if (u < 0) u = 0;
    if (u > 1) u = 1;
    for (i = 0; i < 3; ++i) {
        double e = a[i] + u * d[i] - p->centre[i];
        dist2 += e * e;
    }
    return dist2 >= p->radius * p->radius;
}


static void occluder_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const occluder_params *p = BENCH_PARAMS(occluder_params, user);
    bench_count(user, BENCH_CB_LI, t);
    if (occluder_visible(p, (double)t)) {
        point_li_unshadowed(&p->light, (double)t, out);
    } else {
        out[0] = out[1] = out[2] = 0;
    }
}

static void occluder_build(const void *params, hrm_medium *m)
{
    point_build_with(&((const occluder_params *)params)->light, m, occluder_li);
}

/* The shadow on the ray, in long double: x(s) is shadowed when the direction
   from the light P to x(s) lies inside the cone tangent to the sphere, of
   half-angle alpha with sin(alpha) = R / |C - P| (axis u = (C - P)/|C - P|).
   Tangency, ((x - P).u)^2 = cos^2(alpha) |x - P|^2, is a quadratic
   A s^2 + B s + C0 = 0 whose roots are the shadow's edges; with A < 0 (the
   ray crosses the cone, as here) the shadow lies between them. Returns 0
   when the ray misses the cone. */
static int occluder_shadow(const occluder_params *p, long double *lo, long double *hi)
{
    long double P[3], u[3], w[3], len = 0, cos2, wu = 0, ww = 0, A, B, C0, disc, q, r1, r2;
    int i;
    P[0] = LD(p->light.delta);
    P[1] = LD(p->light.D);
    P[2] = 0;
    for (i = 0; i < 3; ++i) {
        u[i] = LD(p->centre[i]) - P[i];
        len += u[i] * u[i];
    }
    len = sqrtl(len);
    for (i = 0; i < 3; ++i) {
        u[i] /= len;
        w[i] = -P[i]; /* x(s) - P = w + s (1, 0, 0) */
        wu += w[i] * u[i];
        ww += w[i] * w[i];
    }
    cos2 = 1 - (LD(p->radius) / len) * (LD(p->radius) / len);
    A = u[0] * u[0] - cos2;
    B = 2 * (wu * u[0] - cos2 * w[0]);
    C0 = wu * wu - cos2 * ww;
    disc = B * B - 4 * A * C0;
    if (!(A < 0) || disc <= 0) return 0;
    q = -(B + (B < 0 ? -sqrtl(disc) : sqrtl(disc))) / 2; /* no cancellation */
    r1 = q / A;
    r2 = C0 / q;
    *lo = r1 < r2 ? r1 : r2;
    *hi = r1 < r2 ? r2 : r1;
    return 1;
}

static void occluder_integrand(const void *params, long double t0, long double s,
                               long double out[HRM_CHANNELS])
{
    const occluder_params *p = (const occluder_params *)params;
    long double lo, hi;
    /* Quadrature nodes never sit on an edge: the edges are split points. */
    if (occluder_shadow(p, &lo, &hi) && s > lo && s < hi) {
        out[0] = out[1] = out[2] = 0;
        return;
    }
    point_integrand_of(&p->light, t0, s, out);
}

static int occluder_split(const void *params, long double out[], int max)
{
    const occluder_params *p = (const occluder_params *)params;
    long double lo, hi;
    int n = point_split(&p->light, out, max);
    if (n + 2 <= max && occluder_shadow(p, &lo, &hi)) {
        /* The visibility test hrm sees must put its edges at the same place. */
        double eps = 1e-9 * (1 + fabs((double)hi));
        if (!occluder_visible(p, (double)lo - eps) || occluder_visible(p, (double)lo + eps) ||
            occluder_visible(p, (double)hi - eps) || !occluder_visible(p, (double)hi + eps))
            fprintf(stderr, "bench: occluder: shadow edges and visibility test disagree\n");
        out[n++] = lo;
        out[n++] = hi;
    }
    return n;
}

static int occluder_light(const void *params, double pos[3])
{
    return point_light(&((const occluder_params *)params)->light, pos);
}

static void occluder_print(FILE *out, const void *params)
{
    const occluder_params *p = (const occluder_params *)params;
    long double lo, hi;
    point_print_light(out, &p->light);
    fprintf(out, "  opaque sphere: ");
    bench_print_vec(out, "centre", p->centre);
    fprintf(out, ", radius %g; ", p->radius);
    if (occluder_shadow(p, &lo, &hi))
        fprintf(out, "shadow on the ray: s in [%.19Lg, %.19Lg] (tangency, long double)\n", lo, hi);
    else
        fprintf(out, "it casts no shadow on the ray\n");
}

/* ------------------------------------------------------------------------ */
/* hetero: smooth heterogeneous medium given by callbacks only (hrm         */
/* integrates tau itself), sigma_s(s) = a + b sin(omega s + phi) per        */
/* channel, constant sigma_a with emission Le, and a directional light      */
/* dimmed smoothly along the ray: Li(s) = E p (1 + m cos(nu s)).            */
/* ------------------------------------------------------------------------ */

typedef struct hetero_params {
    double sigma_a[3];
    double a[3], b[3], omega, phi[3]; /* sigma_s */
    double Le[3];
    double E[3], m, nu;               /* Li */
} hetero_params;

static const hetero_params hetero_scene = {
    {0.05, 0.04, 0.03},
    {0.20, 0.30, 0.40}, {0.15, 0.25, 0.30}, 1.3, {0.0, 1.0, 2.0},
    {0.8, 0.5, 0.3},
    {4.0, 3.5, 3.0}, 0.5, 0.6};

static void hetero_sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const hetero_params *p = BENCH_PARAMS(hetero_params, user);
    int c;
    bench_count(user, BENCH_CB_SIGMA_A, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)p->sigma_a[c];
}

static void hetero_sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const hetero_params *p = BENCH_PARAMS(hetero_params, user);
    int c;
    bench_count(user, BENCH_CB_SIGMA_S, t);
    for (c = 0; c < 3; ++c)
        out[c] = (hrm_real)(p->a[c] + p->b[c] * sin(p->omega * (double)t + p->phi[c]));
}

static void hetero_le(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const hetero_params *p = BENCH_PARAMS(hetero_params, user);
    int c;
    bench_count(user, BENCH_CB_LE, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)p->Le[c];
}

static void hetero_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const hetero_params *p = BENCH_PARAMS(hetero_params, user);
    int c;
    bench_count(user, BENCH_CB_LI, t);
    for (c = 0; c < 3; ++c)
        out[c] = (hrm_real)(p->E[c] * BENCH_PHASE * (1 + p->m * cos(p->nu * (double)t)));
}

static void hetero_build(const void *params, hrm_medium *m)
{
    (void)params;
    m->sigma_a = hetero_sigma_a;
    m->sigma_s = hetero_sigma_s;
    m->Le = hetero_le;
    m->Li = hetero_li;
}

/* tau(t0, s) = (sigma_a + a)(s - t0) - (b / omega)(cos(omega s + phi) - cos(omega t0 + phi)) */
static void hetero_integrand(const void *params, long double t0, long double s,
                             long double out[HRM_CHANNELS])
{
    const hetero_params *p = (const hetero_params *)params;
    int c;
    for (c = 0; c < 3; ++c) {
        long double om = LD(p->omega), ph = LD(p->phi[c]), b = LD(p->b[c]);
        long double tau = (LD(p->sigma_a[c]) + LD(p->a[c])) * (s - t0) -
                          b / om * (cosl(om * s + ph) - cosl(om * t0 + ph));
        long double ss = LD(p->a[c]) + b * sinl(om * s + ph);
        long double li = LD(p->E[c]) * BENCH_PHASE_L * (1 + LD(p->m) * cosl(LD(p->nu) * s));
        out[c] = expl(-tau) * (LD(p->sigma_a[c]) * LD(p->Le[c]) + ss * li);
    }
}

static void hetero_print(FILE *out, const void *params)
{
    const hetero_params *p = (const hetero_params *)params;
    fprintf(out, "  callbacks only, no closed-form Tr given to hrm: ");
    bench_print_vec(out, "sigma_a", p->sigma_a);
    fprintf(out, ", ");
    bench_print_vec(out, "Le", p->Le);
    fprintf(out, "\n  sigma_s(s) = a + b sin(omega s + phi), ");
    bench_print_vec(out, "a", p->a);
    fprintf(out, ", ");
    bench_print_vec(out, "b", p->b);
    fprintf(out, ", omega = %g, ", p->omega);
    bench_print_vec(out, "phi", p->phi);
    fprintf(out, "\n  Li(s) = E p (1 + m cos(nu s)), p = 1/(4 pi), ");
    bench_print_vec(out, "E", p->E);
    fprintf(out, ", m = %g, nu = %g\n", p->m, p->nu);
}

/* thick: the directional scene in an optically thick medium, sigma_t T =
   50, 200 and 1000: the integrand is a boundary layer exp(-sigma_t (1 + k) s)
   of width 1/120 in blue. */
static const directional_params thick_scene = {
    {1.0, 4.0, 20.0}, {4.0, 16.0, 80.0}, {3.0, 2.5, 2.0}, 0.1, 0.2};

/* ------------------------------------------------------------------------ */
/* hifreq: high-frequency heterogeneous medium from callbacks,              */
/* sigma_s(s) = a + b1 sin(w1 s + phi) + b2 sin(w2 s + 2 phi), about 50     */
/* periods of the fast term along the ray; constant sigma_a, no emission,   */
/* the smooth sky light of hetero.                                          */
/* ------------------------------------------------------------------------ */

typedef struct hifreq_params {
    double sigma_a[3];
    double a[3], b1[3], b2[3], w1, w2, phi[3]; /* sigma_s */
    double E[3], m, nu;                        /* Li */
} hifreq_params;

static const hifreq_params hifreq_scene = {
    {0.05, 0.04, 0.03},
    {0.50, 0.70, 0.90}, {0.25, 0.35, 0.45}, {0.20, 0.30, 0.40}, 7.0, 31.0, {0.0, 1.0, 2.0},
    {4.0, 3.5, 3.0}, 0.5, 0.6};

static void hifreq_sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const hifreq_params *p = BENCH_PARAMS(hifreq_params, user);
    int c;
    bench_count(user, BENCH_CB_SIGMA_A, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)p->sigma_a[c];
}

static void hifreq_sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const hifreq_params *p = BENCH_PARAMS(hifreq_params, user);
    double s = (double)t;
    int c;
    bench_count(user, BENCH_CB_SIGMA_S, t);
    for (c = 0; c < 3; ++c)
        out[c] = (hrm_real)(p->a[c] + p->b1[c] * sin(p->w1 * s + p->phi[c]) +
                            p->b2[c] * sin(p->w2 * s + 2 * p->phi[c]));
}

static void hifreq_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const hifreq_params *p = BENCH_PARAMS(hifreq_params, user);
    int c;
    bench_count(user, BENCH_CB_LI, t);
    for (c = 0; c < 3; ++c)
        out[c] = (hrm_real)(p->E[c] * BENCH_PHASE * (1 + p->m * cos(p->nu * (double)t)));
}

static void hifreq_build(const void *params, hrm_medium *m)
{
    (void)params;
    m->sigma_a = hifreq_sigma_a;
    m->sigma_s = hifreq_sigma_s;
    m->Li = hifreq_li;
}

/* tau(t0, s) = (sigma_a + a)(s - t0) - (b1 / w1)(cos(w1 s + phi) - cos(w1 t0 + phi))
               - (b2 / w2)(cos(w2 s + 2 phi) - cos(w2 t0 + 2 phi)) */
static void hifreq_integrand(const void *params, long double t0, long double s,
                             long double out[HRM_CHANNELS])
{
    const hifreq_params *p = (const hifreq_params *)params;
    int c;
    for (c = 0; c < 3; ++c) {
        long double w1 = LD(p->w1), w2 = LD(p->w2), ph = LD(p->phi[c]);
        long double b1 = LD(p->b1[c]), b2 = LD(p->b2[c]);
        long double tau = (LD(p->sigma_a[c]) + LD(p->a[c])) * (s - t0) -
                          b1 / w1 * (cosl(w1 * s + ph) - cosl(w1 * t0 + ph)) -
                          b2 / w2 * (cosl(w2 * s + 2 * ph) - cosl(w2 * t0 + 2 * ph));
        long double ss = LD(p->a[c]) + b1 * sinl(w1 * s + ph) + b2 * sinl(w2 * s + 2 * ph);
        long double li = LD(p->E[c]) * BENCH_PHASE_L * (1 + LD(p->m) * cosl(LD(p->nu) * s));
        out[c] = expl(-tau) * ss * li;
    }
}

static void hifreq_print(FILE *out, const void *params)
{
    const hifreq_params *p = (const hifreq_params *)params;
    fprintf(out, "  callbacks only, no closed-form Tr given to hrm: ");
    bench_print_vec(out, "sigma_a", p->sigma_a);
    fprintf(out, "\n  sigma_s(s) = a + b1 sin(w1 s + phi) + b2 sin(w2 s + 2 phi), ");
    bench_print_vec(out, "a", p->a);
    fprintf(out, ",\n    ");
    bench_print_vec(out, "b1", p->b1);
    fprintf(out, ", ");
    bench_print_vec(out, "b2", p->b2);
    fprintf(out, ", w1 = %g, w2 = %g, ", p->w1, p->w2);
    bench_print_vec(out, "phi", p->phi);
    fprintf(out, "\n  Li(s) = E p (1 + m cos(nu s)), p = 1/(4 pi), ");
    bench_print_vec(out, "E", p->E);
    fprintf(out, ", m = %g, nu = %g\n", p->m, p->nu);
}

/* ------------------------------------------------------------------------ */
/* emission: emission only (a flame), no scattering and no Li: homogeneous  */
/* absorption sigma_a and a Gaussian emission profile                       */
/* Le(s) = A exp(-(s - c)^2 / (2 w^2)); L has a closed form with erf.       */
/* ------------------------------------------------------------------------ */

typedef struct emission_params {
    double sigma_a[3];
    double A[3], c, w;
} emission_params;

static const emission_params emission_scene = {{0.3, 0.5, 0.8}, {2.0, 1.5, 1.0}, 6.0, 0.7};

static void emission_le(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const emission_params *p = BENCH_PARAMS(emission_params, user);
    double x = ((double)t - p->c) / p->w;
    int c;
    bench_count(user, BENCH_CB_LE, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->A[c] * exp(-0.5 * x * x));
}

static void emission_build(const void *params, hrm_medium *m)
{
    const emission_params *p = (const emission_params *)params;
    int c;
    m->flags = HRM_MEDIUM_HOMOGENEOUS;
    for (c = 0; c < 3; ++c) {
        m->const_sigma_a[c] = (hrm_real)p->sigma_a[c];
        m->const_sigma_s[c] = 0;
    }
    m->Le = emission_le;
}

static void emission_integrand(const void *params, long double t0, long double s,
                               long double out[HRM_CHANNELS])
{
    const emission_params *p = (const emission_params *)params;
    long double x = (s - LD(p->c)) / LD(p->w);
    int c;
    for (c = 0; c < 3; ++c)
        out[c] = expl(-LD(p->sigma_a[c]) * (s - t0)) * LD(p->sigma_a[c]) * LD(p->A[c]) *
                 expl(-0.5L * x * x);
}

/* erf(b) - erf(a), a <= b, without cancellation in the tails. */
static long double bench_erf_diff(long double a, long double b)
{
    if (a > 0) return erfcl(a) - erfcl(b);
    if (b < 0) return erfcl(-b) - erfcl(-a);
    return erfl(b) - erfl(a);
}

/* With x = s - c and m = sigma_a w^2, completing the square:
   L = sigma_a A exp(sigma_a^2 w^2 / 2 - sigma_a (c - t0)) w sqrt(pi/2)
       [erf((x1 + m) / (w sqrt 2)) - erf((x0 + m) / (w sqrt 2))]. */
static void emission_closed(const void *params, long double t0, long double t1,
                            long double L[HRM_CHANNELS])
{
    const emission_params *p = (const emission_params *)params;
    long double w = LD(p->w), r2 = sqrtl(2.0L);
    int c;
    for (c = 0; c < 3; ++c) {
        long double sa = LD(p->sigma_a[c]), m = sa * w * w;
        long double x0 = t0 - LD(p->c), x1 = t1 - LD(p->c);
        L[c] = sa * LD(p->A[c]) * expl(sa * sa * w * w / 2 - sa * (LD(p->c) - t0)) * w *
               sqrtl(BENCH_PI_L / 2) * bench_erf_diff((x0 + m) / (w * r2), (x1 + m) / (w * r2));
    }
}

static void emission_print(FILE *out, const void *params)
{
    const emission_params *p = (const emission_params *)params;
    fprintf(out, "  homogeneous, no scattering (Li absent): ");
    bench_print_vec(out, "sigma_a", p->sigma_a);
    fprintf(out, "\n  Le(s) = A exp(-(s - c)^2 / (2 w^2)), source sigma_a Le, ");
    bench_print_vec(out, "A", p->A);
    fprintf(out, ", c = %g, w = %g\n", p->c, p->w);
}

/* ------------------------------------------------------------------------ */
/* smoke: a spotlight in smoke. Heterogeneous medium from callbacks whose   */
/* coefficients vary by up to +-50% along the ray,                          */
/*   sigma_a(x) = a0 m_a(x),  sigma_s(x) = s0 m_s(x),                       */
/*   m(x) = 1 + b1 sin(w1 x + p1) + b2 sin(w2 x + p2),  |b1| + |b2| = 0.5,  */
/* lit by an isotropic point light of intensity I at (delta, D, 0). The     */
/* smoke is stratified (sigma depends on x alone, everywhere in space), so  */
/* the optical depth of any segment from x = a to x = b, of length len, is  */
/* len times the mean of sigma_t over [a, b] in x, in closed form:          */
/*   mean of sin(w x + p) over [a, b] = sin(w c + p) sinc(w h / 2),         */
/*   c = (a + b) / 2, h = b - a  (no cancellation for short segments).      */
/* Hence, exactly:                                                          */
/*   eye ray    tau(ta, tb) = (tb - ta) mean[ta, tb] sigma_t,               */
/*   light      Li(s) = p I exp(-r mean[s, delta] sigma_t) / r^2,           */
/*              r = sqrt((s - delta)^2 + D^2) (the segment to the light),   */
/* in double for hrm and, separately, in long double for the reference.     */
/* ------------------------------------------------------------------------ */

#define SMOKE_T0 0.0
#define SMOKE_T1 10.0

typedef struct smoke_params {
    double sigma_a[3], sigma_s[3];  /* the means a0 and s0 */
    double ba[2], wa[2], pa[2];     /* m_a: amplitudes, frequencies, phases */
    double bs[2], ws[2], ps[2];     /* m_s */
    double I[3];                    /* radiant intensity */
    double delta, D;
} smoke_params;

static const smoke_params smoke_scene = {
    {0.04, 0.05, 0.06}, {0.25, 0.30, 0.35},
    {0.30, 0.20}, {1.7, 3.1}, {0.4, 2.0},
    {0.30, 0.20}, {1.3, 2.9}, {1.1, 0.3},
    {10.0, 8.0, 6.0}, 5.0, 0.4};

static double smoke_sinc(double x)
{
    return x == 0 ? 1 : sin(x) / x;
}

static long double smoke_sincl(long double x)
{
    return x == 0 ? 1 : sinl(x) / x;
}

/* The mean of m over [a, b] (b = a: m(a)); double, for hrm. */
static double smoke_mean(const double b[2], const double w[2], const double p[2], double a,
                         double bb)
{
    double c = 0.5 * (a + bb), h = bb - a;
    return 1 + b[0] * sin(w[0] * c + p[0]) * smoke_sinc(0.5 * w[0] * h) +
           b[1] * sin(w[1] * c + p[1]) * smoke_sinc(0.5 * w[1] * h);
}

/* The same in long double, for the reference. */
static long double smoke_meanl(const double b[2], const double w[2], const double p[2],
                               long double a, long double bb)
{
    long double c = (a + bb) / 2, h = bb - a;
    return 1 + LD(b[0]) * sinl(LD(w[0]) * c + LD(p[0])) * smoke_sincl(LD(w[0]) * h / 2) +
           LD(b[1]) * sinl(LD(w[1]) * c + LD(p[1])) * smoke_sincl(LD(w[1]) * h / 2);
}

static long double smoke_modl(const double b[2], const double w[2], const double p[2],
                              long double x)
{
    return 1 + LD(b[0]) * sinl(LD(w[0]) * x + LD(p[0])) + LD(b[1]) * sinl(LD(w[1]) * x + LD(p[1]));
}

/* Mean sigma_t over [a, b] in x, per channel. */
static void smoke_mean_st(const smoke_params *p, double a, double b, double out[3])
{
    double ma = smoke_mean(p->ba, p->wa, p->pa, a, b), ms = smoke_mean(p->bs, p->ws, p->ps, a, b);
    int c;
    for (c = 0; c < 3; ++c) out[c] = p->sigma_a[c] * ma + p->sigma_s[c] * ms;
}

static void smoke_mean_stl(const smoke_params *p, long double a, long double b,
                           long double out[3])
{
    long double ma = smoke_meanl(p->ba, p->wa, p->pa, a, b);
    long double ms = smoke_meanl(p->bs, p->ws, p->ps, a, b);
    int c;
    for (c = 0; c < 3; ++c) out[c] = LD(p->sigma_a[c]) * ma + LD(p->sigma_s[c]) * ms;
}

static void smoke_sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const smoke_params *p = BENCH_PARAMS(smoke_params, user);
    double m = smoke_mean(p->ba, p->wa, p->pa, (double)t, (double)t);
    int c;
    bench_count(user, BENCH_CB_SIGMA_A, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->sigma_a[c] * m);
}

static void smoke_sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const smoke_params *p = BENCH_PARAMS(smoke_params, user);
    double m = smoke_mean(p->bs, p->ws, p->ps, (double)t, (double)t);
    int c;
    bench_count(user, BENCH_CB_SIGMA_S, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->sigma_s[c] * m);
}

static void smoke_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const smoke_params *p = BENCH_PARAMS(smoke_params, user);
    double s = (double)t, x = s - p->delta, r2 = x * x + p->D * p->D, r = sqrt(r2), st[3];
    int c;
    bench_count(user, BENCH_CB_LI, t);
    smoke_mean_st(p, s, p->delta, st);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(BENCH_PHASE * p->I[c] * exp(-r * st[c]) / r2);
}

/* The exact eye-ray transmittance, for hrm's transmittance callback. */
static void smoke_tr(void *user, hrm_real ta, hrm_real tb, hrm_real out[HRM_CHANNELS])
{
    const smoke_params *p = BENCH_PARAMS(smoke_params, user);
    double st[3];
    int c;
    bench_count(user, BENCH_CB_TR, tb);
    smoke_mean_st(p, (double)ta, (double)tb, st);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)exp(-((double)tb - (double)ta) * st[c]);
}

static void smoke_build(const void *params, hrm_medium *m)
{
    (void)params;
    m->sigma_a = smoke_sigma_a;
    m->sigma_s = smoke_sigma_s;
    m->Li = smoke_li;
}

static void smoke_integrand(const void *params, long double t0, long double s,
                            long double out[HRM_CHANNELS])
{
    const smoke_params *p = (const smoke_params *)params;
    long double x = s - LD(p->delta), r2 = x * x + LD(p->D) * LD(p->D), r = sqrtl(r2);
    long double eye[3], light[3], ms = smoke_modl(p->bs, p->ws, p->ps, s);
    int c;
    smoke_mean_stl(p, t0, s, eye);
    smoke_mean_stl(p, s, LD(p->delta), light);
    for (c = 0; c < 3; ++c) {
        long double li = BENCH_PHASE_L * LD(p->I[c]) * expl(-r * light[c]) / r2;
        out[c] = expl(-(s - t0) * eye[c]) * LD(p->sigma_s[c]) * ms * li;
    }
}

static int smoke_split(const void *params, long double out[], int max)
{
    if (max < 1) return 0;
    out[0] = LD(((const smoke_params *)params)->delta);
    return 1;
}

static int smoke_light(const void *params, double pos[3])
{
    const smoke_params *p = (const smoke_params *)params;
    pos[0] = p->delta;
    pos[1] = p->D;
    pos[2] = 0;
    return 1;
}

/* A check of the closed forms: sigma_t integrated by Gauss-Legendre along a
   segment from x = a to the point (b, y, 0) (length len), in long double. */
typedef struct smoke_segment {
    const smoke_params *p;
    long double a, b, len;
} smoke_segment;

static void smoke_segment_st(const void *params, long double t0, long double l,
                             long double out[HRM_CHANNELS])
{
    const smoke_segment *g = (const smoke_segment *)params;
    long double x = g->a + (g->b - g->a) * l / g->len;
    long double ma = smoke_modl(g->p->ba, g->p->wa, g->p->pa, x);
    long double ms = smoke_modl(g->p->bs, g->p->ws, g->p->ps, x);
    int c;
    (void)t0;
    for (c = 0; c < 3; ++c) out[c] = LD(g->p->sigma_a[c]) * ma + LD(g->p->sigma_s[c]) * ms;
}

/* The largest relative difference between the closed-form optical depth and
   a 20-point Gauss-Legendre quadrature of sigma_t, on the eye ray and on
   the light paths from 11 points of the ray. */
static long double smoke_check_tau(const smoke_params *p)
{
    ref_rule rule;
    long double worst = 0, quad[3], closed[3], pts[2], mean[3];
    int k, c;
    ref_rule_init(&rule);
    for (k = -1; k <= 10; ++k) {
        smoke_segment g;
        long double d;
        g.p = p;
        if (k < 0) { /* the eye ray */
            g.a = LD(SMOKE_T0);
            g.b = LD(SMOKE_T1);
            g.len = g.b - g.a;
        } else { /* from x(s) to the light */
            long double s = LD(SMOKE_T0) + (LD(SMOKE_T1) - LD(SMOKE_T0)) * k / 10;
            g.a = s;
            g.b = LD(p->delta);
            g.len = sqrtl((s - g.b) * (s - g.b) + LD(p->D) * LD(p->D));
        }
        pts[0] = 0;
        pts[1] = g.len;
        ref_integrate(&rule, smoke_segment_st, &g, pts, 2, 0.125L, quad);
        smoke_mean_stl(p, g.a, g.b, mean);
        for (c = 0; c < 3; ++c) closed[c] = g.len * mean[c];
        d = ref_rel_diff(quad, closed);
        if (!(d <= worst)) worst = d;
    }
    return worst;
}

static void smoke_print(FILE *out, const void *params)
{
    const smoke_params *p = (const smoke_params *)params;
    double lo = HUGE_VAL, hi = 0;
    int k, c;
    for (k = 0; k <= 10000; ++k) { /* sigma_t / its mean, sampled */
        double x = SMOKE_T0 + (SMOKE_T1 - SMOKE_T0) * k / 10000.0;
        double ma = smoke_mean(p->ba, p->wa, p->pa, x, x), ms = smoke_mean(p->bs, p->ws, p->ps, x, x);
        for (c = 0; c < 3; ++c) {
            double q = (p->sigma_a[c] * ma + p->sigma_s[c] * ms) / (p->sigma_a[c] + p->sigma_s[c]);
            if (q < lo) lo = q;
            if (q > hi) hi = q;
        }
    }
    fprintf(out, "  callbacks only: sigma_a(x) = a0 m_a(x), sigma_s(x) = s0 m_s(x), "
                 "m(x) = 1 + b1 sin(w1 x + p1) + b2 sin(w2 x + p2)\n    ");
    bench_print_vec(out, "a0", p->sigma_a);
    fprintf(out, ", m_a: b = (%g, %g), w = (%g, %g), p = (%g, %g)\n    ", p->ba[0], p->ba[1],
            p->wa[0], p->wa[1], p->pa[0], p->pa[1]);
    bench_print_vec(out, "s0", p->sigma_s);
    fprintf(out, ", m_s: b = (%g, %g), w = (%g, %g), p = (%g, %g)\n", p->bs[0], p->bs[1],
            p->ws[0], p->ws[1], p->ps[0], p->ps[1]);
    fprintf(out, "    sigma_t on the ray: %.2f..%.2f times its mean (a0 + s0)\n", lo, hi);
    fprintf(out, "  Li(s) = p I exp(-tau_light) / r^2, r = sqrt((s - delta)^2 + D^2), p = 1/(4 pi), ");
    bench_print_vec(out, "I", p->I);
    fprintf(out, ", delta = %g, D = %g\n", p->delta, p->D);
    fprintf(out, "  the smoke is stratified (sigma depends on x only), so tau of a segment from x = a\n"
                 "  to x = b is its length times the mean of sigma_t over [a, b], in closed form\n"
                 "  (sin(w c + p) sinc(w (b - a) / 2)): eye ray and light path exact; it agrees with\n"
                 "  %d-point Gauss-Legendre quadrature of sigma_t (eye ray, 11 light paths) to %.1Le\n",
            REF_GL_POINTS, smoke_check_tau(p));
}

/* ------------------------------------------------------------------------ */
/* The scene table: a new scene is one more row.                            */
/* ------------------------------------------------------------------------ */


/* ------------------------------------------------------------------------ */
/* slab: a dense slab (sigma_t 5, 100 times the medium around it) across    */
/* [4, 5] of a thin medium, from callbacks, under a constant sky light:     */
/* the integrand jumps at both faces.                                       */
/* ------------------------------------------------------------------------ */

typedef struct slab_params {
    double sigma_a[3], sigma_s[3]; /* outside */
    double dense;                  /* inside: these times dense */
    double lo, hi;                 /* the slab's faces */
    double E[3];                   /* Li */
} slab_params;

static const slab_params slab_scene = {
    {0.01, 0.01, 0.01}, {0.04, 0.045, 0.05}, 100.0, 4.0, 5.0, {2.0, 1.5, 1.0}};

static double slab_k(const slab_params *p, double s) { return s >= p->lo && s < p->hi ? p->dense : 1; }

static void slab_sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const slab_params *p = BENCH_PARAMS(slab_params, user);
    int c;
    bench_count(user, BENCH_CB_SIGMA_A, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->sigma_a[c] * slab_k(p, (double)t));
}

static void slab_sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const slab_params *p = BENCH_PARAMS(slab_params, user);
    int c;
    bench_count(user, BENCH_CB_SIGMA_S, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->sigma_s[c] * slab_k(p, (double)t));
}

static void slab_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const slab_params *p = BENCH_PARAMS(slab_params, user);
    int c;
    bench_count(user, BENCH_CB_LI, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->E[c] * BENCH_PHASE);
}

static void slab_build(const void *params, hrm_medium *m)
{
    (void)params;
    m->sigma_a = slab_sigma_a;
    m->sigma_s = slab_sigma_s;
    m->Li = slab_li;
}

/* tau(t0, s): sigma_t times the length outside, plus dense times inside */
static void slab_integrand(const void *params, long double t0, long double s,
                           long double out[HRM_CHANNELS])
{
    const slab_params *p = (const slab_params *)params;
    long double lo = LD(p->lo), hi = LD(p->hi), a = t0 > lo ? t0 : lo, b = s < hi ? s : hi;
    long double in = b > a ? b - a : 0, k = s >= lo && s < hi ? LD(p->dense) : 1;
    int c;
    for (c = 0; c < 3; ++c) {
        long double st = LD(p->sigma_a[c]) + LD(p->sigma_s[c]);
        long double tau = st * ((s - t0) - in + LD(p->dense) * in);
        out[c] = expl(-tau) * LD(p->sigma_s[c]) * k * LD(p->E[c]) * BENCH_PHASE_L;
    }
}

static int slab_split(const void *params, long double out[], int max)
{
    const slab_params *p = (const slab_params *)params;
    if (max < 2) return 0;
    out[0] = LD(p->lo);
    out[1] = LD(p->hi);
    return 2;
}

static void slab_print(FILE *out, const void *params)
{
    const slab_params *p = (const slab_params *)params;
    fprintf(out, "  callbacks only: outside the slab ");
    bench_print_vec(out, "sigma_a", p->sigma_a);
    fprintf(out, ", ");
    bench_print_vec(out, "sigma_s", p->sigma_s);
    fprintf(out, "; inside [%g, %g) %g times these\n  Li = E p, ", p->lo, p->hi, p->dense);
    bench_print_vec(out, "E", p->E);
    fprintf(out, "\n");
}

/* ------------------------------------------------------------------------ */
/* cloud: an optically thick heterogeneous cloud from callbacks, sigma_t T  */
/* about 100 / 250 / 500, the ray starting at its face (or the camera in    */
/* it). The density ripples at two frequencies,                             */
/* rho(s) = 1 + a1 sin(w1 s + f1) + a2 sin(w2 s + f2), sigma_t = k rho      */
/* (albedo alb); a directional light whose optical depth to x(s) is         */
/* ell sigma_t(s) (the column above as dense as the point):                 */
/* Li(s) = E p exp(-ell sigma_t(s)). tau is in closed form for the          */
/* reference; hrm integrates it from the callbacks.                         */
/* ------------------------------------------------------------------------ */

typedef struct cloud_params {
    double k[3], albedo;                 /* sigma_t = k rho, sigma_s = albedo sigma_t */
    double a1, w1, f1, a2, w2, f2;       /* rho */
    double ell;                          /* the light's path, in units of 1 / sigma_t */
    double E[3];
} cloud_params;

static const cloud_params cloud_scene = {
    {10.0, 25.0, 50.0}, 0.9, 0.4, 1.3, 0.4, 0.15, 3.7, 1.1, 0.1, {3.0, 2.5, 2.0}};

static long double cloud_rho(const cloud_params *p, long double s)
{
    return 1 + LD(p->a1) * sinl(LD(p->w1) * s + LD(p->f1)) + LD(p->a2) * sinl(LD(p->w2) * s + LD(p->f2));
}

/* int_0^s rho */
static long double cloud_rho_integral(const cloud_params *p, long double s)
{
    return s + LD(p->a1) * (cosl(LD(p->f1)) - cosl(LD(p->w1) * s + LD(p->f1))) / LD(p->w1) +
           LD(p->a2) * (cosl(LD(p->f2)) - cosl(LD(p->w2) * s + LD(p->f2))) / LD(p->w2);
}

static void cloud_sigma(void *user, hrm_real t, hrm_real out[HRM_CHANNELS], int scattering)
{
    const cloud_params *p = BENCH_PARAMS(cloud_params, user);
    double rho = (double)cloud_rho(p, LD(t)), f = scattering ? p->albedo : 1 - p->albedo;
    int c;
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(f * p->k[c] * rho);
}

static void cloud_sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    bench_count(user, BENCH_CB_SIGMA_A, t);
    cloud_sigma(user, t, out, 0);
}

static void cloud_sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    bench_count(user, BENCH_CB_SIGMA_S, t);
    cloud_sigma(user, t, out, 1);
}

static void cloud_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const cloud_params *p = BENCH_PARAMS(cloud_params, user);
    double rho = (double)cloud_rho(p, LD(t));
    int c;
    bench_count(user, BENCH_CB_LI, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->E[c] * BENCH_PHASE * exp(-p->ell * p->k[c] * rho));
}

static void cloud_build(const void *params, hrm_medium *m)
{
    (void)params;
    m->sigma_a = cloud_sigma_a;
    m->sigma_s = cloud_sigma_s;
    m->Li = cloud_li;
}

static void cloud_integrand(const void *params, long double t0, long double s,
                            long double out[HRM_CHANNELS])
{
    const cloud_params *p = (const cloud_params *)params;
    long double rho = cloud_rho(p, s), tau1 = cloud_rho_integral(p, s) - cloud_rho_integral(p, t0);
    int c;
    for (c = 0; c < 3; ++c) {
        long double k = LD(p->k[c]);
        long double li = LD(p->E[c]) * BENCH_PHASE_L * expl(-LD(p->ell) * k * rho);
        out[c] = expl(-k * tau1) * LD(p->albedo) * k * rho * li;
    }
}

static void cloud_print(FILE *out, const void *params)
{
    const cloud_params *p = (const cloud_params *)params;
    fprintf(out, "  callbacks only: sigma_t = k rho(s), ");
    bench_print_vec(out, "k", p->k);
    fprintf(out, ", albedo %g,\n  rho(s) = 1 + %g sin(%g s + %g) + %g sin(%g s + %g),"
                 " tau(T) = k * %.4g\n  Li = E p exp(-%g sigma_t(s)), ",
            p->albedo, p->a1, p->w1, p->f1, p->a2, p->w2, p->f2,
            (double)cloud_rho_integral(p, 10.0L), p->ell);
    bench_print_vec(out, "E", p->E);
    fprintf(out, "\n");
}

/* ------------------------------------------------------------------------ */
/* dense: a dense smooth front at the start of a long ray, from callbacks:  */
/* sigma_t(s) = k_c (base + amp exp(-(s / w)^2)) on [0, 30] (w = 0.2: the   */
/* front holds 1.8 of the ray's 3.3 optical depths), albedo 0.8, sky light. */
/* tau(0, s) = k_c (base s + amp w (sqrt(pi) / 2) erf(s / w)).              */
/* ------------------------------------------------------------------------ */

typedef struct dense_params {
    double base, amp, w, albedo;
    double k[3]; /* per channel */
    double E[3]; /* Li */
} dense_params;

static const dense_params dense_scene = {0.05, 10.0, 0.2, 0.8, {1.0, 0.9, 0.8}, {2.0, 1.5, 1.0}};

static double dense_sigma_t(const dense_params *p, double s)
{
    double x = s / p->w;
    return p->base + p->amp * exp(-x * x);
}

static void dense_sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const dense_params *p = BENCH_PARAMS(dense_params, user);
    double v = dense_sigma_t(p, (double)t);
    int c;
    bench_count(user, BENCH_CB_SIGMA_A, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)((1 - p->albedo) * p->k[c] * v);
}

static void dense_sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const dense_params *p = BENCH_PARAMS(dense_params, user);
    double v = dense_sigma_t(p, (double)t);
    int c;
    bench_count(user, BENCH_CB_SIGMA_S, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->albedo * p->k[c] * v);
}

static void dense_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const dense_params *p = BENCH_PARAMS(dense_params, user);
    int c;
    bench_count(user, BENCH_CB_LI, t);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(p->E[c] * BENCH_PHASE);
}

static void dense_build(const void *params, hrm_medium *m)
{
    (void)params;
    m->sigma_a = dense_sigma_a;
    m->sigma_s = dense_sigma_s;
    m->Li = dense_li;
}

static void dense_integrand(const void *params, long double t0, long double s,
                            long double out[HRM_CHANNELS])
{
    const dense_params *p = (const dense_params *)params;
    long double w = LD(p->w), x = s / w, x0 = t0 / w;
    long double sg = LD(p->base) + LD(p->amp) * expl(-x * x);
    long double tau = LD(p->base) * (s - t0) + LD(p->amp) * w * 0.886226925452758013649083741671L * (erfl(x) - erfl(x0));
    int c;
    for (c = 0; c < 3; ++c)
        out[c] = expl(-LD(p->k[c]) * tau) * LD(p->albedo) * LD(p->k[c]) * sg * LD(p->E[c]) * BENCH_PHASE_L;
}

static void dense_print(FILE *out, const void *params)
{
    const dense_params *p = (const dense_params *)params;
    fprintf(out, "  callbacks only: sigma_t(s) = k (%g + %g exp(-(s/%g)^2)), ", p->base, p->amp, p->w);
    bench_print_vec(out, "k", p->k);
    fprintf(out, ", albedo %g\n  Li = E p, ", p->albedo);
    bench_print_vec(out, "E", p->E);
    fprintf(out, "\n");
}

const bench_scene bench_scenes[] = {
    {.name = "directional",
     .description = "homogeneous medium, directional light whose path through the medium grows along the ray",
     .params = &directional_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = directional_print,
     .build = directional_build, .integrand = directional_integrand,
     .closed_form = directional_closed},
    {.name = "point",
     .description = "homogeneous medium, point light 0.5 from the ray (a sharp but smooth peak)",
     .params = &point_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_EQUIANGULAR, .light = point_light, .print_params = point_print,
     .build = point_build, .integrand = point_integrand, .split_points = point_split},
    {.name = "occluder",
     .description = "the point light with an opaque sphere casting a sharp shadow over the peak",
     .params = &occluder_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 0,
     .natural_warp = BENCH_WARP_EQUIANGULAR, .light = occluder_light,
     .print_params = occluder_print, .build = occluder_build, .integrand = occluder_integrand,
     .split_points = occluder_split},
    {.name = "hetero",
     .description = "sinusoidal sigma_s from callbacks (hrm integrates tau), emission, smooth sky light",
     .params = &hetero_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = hetero_print, .build = hetero_build,
     .integrand = hetero_integrand},
    {.name = "hifreq",
     .description = "high-frequency sigma_s from callbacks (about 50 periods on the ray), sky light",
     .params = &hifreq_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = hifreq_print, .build = hifreq_build,
     .integrand = hifreq_integrand, .ref_panel = 0.0625L},
    {.name = "emission",
     .description = "emission only: absorbing medium with a Gaussian emission profile, no Li",
     .params = &emission_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = emission_print,
     .build = emission_build, .integrand = emission_integrand, .closed_form = emission_closed},
    {.name = "thick",
     .description = "optically thick (sigma_t T = 50, 200, 1000), directional light",
     .params = &thick_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = directional_print,
     .build = directional_build, .integrand = directional_integrand,
     .closed_form = directional_closed, .ref_panel = 0.005L},
    {.name = "thin",
     .description = "optically thin (sigma_t T ~ 1e-3), point light 0.3 from the ray",
     .params = &thin_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_EQUIANGULAR, .light = point_light, .print_params = point_print,
     .build = point_build, .integrand = point_integrand, .split_points = point_split},
    {.name = "smoke",
     .description = "spotlight in smoke: sigma_a, sigma_s from callbacks varying +-50% along the ray, point light 0.4 from it",
     .params = &smoke_scene, .t0 = SMOKE_T0, .t1 = SMOKE_T1, .smooth = 1,
     .natural_warp = BENCH_WARP_EQUIANGULAR, .light = smoke_light, .print_params = smoke_print,
     .build = smoke_build, .transmittance = smoke_tr, .integrand = smoke_integrand,
     .split_points = smoke_split},
    {.name = "slab",
     .description = "a dense slab (sigma_t x100) across [4, 5] of a thin medium, from callbacks, sky light",
     .params = &slab_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 0,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = slab_print, .build = slab_build,
     .integrand = slab_integrand, .split_points = slab_split},
    {.name = "cloud",
     .description = "an optically thick heterogeneous cloud (sigma_t T ~ 100, 250, 500) from callbacks, directional light",
     .params = &cloud_scene, .t0 = 0.0, .t1 = 10.0, .smooth = 1,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = cloud_print, .build = cloud_build,
     .integrand = cloud_integrand, .ref_panel = 0.005L},
    {.name = "dense",
     .description = "a dense smooth front at the start of a long ray (sigma_t x200 within 0.2 of t0, [0, 30]) from callbacks, sky light",
     .params = &dense_scene, .t0 = 0.0, .t1 = 30.0, .smooth = 1,
     .natural_warp = BENCH_WARP_DISTANCE, .print_params = dense_print, .build = dense_build,
     .integrand = dense_integrand, .ref_panel = 0.025L},
};

const int bench_scene_count = (int)(sizeof bench_scenes / sizeof bench_scenes[0]);

int bench_scene_breaks(const bench_scene *sc, hrm_real out[2])
{
    const occluder_params *p;
    hrm_real origin[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, light[3], centre[3];
    int i, n = 0;
    if (strcmp(sc->name, "slab") == 0) { /* the faces, as a renderer knows them */
        out[0] = (hrm_real)slab_scene.lo;
        out[1] = (hrm_real)slab_scene.hi;
        return 2;
    }
    if (strcmp(sc->name, "occluder") != 0) return 0;
    p = (const occluder_params *)sc->params;
    light[0] = (hrm_real)p->light.delta;
    light[1] = (hrm_real)p->light.D;
    light[2] = 0;
    for (i = 0; i < 3; ++i) centre[i] = (hrm_real)p->centre[i];
    if (hrm_sphere_breaks(origin, dir, light, centre, (hrm_real)p->radius, (hrm_real)sc->t0,
                          (hrm_real)sc->t1, out, &n) != HRM_OK)
        return 0;
    return n;
}
