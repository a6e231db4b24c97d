/* render.c - `make render`: four scenes rendered by hrm.h the way a
   renderer calls it (one hrm_solve per camera ray, the public API only),
   measured by what a renderer pays at equal image error, against the
   marches production renderers ship and an independent reference.

   Scenes (parameters fixed here and in README.md; later work quotes its
   targets against what this program prints for them)
     shafts  a point light inside a homogeneous medium, four spheres around
             it casting sharp shafts, a back wall (single scattering).
             Shadow rays are analytic (sphere tests and exp(-sigma_t r)).
     cloud   a procedural cloud, optically thick in its core, lit by the
             sun (directional) and a point light; shadow rays through
             hrm_transmittance (Simpson, 4 panels, tau coupled).
     smoke   a spot light (a cone with a smooth falloff, its apex in view,
             on a pixel corner) inside heterogeneous fBm smoke with soft
             edges, a sphere occluder casting a shaft down the beam;
             shadow rays through hrm_transmittance (Simpson, 8 panels,
             tau coupled).
     lamps   four point lights at depths 3 to 11 along the view in a
             homogeneous fog, a wall behind them; shadow rays analytic.
             The four described to hrm_light_options at once (its
             mixture warp, one solve whose Li traces four shadow rays)
             against one solve per lamp described alone (its equiangular
             warp, one shadow ray a Li), at equal traced shadow rays, for
             the image and for each lamp's light (the mixture's share:
             each lamp's solve under the mixture's warp).
   Every scene's shadow rays use these explicit options, shared by its
   reference and every configuration. Each thread gives hrm a workspace
   (options.workspace, WS_BYTES): a camera ray's solve takes
   hrm_workspace_size of it, the shadow rays its Li traces the rest, so
   the solves' deep storage stays off the threads' stacks; the answers
   are those of the stack, bit for bit.

   Baselines: what a renderer author writes by hand, here in this file
   (no library overhead in their cost), each with per-step analytic
   extinction (Hillaire 2015) and one jittered offset per pixel:
     MARCH UNIFORM      N steps uniform in t, one sample each, all lights
     MARCH EQUIANGULAR  N steps uniform in the equiangular angle towards
                        the point or spot light (Kulla and Fajardo 2012),
                        the source times dt/dtheta held constant over a
                        step; in a heterogeneous medium the optical depth
                        from a uniform march of N steps (their decoupled
                        march); a directional light (the cloud's sun) by
                        a uniform march that shares those sigma samples
                        (one march per light, Cycles' way); the lamps
                        one march of N steps each
   Speedups are quoted against the best baseline at each RMSE and cost.

   References: composite Gauss-Legendre (8 nodes a panel) in t, a rule no
   configuration uses, on panels cut at every breakpoint the geometry
   gives (shadow and spot cones, the medium's bounds) and graded towards
   the light's foot on the ray (uniform in asinh((t - t_foot) / D)), the
   optical depth at each node from the same panel's interpolant of
   sigma_t; computed at a panel count and checked against twice it.

   Costs per pixel, counted in this file: Li calls; traced shadow rays
   (Li calls' rays towards a light: outside a spot's cone none); density
   lookups (every evaluation of the density, camera and shadow rays);
   CPU seconds (thread CPU time, summed over threads). Relative RMSE over
   the pixels whose ray meets the medium, twice: without the pixels whose
   ray passes within one pixel's footprint of the point or spot light,
   and over all of them. Per adaptive rung, judged per channel of each
   camera solve's L against the reference's L for the same lights:
   silent (HRM_OK, off by more than 3 rtol |L_ref| + atol) and false
   alarms (a warning, within rtol |L_ref| + atol), in pixels.

   Writes to render/out/ (or argv[1]):
     <scene>_overview.png   reference and each configuration at equal
                            Li calls, with false-colour error maps
     <scene>_equal_time.png the same at equal CPU time
     <scene>_reference.png
     summary.md             every rung, the equal-RMSE tables

   usage: render [outdir [scene [quick]]]   scene: shafts, cloud, smoke,
   lamps or all. Threads: one per processor (sysconf), rows interleaved. */
#define _POSIX_C_SOURCE 200809L
#define HRM_IMPLEMENTATION
#include "hrm.h"
#include "png.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#if HRM_CHANNELS != 3
#error "this example is written for RGB (HRM_CHANNELS 3)"
#endif

#define PI 3.14159265358979323846
#define MAX_RUNGS 12
#define MAX_OCC 6
#define MAX_LIGHTS 4 /* the lamps' */
#define MAX_N 2048   /* the marches' largest step count */
#define WS_BYTES (1u << 19) /* a thread's workspace for hrm: any camera solve
                               and its shadow rays (hrm_workspace_size) */
#define GL_N 8       /* the reference's nodes per panel */
#define MAX_CUTS 32  /* the reference's breakpoints per ray */

/* ======================================================================
   Vectors
   ====================================================================== */
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void sub3(const double a[3], const double b[3], double out[3])
{
    int i;
    for (i = 0; i < 3; ++i) out[i] = a[i] - b[i];
}

static double norm3(double v[3])
{
    double n = sqrt(dot3(v, v));
    int i;
    if (n > 0)
        for (i = 0; i < 3; ++i) v[i] /= n;
    return n;
}

/* Where o + t d (unit d) is inside the sphere (c, r): [ta, tb], or 0. */
static int sphere_span(const double o[3], const double d[3], const double c[3], double r,
                       double *ta, double *tb)
{
    double oc[3], b, q, disc;
    sub3(o, c, oc);
    b = dot3(oc, d);
    q = dot3(oc, oc) - r * r;
    disc = b * b - q;
    if (disc <= 0) return 0;
    disc = sqrt(disc);
    *ta = -b - disc;
    *tb = -b + disc;
    return 1;
}

/* Where o + t d (unit d), t in (t0, t1), crosses the cone of apex A, unit
   axis a and half-angle acos(cosang) (its nappe along +a): ascending into
   out, the count returned (at most 2). The squared equation
   ((w + t d).a)^2 = cos^2 |w + t d|^2, w = o - A, then the nappe kept. */
static int cone_cross(const double o[3], const double d[3], const double A[3], const double a[3],
                      double cosang, double t0, double t1, double out[2])
{
    double w[3], da = 0, wa, qa, qb, qc, c2 = cosang * cosang, disc, r[2];
    int n = 0, k, i;
    sub3(o, A, w);
    da = dot3(d, a);
    wa = dot3(w, a);
    qa = da * da - c2;
    qb = 2 * (wa * da - c2 * dot3(w, d));
    qc = wa * wa - c2 * dot3(w, w);
    if (fabs(qa) < 1e-14) {
        if (qb == 0) return 0;
        r[0] = -qc / qb;
        k = 1;
    } else {
        disc = qb * qb - 4 * qa * qc;
        if (disc < 0) return 0;
        disc = sqrt(disc);
        /* the stable pair of roots */
        {
            double q = -0.5 * (qb + (qb >= 0 ? disc : -disc));
            r[0] = q / qa;
            r[1] = q != 0 ? qc / q : r[0];
        }
        k = 2;
        if (r[1] < r[0]) {
            double x = r[0];
            r[0] = r[1];
            r[1] = x;
        }
    }
    for (i = 0; i < k; ++i)
        if (r[i] > t0 && r[i] < t1 && wa + r[i] * da > 0) out[n++] = r[i];
    return n;
}

static double smoothstep(double e0, double e1, double x)
{
    double u = (x - e0) / (e1 - e0);
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    return u * u * (3 - 2 * u);
}

/* (1 - exp(-x)) / x, its series where x is tiny (Cycles switches at 1e-5) */
static double phi1(double x)
{
    return x < 1e-5 ? 1 - 0.5 * x : -expm1(-x) / x;
}

/* ======================================================================
   Scenes
   ====================================================================== */
enum { SHAFTS, CLOUD, SMOKE, LAMPS };

typedef struct occluder {
    double c[3], r;
} occluder;

/* The reference's rule: Gauss-Legendre nodes x and weights w on [-1, 1],
   and W[j][k], the weight of sigma_t at node k in the integral from -1 to
   node j of their interpolating polynomial. */
typedef struct gl_rule {
    double x[GL_N], w[GL_N], W[GL_N][GL_N];
} gl_rule;

typedef struct scene {
    const char *name;
    int kind;
    int w, h;
    double eye[3], tan_half;  /* camera at eye looking down +z */
    int nlights;              /* lights: bit 0 the point or spot light,
                                 bit 1 the sun (cloud); lamps: bit k
                                 lamp k */
    double light[3], I[3];    /* point light or spot apex, intensity */
    double lamp[MAX_LIGHTS][3], lamp_I[MAX_LIGHTS][3]; /* the lamps */
    occluder occ[MAX_OCC];    /* spheres between the light and the ray */
    int nocc;
    /* shafts: a homogeneous medium and a wall */
    double sa[3], ss[3], st[3];
    double wall_z, wall_albedo[3];
    /* cloud and smoke: a density inside a sphere */
    double cc[3], cr, peak;   /* density support (sphere) and its scale */
    double ka[3], ks[3], kt[3]; /* sigma per unit density */
    double g;                 /* Henyey-Greenstein asymmetry */
    double feature;           /* the medium's thinnest feature (0: none) */
    double sun[3], E[3];      /* cloud: direction to the sun, irradiance */
    double axis[3], cos_in, cos_out; /* smoke: the spot's axis and cone */
    hrm_options shadow;       /* shadow rays through the density */
    int ref_panels;           /* the reference's panels per ray */
    const gl_rule *gl;
} scene;

/* Light l's position: a lamp, or the scene's point or spot light. */
static const double *light_pos(const scene *s, int l)
{
    return s->kind == LAMPS ? s->lamp[l] : s->light;
}

/* Whether the medium is homogeneous (sigma constant, shadow rays and
   optical depths in closed form). */
static int homogeneous(const scene *s)
{
    return s->kind == SHAFTS || s->kind == LAMPS;
}

static void make_shafts(scene *s, int quick)
{
    static const occluder occ[4] = {{{-0.75, 1.25, 5.4}, 0.32},
                                    {{0.85, 1.55, 5.5}, 0.28},
                                    {{0.05, 2.45, 5.2}, 0.26},
                                    {{0.35, 0.95, 6.5}, 0.30}};
    int i;
    memset(s, 0, sizeof *s);
    s->name = "shafts";
    s->kind = SHAFTS;
    s->nlights = 1;
    s->w = quick ? 128 : 256;
    s->h = quick ? 96 : 192;
    s->eye[1] = 0.6;
    s->tan_half = 0.42;
    for (i = 0; i < 3; ++i) {
        s->sa[i] = 0.02;
        s->ss[i] = 0.20 + 0.03 * i; /* a little bluer scattering */
        s->st[i] = s->sa[i] + s->ss[i];
    }
    s->light[0] = 0.05;
    s->light[1] = 1.65;
    s->light[2] = 5.8;
    s->I[0] = 9.0;
    s->I[1] = 8.0;
    s->I[2] = 6.5;
    memcpy(s->occ, occ, sizeof occ);
    s->nocc = 4;
    s->wall_z = 9.0;
    s->wall_albedo[0] = s->wall_albedo[1] = s->wall_albedo[2] = 0.6;
    s->ref_panels = 48;
}

static void make_cloud(scene *s, int quick)
{
    int i;
    memset(s, 0, sizeof *s);
    s->name = "cloud";
    s->kind = CLOUD;
    s->nlights = 2;
    s->w = quick ? 64 : 128;
    s->h = quick ? 48 : 96;
    s->eye[2] = -3.4;
    s->tan_half = 0.40;
    s->cr = 1.15;
    s->peak = 60.0; /* optical depth through the core ~ 60 */
    for (i = 0; i < 3; ++i) {
        s->ka[i] = 0.02;
        s->ks[i] = 0.98;
        s->kt[i] = 1.0;
    }
    s->sun[0] = -0.5;
    s->sun[1] = 0.8;
    s->sun[2] = -0.35;
    norm3(s->sun);
    s->E[0] = 7.8;
    s->E[1] = 7.2;
    s->E[2] = 6.3;
    s->light[0] = 1.45;
    s->light[1] = -0.35;
    s->light[2] = -0.6;
    s->I[0] = 0.9;
    s->I[1] = 0.55;
    s->I[2] = 0.3; /* a warm lamp, lower right */
    s->g = 0.4;
    /* the finest billow (sin 37 q) has a period of 0.2; where the density
       barely exceeds 0 its wisps are 0.02-0.03 wide along a ray */
    s->feature = 0.02;
    s->shadow = hrm_default_options(HRM_SIMPSON);
    s->shadow.steps = 4;
    s->shadow.tau_mode = HRM_TAU_COUPLED;
    s->ref_panels = 96;
}

