/* bench/measure.c - the measurements: every solve the benchmark makes.

   For every scene (scenes.h), method, warp and way of giving the medium it
   solves one ray with hrm_solve and compares L with an independent
   reference (reference.h): the error is Munoz 2014's
   |L - Lref| / max(|L|, |Lref|), worst channel. Fixed-step methods are swept
   over the step count N, adaptive methods over the relative tolerance rtol;
   each runs with no warp and with the scene's natural warp (importance
   sampling as a change of variable), and a homogeneous scene both as
   constants and as sigma callbacks. Every solve's evaluation counts are
   checked against the callbacks hrm made; every row is timed (median over
   repeated solves) unless --no-timing.

   Then the measurements behind three summary sections: the equiangular gain
   on the point scene, the transmittance table (point and smoke scenes, five
   ways of getting tau) and the library overhead against a hand-written
   ray-marching loop at two Li costs. Everything lands in bench_state; this
   file prints nothing but the progress line and check failures (stderr).

   The whole of hrm's implementation is compiled here. */

#define _POSIX_C_SOURCE 200809L /* clock_gettime, isatty */
#define HRM_IMPLEMENTATION
#include "bench.h"
#include "qag.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *const bench_warp_names[BENCH_WARP_COUNT] = {"none", "distance", "equiangular"};
const char *const bench_medium_names[BENCH_MEDIUM_COUNT] = {"const", "sigma"};

const double bench_section_steps[BENCH_SECTION_PARAMS] = {8, 32, 128};
const double bench_section_tols[BENCH_SECTION_PARAMS] = {1e-2, 1e-4, 1e-6};

/* ------------------------------------------------------------------------ */
/* Small helpers                                                            */
/* ------------------------------------------------------------------------ */

double bench_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int bench_finite(double x)
{
    return x - x == 0;
}

int bench_find_scene(const char *name)
{
    int si;
    for (si = 0; si < bench_scene_count; ++si)
        if (!strcmp(bench_scenes[si].name, name)) return si;
    return -1;
}

static void *bench_grow(void *p, int *cap, int need, size_t size)
{
    if (need <= *cap) return p;
    *cap = *cap ? 2 * *cap : 256;
    if (*cap < need) *cap = need;
    p = realloc(p, (size_t)*cap * size);
    if (!p) {
        fprintf(stderr, "bench: out of memory\n");
        exit(BENCH_EXIT_OUTPUT);
    }
    return p;
}

/* ------------------------------------------------------------------------ */
/* Methods                                                                  */
/* ------------------------------------------------------------------------ */

static const char *const bench_colors[] = {
    "#1f77b4", "#ff7f0e", "#7f7f7f", "#8c564b", "#d62728", "#9467bd", "#2ca02c",
    "#17becf", "#bcbd22", "#e377c2", "#000000", "#8c6d31", "#393b79", "#ad494a", "#637939",
    "#00a087", "#5254a3", "#e7969c", "#b5cf6b", "#de9ed6", "#6b6ecf", "#843c39"};

static void bench_method_add(bench_state *st, hrm_method id, hrm_gk_mode mode, hrm_gk_rule rule,
                             int expo, const char *suffix)
{
    bench_method *b = &st->methods[st->nmethods];
    b->id = id;
    b->gk_mode = mode;
    b->gk_rule = rule;
    b->expo = expo;
    snprintf(b->name, sizeof b->name, "%s%s", hrm_method_name(id), suffix);
    b->kind = BENCH_ADAPTIVE;
    b->order = 0;
    switch (id) {
    case HRM_RECTANGLE: b->kind = BENCH_FIXED; b->order = 2; break;
    case HRM_SIMPSON: b->kind = BENCH_FIXED; b->order = 4; break;
    case HRM_MONTE_CARLO: b->kind = BENCH_RANDOM; b->order = 0.5; break;
    case HRM_EULER: b->kind = BENCH_FIXED; b->order = 1; break;
    case HRM_RK4: b->kind = BENCH_FIXED; b->order = 4; break;
    case HRM_ADAMS_BASHFORTH: b->kind = BENCH_FIXED; b->order = 4; break;
    case HRM_ANALYTIC_MARCH: b->kind = BENCH_FIXED; b->order = 2; break;
    case HRM_NESTED_SIMPSON: case HRM_GAUSS_KRONROD: case HRM_BOGACKI_SHAMPINE:
    case HRM_DORMAND_PRINCE: case HRM_FEHLBERG: case HRM_CASH_KARP: case HRM_VERNER:
        break;
    default: b->kind = BENCH_OTHER; break;
    }
    b->color = bench_colors[st->nmethods % COUNT_OF(bench_colors)];
    b->marker = st->nmethods % 5;
    st->nmethods++;
}

void bench_state_init(bench_state *st)
{
    int m;
    memset(st, 0, sizeof *st);
    for (m = 1; m < (int)HRM_METHOD_COUNT; ++m) {
        if (m == (int)HRM_GAUSS_KRONROD) {
            /* the default (global, G7/K15), global with G3/K7, and
               Munoz's local mode (G7/K15) */
            bench_method_add(st, HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_RULE_DEFAULT, 0, "-global");
            bench_method_add(st, HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_K7, 0, "-k7");
            bench_method_add(st, HRM_GAUSS_KRONROD, HRM_GK_LOCAL, HRM_GK_RULE_DEFAULT, 0, "-local");
        } else {
            bench_method_add(st, (hrm_method)m, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 0, "");
        }
    }
    /* the exponentially fitted variants (options.exponential = 1) */
    bench_method_add(st, HRM_SIMPSON, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 1, "-exp");
    bench_method_add(st, HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_RULE_DEFAULT, 1, "-global-exp");
    bench_method_add(st, HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_K7, 1, "-k7-exp");
    bench_method_add(st, HRM_GAUSS_KRONROD, HRM_GK_LOCAL, HRM_GK_RULE_DEFAULT, 1, "-local-exp");
    bench_method_add(st, HRM_BOGACKI_SHAMPINE, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 1, "-exp");
    bench_method_add(st, HRM_DORMAND_PRINCE, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 1, "-exp");
    /* and with the source's own decay factored (options.exponential = 2) */
    bench_method_add(st, HRM_SIMPSON, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 2, "-exp2");
    bench_method_add(st, HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, HRM_GK_K7, 2, "-k7-exp2");
    bench_method_add(st, HRM_DORMAND_PRINCE, HRM_GK_DEFAULT, HRM_GK_RULE_DEFAULT, 2, "-exp2");
    st->timings = 5;
    st->batch_seconds = 1e-3;
    st->equi.scene = st->trans.point = st->trans.smoke = -1;
    st->overhead[0].scene = st->overhead[1].scene = -1;
    ref_rule_init(&st->rule);
}

