/* bench/sweep.c - silent answers in random scenes: how often an adaptive
   method returns HRM_OK more than 3 rtol off an independent reference (a
   silent answer, the worst defect), and how often it warns on an answer
   within rtol (a false alarm). Part of `make bench` (build/bench_sweep);
   writes its table on stdout and to OUTDIR/sweep.md.

   Three families of camera rays, each solved by every adaptive method with
   its defaults, rtol log-uniform in 1e-5..1e-1 (float: 2e-4..1e-1), the
   fog given as constants and again as one sigma callback:
     fog     thick homogeneous fog (sigma_t 0.1..2, albedo 1/2) past one
             point light (its foot 0.5..4.5 along the ray, 0.01..1 off it;
             the ray 1..11 beyond the foot) with the light's equiangular
             warp (hrm_equiangular_warp); Li the light through the fog,
             P / r^2 e^(-sigma_t r). Reference: 8-point Gauss-Legendre on
             panels graded towards the foot, 64 a piece.
     lights  1 to 3 point or spot lights and 0 to 2 sphere occluders near
             a random ray in fog (sigma_t 0.01..1), described to
             hrm_light_options (its warp and breakpoints; the ray ends at
             the first sphere it meets); Li the host's: visibility, the
             spot's cone with a smoothstep falloff, P / r^2 e^(-sigma_t r).
             Reference: adaptive Simpson in long double between the jumps
             and kinks of Li, found by a scan of 4000 points of the lights'
             states (visible, in the cone, in the falloff) and bisection.
     kinks   an Li whose slope jumps, as a host's shadow ray of a few fixed
             steps makes it where its nodes cross a cloud's edge: Li =
             e^-g(t) over [0, 1], g piecewise linear, 0 up to the first of
             1-3 knots in [0.2, 0.5], its slope rising by 0..60 at each;
             fog sigma_t 0.5..4.5 (albedo 0.9), no warp. Reference: the
             closed form, piece by piece.
     media   heterogeneous media from one sigma callback (media_scene):
             a front at the camera, Gaussian bumps, a slab, on rays 1-30
             long, medium.feature their narrowest; a point light under
             its equiangular warp or a sky light (every other ray the
             distance warp); the slab's faces as breakpoints every other
             ray; then again with the exact Tr as the host's callback.
             Reference: 8-point Gauss-Legendre with tau in closed form,
             panels cut at the slab's faces and graded towards the bumps,
             the front and the light's foot (against 4 times the panels:
             within 7e-9 on every ray).
   usage: bench_sweep [outdir] [rays a family] */
#define HRM_IMPLEMENTATION
#include "hrm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NMETH 6
#define MAXL 3
#define MAXS 2
#define SCAN 4000

static const hrm_method methods[NMETH] = {HRM_NESTED_SIMPSON, HRM_GAUSS_KRONROD,  HRM_DORMAND_PRINCE,
                                          HRM_CASH_KARP,      HRM_VERNER,         HRM_BOGACKI_SHAMPINE};

typedef struct tally {
    long ok, silent, warned, false_alarm, evals, runs;
    double worst; /* the largest error / rtol of an HRM_OK answer */
} tally;

/* The fog: sigma_t and sigma_s, the first member of each family's user
   data. */
typedef struct fogc {
    double st, ss;
} fogc;

static void fog_sigma(void *user, hrm_real t, hrm_real sa[HRM_CHANNELS], hrm_real ss[HRM_CHANNELS])
{
    const fogc *f = (const fogc *)user;
    int c;
    (void)t;
    for (c = 0; c < HRM_CHANNELS; ++c) {
        sa[c] = (hrm_real)(f->st - f->ss);
        ss[c] = (hrm_real)f->ss;
    }
}

/* The camera ray's medium: the fog (the user data's first member) as
   constants or (cb) its sigma callback, Li the family's. */
static hrm_medium fog_medium(void *user, hrm_spectrum_fn li, int cb)
{
    const fogc *f = (const fogc *)user;
    hrm_medium md;
    int c;
    memset(&md, 0, sizeof md);
    md.Li = li;
    md.user = user;
    if (cb) {
        md.sigma = fog_sigma;
    } else {
        md.flags = HRM_MEDIUM_HOMOGENEOUS;
        for (c = 0; c < HRM_CHANNELS; ++c) {
            md.const_sigma_a[c] = (hrm_real)(f->st - f->ss);
            md.const_sigma_s[c] = (hrm_real)f->ss;
        }
    }
    return md;
}