/* The smoke: fBm inside a sphere of radius 2.1 at z = 6, soft edges (the
   density fades out over the sphere's outer fifth), an optical depth of
   1-5 along most camera rays (67% of those that meet it, median 2.1); a spot light whose apex
   projects onto a pixel corner (at least 0.7 pixel from every pixel
   centre), shining down and to the right, a sphere in its beam. */
static void make_smoke(scene *s, int quick)
{
    static const double axis[3] = {0.42, -1.0, 0.18};
    const double corner_x = 0.375, corner_y = 1.0 / 3, z = 5.5; /* of w, h */
    double aspect;
    int i;
    memset(s, 0, sizeof *s);
    s->name = "smoke";
    s->kind = SMOKE;
    s->nlights = 1;
    s->w = quick ? 64 : 128;
    s->h = quick ? 48 : 96;
    s->tan_half = 0.40;
    aspect = (double)s->w / s->h;
    s->cc[2] = 6.0;
    s->cr = 2.1;
    s->peak = 1.0;
    for (i = 0; i < 3; ++i) {
        s->kt[i] = 1.0;
        s->ks[i] = 0.88 + 0.04 * i;
        s->ka[i] = s->kt[i] - s->ks[i];
    }
    s->g = 0.3;
    /* the apex on the corner (3 w / 8, h / 3): a pixel corner, as both
       are whole numbers of pixels at either size */
    s->light[0] = (2 * corner_x - 1) * s->tan_half * aspect * z;
    s->light[1] = (1 - 2 * corner_y) * s->tan_half * z;
    s->light[2] = z;
    s->I[0] = 30.0;
    s->I[1] = 26.0;
    s->I[2] = 20.0;
    memcpy(s->axis, axis, sizeof axis);
    norm3(s->axis);
    s->cos_in = cos(14.0 * PI / 180);
    s->cos_out = cos(24.0 * PI / 180);
    for (i = 0; i < 3; ++i) s->occ[0].c[i] = s->light[i] + 0.8 * s->axis[i];
    s->occ[0].c[0] += 0.06;
    s->occ[0].r = 0.15;
    s->nocc = 1;
    s->shadow = hrm_default_options(HRM_SIMPSON);
    s->shadow.steps = 8;
    s->shadow.tau_mode = HRM_TAU_COUPLED;
    s->ref_panels = 48;
}

/* Lamps: four point lights at depths 3 to 11 along the view (a street
   of lamps receding into fog), in a homogeneous fog that ends on a wall
   at z = 14 the lamps light; each camera ray passes all four, their
   peaks along it apart. Shadow rays are analytic (exp(-sigma_t r)). */
static void make_lamps(scene *s, int quick)
{
    static const double pos[MAX_LIGHTS][3] = {
        {-0.5, 0.3, 3.0}, {0.7, -0.25, 5.5}, {-0.9, -0.6, 8.0}, {1.2, 0.9, 11.0}};
    static const double I[MAX_LIGHTS][3] = {
        {3.0, 2.6, 2.0}, {5.0, 5.5, 6.5}, {9.0, 8.0, 6.0}, {16.0, 13.0, 10.0}};
    int i;
    memset(s, 0, sizeof *s);
    s->name = "lamps";
    s->kind = LAMPS;
    s->nlights = MAX_LIGHTS;
    s->w = quick ? 64 : 128;
    s->h = quick ? 48 : 96;
    s->tan_half = 0.42;
    for (i = 0; i < 3; ++i) {
        s->sa[i] = 0.015;
        s->ss[i] = 0.10 + 0.02 * i;
        s->st[i] = s->sa[i] + s->ss[i];
    }
    memcpy(s->lamp, pos, sizeof pos);
    memcpy(s->lamp_I, I, sizeof I);
    memcpy(s->light, pos[0], sizeof s->light);
    memcpy(s->I, I[0], sizeof s->I);
    s->wall_z = 14.0;
    s->wall_albedo[0] = s->wall_albedo[1] = s->wall_albedo[2] = 0.5;
    s->ref_panels = 48;
}

/* The cloud's density at p: zero outside the sphere; inside, a soft ball
   (1 - r^2)^2 carved by a few smooth billows, peak at the core. */
static double cloud_density(const scene *s, const double p[3])
{
    double q[3], r2 = 0, b;
    int i;
    for (i = 0; i < 3; ++i) {
        q[i] = (p[i] - s->cc[i]) / s->cr;
        r2 += q[i] * q[i];
    }
    if (r2 >= 1) return 0;
    b = 0.55 + 0.25 * sin(4.1 * q[0] + 1.3) * sin(3.7 * q[1] + 0.4) * sin(4.4 * q[2] + 2.0) +
        0.12 * sin(9.0 * q[0] - 7.0 * q[1] + 0.5) * sin(8.0 * q[2] + 6.0 * q[1]) +
        0.06 * sin(19.0 * q[1] + 13.0 * q[2] + 1.1) * sin(17.0 * q[0] - 11.0 * q[2] + 0.3) +
        0.03 * sin(37.0 * q[0] + 29.0 * q[1] - 2.0) * sin(31.0 * q[2] - 23.0 * q[0] + 0.9);
    /* a sharp-edged iso-surface (a kink where the density reaches 0), a
       thick core, and nothing left at the sphere (r2 = 1: b - 0.04 at
       most), where a jump of sigma would make every shadow ray's last
       node, on the sphere, flip between two values with the rounding of
       r2 */
    b = (1 - r2) * 1.6 + (b - 0.55) * 2.2 - 0.45 - 0.6 * r2 * r2 * r2 * r2;
    return b > 0 ? s->peak * b : 0;
}

/* Value noise: a hash of the lattice corners, quintic interpolation. */
static double lattice(long x, long y, long z)
{
    uint64_t h = (uint64_t)x * 0x8da6b343u + (uint64_t)y * 0xd8163841u + (uint64_t)z * 0xcb1ab31fu;
    h ^= h >> 29;
    h *= 0xbf58476d1ce4e5b9u;
    h ^= h >> 32;
    return (double)(h & 0xffffffu) / (double)0x800000u - 1; /* [-1, 1) */
}

static double value_noise(const double p[3])
{
    double f[3], u[3], v = 0;
    long c[3];
    int i, k;
    for (i = 0; i < 3; ++i) {
        double fl = floor(p[i]);
        c[i] = (long)fl;
        f[i] = p[i] - fl;
        u[i] = f[i] * f[i] * f[i] * (f[i] * (f[i] * 6 - 15) + 10);
    }
    for (k = 0; k < 8; ++k) {
        double wgt = 1;
        for (i = 0; i < 3; ++i) wgt *= (k >> i) & 1 ? u[i] : 1 - u[i];
        v += wgt * lattice(c[0] + (k & 1), c[1] + ((k >> 1) & 1), c[2] + ((k >> 2) & 1));
    }
    return v;
}

/* The smoke's density at p: exp(2 fBm) (5 octaves of value noise, each
   twice the frequency and half the amplitude of the last), faded to 0
   between 0.8 and 1 of the sphere's radius (smoothstep: soft edges,
   sigma C1 everywhere). */
static double smoke_density(const scene *s, const double p[3])
{
    double q[3], r2 = 0, edge, n = 0, amp = 1, f = 1.9;
    int i, o;
    for (i = 0; i < 3; ++i) {
        q[i] = (p[i] - s->cc[i]) / s->cr;
        r2 += q[i] * q[i];
    }
    if (r2 >= 1) return 0;
    edge = smoothstep(1.0, 0.8, sqrt(r2));
    for (o = 0; o < 5; ++o) {
        double x[3];
        for (i = 0; i < 3; ++i) x[i] = q[i] * f + 17.3 * o + 0.5 * i;
        n += amp * value_noise(x);
        amp *= 0.5;
        f *= 2.03;
    }
    return s->peak * edge * exp(2.0 * n / 1.9375);
}

static double hg(double g, double cosang)
{
    double d = 1 + g * g - 2 * g * cosang;
    return (1 - g * g) / (4 * PI * d * sqrt(d));
}

/* ======================================================================
   One camera ray: the medium's callbacks see this as their user pointer
   ====================================================================== */
typedef struct ray {
    const scene *s;
    double o[3], d[3];        /* origin, unit direction */
    int lights;               /* which lights Li sums */
    long li, traced, lookups; /* what the ray cost, counted here */
    long shadow_lookups;      /* of the lookups, those of its shadow rays */
    hrm_status shadow_status; /* the first shadow ray's problem */
    unsigned char *shadow_ws; /* its shadow rays' workspace (the rest of the */
    size_t shadow_ws_size;    /* thread's, past the camera solve's share) */
} ray;

static void point_at(const ray *r, double t, double p[3])
{
    int i;
    for (i = 0; i < 3; ++i) p[i] = r->o[i] + t * r->d[i];
}

/* The density at t: one lookup. */
static double density_at(ray *r, double t)
{
    double p[3];
    point_at(r, t, p);
    r->lookups++;
    return r->s->kind == CLOUD ? cloud_density(r->s, p) : smoke_density(r->s, p);
}

static void dens_sigma(void *user, hrm_real t, hrm_real out[HRM_CHANNELS], const double k[3])
{
    ray *r = (ray *)user;
    double rho = density_at(r, (double)t);
    int c;
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(rho * k[c]);
}
/* sigma_a and sigma_s from one lookup (medium.sigma). */
static void dens_sigma_as(void *user, hrm_real t, hrm_real sa[HRM_CHANNELS], hrm_real ss[HRM_CHANNELS])
{
    ray *r = (ray *)user;
    double rho = density_at(r, (double)t);
    int c;
    for (c = 0; c < 3; ++c) {
        sa[c] = (hrm_real)(rho * r->s->ka[c]);
        ss[c] = (hrm_real)(rho * r->s->ks[c]);
    }
}
static void dens_sigma_t(void *u, hrm_real t, hrm_real o[HRM_CHANNELS])
{
    dens_sigma(u, t, o, ((ray *)u)->s->kt);
}

/* Is the segment from p towards unit direction v, dist long, blocked by
   an occluder? */
static int blocked(const scene *s, const double p[3], const double v[3], double dist)
{
    int k;
    for (k = 0; k < s->nocc; ++k) {
        double ta, tb;
        if (sphere_span(p, v, s->occ[k].c, s->occ[k].r, &ta, &tb) && tb > 0 && ta < dist) return 1;
    }
    return 0;
}

/* Shafts: in-scattered radiance at t (isotropic phase; the point light's
   1/r^2, its attenuation exp(-sigma_t r) and the occluders' shadow). */
static void shafts_Li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    ray *r = (ray *)user;
    const scene *s = r->s;
    double p[3], v[3], dist;
    int c, lit;
    point_at(r, (double)t, p);
    sub3(s->light, p, v);
    dist = norm3(v);
    lit = !blocked(s, p, v, dist);
    r->li++;
    r->traced++;
    for (c = 0; c < 3; ++c)
        out[c] = (hrm_real)(lit ? s->I[c] / (4 * PI * dist * dist) * exp(-s->st[c] * dist) : 0);
}

/* Transmittance from p towards unit direction d over [0, dist] through
   the density's sphere: one shadow ray, its lookups the camera ray's. */
static void shadow_ray(ray *r, const double p[3], const double d[3], double dist, hrm_real Tr[3])
{
    const scene *s = r->s;
    ray sr;
    hrm_medium m;
    hrm_options so;
    double ta, tb;
    hrm_status st;
    Tr[0] = Tr[1] = Tr[2] = 1;
    r->traced++;
    if (!sphere_span(p, d, s->cc, s->cr, &ta, &tb)) return;
    if (ta < 0) ta = 0;
    if (tb > dist) tb = dist;
    if (!(tb > ta)) return;
    memset(&sr, 0, sizeof sr);
    sr.s = s;
    memcpy(sr.o, p, sizeof sr.o);
    memcpy(sr.d, d, sizeof sr.d);
    memset(&m, 0, sizeof m);
    m.user = &sr;
    m.sigma_t = dens_sigma_t;
    so = s->shadow;
    so.workspace = r->shadow_ws;
    so.workspace_size = r->shadow_ws_size;
    st = hrm_transmittance(&m, (hrm_real)ta, (hrm_real)tb, &so, Tr, NULL);
    r->lookups += sr.lookups;
    r->shadow_lookups += sr.lookups;
    if (st != HRM_OK && r->shadow_status == HRM_OK) r->shadow_status = st;
}

