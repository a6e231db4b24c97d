/* bench/shadow.c - shadow rays: what hrm_transmittance's estimator pays
   in density lookups for an accuracy of Tr, against what renderers march
   by hand, on four media. Part of `make bench` (build/bench_shadow);
   writes its tables on stdout and to OUTDIR/shadow.md.

   Media (each in the unit ball, density 0 outside):
     smooth   three wide Gaussian blobs (no feature below 0.3)
     smoke    exp(2 fBm): 5 octaves of value noise, each twice the
              frequency of the last (finest lattice 0.07), faded out over
              the ball's outer fifth
     voxels   a 32^3 grid of hashed densities, trilinear between voxel
              centres (a kink at every voxel face)
     spheres  16 hard-edged spheres (radii 0.04-0.25, densities 1-6,
              overlaps adding) in a background of 0.2: jumps
   Rays: 2000 random points of the ball towards random points of it,
   the density scaled so that tau along most rays is 0.2-5; rays with
   Tr < 1e-2 left out. Reference: composite 8-point Gauss-Legendre on
   4096 panels (on voxels, cut at every voxel face: exact for the cubic a
   trilinear field is along a line; on spheres, cut where the ray enters
   and leaves each), checked against 2048 panels.

   Per ray and configuration: density lookups and the relative error of
   Tr. Configurations:
     hrm tol X      hrm_transmittance with options.tr_tol = X (method 0),
                    medium.feature given (smoke 0.07, voxels 1/32,
                    spheres 0.08, the least diameter; the last such row
                    at 1e-3 without it); the
                    last columns: of the rays beyond it, those returned
                    HRM_OK; the count (not share) of HRM_OK answers beyond 3
                    tolerances (silent, as every bench table counts them)
     trapezoid N    a uniform march, sigma at N + 1 points
     midpoint N     Hillaire's march: sigma at each step's midpoint
     ratio k        ratio tracking (unbiased; majorant the largest
                    density on the ray times k, free-flight samples by
                    exponential steps), its RMS error over 16 runs
   and, per ray, the fewest trapezoid points that reach each target
   ("oracle": told the step that happens to reach it).

   usage: bench_shadow [outdir] */
#define HRM_IMPLEMENTATION
#include "hrm.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NRAYS 2000
#define GLN 8
#define GRID 32

enum { SMOOTH, SMOKE, VOXELS, SPHERES, NMEDIA };
static const char *const medium_name[NMEDIA] = {"smooth", "smoke", "voxels", "spheres"};
#define NSPH 16

typedef struct medium {
    int kind;
    double scale;            /* density scale */
    float grid[GRID * GRID * GRID];
    double sc[NSPH][3], sr[NSPH], sv[NSPH]; /* spheres: centre, radius, density */
} medium;

typedef struct ray {
    const medium *m;
    double o[3], d[3];
    long lookups;
} ray;

static uint64_t mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15u;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static double unit(uint64_t *z)
{
    *z = mix64(*z);
    return (double)(*z >> 11) * (1.0 / 9007199254740992.0);
}

static double lattice(long x, long y, long z)
{
    uint64_t h = mix64((uint64_t)x * 0x8da6b343u ^ (uint64_t)y * 0xd8163841u ^ (uint64_t)z * 0xcb1ab31fu);
    return (double)(h & 0xffffffu) / (double)0x800000u - 1;
}

static double value_noise(const double p[3])
{
    double u[3], v = 0;
    long c[3];
    int i, k;
    for (i = 0; i < 3; ++i) {
        double fl = floor(p[i]), f = p[i] - fl;
        c[i] = (long)fl;
        u[i] = f * f * f * (f * (f * 6 - 15) + 10);
    }
    for (k = 0; k < 8; ++k) {
        double w = 1;
        for (i = 0; i < 3; ++i) w *= (k >> i) & 1 ? u[i] : 1 - u[i];
        v += w * lattice(c[0] + (k & 1), c[1] + ((k >> 1) & 1), c[2] + ((k >> 2) & 1));
    }
    return v;
}

static double smoothstep(double e0, double e1, double x)
{
    double u = (x - e0) / (e1 - e0);
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    return u * u * (3 - 2 * u);
}

