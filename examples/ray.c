/* ray.c - one camera ray through a heterogeneous, emitting medium lit by a
   point light: what a renderer's volume integrator does per pixel with hrm.h.
   First fixed step counts against a converged run, then an adaptive method
   as a renderer sets it up: rtol from the bench's advice, the light's
   equiangular warp, and a budget of samples per ray.

   Build: make examples   (or: cc -std=c99 -O2 -I.. ray.c -lm)

   To adopt it, keep the callbacks' shape and replace density() by your
   grid lookup and in_scattered()'s single light by your light loop. */
#define HRM_IMPLEMENTATION
#include "hrm.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#if HRM_CHANNELS != 3
#error "this example is written for RGB (HRM_CHANNELS 3)"
#endif

#define PI 3.14159265358979323846

/* Read-only scene data, shared by every ray (and thread). */
typedef struct scene {
    double center[3], width, peak;   /* Gaussian density blob */
    double absorb[3], scatter[3];    /* sigma_a, sigma_s per unit density */
    double extinct[3];               /* their sum, for shadow rays */
    double glow[3];                  /* Le of the gas at peak density */
    double light_pos[3], light_I[3]; /* point light: radiant intensity */
    double g;                        /* Henyey-Greenstein asymmetry */
    const hrm_options *shadow;       /* how shadow rays are integrated */
} scene;

/* The medium's user pointer. Callbacks receive only t, so each ray carries
   the origin and direction that turn t into a point; being per ray, it is
   also where a callback may write without locking. */
typedef struct ray {
    const scene *s;
    double o[3], d[3];        /* origin, unit direction */
    hrm_status shadow_status; /* first shadow-ray problem: Li returns void */
    long shadow_medium_evals; /* the real cost of Li, invisible to hrm */
} ray;

static double density(const ray *r, hrm_real t) {
    double d2 = 0;
    int i;
    for (i = 0; i < 3; ++i) {
        double x = r->o[i] + (double)t * r->d[i] - r->s->center[i];
        d2 += x * x;
    }
    return r->s->peak * exp(-0.5 * d2 / (r->s->width * r->s->width));
}

/* sigma_a, sigma_s and sigma_t all follow the density: rho(t) * k. The
   camera ray takes sigma_a and sigma_s from one density lookup
   (medium.sigma); shadow rays need extinction only (medium.sigma_t). */
static void coefficients(void *user, hrm_real t, hrm_real sa[HRM_CHANNELS],
                         hrm_real ss[HRM_CHANNELS]) {
    const ray *r = (const ray *)user;
    double rho = density(r, t);
    int c;
    for (c = 0; c < 3; ++c) {
        sa[c] = (hrm_real)(rho * r->s->absorb[c]);
        ss[c] = (hrm_real)(rho * r->s->scatter[c]);
    }
}
static void sigma_t(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
    const ray *r = (const ray *)user;
    double rho = density(r, t);
    int c;
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(rho * r->s->extinct[c]);
}

/* Le is the radiance of the hot gas, not a source per length: hrm
   multiplies it by sigma_a (pbrt-v4; set HRM_EMISSION_PER_LENGTH for the
   other convention). Squaring the density makes the core glow hotter. */
static void emitted(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
    const ray *r = (const ray *)user;
    double heat = density(r, t) / r->s->peak;
    int c;
    for (c = 0; c < 3; ++c) out[c] = (hrm_real)(r->s->glow[c] * heat * heat);
}

/* In-scattered radiance toward the camera at t: the light's inverse-square
   irradiance, attenuated along the shadow ray, times the phase function.
   This is the expensive call that hrm counts in stats.evals. */
static void in_scattered(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
    ray *r = (ray *)user;
    const scene *s = r->s;
    ray shadow = *r;
    hrm_medium m;
    hrm_real Tr[HRM_CHANNELS];
    hrm_stats st;
    hrm_status status;
    double dist = 0, cos_theta = 0, denom, phase;
    int i;

    for (i = 0; i < 3; ++i) {
        shadow.o[i] = r->o[i] + (double)t * r->d[i];
        shadow.d[i] = s->light_pos[i] - shadow.o[i];
        dist += shadow.d[i] * shadow.d[i];
    }
    dist = sqrt(dist);
    for (i = 0; i < 3; ++i) {
        shadow.d[i] /= dist;
        /* Scattering angle: light arrives along -shadow.d, leaves along -d. */
        cos_theta += shadow.d[i] * r->d[i];
    }

    /* A nested solve on the same medium, from inside a callback of the
       running one: hrm keeps no state between calls, so this is allowed. */
    memset(&m, 0, sizeof m); /* all absent; {0} is C-only under g++ -Wextra */
    m.user = &shadow;
    m.sigma_t = sigma_t;
    status = hrm_transmittance(&m, 0, (hrm_real)dist, s->shadow, Tr, &st);
    r->shadow_medium_evals += st.medium_evals;
    if (status != HRM_OK && r->shadow_status == HRM_OK) r->shadow_status = status;

    denom = 1 + s->g * s->g - 2 * s->g * cos_theta;
    phase = (1 - s->g * s->g) / (4 * PI * denom * sqrt(denom));
    for (i = 0; i < 3; ++i)
        out[i] = (hrm_real)(phase * (double)Tr[i] * s->light_I[i] / (dist * dist));
}

