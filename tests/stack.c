/* stack.c - the stack hrm_solve and hrm_transmittance use, per method, as
   a program of its own (pthreads; no heap is involved: hrm never
   allocates, so its stack is all the memory a solve needs).

   How: each solve runs on a thread whose stack (ST_STACK bytes) is ours,
   allocated and filled with a pattern before the thread starts
   (pthread_attr_setstack). After the join, the stack is scanned from its
   low end: the first byte that no longer holds the pattern is the deepest
   one written (the stack grows down; a frame's callees write below the
   whole of it, so arrays a solve reserves but leaves partly unwritten are
   counted, but for the deepest frame's own). A thread that only calls
   each callback once and returns gives the baseline (thread start, the
   thread's descriptor and TLS that glibc puts at the top of a stack
   given to it, the callbacks' frames), printed and subtracted. The
   callbacks are a few lines of arithmetic, so what remains is hrm's.

   Each method runs over every variant that may change its deepest path:
   both forms (the IVP methods: Euler, RK4, Adams-Bashforth and the
   pairs), no warp and the distance, equiangular and user warps, the
   exponential fits 0/1/2 where accepted, Gauss-Kronrod's global and local
   modes with K15 and K7, no breakpoints, two and HRM_MAX_BREAKS; a medium
   of constants, of sigma callbacks (the decoupled transmittance layer, or
   coupled tau) or with a transmittance callback; a smooth scene and a hard
   one (a slab, a shadow's jump and a light close to the ray at rtol 1e-9,
   which fills the adaptive drivers' interval storage and sends them to
   their left-to-right finish), with the jump search on and off; then the
   other options one at a time (jitter, stratified, the step controls, a
   sigma_t callback, an infinite ray, a cut-off). Options a method rejects
   (HRM_ERR_BAD_OPTION) are skipped. hrm_transmittance runs on sigma
   callbacks without a method (the shadow-ray estimator, what options NULL
   gives), with the transmittance layer and with coupled tau under every
   method (whose rule then integrates tau). The host's data (scenes,
   media, options, breakpoints, result) lives outside the measured stack,
   as a renderer's would in its own frames.

   Printed: the baseline, per method the largest use (rounded up to 256
   bytes) and the configuration that reached it, and the same with a
   shadow ray in Li: Li calling hrm_solve (or hrm_transmittance) with the
   method's worst configuration, the re-entrance the manual allows.
   Checked: every figure within STACK_LIMIT, twice it with a nested
   solve, and the painting itself (a thread that writes 8 KiB of locals
   is measured within 512 bytes of 8 KiB, one that writes 64 KiB at 56
   KiB more).

   Build and run (the configuration of tests/run.sh):
     gcc -std=c99 -O2 -Wall -Wextra -pedantic -Werror -Wshadow \
         -Wdouble-promotion -I. tests/stack.c -o /tmp/stack -lm -pthread
   Callbacks read their scene through the user pointer; nothing here is
   mutable and global but the harness's tally. */
#define _POSIX_C_SOURCE 200112L /* pthread_attr_setstack, posix_memalign */
#define HRM_IMPLEMENTATION
#include "hrm.h"
#define HARNESS_IMPLEMENTATION /* a single-file program: the tally lives here */
#include "harness.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NCH HRM_CHANNELS

/* The limit checked, the manual's figure: 48 KiB per channel and 48 KiB
   more, in double; half that in float (almost all of a solve's stack is
   arrays of hrm_real per channel: the figure grows linearly with both).
   That is 192 KiB with 3 channels in double, 432 KiB with 8, 96 and 216
   KiB in float. Measured, the largest (nested Simpson, on the hard scene
   without the jump search: its worst-first storage, then its left-to-
   right finish), bytes beyond the baseline (with the harness's own frame
   of 2.3 KiB, since taken off the measured stack):
                      double 3 ch   double 8 ch   float 3 ch   float 8 ch
     gcc -O0               94680        212136        49592       108744
     gcc -O2               94360        211976        49336       108360
     clang -O2             96696        215520        50528       110352
   The largest build is clang -O2 (it inlines more of the drivers into
   one frame), not gcc -O0; a limit of 1.5 times gcc -O0's 3-channel
   figure alone would not hold with 8 channels. So the limit is about
   twice the largest build in each configuration (2.03 times clang -O2's
   in double with 3 channels, 2.05 with 8, 1.95 and 2.0 in float),
   rounded up to 48 KiB steps: room for another compiler's inlining and a
   few more locals, while an array added to the solve's context or a
   driver's storage (HRM_GK_INTERVALS, HRM_NS_INTERVALS, HRM_TAU_PANELS)
   shows here. */
#ifndef STACK_LIMIT /* (-DSTACK_LIMIT=...: to measure a build past it) */
#define STACK_LIMIT ((48L + 48L * NCH) * 1024L * (long)sizeof(hrm_real) / 8)
#endif

/* Each thread's stack: over twice the limit of a nested solve, so that a
   solve past its limit is measured, not overflowed; not much more, since
   each measure scans it whole. */
#define ST_STACK ((256L + 256L * NCH) * 1024L * (long)sizeof(hrm_real) / 8)
#define ST_MARGIN (ST_STACK / 4) /* left unused, or the measure failed */
#define ST_PAINT 0xA5
#define ST_PROBE 8192                 /* the painting's self-test, bytes */
#define ST_MAX_CASES 24000

