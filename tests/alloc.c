/* alloc.c - hrm.h never allocates: a program of its own that counts the
   heap calls made while hrm's public functions run. Build it with
     -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free
   (make test does; without the flags it does not link, so it cannot pass
   by counting nothing). The linker then sends every call of those four
   functions made from this program's own code, which includes hrm.h's
   implementation compiled below, to the __wrap_ functions here. Calls made
   inside libc itself are not seen; hrm's imports are libm's and memcpy,
   memmove and memset, none of which allocates.
   Counted, one solve at a time (single-threaded): every method (and the
   default and an unknown one) x form x warp (none, distance, equiangular,
   user) x exponential mode x medium (constants, sigma_a and sigma_s
   callbacks, a sigma_t callback too, a transmittance callback) x with and
   without breakpoints, accepted or rejected; then each method with the
   other options (jitter, stratified, Gauss-Kronrod's rule and mode, step
   control, tau mode, find_jumps, emission per length, a medium with a
   slab, an infinite ray, a budget that runs out), an Li whose shadow ray
   is hrm_transmittance or a nested hrm_solve, every error path, and the
   other public functions. A deliberate malloc, calloc, realloc and free
   between them must each be counted. */
#define HRM_IMPLEMENTATION
#include "hrm.h"
#define HARNESS_IMPLEMENTATION /* a single-file program: the tally lives here */
#include "harness.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mt_scene.h"

#define NCH HRM_CHANNELS

/* The one mutable global besides the harness's tally: the linker's
   wrappers take no user pointer, so the count cannot travel any other way.
   A plain counter (every solve here runs on the main thread), but
   volatile: the compiler takes malloc and free for the C library's, which
   touch no variable of ours, and without it kept the count's value from
   before an inlined malloc (gcc -O2 missed one in hrm_sphere_breaks). */
static volatile long alloc_calls;

#ifdef __cplusplus
extern "C" { /* (the linker's names) */
#endif
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t k);
void *__real_realloc(void *p, size_t n);
void __real_free(void *p);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t k);
void *__wrap_realloc(void *p, size_t n);
void __wrap_free(void *p);
void *__wrap_malloc(size_t n) { alloc_calls++; return __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t k) { alloc_calls++; return __real_calloc(n, k); }
void *__wrap_realloc(void *p, size_t n) { alloc_calls++; return __real_realloc(p, n); }
void __wrap_free(void *p) { alloc_calls++; __real_free(p); }
#ifdef __cplusplus
}
#endif










static void al_scene_init(mt_scene *s)
{
    int c;
    memset(s, 0, sizeof *s);
    for (c = 0; c < NCH; ++c) s->k[c] = 0.4 + 0.1 * c;
    s->delta = 3.7;
    s->D = 0.3;
}

/* medium kinds: 0 constants, 1 sigma_a and sigma_s, 2 with sigma_t too,
   3 a transmittance callback */
#define AL_MEDIA 4
static hrm_medium al_medium(const mt_scene *s, int kind)
{
    hrm_medium m;
    int c;
    memset(&m, 0, sizeof m);
    m.user = (void *)s;
    m.Le = mt_le;
    m.Li = mt_li;
    if (kind == 0) {
        m.flags = HRM_MEDIUM_HOMOGENEOUS;
        for (c = 0; c < NCH; ++c) {
            m.const_sigma_a[c] = (hrm_real)(0.3 * s->k[c]);
            m.const_sigma_s[c] = (hrm_real)(0.7 * s->k[c]);
        }
        return m;
    }
    m.sigma_a = mt_sa;
    m.sigma_s = mt_ss;
    if (kind == 2) m.sigma_t = mt_st;
    if (kind == 3) m.transmittance = mt_tr;
    return m;
}

/* One case: which options and scene. */
typedef struct al_case {
    int method, form, warp, expo, medium, breaks;
    int variant;             /* MT_V_* or AL_V_*: the other options */
    int shadow;
    double t1;
} al_case;

enum {
    AL_V_PER_LENGTH = MT_V_SHARED, AL_V_SLAB, AL_V_BUDGET, AL_V_TIGHT, AL_V_NULL_OPTIONS,
    AL_V_COUNT
};

typedef struct al_tally {
    long solves, answered, allocs;
} al_tally;