int main(void) {
    /* The first run is converged (same shadow rays): the others' yardstick. */
    static const struct { hrm_method method; int steps; } runs[] = {
        {HRM_SIMPSON, 4096}, {HRM_SIMPSON, 8}, {HRM_SIMPSON, 16}, {HRM_RK4, 16},
        {HRM_ADAMS_BASHFORTH, 32}, {HRM_RECTANGLE, 64}, {HRM_MONTE_CARLO, 64},
    };
    const double t_wall = 10, L_wall[3] = {0.20, 0.18, 0.15};
    hrm_options opt, shadow_opt = hrm_default_options(HRM_SIMPSON);
    scene s = {
        {0.3, 0.0, 5.0}, 1.0, 1.2,          /* blob: centre, width, peak */
        {0.05, 0.05, 0.06}, {0.50, 0.55, 0.60}, {0.55, 0.60, 0.66},
        {4.0, 1.2, 0.3},                    /* glow: orange-hot core */
        {1.5, 3.0, 7.0}, {40.0, 38.0, 34.0},
        0.4, &shadow_opt                    /* mildly forward scattering */
    };
    ray r = {&s, {0, 0, 0}, {0, 0, 1}, HRM_OK, 0};
    hrm_medium m;
    hrm_result ref, res;
    hrm_status status;
    size_t k;
    int c;

    /* Every camera-ray sample fires a shadow ray: keep them cheap. Their
       error reaches L only through the scattering term. */
    shadow_opt.steps = 8;
    memset(&m, 0, sizeof m);
    m.user = &r;
    m.sigma = coefficients; /* one lookup: sigma_a and sigma_s (sigma_t their sum) */
    m.Le = emitted;
    m.Li = in_scattered;

    for (k = 0; k < sizeof runs / sizeof runs[0]; ++k) {
        double err = 0, pixel[3];
        opt = hrm_default_options(runs[k].method);
        opt.steps = runs[k].steps;
        opt.jitter = 1;     /* rectangle: trades banding for noise */
        opt.stratified = 1; /* Monte Carlo: one sample per segment */
        opt.seed = 12345;   /* a renderer hashes the pixel into it */
        r.shadow_status = HRM_OK;
        r.shadow_medium_evals = 0;

        status = hrm_solve(&m, 0, (hrm_real)t_wall, &opt, &res);
        if (status != HRM_OK || r.shadow_status != HRM_OK)
            fprintf(stderr, "%s: %s; shadow rays: %s\n", hrm_method_name(opt.method),
                    hrm_status_string(status), hrm_status_string(r.shadow_status));
        if (status < 0) return 1; /* no usable answer (L = 0, Tr = 1) */
        if (k == 0) ref = res;

        /* The pixel: the medium's own radiance plus the wall seen through it. */
        for (c = 0; c < 3; ++c) {
            double e = fabs((double)(res.L[c] - ref.L[c])) / (double)ref.L[c];
            pixel[c] = (double)res.L[c] + (double)res.Tr[c] * L_wall[c];
            if (e > err) err = e;
        }
        printf("%s%-15s %4d steps  evals %4ld  medium %4ld  shadow-ray medium %6ld"
               "  error %.1e\n", k ? "\n" : "", hrm_method_name(opt.method), opt.steps,
               res.stats.evals, res.stats.medium_evals, r.shadow_medium_evals, err);
        printf("    L %.6f %.6f %.6f  Tr %.6f %.6f %.6f  L + Tr*L_wall %.6f %.6f %.6f\n",
               (double)res.L[0], (double)res.L[1], (double)res.L[2],
               (double)res.Tr[0], (double)res.Tr[1], (double)res.Tr[2],
               pixel[0], pixel[1], pixel[2]);
    }

    /* An adaptive method instead of a step count, set up as a renderer
       would: rtol from the bench's advice (README, Tolerances: 1e-2 for
       previews, 1e-3 for final frames: the relative error the image can
       take, not a safety factor below it), the point light's equiangular
       warp, and a budget per ray (max_evals: the most shadow rays this
       pixel may cost; past it the call returns HRM_WARN_MAX_EVALS with its
       best estimate and result.error says how far it may be off). */
    {
        static const struct { double rtol; long budget; } advice[] = {
            {1e-2, 0}, {1e-3, 0}, {1e-3, 16}};
        hrm_real origin[3] = {0, 0, 0}, dir[3] = {0, 0, 1}, light[3];
        for (c = 0; c < 3; ++c) light[c] = (hrm_real)s.light_pos[c];
        for (k = 0; k < sizeof advice / sizeof advice[0]; ++k) {
            double err = 0, est = 0;
            opt = hrm_default_options(HRM_NESTED_SIMPSON);
            opt.rtol = (hrm_real)advice[k].rtol;
            opt.max_evals = advice[k].budget; /* 0: the default, 100000 */
            if (hrm_equiangular_warp(origin, dir, light, &opt.warp) != HRM_OK)
                opt.warp.kind = HRM_WARP_NONE; /* a direction or position not finite */
            r.shadow_status = HRM_OK;
            status = hrm_solve(&m, 0, (hrm_real)t_wall, &opt, &res);
            if (status < 0) return 1;
            for (c = 0; c < 3; ++c) {
                double e = fabs((double)(res.L[c] - ref.L[c])) / (double)ref.L[c];
                double q = (double)res.error[c] / (double)res.L[c];
                if (e > err) err = e;
                if (q > est) est = q;
            }
            printf("\nnested-simpson  rtol %.0e  budget %-6s evals %4ld  %s\n"
                   "    error %.1e (estimated %.1e)\n", advice[k].rtol,
                   advice[k].budget ? "16" : "none", res.stats.evals,
                   hrm_status_string(status), err, est);
        }
    }
    return 0;
}