void bench_state_free(bench_state *st)
{
    free(st->rows);
    free(st->sweeps);
    st->rows = NULL;
    st->sweeps = NULL;
}

int bench_is_swept_over_n(const bench_method *me)
{
    return me->kind == BENCH_FIXED || me->kind == BENCH_RANDOM;
}

const char *bench_kind_name(bench_kind k)
{
    return k == BENCH_FIXED      ? "fixed-step, swept over N"
           : k == BENCH_RANDOM   ? "fixed-step, random (error: RMS over seeds), swept over N"
           : k == BENCH_ADAPTIVE ? "adaptive, swept over rtol"
                                 : "no sweep in the bench yet: listed, not run";
}

const char *bench_control_name(hrm_control c)
{
    return c == HRM_CONTROL_MUNOZ ? "munoz" : c == HRM_CONTROL_GONTERMAN ? "gonterman" : "pi";
}

/* ------------------------------------------------------------------------ */
/* What runs: the selection                                                 */
/* ------------------------------------------------------------------------ */

int bench_scene_selected(const bench_config *cfg, int si)
{
    return !cfg->any_scene || cfg->scene_on[si];
}

int bench_method_selected(const bench_state *st, int mi)
{
    const bench_method *me = &st->methods[mi];
    const bench_config *cfg = &st->cfg;
    if (me->kind == BENCH_OTHER) return 0;
    if (cfg->any_method && !cfg->method_on[mi]) return 0;
    /* --steps alone runs the fixed-step methods, --tol alone the adaptive ones */
    if (bench_is_swept_over_n(me)) return !cfg->user_tols || cfg->user_steps;
    return !cfg->user_steps || cfg->user_tols;
}

/* The summary sections run every method that --method leaves in but the
   fitted variants (they have their own section). */
static int bench_method_in_sections(const bench_state *st, int mi)
{
    return st->methods[mi].kind != BENCH_OTHER && !st->methods[mi].expo &&
           (!st->cfg.any_method || st->cfg.method_on[mi]);
}