/* Cloud: in-scattered radiance at t from the lights r->lights selects
   (Henyey-Greenstein phase), each through its own shadow ray. */
static void cloud_Li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    ray *r = (ray *)user;
    const scene *s = r->s;
    double p[3], v[3], dist;
    hrm_real Tr[3];
    int c;
    point_at(r, (double)t, p);
    r->li++;
    for (c = 0; c < 3; ++c) out[c] = 0;
    if (r->lights & 2) {
        double ph = hg(s->g, dot3(s->sun, r->d));
        shadow_ray(r, p, s->sun, 1e30, Tr);
        for (c = 0; c < 3; ++c) out[c] += (hrm_real)(ph * s->E[c] * (double)Tr[c]);
    }
    if (r->lights & 1) {
        double ph;
        sub3(s->light, p, v);
        dist = norm3(v);
        ph = hg(s->g, dot3(v, r->d));
        shadow_ray(r, p, v, dist, Tr);
        for (c = 0; c < 3; ++c) out[c] += (hrm_real)(ph * s->I[c] / (dist * dist) * (double)Tr[c]);
    }
}

/* Smoke: the spot light's in-scattered radiance at t: no shadow ray
   outside its cone; inside, the occluder's test, then the smoke's. */
static void smoke_Li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    ray *r = (ray *)user;
    const scene *s = r->s;
    double p[3], v[3], dist, cone, ph;
    hrm_real Tr[3];
    int c;
    point_at(r, (double)t, p);
    r->li++;
    for (c = 0; c < 3; ++c) out[c] = 0;
    sub3(s->light, p, v);
    dist = norm3(v);
    cone = smoothstep(s->cos_out, s->cos_in, -dot3(v, s->axis));
    if (!(cone > 0)) return;
    if (blocked(s, p, v, dist)) {
        r->traced++;
        return;
    }
    ph = hg(s->g, dot3(v, r->d));
    shadow_ray(r, p, v, dist, Tr);
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(ph * cone * s->I[c] / (dist * dist) * (double)Tr[c]);
}

/* Lamps: in-scattered radiance at t from the lamps r->lights selects
   (isotropic phase), each a traced shadow ray: 1/r^2 and exp(-sigma_t r). */
static void lamps_Li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    ray *r = (ray *)user;
    const scene *s = r->s;
    double p[3], v[3], dist;
    int c, l;
    point_at(r, (double)t, p);
    r->li++;
    for (c = 0; c < 3; ++c) out[c] = 0;
    for (l = 0; l < s->nlights; ++l) {
        if (!(r->lights & (1 << l))) continue;
        sub3(s->lamp[l], p, v);
        dist = norm3(v);
        r->traced++;
        for (c = 0; c < 3; ++c)
            out[c] += (hrm_real)(s->lamp_I[l][c] / (4 * PI * dist * dist) * exp(-s->st[c] * dist));
    }
}

static hrm_spectrum_fn scene_Li(const scene *s)
{
    return s->kind == SHAFTS ? shafts_Li : s->kind == CLOUD ? cloud_Li : s->kind == SMOKE ? smoke_Li : lamps_Li;
}

/* sigma_t and sigma_s at t for the host's own marches: one lookup. */
static void host_sigma(ray *r, double t, double st[3], double ss[3])
{
    int c;
    if (homogeneous(r->s)) {
        memcpy(st, r->s->st, sizeof r->s->st);
        memcpy(ss, r->s->ss, sizeof r->s->ss);
        return;
    } else {
        double rho = density_at(r, t);
        for (c = 0; c < 3; ++c) {
            st[c] = rho * r->s->kt[c];
            ss[c] = rho * r->s->ks[c];
        }
    }
}

/* ======================================================================
   The production baselines: marches a renderer author writes by hand
   ====================================================================== */
/* The uniform march (Hillaire 2015): N steps over [t0, t1], one sample
   each at the pixel's offset xi in [0, 1), the source constant over the
   step and the extinction integrated exactly: dL = Tr S dt (1 -
   exp(-dtau)) / dtau, Tr *= exp(-dtau), dtau = sigma_t dt at the sample
   (the shafts' sigma_t is constant: Tr exact). lights 0: sigma_t only,
   no Li (the optical depth for the equiangular march). tau, when given,
   receives the optical depth at the N + 1 step ends. */
static void march_uniform(ray *r, double t0, double t1, int N, double xi, int lights, double L[3],
                          double Tr[3], double tau[][3])
{
    double dt = (t1 - t0) / N, st[3], ss[3], acc[3] = {0, 0, 0};
    hrm_real li[3] = {0, 0, 0};
    hrm_spectrum_fn Li = scene_Li(r->s);
    int k, c;
    for (c = 0; c < 3; ++c) L[c] = 0;
    if (tau)
        for (c = 0; c < 3; ++c) tau[0][c] = 0;
    r->lights = lights;
    for (k = 0; k < N; ++k) {
        double ts = t0 + (k + xi) * dt;
        host_sigma(r, ts, st, ss);
        if (lights) Li(r, (hrm_real)ts, li);
        for (c = 0; c < 3; ++c) {
            double dtau = st[c] * dt;
            L[c] += exp(-acc[c]) * ss[c] * (double)li[c] * dt * phi1(dtau);
            acc[c] += dtau;
            if (tau) tau[k + 1][c] = acc[c];
        }
    }
    for (c = 0; c < 3; ++c) Tr[c] = exp(-acc[c]);
}

/* The optical depth at t: the shafts' closed form, or the uniform
   march's table (N steps of dt from t0), linear between its ends. */
static double tau_at(const ray *r, double t, double t0, double dt, int N, double tau[][3], int c)
{
    double u, f;
    int k;
    if (homogeneous(r->s)) return r->s->st[c] * (t - t0);
    u = (t - t0) / dt;
    if (!(u > 0)) return 0;
    if (u >= N) return tau[N][c];
    k = (int)u;
    f = u - k;
    return tau[k][c] + f * (tau[k + 1][c] - tau[k][c]);
}

/* The equiangular march towards the light P (Kulla and Fajardo 2012): N
   steps uniform in theta = atan((t - Delta) / D), the sample at the
   pixel's offset in each; the source times dt/dtheta held constant over
   a step, the step's extinction exact from the optical depth at its ends
   (the closed form, or the decoupled uniform march's table). */
static void march_equiangular(ray *r, double t0, double t1, int N, double xi, int lights,
                              const double P[3], double tau[][3], double L[3])
{
    const scene *s = r->s;
    double w[3], delta, D, perp[3], ta, tb, dth, dt = (t1 - t0) / N, st[3], ss[3];
    hrm_real li[3];
    hrm_spectrum_fn Li = scene_Li(s);
    int k, c;
    sub3(P, r->o, w);
    delta = dot3(w, r->d);
    for (c = 0; c < 3; ++c) perp[c] = w[c] - delta * r->d[c];
    D = sqrt(dot3(perp, perp));
    for (c = 0; c < 3; ++c) L[c] = 0;
    ta = atan2(t0 - delta, D);
    tb = atan2(t1 - delta, D);
    dth = (tb - ta) / N;
    if (!(D > 1e-12 * (t1 - t0)) || !(dth > 0)) {
        double Tr[3];
        march_uniform(r, t0, t1, N, xi, lights, L, Tr, NULL);
        return;
    }
    r->lights = lights;
    for (k = 0; k < N; ++k) {
        double th = ta + (k + xi) * dth, ts = delta + D * tan(th), cs = cos(th);
        double tl = delta + D * tan(ta + k * dth), tr = k + 1 == N ? t1 : delta + D * tan(ta + (k + 1) * dth);
        tl = tl < t0 ? t0 : tl > t1 ? t1 : tl;
        tr = tr < t0 ? t0 : tr > t1 ? t1 : tr;
        ts = ts < t0 ? t0 : ts > t1 ? t1 : ts;
        host_sigma(r, ts, st, ss);
        Li(r, (hrm_real)ts, li);
        for (c = 0; c < 3; ++c) {
            double al = tau_at(r, tl, t0, dt, N, tau, c), ar = tau_at(r, tr, t0, dt, N, tau, c);
            L[c] += ss[c] * (double)li[c] * D / (cs * cs) * dth * exp(-al) * phi1(ar - al > 0 ? ar - al : 0);
        }
    }
}

/* ======================================================================
   The reference: composite Gauss-Legendre in t
   ====================================================================== */
/* Legendre P_0..P_n at x (three-term recurrence). */
static void legendre(int n, double x, double P[])
{
    int m;
    P[0] = 1;
    if (n > 0) P[1] = x;
    for (m = 1; m < n; ++m) P[m + 1] = ((2 * m + 1) * x * P[m] - m * P[m - 1]) / (m + 1);
}

/* Nodes and weights by Newton's method on P_n from Chebyshev guesses;
   W from the Lagrange polynomials in the Legendre basis (the rule is
   exact for their products: the coefficient of P_m in l_k is (2m + 1)/2
   w_k P_m(x_k)) and the integral of P_m from -1, (P_{m+1} - P_{m-1}) /
   (2m + 1), or x + 1 for m = 0. */
static void gl_init(gl_rule *g)
{
    double P[GL_N + 2], Q[GL_N + 2];
    int j, k, m, it;
    for (j = 0; j < GL_N; ++j) {
        double x = -cos(PI * (j + 0.75) / (GL_N + 0.5)), dp = 1;
        for (it = 0; it < 100; ++it) {
            double dx;
            legendre(GL_N, x, P);
            dp = GL_N * (x * P[GL_N] - P[GL_N - 1]) / (x * x - 1);
            dx = P[GL_N] / dp;
            x -= dx;
            if (fabs(dx) < 1e-16) break;
        }
        legendre(GL_N, x, P);
        dp = GL_N * (x * P[GL_N] - P[GL_N - 1]) / (x * x - 1);
        g->x[j] = x;
        g->w[j] = 2 / ((1 - x * x) * dp * dp);
    }
    for (j = 0; j < GL_N; ++j) {
        legendre(GL_N, g->x[j], Q);
        for (k = 0; k < GL_N; ++k) {
            double sum = 0;
            legendre(GL_N, g->x[k], P);
            for (m = 0; m < GL_N; ++m) {
                double I = m == 0 ? g->x[j] + 1 : (Q[m + 1] - Q[m - 1]) / (2 * m + 1);
                sum += (2 * m + 1) / 2.0 * g->w[k] * P[m] * I;
            }
            g->W[j][k] = sum;
        }
    }
}

static void sort_unique(double *v, int *n)
{
    int i, k;
    for (i = 1; i < *n; ++i) {
        double x = v[i];
        for (k = i; k > 0 && v[k - 1] > x; --k) v[k] = v[k - 1];
        v[k] = x;
    }
    for (i = k = 0; i < *n; ++i)
        if (k == 0 || v[i] > v[k - 1]) v[k++] = v[i];
    *n = k;
}

/* The reference's cuts of [t0, t1] (t0 and t1 included): every cone of
   a shadow (tangent to an occluder from the light) and of the spot, the
   density's sphere, the foot of the light at P. Extra cuts cost nodes,
   not accuracy. */
static int reference_cuts(const ray *r, double t0, double t1, const double P[3], double *cut)
{
    const scene *s = r->s;
    double a[3], w[3], x[2], ta, tb, delta;
    int n = 0, k, i, m;
    cut[n++] = t0;
    cut[n++] = t1;
    for (k = 0; k < s->nocc; ++k) {
        double dist;
        sub3(s->occ[k].c, s->light, a);
        dist = norm3(a);
        if (dist <= s->occ[k].r) continue;
        m = cone_cross(r->o, r->d, s->light, a, sqrt(1 - s->occ[k].r * s->occ[k].r / (dist * dist)), t0,
                       t1, x);
        for (i = 0; i < m; ++i) cut[n++] = x[i];
    }
    if (s->kind == SMOKE) {
        m = cone_cross(r->o, r->d, s->light, s->axis, s->cos_in, t0, t1, x);
        for (i = 0; i < m; ++i) cut[n++] = x[i];
        m = cone_cross(r->o, r->d, s->light, s->axis, s->cos_out, t0, t1, x);
        for (i = 0; i < m; ++i) cut[n++] = x[i];
    }
    if (!homogeneous(s) && sphere_span(r->o, r->d, s->cc, s->cr, &ta, &tb)) {
        if (ta > t0 && ta < t1) cut[n++] = ta;
        if (tb > t0 && tb < t1) cut[n++] = tb;
    }
    sub3(P, r->o, w);
    delta = dot3(w, r->d);
    if (delta > t0 && delta < t1) cut[n++] = delta;
    sort_unique(cut, &n);
    return n;
}