/* Runs one case, adding its solve and its heap calls to *t: the count
   covers the hrm calls only (hrm_default_options included). */
static void al_run(const al_case *k, const mt_scene *base, al_tally *t, hrm_result *r)
{
    mt_scene s = *base;
    hrm_medium m;
    hrm_options o;
    hrm_real brk[3] = {(hrm_real)2.5, (hrm_real)3.7, (hrm_real)6};
    hrm_status st;
    long before = alloc_calls;
    o = hrm_default_options((hrm_method)k->method);
    t->allocs += alloc_calls - before;
    s.shadow = k->shadow;
    s.slab = k->variant == AL_V_SLAB;
    s.shadow_medium = al_medium(base, 1); /* its Li casts no shadow ray */
    m = al_medium(&s, k->medium);
    o.form = (hrm_form)k->form;
    o.exponential = k->expo;
    o.rtol = (hrm_real)1e-5;
    o.steps = 16;
    o.max_evals = 3000;
    o.seed = 11;
    if (k->warp == 1) o.warp.kind = HRM_WARP_DISTANCE;
    if (k->warp == 2) {
        o.warp.kind = HRM_WARP_EQUIANGULAR;
        o.warp.delta = (hrm_real)s.delta;
        o.warp.D = (hrm_real)s.D;
    }
    if (k->warp == 3) {
        o.warp.kind = HRM_WARP_USER;
        o.warp.t_of_u = mt_t_of_u;
        o.warp.dt_du = mt_dt_du;
        o.warp.u_of_t = mt_u_of_t;
    }
    if (k->breaks) {
        o.breaks = brk;
        o.nbreaks = 3;
    }
    mt_option(&o, k->variant);
    switch (k->variant) {
    case AL_V_PER_LENGTH: m.flags |= HRM_EMISSION_PER_LENGTH; break;
    case AL_V_BUDGET: o.max_evals = 40; o.rtol = (hrm_real)1e-9; break;
    case AL_V_TIGHT: o.rtol = (hrm_real)1e-20; o.atol = (hrm_real)1e-30; o.tau_tol = (hrm_real)1e-12; break;
    default: break;
    }
    before = alloc_calls;
    st = hrm_solve(&m, 0, (hrm_real)k->t1, k->variant == AL_V_NULL_OPTIONS ? 0 : &o, r);
    t->allocs += alloc_calls - before;
    t->solves++;
    t->answered += st >= 0;
}

/* The grid: every method x form x warp x fit x medium x breaks. */
static void al_grid(void)
{
    mt_scene s;
    al_tally per[HRM_METHOD_COUNT + 1];
    long solves = 0, answered = 0;
    int mi, f, w, e, md, b;
    al_scene_init(&s);
    memset(per, 0, sizeof per);
    for (mi = 0; mi <= (int)HRM_METHOD_COUNT; ++mi)
        for (f = 0; f <= (int)HRM_FORM_RTE; ++f)
            for (w = 0; w < 4; ++w)
                for (e = 0; e < 3; ++e)
                    for (md = 0; md < AL_MEDIA; ++md)
                        for (b = 0; b < 2; ++b) {
                            al_case k;
                            hrm_result r;
                            memset(&k, 0, sizeof k);
                            k.method = mi;
                            k.form = f;
                            k.warp = w;
                            k.expo = e;
                            k.medium = md;
                            k.breaks = b;
                            k.t1 = 8;
                            al_run(&k, &s, &per[mi], &r);
                        }
    for (mi = 0; mi <= (int)HRM_METHOD_COUNT; ++mi) {
        const char *name = mi < (int)HRM_METHOD_COUNT ? hrm_method_name((hrm_method)mi) : "(unknown method)";
        CHECK_INT(per[mi].allocs, 0, "%s: heap calls during %ld solves (%ld answered)", name, per[mi].solves,
                  per[mi].answered);
        solves += per[mi].solves;
        answered += per[mi].answered;
    }
    /* the grid reaches the solvers: every method answers each case
       without a fit (3 forms - a quadrature rule ignores the form - x 4
       warps x 4 media x 2 = 96), those with the fits also the fitted
       optical-depth cases (224), the unknown method none */
    for (mi = 1; mi < (int)HRM_METHOD_COUNT; ++mi)
        CHECK(per[mi].answered >= 96, "%s answers in the grid (%ld of %ld)", hrm_method_name((hrm_method)mi),
              per[mi].answered, per[mi].solves);
    CHECK_INT(per[HRM_METHOD_COUNT].answered, 0, "an unknown method answers nowhere");
    NOTE("%ld solves, %ld answered", solves, answered);
}