int bench_warp_apply(const bench_scene *sc, bench_warp_id w, hrm_options *o)
{
    static const hrm_real origin[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
    double pos[3];
    hrm_real light[3];
    int i;
    memset(&o->warp, 0, sizeof o->warp);
    switch (w) {
    case BENCH_WARP_NONE:
        return 1;
    case BENCH_WARP_DISTANCE:
        o->warp.kind = HRM_WARP_DISTANCE;
        o->warp.sigma_ref = 0; /* hrm's choice: the mean extinction over the ray */
        return 1;
    case BENCH_WARP_EQUIANGULAR:
        /* from hrm_equiangular_warp for the ray x(s) = (s, 0, 0) */
        if (!sc->light || !sc->light(sc->params, pos)) return 0;
        for (i = 0; i < 3; ++i) light[i] = (hrm_real)pos[i];
        return hrm_equiangular_warp(origin, dir, light, &o->warp) == HRM_OK;
    default:
        return 0;
    }
}

int bench_scene_warps(const bench_config *cfg, const bench_scene *sc,
                      bench_warp_id out[BENCH_WARP_COUNT])
{
    hrm_options probe;
    int w, n = 0;
    for (w = 0; w < BENCH_WARP_COUNT; ++w) {
        int on = cfg->any_warp ? cfg->warp_on[w] || (cfg->natural_on && (int)sc->natural_warp == w)
                               : w == BENCH_WARP_NONE || (int)sc->natural_warp == w;
        if (on && bench_warp_apply(sc, (bench_warp_id)w, &probe)) out[n++] = (bench_warp_id)w;
    }
    return n;
}

int bench_scene_media(const bench_config *cfg, int si, bench_medium_id out[BENCH_MEDIUM_COUNT])
{
    hrm_medium m;
    bench_calls calls;
    int k, n = 0;
    for (k = 0; k < BENCH_MEDIUM_COUNT; ++k)
        if ((!cfg->any_medium || cfg->medium_on[k]) &&
            bench_medium_build(&bench_scenes[si], (bench_medium_id)k, &m, &calls))
            out[n++] = (bench_medium_id)k;
    return n;
}

int bench_params_of(const bench_config *cfg, const bench_method *me, const double **p)
{
    if (bench_is_swept_over_n(me)) {
        *p = cfg->steps;
        return cfg->nsteps;
    }
    *p = cfg->tols;
    return cfg->ntols;
}

/* ------------------------------------------------------------------------ */
/* References                                                               */
/* ------------------------------------------------------------------------ */

static void bench_reference_compute(const bench_scene *sc, const ref_rule *rule,
                                    bench_reference *ref)
{
    long double pts[REF_MAX_POINTS], cut[REF_MAX_POINTS], coarse[HRM_CHANNELS],
        fine[HRM_CHANNELS];
    long double t0 = (long double)sc->t0, t1 = (long double)sc->t1;
    int n = 0, k = 0, i, j;

    ref->panel = sc->ref_panel > 0 ? sc->ref_panel : REF_PANEL;
    if (sc->split_points) k = sc->split_points(sc->params, cut, REF_MAX_POINTS - 2);
    pts[n++] = t0;
    ref->nsplits = 0;
    for (i = 0; i < k; ++i) {
        if (!(cut[i] > t0 && cut[i] < t1)) continue;
        for (j = n; j > 1 && pts[j - 1] > cut[i]; --j) pts[j] = pts[j - 1];
        pts[j] = cut[i];
        ++n;
    }
    for (i = 1; i < n; ++i) ref->splits[ref->nsplits++] = pts[i];
    pts[n++] = t1;

    ref_integrate(rule, sc->integrand, sc->params, pts, n, ref->panel, coarse);
    ref_integrate(rule, sc->integrand, sc->params, pts, n, ref->panel / 2, fine);
    if (sc->closed_form) {
        sc->closed_form(sc->params, t0, t1, ref->L);
        ref->accuracy = ref_rel_diff(fine, ref->L); /* checks the quadrature */
    } else {
        memcpy(ref->L, fine, sizeof fine);
        ref->accuracy = ref_rel_diff(coarse, fine);
    }
    ref->done = 1;
}

const bench_reference *bench_reference_get(bench_state *st, int si)
{
    bench_reference *ref = &st->refs[si];
    if (!ref->done) {
        bench_reference_compute(&bench_scenes[si], &st->rule, ref);
        if (!(ref->accuracy <= BENCH_REF_CHECK)) {
            st->ref_bad++;
            fprintf(stderr, "\nbench: scene %s: reference accuracy %.1Le worse than %.0Le\n",
                    bench_scenes[si].name, ref->accuracy, BENCH_REF_CHECK);
        }
    }
    return ref;
}

/* Munoz 2014's relative error |L - Lref| / max(|L|, |Lref|), worst channel;
   NaN if hrm returned anything not finite. */
static double bench_rel_error(const hrm_real L[HRM_CHANNELS], const long double *ref)
{
    long double l[HRM_CHANNELS];
    int c;
    for (c = 0; c < HRM_CHANNELS; ++c) {
        l[c] = (long double)L[c];
        if (l[c] - l[c] != 0) return (double)NAN;
    }
    return (double)ref_rel_diff(l, ref);
}

/* ------------------------------------------------------------------------ */
/* Timing                                                                   */
/* ------------------------------------------------------------------------ */

/* A batch of `reps` repetitions of the timed work; returns a value computed
   from the results, which the timer keeps in a volatile so that the work
   cannot be optimised away. */
typedef double (*bench_batch_fn)(void *ctx, long reps);

/* Nanoseconds per repetition of fn over `batches` batches, each repeated
   until it lasts st->batch_seconds: their median (use_min 0), or their
   minimum (use_min 1: interference from other processes only ever adds
   time, so the minimum is the steadier estimate of the work itself). */
static double bench_time_stat(const bench_state *st, bench_batch_fn fn, void *ctx, int batches,
                              int use_min)
{
    volatile double sink;
    double t[32], batch, start;
    long reps = 1;
    int i, n = batches < 32 ? batches : 32;
    for (;;) {
        start = bench_seconds();
        sink = fn(ctx, reps);
        batch = bench_seconds() - start;
        if (batch >= st->batch_seconds || reps >= (1L << 28)) break;
        /* Jump close to the target, at most x16 at a time. */
        if (batch > st->batch_seconds / 16)
            reps = (long)ceil((double)reps * 1.1 * st->batch_seconds / batch);
        else
            reps *= 16;
    }
    for (i = 0; i < n; ++i) {
        start = bench_seconds();
        sink = fn(ctx, reps);
        t[i] = 1e9 * (bench_seconds() - start) / (double)reps;
    }
    (void)sink;
    qsort(t, (size_t)n, sizeof t[0], bench_cmp_double);
    return use_min ? t[0] : t[n / 2];
}

/* ------------------------------------------------------------------------ */
/* One measurement                                                          */
/* ------------------------------------------------------------------------ */

typedef struct bench_case {
    const bench_scene *sc;
    const hrm_medium *medium;
    bench_calls *calls;
    bench_warp_id warp;
    hrm_options options;
    int seeds;
    const char *label;  /* how the medium is given, for messages */
} bench_case;

static double bench_solve_batch(void *ctx, long reps)
{
    const bench_case *bc = (const bench_case *)ctx;
    hrm_options opt = bc->options;
    hrm_result res;
    double sum = 0;
    long r;
    for (r = 0; r < reps; ++r) {
        opt.seed = (uint64_t)(r % bc->seeds) + 1;
        hrm_solve(bc->medium, (hrm_real)bc->sc->t0, (hrm_real)bc->sc->t1, &opt, &res);
        sum += (double)res.L[0];
    }
    return sum;
}

/* hrm's stats against the callbacks it made: every source evaluation calls
   Li where the scene has it (each such scene scatters everywhere) and Le
   where it has emission (absorbing everywhere); medium evaluations are
   counted as scenes.h says. */
static void bench_check_counts(bench_state *st, const bench_case *bc, const bench_method *me,
                               const bench_counts *n, const hrm_stats *s)
{
    const hrm_medium *m = bc->medium;
    int ok = n->medium == s->medium_evals;
    if (m->Li) ok &= n->li == s->evals;
    if (m->Le) ok &= n->le == s->evals;
    if (ok) return;
    if (++st->count_mismatches <= 10)
        fprintf(stderr,
                "\nbench: count mismatch: %s %s warp %s %s, N or rtol %g: stats evals=%ld "
                "medium_evals=%ld; callbacks Li=%ld Le=%ld, medium evaluations %ld "
                "(sigma_a=%ld sigma_s=%ld transmittance=%ld)\n",
                bc->sc->name, me->name, bench_warp_names[bc->warp], bc->label,
                me->kind == BENCH_ADAPTIVE ? (double)bc->options.rtol : (double)bc->options.steps,
                s->evals, s->medium_evals, n->li, n->le, n->medium, n->sigma_a, n->sigma_s, n->tr);
}

/* Solves the case (every seed), checks the counts, fills row's stats,
   rel_error and status, and times it if asked. */
static void bench_run_case(bench_state *st, const bench_reference *ref, const bench_method *me,
                           const bench_case *bc, int timed, bench_row *row)
{
    hrm_options opt = bc->options;
    hrm_result res;
    double sumsq = 0, err = 0;
    int i;

    row->status = HRM_OK;
    for (i = 0; i < bc->seeds; ++i) {
        hrm_status s;
        opt.seed = (uint64_t)i + 1;
        memset(&bc->calls->n, 0, sizeof bc->calls->n);
        s = hrm_solve(bc->medium, (hrm_real)bc->sc->t0, (hrm_real)bc->sc->t1, &opt, &res);
        if (s >= 0) /* a failed solve stops mid-way: nothing to compare */
            bench_check_counts(st, bc, me, &bc->calls->n, &res.stats);
        if (i == 0) {
            int c;
            row->stats = res.stats;
            row->est_error = (double)NAN;
            for (c = 0; c < HRM_CHANNELS && s >= 0; ++c) {
                double e = (double)res.error[c] / fabs((double)ref->L[c]);
                if (res.error[c] >= 0 && !(e <= row->est_error)) row->est_error = e;
            }
        }
        if (s < 0 ? row->status >= 0 : row->status >= 0 && s > row->status) row->status = s;
        err = s < 0 ? (double)NAN : bench_rel_error(res.L, ref->L);
        sumsq += err * err;
    }
    st->solves += bc->seeds;
    row->rel_error = bc->seeds > 1 ? sqrt(sumsq / bc->seeds) : err;
    row->ns_per_ray =
        timed ? bench_time_stat(st, bench_solve_batch, (void *)bc, st->timings, 0) : (double)NAN;
}

static void bench_case_init(bench_case *bc, const bench_state *st, const bench_scene *sc,
                            const bench_method *me, bench_warp_id warp, double param,
                            const hrm_medium *medium, bench_calls *calls, const char *label)
{
    bc->sc = sc;
    bc->medium = medium;
    bc->calls = calls;
    bc->warp = warp;
    bc->label = label;
    bc->options = hrm_default_options(me->id);
    bc->options.gk_mode = me->gk_mode;
    bc->options.gk_rule = me->gk_rule;
    bc->options.exponential = me->expo;
    if (bench_is_swept_over_n(me)) {
        bc->options.steps = (int)param;
    } else {
        bc->options.rtol = (hrm_real)param;
        bc->options.max_evals = BENCH_MAX_EVALS;
        /* The Runge-Kutta pairs only: hrm also derives h_min's default from
           the control, which would change the quadrature methods. */
        if (me->id != HRM_NESTED_SIMPSON && me->id != HRM_GAUSS_KRONROD)
            bc->options.control = st->cfg.control;
    }
    bench_warp_apply(sc, warp, &bc->options);
    bc->seeds = me->kind == BENCH_RANDOM ? st->cfg.seeds : 1;
}

/* ------------------------------------------------------------------------ */
/* Rows and sweeps                                                          */
/* ------------------------------------------------------------------------ */

static bench_row *bench_new_row(bench_state *st)
{
    st->rows = (bench_row *)bench_grow(st->rows, &st->rows_cap, st->nrows + 1, sizeof *st->rows);
    memset(&st->rows[st->nrows], 0, sizeof *st->rows);
    return &st->rows[st->nrows++];
}

static bench_sweep *bench_new_sweep(bench_state *st)
{
    st->sweeps = (bench_sweep *)bench_grow(st->sweeps, &st->sweeps_cap, st->nsweeps + 1,
                                           sizeof *st->sweeps);
    memset(&st->sweeps[st->nsweeps], 0, sizeof *st->sweeps);
    return &st->sweeps[st->nsweeps++];
}

const bench_sweep *bench_find_sweep(const bench_state *st, int scene, int method,
                                    bench_warp_id warp, bench_medium_id medium)
{
    int i;
    for (i = 0; i < st->nsweeps; ++i) {
        const bench_sweep *sw = &st->sweeps[i];
        if (sw->scene == scene && sw->method == method && sw->warp == warp &&
            sw->medium == medium)
            return sw;
    }
    return NULL;
}

/* -(least-squares slope) of y against x; NaN with fewer than 2 distinct x. */
static double bench_order(const double *x, const double *y, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, den;
    int i;
    for (i = 0; i < n; ++i) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        sxy += x[i] * y[i];
    }
    den = n * sxx - sx * sx;
    return n >= 2 && den > 0 ? -(n * sxy - sx * sy) / den : (double)NAN;
}