typedef struct scene {
    fogc fog;
    int nl, ns;
    hrm_light L[MAXL];
    hrm_sphere S[MAXS];
    double o[3], d[3];
} scene;

static double uni(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (double)(*s >> 8) / 16777216.0;
}

static double pick_rtol(unsigned *s)
{
    double lo = sizeof(hrm_real) == sizeof(float) ? log10(2e-4) : -5;
    return pow(10, lo + (-1 - lo) * uni(s));
}

static void count(tally *t, hrm_status st, double err, double rtol, long evals)
{
    t->runs++;
    t->evals += evals;
    if (st == HRM_OK) {
        t->ok++;
        if (err > 3 * rtol) t->silent++;
        if (err / rtol > t->worst) t->worst = err / rtol;
    } else if (st > 0) {
        t->warned++;
        if (err <= rtol) t->false_alarm++;
    }
}

/* Every method with its defaults at rtol over [0, t1] of the fog in user
   (fog_medium, Li li, as constants or its callback cb), under warp where
   given, each answer counted against ref. */
static void solve_all(void *user, hrm_spectrum_fn li, int cb, const hrm_warp *warp, double t1, double rtol,
                      double ref, tally t[NMETH])
{
    int m;
    for (m = 0; m < NMETH; ++m) {
        hrm_medium md = fog_medium(user, li, cb);
        hrm_options o = hrm_default_options(methods[m]);
        hrm_result r;
        hrm_status st;
        o.rtol = (hrm_real)rtol;
        if (warp) o.warp = *warp;
        st = hrm_solve(&md, 0, (hrm_real)t1, &o, &r);
        count(&t[m], st, fabs((double)r.L[0] - ref) / ref, rtol, r.stats.evals);
    }
}

/* ---- fog: one point light, its equiangular warp ---- */

typedef struct fog {
    fogc fog; /* albedo 1/2 */
    double delta, D;
} fog;

static double fog_f(const fog *f, double t)
{
    double x = t - f->delta, r2 = x * x + f->D * f->D;
    return f->fog.ss / r2 * exp(-f->fog.st * (sqrt(r2) + t));
}

static void fog_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const fog *f = (const fog *)user;
    double x = (double)t - f->delta, r2 = x * x + f->D * f->D;
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)(exp(-f->fog.st * sqrt(r2)) / r2);
}

/* 8-point Gauss-Legendre (Abramowitz and Stegun 25.4.30) of f on n
   panels of [a, b] */
static double gl8(double (*f)(const void *, double), const void *ctx, double a, double b, int n)
{
    static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    double h = (b - a) / n, sum = 0;
    int i, j;
    for (i = 0; i < n; ++i) {
        double m = a + (i + 0.5) * h;
        for (j = 0; j < 4; ++j) sum += w[j] * (f(ctx, m - 0.5 * h * x[j]) + f(ctx, m + 0.5 * h * x[j]));
    }
    return sum * 0.5 * h;
}

static double fog_fv(const void *f, double t)
{
    return fog_f((const fog *)f, t);
}

static double fog_gl(const fog *f, double a, double b, int n)
{
    return gl8(fog_fv, f, a, b, n);
}

static double fog_ref(const fog *f, double t1)
{
    double cut[48], tot = 0;
    int n = 0, k, j;
    cut[n++] = 0;
    cut[n++] = t1;
    cut[n++] = f->delta;
    for (k = -4; k <= 16; ++k)
        for (j = -1; j <= 1; j += 2) {
            double x = f->delta + j * f->D * pow(2, k);
            if (x > 0 && x < t1) cut[n++] = x;
        }
    for (k = 1; k < n; ++k)
        for (j = k; j > 0 && cut[j] < cut[j - 1]; --j) {
            double x = cut[j];
            cut[j] = cut[j - 1];
            cut[j - 1] = x;
        }
    for (k = 0; k + 1 < n; ++k)
        if (cut[k + 1] > cut[k]) tot += fog_gl(f, cut[k], cut[k + 1], 64);
    return tot;
}