/* Each method with the options the grid leaves at zero, both forms, with
   and without a warp; an infinite ray under each warp that ends it. */
static void al_options(void)
{
    mt_scene s;
    al_tally per[HRM_METHOD_COUNT];
    long solves = 0, answered = 0;
    int mi, v, f, w;
    al_scene_init(&s);
    memset(per, 0, sizeof per);
    for (mi = 1; mi < (int)HRM_METHOD_COUNT; ++mi)
        for (v = 0; v < AL_V_COUNT; ++v)
            for (f = HRM_FORM_OPTICAL_DEPTH; f <= HRM_FORM_RTE; ++f)
                for (w = 0; w < 4; ++w) {
                    al_case k;
                    hrm_result r;
                    memset(&k, 0, sizeof k);
                    k.method = mi;
                    k.form = f;
                    k.warp = w;
                    k.variant = v;
                    k.medium = 1 + (v + w) % 3;
                    k.expo = (v + w) % 3;
                    k.t1 = 8;
                    al_run(&k, &s, &per[mi], &r);
                    if (w > 0) { /* the same to infinity */
                        k.t1 = (double)INFINITY;
                        al_run(&k, &s, &per[mi], &r);
                    }
                }
    for (mi = 1; mi < (int)HRM_METHOD_COUNT; ++mi) {
        CHECK_INT(per[mi].allocs, 0, "%s: heap calls during %ld solves with the other options",
                  hrm_method_name((hrm_method)mi), per[mi].solves);
        CHECK(per[mi].answered > 0, "%s answers with the other options", hrm_method_name((hrm_method)mi));
        solves += per[mi].solves;
        answered += per[mi].answered;
    }
    NOTE("%ld solves, %ld answered", solves, answered);
}

/* An Li that calls hrm_transmittance or hrm_solve for its shadow ray. The
   shadow must be seen (L below the unshadowed one), so the nested calls
   did run. */
static void al_nested(void)
{
    mt_scene s;
    al_tally t[3];
    double L[3][HRM_METHOD_COUNT];
    int mi, sh, darker = 0;
    al_scene_init(&s);
    memset(t, 0, sizeof t);
    for (sh = 0; sh < 3; ++sh)
        for (mi = 1; mi < (int)HRM_METHOD_COUNT; ++mi) {
            al_case k;
            hrm_result r;
            memset(&k, 0, sizeof k);
            k.method = mi;
            k.form = HRM_FORM_OPTICAL_DEPTH;
            k.medium = 1;
            k.shadow = sh;
            k.warp = 2;
            k.t1 = 8;
            al_run(&k, &s, &t[sh], &r);
            L[sh][mi] = (double)r.L[0];
        }
    for (mi = 1; mi < (int)HRM_METHOD_COUNT; ++mi) darker += L[1][mi] < L[0][mi] && L[2][mi] < L[0][mi];
    CHECK_INT(t[1].allocs, 0, "heap calls with hrm_transmittance in Li (%ld solves)", t[1].solves);
    CHECK_INT(t[2].allocs, 0, "heap calls with a nested hrm_solve in Li (%ld solves)", t[2].solves);
    CHECK_INT(darker, (int)HRM_METHOD_COUNT - 1, "every method sees the nested shadow rays' attenuation");
}