static void bench_fit_sweep(const bench_state *st, bench_sweep *sw)
{
    double x[BENCH_MAX_PARAMS], y[BENCH_MAX_PARAMS];
    int i, k = 0, t;
    for (i = 0; i < sw->count; ++i) {
        const bench_row *r = &st->rows[sw->first + i];
        if (!(r->rel_error > BENCH_FIT_FLOOR) || !bench_finite(r->rel_error) ||
            r->stats.evals <= 0)
            continue;
        x[k] = log((double)r->stats.evals);
        y[k] = log(r->rel_error);
        ++k;
    }
    sw->points = k;
    sw->order = bench_order(x, y, k);
    t = k < BENCH_TAIL ? k : BENCH_TAIL;
    sw->tail = bench_order(x + (k - t), y + (k - t), t);
}

/* ------------------------------------------------------------------------ */
/* Progress (stderr)                                                        */
/* ------------------------------------------------------------------------ */

void bench_progress_start(bench_state *st, double start)
{
    bench_progress *pg = &st->progress;
    int si, mi;
    memset(pg, 0, sizeof *pg);
    pg->start = start;
    pg->tty = isatty(2);
    for (si = 0; si < bench_scene_count; ++si) {
        bench_warp_id w[BENCH_WARP_COUNT];
        bench_medium_id md[BENCH_MEDIUM_COUNT];
        int nw, nm;
        if (!bench_scene_selected(&st->cfg, si)) continue;
        nw = bench_scene_warps(&st->cfg, &bench_scenes[si], w);
        nm = bench_scene_media(&st->cfg, si, md);
        for (mi = 0; mi < st->nmethods; ++mi) {
            const double *p;
            if (bench_method_selected(st, mi))
                pg->total += (long)nw * nm * bench_params_of(&st->cfg, &st->methods[mi], &p);
        }
    }
}