static void run_fog(int rays, int cb, tally t[NMETH])
{
    unsigned seed = 1;
    int i;
    for (i = 0; i < rays; ++i) {
        fog f;
        double t1, rtol, ref;
        hrm_real org[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, lp[3];
        hrm_warp warp;
        f.delta = 0.5 + 4 * uni(&seed);
        f.D = pow(10, -2 + 2 * uni(&seed));
        f.fog.st = pow(10, -1 + 1.3 * uni(&seed));
        f.fog.ss = 0.5 * f.fog.st;
        t1 = f.delta + 1 + 10 * uni(&seed);
        rtol = pick_rtol(&seed);
        ref = fog_ref(&f, t1);
        lp[0] = (hrm_real)f.delta;
        lp[1] = 0;
        lp[2] = (hrm_real)f.D;
        hrm_equiangular_warp(org, dir, lp, &warp);
        solve_all(&f, fog_li, cb, &warp, t1, rtol, ref, t);
    }
}

/* ---- kinks: an Li whose slope jumps ---- */

typedef struct kinks {
    fogc fog; /* albedo 0.9 */
    int nk;
    double k[3], s[4]; /* knots (ascending), g's slope on each piece */
} kinks;

static double kinks_g(const kinks *q, double t)
{
    double g = 0;
    int i;
    for (i = 0; i < q->nk && t > q->k[i]; ++i) g += (q->s[i + 1] - q->s[i]) * (t - q->k[i]);
    return g;
}

static void kinks_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    double v = exp(-kinks_g((const kinks *)user, (double)t));
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)v;
}

/* sigma_s e^-(sigma_t t + g(t)) over [0, 1], g linear on each piece */
static double kinks_ref(const kinks *q)
{
    double L = 0, a = 0;
    int i;
    for (i = 0; i <= q->nk; ++i) {
        double b = i < q->nk ? q->k[i] : 1, r = q->fog.st + q->s[i];
        L += q->fog.ss * exp(-q->fog.st * a - kinks_g(q, a)) * -expm1(-r * (b - a)) / r;
        a = b;
    }
    return L;
}

static void run_kinks(int rays, int cb, tally t[NMETH])
{
    unsigned seed = 3;
    int i, j;
    for (i = 0; i < rays; ++i) {
        kinks q;
        double rtol, ref;
        q.nk = 1 + (int)(3 * uni(&seed));
        if (q.nk > 3) q.nk = 3;
        q.fog.st = 0.5 + 4 * uni(&seed);
        q.fog.ss = 0.9 * q.fog.st;
        for (j = 0; j < q.nk; ++j) q.k[j] = 0.2 + 0.3 * uni(&seed);
        for (j = 1; j < q.nk; ++j) { /* ascending */
            double x = q.k[j];
            int l = j;
            for (; l > 0 && q.k[l - 1] > x; --l) q.k[l] = q.k[l - 1];
            q.k[l] = x;
        }
        q.s[0] = 0;
        for (j = 1; j <= q.nk; ++j) q.s[j] = q.s[j - 1] + 60 * uni(&seed);
        rtol = pick_rtol(&seed);
        ref = kinks_ref(&q);
        solve_all(&q, kinks_li, cb, NULL, 1, rtol, ref, t);
    }
}

/* ---- lights: hrm_light_options on random lights and spheres ---- */

/* Whether the segment from x to the light at v (x + v) crosses sphere s. */
static int blocked(const hrm_sphere *s, const long double x[3], const long double v[3], long double r)
{
    long double oc[3], b = 0, c = 0, disc;
    int j;
    for (j = 0; j < 3; ++j) {
        oc[j] = x[j] - (long double)s->center[j];
        b += oc[j] * v[j] / r;
        c += oc[j] * oc[j];
    }
    c -= (long double)s->radius * (long double)s->radius;
    disc = b * b - c;
    return disc > 0 && -b + sqrtl(disc) > 0 && -b - sqrtl(disc) < r;
}

/* Li at t and, through *state, which lights are visible, in their cone
   and in their falloff (the changes of state are Li's jumps and kinks). */