/* The density at p (no count). */
static double density(const medium *m, const double p[3])
{
    double r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    if (r2 >= 1) return 0;
    if (m->kind == SMOOTH) {
        static const double c[3][4] = {{0.3, 0.1, -0.2, 0.35}, {-0.35, -0.2, 0.1, 0.4}, {0.05, 0.4, 0.3, 0.3}};
        double v = 0;
        int k;
        for (k = 0; k < 3; ++k) {
            double dx = p[0] - c[k][0], dy = p[1] - c[k][1], dz = p[2] - c[k][2];
            v += exp(-(dx * dx + dy * dy + dz * dz) / (2 * c[k][3] * c[k][3]));
        }
        return m->scale * v * smoothstep(1, 0.8, sqrt(r2));
    }
    if (m->kind == SMOKE) {
        double n = 0, amp = 1, f = 1.9, x[3];
        int o, i;
        for (o = 0; o < 5; ++o) {
            for (i = 0; i < 3; ++i) x[i] = p[i] * f + 17.3 * o + 0.5 * i;
            n += amp * value_noise(x);
            amp *= 0.5;
            f *= 2.03;
        }
        return m->scale * exp(2.0 * n / 1.9375) * smoothstep(1, 0.8, sqrt(r2));
    }
    if (m->kind == SPHERES) {
        /* a thin background and hard-edged spheres, overlaps adding */
        double v = 0.2;
        int k, i;
        for (k = 0; k < NSPH; ++k) {
            double q = 0;
            for (i = 0; i < 3; ++i) q += (p[i] - m->sc[k][i]) * (p[i] - m->sc[k][i]);
            if (q < m->sr[k] * m->sr[k]) v += m->sv[k];
        }
        return m->scale * v;
    }
    {
        /* trilinear between voxel centres of the grid over [-1, 1]^3 */
        double g[3], f[3], v = 0;
        int c[3], i, k;
        for (i = 0; i < 3; ++i) {
            g[i] = (p[i] + 1) * 0.5 * GRID - 0.5;
            if (g[i] < 0) g[i] = 0;
            if (g[i] > GRID - 1.000001) g[i] = GRID - 1.000001;
            c[i] = (int)g[i];
            f[i] = g[i] - c[i];
        }
        for (k = 0; k < 8; ++k) {
            double w = 1;
            int x = c[0] + (k & 1), y = c[1] + ((k >> 1) & 1), z = c[2] + ((k >> 2) & 1);
            for (i = 0; i < 3; ++i) w *= (k >> i) & 1 ? f[i] : 1 - f[i];
            v += w * (double)m->grid[(z * GRID + y) * GRID + x];
        }
        return m->scale * v;
    }
}

static double lookup(ray *r, double t)
{
    double p[3];
    int i;
    for (i = 0; i < 3; ++i) p[i] = r->o[i] + t * r->d[i];
    r->lookups++;
    return density(r->m, p);
}

static void sigma_t(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    double v = lookup((ray *)user, (double)t);
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)v;
}

/* Gauss-Legendre nodes and weights (Newton on P_n). */
static void gl_rule(double x[GLN], double w[GLN])
{
    int j, it, m;
    for (j = 0; j < GLN; ++j) {
        double z = -cos(3.14159265358979323846 * (j + 0.75) / (GLN + 0.5)), p0 = 1, p1 = z, dp = 1;
        for (it = 0; it < 100; ++it) {
            p0 = 1;
            p1 = z;
            for (m = 1; m < GLN; ++m) {
                double p2 = ((2 * m + 1) * z * p1 - m * p0) / (m + 1);
                p0 = p1;
                p1 = p2;
            }
            dp = GLN * (z * p1 - p0) / (z * z - 1);
            if (fabs(p1 / dp) < 1e-16) break;
            z -= p1 / dp;
        }
        x[j] = z;
        w[j] = 2 / ((1 - z * z) * dp * dp);
    }
}

/* tau over [0, L] by composite Gauss-Legendre; on voxels every panel
   lies within one voxel (cut at the faces). */
