/* render.c - a small volume renderer on hrm.h: a smoke cloud inside a
   sphere, lit by a point light through shadow rays, in front of a sky.
   Writes a binary PPM.

   usage: render [out.ppm [method [steps]]]
     out.ppm  output path (default render.ppm)
     method   a name printed by hrm_method_name: simpson (default), rk4, ...
     steps    options.steps of each camera ray (default 16; shadow rays: 6)
   Build: make examples   (or: cc -std=c99 -O2 -I.. render.c -lm) */
#define HRM_IMPLEMENTATION
#include "hrm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if HRM_CHANNELS != 3
#error "this example is written for RGB (HRM_CHANNELS 3)"
#endif

#define WIDTH 256
#define HEIGHT 256
#define PI 3.14159265358979323846

/* Read-only scene data, shared by every ray. */
typedef struct cloud {
    double center[3], radius, peak;  /* density support and its maximum */
    double absorb[3], scatter[3];    /* sigma_a, sigma_s per unit density */
    double extinct[3];               /* their sum, for shadow rays */
    double light_pos[3], light_I[3]; /* point light: radiant intensity */
    double ambient[3];               /* crude stand-in for sky light and
                                        multiple scattering */
    double g;                        /* Henyey-Greenstein asymmetry */
    const hrm_options *shadow;       /* how shadow rays are integrated */
} cloud;

/* The medium's user pointer: per ray, so callbacks may write to it. */
typedef struct ray {
    const cloud *cl;
    double o[3], d[3];        /* origin, unit direction */
    hrm_status shadow_status; /* first shadow-ray problem: Li returns void */
    long shadow_medium_evals;
} ray;

/* Where the ray (unit d) is inside the sphere, for t >= 0. 0: nowhere. */
static int clip_to_sphere(const cloud *cl, const double o[3], const double d[3],
                          double *t0, double *t1) {
    double b = 0, c = -cl->radius * cl->radius, disc;
    int i;
    for (i = 0; i < 3; ++i) {
        double oc = o[i] - cl->center[i];
        b += oc * d[i];
        c += oc * oc;
    }
    disc = b * b - c;
    if (disc <= 0) return 0;
    *t0 = -b - sqrt(disc);
    *t1 = -b + sqrt(disc);
    if (*t1 <= 0) return 0;
    if (*t0 < 0) *t0 = 0;
    return 1;
}

/* Zero outside the sphere; inside, (1 - r^2)^2 softens the silhouette and
   the sines make cheap, smooth billows. Along any chord this is smooth, so
   once a ray is clipped to the sphere the fourth-order methods keep their
   order; unclipped, the seam at the surface would cost some of it. */
static double density(const ray *r, hrm_real t) {
    const cloud *cl = r->cl;
    double q[3], r2 = 0, detail;
    int i;
    for (i = 0; i < 3; ++i) {
        q[i] = (r->o[i] + (double)t * r->d[i] - cl->center[i]) / cl->radius;
        r2 += q[i] * q[i];
    }
    if (r2 >= 1) return 0;
    detail = sin(6.0 * q[0] + 1.3) * sin(5.0 * q[1] + 0.7) * sin(5.5 * q[2] + 2.1)
           + 0.5 * sin(12.0 * q[0] + 9.0 * q[2] + 0.5) * sin(11.0 * q[1] - 7.0 * q[0]);
    detail = 0.5 + 0.5 * detail / 1.5; /* in [0, 1] */
    return cl->peak * (1 - r2) * (1 - r2) * detail * detail;
}

/* sigma_a, sigma_s and sigma_t all follow the density: rho(t) * k. */
static void scaled(void *user, hrm_real t, const double k[3], hrm_real out[HRM_CHANNELS]) {
    double rho = density((const ray *)user, t);
    int c;
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(rho * k[c]);
}
static void sigma_a(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
    scaled(user, t, ((const ray *)user)->cl->absorb, out);
}
static void sigma_s(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
    scaled(user, t, ((const ray *)user)->cl->scatter, out);
}
static void sigma_t(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
    scaled(user, t, ((const ray *)user)->cl->extinct, out);
}

/* Single scattering from the point light (HG phase, inverse square, shadow
   ray through the cloud), plus the ambient term. */