static long double lights_li(const scene *sc, long double t, unsigned *state)
{
    long double x[3], tot = 0;
    unsigned s = 0;
    int k, j, q;
    for (j = 0; j < 3; ++j) x[j] = (long double)sc->o[j] + t * (long double)sc->d[j];
    for (k = 0; k < sc->nl; ++k) {
        const hrm_light *l = &sc->L[k];
        long double v[3], r2 = 0, r, f = 1;
        int vis = 1;
        for (j = 0; j < 3; ++j) {
            v[j] = (long double)l->position[j] - x[j];
            r2 += v[j] * v[j];
        }
        r = sqrtl(r2);
        if (l->kind == HRM_LIGHT_SPOT) {
            long double ca = 0, cc = cosl((long double)l->cone), cf = cosl((long double)l->falloff);
            for (j = 0; j < 3; ++j) ca += -v[j] / r * (long double)l->direction[j];
            if (ca > cc) s |= 1u << (4 * k);
            if (ca > cf) s |= 2u << (4 * k);
            if (ca <= cc) {
                f = 0;
            } else if (ca < cf) {
                long double u = (ca - cc) / (cf - cc);
                f = u * u * (3 - 2 * u);
            }
        }
        for (q = 0; q < sc->ns; ++q)
            if (blocked(&sc->S[q], x, v, r)) {
                s |= 4u << (4 * k + q);
                vis = 0;
            }
        if (vis && f > 0) tot += f * (long double)l->power / r2 * expl(-(long double)sc->fog.st * r);
    }
    if (state) *state = s;
    return tot;
}

static void lights_hrm_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    double v = (double)lights_li((const scene *)user, (long double)t, NULL);
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)v;
}

static long double lights_f(const scene *sc, long double t)
{
    return (long double)sc->fog.ss * lights_li(sc, t, NULL) * expl(-(long double)sc->fog.st * t);
}

static long double simpson(const scene *sc, long double a, long double b, long double fa, long double fm,
                           long double fb, long double whole, long double eps, int depth)
{
    long double m = (a + b) / 2, lm = (a + m) / 2, rm = (m + b) / 2, flm = lights_f(sc, lm), frm = lights_f(sc, rm);
    long double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth > 45 || fabsl(left + right - whole) <= 15 * eps) return left + right + (left + right - whole) / 15;
    return simpson(sc, a, m, fa, flm, fm, left, eps / 2, depth + 1) +
           simpson(sc, m, b, fm, frm, fb, right, eps / 2, depth + 1);
}

/* The reference on [0, t1]: pts holds SCAN + 64 + 2 abscissae. */
static double lights_ref(const scene *sc, double t1, long double *pts)
{
    long double tot = 0, prev = 0;
    unsigned sp, s;
    int n = 0, k, it;
    lights_li(sc, 0, &sp);
    pts[n++] = 0;
    for (k = 1; k <= SCAN; ++k) {
        long double t = (long double)t1 * k / SCAN;
        lights_li(sc, t, &s);
        if (s != sp && n < SCAN) {
            long double a = prev, b = t;
            for (it = 0; it < 80; ++it) {
                long double mid = (a + b) / 2;
                unsigned sm;
                lights_li(sc, mid, &sm);
                if (sm == sp) a = mid;
                else b = mid;
            }
            pts[n++] = (a + b) / 2;
        }
        if (k % (SCAN / 64) == 0 || k == SCAN) pts[n++] = t;
        sp = s;
        prev = t;
    }
    for (k = 0; k + 1 < n; ++k) {
        long double a = pts[k], b = pts[k + 1], fa, fb, fm;
        if (!(b > a)) continue;
        fa = lights_f(sc, a);
        fb = lights_f(sc, b);
        fm = lights_f(sc, (a + b) / 2);
        tot += simpson(sc, a, b, fa, fm, fb, (b - a) / 6 * (fa + 4 * fm + fb),
                       1e-12L * (fabsl(fa) + fabsl(fb) + fabsl(fm)) * (b - a) + 1e-300L, 0);
    }
    return (double)tot;
}

/* A random scene; its ray's end in *t1 (the first sphere it meets); 0 if
   the camera sits in a sphere or the ray is shorter than 0.05. */