void bench_progress_show(bench_state *st, const char *what)
{
    bench_progress *pg = &st->progress;
    double pct = pg->total ? 100.0 * (double)pg->done / (double)pg->total : 100.0;
    double now = bench_seconds(), el = now - pg->start;
    if (pg->tty && now - pg->shown >= 0.1) { /* at most ten redraws a second */
        pg->shown = now;
        fprintf(stderr, "\r\033[K[%3.0f%%] %5.1f s  %s", pct, el, what);
        fflush(stderr);
    }
}

/* ------------------------------------------------------------------------ */
/* The sweeps of one scene                                                  */
/* ------------------------------------------------------------------------ */

void bench_run_scene(bench_state *st, int si)
{
    const bench_scene *sc = &bench_scenes[si];
    const bench_reference *ref = bench_reference_get(st, si);
    bench_calls calls[BENCH_MEDIUM_COUNT];
    hrm_medium media[BENCH_MEDIUM_COUNT];
    bench_warp_id warps[BENCH_WARP_COUNT];
    bench_medium_id mids[BENCH_MEDIUM_COUNT];
    int nw = bench_scene_warps(&st->cfg, sc, warps), nm = bench_scene_media(&st->cfg, si, mids);
    int mi, wi, k, j;

    for (j = 0; j < nm; ++j) bench_medium_build(sc, mids[j], &media[j], &calls[j]);
    /* method, then warp, then medium: the two ways of giving the medium end
       up next to each other in the tables */
    for (mi = 0; mi < st->nmethods; ++mi) {
        const bench_method *me = &st->methods[mi];
        const double *params;
        int np;
        if (!bench_method_selected(st, mi)) continue;
        np = bench_params_of(&st->cfg, me, &params);
        for (wi = 0; wi < nw; ++wi)
            for (j = 0; j < nm; ++j) {
                char what[96];
                int first = st->nrows, sw_index;
                snprintf(what, sizeof what, "%-11s %-22s %-11s %s", sc->name, me->name,
                         bench_warp_names[warps[wi]], bench_medium_names[mids[j]]);
                for (k = 0; k < np; ++k) {
                    bench_case bc;
                    bench_row *r;
                    bench_progress_show(st, what);
                    bench_case_init(&bc, st, sc, me, warps[wi], params[k], &media[j], &calls[j],
                                    bench_medium_names[mids[j]]);
                    r = bench_new_row(st);
                    r->scene = si;
                    r->method = mi;
                    r->warp = warps[wi];
                    r->medium = mids[j];
                    r->param = params[k];
                    bench_run_case(st, ref, me, &bc, st->cfg.timed, r);
                    if (r->status < 0) st->errors++;
                    st->progress.done++;
                }
                sw_index = st->nsweeps;
                {
                    bench_sweep *sw = bench_new_sweep(st);
                    sw->scene = si;
                    sw->method = mi;
                    sw->warp = warps[wi];
                    sw->medium = mids[j];
                    sw->first = first;
                    sw->count = st->nrows - first;
                }
                if (bench_is_swept_over_n(me)) bench_fit_sweep(st, &st->sweeps[sw_index]);
            }
    }
}

/* ------------------------------------------------------------------------ */
/* Equiangular gain on the point scene                                      */
/* ------------------------------------------------------------------------ */

/* One untimed solve of a section: its error (NaN on an error status). */
static double bench_section_solve_breaks(bench_state *st, int si, const bench_method *me,
                                         bench_warp_id warp, double param, const hrm_medium *m,
                                         bench_calls *calls, hrm_tau_mode tau_mode,
                                         const char *label, const hrm_real *breaks, int nbreaks,
                                         int find_jumps, double cutoff, bench_row *row)
{
    bench_case bc;
    bench_case_init(&bc, st, &bench_scenes[si], me, warp, param, m, calls, label);
    bc.options.tau_mode = tau_mode;
    bc.options.cutoff = (hrm_real)cutoff;
    bc.options.breaks = breaks;
    bc.options.nbreaks = nbreaks;
    bc.options.find_jumps = find_jumps;
    memset(row, 0, sizeof *row);
    row->scene = si;
    row->warp = warp;
    row->param = param;
    bench_run_case(st, bench_reference_get(st, si), me, &bc, 0, row);
    if (row->status < 0) st->errors++;
    return row->status < 0 ? (double)NAN : row->rel_error;
}

static double bench_section_solve(bench_state *st, int si, const bench_method *me,
                                  bench_warp_id warp, double param, const hrm_medium *m,
                                  bench_calls *calls, hrm_tau_mode tau_mode, const char *label,
                                  bench_row *row)
{
    return bench_section_solve_breaks(st, si, me, warp, param, m, calls, tau_mode, label, NULL, 0,
                                      0, 0, row);
}