/* The reference along one camera ray over [t0, t1]: panels cut at the
   geometry's breakpoints and, between them, ends uniform in asinh((t -
   Delta) / D) (Delta, D: the light's foot and distance), about `panels`
   over the ray; Gauss-Legendre on each, tau at a node from the panel's
   interpolant of sigma_t. L per light into Lk[light], Tr of the ray. The
   lamps' medium is homogeneous: one pass per lamp, graded towards its
   foot; the other scenes one pass for all their lights, graded towards
   the point or spot light. */
static void reference_ray(ray *r, double t0, double t1, int panels, double Lk[MAX_LIGHTS][3], double Tr[3])
{
    const scene *s = r->s;
    const gl_rule *g = s->gl;
    double cut[MAX_CUTS], w[3], perp[3], delta, D, u0, u1, tau[3];
    hrm_spectrum_fn Li = scene_Li(s);
    int ncut, i, k, j, c, l, pass, npass = s->kind == LAMPS ? s->nlights : 1;
    memset(Lk, 0, MAX_LIGHTS * 3 * sizeof(double));
    for (pass = 0; pass < npass; ++pass) {
        const double *P = light_pos(s, pass);
        int first = s->kind == LAMPS ? pass : 0, last = s->kind == LAMPS ? pass + 1 : s->nlights;
        ncut = reference_cuts(r, t0, t1, P, cut);
        sub3(P, r->o, w);
        delta = dot3(w, r->d);
        for (c = 0; c < 3; ++c) perp[c] = w[c] - delta * r->d[c];
        D = sqrt(dot3(perp, perp));
        if (D < 1e-9 * (t1 - t0)) D = 1e-9 * (t1 - t0);
        u0 = asinh((t0 - delta) / D);
        u1 = asinh((t1 - delta) / D);
        for (c = 0; c < 3; ++c) tau[c] = 0;
        for (i = 0; i + 1 < ncut; ++i) {
            double a = cut[i], b = cut[i + 1];
            double ua = asinh((a - delta) / D), ub = asinh((b - delta) / D);
            int np = (int)ceil(panels * (ub - ua) / (u1 - u0));
            if (np < 1) np = 1;
            for (k = 0; k < np; ++k) {
                double pa = k == 0 ? a : delta + D * sinh(ua + (ub - ua) * k / np);
                double pb = k + 1 == np ? b : delta + D * sinh(ua + (ub - ua) * (k + 1) / np);
                double h = (pb - pa) / 2, st[GL_N][3], ss[GL_N][3], x[GL_N];
                if (!(pb > pa)) continue;
                for (j = 0; j < GL_N; ++j) {
                    x[j] = pa + h * (1 + g->x[j]);
                    host_sigma(r, x[j], st[j], ss[j]);
                }
                for (j = 0; j < GL_N; ++j) {
                    double tj[3];
                    for (c = 0; c < 3; ++c) {
                        double sum = 0;
                        if (homogeneous(s)) {
                            tj[c] = s->st[c] * (x[j] - t0);
                            continue;
                        }
                        for (l = 0; l < GL_N; ++l) sum += g->W[j][l] * st[l][c];
                        tj[c] = tau[c] + h * sum;
                    }
                    for (l = first; l < last; ++l) {
                        hrm_real li[3];
                        r->lights = 1 << l;
                        Li(r, (hrm_real)x[j], li);
                        for (c = 0; c < 3; ++c)
                            Lk[l][c] += h * g->w[j] * exp(-tj[c]) * ss[j][c] * (double)li[c];
                    }
                }
                for (c = 0; c < 3; ++c) {
                    double sum = 0;
                    if (homogeneous(s)) {
                        tau[c] = s->st[c] * (pb - t0);
                        continue;
                    }
                    for (j = 0; j < GL_N; ++j) sum += g->w[j] * st[j][c];
                    tau[c] += h * sum;
                }
            }
        }
    }
    for (c = 0; c < 3; ++c) Tr[c] = exp(-tau[c]);
}

/* ======================================================================
   Configurations: what the host asks of hrm per camera ray
   ====================================================================== */
/* HRM_SHARES: a mixture configuration's solves, one per light, each
   under the mixture's warp (each light's share of its error; the lamps'
   per-light table, not costed) */
enum { HRM_RUN, BASE_UNIFORM, BASE_EQUIANGULAR, REFERENCE, HRM_SHARES };

typedef struct config {
    const char *name;     /* label */
    int base;             /* HRM_RUN, or a baseline, or the reference */
    hrm_method method;
    int warp;             /* 1: equiangular warp towards the point light */
    int breaks;           /* 1: the occluders' shadow edges (and the
                             spot's cone) as breakpoints */
    int split;            /* 1: one solve per light, each with its warp
                             (lamps: each lamp alone described to
                             hrm_light_options; 0: all four, the
                             mixture warp) */
    int exponential;      /* options.exponential */
    double h_max;         /* Runge-Kutta pairs: the largest step (0: none) */
    int gk_local;         /* Gauss-Kronrod: local mode, 7-point rule */
    int nrungs;
    double rung[MAX_RUNGS]; /* N (fixed-step, baselines), rtol (adaptive),
                               panels (the reference) */
} config;

static int adaptive(const config *cf)
{
    hrm_method m = cf->method;
    return (cf->base == HRM_RUN || cf->base == HRM_SHARES) &&
           (m == HRM_NESTED_SIMPSON || m == HRM_GAUSS_KRONROD || m == HRM_BOGACKI_SHAMPINE ||
            m == HRM_DORMAND_PRINCE || m == HRM_FEHLBERG || m == HRM_CASH_KARP || m == HRM_VERNER);
}

/* splitmix64: decorrelated seeds per pixel and rung. */
static uint64_t mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15u;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* The breakpoints a host gives: each occluder's shadow edges
   (hrm_sphere_breaks), and for a spot light its two cones, merged into
   one increasing list strictly inside (t0, t1). */
static int host_breaks(const scene *s, const ray *r, double t0, double t1, hrm_real *out)
{
    hrm_real o[3], d[3], L[3], c[3], b[2];
    double x[2], v[MAX_CUTS];
    int i, k, n = 0, cnt;
    for (i = 0; i < 3; ++i) {
        o[i] = (hrm_real)r->o[i];
        d[i] = (hrm_real)r->d[i];
        L[i] = (hrm_real)s->light[i];
    }
    for (k = 0; k < s->nocc; ++k) {
        for (i = 0; i < 3; ++i) c[i] = (hrm_real)s->occ[k].c[i];
        if (hrm_sphere_breaks(o, d, L, c, (hrm_real)s->occ[k].r, (hrm_real)t0, (hrm_real)t1, b,
                              &cnt) != HRM_OK)
            continue;
        for (i = 0; i < cnt; ++i) v[n++] = (double)b[i];
    }
    if (s->kind == SMOKE) {
        cnt = cone_cross(r->o, r->d, s->light, s->axis, s->cos_in, t0, t1, x);
        for (i = 0; i < cnt; ++i) v[n++] = x[i];
        cnt = cone_cross(r->o, r->d, s->light, s->axis, s->cos_out, t0, t1, x);
        for (i = 0; i < cnt; ++i) v[n++] = x[i];
    }
    sort_unique(v, &n);
    for (i = k = 0; i < n && k < HRM_MAX_BREAKS; ++i)
        if (v[i] > t0 && v[i] < t1) out[k++] = (hrm_real)v[i];
    return k;
}

/* The scene's point or spot light and its occluders as hrm describes
   them: hrm_light_options gives the ray's warp and breakpoints (the
   configurations with both). */
static hrm_status light_plan(const scene *s, const ray *r, double t0, double t1, hrm_ray_plan *plan,
                             hrm_options *o)
{
    hrm_light l;
    hrm_sphere sp[MAX_OCC];
    hrm_real O[3], D[3];
    int i, k;
    memset(&l, 0, sizeof l);
    l.kind = s->kind == SMOKE ? HRM_LIGHT_SPOT : HRM_LIGHT_POINT;
    l.power = (hrm_real)(s->I[0] + s->I[1] + s->I[2]);
    if (s->kind == SMOKE) {
        l.cone = (hrm_real)acos(s->cos_out);
        l.falloff = (hrm_real)acos(s->cos_in);
    }
    for (i = 0; i < 3; ++i) {
        O[i] = (hrm_real)r->o[i];
        D[i] = (hrm_real)r->d[i];
        l.position[i] = (hrm_real)s->light[i];
        l.direction[i] = (hrm_real)s->axis[i];
    }
    for (k = 0; k < s->nocc; ++k) {
        for (i = 0; i < 3; ++i) sp[k].center[i] = (hrm_real)s->occ[k].c[i];
        sp[k].radius = (hrm_real)s->occ[k].r;
    }
    return hrm_light_options(&l, 1, sp, s->nocc, O, D, (hrm_real)t0, (hrm_real)t1, plan, o);
}

/* The lamps as hrm describes them: lamp `only`, or all of them (-1), to
   hrm_light_options: the equiangular warp for one, the mixture warp for
   several. */
static hrm_status lamps_plan(const scene *s, const ray *r, double t0, double t1, int only,
                             hrm_ray_plan *plan, hrm_options *o)
{
    hrm_light l[MAX_LIGHTS];
    hrm_real O[3], D[3];
    int i, k, n = 0;
    for (k = 0; k < s->nlights; ++k) {
        if (only >= 0 && k != only) continue;
        memset(&l[n], 0, sizeof l[n]);
        l[n].kind = HRM_LIGHT_POINT;
        l[n].power = (hrm_real)(s->lamp_I[k][0] + s->lamp_I[k][1] + s->lamp_I[k][2]);
        for (i = 0; i < 3; ++i) l[n].position[i] = (hrm_real)s->lamp[k][i];
        n++;
    }
    for (i = 0; i < 3; ++i) {
        O[i] = (hrm_real)r->o[i];
        D[i] = (hrm_real)r->d[i];
    }
    return hrm_light_options(l, n, NULL, 0, O, D, (hrm_real)t0, (hrm_real)t1, plan, o);
}

/* The options of one camera ray for the configuration at rung q. */
static hrm_options ray_options(const config *cf, double q, uint64_t seed)
{
    hrm_options o = hrm_default_options(cf->method);
    if (adaptive(cf)) {
        o.rtol = (hrm_real)q;
        o.h_max = (hrm_real)cf->h_max;
        if (cf->gk_local) {
            o.gk_mode = HRM_GK_LOCAL;
            o.gk_rule = HRM_GK_K7;
        }
    } else {
        o.steps = (int)q;
    }
    o.seed = seed;
    o.exponential = cf->exponential;
    return o;
}

/* The equiangular warp of this ray towards a point light (a warp per
   light: see the cloud's split below). */
static void light_warp(const ray *r, const double light[3], hrm_warp *w)
{
    hrm_real O[3], D[3], Lp[3];
    int c;
    for (c = 0; c < 3; ++c) {
        O[c] = (hrm_real)r->o[c];
        D[c] = (hrm_real)r->d[c];
        Lp[c] = (hrm_real)light[c];
    }
    if (hrm_equiangular_warp(O, D, Lp, w) != HRM_OK) w->kind = HRM_WARP_NONE;
}

/* What one pixel gave and cost. */
typedef struct pixel_out {
    double rgb[3];
    int met;           /* the camera ray meets the medium */
    int nsol;          /* camera solves (or the reference's lights) */
    double L[MAX_LIGHTS][3]; /* each solve's L */
    int mask[MAX_LIGHTS];    /* the lights of each solve */
    hrm_status st[MAX_LIGHTS]; /* each solve's status */
    double tr;         /* Tr of the camera ray (green) */
    long li, traced, lookups, shadow_lookups;
    unsigned warned;   /* bit s: a solve or shadow ray returned status s
                          (warnings 1..14; bit 15: an error) */
} pixel_out;

static unsigned status_bit(hrm_status st)
{
    return st == HRM_OK ? 0u : st > 0 && st < 15 ? 1u << st : 1u << 15;
}

/* The camera ray of pixel (x, y), its span [t0, t1] in the medium and
   what is behind it; 0 where it misses the medium. */