static int lights_scene(unsigned *seed, scene *sc, double *t1)
{
    double len;
    int k, j;
    memset(sc, 0, sizeof *sc);
    sc->nl = 1 + (int)(MAXL * uni(seed));
    if (uni(seed) < 0.5) sc->nl = 1;
    sc->ns = (int)(3 * uni(seed));
    for (k = 0; k < 3; ++k) {
        sc->o[k] = -1 + 2 * uni(seed);
        sc->d[k] = -1 + 2 * uni(seed);
    }
    len = sqrt(sc->d[0] * sc->d[0] + sc->d[1] * sc->d[1] + sc->d[2] * sc->d[2]);
    for (k = 0; k < 3; ++k) sc->d[k] /= len;
    *t1 = 1 + 9 * uni(seed);
    sc->fog.st = pow(10, -2 + 2 * uni(seed));
    sc->fog.ss = sc->fog.st * (0.3 + 0.7 * uni(seed));
    for (k = 0; k < sc->nl; ++k) {
        hrm_light *l = &sc->L[k];
        double tf = *t1 * uni(seed), off = pow(10, -2 + 2 * uni(seed)), a[3];
        l->kind = uni(seed) < 0.5 ? HRM_LIGHT_POINT : HRM_LIGHT_SPOT;
        for (j = 0; j < 3; ++j) a[j] = -1 + 2 * uni(seed);
        for (j = 0; j < 3; ++j) l->position[j] = (hrm_real)(sc->o[j] + tf * sc->d[j] + off * a[j]);
        l->power = (hrm_real)(0.5 + 5 * uni(seed));
        if (l->kind == HRM_LIGHT_SPOT) {
            double ax[3], al = 0;
            for (j = 0; j < 3; ++j) {
                ax[j] = -1 + 2 * uni(seed);
                al += ax[j] * ax[j];
            }
            al = sqrt(al);
            for (j = 0; j < 3; ++j) l->direction[j] = (hrm_real)(ax[j] / al);
            l->cone = (hrm_real)(0.2 + 1.2 * uni(seed));
            l->falloff = (hrm_real)((double)l->cone * uni(seed));
        }
    }
    for (k = 0; k < sc->ns; ++k) {
        double tf = *t1 * uni(seed);
        for (j = 0; j < 3; ++j) sc->S[k].center[j] = (hrm_real)(sc->o[j] + tf * sc->d[j] + 1.5 * (-1 + 2 * uni(seed)));
        sc->S[k].radius = (hrm_real)(0.05 + 0.5 * uni(seed));
    }
    for (k = 0; k < sc->ns; ++k) {
        double oc[3], b = 0, c = 0, disc, r = (double)sc->S[k].radius;
        for (j = 0; j < 3; ++j) {
            oc[j] = sc->o[j] - (double)sc->S[k].center[j];
            b += oc[j] * sc->d[j];
            c += oc[j] * oc[j];
        }
        c -= r * r;
        disc = b * b - c;
        if (c <= 0) return 0;
        if (disc > 0 && -b - sqrt(disc) > 0 && -b - sqrt(disc) < *t1) *t1 = -b - sqrt(disc);
    }
    return *t1 >= 0.05;
}

static void run_lights(int rays, int cb, tally t[NMETH], long double *pts)
{
    unsigned seed = 3;
    int i, m;
    for (i = 0; i < rays; ++i) {
        scene sc;
        double t1, rtol, ref;
        hrm_real org[3], dir[3];
        int k;
        if (!lights_scene(&seed, &sc, &t1)) continue;
        rtol = pick_rtol(&seed);
        ref = lights_ref(&sc, t1, pts);
        if (!(ref > 0)) continue;
        for (k = 0; k < 3; ++k) {
            org[k] = (hrm_real)sc.o[k];
            dir[k] = (hrm_real)sc.d[k];
        }
        for (m = 0; m < NMETH; ++m) {
            hrm_medium md = fog_medium(&sc, lights_hrm_li, cb);
            hrm_options o = hrm_default_options(methods[m]);
            hrm_ray_plan plan;
            hrm_result r;
            hrm_status st;
            o.rtol = (hrm_real)rtol;
            if (hrm_light_options(sc.L, sc.nl, sc.S, sc.ns, org, dir, 0, (hrm_real)t1, &plan, &o) != HRM_OK) continue;
            st = hrm_solve(&md, 0, (hrm_real)t1, &o, &r);
            count(&t[m], st, fabs((double)r.L[0] - ref) / ref, rtol, r.stats.evals);
        }
    }
}