/* Every error path, with the exact status (so each path was reached). */
static void al_errors(void)
{
    mt_scene s, bad;
    hrm_medium m, mb;
    hrm_options o;
    hrm_result r;
    hrm_real Tr[NCH], brk[2] = {5, 2};
    hrm_status st[16];
    long before, allocs;
    int i, n = 0;
    al_scene_init(&s);
    bad = s;
    m = al_medium(&s, 1);
    o = hrm_default_options(HRM_GAUSS_KRONROD);
    before = alloc_calls;
    st[n++] = hrm_solve(0, 0, 1, &o, &r);
    st[n++] = hrm_solve(&m, 0, 1, &o, 0);
    st[n++] = hrm_transmittance(&m, 0, 1, &o, 0, 0);
    st[n++] = hrm_solve(&m, 2, 1, &o, &r);
    st[n++] = hrm_solve(&m, 0, (hrm_real)NAN, &o, &r);
    o.steps = -1;
    st[n++] = hrm_solve(&m, 0, 1, &o, &r);
    o = hrm_default_options(HRM_METHOD_COUNT);
    st[n++] = hrm_solve(&m, 0, 1, &o, &r);
    o = hrm_default_options(HRM_GAUSS_KRONROD);
    o.rtol = -1;
    st[n++] = hrm_solve(&m, 0, 1, &o, &r);
    o = hrm_default_options(HRM_SIMPSON);
    mb = al_medium(&s, 0);
    mb.const_sigma_a[0] = -1;
    st[n++] = hrm_solve(&mb, 0, 1, &o, &r);
    bad.bad = 1;
    mb = al_medium(&bad, 1);
    st[n++] = hrm_solve(&mb, 0, 8, &o, &r);
    o.warp.kind = HRM_WARP_DISTANCE;
    o.warp.sigma_ref = -1;
    st[n++] = hrm_solve(&m, 0, 8, &o, &r);
    o.warp.kind = HRM_WARP_EQUIANGULAR;
    o.warp.delta = 4;
    o.warp.D = 0;
    st[n++] = hrm_solve(&m, 0, 8, &o, &r);
    o = hrm_default_options(HRM_SIMPSON);
    o.breaks = brk;
    o.nbreaks = 2;
    st[n++] = hrm_solve(&m, 0, 8, &o, &r);
    o = hrm_default_options(HRM_SIMPSON);
    bad.bad = 3;
    mb = al_medium(&bad, 1);
    st[n++] = hrm_solve(&mb, 0, 8, &o, &r);
    bad.bad = 2;
    st[n++] = hrm_transmittance(&mb, 0, 8, &o, Tr, 0);
    allocs = alloc_calls - before;
    {
        static const hrm_status want[] = {HRM_ERR_NULL_ARGUMENT, HRM_ERR_NULL_ARGUMENT, HRM_ERR_NULL_ARGUMENT,
                                          HRM_ERR_BAD_INTERVAL, HRM_ERR_BAD_INTERVAL, HRM_ERR_BAD_STEPS,
                                          HRM_ERR_BAD_METHOD, HRM_ERR_BAD_OPTION, HRM_ERR_BAD_MEDIUM,
                                          HRM_ERR_CALLBACK_VALUE, HRM_ERR_BAD_WARP, HRM_ERR_SINGULAR,
                                          HRM_ERR_BAD_BREAKS, HRM_ERR_RANGE, HRM_ERR_CALLBACK_VALUE};
        CHECK_INT(n, (int)(sizeof want / sizeof want[0]), "error cases");
        for (i = 0; i < n; ++i) CHECK_INT(st[i], want[i], "error case %d: %s", i, hrm_status_string(want[i]));
    }
    CHECK_INT(allocs, 0, "heap calls on %d error paths", n);
}

/* hrm_transmittance alone, every method and form, each medium, coupled
   and decoupled tau, finite and infinite rays, NULL options and stats. */
static void al_transmittance(void)
{
    mt_scene s;
    hrm_real Tr[NCH];
    hrm_stats stats;
    long before, calls = 0, answered = 0, allocs = 0;
    int mi, f, md, tm, inf;
    al_scene_init(&s);
    for (mi = 0; mi < (int)HRM_METHOD_COUNT; ++mi)
        for (f = 0; f <= (int)HRM_FORM_RTE; ++f)
            for (md = 0; md < AL_MEDIA; ++md)
                for (tm = 0; tm <= (int)HRM_TAU_COUPLED; ++tm)
                    for (inf = 0; inf < 2; ++inf) {
                        hrm_medium m = al_medium(&s, md);
                        hrm_options o;
                        hrm_status st;
                        before = alloc_calls;
                        o = hrm_default_options((hrm_method)mi);
                        allocs += alloc_calls - before;
                        o.form = (hrm_form)f;
                        o.tau_mode = (hrm_tau_mode)tm;
                        if (inf) o.warp.kind = HRM_WARP_DISTANCE;
                        before = alloc_calls;
                        st = hrm_transmittance(&m, 0, inf ? (hrm_real)INFINITY : 8, &o, Tr, &stats);
                        allocs += alloc_calls - before;
                        calls++;
                        answered += st >= 0;
                    }
    {
        hrm_medium m = al_medium(&s, 1);
        before = alloc_calls;
        answered += hrm_transmittance(&m, 0, 8, 0, Tr, 0) >= 0;
        allocs += alloc_calls - before;
        calls++;
    }
    CHECK_INT(allocs, 0, "heap calls during %ld calls of hrm_transmittance (%ld answered)", calls, answered);
    CHECK(answered > calls / 2, "hrm_transmittance answers (%ld of %ld)", answered, calls);
}

