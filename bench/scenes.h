/* bench/scenes.h - the benchmark's scenes (defined in scenes.c).

   Every scene is one ray x(s) = (s, 0, 0), s in [t0, t1], through a medium,
   given twice: as an hrm_medium (double callbacks, what hrm sees) and as a
   long double integrand Tr(t0, s) S(s) with its split points, or a closed
   form, for the reference (reference.h). The two share only the parameter
   values. The first three are the scenes of Munoz 2014 Fig. 4; then a
   smooth and a high-frequency heterogeneous medium, emission alone, an
   optically thick and an optically thin medium, and a spotlight in smoke
   (heterogeneous medium, point light, closed-form optical depths).

   Each scene also names its natural warp (importance sampling, Munoz 2014
   s.5): distance for directional light and heterogeneous media, equiangular
   toward the point light where there is one.

   A homogeneous scene's medium can be given to hrm two ways (bench_medium_id):
   as constants (HRM_MEDIUM_HOMOGENEOUS, closed-form Tr, no medium
   evaluation) or as sigma callbacks that return the same constants, so that
   hrm integrates tau as for any heterogeneous medium. */
#ifndef BENCH_SCENES_H
#define BENCH_SCENES_H

#include <stdio.h>

#include "hrm.h"
#include "reference.h"

#if HRM_CHANNELS != 3
#error "the benchmark scenes are written for HRM_CHANNELS == 3"
#endif

#define BENCH_PI 3.14159265358979323846
#define BENCH_PI_L 3.141592653589793238462643383279502884L
#define BENCH_PHASE (0.25 / BENCH_PI)      /* isotropic phase function, 1/(4 pi) */
#define BENCH_PHASE_L (0.25L / BENCH_PI_L)

/* Callbacks, for counting: the three medium ones, then the two source ones. */
enum {
    BENCH_CB_SIGMA_A = 1,
    BENCH_CB_SIGMA_S = 2,
    BENCH_CB_TR = 4,      /* the transmittance callback */
    BENCH_CB_LE = 8,
    BENCH_CB_LI = 16
};

/* The callbacks hrm made during one solve. A medium evaluation (hrm_stats.
   medium_evals) is one abscissa's sigma and/or transmittance callbacks: the
   bench counts a run of consecutive medium callbacks at one abscissa (tb for
   the transmittance), none of them twice, as one. */
typedef struct bench_counts {
    long sigma_a, sigma_s, tr, le, li;
    long medium;          /* medium evaluations, counted as above */
    unsigned run;         /* the open run's callbacks (BENCH_CB_*); 0: none */
    double run_t;         /* and its abscissa */
} bench_counts;

/* The user pointer of every medium: the scene's parameters, the callback
   counts, and what the generic wrappers below need. */
typedef struct bench_calls {
    const void *params;
    bench_counts n;
    double const_sigma_a[3], const_sigma_s[3]; /* bench_medium_as_sigma */
    hrm_spectrum_fn inner_li;                  /* bench_medium_busy_li */
    long busy_iters;
} bench_calls;

#define BENCH_PARAMS(type, user) ((const type *)((const bench_calls *)(user))->params)

/* Counts one callback (BENCH_CB_*) at abscissa t. */
void bench_count(void *user, unsigned which, hrm_real t);

typedef enum bench_warp_id {
    BENCH_WARP_NONE,
    BENCH_WARP_DISTANCE,    /* sigma_ref 0: hrm's choice, the thinnest channel's mean extinction over the ray */
    BENCH_WARP_EQUIANGULAR, /* toward the scene's point light */
    BENCH_WARP_COUNT
} bench_warp_id;

/* How the medium is given to hrm. */
typedef enum bench_medium_id {
    BENCH_MEDIUM_CONST,     /* HRM_MEDIUM_HOMOGENEOUS with constants */
    BENCH_MEDIUM_SIGMA,     /* sigma callbacks (heterogeneous scenes: only this) */
    BENCH_MEDIUM_COUNT
} bench_medium_id;

typedef struct bench_scene {
    const char *name;
    const char *description;             /* one line */
    const void *params;
    double t0, t1;
    int smooth;                          /* integrand analytic along the ray */
    bench_warp_id natural_warp;
    /* The point light's position (the ray is x(s) = (s, 0, 0)); NULL or 0:
       none, and no equiangular warp. */
    int (*light)(const void *params, double pos[3]);
    long double ref_panel;               /* reference panel width; 0: REF_PANEL */
    void (*print_params)(FILE *out, const void *params);
    /* Fills all of the medium but user. A homogeneous scene sets
       HRM_MEDIUM_HOMOGENEOUS; bench_medium_as_sigma turns it into callbacks. */
    void (*build)(const void *params, hrm_medium *medium);
    /* The exact eye-ray transmittance Tr(ta, tb) in closed form, for hrm's
       transmittance callback (NULL: none written). */
    hrm_transmittance_fn transmittance;
    /* The reference: Tr(t0, s) S(s) in long double, the points in (t0, t1)
       where it is not smooth (NULL: none), and a closed form (NULL: none). */
    ref_integrand_fn integrand;
    int (*split_points)(const void *params, long double out[], int max);
    void (*closed_form)(const void *params, long double t0, long double t1,
                        long double L[HRM_CHANNELS]);
} bench_scene;

extern const bench_scene bench_scenes[];
extern const int bench_scene_count;

/* The breakpoints a renderer would give for the scene's ray: the
   occluder's shadow edges from hrm_sphere_breaks; out[0..1], the count
   returned (0 for a scene without an occluder). */
int bench_scene_breaks(const bench_scene *sc, hrm_real out[2]);

/* The scene's medium as hrm sees it, given as `how`, with user = calls
   (whose counts are cleared). Returns 0 if the scene cannot be given that
   way (a heterogeneous scene as constants). */
int bench_medium_build(const bench_scene *sc, bench_medium_id how, hrm_medium *m,
                       bench_calls *calls);

/* Makes the medium's Li cost about `iters` dependent floating-point
   operations more (bench_busy), without changing its value beyond a
   rounding of 1e-300: the Li of a renderer that traces a shadow ray. */
void bench_medium_busy_li(hrm_medium *m, bench_calls *calls, long iters);

/* `iters` dependent multiply-adds from x; converges to 0.5 (never 0). */
double bench_busy(long iters, double x);

#endif