/* ---- media: heterogeneous media from callbacks ---- */

typedef struct media {
    double T, base, alb;
    int nb;
    double bc[3], bw[3], ba[3];  /* Gaussian bumps: centre, width, height */
    double sa, sb, sd;           /* a slab (sd 0: none) */
    double fa, fw;               /* a front at t = 0 (fa 0: none) */
    double lc, lD, lp;           /* a point light (lp 0: the sky) */
} media;

#define SQRT_PI_2 0.88622692545275801 /* sqrt(pi) / 2 */

static double media_sigma_t(const media *q, double t)
{
    double v = q->base, x;
    int k;
    for (k = 0; k < q->nb; ++k) {
        x = (t - q->bc[k]) / q->bw[k];
        v += q->ba[k] * exp(-x * x);
    }
    if (t >= q->sa && t < q->sb) v += q->sd;
    x = t / q->fw;
    return v + q->fa * exp(-x * x);
}

/* tau(0, t) in closed form */
static double media_tau(const media *q, double t)
{
    double tau = q->base * t, lo = t < q->sa ? t : q->sa, hi = t < q->sb ? t : q->sb;
    int k;
    for (k = 0; k < q->nb; ++k)
        tau += q->ba[k] * q->bw[k] * SQRT_PI_2 * (erf((t - q->bc[k]) / q->bw[k]) + erf(q->bc[k] / q->bw[k]));
    tau += q->sd * (hi - lo);
    return tau + q->fa * q->fw * SQRT_PI_2 * erf(t / q->fw);
}

static double media_li_of(const media *q, double t)
{
    double x = t - q->lc;
    return q->lp > 0 ? q->lp / (q->lD * q->lD + x * x) : 1 + 0.5 * sin(1.3 * t);
}

static void media_sigma(void *user, hrm_real t, hrm_real sa[HRM_CHANNELS], hrm_real ss[HRM_CHANNELS])
{
    const media *q = (const media *)user;
    double v = media_sigma_t(q, (double)t);
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) {
        sa[c] = (hrm_real)((1 - q->alb) * v);
        ss[c] = (hrm_real)(q->alb * v);
    }
}

static void media_tr(void *user, hrm_real ta, hrm_real tb, hrm_real out[HRM_CHANNELS])
{
    const media *q = (const media *)user;
    double tr = exp(-(media_tau(q, (double)tb) - media_tau(q, (double)ta)));
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)tr;
}

static void media_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    double v = media_li_of((const media *)user, (double)t);
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)v;
}

static double media_f(const void *p, double t)
{
    const media *q = (const media *)p;
    return q->alb * media_sigma_t(q, t) * media_li_of(q, t) * exp(-media_tau(q, t));
}

/* 8-point Gauss-Legendre on n panels of each piece between cuts at the
   slab's faces and graded towards each bump, the front and the light */
static double media_ref(const media *q, int n)
{
    double cut[80], tot = 0;
    int nc = 0, k, j, l;
    cut[nc++] = 0;
    cut[nc++] = q->T;
    if (q->sd > 0) {
        cut[nc++] = q->sa;
        cut[nc++] = q->sb;
    }
    for (k = 0; k < 5; ++k)
        for (j = -1; j <= 1; j += 2) {
            double g = pow(2, k - 2);
            for (l = 0; l < q->nb; ++l) cut[nc++] = q->bc[l] + j * g * q->bw[l];
            if (q->fa > 0 && j > 0) cut[nc++] = g * q->fw;
        }
    if (q->lp > 0)
        for (k = -4; k <= 4; ++k)
            for (j = -1; j <= 1; j += 2) cut[nc++] = q->lc + j * q->lD * pow(2, k);
    for (k = 0; k < nc; ++k) cut[k] = cut[k] < 0 ? 0 : cut[k] > q->T ? q->T : cut[k];
    for (k = 1; k < nc; ++k)
        for (j = k; j > 0 && cut[j] < cut[j - 1]; --j) {
            double y = cut[j];
            cut[j] = cut[j - 1];
            cut[j - 1] = y;
        }
    for (k = 0; k + 1 < nc; ++k)
        if (cut[k + 1] > cut[k]) tot += gl8(media_f, q, cut[k], cut[k + 1], n);
    return tot;
}