static double ref_tau(const medium *m, const double o[3], const double d[3], double L, int panels)
{
    double x[GLN], w[GLN], cut[4 * GRID + 8 + 4096 * 2 + 2 * NSPH], tau = 0;
    ray r;
    int n = 0, i, j, k;
    gl_rule(x, w);
    memset(&r, 0, sizeof r);
    r.m = m;
    memcpy(r.o, o, sizeof r.o);
    memcpy(r.d, d, sizeof r.d);
    for (k = 0; k <= panels; ++k) cut[n++] = L * k / panels;
    if (m->kind == VOXELS)
        for (i = 0; i < 3; ++i)
            if (fabs(d[i]) > 1e-12)
                for (k = 0; k <= GRID; ++k) {
                    /* voxel centres are the trilinear kinks */
                    double face = -1 + (k + 0.5) * 2.0 / GRID, t = (face - o[i]) / d[i];
                    if (t > 0 && t < L) cut[n++] = t;
                }
    if (m->kind == SPHERES)
        for (k = 0; k < NSPH; ++k) {
            /* the ray's entry and exit of sphere k: |o + t d - c|^2 = r^2 */
            double oc[3], bq = 0, cq = -m->sr[k] * m->sr[k], disc;
            for (i = 0; i < 3; ++i) {
                oc[i] = o[i] - m->sc[k][i];
                bq += oc[i] * d[i];
                cq += oc[i] * oc[i];
            }
            disc = bq * bq - cq;
            if (disc > 0)
                for (i = -1; i <= 1; i += 2) {
                    double t = -bq + i * sqrt(disc);
                    if (t > 0 && t < L) cut[n++] = t;
                }
        }
    /* sort */
    for (i = 1; i < n; ++i) {
        double v = cut[i];
        for (k = i; k > 0 && cut[k - 1] > v; --k) cut[k] = cut[k - 1];
        cut[k] = v;
    }
    for (i = 0; i + 1 < n; ++i) {
        double a = cut[i], b = cut[i + 1], h = (b - a) / 2;
        if (!(b > a)) continue;
        for (j = 0; j < GLN; ++j) tau += h * w[j] * lookup(&r, a + h * (1 + x[j]));
    }
    return tau;
}

typedef struct sample {
    double lookups, err;
} sample;

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* median and 95th percentile of v[0..n) (sorted in place) */
static void quantiles(double *v, int n, double *med, double *p95)
{
    qsort(v, (size_t)n, sizeof *v, by_value);
    *med = v[n / 2];
    *p95 = v[(n * 95) / 100];
}

#define NHRM 6 /* hrm's rows */
#define NCONF 32
typedef struct table {
    const char *name[NCONF];
    double target[NCONF]; /* hrm: its tolerance; others 0 */
    int n;
    double *lk[NCONF], *err[NCONF];
    unsigned char ok[NHRM][NRAYS]; /* hrm: HRM_OK returned */
} table;