/* ----------------------------------------------------------------------
   The scene: sigma_t = k (1 + 0.5 x / (1 + x^2)) per channel, x = t - 4,
   albedo 0.7, emission 0.3, a point light D from the ray at delta. Hard:
   sigma 4 times larger in the slab [3, 5] (sigma callbacks) and the light
   shadowed over [5, 5.5]. shadow: Li casts a shadow ray through inner,
   by hrm_solve (1) or hrm_transmittance (2). */
typedef struct st_scene {
    double k[NCH], delta, D;
    int hard, shadow;
    const hrm_medium *inner;
    const hrm_options *inner_opt;
} st_scene;

static double st_sig(const st_scene *s, int c, double t)
{
    double x = t - 4, v = s->k[c] * (1 + 0.5 * x / (1 + x * x));
    return s->hard && t >= 3 && t <= 5 ? 4 * v : v;
}

static void st_sa(void *u, hrm_real t, hrm_real out[NCH])
{
    const st_scene *s = (const st_scene *)u;
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(0.3 * st_sig(s, c, (double)t));
}

static void st_ss(void *u, hrm_real t, hrm_real out[NCH])
{
    const st_scene *s = (const st_scene *)u;
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(0.7 * st_sig(s, c, (double)t));
}

static void st_st(void *u, hrm_real t, hrm_real out[NCH])
{
    const st_scene *s = (const st_scene *)u;
    int c;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)st_sig(s, c, (double)t);
}

/* Tr(ta, tb) of the smooth sigma_t (no slab), in closed form. */
static void st_tr(void *u, hrm_real ta, hrm_real tb, hrm_real out[NCH])
{
    const st_scene *s = (const st_scene *)u;
    double a = (double)ta - 4, b = (double)tb - 4;
    int c;
    for (c = 0; c < NCH; ++c)
        out[c] = (hrm_real)exp(-s->k[c] * ((b - a) + 0.25 * (log(1 + b * b) - log(1 + a * a))));
}

static void st_le(void *u, hrm_real t, hrm_real out[NCH])
{
    int c;
    (void)u;
    (void)t;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(0.3 + 0.01 * c);
}

static void st_li(void *u, hrm_real t, hrm_real out[NCH])
{
    const st_scene *s = (const st_scene *)u;
    double x = (double)t - s->delta, v = 1 / (s->D * s->D + x * x);
    hrm_real tr[NCH];
    int c;
    for (c = 0; c < NCH; ++c) tr[c] = 1;
    if (s->hard && (double)t >= 5 && (double)t <= 5.5) v = 0;
    if (s->shadow == 1) {
        hrm_result r;
        hrm_solve(s->inner, t, t + (hrm_real)s->D, s->inner_opt, &r);
        memcpy(tr, r.Tr, sizeof tr);
    } else if (s->shadow == 2) {
        hrm_transmittance(s->inner, t, t + (hrm_real)s->D, s->inner_opt, tr, 0);
    }
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)(v * (double)tr[c]);
}

/* A user warp: u = t / (t + 1), t in [0, inf). */
static hrm_real st_t_of_u(void *u, hrm_real x) { (void)u; return x / (1 - x); }
static hrm_real st_dt_du(void *u, hrm_real x) { (void)u; return 1 / ((1 - x) * (1 - x)); }
static hrm_real st_u_of_t(void *u, hrm_real t) { (void)u; return isinf(t) ? (hrm_real)1 : t / (t + 1); }

/* ----------------------------------------------------------------------
   The cases. */
enum { ST_MED_CONST, ST_MED_LAYER, ST_MED_COUPLED, ST_MED_TR, ST_MED_COUNT };
enum { ST_V_NONE, ST_V_JITTER, ST_V_STRATIFIED, ST_V_MUNOZ, ST_V_GONTERMAN, ST_V_SIGMA_T, ST_V_INFINITE, ST_V_CUTOFF,
       ST_V_COUNT };
static const char *const st_med_name[ST_MED_COUNT] = {"constants", "sigma cb", "sigma cb coupled", "Tr cb"};
static const char *const st_warp_name[4] = {"no warp", "distance", "equiangular", "user warp"};
static const char *const st_v_name[ST_V_COUNT] = {"", ", jitter", ", stratified", ", Munoz control",
                                                 ", Gonterman control", ", sigma_t cb", ", t1 = inf",
                                                 ", cut-off 0.5"};

typedef struct st_case {
    hrm_method method;
    int tr_only;             /* hrm_transmittance */
    hrm_form form;
    int warp, expo, breaks;  /* breaks: 0 none, 1 two, 2 HRM_MAX_BREAKS */
    int medium, hard, jumps; /* jumps: options.find_jumps */
    hrm_gk_mode gk_mode;
    hrm_gk_rule gk_rule;
    int variant;             /* ST_V_* */
    int shadow;              /* 1: Li nests hrm_solve, 2: hrm_transmittance,
                                of the same case without a shadow */
    unsigned char *ws;       /* options.workspace (the shadow ray's: the
                                rest past the outer solve's share), or 0 */
} st_case;

/* The IVP methods, whose form matters (the quadratures ignore it). */
static int st_has_forms(hrm_method m)
{
    return m == HRM_EULER || m == HRM_RK4 || m == HRM_ADAMS_BASHFORTH || m == HRM_BOGACKI_SHAMPINE ||
           m == HRM_DORMAND_PRINCE || m == HRM_FEHLBERG || m == HRM_CASH_KARP || m == HRM_VERNER;
}

static int st_adaptive(hrm_method m)
{
    return m == HRM_NESTED_SIMPSON || m == HRM_GAUSS_KRONROD || m == HRM_BOGACKI_SHAMPINE ||
           m == HRM_DORMAND_PRINCE || m == HRM_FEHLBERG || m == HRM_CASH_KARP || m == HRM_VERNER;
}