/* A ray 1-30 long: sigma_t a base 0.02-0.32, 0-3 Gaussian bumps 0.01-0.51
   wide up to 5 high, a slab 3 in 10 (up to 3 more), a front at t = 0 4 in
   10 (up to 20 high, 0.05-0.55 wide), albedo 0.5-0.95; a point light
   0.05-0.55 from the ray 4 in 10, else a sky light 1 + 0.5 sin 1.3t;
   medium.feature the narrowest of them. */
static void media_scene(unsigned *seed, media *q)
{
    int k;
    memset(q, 0, sizeof *q);
    q->T = 1 + 29 * uni(seed);
    q->base = 0.02 + 0.3 * uni(seed);
    q->alb = 0.5 + 0.45 * uni(seed);
    q->nb = (int)(4 * uni(seed));
    if (q->nb > 3) q->nb = 3;
    for (k = 0; k < q->nb; ++k) {
        q->bc[k] = q->T * uni(seed);
        q->bw[k] = 0.01 + 0.5 * uni(seed);
        q->ba[k] = 5 * uni(seed) * uni(seed);
    }
    if (uni(seed) < 0.3) {
        q->sa = 0.9 * q->T * uni(seed);
        q->sb = q->sa + 0.02 + 0.2 * q->T * uni(seed);
        if (q->sb > q->T) q->sb = q->T;
        q->sd = 3 * uni(seed);
    }
    if (uni(seed) < 0.4) {
        q->fa = 20 * uni(seed);
        q->fw = 0.05 + 0.5 * uni(seed);
    } else {
        q->fw = 1; /* (no front: fa 0) */
    }
    if (uni(seed) < 0.4) {
        q->lc = q->T * uni(seed);
        q->lD = 0.05 + 0.5 * uni(seed);
        q->lp = 0.05 + uni(seed);
    }
}

/* Each ray under its light's warp (a sky light's: the distance warp
   every other ray, else none), the slab's faces as breakpoints every
   other ray; tr: the exact Tr given as the host's callback. */
static void run_media(int rays, int tr, tally t[NMETH])
{
    unsigned seed = 5;
    int i, m, k;
    for (i = 0; i < rays; ++i) {
        media q;
        double rtol, ref, fw = 1e30;
        hrm_real brk[2];
        media_scene(&seed, &q);
        rtol = pick_rtol(&seed);
        ref = media_ref(&q, 8);
        if (!(ref > 0)) continue;
        for (k = 0; k < q.nb; ++k) fw = q.bw[k] < fw ? q.bw[k] : fw;
        if (q.fa > 0 && q.fw < fw) fw = q.fw;
        if (q.sd > 0 && q.sb - q.sa < fw) fw = q.sb - q.sa;
        brk[0] = (hrm_real)q.sa;
        brk[1] = (hrm_real)q.sb;
        for (m = 0; m < NMETH; ++m) {
            hrm_medium md;
            hrm_options o = hrm_default_options(methods[m]);
            hrm_result r;
            hrm_status st;
            memset(&md, 0, sizeof md);
            md.user = &q;
            md.sigma = media_sigma;
            md.transmittance = tr ? media_tr : NULL;
            md.Li = media_li;
            md.feature = fw < 1e30 ? (hrm_real)fw : 0;
            o.rtol = (hrm_real)rtol;
            if (q.lp > 0) {
                o.warp.kind = HRM_WARP_EQUIANGULAR;
                o.warp.delta = (hrm_real)q.lc;
                o.warp.D = (hrm_real)q.lD;
            } else if (i % 2) {
                o.warp.kind = HRM_WARP_DISTANCE;
            }
            if (q.sd > 0 && q.sa > 0 && q.sb < q.T && i % 2 == 0) {
                o.breaks = brk;
                o.nbreaks = 2;
            }
            st = hrm_solve(&md, 0, (hrm_real)q.T, &o, &r);
            count(&t[m], st, fabs((double)r.L[0] - ref) / ref, rtol, r.stats.evals);
        }
    }
}