static void in_scattered(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
    ray *r = (ray *)user;
    const cloud *cl = r->cl;
    ray shadow = *r;
    hrm_medium m;
    hrm_real Tr[HRM_CHANNELS] = {1, 1, 1};
    double dist = 0, cos_theta = 0, ta, tb, denom, phase;
    int i;

    for (i = 0; i < 3; ++i) {
        shadow.o[i] = r->o[i] + (double)t * r->d[i];
        shadow.d[i] = cl->light_pos[i] - shadow.o[i];
        dist += shadow.d[i] * shadow.d[i];
    }
    dist = sqrt(dist);
    for (i = 0; i < 3; ++i) {
        shadow.d[i] /= dist;
        cos_theta += shadow.d[i] * r->d[i];
    }
    /* Only the part of the shadow ray inside the sphere has any density:
       spend its steps there, as main() does for the camera ray. */
    if (clip_to_sphere(cl, shadow.o, shadow.d, &ta, &tb) && ta < dist) {
        hrm_stats st;
        hrm_status status;
        memset(&m, 0, sizeof m);
        m.user = &shadow;
        m.sigma_t = sigma_t;
        status = hrm_transmittance(&m, (hrm_real)ta, (hrm_real)(tb < dist ? tb : dist),
                                   cl->shadow, Tr, &st);
        r->shadow_medium_evals += st.medium_evals;
        if (status != HRM_OK && r->shadow_status == HRM_OK) r->shadow_status = status;
    }
    denom = 1 + cl->g * cl->g - 2 * cl->g * cos_theta;
    phase = (1 - cl->g * cl->g) / (4 * PI * denom * sqrt(denom));
    for (i = 0; i < 3; ++i)
        out[i] = (hrm_real)(phase * (double)Tr[i] * cl->light_I[i] / (dist * dist)
                            + cl->ambient[i]);
}

/* Vertical gradient: horizon haze to zenith blue, darker ground below. */
static void sky(const double d[3], double out[3]) {
    static const double horizon[3] = {0.75, 0.78, 0.82}, zenith[3] = {0.22, 0.38, 0.70},
                        ground[3] = {0.30, 0.27, 0.24};
    int c;
    for (c = 0; c < 3; ++c)
        out[c] = d[1] >= 0 ? horizon[c] + (zenith[c] - horizon[c]) * sqrt(d[1])
                           : ground[c] + (horizon[c] - ground[c]) * exp(8.0 * d[1]);
}

/* Decorrelated seeds for neighbouring pixels (splitmix64 finaliser), so
   jitter and Monte Carlo noise does not form patterns across the image. */