static void st_scene_init(st_scene *s, int hard)
{
    int c;
    memset(s, 0, sizeof *s);
    for (c = 0; c < NCH; ++c) s->k[c] = 0.4 + 0.1 * c;
    s->hard = hard;
    s->delta = 3.7;
    s->D = hard ? 0.05 : 0.3;
}

/* The medium and options of case k over scene s (which the callbacks and
   the user warp read); *t1 the ray's end. */
static void st_setup(const st_case *k, st_scene *s, hrm_real *brk, hrm_medium *m, hrm_options *o,
                     hrm_real *t1)
{
    int c, i;
    memset(m, 0, sizeof *m);
    m->user = s;
    m->Le = st_le;
    m->Li = st_li;
    if (k->medium == ST_MED_CONST) {
        m->flags = HRM_MEDIUM_HOMOGENEOUS;
        for (c = 0; c < NCH; ++c) {
            m->const_sigma_a[c] = (hrm_real)(0.3 * s->k[c]);
            m->const_sigma_s[c] = (hrm_real)(0.7 * s->k[c]);
        }
    } else {
        m->sigma_a = st_sa;
        m->sigma_s = st_ss;
        if (k->medium == ST_MED_TR) m->transmittance = st_tr;
        if (k->variant == ST_V_SIGMA_T) m->sigma_t = st_st;
    }
    *o = hrm_default_options(k->method);
    o->form = k->form;
    o->exponential = k->expo;
    o->find_jumps = k->jumps;
    o->gk_mode = k->gk_mode;
    o->gk_rule = k->gk_rule;
    o->seed = 7;
    if (k->medium == ST_MED_COUPLED) o->tau_mode = HRM_TAU_COUPLED;
    if (k->hard) {
        o->rtol = (hrm_real)1e-9; /* (float: clipped to 100 epsilons) */
        o->max_evals = 6000;      /* past every driver's storage */
        if (k->method == HRM_METHOD_DEFAULT) o->tr_tol = (hrm_real)1e-9; /* (the shadow-ray estimator) */
    }
    o->warp.kind = (hrm_warp_kind)k->warp;
    if (k->warp == HRM_WARP_DISTANCE) o->warp.sigma_ref = k->variant == ST_V_INFINITE ? (hrm_real)0.5 : 0;
    if (k->warp == HRM_WARP_EQUIANGULAR) {
        o->warp.delta = (hrm_real)s->delta;
        o->warp.D = (hrm_real)s->D;
    }
    if (k->warp == HRM_WARP_USER) {
        o->warp.t_of_u = st_t_of_u;
        o->warp.dt_du = st_dt_du;
        o->warp.u_of_t = st_u_of_t;
    }
    if (k->breaks == 1) {
        brk[0] = 5;
        brk[1] = (hrm_real)5.5; /* the shadow's edges */
        o->breaks = brk;
        o->nbreaks = 2;
    } else if (k->breaks == 2) {
        for (i = 0; i < HRM_MAX_BREAKS; ++i) brk[i] = (hrm_real)(8.0 * (i + 1) / (HRM_MAX_BREAKS + 1));
        o->breaks = brk;
        o->nbreaks = HRM_MAX_BREAKS;
    }
    switch (k->variant) {
    case ST_V_JITTER: o->jitter = 1; break;
    case ST_V_STRATIFIED: o->stratified = 1; break;
    case ST_V_MUNOZ: o->control = HRM_CONTROL_MUNOZ; break;
    case ST_V_GONTERMAN: o->control = HRM_CONTROL_GONTERMAN; break;
    case ST_V_CUTOFF: o->cutoff = (hrm_real)0.5; break; /* the ray cut (hrm__cut_ray) */
    default: break;
    }
    *t1 = k->variant == ST_V_INFINITE ? (hrm_real)INFINITY : (hrm_real)8;
}

/* What a call holds outside hrm: the scenes, media, options, breakpoints
   and result of the host, in memory the host owns (st_job's, off the
   measured stack: a host's frame is not hrm's; on it, 2 352 bytes that
   tests/stack.c had counted as the solve's). */
typedef struct st_call {
    st_scene s, si;
    hrm_medium m, mi;
    hrm_options o, oi;
    hrm_real brk[HRM_MAX_BREAKS], brki[HRM_MAX_BREAKS], t1, t1i;
    hrm_result r;
    st_case ki;
} st_call;

/* Run case k in w; its status. A shadow ray nests the same case without
   one. */
static hrm_status st_run(const st_case *k, st_call *w)
{
    w->ki = *k;
    st_scene_init(&w->s, k->hard);
    st_setup(k, &w->s, w->brk, &w->m, &w->o, &w->t1);
    if (k->shadow) {
        w->ki.shadow = 0;
        w->ki.variant = ST_V_NONE; /* (a finite shadow ray) */
        w->ki.breaks = 0;          /* (the outer ray's abscissae) */
        st_scene_init(&w->si, k->hard);
        st_setup(&w->ki, &w->si, w->brki, &w->mi, &w->oi, &w->t1i);
        w->s.shadow = k->shadow;
        w->s.inner = &w->mi;
        w->s.inner_opt = &w->oi;
    }
    if (k->ws) {
        w->o.workspace = k->ws;
        w->o.workspace_size = hrm_workspace_size(&w->o);
        if (k->shadow) {
            w->oi.workspace = k->ws + w->o.workspace_size;
            w->oi.workspace_size = hrm_workspace_size(&w->oi);
        }
    }
    if (k->tr_only) return hrm_transmittance(&w->m, 0, w->t1, &w->o, w->r.Tr, 0);
    return hrm_solve(&w->m, 0, w->t1, &w->o, &w->r);
}