static void report(FILE *out, const char *what, int nrays, table *tb, double *oracle[3])
{
    static const double targets[3] = {1e-2, 1e-3, 1e-4};
    double med, p95, emed, ep95;
    int i, k, j;
    fprintf(out, "\n### %s (%d shadow rays with Tr > 1e-2)\n\n", what, nrays);
    fprintf(out, "| configuration | lookups median | p95 | error median | p95 | max | beyond its tolerance | of them HRM_OK "
                 "| beyond 3 tolerances, HRM_OK (silent) |\n");
    fprintf(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (i = 0; i < tb->n; ++i) {
        double mx = 0;
        long beyond = 0, ok = 0, silent = 0;
        for (k = 0; k < nrays; ++k) {
            int miss = tb->target[i] > 0 && tb->err[i][k] > tb->target[i];
            if (tb->err[i][k] > mx) mx = tb->err[i][k];
            beyond += miss;
            ok += miss && tb->ok[i][k];
            silent += tb->target[i] > 0 && tb->err[i][k] > 3 * tb->target[i] && tb->ok[i][k];
        }
        quantiles(tb->lk[i], nrays, &med, &p95);
        quantiles(tb->err[i], nrays, &emed, &ep95);
        fprintf(out, "| %s | %.0f | %.0f | %.2g | %.2g | %.2g |", tb->name[i], med, p95, emed, ep95, mx);
        if (tb->target[i] > 0)
            fprintf(out, " %.1f%% | %.1f%% | %ld |\n", 100.0 * (double)beyond / nrays, 100.0 * (double)ok / nrays, silent);
        else
            fprintf(out, " - | - | - |\n");
    }
    fprintf(out, "\nOracle: per ray, the fewest trapezoid points that reach the error (told the step):");
    for (j = 0; j < 3; ++j) {
        quantiles(oracle[j], nrays, &med, &p95);
        fprintf(out, "%s %.0e median %.0f, p95 %.0f", j ? ";" : "", targets[j], med, p95);
    }
    fprintf(out, ".\n");
}

int main(int argc, char **argv)
{
    static const double tols[NHRM] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-3};
    static const int Ns[8] = {4, 8, 16, 32, 64, 128, 256, 512};
    static const double majorant[3] = {1, 2, 4};
    static const char *const hrm_names[NHRM] = {"hrm tol 1e-1", "hrm tol 1e-2", "hrm tol 1e-3", "hrm tol 1e-4",
                                                "hrm tol 1e-5", "hrm tol 1e-3, feature not given"};
    static const double scales[NMEDIA] = {1.6, 1.0, 1.5, 1.0};
    static const double features[NMEDIA] = {0, 0.07, 1.0 / GRID, 0.08};
    char names[NCONF][32], path[512];
    const char *dir = argc > 1 ? argv[1] : "bench/out";
    FILE *md;
    medium *m = (medium *)malloc(sizeof *m);
    double worst_ref = 0;
    int kind, i;
    if (!m) return 1;
    snprintf(path, sizeof path, "%s/shadow.md", dir);
    md = fopen(path, "w");
    if (!md) {
        fprintf(stderr, "bench_shadow: cannot write %s\n", path);
        return 3;
    }
    fprintf(md, "## Shadow rays: density lookups for an accuracy of Tr\n\n"
                "`build/bench_shadow` (part of `make bench`); bench/shadow.c says what each row is. "
                "Errors relative to Tr; lookups per ray.\n");
    for (kind = 0; kind < NMEDIA; ++kind) {
        static table tb;
        double *oracle[3];
        int nrays = 0, attempts;
        uint64_t z = 12345u + (uint64_t)kind;
        memset(m, 0, sizeof *m);
        m->kind = kind;
        m->scale = scales[kind];
        for (i = 0; i < GRID * GRID * GRID; ++i) {
            z = mix64(z);
            m->grid[i] = (float)(2.0 * (double)(z >> 40) / (double)(1u << 24));
        }
        for (i = 0; i < NSPH; ++i) {
            /* inside the ball: centres within 0.8, radii 0.04-0.25 (the
               thinnest feature a diameter of 0.08), densities 1-6 */
            int c;
            do {
                for (c = 0; c < 3; ++c) m->sc[i][c] = unit(&z) * 1.6 - 0.8;
            } while (m->sc[i][0] * m->sc[i][0] + m->sc[i][1] * m->sc[i][1] + m->sc[i][2] * m->sc[i][2] > 0.64);
            m->sr[i] = 0.04 + 0.21 * unit(&z);
            m->sv[i] = 1 + 5 * unit(&z);
        }
        memset(&tb, 0, sizeof tb);
        for (i = 0; i < NHRM; ++i) {
            tb.name[tb.n] = hrm_names[i];
            tb.target[tb.n++] = tols[i];
        }
        for (i = 0; i < 8; ++i) {
            snprintf(names[tb.n], sizeof names[0], "trapezoid %d", Ns[i]);
            tb.name[tb.n] = names[tb.n];
            tb.n++;
        }
        for (i = 0; i < 8; ++i) {
            snprintf(names[tb.n], sizeof names[0], "midpoint %d", Ns[i]);
            tb.name[tb.n] = names[tb.n];
            tb.n++;
        }
        for (i = 0; i < 3; ++i) {
            snprintf(names[tb.n], sizeof names[0], "ratio tracking x%g", majorant[i]);
            tb.name[tb.n] = names[tb.n];
            tb.n++;
        }
        for (i = 0; i < tb.n; ++i) {
            tb.lk[i] = (double *)calloc(NRAYS, sizeof(double));
            tb.err[i] = (double *)calloc(NRAYS, sizeof(double));
        }
        for (i = 0; i < 3; ++i) oracle[i] = (double *)calloc(NRAYS, sizeof(double));
        z = 777u + (uint64_t)kind;
        for (attempts = 0; nrays < NRAYS && attempts < 20 * NRAYS; ++attempts) {
            double a[3], b[3], d[3], L, tau, tau2, tr, dmax = 0;
            ray r;
            hrm_medium hm;
            hrm_options o;
            hrm_real T[HRM_CHANNELS];
            int k, c, j;
            for (c = 0; c < 3; ++c) {
                a[c] = unit(&z) * 2 - 1;
                b[c] = unit(&z) * 2 - 1;
            }
            if (a[0] * a[0] + a[1] * a[1] + a[2] * a[2] >= 1 || b[0] * b[0] + b[1] * b[1] + b[2] * b[2] >= 1)
                continue;
            for (c = 0; c < 3; ++c) d[c] = b[c] - a[c];
            L = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (L < 0.05) continue;
            for (c = 0; c < 3; ++c) d[c] /= L;
            tau = ref_tau(m, a, d, L, 4096);
            tr = exp(-tau);
            if (tr < 1e-2) continue;
            tau2 = ref_tau(m, a, d, L, 2048);
            if (fabs(exp(-tau2) - tr) / tr > worst_ref) worst_ref = fabs(exp(-tau2) - tr) / tr;
            memset(&r, 0, sizeof r);
            r.m = m;
            memcpy(r.o, a, sizeof r.o);
            memcpy(r.d, d, sizeof r.d);
            /* hrm's estimator */
            memset(&hm, 0, sizeof hm);
            hm.user = &r;
            hm.sigma_t = sigma_t;
            hm.feature = (hrm_real)features[kind];
            for (i = 0; i < NHRM; ++i) {
                memset(&o, 0, sizeof o);
                o.tr_tol = (hrm_real)tols[i];
                hm.feature = i == NHRM - 1 ? 0 : (hrm_real)features[kind];
                r.lookups = 0;
                tb.ok[i][nrays] = hrm_transmittance(&hm, 0, (hrm_real)L, &o, T, NULL) == HRM_OK;
                tb.lk[i][nrays] = (double)r.lookups;
                tb.err[i][nrays] = fabs((double)T[0] - tr) / tr;
            }
            /* trapezoid and midpoint marches */
            for (j = 0; j < 8; ++j) {
                double h = L / Ns[j], s = 0;
                r.lookups = 0;
                for (k = 0; k <= Ns[j]; ++k) s += (k == 0 || k == Ns[j] ? 0.5 : 1) * lookup(&r, h * k);
                tb.lk[NHRM + j][nrays] = (double)r.lookups;
                tb.err[NHRM + j][nrays] = fabs(exp(-s * h) - tr) / tr;
                r.lookups = 0;
                s = 0;
                for (k = 0; k < Ns[j]; ++k) s += lookup(&r, h * (k + 0.5));
                tb.lk[NHRM + 8 + j][nrays] = (double)r.lookups;
                tb.err[NHRM + 8 + j][nrays] = fabs(exp(-s * h) - tr) / tr;
            }
            /* ratio tracking with a majorant from the densest of 64
               points (the host's bound of its grid or noise), times k */
            for (k = 0; k <= 64; ++k) {
                double v = lookup(&r, L * k / 64);
                if (v > dmax) dmax = v;
            }
            for (j = 0; j < 3; ++j) {
                double mu = dmax * 1.5 * majorant[j], sq = 0;
                int rep;
                r.lookups = 0;
                for (rep = 0; rep < 16; ++rep) {
                    double t = 0, est = 1;
                    for (;;) {
                        t -= log(1 - unit(&z)) / mu;
                        if (t >= L) break;
                        est *= 1 - lookup(&r, t) / mu;
                    }
                    sq += (est - tr) * (est - tr);
                }
                tb.lk[NHRM + 16 + j][nrays] = (double)r.lookups / 16;
                tb.err[NHRM + 16 + j][nrays] = sqrt(sq / 16) / tr;
            }
            /* the oracle */
            for (j = 0; j < 3; ++j) {
                static const double tg[3] = {1e-2, 1e-3, 1e-4};
                int n;
                for (n = 1; n < 4096; ++n) {
                    double h = L / n, s = 0;
                    for (k = 0; k <= n; ++k) s += (k == 0 || k == n ? 0.5 : 1) * lookup(&r, h * k);
                    if (fabs(exp(-s * h) - tr) / tr <= tg[j]) break;
                }
                oracle[j][nrays] = n + 1;
            }
            nrays++;
        }
        report(stdout, medium_name[kind], nrays, &tb, oracle);
        report(md, medium_name[kind], nrays, &tb, oracle);
        for (i = 0; i < tb.n; ++i) {
            free(tb.lk[i]);
            free(tb.err[i]);
        }
        for (i = 0; i < 3; ++i) free(oracle[i]);
    }
    fprintf(md, "\nReferences: 4096 against 2048 Gauss-Legendre panels differ by at most %.2g relative.\n",
            worst_ref);
    printf("\nshadow rays: references agree to %.2g; wrote %s\n", worst_ref, path);
    fclose(md);
    free(m);
    return worst_ref < 1e-7 ? 0 : 4;
}