/* The other public functions. */
static void al_public(void)
{
    hrm_real origin[3] = {0, 0, 0}, dir[3] = {1, 0, 0}, zero[3] = {0, 0, 0}, light[3] = {3, 1, 0};
    hrm_real center[3] = {3, (hrm_real)0.5, 0}, out[2];
    hrm_warp warp;
    long before, allocs, seen = 0;
    int i, count = 0, sphere = 0, version;
    hrm_status a, b, c, d, e;
    before = alloc_calls;
    for (i = -1; i <= (int)HRM_METHOD_COUNT; ++i) {
        hrm_options o = hrm_default_options((hrm_method)i); /* (used: not elided) */
        seen += o.steps + (long)strlen(hrm_method_name((hrm_method)i));
    }
    for (i = -13; i <= 8; ++i) seen += (long)strlen(hrm_status_string((hrm_status)i));
    version = hrm_version();
    a = hrm_equiangular_warp(origin, dir, light, &warp);
    b = hrm_equiangular_warp(origin, zero, light, &warp);
    c = hrm_sphere_breaks(origin, dir, light, center, (hrm_real)0.2, 0, 8, out, &count);
    sphere += count;
    d = hrm_sphere_breaks(origin, dir, light, light, (hrm_real)0.2, 0, 8, out, &count);
    e = hrm_sphere_breaks(origin, dir, light, center, -1, 0, 8, out, &count);
    allocs = alloc_calls - before;
    CHECK_INT(allocs, 0, "heap calls in hrm_default_options, hrm_method_name, hrm_status_string, hrm_version, "
                         "hrm_equiangular_warp and hrm_sphere_breaks");
    CHECK(seen > 0 && version > 0, "the names and the version were read");
    CHECK(a == HRM_OK && b == HRM_ERR_BAD_WARP, "hrm_equiangular_warp ran (%d, %d)", (int)a, (int)b);
    CHECK(c == HRM_OK && sphere == 2 && d == HRM_OK && e == HRM_ERR_BAD_WARP,
          "hrm_sphere_breaks ran (%d with %d breaks, %d, %d)", (int)c, sphere, (int)d, (int)e);
}

/* The count sees what it must: one deliberate call of each function,
   through volatile pointers (a compiler may elide a malloc and its free). */
static void al_counter(void)
{
    void *(*volatile m)(size_t) = malloc;
    void *(*volatile ca)(size_t, size_t) = calloc;
    void *(*volatile re)(void *, size_t) = realloc;
    void (*volatile fr)(void *) = free;
    long before = alloc_calls, after_m, after_c, after_r, after_f;
    void *p = m(64), *q;
    after_m = alloc_calls;
    q = ca(4, 16);
    after_c = alloc_calls;
    p = re(p, 128);
    after_r = alloc_calls;
    fr(p);
    after_f = alloc_calls;
    fr(q);
    CHECK_INT(after_m - before, 1, "malloc counted");
    CHECK_INT(after_c - after_m, 1, "calloc counted");
    CHECK_INT(after_r - after_c, 1, "realloc counted");
    CHECK_INT(after_f - after_r, 1, "free counted");
}

int main(void)
{
    RUN_GROUP(al_counter);
    RUN_GROUP(al_grid);
    RUN_GROUP(al_options);
    RUN_GROUP(al_nested);
    RUN_GROUP(al_errors);
    RUN_GROUP(al_transmittance);
    RUN_GROUP(al_public);
    RUN_GROUP(al_counter); /* still counting at the end */
    return harness_summary();
}