static void st_describe(const st_case *k, char *buf, size_t n)
{
    static const char *const br[3] = {"", ", 2 breaks", ", 64 breaks"};
    char gk[32] = "";
    if (k->method == HRM_GAUSS_KRONROD)
        snprintf(gk, sizeof gk, ", %s %s", k->gk_rule == HRM_GK_K7 ? "K7" : "K15",
                 k->gk_mode == HRM_GK_LOCAL ? "local" : "global");
    snprintf(buf, n, "%s%s%s%s, %s%s%s, exp %d%s, jumps %d%s", !k->tr_only ? "" : k->method ? hrm_method_name(k->method) : "no method",
             k->tr_only ? ", " : "", st_has_forms(k->method) ? (k->form == HRM_FORM_RTE ? "rte, " : "od, ") : "",
             st_warp_name[k->warp], st_med_name[k->medium], k->hard ? ", hard" : ", smooth", gk, k->expo,
             br[k->breaks], k->jumps, st_v_name[k->variant]);
}

/* Every case of the table (before filtering). */
static int st_cases(st_case *k, int max)
{
    int n = 0, mi, f, w, e, b, md, h, j, g, v, tr;
    static const int jumps_adaptive[2] = {0, -1}, jumps_fixed[2] = {0, 1};
    for (tr = 0; tr < 2; ++tr)
        for (mi = 1; mi < (int)HRM_METHOD_COUNT; ++mi)
            for (f = HRM_FORM_OPTICAL_DEPTH; f <= HRM_FORM_RTE; ++f)
                for (w = 0; w < 4; ++w)
                    for (e = 0; e < 3; ++e)
                        for (b = 0; b < 3; ++b)
                            for (md = 0; md < ST_MED_COUNT; ++md)
                                for (h = 0; h < 2; ++h)
                                    for (j = 0; j < 2; ++j)
                                        for (g = 0; g < 4 && n < max; ++g) {
                                            st_case c;
                                            hrm_method m = (hrm_method)mi;
                                            if (f == HRM_FORM_RTE && !st_has_forms(m)) continue;
                                            if (g > 0 && m != HRM_GAUSS_KRONROD) continue;
                                            /* hrm_transmittance: no source, so no fit and
                                               no warp (it ignores it); tau by the method
                                               only where coupled, else the layer alone */
                                            if (tr && (e || w || md == ST_MED_CONST || md == ST_MED_TR)) continue;
                                            if (tr && md == ST_MED_LAYER && mi != HRM_SIMPSON) continue;
                                            memset(&c, 0, sizeof c);
                                            c.method = m;
                                            c.tr_only = tr;
                                            c.form = (hrm_form)f;
                                            c.warp = w;
                                            c.expo = e;
                                            c.breaks = b;
                                            c.medium = md;
                                            c.hard = h;
                                            c.jumps = st_adaptive(m) ? jumps_adaptive[j] : jumps_fixed[j];
                                            c.gk_mode = g & 1 ? HRM_GK_LOCAL : HRM_GK_GLOBAL;
                                            c.gk_rule = g & 2 ? HRM_GK_K7 : HRM_GK_K15;
                                            k[n++] = c;
                                        }
    /* the other options, one at a time, on the hard scene with sigma
       callbacks (each method ignores or rejects those not its own) */
    for (mi = 1; mi < (int)HRM_METHOD_COUNT; ++mi)
        for (f = HRM_FORM_OPTICAL_DEPTH; f <= HRM_FORM_RTE; ++f)
            for (v = 1; v < ST_V_COUNT; ++v)
                for (w = 0; w < 4 && n < max; ++w) {
                    st_case c;
                    hrm_method m = (hrm_method)mi;
                    if (f == HRM_FORM_RTE && !st_has_forms(m)) continue;
                    if (w == 0 && v == ST_V_INFINITE) continue; /* (needs a warp) */
                    if (w != 0 && v != ST_V_INFINITE) continue;
                    memset(&c, 0, sizeof c);
                    c.method = m;
                    c.form = (hrm_form)f;
                    c.warp = w;
                    c.medium = ST_MED_LAYER;
                    c.hard = 1;
                    c.variant = v;
                    k[n++] = c;
                }
    /* hrm_transmittance without a method: the shadow-ray estimator (its
       panels on its own frame), with and without breakpoints and a
       cut-off; hard: tr_tol 1e-9, which fills its panels */
    for (h = 0; h < 2; ++h)
        for (b = 0; b < 3; ++b)
            for (v = 0; v < 2 && n < max; ++v) {
                st_case c;
                memset(&c, 0, sizeof c);
                c.method = HRM_METHOD_DEFAULT;
                c.tr_only = 1;
                c.medium = ST_MED_LAYER;
                c.hard = h;
                c.breaks = b;
                c.variant = v ? ST_V_CUTOFF : ST_V_NONE;
                k[n++] = c;
            }
    return n;
}

/* ----------------------------------------------------------------------
   The measure. */
enum { ST_IDLE, ST_CALLBACKS, ST_SOLVE, ST_PROBE_RUN, ST_PROBE8_RUN };

typedef struct st_job {
    const st_case *k;
    int mode;
    hrm_status st;
    st_call call; /* the host's data (the measuring thread's, not the
                     measured one's) */
} st_job;