void bench_measure_equiangular(bench_state *st)
{
    bench_equi *eq = &st->equi;
    int si = bench_find_scene("point"), mi, k, w;
    hrm_medium m;
    bench_calls calls;
    eq->scene = -1;
    eq->n = 0;
    if (si < 0 || !bench_scene_selected(&st->cfg, si)) return;
    eq->scene = si;
    bench_medium_build(&bench_scenes[si], BENCH_MEDIUM_CONST, &m, &calls);
    /* rectangle and monte-carlo first: the pair the paper reports on */
    for (w = 0; w < 2; ++w)
        for (mi = 0; mi < st->nmethods; ++mi) {
            const bench_method *me = &st->methods[mi];
            int first = me->id == HRM_RECTANGLE || me->id == HRM_MONTE_CARLO;
            if (!bench_is_swept_over_n(me) || first != !w || !bench_method_in_sections(st, mi))
                continue;
            for (k = 0; k < BENCH_SECTION_PARAMS; ++k) {
                bench_row r;
                double e0 = bench_section_solve(st, si, me, BENCH_WARP_NONE,
                                                bench_section_steps[k], &m, &calls,
                                                HRM_TAU_DEFAULT, "const", &r);
                double e1 = bench_section_solve(st, si, me, BENCH_WARP_EQUIANGULAR,
                                                bench_section_steps[k], &m, &calls,
                                                HRM_TAU_DEFAULT, "const", &r);
                eq->ratio[eq->n][k] = bench_finite(e0) && bench_finite(e1) && e1 > 0
                                          ? e0 / e1
                                          : (double)NAN;
            }
            eq->method[eq->n++] = mi;
        }
}

/* ------------------------------------------------------------------------ */
/* Transmittance: five ways of getting tau, equiangular warp                */
/* ------------------------------------------------------------------------ */

void bench_measure_transmittance(bench_state *st)
{
    bench_trans *tr = &st->trans;
    int point = bench_find_scene("point"), smoke = bench_find_scene("smoke"), mi, k, col;
    hrm_medium m[BENCH_TRANS_COLS];
    bench_calls calls[BENCH_TRANS_COLS];
    static const hrm_tau_mode modes[BENCH_TRANS_COLS] = {
        HRM_TAU_DEFAULT, HRM_TAU_DEFAULT, HRM_TAU_DEFAULT, HRM_TAU_COUPLED, HRM_TAU_DEFAULT};
    static const char *const labels[BENCH_TRANS_COLS] = {
        "const", "sigma", "sigma, tau default", "sigma, tau coupled", "sigma, exact Tr"};
    int scene_of[BENCH_TRANS_COLS];

    tr->point = point >= 0 && bench_scene_selected(&st->cfg, point) ? point : -1;
    tr->smoke = smoke >= 0 && bench_scene_selected(&st->cfg, smoke) ? smoke : -1;
    tr->n = 0;
    if (tr->point < 0 && tr->smoke < 0) return;
    for (col = 0; col < BENCH_TRANS_COLS; ++col) {
        scene_of[col] = col < 2 ? tr->point : tr->smoke;
        if (scene_of[col] < 0) continue;
        bench_medium_build(&bench_scenes[scene_of[col]],
                           col == 0 ? BENCH_MEDIUM_CONST : BENCH_MEDIUM_SIGMA, &m[col], &calls[col]);
        if (col == 4) m[col].transmittance = bench_scenes[scene_of[col]].transmittance;
    }
    for (mi = 0; mi < st->nmethods; ++mi) {
        const bench_method *me = &st->methods[mi];
        if (!bench_method_in_sections(st, mi)) continue;
        for (k = 0; k < BENCH_SECTION_PARAMS; ++k) {
            bench_trans_row *r = &tr->rows[tr->n++];
            r->method = mi;
            r->param = bench_is_swept_over_n(me) ? bench_section_steps[k] : bench_section_tols[k];
            for (col = 0; col < BENCH_TRANS_COLS; ++col) {
                bench_row row;
                r->ran[col] = scene_of[col] >= 0;
                r->err[col] = (double)NAN;
                if (!r->ran[col]) continue;
                r->err[col] = bench_section_solve(st, scene_of[col], me, BENCH_WARP_EQUIANGULAR,
                                                  r->param, &m[col], &calls[col], modes[col],
                                                  labels[col], &row);
                r->status[col] = row.status;
                if (col == 2) r->stats_c = row.stats;
            }
        }
    }
}

/* ------------------------------------------------------------------------ */
/* A general-purpose quadrature: QUADPACK's QAG (GK15)                      */
/* ------------------------------------------------------------------------ */

void bench_measure_qag(bench_state *st)
{
    int si, k, c;
    st->qag_check = qag_rule_check();
    if (st->qag_check > BENCH_QAG_CHECK) st->ref_bad++;
    for (si = 0; si < bench_scene_count; ++si) {
        const bench_scene *sc = &bench_scenes[si];
        const bench_reference *ref;
        bench_qag *q = &st->qag[si];
        q->n = 0;
        if (!bench_scene_selected(&st->cfg, si)) continue;
        ref = bench_reference_get(st, si);
        for (k = 0; k < st->cfg.ntols; ++k) {
            double out[HRM_CHANNELS];
            hrm_real L[HRM_CHANNELS];
            int ok;
            q->evals[k] = qag_integrate(sc->integrand, sc->params, sc->t0, sc->t0, sc->t1, st->cfg.tols[k], out, &ok);
            for (c = 0; c < HRM_CHANNELS; ++c) L[c] = (hrm_real)out[c];
            q->err[k] = ok ? bench_rel_error(L, ref->L) : (double)NAN;
            q->n++;
        }
    }
}

/* ------------------------------------------------------------------------ */
/* Early ray termination on sigma callbacks                                 */
/* ------------------------------------------------------------------------ */

void bench_measure_cutoff(bench_state *st)
{
    static const char *const names[BENCH_CUT_SCENES] = {"thick", "cloud"};
    int s, mi, k, c;
    st->cut.n = 0;
    for (s = 0; s < BENCH_CUT_SCENES; ++s) {
        int si = bench_find_scene(names[s]);
        hrm_medium m;
        bench_calls calls;
        if (si < 0 || !bench_scene_selected(&st->cfg, si)) continue;
        bench_medium_build(&bench_scenes[si], BENCH_MEDIUM_SIGMA, &m, &calls);
        for (mi = 0; mi < st->nmethods; ++mi) {
            const bench_method *me = &st->methods[mi];
            if (bench_is_swept_over_n(me) || me->expo || !bench_method_in_sections(st, mi)) continue;
            for (k = 0; k < BENCH_SECTION_PARAMS; ++k) {
                bench_cut_row *r = &st->cut.rows[st->cut.n++];
                r->scene = si;
                r->method = mi;
                r->param = bench_section_tols[k];
                for (c = 0; c < 2; ++c)
                    bench_section_solve_breaks(st, si, me, BENCH_WARP_NONE, r->param, &m, &calls, HRM_TAU_DEFAULT,
                                               "sigma", NULL, 0, 0, c ? BENCH_CUTOFF : 0, &r->r[c]);
            }
        }
    }
}