static int camera_ray(const scene *s, int x, int y, ray *r, double *t0, double *t1, double behind[3])
{
    double ta, tb;
    int c, k;
    memset(r, 0, sizeof *r);
    r->s = s;
    memcpy(r->o, s->eye, sizeof r->o);
    r->d[0] = (2 * (x + 0.5) / s->w - 1) * s->tan_half * s->w / s->h;
    r->d[1] = (1 - 2 * (y + 0.5) / s->h) * s->tan_half;
    r->d[2] = 1;
    norm3(r->d);
    for (c = 0; c < 3; ++c) behind[c] = 0;
    *t0 = 0;
    if (homogeneous(s)) {
        /* the ray ends on the wall or on the nearest occluder: both lit
           diffusely by the point light (lamps: each lamp), shadowed by
           the other spheres */
        double p[3], n[3] = {0, 0, -1}, v[3], dist, cosl;
        int l;
        *t1 = (s->wall_z - r->o[2]) / r->d[2];
        for (k = 0; k < s->nocc; ++k)
            if (sphere_span(r->o, r->d, s->occ[k].c, s->occ[k].r, &ta, &tb) && ta > 0 && ta < *t1) {
                *t1 = ta;
                point_at(r, ta, p);
                sub3(p, s->occ[k].c, n);
                norm3(n);
            }
        point_at(r, *t1, p);
        for (l = 0; l < s->nlights; ++l) {
            const double *I = s->kind == LAMPS ? s->lamp_I[l] : s->I;
            sub3(light_pos(s, l), p, v);
            dist = norm3(v);
            cosl = dot3(n, v);
            if (cosl > 0 && !blocked(s, p, v, dist))
                for (c = 0; c < 3; ++c)
                    behind[c] += s->wall_albedo[c] / PI * I[c] * cosl / (dist * dist) * exp(-s->st[c] * dist);
        }
        return 1;
    }
    if (s->kind == CLOUD) {
        /* behind the cloud: a sky gradient */
        double sky = 0.5 + 0.5 * r->d[1];
        behind[0] = 0.30 + 0.15 * sky;
        behind[1] = 0.40 + 0.22 * sky;
        behind[2] = 0.55 + 0.35 * sky;
    }
    /* the ray clipped to the density's sphere; the smoke's occluder
       (black) ends it */
    if (!sphere_span(r->o, r->d, s->cc, s->cr, &ta, &tb) || tb <= 0) return 0;
    *t0 = ta > 0 ? ta : 0;
    *t1 = tb;
    for (k = 0; k < s->nocc && s->kind == SMOKE; ++k) {
        double oa, ob;
        if (sphere_span(r->o, r->d, s->occ[k].c, s->occ[k].r, &oa, &ob) && oa > 0 && oa < *t1) {
            *t1 = oa;
            for (c = 0; c < 3; ++c) behind[c] = 0;
        }
    }
    return *t1 > *t0;
}

/* Solve one camera ray (the drop-in: L + Tr * L_behind), by hrm, a
   baseline march or the reference. */
static void shade(const scene *s, const config *cf, double q, int x, int y, double (*scratch)[3],
                  unsigned char *ws, pixel_out *po)
{
    ray r;
    double t0, t1, behind[3], Tr[3];
    uint64_t seed = mix64(((uint64_t)y << 20) ^ (uint64_t)x ^ ((uint64_t)(q * 1e6) << 40));
    int c, k;

    memset(po, 0, sizeof *po);
    po->met = camera_ray(s, x, y, &r, &t0, &t1, behind);
    if (!po->met) {
        memcpy(po->rgb, behind, sizeof po->rgb);
        return;
    }
    if (cf->base == REFERENCE) {
        reference_ray(&r, t0, t1, (int)q, po->L, Tr);
        po->nsol = s->nlights;
        for (k = 0; k < s->nlights; ++k) po->mask[k] = 1 << k;
        for (c = 0; c < 3; ++c) {
            double sum = 0;
            for (k = 0; k < MAX_LIGHTS; ++k) sum += po->L[k][c];
            po->rgb[c] = sum + Tr[c] * behind[c];
        }
        po->tr = Tr[1];
    } else if (cf->base != HRM_RUN && cf->base != HRM_SHARES) {
        /* one random offset per pixel (Cycles' way), the same for every
           step */
        double xi = (double)(seed >> 11) * (1.0 / 9007199254740992.0);
        int N = (int)q, all = (1 << s->nlights) - 1;
        po->nsol = 1;
        po->mask[0] = all;
        if (cf->base == BASE_UNIFORM) {
            march_uniform(&r, t0, t1, N, xi, all, po->L[0], Tr, NULL);
        } else {
            /* the optical depth from a uniform march of N steps, with the
               sun's light where there is a sun; then the equiangular
               march for the point or spot light (lamps: one march of N
               steps per lamp, towards it) */
            double Ls[3] = {0, 0, 0}, Ll[3];
            if (!homogeneous(s)) march_uniform(&r, t0, t1, N, xi, all & 2, Ls, Tr, scratch);
            march_equiangular(&r, t0, t1, N, xi, 1, light_pos(s, 0), scratch, po->L[0]);
            for (k = 1; k < s->nlights && s->kind == LAMPS; ++k) {
                march_equiangular(&r, t0, t1, N, xi, 1 << k, light_pos(s, k), scratch, Ll);
                for (c = 0; c < 3; ++c) po->L[0][c] += Ll[c];
            }
            if (homogeneous(s))
                for (c = 0; c < 3; ++c) Tr[c] = exp(-s->st[c] * (t1 - t0));
            for (c = 0; c < 3; ++c) po->L[0][c] += Ls[c];
        }
        for (c = 0; c < 3; ++c) po->rgb[c] = po->L[0][c] + Tr[c] * behind[c];
        po->tr = Tr[1];
    } else {
        hrm_medium m;
        hrm_options o = ray_options(cf, q, seed);
        hrm_result res;
        hrm_real brk[HRM_MAX_BREAKS];
        hrm_ray_plan plan;
        int planned = 0;
        memset(&m, 0, sizeof m);
        m.user = &r;
        m.Li = scene_Li(s);
        if (homogeneous(s)) {
            m.flags = HRM_MEDIUM_HOMOGENEOUS;
            for (c = 0; c < 3; ++c) {
                m.const_sigma_a[c] = (hrm_real)s->sa[c];
                m.const_sigma_s[c] = (hrm_real)s->ss[c];
            }
        } else {
            /* sigma_a and sigma_s from one lookup; the medium scan
               samples sigma at the feature's spacing where the scene has
               one */
            m.sigma = dens_sigma_as;
            m.feature = (hrm_real)s->feature;
        }
        if (cf->breaks && cf->warp && s->kind != CLOUD && s->kind != LAMPS) {
            /* the light described: its warp and breakpoints from hrm */
            planned = light_plan(s, &r, t0, t1, &plan, &o) == HRM_OK;
        } else if (cf->breaks) {
            o.nbreaks = host_breaks(s, &r, t0, t1, brk);
            o.breaks = brk;
        }
        for (c = 0; c < 3; ++c) po->rgb[c] = 0;
        /* several lights: one solve per light, each with the warp that
           suits it (equiangular for the point light, none for the sun),
           or one solve for all (each Li a shadow ray per light) */
        po->nsol = cf->split || cf->base == HRM_SHARES ? s->nlights : 1;
        /* the thread's workspace: the camera solve's storage first, its
           shadow rays' in the rest (hrm_workspace_size each) */
        if (hrm_workspace_size(&o) + hrm_workspace_size(&s->shadow) <= WS_BYTES) {
            o.workspace = ws;
            o.workspace_size = hrm_workspace_size(&o);
            r.shadow_ws = ws + o.workspace_size;
            r.shadow_ws_size = hrm_workspace_size(&s->shadow);
        }
        for (k = 0; k < po->nsol; ++k) {
            hrm_options ok = o;
            hrm_status st;
            r.lights = po->nsol > 1 ? 1 << k : (1 << s->nlights) - 1;
            if (cf->warp && s->kind == LAMPS) {
                /* each lamp alone (split), or all of them: the mixture */
                if (lamps_plan(s, &r, t0, t1, cf->split ? k : -1, &plan, &ok) != HRM_OK) ok.warp = o.warp;
            } else if (cf->warp && (r.lights & 1) && !planned) {
                light_warp(&r, s->light, &ok.warp);
            }
            st = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &ok, &res);
            po->warned |= status_bit(st) | status_bit(r.shadow_status);
            po->st[k] = st;
            po->mask[k] = r.lights;
            if (k == 0) po->tr = (double)res.Tr[1];
            for (c = 0; c < 3; ++c) {
                po->L[k][c] = (double)res.L[c];
                po->rgb[c] += (double)res.L[c] + (k == 0 ? (double)res.Tr[c] * behind[c] : 0);
            }
        }
    }
    po->li = r.li;
    po->traced = r.traced;
    po->lookups = r.lookups;
    po->shadow_lookups = r.shadow_lookups;
}

/* ======================================================================
   Rendering: rows interleaved over threads
   ====================================================================== */
typedef struct frame {
    int w, h;
    double *rgb;        /* linear radiance, w * h * 3 */
    unsigned char *in;  /* w * h: bit 0, the camera ray meets the medium;
                           bit 1, a solve or shadow ray warned; bit 2, it
                           passes within a pixel's footprint of the light */
    double *L;          /* w * h * MAX_LIGHTS * 3: each camera solve's L */
    int *st;            /* w * h * MAX_LIGHTS: its status */
    unsigned char *mask;/* w * h * MAX_LIGHTS: its lights (0: no solve) */
    double *tr;         /* w * h: Tr of the camera ray (green) */
    long li, traced, lookups; /* over the image */
    long shadow_lookups;      /* of the lookups, the shadow rays' */
    long warned;        /* pixels whose solve or shadow ray warned */
    long by[16];        /* of them, those with status s (bit 15: errors) */
    double cpu;         /* thread CPU seconds, summed */
} frame;

typedef struct job {
    const scene *s;
    const config *cf;
    double q;
    frame *f;
    int first, stride;
    long li, traced, lookups, shadow_lookups, warned, by[16];
    double cpu;
} job;

static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Whether pixel (x, y)'s ray passes within one pixel's footprint (its
   angular size times the distance) of the point or spot light (a lamp). */
static int near_light(const scene *s, int x, int y)
{
    ray r;
    double t0, t1, behind[3], w[3], delta, perp[3];
    int c, l;
    camera_ray(s, x, y, &r, &t0, &t1, behind);
    for (l = 0; l < (s->kind == LAMPS ? s->nlights : 1); ++l) {
        sub3(light_pos(s, l), r.o, w);
        delta = dot3(w, r.d);
        if (delta <= 0) continue;
        for (c = 0; c < 3; ++c) perp[c] = w[c] - delta * r.d[c];
        if (sqrt(dot3(perp, perp)) < delta * 2 * s->tan_half / s->h) return 1;
    }
    return 0;
}

static void *worker(void *arg)
{
    job *j = (job *)arg;
    frame *f = j->f;
    double (*scratch)[3] = (double (*)[3])malloc((MAX_N + 1) * sizeof *scratch);
    /* each thread's workspace for hrm (options.workspace): its solves'
       deep storage off the thread's stack, aligned to 16 */
    unsigned char *mem = (unsigned char *)malloc(WS_BYTES + 16), *ws;
    double start = thread_cpu();
    int x, y, k;
    if (!scratch || !mem) {
        free(scratch);
        free(mem);
        return NULL;
    }
    ws = mem + (16 - (size_t)((uintptr_t)mem % 16)) % 16;
    for (y = j->first; y < f->h; y += j->stride)
        for (x = 0; x < f->w; ++x) {
            size_t i = (size_t)y * f->w + x;
            pixel_out po;
            shade(j->s, j->cf, j->q, x, y, scratch, ws, &po);
            memcpy(f->rgb + 3 * i, po.rgb, sizeof po.rgb);
            f->in[i] = (unsigned char)(po.met | (po.warned ? 2 : 0) | (near_light(j->s, x, y) ? 4 : 0));
            f->tr[i] = po.tr;
            for (k = 0; k < MAX_LIGHTS; ++k) {
                f->mask[MAX_LIGHTS * i + k] = (unsigned char)(k < po.nsol ? po.mask[k] : 0);
                f->st[MAX_LIGHTS * i + k] = po.st[k];
                memcpy(f->L + 3 * (MAX_LIGHTS * i + k), po.L[k], sizeof po.L[k]);
            }
            j->li += po.li;
            j->traced += po.traced;
            j->lookups += po.lookups;
            j->shadow_lookups += po.shadow_lookups;
            j->warned += po.warned != 0;
            for (k = 0; k < 16; ++k) j->by[k] += (po.warned >> k) & 1u;
        }
    j->cpu = thread_cpu() - start;
    free(scratch);
    free(mem);
    return NULL;
}

static int nthreads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 64 ? 64 : (int)n;
}

