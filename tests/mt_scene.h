/* mt_scene.h - the scene of tests/threads.c and tests/alloc.c, two
   single-file programs that include hrm.h's implementation first: sigma_t
   = k (1 + 0.5 sin t) per channel (times 4 inside the slab [3, 5] when
   slab is set), albedo 0.7, emission 0.3, a point light D from the ray
   projecting at delta, whose Li may cast a shadow ray through
   shadow_medium: 1 hrm_transmittance, 2 hrm_solve (re-entrance). bad
   makes sigma_a NaN (1), negative (2) or beyond HRM_REAL's range (3) past
   t = 4. Read-only through the user pointer. */
#ifndef HRM_TEST_MT_SCENE_H
#define HRM_TEST_MT_SCENE_H

#include <float.h>
#include <math.h>

typedef struct mt_scene {
    double k[HRM_CHANNELS], delta, D;
    int slab, bad;
    int shadow;
    hrm_medium shadow_medium;
} mt_scene;

static double mt_sig(const mt_scene *s, int c, double t)
{
    double v = s->k[c] * (1 + 0.5 * sin(t));
    return s->slab && t >= 3 && t <= 5 ? 4 * v : v;
}

static void mt_sa(void *u, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const mt_scene *s = (const mt_scene *)u;
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) {
        double v = 0.3 * mt_sig(s, c, (double)t);
        if (s->bad && (double)t > 4)
            v = s->bad == 1 ? (double)NAN
              : s->bad == 2 ? -1.0
                            : (sizeof(hrm_real) == sizeof(float) ? (double)FLT_MAX : DBL_MAX) / 16;
        out[c] = (hrm_real)v;
    }
}

static void mt_ss(void *u, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const mt_scene *s = (const mt_scene *)u;
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)(0.7 * mt_sig(s, c, (double)t));
}

static void mt_st(void *u, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const mt_scene *s = (const mt_scene *)u;
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)mt_sig(s, c, (double)t);
}

/* Tr(ta, tb) of mt_sig without the slab, in closed form. */
static void mt_tr(void *u, hrm_real ta, hrm_real tb, hrm_real out[HRM_CHANNELS])
{
    const mt_scene *s = (const mt_scene *)u;
    double a = (double)ta, b = (double)tb;
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)exp(-s->k[c] * ((b - a) - 0.5 * (cos(b) - cos(a))));
}

static void mt_le(void *u, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    int c;
    (void)u;
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)(0.3 + 0.01 * c + 0.0 * (double)t);
}

static void mt_li(void *u, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const mt_scene *s = (const mt_scene *)u;
    double x = (double)t - s->delta, r2 = s->D * s->D + x * x;
    hrm_real tr[HRM_CHANNELS];
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) tr[c] = 1;
    if (s->shadow == 1) {
        /* the shadow ray: from the projection of the sample towards the
           light, through the same medium, as long as the distance D */
        hrm_options o = hrm_default_options(HRM_SIMPSON);
        double a = (double)t < s->delta ? (double)t : s->delta;
        hrm_transmittance(&s->shadow_medium, (hrm_real)a, (hrm_real)(a + s->D), &o, tr, 0);
    } else if (s->shadow == 2) {
        /* the same ray solved whole (its medium's own Li casts none) */
        hrm_options o = hrm_default_options(HRM_SIMPSON);
        hrm_result r;
        double a = (double)t < s->delta ? (double)t : s->delta;
        o.steps = 4;
        o.tau_mode = HRM_TAU_COUPLED; /* (cheap: tau from its 9 nodes) */
        hrm_solve(&s->shadow_medium, (hrm_real)a, (hrm_real)(a + s->D), &o, &r);
        for (c = 0; c < HRM_CHANNELS; ++c) tr[c] = r.Tr[c];
    }
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)((double)tr[c] / r2);
}

/* A user warp: u = t / (t + 1), t in [0, inf). */
/* The options a test table leaves at zero, one at a time: those threads.c
   and alloc.c share (each numbers its own from MT_V_SHARED on). */
enum {
    MT_V_NONE, MT_V_JITTER, MT_V_STRATIFIED, MT_V_K7, MT_V_GK_LOCAL, MT_V_MUNOZ, MT_V_GONTERMAN,
    MT_V_COUPLED, MT_V_FIND_JUMPS, MT_V_NO_JUMPS, MT_V_SHARED
};

/* Sets the shared option v (MT_V_*); others are the caller's. */
static void mt_option(hrm_options *o, int v)
{
    switch (v) {
    case MT_V_JITTER: o->jitter = 1; break;
    case MT_V_STRATIFIED: o->stratified = 1; break;
    case MT_V_K7: o->gk_rule = HRM_GK_K7; break;
    case MT_V_GK_LOCAL: o->gk_mode = HRM_GK_LOCAL; break;
    case MT_V_MUNOZ: o->control = HRM_CONTROL_MUNOZ; break;
    case MT_V_GONTERMAN: o->control = HRM_CONTROL_GONTERMAN; break;
    case MT_V_COUPLED: o->tau_mode = HRM_TAU_COUPLED; break;
    case MT_V_FIND_JUMPS: o->find_jumps = 1; break;
    case MT_V_NO_JUMPS: o->find_jumps = -1; break;
    default: break;
    }
}

static hrm_real mt_t_of_u(void *u, hrm_real x) { (void)u; return x / (1 - x); }
static hrm_real mt_dt_du(void *u, hrm_real x) { (void)u; return 1 / ((1 - x) * (1 - x)); }
static hrm_real mt_u_of_t(void *u, hrm_real t) { (void)u; return isinf(t) ? (hrm_real)1 : t / (t + 1); }

#endif