/* ------------------------------------------------------------------------ */
/* Breakpoints on the occluder scene                                        */
/* ------------------------------------------------------------------------ */

/* The fewest evaluations from which a sweep (loose to tight) stays within
   each target; -1 where it never does. */
static void bench_brk_fewest(const long *evals, const double *err, int n, long out[3])
{
    static const double targets[3] = {1e-2, 1e-4, 1e-6};
    int t, k, j;
    for (t = 0; t < 3; ++t) {
        out[t] = -1;
        for (k = 0; k < n && out[t] < 0; ++k) {
            int ok = 1;
            for (j = k; j < n; ++j) ok &= bench_finite(err[j]) && err[j] <= targets[t];
            if (ok) out[t] = evals[k];
        }
    }
}

void bench_measure_breaks(bench_state *st)
{
    static const char *const names[BENCH_BRK_SCENES] = {"occluder", "slab"};
    static const bench_warp_id warps[2] = {BENCH_WARP_NONE, BENCH_WARP_EQUIANGULAR};
    int bi;
    for (bi = 0; bi < BENCH_BRK_SCENES; ++bi) {
        bench_brk *b = &st->brk[bi];
        int si = bench_find_scene(names[bi]), mi, w, j, way, k;
        const bench_scene *sc;
        hrm_real br[2];
        b->scene = -1;
        b->n = 0;
        if (si < 0 || !bench_scene_selected(&st->cfg, si)) continue;
        b->scene = si;
        sc = &bench_scenes[si];
        b->nbreaks = bench_scene_breaks(sc, br);
        for (k = 0; k < b->nbreaks; ++k) b->breaks[k] = (double)br[k];
        for (mi = 0; mi < st->nmethods; ++mi) {
            const bench_method *me = &st->methods[mi];
            const double *params;
            int np;
            if (!bench_method_in_sections(st, mi) || me->kind == BENCH_RANDOM) continue;
            np = bench_params_of(&st->cfg, me, &params);
            for (w = 0; w < 2; ++w) {
                bench_medium_id mids[BENCH_MEDIUM_COUNT];
                int nm = bench_scene_media(&st->cfg, si, mids);
                /* the slab has no point light: its natural warp instead */
                bench_warp_id warp = w == 0 ? warps[0] : sc->light ? warps[1] : sc->natural_warp;
                for (j = 0; j < nm && b->n < BENCH_BRK_ROWS; ++j) {
                    bench_brk_row *r = &b->rows[b->n++];
                    hrm_medium m;
                    bench_calls calls;
                    r->method = mi;
                    r->warp = warp;
                    r->medium = mids[j];
                    bench_medium_build(sc, mids[j], &m, &calls);
                    r->np = np;
                    for (k = 0; k < np; ++k) r->param[k] = params[k];
                    for (way = 0; way < 3; ++way) {
                        long *ev = r->evals[way];
                        double *er = r->err[way];
                        for (k = 0; k < np; ++k) {
                            bench_row row;
                            er[k] = bench_section_solve_breaks(st, si, me, warp, params[k], &m, &calls,
                                                               HRM_TAU_DEFAULT, bench_medium_names[mids[j]],
                                                               way == 1 ? br : NULL,
                                                               way == 1 ? b->nbreaks : 0,
                                                               way == 0 ? -1 : way == 1 ? 0 : 1, 0, &row);
                            ev[k] = row.stats.evals;
                        }
                        bench_brk_fewest(ev, er, np, r->fewest[way]);
                    }
                }
            }
        }
    }
}

/* ------------------------------------------------------------------------ */
/* Library overhead against a hand-written ray march                        */
/* ------------------------------------------------------------------------ */

typedef struct bench_floor {
    const bench_scene *sc;
    const hrm_medium *m;
    int N;
    int march;     /* 0: the callbacks alone; 1: the hand-written ray march */
    hrm_real L[HRM_CHANNELS];
} bench_floor;

/* The floor: what a renderer's own ray-marching loop does per sample, with
   the same callbacks hrm calls per evaluation. march 0 calls them only;
   march 1 is the rectangle rule with Tr in closed form (homogeneous) or tau
   by the trapezoid rule on sigma_t (callbacks). */
static double bench_floor_batch(void *ctx, long reps)
{
    bench_floor *f = (bench_floor *)ctx;
    const hrm_medium *m = f->m;
    double T = f->sc->t1 - f->sc->t0, h = T / f->N, sum = 0;
    long r;
    int k, c;
    for (r = 0; r < reps; ++r) {
        hrm_real L[HRM_CHANNELS] = {0}, tau[HRM_CHANNELS] = {0}, prev[HRM_CHANNELS] = {0};
        double prev_s = f->sc->t0;
        for (k = 0; k < f->N; ++k) {
            hrm_real s = (hrm_real)(f->sc->t0 + (k + 0.5) * h);
            hrm_real sa[HRM_CHANNELS] = {0}, ss[HRM_CHANNELS] = {0}, le[HRM_CHANNELS] = {0},
                     li[HRM_CHANNELS] = {0};
            if (m->flags & HRM_MEDIUM_HOMOGENEOUS) {
                for (c = 0; c < HRM_CHANNELS; ++c) {
                    sa[c] = m->const_sigma_a[c];
                    ss[c] = m->const_sigma_s[c];
                }
            } else {
                if (m->sigma_a) m->sigma_a(m->user, s, sa);
                if (m->sigma_s) m->sigma_s(m->user, s, ss);
            }
            if (m->Le) m->Le(m->user, s, le);
            if (m->Li) m->Li(m->user, s, li);
            if (!f->march) {
                sum += (double)(sa[0] + ss[0] + le[0] + li[0]);
                continue;
            }
            for (c = 0; c < HRM_CHANNELS; ++c) {
                hrm_real st = sa[c] + ss[c], tr;
                if (m->flags & HRM_MEDIUM_HOMOGENEOUS) {
                    tr = exp(-st * (s - f->sc->t0));
                } else {
                    tau[c] += (k ? (prev[c] + st) / 2 : st) * (s - prev_s);
                    prev[c] = st;
                    tr = exp(-tau[c]);
                }
                L[c] += h * tr * (sa[c] * le[c] + ss[c] * li[c]);
            }
            prev_s = s;
        }
        memcpy(f->L, L, sizeof L);
        sum += (double)L[0];
    }
    return sum;
}