static void render(const scene *s, const config *cf, double q, frame *f)
{
    pthread_t th[64];
    job jobs[64];
    int i, k, n = nthreads();
    f->li = f->traced = f->lookups = f->shadow_lookups = f->warned = 0;
    f->cpu = 0;
    memset(f->by, 0, sizeof f->by);
    for (i = 0; i < n; ++i) {
        memset(&jobs[i], 0, sizeof jobs[i]);
        jobs[i].s = s;
        jobs[i].cf = cf;
        jobs[i].q = q;
        jobs[i].f = f;
        jobs[i].first = i;
        jobs[i].stride = n;
        if (pthread_create(&th[i], NULL, worker, &jobs[i]) != 0) worker(&jobs[i]), th[i] = 0;
    }
    for (i = 0; i < n; ++i) {
        if (th[i]) pthread_join(th[i], NULL);
        f->li += jobs[i].li;
        f->traced += jobs[i].traced;
        f->lookups += jobs[i].lookups;
        f->shadow_lookups += jobs[i].shadow_lookups;
        f->warned += jobs[i].warned;
        f->cpu += jobs[i].cpu;
        for (k = 0; k < 16; ++k) f->by[k] += jobs[i].by[k];
    }
}

/* Relative RMSE of a against the reference: sqrt(sum (a - ref)^2 /
   sum ref^2) over every channel of the pixels whose ray meets the medium
   (the others are exact in every configuration); all_px 0 leaves out the
   pixels next to the light. */
static double rel_rmse(const frame *a, const frame *ref, int all_px)
{
    double num = 0, den = 0;
    size_t i, n = (size_t)ref->w * ref->h * 3;
    for (i = 0; i < n; ++i) {
        double d = a->rgb[i] - ref->rgb[i];
        if (!(ref->in[i / 3] & 1) || (!all_px && (ref->in[i / 3] & 4))) continue;
        num += d * d;
        den += ref->rgb[i] * ref->rgb[i];
    }
    return den > 0 ? sqrt(num / den) : 0;
}

/* Light l's relative RMSE: the L of a's solve for light l alone (solve
   l) against the reference's, over the pixels rel_rmse(a, ref, 0)
   counts; -1 where a has no such solve. */
static double light_rmse(const frame *a, const frame *ref, int l)
{
    double num = 0, den = 0;
    size_t i, np = (size_t)ref->w * ref->h;
    int c;
    for (i = 0; i < np; ++i) {
        size_t at = MAX_LIGHTS * i + (size_t)l;
        if (!(ref->in[i] & 1) || (ref->in[i] & 4)) continue;
        if (a->mask[at] != 1u << l) return -1;
        for (c = 0; c < 3; ++c) {
            double d = a->L[3 * at + (size_t)c] - ref->L[3 * at + (size_t)c];
            num += d * d;
            den += ref->L[3 * at + (size_t)c] * ref->L[3 * at + (size_t)c];
        }
    }
    return den > 0 ? sqrt(num / den) : 0;
}

/* The mean reference pixel over the pixels that meet the medium. */
static double mean_pixel(const frame *ref)
{
    double sum = 0;
    long n = 0;
    size_t i, np = (size_t)ref->w * ref->h;
    for (i = 0; i < np; ++i)
        if (ref->in[i] & 1) {
            sum += ref->rgb[3 * i] + ref->rgb[3 * i + 1] + ref->rgb[3 * i + 2];
            n += 3;
        }
    return n ? sum / n : 0;
}

/* What the statuses were worth: per channel of each camera solve's L
   against the reference's L for the same lights, the pixels with a
   silent miss (HRM_OK, |L - L_ref| > 3 rtol |L_ref| + atol) and those
   with a false alarm (a warning, |L - L_ref| <= rtol |L_ref| + atol in
   every channel). */
static void judge(const frame *a, const frame *ref, double rtol, double atol, long *silent, long *alarms)
{
    size_t i, np = (size_t)ref->w * ref->h;
    *silent = *alarms = 0;
    for (i = 0; i < np; ++i) {
        int k, l, c, sil = 0, fa = 0;
        if (!(ref->in[i] & 1)) continue;
        for (k = 0; k < MAX_LIGHTS; ++k) {
            int mask = a->mask[MAX_LIGHTS * i + k], st = a->st[MAX_LIGHTS * i + k], within = 1, off = 0;
            if (!mask) continue;
            for (c = 0; c < 3; ++c) {
                double want = 0, e;
                for (l = 0; l < MAX_LIGHTS; ++l)
                    if (mask & (1 << l)) want += ref->L[3 * (MAX_LIGHTS * i + l) + c];
                e = fabs(a->L[3 * (MAX_LIGHTS * i + k) + c] - want);
                if (e > 3 * rtol * fabs(want) + atol) off = 1;
                if (e > rtol * fabs(want) + atol) within = 0;
            }
            if (st == HRM_OK && off) sil = 1;
            if (st > 0 && within) fa = 1;
        }
        *silent += sil;
        *alarms += fa;
    }
}

/* ======================================================================
   Pictures
   ====================================================================== */
/* Linear radiance to sRGB-like 8 bits: exposure, a soft shoulder, gamma. */
static void to_image(const frame *f, double exposure, image8 *im)
{
    size_t i, n = (size_t)f->w * f->h * 3;
    for (i = 0; i < n; ++i) {
        double v = f->rgb[i] * exposure;
        v = v / (1 + 0.25 * v);
        v = v <= 0 ? 0 : pow(v, 1 / 2.2);
        im->px[i] = (unsigned char)(v >= 1 ? 255 : 255 * v + 0.5);
    }
}

/* |a - ref| per pixel (channels summed) relative to the reference's mean,
   in false colour on a log scale from 1e-4 (black) to 1e-1 (white). */
static void error_map(const frame *a, const frame *ref, image8 *im)
{
    double mean = 0, e;
    size_t i, n = (size_t)ref->w * ref->h;
    for (i = 0; i < 3 * n; ++i) mean += ref->rgb[i];
    mean /= (double)(3 * n);
    for (i = 0; i < n; ++i) {
        e = (fabs(a->rgb[3 * i] - ref->rgb[3 * i]) + fabs(a->rgb[3 * i + 1] - ref->rgb[3 * i + 1]) +
             fabs(a->rgb[3 * i + 2] - ref->rgb[3 * i + 2])) / (3 * mean);
        false_colour(e > 0 ? (log10(e) + 4) / 3 : 0, im->px + 3 * i);
    }
}

/* ======================================================================
   Ladders and the equal-RMSE search
   ====================================================================== */
enum { C_LI, C_TRACED, C_LOOKUPS, C_CPU, NCOST };

typedef struct rung_result {
    double q, rmse[2];   /* rmse[0] without the pixels next to the light,
                            rmse[1] over all */
    double cost[NCOST];  /* per pixel (CPU: seconds for the image) */
    double camera;       /* of the lookups per pixel, the camera rays' */
    long silent, alarms; /* -1: not judged (fixed-step methods) */
    double light_rmse[MAX_LIGHTS]; /* lamps: each lamp's relative RMSE
                                      (the mixture's shares), -1: none */
    char warned[96];     /* pixels warned, by status */
} rung_result;

typedef struct ladder {
    const config *cf;
    int n;
    rung_result r[MAX_RUNGS];
    frame best;        /* the rung nearest the equal-Li budget */
    frame at_time;     /* the rung nearest the equal-CPU budget */
    double best_cost[NCOST], at_time_cost[NCOST];
} ladder;

/* The cost to reach `target` (in rmse[all_px]): log-log interpolation
   between the two rungs around the first crossing (linear in log RMSE
   where a cost is 0); *at_most 1 where the first rung is already below
   it (its cost bounds it). 0 where not reached on the ladder. */
static int cost_to(const ladder *l, double target, int all_px, double cost[NCOST], int *at_most)
{
    int i, k;
    *at_most = 0;
    for (i = 0; i < l->n; ++i) {
        if (l->r[i].rmse[all_px] > target) continue;
        if (i == 0) {
            *at_most = 1;
            memcpy(cost, l->r[0].cost, sizeof l->r[0].cost);
            return 1;
        }
        {
            const rung_result *a = &l->r[i - 1], *b = &l->r[i];
            double u = (log(target) - log(a->rmse[all_px])) / (log(b->rmse[all_px]) - log(a->rmse[all_px]));
            for (k = 0; k < NCOST; ++k)
                cost[k] = a->cost[k] > 0 && b->cost[k] > 0
                              ? exp(log(a->cost[k]) + u * (log(b->cost[k]) - log(a->cost[k])))
                              : a->cost[k] + u * (b->cost[k] - a->cost[k]);
        }
        return 1;
    }
    return 0;
}

/* The equal-RMSE tables: each configuration's cost to reach 1e-2 and
   1e-3, and the best baseline's over it, cost by cost. */