static uint64_t pixel_seed(int x, int y) {
    uint64_t z = (uint64_t)y * WIDTH + (uint64_t)x + 0x9e3779b97f4a7c15u;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static int usage(void) {
    int m;
    fprintf(stderr, "usage: render [out.ppm [method [steps]]]\nmethods:");
    for (m = 1; m < HRM_METHOD_COUNT; ++m)
        fprintf(stderr, " %s", hrm_method_name((hrm_method)m));
    fprintf(stderr, "\n");
    return 2;
}

int main(int argc, char **argv) {
    const char *path = argc > 1 ? argv[1] : "render.ppm";
    const double eye[3] = {0, 0, -3.2}, tan_half_fov = 0.4; /* ~44 degrees */
    hrm_method method = HRM_SIMPSON;
    hrm_options opt, shadow_opt = hrm_default_options(HRM_SIMPSON);
    cloud cl = {
        {0, 0, 0}, 1.0, 12.0,
        {0.10, 0.10, 0.10}, {0.90, 0.92, 0.95},   /* bright, faintly blue smoke */
        {1.00, 1.02, 1.05},
        {-3.0, 2.5, 0.0}, {170.0, 160.0, 140.0},  /* warm light, upper left */
        {0.06, 0.08, 0.11}, 0.3, &shadow_opt
    };
    ray r;
    hrm_medium m;
    unsigned char *image;
    long long rays = 0, steps_taken = 0, warnings = 0; /* totals for the image */
    long long evals = 0, medium_evals = 0, shadow_evals = 0;
    clock_t start;
    double seconds;
    FILE *f;
    int x, y, c, ok, steps = 16;

    if (argc > 2) { /* any method hrm.h knows, by the name it gives it */
        int k;
        for (k = 1; k < HRM_METHOD_COUNT; ++k)
            if (strcmp(argv[2], hrm_method_name((hrm_method)k)) == 0) break;
        if (k == HRM_METHOD_COUNT) return usage();
        method = (hrm_method)k;
    }
    if (argc > 3) {
        char *end;
        long n = strtol(argv[3], &end, 10);
        if (*end != '\0' || end == argv[3] || n < 1 || n > 1000000) return usage();
        steps = (int)n;
    }
    opt = hrm_default_options(method);
    opt.steps = steps;
    opt.jitter = 1;     /* rectangle rule: noise instead of banding */
    opt.stratified = 1; /* Monte Carlo: one sample per segment */
    shadow_opt.steps = 6;

    memset(&r, 0, sizeof r);
    r.cl = &cl;
    memset(&m, 0, sizeof m);
    m.user = &r;
    m.sigma_a = sigma_a;
    m.sigma_s = sigma_s;
    m.Li = in_scattered;
    image = (unsigned char *)malloc(3 * WIDTH * HEIGHT);
    if (!image) return 1;

    start = clock();
    for (y = 0; y < HEIGHT; ++y) {
        for (x = 0; x < WIDTH; ++x) {
            double d[3], len, bg[3], color[3], t0, t1;
            d[0] = (2 * (x + 0.5) / WIDTH - 1) * tan_half_fov;
            d[1] = (1 - 2 * (y + 0.5) / HEIGHT) * tan_half_fov;
            d[2] = 1;
            len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (c = 0; c < 3; ++c) d[c] /= len;
            sky(d, bg);
            memcpy(color, bg, sizeof color);

            /* Outside the sphere the medium is empty: hand hrm only the
               chord through it, so every step lands in the cloud and the
               integrand has no seam. */
            if (clip_to_sphere(&cl, eye, d, &t0, &t1)) {
                hrm_result res;
                hrm_status status;
                memcpy(r.o, eye, sizeof r.o);
                memcpy(r.d, d, sizeof r.d);
                opt.seed = pixel_seed(x, y);
                r.shadow_status = HRM_OK;
                r.shadow_medium_evals = 0;
                status = hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, &opt, &res);
                if (status < 0 || r.shadow_status < 0) {
                    fprintf(stderr, "pixel %d,%d: %s; shadow rays: %s\n", x, y,
                            hrm_status_string(status), hrm_status_string(r.shadow_status));
                    free(image);
                    return 1;
                }
                warnings += status != HRM_OK || r.shadow_status != HRM_OK;
                for (c = 0; c < 3; ++c) /* the sky seen through the cloud */
                    color[c] = (double)res.L[c] + (double)res.Tr[c] * bg[c];
                ++rays;
                steps_taken += res.stats.steps;
                evals += res.stats.evals;
                medium_evals += res.stats.medium_evals;
                shadow_evals += r.shadow_medium_evals;
            }
            for (c = 0; c < 3; ++c) { /* clamp, then gamma 2.2 */
                double v = color[c] < 0 ? 0 : color[c] > 1 ? 1 : color[c];
                image[3 * (y * WIDTH + x) + c] = (unsigned char)(255 * pow(v, 1 / 2.2) + .5);
            }
        }
    }

    seconds = (double)(clock() - start) / CLOCKS_PER_SEC;

    f = fopen(path, "wb");
    ok = f && fprintf(f, "P6\n%d %d\n255\n", WIDTH, HEIGHT) > 0 &&
         fwrite(image, 3, WIDTH * HEIGHT, f) == (size_t)(WIDTH * HEIGHT);
    if (f && fclose(f) != 0) ok = 0;
    free(image);
    if (!ok) {
        fprintf(stderr, "render: cannot write %s\n", path);
        return 1;
    }
    printf("%s: %dx%d, %s, %.1f steps per camera ray, %d per shadow ray\n", path, WIDTH,
           HEIGHT, hrm_method_name(method), rays ? (double)steps_taken / (double)rays : 0.0,
           shadow_opt.steps);
    printf("%lld camera rays through the cloud, %lld source evaluations (a shadow ray"
           " each)\n%lld medium evaluations on camera rays, %lld on shadow rays\n"
           "%lld rays with a warning, %.2f s CPU\n", rays, evals, medium_evals,
           shadow_evals, warnings, seconds);
    return 0;
}