/* ST_PROBE (and 8 ST_PROBE) bytes of locals, every one written
   (volatile: kept). */
static int st_probe(void)
{
    volatile unsigned char buf[ST_PROBE];
    int i, sum = 0;
    for (i = 0; i < ST_PROBE; ++i) buf[i] = (unsigned char)i;
    for (i = 0; i < ST_PROBE; i += 512) sum += buf[i];
    return sum;
}

static int st_probe8(void)
{
    volatile unsigned char buf[8 * ST_PROBE];
    int i, sum = 0;
    for (i = 0; i < 8 * ST_PROBE; ++i) buf[i] = (unsigned char)i;
    for (i = 0; i < 8 * ST_PROBE; i += 512) sum += buf[i];
    return sum;
}

/* The baseline's thread calls each callback once: their frames (and
   libm's) are in the baseline, not in hrm's figure. */
static void st_callbacks_once(void)
{
    st_scene s;
    hrm_real out[NCH];
    volatile hrm_real sink = 0;
    st_scene_init(&s, 1);
    st_sa(&s, 4, out);
    sink += out[0];
    st_ss(&s, 4, out);
    sink += out[0];
    st_st(&s, 4, out);
    sink += out[0];
    st_tr(&s, 1, 4, out);
    sink += out[0];
    st_le(&s, 4, out);
    sink += out[0];
    st_li(&s, 4, out);
    sink += out[0] + st_t_of_u(0, (hrm_real)0.5) + st_dt_du(0, (hrm_real)0.5) + st_u_of_t(0, 4);
    (void)sink;
}

/* One start routine per job: called through a pointer, none is inlined
   into another, so a thread's frames are its job's alone (one routine
   for all, with the probes inlined, gave every thread a 72 KiB frame). */
static void *st_entry_idle(void *arg) { return arg; }

static void *st_entry_callbacks(void *arg)
{
    st_callbacks_once();
    return arg;
}

static void *st_entry_solve(void *arg)
{
    st_job *j = (st_job *)arg;
    j->st = st_run(j->k, &j->call);
    return 0;
}

static void *st_entry_probe(void *arg)
{
    st_job *j = (st_job *)arg;
    j->st = (hrm_status)(st_probe() < 0);
    return 0;
}

static void *st_entry_probe8(void *arg)
{
    st_job *j = (st_job *)arg;
    j->st = (hrm_status)(st_probe8() < 0);
    return 0;
}

static void *(*const st_entry[])(void *) = {st_entry_idle, st_entry_callbacks, st_entry_solve, st_entry_probe,
                                           st_entry_probe8};

/* The bytes of the stack a job touched, thread and all (-1: no thread),
   on mem (ST_STACK bytes, painted): repainted after, where touched. */
static long st_used(unsigned char *mem, st_job *j)
{
    pthread_attr_t at;
    pthread_t tid;
    long used = -1, i = 0;
    if (pthread_attr_init(&at) != 0) return -1;
    if (pthread_attr_setstack(&at, mem, (size_t)ST_STACK) == 0 &&
        pthread_create(&tid, &at, st_entry[j->mode], j) == 0) {
        pthread_join(tid, 0);
        /* it grows down: the first byte from the low end that changed,
           found a page at a time, then byte by byte */
        while (i + 4096 <= ST_STACK && mem[i] == ST_PAINT && memcmp(mem + i, mem + i + 1, 4095) == 0) i += 4096;
        while (i < ST_STACK && mem[i] == ST_PAINT) ++i;
        used = ST_STACK - i;
        memset(mem + i, ST_PAINT, (size_t)(ST_STACK - i));
    }
    pthread_attr_destroy(&at);
    return used;
}

/* A painted stack for st_used (NULL: no memory). */
static unsigned char *st_stack_new(void)
{
    void *p = 0;
    if (posix_memalign(&p, 4096, (size_t)ST_STACK) != 0) return 0;
    memset(p, ST_PAINT, (size_t)ST_STACK);
    return (unsigned char *)p;
}

static long st_round(long b) { return (b + 255) / 256 * 256; }

/* ----------------------------------------------------------------------
   The tests. */
/* A thread that does nothing (ST_IDLE) or calls each callback once
   (ST_CALLBACKS, the baseline of the solves); -1: no thread. */
static long st_empty(unsigned char *mem, int mode)
{
    st_job j;
    memset(&j, 0, sizeof j);
    j.mode = mode;
    return st_used(mem, &j);
}

/* The painting sees 8 KiB of locals as 8 KiB, and 64 KiB as 56 KiB more. */
static void st_paint(void)
{
    unsigned char *mem = st_stack_new();
    long idle, base, probe, probe8;
    CHECK(mem != 0, "%ld bytes for a thread's stack", ST_STACK);
    if (!mem) return;
    idle = st_empty(mem, ST_IDLE);
    base = st_empty(mem, ST_CALLBACKS);
    CHECK(idle > 0 && idle <= base && base < ST_MARGIN, "threads on our own painted stack: %ld and %ld bytes",
          idle, base);
    probe = st_empty(mem, ST_PROBE_RUN) - idle;
    probe8 = st_empty(mem, ST_PROBE8_RUN) - idle;
    NOTE("a thread that returns: %ld bytes (its start, and the descriptor and TLS that glibc puts at the top of "
         "a stack given to it); one that calls each callback once, the solves' baseline: %ld bytes", idle, base);
    NOTE("threads that write %d and %d bytes of locals: %ld and %ld bytes more than one that returns", ST_PROBE,
         8 * ST_PROBE, probe, probe8);
    /* The frame around the locals adds a little; the thread's exit, below
       the frame that called the job, takes back a little (what a job
       shallower than the exit path would not show). So within 512 bytes,
       and their difference to alignment. */
    CHECK(probe >= ST_PROBE - 512 && probe <= ST_PROBE + 512, "%d bytes of locals measured as %ld", ST_PROBE, probe);
    CHECK(probe8 - probe >= 7 * ST_PROBE - 64 && probe8 - probe <= 7 * ST_PROBE + 64,
          "%d bytes more locals measured as %ld more", 7 * ST_PROBE, probe8 - probe);
    free(mem);
}