static void equal_rmse_tables(FILE *out, const ladder *lad, int ncfg, int all_px)
{
    static const double target[2] = {1e-2, 1e-3};
    int t, i, k;
    for (t = 0; t < 2; ++t) {
        double best[NCOST], c[NCOST];
        int at_most;
        for (k = 0; k < NCOST; ++k) best[k] = -1;
        for (i = 0; i < ncfg; ++i)
            if (lad[i].cf->base != HRM_RUN && cost_to(&lad[i], target[t], all_px, c, &at_most))
                for (k = 0; k < NCOST; ++k)
                    if (best[k] < 0 || c[k] < best[k]) best[k] = c[k];
        fprintf(out, "\nTo relative RMSE %.0e (%s): cost per pixel (CPU: seconds for the image), and "
                     "the best baseline's cost over it:\n\n",
                target[t], all_px ? "all pixels" : "without the pixels next to the light");
        fprintf(out, "| configuration | Li | traced | lookups | CPU s | x Li | x traced | x lookups | x CPU |\n");
        fprintf(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        for (i = 0; i < ncfg; ++i) {
            fprintf(out, "| %s", lad[i].cf->name);
            if (!cost_to(&lad[i], target[t], all_px, c, &at_most)) {
                fprintf(out, " | not reached | | | | | | | |\n");
                continue;
            }
            for (k = 0; k < NCOST; ++k)
                fprintf(out, k == C_CPU ? " | %s%.3f" : " | %s%.1f", at_most ? "<= " : "", c[k]);
            for (k = 0; k < NCOST; ++k) {
                if (best[k] > 0 && c[k] > 0)
                    fprintf(out, " | %s%.2f", at_most ? ">= " : "", best[k] / c[k]);
                else
                    fprintf(out, " | -");
            }
            fprintf(out, " |\n");
        }
    }
}

/* ======================================================================
   Sheets
   ====================================================================== */
#define PAD 6

typedef struct tile {
    const char *name;
    const frame *f;
    double rmse, li, cpu;
} tile;

/* One column per tile: the image, its error map, four lines of labels. */
static int write_sheet(const char *path, const scene *s, const frame *ref, const tile *t, int n,
                       double exposure, const char *title)
{
    static const unsigned char white[3] = {235, 235, 235}, grey[3] = {150, 150, 150};
    image8 sheet, im;
    int sc = s->w >= 200 ? 2 : 1; /* the labels' scale: a name fits a tile */
    int i, ok, W = n * (s->w + PAD) + PAD, H = 22 + 2 * (s->h + PAD) + 4 * (6 * sc + 2) + PAD;
    char line[96];
    if (!image8_alloc(&sheet, W, H)) return 0;
    if (!image8_alloc(&im, s->w, s->h)) {
        image8_free(&sheet);
        return 0;
    }
    image8_fill(&sheet, 24, 24, 28);
    draw_text(&sheet, PAD, 6, title, 2, white);
    for (i = 0; i < n; ++i) {
        int x = PAD + i * (s->w + PAD), y = 22;
        to_image(t[i].f, exposure, &im);
        image8_blit(&sheet, &im, x, y);
        error_map(t[i].f, ref, &im);
        image8_blit(&sheet, &im, x, y + s->h + PAD);
        y += 2 * (s->h + PAD);
        draw_text(&sheet, x, y, t[i].name, sc, white);
        if (t[i].li > 0) {
            snprintf(line, sizeof line, "%.1f LI/PX", t[i].li);
            draw_text(&sheet, x, y + 1 * (6 * sc + 2), line, sc, grey);
            snprintf(line, sizeof line, "RMSE %.2g", t[i].rmse);
            draw_text(&sheet, x, y + 2 * (6 * sc + 2), line, sc, grey);
            snprintf(line, sizeof line, "%.2f CPU S", t[i].cpu);
            draw_text(&sheet, x, y + 3 * (6 * sc + 2), line, sc, grey);
        }
    }
    ok = png_write(path, &sheet);
    image8_free(&im);
    image8_free(&sheet);
    return ok;
}

/* ======================================================================
   A scene's study
   ====================================================================== */
static int frame_alloc(frame *f, const scene *s)
{
    size_t n = (size_t)s->w * s->h;
    memset(f, 0, sizeof *f);
    f->w = s->w;
    f->h = s->h;
    f->rgb = (double *)calloc(n * 3, sizeof(double));
    f->in = (unsigned char *)calloc(n, 1);
    f->L = (double *)calloc(n * MAX_LIGHTS * 3, sizeof(double));
    f->st = (int *)calloc(n * MAX_LIGHTS, sizeof(int));
    f->mask = (unsigned char *)calloc(n * MAX_LIGHTS, 1);
    f->tr = (double *)calloc(n, sizeof(double));
    return f->rgb && f->in && f->L && f->st && f->mask && f->tr;
}

static void frame_free(frame *f)
{
    free(f->rgb);
    free(f->in);
    free(f->L);
    free(f->st);
    free(f->mask);
    free(f->tr);
}

/* The image and its pixel flags (what the sheets show). */
static void frame_copy(frame *dst, const frame *src)
{
    size_t n = (size_t)src->w * src->h;
    memcpy(dst->rgb, src->rgb, n * 3 * sizeof(double));
    memcpy(dst->in, src->in, n);
}

static const char *label_of(const config *cf, double q, char *buf, size_t n)
{
    if (cf->base == REFERENCE)
        snprintf(buf, n, "%d panels", (int)q);
    else if (adaptive(cf))
        snprintf(buf, n, "rtol %.0e", q);
    else
        snprintf(buf, n, "N %d", (int)q);
    return buf;
}

/* "N" or "N (s: n, ...)": the pixels that warned, by hrm_status code. */
static const char *warned_text(const frame *f, char *buf, size_t n)
{
    size_t at;
    int k, first = 1;
    at = (size_t)snprintf(buf, n, "%ld", f->warned);
    for (k = 1; k < 16 && at < n; ++k) {
        if (!f->by[k]) continue;
        if (k == 15)
            at += (size_t)snprintf(buf + at, n - at, "%serrors: %ld", first ? " (" : ", ", f->by[k]);
        else
            at += (size_t)snprintf(buf + at, n - at, "%s%d: %ld", first ? " (" : ", ", k, f->by[k]);
        first = 0;
    }
    if (!first && at < n) snprintf(buf + at, n - at, ")");
    return buf;
}

static void frame_costs(const frame *f, double cost[NCOST])
{
    double np = (double)f->w * f->h;
    cost[C_LI] = (double)f->li / np;
    cost[C_TRACED] = (double)f->traced / np;
    cost[C_LOOKUPS] = (double)f->lookups / np;
    cost[C_CPU] = f->cpu;
}

/* The smoke's optical depth along the camera rays that meet it: the
   fraction with tau (green) in [1, 5], and the median. */
static void depth_text(const frame *ref, char *buf, size_t n)
{
    size_t i, np = (size_t)ref->w * ref->h, m = 0, in = 0;
    double *tau = (double *)malloc(np * sizeof(double));
    if (!tau) {
        snprintf(buf, n, "?");
        return;
    }
    for (i = 0; i < np; ++i)
        if (ref->in[i] & 1) {
            tau[m] = -log(ref->tr[i]);
            in += tau[m] >= 1 && tau[m] <= 5;
            m++;
        }
    /* insertion sort is enough for a median of at most 20 000 */
    for (i = 1; i < m; ++i) {
        double x = tau[i];
        size_t k;
        for (k = i; k > 0 && tau[k - 1] > x; --k) tau[k] = tau[k - 1];
        tau[k] = x;
    }
    snprintf(buf, n, "optical depth of the camera rays that meet the medium: median %.2f, %.0f%% in [1, 5]",
             m ? tau[m / 2] : 0, m ? 100.0 * (double)in / (double)m : 0);
    free(tau);
}

/* y at x on a ladder's points (xs ascending), log-log between the two
   around x; -1 outside them or where a y is not positive. */
static double loglog_at(const double *xs, const double *ys, int n, double x)
{
    int i;
    for (i = 0; i + 1 < n; ++i)
        if (x >= xs[i] && x <= xs[i + 1] && xs[i] > 0 && ys[i] > 0 && ys[i + 1] > 0) {
            double u = xs[i + 1] > xs[i] ? log(x / xs[i]) / log(xs[i + 1] / xs[i]) : 0;
            return exp(log(ys[i]) + u * log(ys[i + 1] / ys[i]));
        }
    return n > 0 && x == xs[n - 1] && ys[n - 1] > 0 ? ys[n - 1] : -1;
}

/* The lamps' mixture against one solve per lamp: for each mixture
   configuration (the warp of all four lamps) and its split partner (the
   same method, each lamp alone with its own warp), at each rung of the
   mixture: its image RMSE and each lamp's (its share: the lamp's solve
   under the mixture's warp), against the partner's at the same traced
   shadow rays per pixel (log-log between its rungs). */
static void lamps_table(FILE *out, const scene *s, const ladder *lad, int ncfg)
{
    int i, j, k, l;
    fprintf(out, "\nThe mixture warp against one solve per lamp at equal traced shadow rays (the split's "
                 "figures log-log between its rungs at the mixture's traced count; - outside its ladder): "
                 "relative RMSE of the image and of each lamp's light (without the pixels next to a "
                 "lamp), mixture / split and their ratio.\n\n");
    fprintf(out, "| configuration | budget | traced / px | image |");
    for (l = 0; l < s->nlights; ++l) fprintf(out, " lamp %d |", l + 1);
    fprintf(out, "\n|---|---|---:|---:|");
    for (l = 0; l < s->nlights; ++l) fprintf(out, "---:|");
    fprintf(out, "\n");
    for (i = 0; i < ncfg; ++i) {
        const ladder *m = &lad[i], *p = NULL;
        double xs[MAX_RUNGS], ys[MAX_LIGHTS + 1][MAX_RUNGS];
        char buf[64];
        if (m->cf->base != HRM_RUN || !m->cf->warp || m->cf->split) continue;
        for (j = 0; j < ncfg; ++j)
            if (lad[j].cf->base == HRM_RUN && lad[j].cf->warp && lad[j].cf->split &&
                lad[j].cf->method == m->cf->method)
                p = &lad[j];
        if (!p) continue;
        for (k = 0; k < p->n; ++k) {
            xs[k] = p->r[k].cost[C_TRACED];
            ys[0][k] = p->r[k].rmse[0];
            for (l = 0; l < s->nlights; ++l) ys[l + 1][k] = p->r[k].light_rmse[l];
        }
        for (k = 0; k < m->n; ++k) {
            const rung_result *r = &m->r[k];
            double T = r->cost[C_TRACED];
            fprintf(out, "| %s | %s | %.1f |", m->cf->name, label_of(m->cf, r->q, buf, sizeof buf), T);
            for (l = 0; l <= s->nlights; ++l) {
                double mine = l == 0 ? r->rmse[0] : r->light_rmse[l - 1], theirs = loglog_at(xs, ys[l], p->n, T);
                if (theirs > 0 && mine >= 0)
                    fprintf(out, " %.2g / %.2g (%.2f) |", mine, theirs, mine / theirs);
                else
                    fprintf(out, " %.2g / - |", mine);
            }
            fprintf(out, "\n");
        }
    }
}

static int study(const scene *s, const config *cfg, int ncfg, double budget, double exposure,
                 const char *dir, FILE *md)
{
    static const config refc = {"REFERENCE", REFERENCE, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, 0, {0}};
    frame ref, check, work, shares;
    ladder *lad = (ladder *)calloc((size_t)ncfg, sizeof(ladder));
    tile tiles[16];
    char path[512], buf[64], dbuf[160];
    double agree[2], atol, cpu_budget = -1, refcost[NCOST], chkcost[NCOST];
    long near = 0;
    int i, j, k, ok = 1;
    size_t px;
    image8 im;

    if (!lad || !frame_alloc(&ref, s) || !frame_alloc(&check, s) || !frame_alloc(&work, s) ||
        !frame_alloc(&shares, s))
        return 0;
    /* the reference at twice the panels, checked against the count */
    render(s, &refc, 2 * s->ref_panels, &ref);
    render(s, &refc, s->ref_panels, &check);
    frame_costs(&ref, refcost);
    frame_costs(&check, chkcost);
    agree[0] = rel_rmse(&check, &ref, 0);
    agree[1] = rel_rmse(&check, &ref, 1);
    atol = 1e-4 * mean_pixel(&ref);
    for (px = 0; px < (size_t)s->w * s->h; ++px) near += (ref.in[px] & 5) == 5;
    depth_text(&ref, dbuf, sizeof dbuf);
    fprintf(md, "\n## %s (%dx%d)\n\n", s->name, s->w, s->h);
    fprintf(md, "Reference: composite Gauss-Legendre, %d nodes a panel, about %d panels a ray graded "
                "towards the light's foot and cut at the geometry's breakpoints (%.0f Li, %.0f density "
                "lookups per pixel, %.1f CPU s); against %d panels: relative RMSE %.2g (%.2g over all "
                "pixels), %s a tenth of the smallest RMSE the tables report (1e-3). %s. "
                "Pixels next to the light (their ray within one pixel's footprint of it): %ld. "
                "atol for the statuses: 1e-4 of the mean pixel, %.3g.\n\n",
            GL_N, 2 * s->ref_panels, refcost[C_LI], refcost[C_LOOKUPS], refcost[C_CPU] + chkcost[C_CPU],
            s->ref_panels, agree[0], agree[1], agree[0] < 1e-4 && agree[1] < 1e-4 ? "below" : "NOT below",
            dbuf, near, atol);
    printf("%s (%dx%d): reference %.0f Li/px, %.1f CPU s; at half its panels it differs by %.2g (all "
           "pixels %.2g); %s\n",
           s->name, s->w, s->h, refcost[C_LI], refcost[C_CPU] + chkcost[C_CPU], agree[0], agree[1], dbuf);
    snprintf(path, sizeof path, "%s/%s_reference.png", dir, s->name);
    if (image8_alloc(&im, s->w, s->h)) {
        to_image(&ref, exposure, &im);
        ok &= png_write(path, &im);
        image8_free(&im);
    }

    fprintf(md, "| configuration | budget | Li / px | traced / px | lookups / px (camera rays) | CPU s | relative RMSE "
                "| all pixels | pixels warned | silent | false alarms |\n");
    fprintf(md, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (i = 0; i < ncfg; ++i) {
        ladder *l = &lad[i];
        double best = 1e300, bestt = 1e300;
        l->cf = &cfg[i];
        if (!frame_alloc(&l->best, s) || !frame_alloc(&l->at_time, s)) return 0;
        for (k = 0; k < cfg[i].nrungs; ++k) {
            rung_result *r = &l->r[l->n++];
            render(s, &cfg[i], cfg[i].rung[k], &work);
            r->q = cfg[i].rung[k];
            r->rmse[0] = rel_rmse(&work, &ref, 0);
            r->rmse[1] = rel_rmse(&work, &ref, 1);
            frame_costs(&work, r->cost);
            r->camera = (double)(work.lookups - work.shadow_lookups) / ((double)s->w * s->h);
            warned_text(&work, r->warned, sizeof r->warned);
            r->silent = r->alarms = -1;
            if (adaptive(&cfg[i])) judge(&work, &ref, r->q, atol, &r->silent, &r->alarms);
            for (j = 0; j < MAX_LIGHTS; ++j) r->light_rmse[j] = -1;
            if (s->kind == LAMPS && cfg[i].base == HRM_RUN && cfg[i].warp) {
                /* each lamp's error: the split's solves, or the
                   mixture's shares (rendered apart, not costed) */
                config sc = cfg[i];
                if (!cfg[i].split) {
                    sc.base = HRM_SHARES;
                    render(s, &sc, r->q, &shares);
                }
                for (j = 0; j < s->nlights; ++j) r->light_rmse[j] = light_rmse(cfg[i].split ? &work : &shares, &ref, j);
            }
            fprintf(md, "| %s | %s | %.1f | %.1f | %.1f (%.1f) | %.3f | %.3g | %.3g | %s |", cfg[i].name,
                    label_of(&cfg[i], r->q, buf, sizeof buf), r->cost[C_LI], r->cost[C_TRACED],
                    r->cost[C_LOOKUPS], r->camera, r->cost[C_CPU], r->rmse[0], r->rmse[1], r->warned);
            if (r->silent >= 0)
                fprintf(md, " %ld | %ld |\n", r->silent, r->alarms);
            else
                fprintf(md, " - | - |\n");
            printf("  %-28s %-12s %7.1f Li/px %7.1f traced %8.1f lookups %7.2f CPU s  rmse %.3g (all %.3g)",
                   cfg[i].name, label_of(&cfg[i], r->q, buf, sizeof buf), r->cost[C_LI], r->cost[C_TRACED],
                   r->cost[C_LOOKUPS], r->cost[C_CPU], r->rmse[0], r->rmse[1]);
            if (r->silent >= 0) printf("  silent %ld, false alarms %ld", r->silent, r->alarms);
            printf("\n");
            fflush(stdout);
            if (fabs(log(r->cost[C_LI] / budget)) < best) {
                best = fabs(log(r->cost[C_LI] / budget));
                frame_copy(&l->best, &work);
                memcpy(l->best_cost, r->cost, sizeof r->cost);
            }
            if (cpu_budget > 0 && fabs(log(r->cost[C_CPU] / cpu_budget)) < bestt) {
                bestt = fabs(log(r->cost[C_CPU] / cpu_budget));
                frame_copy(&l->at_time, &work);
                memcpy(l->at_time_cost, r->cost, sizeof r->cost);
            }
            /* past both targets (with a margin), and past the sheet's
               budget or (adaptive methods) down to rtol 1e-3, where
               the statuses are judged */
            if (r->rmse[0] < 5e-4 && r->rmse[1] < 5e-4 &&
                (adaptive(&cfg[i]) ? r->q <= 1.01e-3 : r->cost[C_LI] > budget))
                break;
        }
        if (i == 0) { /* the first baseline sets the equal-time budget */
            cpu_budget = l->best_cost[C_CPU];
            frame_copy(&l->at_time, &l->best);
            memcpy(l->at_time_cost, l->best_cost, sizeof l->best_cost);
        }
    }

    fprintf(md, "\nInterpolated between rungs (log-log; <= where a ladder's first rung is already "
                "below the target). x: the best baseline's cost (the least of the marches' at that "
                "RMSE, cost by cost) over the configuration's, above 1 where it pays less.\n");
    printf("\n%s: equal-RMSE tables\n", s->name);
    for (k = 0; k < 2; ++k) {
        equal_rmse_tables(md, lad, ncfg, k);
        equal_rmse_tables(stdout, lad, ncfg, k);
    }
    if (s->kind == LAMPS) {
        lamps_table(md, s, lad, ncfg);
        lamps_table(stdout, s, lad, ncfg);
    }

    /* the sheets: the reference, then each configuration */
    tiles[0].name = "REFERENCE";
    tiles[0].f = &ref;
    tiles[0].li = -1;
    for (k = 0; k < 2; ++k) {
        for (i = 0; i < ncfg && i < 15; ++i) {
            const frame *f = k == 0 ? &lad[i].best : &lad[i].at_time;
            const double *c = k == 0 ? lad[i].best_cost : lad[i].at_time_cost;
            tiles[i + 1].name = cfg[i].name;
            tiles[i + 1].f = f;
            tiles[i + 1].rmse = rel_rmse(f, &ref, 0);
            tiles[i + 1].li = c[C_LI];
            tiles[i + 1].cpu = c[C_CPU];
        }
        snprintf(path, sizeof path, "%s/%s_%s.png", dir, s->name, k == 0 ? "overview" : "equal_time");
        snprintf(buf, sizeof buf, "%s: %s %.3g", s->name, k == 0 ? "EQUAL LI/PX NEAR" : "EQUAL CPU S NEAR",
                 k == 0 ? budget : cpu_budget);
        ok &= write_sheet(path, s, &ref, tiles, (ncfg < 15 ? ncfg : 15) + 1, exposure, buf);
    }
    fprintf(md, "\nSheets: `%s_overview.png` (each configuration at the rung nearest %.0f Li calls "
                "per pixel), `%s_equal_time.png` (nearest %.3f CPU s, the first baseline's there); "
                "error maps: |error| / mean reference, log scale 1e-4 (black) to 1e-1 (white).\n",
            s->name, budget, s->name, cpu_budget);
    for (i = 0; i < ncfg; ++i) {
        frame_free(&lad[i].best);
        frame_free(&lad[i].at_time);
    }
    free(lad);
    frame_free(&ref);
    frame_free(&check);
    frame_free(&work);
    frame_free(&shares);
    return ok;
}

/* ======================================================================
   The configurations of each scene
   ====================================================================== */
#define FIXED_RUNGS 10, {4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048}
#define SIMPSON_RUNGS 9, {2, 4, 8, 16, 32, 64, 128, 256, 512}
#define RTOL_RUNGS 8, {3e-1, 1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "render/out";
    const char *which = argc > 2 ? argv[2] : "all";
    int quick = argc > 3 && strcmp(argv[3], "quick") == 0, ok = 1;
    /* the baselines first (the first sets the equal-time budget); fields:
       name, base, method, warp, breaks, split, exponential, h_max,
       gk_local, rungs */
    static const config shafts_cfg[] = {
        {"MARCH UNIFORM", BASE_UNIFORM, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"MARCH EQUIANGULAR", BASE_EQUIANGULAR, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"SIMPSON WARP BREAKS", HRM_RUN, HRM_SIMPSON, 1, 1, 0, 0, 0, 0, SIMPSON_RUNGS},
        {"NESTED SIMPSON", HRM_RUN, HRM_NESTED_SIMPSON, 0, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"DORMAND-PRINCE WARP", HRM_RUN, HRM_DORMAND_PRINCE, 1, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"GK K7 WARP BREAKS", HRM_RUN, HRM_GAUSS_KRONROD, 1, 1, 0, 0, 0, 1, RTOL_RUNGS},
        {"NESTED SIMPSON WARP BREAKS", HRM_RUN, HRM_NESTED_SIMPSON, 1, 1, 0, 0, 0, 0, RTOL_RUNGS},
    };
    /* the cloud's features are about 0.1 across. The adaptive methods
       start from their defaults: the medium scan sees a blob between
       their first nodes and the layer's and makes its edges (where sigma
       rises from 0) breakpoints, and the medium check sends the nodes
       where the layer saw the medium. Dormand-Prince takes steps of at
       most 0.1 */
    static const config cloud_cfg[] = {
        {"MARCH UNIFORM", BASE_UNIFORM, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"MARCH EQUIANGULAR", BASE_EQUIANGULAR, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"SIMPSON EXP", HRM_RUN, HRM_SIMPSON, 0, 0, 0, 1, 0, 0, SIMPSON_RUNGS},
        {"NESTED SIMPSON", HRM_RUN, HRM_NESTED_SIMPSON, 0, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"GK K7 EXP", HRM_RUN, HRM_GAUSS_KRONROD, 0, 0, 0, 1, 0, 1, RTOL_RUNGS},
        {"DORMAND-PRINCE EXP", HRM_RUN, HRM_DORMAND_PRINCE, 0, 0, 0, 1, 0.1, 0, RTOL_RUNGS},
        {"NESTED SIMPSON SPLIT WARP", HRM_RUN, HRM_NESTED_SIMPSON, 1, 0, 1, 0, 0, 0, RTOL_RUNGS},
    };
    /* the smoke: the adaptive methods from their defaults, then with the
       spot's warp and breakpoints (the occluder's shadow, the spot's
       cones) */
    static const config smoke_cfg[] = {
        {"MARCH UNIFORM", BASE_UNIFORM, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"MARCH EQUIANGULAR", BASE_EQUIANGULAR, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"SIMPSON WARP BREAKS", HRM_RUN, HRM_SIMPSON, 1, 1, 0, 0, 0, 0, SIMPSON_RUNGS},
        {"NESTED SIMPSON", HRM_RUN, HRM_NESTED_SIMPSON, 0, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"GAUSS-KRONROD", HRM_RUN, HRM_GAUSS_KRONROD, 0, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"DORMAND-PRINCE", HRM_RUN, HRM_DORMAND_PRINCE, 0, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"GK K7 WARP BREAKS", HRM_RUN, HRM_GAUSS_KRONROD, 1, 1, 0, 0, 0, 1, RTOL_RUNGS},
        {"DORMAND-PRINCE WARP BREAKS", HRM_RUN, HRM_DORMAND_PRINCE, 1, 1, 0, 0, 0, 0, RTOL_RUNGS},
        {"NESTED SIMPSON WARP BREAKS", HRM_RUN, HRM_NESTED_SIMPSON, 1, 1, 0, 0, 0, 0, RTOL_RUNGS},
    };
    /* the lamps: Simpson and nested Simpson with the four lamps described
       to hrm_light_options at once (the mixture warp, one solve, each Li
       four shadow rays) and one solve per lamp described alone (its
       equiangular warp, each Li one shadow ray) */
    static const config lamps_cfg[] = {
        {"MARCH UNIFORM", BASE_UNIFORM, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"MARCH EQUIANGULAR", BASE_EQUIANGULAR, HRM_METHOD_DEFAULT, 0, 0, 0, 0, 0, 0, FIXED_RUNGS},
        {"SIMPSON MIXTURE", HRM_RUN, HRM_SIMPSON, 1, 0, 0, 0, 0, 0, SIMPSON_RUNGS},
        {"SIMPSON PER LAMP", HRM_RUN, HRM_SIMPSON, 1, 0, 1, 0, 0, 0, SIMPSON_RUNGS},
        {"NESTED SIMPSON", HRM_RUN, HRM_NESTED_SIMPSON, 0, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"NESTED SIMPSON MIXTURE", HRM_RUN, HRM_NESTED_SIMPSON, 1, 0, 0, 0, 0, 0, RTOL_RUNGS},
        {"NESTED SIMPSON PER LAMP", HRM_RUN, HRM_NESTED_SIMPSON, 1, 0, 1, 0, 0, 0, RTOL_RUNGS},
    };
    scene s;
    gl_rule gl;
    char path[512];
    FILE *md;

    gl_init(&gl);
    snprintf(path, sizeof path, "%s/summary.md", dir);
    md = fopen(path, "w");
    if (!md) {
        fprintf(stderr, "render: cannot write %s (does the directory exist?)\n", path);
        return 1;
    }
    fprintf(md, "# make render\n\nRelative RMSE: sqrt(sum (image - reference)^2 / sum reference^2) over "
                "the pixels whose ray meets the medium, every channel: without the pixels whose ray "
                "passes within one pixel's footprint of the point or spot light, and over all. Costs "
                "per pixel: Li calls; traced shadow rays (the rays towards a light that Li traces); "
                "density lookups (camera and shadow rays, in brackets the camera rays' alone; the shafts' medium is constant: none); CPU "
                "seconds for the image (thread CPU time summed over %d threads, this machine). "
                "Baselines (MARCH ...): hand-written, per-step analytic extinction, one jittered "
                "offset per pixel. Silent: pixels with a camera solve that returned HRM_OK off the "
                "reference by more than 3 rtol |L_ref| + atol in a channel; false alarms: pixels with "
                "a solve that warned yet is within rtol |L_ref| + atol in every channel (adaptive "
                "methods; pixels warned also counts the shadow rays' warnings).\n",
            nthreads());
    if (strcmp(which, "all") == 0 || strcmp(which, "shafts") == 0) {
        make_shafts(&s, quick);
        s.gl = &gl;
        ok &= study(&s, shafts_cfg, (int)(sizeof shafts_cfg / sizeof shafts_cfg[0]), 32, 5.0, dir, md);
    }
    if (strcmp(which, "all") == 0 || strcmp(which, "cloud") == 0) {
        make_cloud(&s, quick);
        s.gl = &gl;
        ok &= study(&s, cloud_cfg, (int)(sizeof cloud_cfg / sizeof cloud_cfg[0]), 32, 1.0, dir, md);
    }
    if (strcmp(which, "all") == 0 || strcmp(which, "smoke") == 0) {
        make_smoke(&s, quick);
        s.gl = &gl;
        ok &= study(&s, smoke_cfg, (int)(sizeof smoke_cfg / sizeof smoke_cfg[0]), 32, 3.0, dir, md);
    }
    if (strcmp(which, "all") == 0 || strcmp(which, "lamps") == 0) {
        make_lamps(&s, quick);
        s.gl = &gl;
        ok &= study(&s, lamps_cfg, (int)(sizeof lamps_cfg / sizeof lamps_cfg[0]), 32, 1.0, dir, md);
    }
    fclose(md);
    printf("wrote %s/summary.md\n", dir);
    return ok ? 0 : 1;
}