static void report(FILE *f, const char *name, int rays, const tally t[NMETH])
{
    int m;
    fprintf(f, "\n### %s (%d rays)\n\n", name, rays);
    fprintf(f, "| method | runs | HRM_OK | silent (> 3 rtol) | worst HRM_OK / rtol | warned | false alarms (within rtol) "
               "| evaluations, mean |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (m = 0; m < NMETH; ++m)
        fprintf(f, "| %s | %ld | %ld | %ld | %.3g | %ld | %ld | %.1f |\n", hrm_method_name(methods[m]), t[m].runs,
                t[m].ok, t[m].silent, t[m].worst, t[m].warned, t[m].false_alarm,
                t[m].runs ? (double)t[m].evals / (double)t[m].runs : 0.0);
}

int main(int argc, char **argv)
{
    static const char *const form[2] = {"constants", "sigma callback"};
    const char *dir = argc > 1 ? argv[1] : "bench/out";
    int rays = argc > 2 ? atoi(argv[2]) : 4000, k, cb;
    tally fog_t[2][NMETH], light_t[2][NMETH], kink_t[2][NMETH], media_t[2][NMETH];
    long double *pts = (long double *)malloc(sizeof(long double) * (SCAN + 66));
    char path[1024], name[160];
    FILE *f;
    if (!pts || rays < 1) return 2;
    memset(fog_t, 0, sizeof fog_t);
    memset(light_t, 0, sizeof light_t);
    memset(kink_t, 0, sizeof kink_t);
    memset(media_t, 0, sizeof media_t);
    for (cb = 0; cb < 2; ++cb) {
        run_fog(rays, cb, fog_t[cb]);
        run_lights(rays, cb, light_t[cb], pts);
        run_kinks(rays, cb, kink_t[cb]);
        run_media(rays, cb, media_t[cb]);
    }
    free(pts);
    snprintf(path, sizeof path, "%s/sweep.md", dir);
    f = fopen(path, "w");
    for (k = 0; k < 2; ++k) {
        FILE *out = k ? f : stdout;
        if (!out) continue;
        fprintf(out, "## Silent answers in random scenes (hrm_real %s)\n\n`build/bench_sweep` (part of `make bench`); "
                     "bench/sweep.c says what each family is. Each ray at one rtol, log-uniform in %s..1e-1, every "
                     "adaptive method with its defaults; the fog as constants, then as a sigma callback (media: a sigma "
                     "callback, then with the exact Tr too).\n",
                sizeof(hrm_real) == sizeof(float) ? "float" : "double",
                sizeof(hrm_real) == sizeof(float) ? "2e-4" : "1e-5");
        for (cb = 0; cb < 2; ++cb) {
            snprintf(name, sizeof name, "fog: thick fog past a point light, its equiangular warp; %s", form[cb]);
            report(out, name, rays, fog_t[cb]);
        }
        for (cb = 0; cb < 2; ++cb) {
            snprintf(name, sizeof name, "lights: 1-3 point and spot lights, 0-2 spheres, hrm_light_options; %s",
                     form[cb]);
            report(out, name, rays, light_t[cb]);
        }
        for (cb = 0; cb < 2; ++cb) {
            snprintf(name, sizeof name, "kinks: an Li whose slope jumps 1-3 times, no warp; %s", form[cb]);
            report(out, name, rays, kink_t[cb]);
        }
        for (cb = 0; cb < 2; ++cb) {
            snprintf(name, sizeof name, "media: fronts, bumps and slabs from a sigma callback%s, a point light "
                     "(its warp) or the sky", cb ? " and the exact Tr" : "");
            report(out, name, rays, media_t[cb]);
        }
    }
    if (!f) {
        fprintf(stderr, "bench_sweep: cannot write %s\n", path);
        return 1;
    }
    fclose(f);
    printf("\nwrote %s\n", path);
    return 0;
}