typedef struct st_worst {
    long bytes;
    int at; /* the case, -1: none */
    int cases;
} st_worst;

static void st_keep(st_worst *w, long bytes, int at)
{
    w->cases++;
    if (bytes > w->bytes) {
        w->bytes = bytes;
        w->at = at;
    }
}

/* The table's rows: each method (by its number), then hrm_transmittance
   with the transmittance layer (its default) and with coupled tau (by the
   method's rule), then Gauss-Kronrod's modes and rules. */
#define ST_ROW_TR HRM_METHOD_COUNT
#define ST_ROW_TR_COUPLED (HRM_METHOD_COUNT + 1)
#define ST_ROW_GK (HRM_METHOD_COUNT + 2) /* + local + 2 K7 */
#define ST_ROW_EST (HRM_METHOD_COUNT + 6) /* the shadow-ray estimator */
#define ST_ROWS (HRM_METHOD_COUNT + 7)

static void st_row_name(int r, char *buf)
{
    if (r < ST_ROW_TR) strcpy(buf, hrm_method_name((hrm_method)r));
    else if (r == ST_ROW_TR) strcpy(buf, "hrm_transmittance");
    else if (r == ST_ROW_TR_COUPLED) strcpy(buf, "  coupled tau");
    else if (r == ST_ROW_EST) strcpy(buf, "  no method");
    else sprintf(buf, "  gk %s %s", (r - ST_ROW_GK) & 2 ? "K7" : "K15", (r - ST_ROW_GK) & 1 ? "local" : "global");
}

/* Whether case k's tau comes from the decoupled transmittance layer (what
   hrm_default_options resolves to: a fit, or Simpson, RK4 and Adams-
   Bashforth under a warp, on sigma callbacks; the RTE form carries Tr in
   its state). */
static int st_layer(const st_case *k)
{
    int fourth = k->method == HRM_SIMPSON || k->method == HRM_RK4 || k->method == HRM_ADAMS_BASHFORTH;
    return !k->tr_only && k->medium == ST_MED_LAYER && !(st_has_forms(k->method) && k->form == HRM_FORM_RTE) &&
           (k->expo || (k->warp != HRM_WARP_NONE && fourth));
}