typedef struct bench_busy_ctx {
    long iters;
} bench_busy_ctx;

static double bench_busy_batch(void *ctx, long reps)
{
    const bench_busy_ctx *b = (const bench_busy_ctx *)ctx;
    double sum = 0;
    long r;
    for (r = 0; r < reps; ++r) sum += bench_busy(b->iters, 0.25 + (double)(r & 7));
    return sum;
}

/* bench_busy iterations that take about BENCH_BUSY_NS here. */
static long bench_calibrate_busy(const bench_state *st)
{
    bench_busy_ctx b;
    double ns;
    b.iters = 4096;
    ns = bench_time_stat(st, bench_busy_batch, &b, BENCH_OVERHEAD_BATCHES, 1) / (double)b.iters;
    return ns > 0 ? (long)ceil(BENCH_BUSY_NS / ns) : b.iters;
}

/* Solves an adaptive method at each rtol of a wide list and returns the one
   whose evaluation count is nearest (in ratio) to target. */
static double bench_tol_for_evals(const bench_state *st, const bench_scene *sc,
                                  const bench_method *me, const hrm_medium *m, bench_calls *calls,
                                  long target)
{
    double best = 1e-6, dist = HUGE_VAL, tol;
    for (tol = 1e-2; tol > 1e-12; tol /= 10) {
        bench_case bc;
        hrm_result res;
        double d;
        bench_case_init(&bc, st, sc, me, BENCH_WARP_NONE, tol, m, calls, "");
        if (hrm_solve(m, (hrm_real)sc->t0, (hrm_real)sc->t1, &bc.options, &res) < 0) continue;
        d = fabs(log((double)(res.stats.evals > 0 ? res.stats.evals : 1) / (double)target));
        if (d < dist) {
            dist = d;
            best = tol;
        }
    }
    return best;
}

void bench_measure_overhead(bench_state *st)
{
    static const char *const scenes[2] = {"directional", "hetero"};
    const long target = BENCH_OVERHEAD_EVALS;
    int s, mi, cost;
    if (!st->cfg.timed) return;
    st->busy_iters = bench_calibrate_busy(st);
    for (s = 0; s < 2; ++s) {
        bench_overhead *ov = &st->overhead[s];
        int si = bench_find_scene(scenes[s]);
        const bench_scene *sc;
        hrm_medium m[2];
        bench_calls calls[2];
        ov->scene = -1;
        ov->n = 0;
        if (si < 0 || !bench_scene_selected(&st->cfg, si)) continue;
        sc = &bench_scenes[si];
        ov->scene = si;
        /* the scene as written: directional as constants, hetero as callbacks */
        for (cost = 0; cost < 2; ++cost) {
            bench_floor fl;
            if (!bench_medium_build(sc, BENCH_MEDIUM_CONST, &m[cost], &calls[cost]))
                bench_medium_build(sc, BENCH_MEDIUM_SIGMA, &m[cost], &calls[cost]);
            if (cost) bench_medium_busy_li(&m[cost], &calls[cost], st->busy_iters);
            fl.sc = sc;
            fl.m = &m[cost];
            fl.N = (int)target;
            fl.march = 0;
            ov->callbacks_ns[cost] =
                bench_time_stat(st, bench_floor_batch, &fl, BENCH_OVERHEAD_BATCHES, 1) / target;
            fl.march = 1;
            ov->loop_ns[cost] =
                bench_time_stat(st, bench_floor_batch, &fl, BENCH_OVERHEAD_BATCHES, 1) / target;
            if (!cost) ov->loop_error = bench_rel_error(fl.L, bench_reference_get(st, si)->L);
        }
        for (mi = 0; mi < st->nmethods; ++mi) {
            const bench_method *me = &st->methods[mi];
            bench_overhead_row *r = &ov->rows[ov->n];
            hrm_result res;
            if (!bench_method_in_sections(st, mi)) continue;
            bench_progress_show(st, "library overhead");
            r->method = mi;
            if (bench_is_swept_over_n(me))
                r->param = me->id == HRM_SIMPSON || me->id == HRM_RK4 ? target / 2 : target;
            else
                r->param = bench_tol_for_evals(st, sc, me, &m[0], &calls[0], target);
            for (cost = 0; cost < 2; ++cost) {
                bench_case bc;
                bench_case_init(&bc, st, sc, me, BENCH_WARP_NONE, r->param, &m[cost],
                                &calls[cost], "");
                bc.seeds = 1;
                if (hrm_solve(&m[cost], (hrm_real)sc->t0, (hrm_real)sc->t1, &bc.options, &res) <
                        0 ||
                    res.stats.evals <= 0)
                    break;
                r->evals = res.stats.evals;
                r->ns_per_ray[cost] =
                    bench_time_stat(st, bench_solve_batch, &bc, BENCH_OVERHEAD_BATCHES, 1);
            }
            if (cost == 2) ov->n++;
        }
    }
}