static void st_table(void)
{
    static st_case cases[ST_MAX_CASES]; /* (static: large; written once, here) */
    st_worst row[ST_ROWS], own[ST_ROWS], lay[ST_ROWS], few[ST_ROWS]; /* the fixed-step methods: tau
                                                         not from the layer (own), from it without the scan
                                                         (lay), and that with 2 breakpoints at most (few) */
    st_case nested;
    char desc[256], name[64];
    long largest = 0, status[3] = {0, 0, 0}, u, base;
    int n, i, r, m, skipped = 0, measured = 0, failed = 0;
    unsigned char *mem = st_stack_new();
    CHECK(mem != 0, "%ld bytes for a thread's stack", ST_STACK);
    if (!mem) return;
    base = st_empty(mem, ST_CALLBACKS);
    CHECK(base > 0, "a thread on our own painted stack");
    if (base <= 0) {
        free(mem);
        return;
    }
    n = st_cases(cases, ST_MAX_CASES);
    CHECK(n < ST_MAX_CASES, "the table fits (%d cases)", n);
    for (r = 0; r < ST_ROWS; ++r) {
        row[r].bytes = 0;
        row[r].at = -1;
        row[r].cases = 0;
        own[r] = lay[r] = few[r] = row[r];
    }
    for (i = 0; i < n; ++i) {
        const st_case *k = &cases[i];
        st_job j;
        memset(&j, 0, sizeof j);
        j.k = k;
        j.mode = ST_SOLVE;
        u = st_used(mem, &j);
        if (j.st == HRM_ERR_BAD_OPTION) { /* not this method's option */
            ++skipped;
            continue;
        }
        if (u < 0) {
            ++failed;
            continue;
        }
        ++measured;
        status[j.st < 0 ? 0 : j.st == HRM_OK ? 1 : 2]++;
        u -= base;
        if (!k->tr_only) st_keep(&row[k->method], u, i);
        else st_keep(&row[k->method == HRM_METHOD_DEFAULT ? ST_ROW_EST
                          : k->medium == ST_MED_COUPLED ? ST_ROW_TR_COUPLED : ST_ROW_TR], u, i);
        if (!k->tr_only && !st_adaptive(k->method) && !st_layer(k)) st_keep(&own[k->method], u, i);
        if (!k->tr_only && !st_adaptive(k->method) && st_layer(k) && k->jumps != 1) {
            st_keep(&lay[k->method], u, i);
            if (k->breaks < 2) st_keep(&few[k->method], u, i);
        }
        if (!k->tr_only && k->method == HRM_GAUSS_KRONROD)
            st_keep(&row[ST_ROW_GK + (k->gk_mode == HRM_GK_LOCAL) + 2 * (k->gk_rule == HRM_GK_K7)], u, i);
    }
    CHECK_INT(failed, 0, "threads that could not be started");
    NOTE("%d cases measured (%ld answered HRM_OK, %ld with a warning, %ld with an error: a range blow-up of the "
         "RTE form), %d options rejected by their method", measured, status[1], status[2], status[0], skipped);
    NOTE("stack use, %s, %d channels, in bytes beyond the baseline (%ld), rounded up to 256:",
         sizeof(hrm_real) == sizeof(float) ? "float" : "double", NCH, base);
    NOTE("  %-20s %8s  %s", "method", "bytes", "worst configuration (cases)");
    for (r = 1; r < ST_ROWS; ++r) {
        const st_worst *w = &row[r];
        st_row_name(r, name);
        if (w->at >= 0) st_describe(&cases[w->at], desc, sizeof desc);
        else strcpy(desc, "-");
        NOTE("  %-20s %8ld  %s (%d)", name, st_round(w->bytes), desc, w->cases);
        CHECK(w->at >= 0 && w->bytes > 1024 && w->bytes <= STACK_LIMIT, "%s: %ld bytes within (1 KiB, %ld]", name,
              w->bytes, STACK_LIMIT);
        if (w->bytes > largest) largest = w->bytes;
        /* The fixed-step methods within 8 KiB without a workspace (3
           channels, double, gcc and clang -O2) wherever their tau is not
           the decoupled layer's: from their own nodes, the stream or a
           closed form (the distance warp's reach on sigma callbacks
           marched without the layer, hrm__reach_march). Measured (bytes
           as the table rounds them, gcc; clang): the rectangle rule and
           Monte Carlo 5 376; 5 632, the analytic march 5 120; 6 144,
           Euler 6 656; 7 424, Simpson 6 144; 7 424, RK4 and Adams-
           Bashforth 7 168; 7 680. With the layer (the default under a
           warp for Simpson, RK4 and Adams-Bashforth, and with a fit), in
           a fixed-step rule's frame of 4 panels, 2 panels' coefficients
           and 4 checkpoints, within 11 KiB (gcc): Simpson 9 728, RK4 and
           Adams-Bashforth 9 984; clang 10 752 (with 2 breakpoints at
           most, the pieces' tables in a frame of 8 pieces: 8 960 and
           9 472; clang 9 984 and 10 240). */
        if (r < ST_ROW_TR && own[r].at >= 0) {
            st_describe(&cases[own[r].at], desc, sizeof desc);
            NOTE("  %-20s %8ld  tau not from the layer: %s", "", st_round(own[r].bytes), desc);
            if (NCH == 3 && sizeof(hrm_real) == 8)
                CHECK(own[r].bytes <= 8192, "%s: %ld bytes of stack without a workspace, tau not from the layer, "
                      "within 8192", name, own[r].bytes);
        }
        if (r < ST_ROW_TR && lay[r].at >= 0) {
            st_describe(&cases[lay[r].at], desc, sizeof desc);
            NOTE("  %-20s %8ld  tau from the layer, no scan: %s", "", st_round(lay[r].bytes), desc);
#if defined(__GNUC__) && !defined(__clang__)
            if (NCH == 3 && sizeof(hrm_real) == 8)
                CHECK(lay[r].bytes <= 11 * 1024, "%s: %ld bytes of stack without a workspace, tau from the layer "
                      "without the scan, within 11 KiB", name, lay[r].bytes);
#endif
        }
        if (r < ST_ROW_TR && few[r].at >= 0) {
            st_describe(&cases[few[r].at], desc, sizeof desc);
            NOTE("  %-20s %8ld  the same, 2 breakpoints at most: %s", "", st_round(few[r].bytes), desc);
        }
    }
    NOTE("the largest: %ld bytes (%ld rounded up), STACK_LIMIT %ld", largest, st_round(largest), STACK_LIMIT);

    /* A shadow ray nested in Li: each method's worst configuration with
       its Li solving the same configuration again (hrm_solve), or its
       transmittance (hrm_transmittance). */
    NOTE("with a shadow ray: Li calls hrm_solve or hrm_transmittance on the worst configuration (bytes):");
    NOTE("  %-20s %8s %8s  %s", "method", "solve", "Tr", "solve / alone");
    for (m = 1; m < (int)HRM_METHOD_COUNT; ++m) {
        long both[2] = {0, 0};
        int s;
        if (row[m].at < 0) continue;
        for (s = 1; s <= 2; ++s) {
            st_job j;
            nested = cases[row[m].at];
            nested.shadow = s;
            memset(&j, 0, sizeof j);
            j.k = &nested;
            j.mode = ST_SOLVE;
            both[s - 1] = st_used(mem, &j) - base;
        }
        NOTE("  %-20s %8ld %8ld  %.2f", hrm_method_name((hrm_method)m), st_round(both[0]), st_round(both[1]),
             (double)both[0] / (double)row[m].bytes);
        CHECK(both[0] > row[m].bytes && both[0] <= 2 * STACK_LIMIT && both[1] <= 2 * STACK_LIMIT,
              "%s with a nested shadow ray: %ld and %ld bytes, within twice STACK_LIMIT",
              hrm_method_name((hrm_method)m), both[0], both[1]);
        CHECK(both[0] < ST_STACK - ST_MARGIN, "the measure kept %ld bytes of its stack unused", ST_MARGIN);
        /* Without a workspace, every method but the worst-first ones
           (nested Simpson, Gauss-Kronrod) within 48 KiB with a shadow ray
           solved in Li (3 channels, double, gcc -O2): a fixed-step rule's
           and a pair's transmittance layer in a frame of 8 panels, the
           fits sized by the rule. Measured: the pairs 44 544 (clang 47 360;
           10 496 more with the adaptive methods' frame of 32 panels and
           15 x 15 fits). */
        if (NCH == 3 && sizeof(hrm_real) == 8 && m != HRM_NESTED_SIMPSON && m != HRM_GAUSS_KRONROD)
            CHECK(both[0] <= 48 * 1024, "%s with a nested shadow ray: %ld bytes, within 48 KiB",
                  hrm_method_name((hrm_method)m), both[0]);
    }

    /* With options.workspace (malloc'ed: not on the painted stack), every
       case again: the deep storage leaves the stack. */
    {
        st_worst wrow[ST_ROWS];
        unsigned char *ws = (unsigned char *)malloc(4u << 20);
        long wlargest = 0;
        CHECK(ws != 0 && (uintptr_t)ws % 16 == 0, "a workspace, aligned to 16");
        if (!ws) {
            free(mem);
            return;
        }
        for (r = 0; r < ST_ROWS; ++r) {
            wrow[r].bytes = 0;
            wrow[r].at = -1;
            wrow[r].cases = 0;
        }
        for (i = 0; i < n; ++i) {
            st_job j;
            cases[i].ws = ws;
            memset(&j, 0, sizeof j);
            j.k = &cases[i];
            j.mode = ST_SOLVE;
            u = st_used(mem, &j);
            if (j.st == HRM_ERR_BAD_OPTION || u < 0) continue;
            u -= base;
            if (!cases[i].tr_only) st_keep(&wrow[cases[i].method], u, i);
            else st_keep(&wrow[cases[i].method == HRM_METHOD_DEFAULT ? ST_ROW_EST
                               : cases[i].medium == ST_MED_COUPLED ? ST_ROW_TR_COUPLED : ST_ROW_TR], u, i);
        }
        NOTE("with options.workspace (hrm_workspace_size bytes; a shadow ray in the rest), bytes of stack:");
        NOTE("  %-20s %8s %8s  %s", "method", "alone", "+ shadow", "worst configuration alone");
        for (r = 1; r < ST_ROWS; ++r) {
            if (r >= ST_ROW_GK && r < ST_ROW_EST) continue; /* (Gauss-Kronrod's modes: its row) */
            long sh = 0;
            if (wrow[r].at < 0) continue;
            st_row_name(r, name);
            st_describe(&cases[wrow[r].at], desc, sizeof desc);
            if (r < ST_ROW_TR) {
                st_job j;
                nested = cases[wrow[r].at];
                nested.shadow = 1;
                memset(&j, 0, sizeof j);
                j.k = &nested;
                j.mode = ST_SOLVE;
                sh = st_used(mem, &j) - base;
            }
            NOTE("  %-20s %8ld %8ld  %s", name, st_round(wrow[r].bytes), st_round(sh), desc);
            CHECK(wrow[r].bytes <= row[r].bytes, "%s: no more stack with a workspace (%ld, %ld without)", name,
                  wrow[r].bytes, row[r].bytes);
            /* The fixed-step methods within 8 KiB with a workspace (3
               channels, double: what make test builds with gcc -O2; clang
               -O2 too), the target of a stack a fiber or a GPU thread can
               spare. Measured: gcc at most 5 120 (RK4, Adams-Bashforth),
               clang 5 888; the shadow-ray estimator 2 048 and 2 560, its
               panels in the workspace too. */
            if (NCH == 3 && sizeof(hrm_real) == 8 &&
                (r == ST_ROW_EST || r == HRM_RECTANGLE || r == HRM_SIMPSON || r == HRM_MONTE_CARLO || r == HRM_EULER ||
                 r == HRM_ANALYTIC_MARCH || r == HRM_RK4 || r == HRM_ADAMS_BASHFORTH))
                CHECK(wrow[r].bytes <= 8192, "%s: %ld bytes of stack with a workspace, within 8192", name,
                      wrow[r].bytes);
            if (wrow[r].bytes > wlargest) wlargest = wrow[r].bytes;
        }
        NOTE("the largest with a workspace: %ld bytes", wlargest);
        for (i = 0; i < n; ++i) cases[i].ws = 0;
        free(ws);
    }
    free(mem);
}

/* The first call of a libm function through the PLT runs the dynamic
   linker's resolver, whose frame (it saves the vector registers) would
   count in whichever thread called it first: every function the
   callbacks and the solves use is bound here, on the main thread. */
static void st_bind(void)
{
    st_case k;
    st_call w;
    int m;
    st_callbacks_once();
    memset(&k, 0, sizeof k);
    for (m = 1; m < (int)HRM_METHOD_COUNT; ++m) {
        for (k.warp = 0; k.warp < 4; ++k.warp) {
            k.method = (hrm_method)m;
            k.medium = ST_MED_LAYER;
            k.hard = 1;
            k.expo = 0;
            st_run(&k, &w);
            k.expo = 2;
            k.medium = ST_MED_TR;
            st_run(&k, &w);
        }
    }
    memset(&k, 0, sizeof k);
    k.tr_only = 1; /* the shadow-ray estimator */
    k.medium = ST_MED_LAYER;
    for (k.hard = 0; k.hard < 2; ++k.hard) st_run(&k, &w);
}

int main(void)
{
    st_bind();
    RUN_GROUP(st_paint);
    RUN_GROUP(st_table);
    return harness_summary();
}
