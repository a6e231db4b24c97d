/* bench/bench.c - single-ray accuracy and speed benchmark of hrm.h.

   For every scene (scenes.h), method and warp it solves one ray with
   hrm_solve and compares L with an independent reference (reference.h):
   the error is Munoz 2014's |L - Lref| / max(|L|, |Lref|), worst channel.
   Fixed-step methods are swept over the step count N, adaptive methods over
   the relative tolerance rtol; each runs with no warp and with the scene's
   natural warp (importance sampling as a change of variable). Every row is
   also timed (median over repeated solves).

   Output: tables on stdout (or CSV rows with --csv), a progress line on
   stderr, and files in the output directory (bench/out by default):
   bench.csv, one SVG per scene, fig4.svg (Munoz 2014 Fig. 4's scenes and
   columns) and summary.md. bench/README.md says how to read them.
   Run with --help for the options and the exit status.

   The program is four tables and a loop: scenes (scenes.h), methods
   (built from hrm_method_name, so a new method appears by itself), warps,
   and the parameters (N or rtol), walked by bench_run_scene(); the
   summaries are computed from the rows afterwards. */

#define _POSIX_C_SOURCE 200809L /* clock_gettime, mkdir, isatty */
#define HRM_IMPLEMENTATION
#include "hrm.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "reference.h"
#include "scenes.h"
#include "svg.h"

#define BENCH_SEEDS 32            /* Monte Carlo: RMS error over seeds 1..32 */
#define BENCH_SEEDS_QUICK 8
#define BENCH_MAX_EVALS 100000L   /* adaptive runs: budget, so none runs away */
#define BENCH_FIT_FLOOR 1e-13     /* errors below this are round-off: not fitted */
#define BENCH_PLOT_FLOOR 1e-16    /* errors below this are drawn at it */
#define BENCH_REF_CHECK 1e-13L    /* a reference must be at least this accurate */
#define BENCH_MAX_PARAMS 16
#define BENCH_MAX_METHODS (HRM_METHOD_COUNT + 1)

enum { /* exit status */
    BENCH_EXIT_OK = 0,
    BENCH_EXIT_SOLVE_ERROR = 1,
    BENCH_EXIT_USAGE = 2,
    BENCH_EXIT_OUTPUT = 3,
    BENCH_EXIT_CHECK = 4
};

static const double bench_steps_full[] = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024};
static const double bench_steps_quick[] = {1, 2, 4, 8, 16, 32, 64};
static const double bench_tols_full[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
static const double bench_tols_quick[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
static const double bench_targets[] = {1e-2, 1e-4, 1e-6}; /* the summary's error targets */
#define BENCH_TARGETS 3

#define COUNT_OF(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* ------------------------------------------------------------------------ */
/* Methods: every hrm method, Gauss-Kronrod in both modes                   */
/* ------------------------------------------------------------------------ */

typedef enum bench_kind {
    BENCH_FIXED,    /* deterministic, swept over N */
    BENCH_RANDOM,   /* swept over N, error as RMS over seeds */
    BENCH_ADAPTIVE, /* swept over rtol */
    BENCH_OTHER     /* no sweep written for it yet: listed, not run */
} bench_kind;

typedef struct bench_method {
    hrm_method id;
    hrm_gk_mode gk_mode;
    char name[40];
    bench_kind kind;
    double order; /* nominal order for smooth integrands (hrm.h manual); 0: none */
    const char *color;
    int marker;
} bench_method;

static bench_method bench_methods[BENCH_MAX_METHODS];
static int bench_method_count;

static const char *const bench_colors[] = {
    "#1f77b4", "#ff7f0e", "#7f7f7f", "#8c564b", "#d62728", "#9467bd", "#2ca02c",
    "#17becf", "#bcbd22", "#e377c2", "#000000", "#8c6d31", "#393b79", "#ad494a", "#637939"};

static void bench_method_add(hrm_method id, hrm_gk_mode mode, const char *suffix)
{
    bench_method *b = &bench_methods[bench_method_count];
    b->id = id;
    b->gk_mode = mode;
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
    case HRM_NESTED_SIMPSON: case HRM_GAUSS_KRONROD: case HRM_BOGACKI_SHAMPINE:
    case HRM_DORMAND_PRINCE: case HRM_FEHLBERG: case HRM_CASH_KARP: case HRM_VERNER:
        break;
    default: b->kind = BENCH_OTHER; break;
    }
    b->color = bench_colors[bench_method_count % COUNT_OF(bench_colors)];
    b->marker = bench_method_count % 5;
    bench_method_count++;
}

static void bench_methods_init(void)
{
    int m;
    for (m = 1; m < (int)HRM_METHOD_COUNT; ++m) {
        if (m == (int)HRM_GAUSS_KRONROD) {
            bench_method_add(HRM_GAUSS_KRONROD, HRM_GK_GLOBAL, "-global");
            bench_method_add(HRM_GAUSS_KRONROD, HRM_GK_LOCAL, "-local");
        } else {
            bench_method_add((hrm_method)m, HRM_GK_DEFAULT, "");
        }
    }
}

static int bench_is_swept_over_n(const bench_method *me)
{
    return me->kind == BENCH_FIXED || me->kind == BENCH_RANDOM;
}

static const char *bench_kind_name(bench_kind k)
{
    return k == BENCH_FIXED      ? "fixed-step, swept over N"
           : k == BENCH_RANDOM   ? "fixed-step, random (error: RMS over seeds), swept over N"
           : k == BENCH_ADAPTIVE ? "adaptive, swept over rtol"
                                 : "no sweep in the bench yet: listed, not run";
}

/* ------------------------------------------------------------------------ */
/* Warps                                                                    */
/* ------------------------------------------------------------------------ */

static const char *const bench_warp_names[BENCH_WARP_COUNT] = {"none", "distance", "equiangular"};

/* Sets options->warp; returns 0 if the warp does not apply to the scene
   (equiangular without a point light). The equiangular warp comes from
   hrm_equiangular_warp for the ray x(s) = (s, 0, 0). */
static int bench_warp_apply(const bench_scene *sc, bench_warp_id w, hrm_options *o)
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
        o->warp.sigma_ref = 0; /* mean sigma_t at t0 (Munoz 2014 s.5) */
        return 1;
    case BENCH_WARP_EQUIANGULAR:
        if (!sc->light || !sc->light(sc->params, pos)) return 0;
        for (i = 0; i < 3; ++i) light[i] = (hrm_real)pos[i];
        return hrm_equiangular_warp(origin, dir, light, &o->warp) == HRM_OK;
    default:
        return 0;
    }
}

/* ------------------------------------------------------------------------ */
/* References                                                               */
/* ------------------------------------------------------------------------ */

typedef struct bench_reference {
    long double L[HRM_CHANNELS];
    long double accuracy; /* estimated relative accuracy, worst channel */
    long double splits[REF_MAX_POINTS];
    int nsplits;          /* interior split points used */
    long double panel;
} bench_reference;

static void bench_reference_compute(const bench_scene *sc, const ref_rule *rule,
                                    bench_reference *ref)
{
    long double pts[REF_MAX_POINTS], cut[REF_MAX_POINTS], coarse[HRM_CHANNELS],
        fine[HRM_CHANNELS];
    int n = 0, k = 0, i, j;

    ref->panel = sc->ref_panel > 0 ? sc->ref_panel : REF_PANEL;
    if (sc->split_points) k = sc->split_points(sc->params, cut, REF_MAX_POINTS - 2);
    pts[n++] = LD(sc->t0);
    ref->nsplits = 0;
    for (i = 0; i < k; ++i) {
        if (!(cut[i] > LD(sc->t0) && cut[i] < LD(sc->t1))) continue;
        for (j = n; j > 1 && pts[j - 1] > cut[i]; --j) pts[j] = pts[j - 1];
        pts[j] = cut[i];
        ++n;
    }
    for (i = 1; i < n; ++i) ref->splits[ref->nsplits++] = pts[i];
    pts[n++] = LD(sc->t1);

    ref_integrate(rule, sc->integrand, sc->params, pts, n, ref->panel, coarse);
    ref_integrate(rule, sc->integrand, sc->params, pts, n, ref->panel / 2, fine);
    if (sc->closed_form) {
        sc->closed_form(sc->params, LD(sc->t0), LD(sc->t1), ref->L);
        ref->accuracy = ref_rel_diff(fine, ref->L); /* checks the quadrature */
    } else {
        memcpy(ref->L, fine, sizeof fine);
        ref->accuracy = ref_rel_diff(coarse, fine);
    }
}

static void bench_reference_print(FILE *out, const bench_scene *sc, const bench_reference *ref)
{
    int i;
    fprintf(out, "  reference L = (%.19Lg, %.19Lg, %.19Lg)\n", ref->L[0], ref->L[1], ref->L[2]);
    if (sc->closed_form) {
        fprintf(out, "    closed form in long double; an independent %d-point Gauss-Legendre "
                     "quadrature agrees to %.1Le\n",
                REF_GL_POINTS, ref->accuracy);
        return;
    }
    fprintf(out, "    %d-point Gauss-Legendre panels in long double", REF_GL_POINTS);
    if (ref->nsplits) {
        fprintf(out, ", split at s =");
        for (i = 0; i < ref->nsplits; ++i)
            fprintf(out, "%s %.19Lg", i ? "," : "", ref->splits[i]);
    }
    fprintf(out, "\n    estimated relative accuracy %.1Le (panels <= %Lg vs <= %Lg)\n",
            ref->accuracy, ref->panel, ref->panel / 2);
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

static int bench_timings = 5;            /* timed batches; the median is reported */
static double bench_batch_seconds = 1e-3; /* a timed batch lasts at least this long */
static volatile double bench_sink;        /* keeps timed work from being optimised away */

static double bench_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef void (*bench_batch_fn)(void *ctx, long reps);

/* Nanoseconds per repetition of fn over `batches` batches, each repeated
   until it lasts bench_batch_seconds: their median (use_min 0), or their
   minimum (use_min 1: interference from other processes only ever adds
   time, so the minimum is the steadier estimate of the work itself). */
static double bench_time_stat(bench_batch_fn fn, void *ctx, int batches, int use_min)
{
    double t[32], batch, start;
    long reps = 1;
    int i, n = batches < 32 ? batches : 32;
    for (;;) {
        start = bench_seconds();
        fn(ctx, reps);
        batch = bench_seconds() - start;
        if (batch >= bench_batch_seconds || reps >= (1L << 28)) break;
        /* Jump close to the target, at most x16 at a time. */
        if (batch > bench_batch_seconds / 16)
            reps = (long)ceil((double)reps * 1.1 * bench_batch_seconds / batch);
        else
            reps *= 16;
    }
    for (i = 0; i < n; ++i) {
        start = bench_seconds();
        fn(ctx, reps);
        t[i] = 1e9 * (bench_seconds() - start) / (double)reps;
    }
    qsort(t, (size_t)n, sizeof t[0], bench_cmp_double);
    return use_min ? t[0] : t[n / 2];
}

/* The median over bench_timings batches: ns_per_ray of every row. */
static double bench_time(bench_batch_fn fn, void *ctx)
{
    return bench_time_stat(fn, ctx, bench_timings, 0);
}

#define BENCH_OVERHEAD_BATCHES 15 /* the overhead table: minimum of these */

/* ------------------------------------------------------------------------ */
/* One measurement: a row                                                   */
/* ------------------------------------------------------------------------ */

typedef struct bench_row {
    int scene, method;
    bench_warp_id warp;
    double param;        /* N, or rtol */
    hrm_stats stats;     /* of one ray (the first seed) */
    double rel_error;    /* RMS over seeds for random methods */
    hrm_status status;   /* an error if any seed gave one, else the largest warning */
    double ns_per_ray;   /* NaN: not timed */
} bench_row;

typedef struct bench_case {
    const hrm_medium *medium;
    bench_calls *calls;
    double t0, t1;
    hrm_options options;
    int seeds;
} bench_case;

static void bench_solve_batch(void *ctx, long reps)
{
    const bench_case *bc = (const bench_case *)ctx;
    hrm_options opt = bc->options;
    hrm_result res;
    double sum = 0;
    long r;
    for (r = 0; r < reps; ++r) {
        opt.seed = (uint64_t)(r % bc->seeds) + 1;
        hrm_solve(bc->medium, (hrm_real)bc->t0, (hrm_real)bc->t1, &opt, &res);
        sum += (double)res.L[0];
    }
    bench_sink = sum;
}

static long bench_count_mismatches;

/* hrm's stats against the callbacks it made: every source evaluation calls
   Li where the scene has it (each such scene scatters everywhere) and Le
   where it has emission (absorbing everywhere); every medium evaluation
   calls sigma_a and sigma_s, where they exist. */
static void bench_check_counts(const bench_scene *sc, const bench_method *me, const bench_row *r,
                               const hrm_medium *m, const bench_calls *calls, const hrm_stats *st)
{
    int ok = 1;
    if (m->Li) ok &= calls->li == st->evals;
    if (m->Le) ok &= calls->le == st->evals;
    if (m->sigma_a) ok &= calls->sigma_a == st->medium_evals;
    if (m->sigma_s) ok &= calls->sigma_s == st->medium_evals;
    if (ok) return;
    if (++bench_count_mismatches <= 10)
        fprintf(stderr,
                "\nbench: count mismatch: %s %s warp %s param %g: stats evals=%ld "
                "medium_evals=%ld, callbacks Li=%ld Le=%ld sigma_a=%ld sigma_s=%ld\n",
                sc->name, me->name, bench_warp_names[r->warp], r->param, st->evals,
                st->medium_evals, calls->li, calls->le, calls->sigma_a, calls->sigma_s);
}

static void bench_run_case(const bench_scene *sc, const bench_reference *ref,
                           const bench_method *me, const bench_case *bc, int timed, bench_row *row)
{
    hrm_options opt = bc->options;
    hrm_result res;
    double sumsq = 0, err = 0;
    int i;

    row->status = HRM_OK;
    for (i = 0; i < bc->seeds; ++i) {
        hrm_status st;
        opt.seed = (uint64_t)i + 1;
        memset(bc->calls, 0, sizeof *bc->calls);
        bc->calls->params = sc->params;
        st = hrm_solve(bc->medium, (hrm_real)bc->t0, (hrm_real)bc->t1, &opt, &res);
        if (st >= 0) /* a failed solve stops mid-way: nothing to compare */
            bench_check_counts(sc, me, row, bc->medium, bc->calls, &res.stats);
        if (i == 0) row->stats = res.stats;
        if (st < 0 ? row->status >= 0 : row->status >= 0 && st > row->status) row->status = st;
        err = st < 0 ? (double)NAN : bench_rel_error(res.L, ref->L);
        sumsq += err * err;
    }
    row->rel_error = bc->seeds > 1 ? sqrt(sumsq / bc->seeds) : err;
    row->ns_per_ray = timed ? bench_time(bench_solve_batch, (void *)bc) : (double)NAN;
}

/* ------------------------------------------------------------------------ */
/* Rows and sweeps                                                          */
/* ------------------------------------------------------------------------ */

/* A sweep: the rows of one scene x method x warp, in sweep order (N
   increasing, or rtol decreasing). */
typedef struct bench_sweep {
    int scene, method;
    bench_warp_id warp;
    int first, count;    /* into bench_rows */
    /* fixed-step methods: the fitted convergence order */
    int points;          /* rows above the fit floor */
    double order;        /* -(least-squares slope of log error vs log evals) */
    double tail;         /* the same over the last BENCH_TAIL of those rows */
} bench_sweep;

static bench_row *bench_rows;
static int bench_nrows, bench_rows_cap;
static bench_sweep *bench_sweeps;
static int bench_nsweeps, bench_sweeps_cap;

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

static bench_row *bench_new_row(void)
{
    bench_rows = (bench_row *)bench_grow(bench_rows, &bench_rows_cap, bench_nrows + 1,
                                         sizeof *bench_rows);
    memset(&bench_rows[bench_nrows], 0, sizeof *bench_rows);
    return &bench_rows[bench_nrows++];
}

static bench_sweep *bench_new_sweep(void)
{
    bench_sweeps = (bench_sweep *)bench_grow(bench_sweeps, &bench_sweeps_cap, bench_nsweeps + 1,
                                             sizeof *bench_sweeps);
    memset(&bench_sweeps[bench_nsweeps], 0, sizeof *bench_sweeps);
    return &bench_sweeps[bench_nsweeps++];
}

static const bench_sweep *bench_find_sweep(int scene, int method, bench_warp_id warp)
{
    int i;
    for (i = 0; i < bench_nsweeps; ++i)
        if (bench_sweeps[i].scene == scene && bench_sweeps[i].method == method &&
            bench_sweeps[i].warp == warp)
            return &bench_sweeps[i];
    return NULL;
}

static int bench_finite(double x)
{
    return x - x == 0;
}

/* ------------------------------------------------------------------------ */
/* Convergence order                                                        */
/* ------------------------------------------------------------------------ */

#define BENCH_TAIL 4 /* the finest points, for the asymptotic order */

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

static void bench_fit_sweep(bench_sweep *sw)
{
    double x[BENCH_MAX_PARAMS], y[BENCH_MAX_PARAMS];
    int i, k = 0, t;
    for (i = 0; i < sw->count; ++i) {
        const bench_row *r = &bench_rows[sw->first + i];
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
/* Configuration                                                            */
/* ------------------------------------------------------------------------ */

typedef struct bench_config {
    int csv, quick, list, timed;
    int scene_on[BENCH_SCENE_COUNT], any_scene;
    int method_on[BENCH_MAX_METHODS], any_method;
    int warp_on[BENCH_WARP_COUNT], natural_on, any_warp;
    double steps[BENCH_MAX_PARAMS], tols[BENCH_MAX_PARAMS];
    int nsteps, ntols;      /* from --steps / --tol; 0: the defaults */
    int user_steps, user_tols;
    hrm_control control;
    const char *out_dir;
    int seeds;
} bench_config;

static const char *bench_control_name(hrm_control c)
{
    return c == HRM_CONTROL_MUNOZ ? "munoz" : c == HRM_CONTROL_GONTERMAN ? "gonterman" : "pi";
}

static int bench_scene_selected(const bench_config *cfg, int si)
{
    return !cfg->any_scene || cfg->scene_on[si];
}

static int bench_method_selected(const bench_config *cfg, int mi)
{
    const bench_method *me = &bench_methods[mi];
    if (me->kind == BENCH_OTHER) return 0;
    if (cfg->any_method && !cfg->method_on[mi]) return 0;
    /* --steps alone runs the fixed-step methods, --tol alone the adaptive ones */
    if (bench_is_swept_over_n(me)) return !cfg->user_tols || cfg->user_steps;
    return !cfg->user_steps || cfg->user_tols;
}

/* The warps a scene runs with: none and its natural warp, or those asked. */
static int bench_scene_warps(const bench_config *cfg, const bench_scene *sc,
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

static int bench_params_of(const bench_config *cfg, const bench_method *me, const double **p)
{
    if (bench_is_swept_over_n(me)) {
        *p = cfg->steps;
        return cfg->nsteps;
    }
    *p = cfg->tols;
    return cfg->ntols;
}

/* ------------------------------------------------------------------------ */
/* Progress (stderr)                                                        */
/* ------------------------------------------------------------------------ */

typedef struct bench_progress {
    long done, total;
    double start, shown; /* when the run started, when the line was last drawn */
    int tty;
} bench_progress;

static void bench_progress_show(bench_progress *pg, const char *scene, const char *method,
                                const char *warp)
{
    double pct = pg->total ? 100.0 * (double)pg->done / (double)pg->total : 100.0;
    double now = bench_seconds(), el = now - pg->start;
    if (pg->tty && now - pg->shown >= 0.1) { /* at most ten redraws a second */
        pg->shown = now;
        fprintf(stderr, "\r\033[K[%3.0f%%] %5.1f s  %-11s %-22s %-11s", pct, el, scene, method,
                warp);
        fflush(stderr);
    }
}

/* ------------------------------------------------------------------------ */
/* Per-scene tables (stdout)                                                */
/* ------------------------------------------------------------------------ */

static char bench_flag(hrm_status st)
{
    return st < 0 ? '!' : st > 0 ? '*' : ' ';
}

static void bench_table_header(const char *what, const double *params, int n, int tol)
{
    int k;
    printf("  %s\n  %-22s %-11s", what, "method", "warp");
    for (k = 0; k < n; ++k) {
        if (tol) printf(" %8.0e", params[k]);
        else printf(" %8.0f", params[k]);
    }
    printf("\n");
}

/* One matrix per kind of sweep: rows method x warp, columns the parameter;
   value 0: rel_error, 1: evals. */
static void bench_print_matrix(const bench_config *cfg, int si, int adaptive, int value)
{
    const double *params = adaptive ? cfg->tols : cfg->steps;
    int n = adaptive ? cfg->ntols : cfg->nsteps, i, k, any = 0;
    for (i = 0; i < bench_nsweeps; ++i) {
        const bench_sweep *sw = &bench_sweeps[i];
        const bench_method *me = &bench_methods[sw->method];
        if (sw->scene != si || (me->kind == BENCH_ADAPTIVE) != adaptive) continue;
        if (!any) {
            bench_table_header(adaptive ? (value ? "adaptive methods: evaluations by rtol"
                                                 : "adaptive methods: achieved rel_error by rtol "
                                                   "(Munoz 2014 Fig. 4, columns 4-5)")
                                        : "fixed-step methods: rel_error by N (monte-carlo: RMS "
                                          "over seeds)",
                               params, n, adaptive);
            any = 1;
        }
        printf("  %-22s %-11s", me->name, bench_warp_names[sw->warp]);
        for (k = 0; k < sw->count; ++k) {
            const bench_row *r = &bench_rows[sw->first + k];
            if (value) printf(" %7ld%c", r->stats.evals, bench_flag(r->status));
            else if (r->status < 0 || !bench_finite(r->rel_error)) printf(" %8s", "error!");
            else printf(" %7.1e%c", r->rel_error, bench_flag(r->status));
        }
        printf("\n");
    }
}

static void bench_print_scene_tables(const bench_config *cfg, int si)
{
    bench_print_matrix(cfg, si, 0, 0);
    bench_print_matrix(cfg, si, 1, 0);
    bench_print_matrix(cfg, si, 1, 1);
    printf("  (* a warning status: the budget of %ld evaluations, h_min or storage ran out, "
           "best estimate shown; ! an error status)\n",
           BENCH_MAX_EVALS);
}

/* ------------------------------------------------------------------------ */
/* The run                                                                  */
/* ------------------------------------------------------------------------ */

typedef struct bench_totals {
    int errors;           /* rows in which a solve returned an error status */
    long solves;
    bench_reference refs[BENCH_SCENE_COUNT];
    int ref_bad;          /* references failing their self-check */
} bench_totals;

static void bench_case_init(bench_case *bc, const bench_config *cfg, const bench_scene *sc,
                            const bench_method *me, bench_warp_id warp, double param,
                            const hrm_medium *medium, bench_calls *calls)
{
    bc->medium = medium;
    bc->calls = calls;
    bc->t0 = sc->t0;
    bc->t1 = sc->t1;
    bc->options = hrm_default_options(me->id);
    bc->options.gk_mode = me->gk_mode;
    if (bench_is_swept_over_n(me)) {
        bc->options.steps = (int)param;
    } else {
        bc->options.rtol = (hrm_real)param;
        bc->options.max_evals = BENCH_MAX_EVALS;
        /* The Runge-Kutta pairs only: hrm also derives h_min's default from
           the control, which would change the quadrature methods. */
        if (me->id != HRM_NESTED_SIMPSON && me->id != HRM_GAUSS_KRONROD)
            bc->options.control = cfg->control;
    }
    bench_warp_apply(sc, warp, &bc->options);
    bc->seeds = me->kind == BENCH_RANDOM ? cfg->seeds : 1;
}

static void bench_print_csv_row(FILE *f, const bench_row *r)
{
    fprintf(f, "%s,%s,%s,%g,%ld,%ld,%ld,%ld,%.6e,%d,%.1f\n", bench_scenes[r->scene].name,
            bench_methods[r->method].name, bench_warp_names[r->warp], r->param, r->stats.evals,
            r->stats.medium_evals, r->stats.steps, r->stats.rejected, r->rel_error, (int)r->status,
            r->ns_per_ray);
}

#define BENCH_CSV_HEADER \
    "scene,method,warp,param,evals,medium_evals,steps,rejected,rel_error,status,ns_per_ray"

static void bench_run_scene(const bench_config *cfg, int si, const ref_rule *rule,
                            bench_totals *tot, bench_progress *pg)
{
    const bench_scene *sc = &bench_scenes[si];
    bench_reference *ref = &tot->refs[si];
    bench_calls calls;
    hrm_medium medium;
    bench_warp_id warps[BENCH_WARP_COUNT];
    int nw = bench_scene_warps(cfg, sc, warps), mi, wi, k;

    bench_reference_compute(sc, rule, ref);
    if (!(ref->accuracy <= BENCH_REF_CHECK)) {
        tot->ref_bad++;
        fprintf(stderr, "\nbench: scene %s: reference accuracy %.1Le worse than %.0Le\n", sc->name,
                ref->accuracy, BENCH_REF_CHECK);
    }
    memset(&calls, 0, sizeof calls);
    calls.params = sc->params;
    memset(&medium, 0, sizeof medium);
    sc->build(sc->params, &medium);
    medium.user = &calls;

    if (!cfg->csv) {
        printf("\n== scene %s: %s\n", sc->name, sc->description);
        printf("  ray t0 = %g, t1 = %g; %s\n", sc->t0, sc->t1,
               sc->smooth ? "smooth integrand" : "integrand with jumps (shadow edges)");
        sc->print_params(stdout, sc->params);
        bench_reference_print(stdout, sc, ref);
        printf("  warps:");
        for (wi = 0; wi < nw; ++wi) {
            hrm_options o;
            bench_warp_apply(sc, warps[wi], &o);
            printf("%s %s", wi ? "," : "", bench_warp_names[warps[wi]]);
            if (warps[wi] == BENCH_WARP_DISTANCE) printf(" (sigma_ref: mean sigma_t at t0)");
            if (warps[wi] == BENCH_WARP_EQUIANGULAR)
                printf(" (delta = %g, D = %g, from hrm_equiangular_warp)", (double)o.warp.delta,
                       (double)o.warp.D);
        }
        printf("\n");
    }
    for (mi = 0; mi < bench_method_count; ++mi) {
        const bench_method *me = &bench_methods[mi];
        const double *params;
        int np;
        if (!bench_method_selected(cfg, mi)) continue;
        np = bench_params_of(cfg, me, &params);
        for (wi = 0; wi < nw; ++wi) {
            bench_sweep *sw = bench_new_sweep();
            sw->scene = si;
            sw->method = mi;
            sw->warp = warps[wi];
            sw->first = bench_nrows;
            for (k = 0; k < np; ++k) {
                bench_case bc;
                bench_row *r;
                bench_progress_show(pg, sc->name, me->name, bench_warp_names[warps[wi]]);
                bench_case_init(&bc, cfg, sc, me, warps[wi], params[k], &medium, &calls);
                r = bench_new_row();
                r->scene = si;
                r->method = mi;
                r->warp = warps[wi];
                r->param = params[k];
                bench_run_case(sc, ref, me, &bc, cfg->timed, r);
                tot->solves += bc.seeds;
                if (r->status < 0) tot->errors++;
                if (cfg->csv) bench_print_csv_row(stdout, r);
                pg->done++;
            }
            sw = &bench_sweeps[bench_nsweeps - 1]; /* bench_new_row never moves sweeps */
            sw->count = bench_nrows - sw->first;
            if (bench_is_swept_over_n(me)) bench_fit_sweep(sw);
        }
    }
    if (!cfg->csv) {
        bench_print_scene_tables(cfg, si);
        fflush(stdout);
    }
}

/* ------------------------------------------------------------------------ */
/* Summaries                                                                */
/* ------------------------------------------------------------------------ */

/* A line of output that goes to stdout and, when md is set, to the
   markdown summary too. */
typedef struct bench_out {
    FILE *md;
    int quiet; /* --csv: no tables on stdout */
} bench_out;

static void bench_both(const bench_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void bench_both(const bench_out *o, const char *fmt, ...)
{
    va_list ap;
    if (!o->quiet) {
        va_start(ap, fmt);
        vprintf(fmt, ap);
        va_end(ap);
    }
    if (o->md) {
        va_start(ap, fmt);
        vfprintf(o->md, fmt, ap);
        va_end(ap);
    }
}

/* A section title: "== title" on the terminal, "## title" in markdown. */
static void bench_section(const bench_out *o, const char *title)
{
    if (!o->quiet) printf("\n== %s\n", title);
    if (o->md) fprintf(o->md, "\n## %s\n\n", title);
}

static void bench_fmt_order(char *buf, size_t n, double v)
{
    if (bench_finite(v)) snprintf(buf, n, "%.2f", v);
    else snprintf(buf, n, "n/a");
}


/* A small table printed aligned on stdout and as a markdown table in the
   summary. Row 0 is the header. */
#define BENCH_TCOLS 12
#define BENCH_TROWS 40
#define BENCH_TCELL 64

typedef struct bench_table {
    int ncols, nrows;
    char cell[BENCH_TROWS][BENCH_TCOLS][BENCH_TCELL];
} bench_table;

static bench_table bench_tab; /* the one table being built */

static void bench_table_start(int ncols)
{
    memset(&bench_tab, 0, sizeof bench_tab);
    bench_tab.ncols = ncols;
}

/* Appends a row; the cells are printf formats' results given one by one
   with bench_table_cell. */
static void bench_table_row(void)
{
    if (bench_tab.nrows < BENCH_TROWS) bench_tab.nrows++;
}

static void bench_table_cell(int col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void bench_table_cell(int col, const char *fmt, ...)
{
    va_list ap;
    if (bench_tab.nrows == 0 || col >= BENCH_TCOLS) return;
    va_start(ap, fmt);
    vsnprintf(bench_tab.cell[bench_tab.nrows - 1][col], BENCH_TCELL, fmt, ap);
    va_end(ap);
}

static void bench_table_emit(const bench_out *o)
{
    int w[BENCH_TCOLS], r, c;
    for (c = 0; c < bench_tab.ncols; ++c) {
        w[c] = 0;
        for (r = 0; r < bench_tab.nrows; ++r) {
            int l = (int)strlen(bench_tab.cell[r][c]);
            if (l > w[c]) w[c] = l;
        }
    }
    if (!o->quiet)
        for (r = 0; r < bench_tab.nrows; ++r) {
            printf(" ");
            for (c = 0; c < bench_tab.ncols; ++c)
                printf(" %-*s", c + 1 < bench_tab.ncols ? w[c] + 1 : 0, bench_tab.cell[r][c]);
            printf("\n");
        }
    if (o->md) {
        for (r = 0; r < bench_tab.nrows; ++r) {
            fprintf(o->md, "|");
            for (c = 0; c < bench_tab.ncols; ++c) fprintf(o->md, " %s |", bench_tab.cell[r][c]);
            fprintf(o->md, "\n");
            if (r == 0) {
                fprintf(o->md, "|");
                for (c = 0; c < bench_tab.ncols; ++c) fprintf(o->md, "---|");
                fprintf(o->md, "\n");
            }
        }
        fprintf(o->md, "\n");
    }
}

/* --- fitted orders ------------------------------------------------------ */

static void bench_order_cell(int col, const bench_sweep *sw)
{
    char a[16], b[16];
    if (!sw) {
        bench_table_cell(col, "-");
        return;
    }
    bench_fmt_order(a, sizeof a, sw->order);
    bench_fmt_order(b, sizeof b, sw->tail);
    bench_table_cell(col, "%s (%s)", a, b);
}

static void bench_print_orders(const bench_config *cfg)
{
    int si, mi, w, col;
    bench_out o = {NULL, 0};
    printf("\n== Fitted convergence order of the fixed-step methods: -(least-squares slope of\n"
           "log rel_error vs log evals) over the N whose error is above %g; in parentheses\n"
           "over the finest %d of them only (the asymptotic order). Nominal:",
           BENCH_FIT_FLOOR, BENCH_TAIL);
    for (mi = 0; mi < bench_method_count; ++mi)
        if (bench_is_swept_over_n(&bench_methods[mi]))
            printf(" %s %g%s", bench_methods[mi].name, bench_methods[mi].order,
                   mi + 1 < bench_method_count && bench_is_swept_over_n(&bench_methods[mi + 1])
                       ? ","
                       : "");
    printf(".\n");
    for (w = 0; w < 2; ++w) {
        int nc = 2;
        bench_table_start(BENCH_TCOLS);
        bench_table_row();
        bench_table_cell(0, "scene");
        bench_table_cell(1, "warp");
        for (mi = 0; mi < bench_method_count; ++mi)
            if (bench_is_swept_over_n(&bench_methods[mi]) && bench_method_selected(cfg, mi) &&
                nc < BENCH_TCOLS)
                bench_table_cell(nc++, "%s", bench_methods[mi].name);
        bench_tab.ncols = nc;
        for (si = 0; si < BENCH_SCENE_COUNT; ++si) {
            bench_warp_id wid = w ? bench_scenes[si].natural_warp : BENCH_WARP_NONE;
            int found = 0;
            for (mi = 0; mi < bench_method_count; ++mi)
                found |= bench_is_swept_over_n(&bench_methods[mi]) &&
                         bench_find_sweep(si, mi, wid) != NULL;
            if (!found) continue;
            bench_table_row();
            bench_table_cell(0, "%s", bench_scenes[si].name);
            bench_table_cell(1, "%s", bench_warp_names[wid]);
            col = 2;
            for (mi = 0; mi < bench_method_count; ++mi)
                if (bench_is_swept_over_n(&bench_methods[mi]) && bench_method_selected(cfg, mi) &&
                    col < BENCH_TCOLS)
                    bench_order_cell(col++, bench_find_sweep(si, mi, wid));
        }
        if (bench_tab.nrows > 1) {
            printf("%s\n", w ? "natural warp:" : "no warp:");
            bench_table_emit(&o);
        }
    }
    printf("(a sharp shadow, as in occluder, drags every fixed-step method to first order)\n");
}

/* --- tolerance proportionality (adaptive methods) ----------------------- */

static double bench_median(double *v, int n)
{
    if (n <= 0) return (double)NAN;
    qsort(v, (size_t)n, sizeof v[0], bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct bench_prop {
    int rows;            /* rows that returned HRM_OK (or only clipped rtol) */
    int above1, above10, below01;
    double lo, med, hi;  /* achieved / rtol over those rows */
    int warned;          /* rows that ended with a warning: the method says it missed */
    double warned_hi;    /* their largest achieved / rtol */
    int errors;          /* rows with an error status */
} bench_prop;

static int bench_status_ok(hrm_status st)
{
    return st == HRM_OK || st == HRM_WARN_RTOL_CLIPPED;
}

/* achieved / rtol over the smooth scenes' rows of one adaptive method;
   group 0: no warp, 1: the scenes' natural warps; scene >= 0: that scene
   alone (smooth or not). */
static void bench_prop_collect(int mi, int group, int scene, bench_prop *p)
{
    static double v[4096];
    int i, k, n = 0;
    memset(p, 0, sizeof *p);
    p->lo = p->med = p->hi = p->warned_hi = (double)NAN;
    for (i = 0; i < bench_nsweeps; ++i) {
        const bench_sweep *sw = &bench_sweeps[i];
        const bench_scene *sc = &bench_scenes[sw->scene];
        if (sw->method != mi || (sw->warp != BENCH_WARP_NONE) != group) continue;
        if (scene >= 0 ? sw->scene != scene : !sc->smooth) continue;
        for (k = 0; k < sw->count; ++k) {
            const bench_row *r = &bench_rows[sw->first + k];
            double q;
            if (r->status < 0 || !bench_finite(r->rel_error)) {
                p->errors++;
                continue;
            }
            q = r->rel_error / r->param;
            if (!bench_status_ok(r->status)) {
                if (!p->warned || q > p->warned_hi) p->warned_hi = q;
                p->warned++;
                continue;
            }
            p->rows++;
            p->above1 += q > 1;
            p->above10 += q > 10;
            p->below01 += q < 0.1;
            if (n < COUNT_OF(v)) v[n++] = q;
        }
    }
    if (n) {
        p->med = bench_median(v, n); /* sorts v */
        p->lo = v[0];
        p->hi = v[n - 1];
    }
}

static void bench_print_proportionality(const bench_config *cfg, const bench_out *o)
{
    int mi, g, si, any = 0, nc;
    for (mi = 0; mi < bench_method_count; ++mi)
        any |= bench_methods[mi].kind == BENCH_ADAPTIVE && bench_method_selected(cfg, mi);
    if (!any || !cfg->ntols) return;
    bench_section(o, "Tolerance proportionality of the adaptive methods");
    bench_both(o, "achieved rel_error / rtol on the smooth scenes (all but occluder), rtol = "
                  "%.0e..%.0e, control %s, budget %ld evaluations.\n"
                  "Goal: at most 10 on every row (never above rtol by more than a factor of 10) "
                  "and at least 0.1 (no effort wasted).\n"
                  "rows: runs that returned HRM_OK, over which min/median/max are taken and "
                  ">1, >10, <0.1 counted; warned: runs that returned a warning (budget, h_min, "
                  "storage: the method reports it missed rtol), with their largest ratio.\n\n",
               cfg->tols[0], cfg->tols[cfg->ntols - 1], bench_control_name(cfg->control),
               BENCH_MAX_EVALS);
    bench_table_start(11);
    bench_table_row();
    bench_table_cell(0, "method");
    bench_table_cell(1, "warp");
    bench_table_cell(2, "rows");
    bench_table_cell(3, "min");
    bench_table_cell(4, "median");
    bench_table_cell(5, "max");
    bench_table_cell(6, ">1");
    bench_table_cell(7, ">10");
    bench_table_cell(8, "<0.1");
    bench_table_cell(9, "warned");
    bench_table_cell(10, "worst warned");
    for (mi = 0; mi < bench_method_count; ++mi) {
        if (bench_methods[mi].kind != BENCH_ADAPTIVE || !bench_method_selected(cfg, mi)) continue;
        for (g = 0; g < 2; ++g) {
            bench_prop p;
            bench_prop_collect(mi, g, -1, &p);
            if (!p.rows && !p.warned && !p.errors) continue;
            bench_table_row();
            bench_table_cell(0, "%s", bench_methods[mi].name);
            bench_table_cell(1, "%s", g ? "natural" : "none");
            bench_table_cell(2, "%d", p.rows);
            bench_table_cell(3, "%.2g", p.lo);
            bench_table_cell(4, "%.2g", p.med);
            bench_table_cell(5, "%.2g", p.hi);
            bench_table_cell(6, "%d", p.above1);
            bench_table_cell(7, "%d", p.above10);
            bench_table_cell(8, "%d", p.below01);
            bench_table_cell(9, "%d", p.warned);
            if (p.warned) bench_table_cell(10, "%.2g", p.warned_hi);
            else bench_table_cell(10, "-");
        }
    }
    bench_table_emit(o);

    for (g = 0; g < 2; ++g) {
        bench_both(o, "Largest achieved/rtol per scene over the runs that returned HRM_OK, %s "
                      "(in brackets: the largest over runs that returned a warning, where "
                      "it is larger):\n\n",
                   g ? "natural warp" : "no warp");
        bench_table_start(BENCH_TCOLS);
        bench_table_row();
        bench_table_cell(0, "method");
        nc = 1;
        for (si = 0; si < BENCH_SCENE_COUNT && nc < BENCH_TCOLS; ++si)
            if (bench_scene_selected(cfg, si))
                bench_table_cell(nc++, "%s%s", bench_scenes[si].name,
                                 bench_scenes[si].smooth ? "" : " (jumps)");
        bench_tab.ncols = nc;
        for (mi = 0; mi < bench_method_count; ++mi) {
            int col = 1;
            if (bench_methods[mi].kind != BENCH_ADAPTIVE || !bench_method_selected(cfg, mi))
                continue;
            bench_table_row();
            bench_table_cell(0, "%s", bench_methods[mi].name);
            for (si = 0; si < BENCH_SCENE_COUNT && col < BENCH_TCOLS; ++si) {
                bench_prop p;
                char a[24] = "-", b[32] = "";
                if (!bench_scene_selected(cfg, si)) continue;
                bench_prop_collect(mi, g, si, &p);
                if (p.rows) snprintf(a, sizeof a, "%.2g", p.hi);
                if (p.warned && (!p.rows || p.warned_hi > p.hi))
                    snprintf(b, sizeof b, " [%.2g]", p.warned_hi);
                if (p.errors) snprintf(b + strlen(b), sizeof b - strlen(b), " error!");
                bench_table_cell(col++, "%s%s", a, b);
            }
        }
        bench_table_emit(o);
    }
}

/* --- equiangular gain on the point scene -------------------------------- */

static void bench_print_equiangular(const bench_config *cfg, const bench_totals *tot,
                                    const bench_out *o)
{
    static const int Ns[] = {8, 32, 128};
    int si, mi, k, w;
    for (si = 0; si < BENCH_SCENE_COUNT && strcmp(bench_scenes[si].name, "point"); ++si) {}
    if (si == BENCH_SCENE_COUNT || !bench_scene_selected(cfg, si)) return;
    bench_section(o, "Equiangular sampling on the point scene");
    bench_both(o, "error(no warp) / error(equiangular) at equal N (above 1: equiangular helps); "
                  "monte-carlo: RMS over seeds 1..%d.\n\n",
               cfg->seeds);
    bench_table_start(1 + COUNT_OF(Ns));
    bench_table_row();
    bench_table_cell(0, "method");
    for (k = 0; k < COUNT_OF(Ns); ++k) bench_table_cell(1 + k, "N = %d", Ns[k]);
    /* rectangle and monte-carlo first: the pair the paper reports on */
    for (w = 0; w < 2; ++w)
        for (mi = 0; mi < bench_method_count; ++mi) {
            const bench_method *me = &bench_methods[mi];
            const bench_scene *sc = &bench_scenes[si];
            int first = me->id == HRM_RECTANGLE || me->id == HRM_MONTE_CARLO;
            bench_calls calls;
            hrm_medium medium;
            if (!bench_is_swept_over_n(me) || first != !w) continue;
            if (cfg->any_method && !cfg->method_on[mi]) continue;
            memset(&medium, 0, sizeof medium);
            sc->build(sc->params, &medium);
            medium.user = &calls;
            bench_table_row();
            bench_table_cell(0, "%s", me->name);
            for (k = 0; k < COUNT_OF(Ns); ++k) {
                double e[2];
                int wi;
                for (wi = 0; wi < 2; ++wi) {
                    bench_case bc;
                    bench_row r;
                    bench_case_init(&bc, cfg, sc, me,
                                    wi ? BENCH_WARP_EQUIANGULAR : BENCH_WARP_NONE, Ns[k], &medium,
                                    &calls);
                    memset(&r, 0, sizeof r);
                    r.warp = wi ? BENCH_WARP_EQUIANGULAR : BENCH_WARP_NONE;
                    r.param = Ns[k];
                    bench_run_case(sc, &tot->refs[si], me, &bc, 0, &r);
                    e[wi] = r.status < 0 ? (double)NAN : r.rel_error;
                }
                if (bench_finite(e[0]) && bench_finite(e[1]) && e[1] > 0)
                    bench_table_cell(1 + k, "%.3g", e[0] / e[1]);
                else
                    bench_table_cell(1 + k, "n/a");
            }
        }
    bench_table_emit(o);
}

/* --- library overhead against a hand-written ray march ------------------ */

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
   by the trapezoid rule on sigma_t (callbacks), as hrm's rectangle rule. */
static void bench_floor_batch(void *ctx, long reps)
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
    bench_sink = sum;
}

/* Solves an adaptive method at each rtol of a wide list and returns the one
   whose evaluation count is nearest (in ratio) to target. */
static double bench_tol_for_evals(const bench_config *cfg, const bench_scene *sc,
                                  const bench_method *me, const hrm_medium *m, bench_calls *calls,
                                  long target)
{
    double best = 1e-6, dist = HUGE_VAL, tol;
    for (tol = 1e-2; tol > 1e-12; tol /= 10) {
        bench_case bc;
        hrm_result res;
        double d;
        bench_case_init(&bc, cfg, sc, me, BENCH_WARP_NONE, tol, m, calls);
        if (hrm_solve(m, (hrm_real)sc->t0, (hrm_real)sc->t1, &bc.options, &res) < 0) continue;
        d = fabs(log((double)(res.stats.evals > 0 ? res.stats.evals : 1) / (double)target));
        if (d < dist) {
            dist = d;
            best = tol;
        }
    }
    return best;
}

static void bench_print_overhead(const bench_config *cfg, const bench_totals *tot,
                                 const bench_out *o)
{
    static const char *const scenes[] = {"directional", "hetero"};
    const long target = 1024;
    char title[96];
    int s, si, mi;
    if (!cfg->timed) return;
    for (s = 0; s < COUNT_OF(scenes); ++s) {
        const bench_scene *sc;
        bench_calls calls;
        hrm_medium m;
        bench_floor fl;
        double cb, floor_ns, fl_err;
        for (si = 0; si < BENCH_SCENE_COUNT && strcmp(bench_scenes[si].name, scenes[s]); ++si) {}
        if (si == BENCH_SCENE_COUNT || !bench_scene_selected(cfg, si)) continue;
        sc = &bench_scenes[si];
        memset(&calls, 0, sizeof calls);
        calls.params = sc->params;
        memset(&m, 0, sizeof m);
        sc->build(sc->params, &m);
        m.user = &calls;
        fl.sc = sc;
        fl.m = &m;
        fl.N = (int)target;
        fl.march = 0;
        cb = bench_time_stat(bench_floor_batch, &fl, BENCH_OVERHEAD_BATCHES, 1) / target;
        fl.march = 1;
        floor_ns = bench_time_stat(bench_floor_batch, &fl, BENCH_OVERHEAD_BATCHES, 1) / target;
        fl_err = bench_rel_error(fl.L, tot->refs[si].L);
        snprintf(title, sizeof title, "Library overhead on the %s scene", sc->name);
        bench_section(o, title);
        bench_both(o, "Time per evaluation at about %ld evaluations, warp none; each time is the "
                      "fastest of %d timed batches, so that other processes' interference drops "
                      "out. Callbacks alone (%s): %.1f ns per evaluation. Hand-written ray march (rectangle rule, the "
                      "same callbacks, %s): %.1f ns per evaluation, %.1f ns beyond the callbacks "
                      "(its rel_error %.1e).\n"
                      "'beyond callbacks' is ns/eval minus the callbacks' own cost; 'ratio' "
                      "divides it by the hand-written loop's; 'total ratio' compares ns/eval "
                      "as is.\n\n",
                   target, BENCH_OVERHEAD_BATCHES,
                   m.flags & HRM_MEDIUM_HOMOGENEOUS ? "Li" : "sigma_a, sigma_s, Le, Li", cb,
                   m.flags & HRM_MEDIUM_HOMOGENEOUS ? "Tr in closed form" : "tau by the trapezoid rule",
                   floor_ns, floor_ns - cb, fl_err);
        bench_table_start(8);
        bench_table_row();
        bench_table_cell(0, "method");
        bench_table_cell(1, "param");
        bench_table_cell(2, "evals");
        bench_table_cell(3, "ns/ray");
        bench_table_cell(4, "ns/eval");
        bench_table_cell(5, "beyond callbacks");
        bench_table_cell(6, "ratio");
        bench_table_cell(7, "total ratio");
        for (mi = 0; mi < bench_method_count; ++mi) {
            const bench_method *me = &bench_methods[mi];
            bench_case bc;
            hrm_result res;
            double param, ns, per;
            if (me->kind == BENCH_OTHER || (cfg->any_method && !cfg->method_on[mi])) continue;
            if (bench_is_swept_over_n(me))
                param = me->id == HRM_SIMPSON || me->id == HRM_RK4 ? target / 2 : target;
            else
                param = bench_tol_for_evals(cfg, sc, me, &m, &calls, target);
            bench_case_init(&bc, cfg, sc, me, BENCH_WARP_NONE, param, &m, &calls);
            bc.seeds = 1;
            if (hrm_solve(&m, (hrm_real)sc->t0, (hrm_real)sc->t1, &bc.options, &res) < 0 ||
                res.stats.evals <= 0)
                continue;
            ns = bench_time_stat(bench_solve_batch, &bc, BENCH_OVERHEAD_BATCHES, 1);
            per = ns / (double)res.stats.evals;
            bench_table_row();
            bench_table_cell(0, "%s", me->name);
            if (bench_is_swept_over_n(me)) bench_table_cell(1, "N = %.0f", param);
            else bench_table_cell(1, "rtol = %.0e", param);
            bench_table_cell(2, "%ld", res.stats.evals);
            bench_table_cell(3, "%.0f", ns);
            bench_table_cell(4, "%.1f", per);
            bench_table_cell(5, "%.1f", per - cb);
            if (floor_ns - cb > 0) bench_table_cell(6, "%.1f", (per - cb) / (floor_ns - cb));
            else bench_table_cell(6, "n/a");
            bench_table_cell(7, "%.2f", per / floor_ns);
        }
        bench_table_emit(o);
    }
}

/* --- per scene: the fewest evaluations to reach an error ---------------- */

/* The rows of sw that reach target reliably: the first row from which every
   later row of the sweep (larger N, tighter rtol) has an error at most
   target and no error status. Returns that row's index in the sweep, or
   count if none. */
static int bench_reliable_from(const bench_sweep *sw, double target)
{
    int k = sw->count;
    while (k > 0) {
        const bench_row *r = &bench_rows[sw->first + k - 1];
        if (r->status < 0 || !(r->rel_error <= target)) break;
        --k;
    }
    return k;
}

/* N as an integer, rtol as a power of ten: a static buffer, one use at a time
   per argument list (two slots alternate). */
static const char *bench_param_str(const bench_method *me, double param)
{
    static char buf[2][24];
    static int slot;
    slot ^= 1;
    if (bench_is_swept_over_n(me)) snprintf(buf[slot], sizeof buf[slot], "%.0f", param);
    else snprintf(buf[slot], sizeof buf[slot], "%.0e", param);
    return buf[slot];
}

static void bench_print_scene_summary(int si, const bench_out *o)
{
    const bench_scene *sc = &bench_scenes[si];
    int t, i, k, mi, w;
    if (!o->quiet) printf("\n-- %s: %s\n", sc->name, sc->description);
    if (o->md) fprintf(o->md, "\n### %s\n\n%s.\n\n", sc->name, sc->description);
    bench_table_start(7);
    bench_table_row();
    bench_table_cell(0, "rel. error");
    bench_table_cell(1, "fewest evals");
    bench_table_cell(2, "method, warp (param)");
    bench_table_cell(3, "its ns/ray");
    bench_table_cell(4, "fastest ns/ray");
    bench_table_cell(5, "method, warp (param)");
    bench_table_cell(6, "its evals");
    for (t = 0; t < BENCH_TARGETS; ++t) {
        const bench_row *be = NULL, *bt = NULL;
        for (i = 0; i < bench_nsweeps; ++i) {
            const bench_sweep *sw = &bench_sweeps[i];
            if (sw->scene != si) continue;
            for (k = bench_reliable_from(sw, bench_targets[t]); k < sw->count; ++k) {
                const bench_row *r = &bench_rows[sw->first + k];
                /* ties: the first found, the loosest N or rtol of the earlier method */
                if (!be || r->stats.evals < be->stats.evals) be = r;
                if (bench_finite(r->ns_per_ray) && (!bt || r->ns_per_ray < bt->ns_per_ray)) bt = r;
            }
        }
        bench_table_row();
        bench_table_cell(0, "%.0e", bench_targets[t]);
        if (!be) {
            bench_table_cell(1, "not reached");
            continue;
        }
        bench_table_cell(1, "%ld", be->stats.evals);
        bench_table_cell(2, "%s, %s (%s%s)", bench_methods[be->method].name,
                         bench_warp_names[be->warp],
                         bench_is_swept_over_n(&bench_methods[be->method]) ? "N " : "rtol ",
                         bench_param_str(&bench_methods[be->method], be->param));
        bench_table_cell(3, bench_finite(be->ns_per_ray) ? "%.0f" : "-", be->ns_per_ray);
        if (bt) {
            bench_table_cell(4, "%.0f", bt->ns_per_ray);
            bench_table_cell(5, "%s, %s (%s%s)", bench_methods[bt->method].name,
                             bench_warp_names[bt->warp],
                             bench_is_swept_over_n(&bench_methods[bt->method]) ? "N " : "rtol ",
                             bench_param_str(&bench_methods[bt->method], bt->param));
            bench_table_cell(6, "%ld", bt->stats.evals);
        }
    }
    bench_table_emit(o);

    /* fitted orders of the fixed-step methods, both warps */
    bench_table_start(4);
    bench_table_row();
    bench_table_cell(0, "fixed-step method");
    bench_table_cell(1, "order, warp none");
    bench_table_cell(2, "order, warp %s", bench_warp_names[sc->natural_warp]);
    bench_table_cell(3, "nominal");
    for (mi = 0; mi < bench_method_count; ++mi) {
        const bench_sweep *sws[2];
        if (!bench_is_swept_over_n(&bench_methods[mi])) continue;
        sws[0] = bench_find_sweep(si, mi, BENCH_WARP_NONE);
        sws[1] = bench_find_sweep(si, mi, sc->natural_warp);
        if (!sws[0] && !sws[1]) continue;
        bench_table_row();
        bench_table_cell(0, "%s", bench_methods[mi].name);
        for (w = 0; w < 2; ++w) bench_order_cell(1 + w, sws[w]);
        bench_table_cell(3, "%g", bench_methods[mi].order);
    }
    if (bench_tab.nrows > 1) bench_table_emit(o);
}

/* ------------------------------------------------------------------------ */
/* Files: CSV, SVG figures                                                  */
/* ------------------------------------------------------------------------ */

static int bench_mkdir_p(const char *dir)
{
    char buf[1024];
    size_t i, n = strlen(dir);
    if (n == 0 || n >= sizeof buf) return -1;
    memcpy(buf, dir, n + 1);
    for (i = 1; i <= n; ++i) {
        if (buf[i] == '/' || buf[i] == 0) {
            char keep = buf[i];
            buf[i] = 0;
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            buf[i] = keep;
        }
    }
    return 0;
}

static int bench_is_dir(const char *dir)
{
    struct stat st;
    errno = 0;
    if (stat(dir, &st) != 0) return 0;
    if (!S_ISDIR(st.st_mode)) {
        errno = ENOTDIR;
        return 0;
    }
    return 1;
}

static FILE *bench_open(const char *dir, const char *name, char *path, size_t n)
{
    FILE *f;
    snprintf(path, n, "%s/%s", dir, name);
    f = fopen(path, "w");
    if (!f) fprintf(stderr, "bench: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

static int bench_close(FILE *f, const char *path)
{
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        fprintf(stderr, "bench: error writing %s\n", path);
        return -1;
    }
    return 0;
}

static int bench_write_csv(const char *dir)
{
    char path[1200];
    FILE *f = bench_open(dir, "bench.csv", path, sizeof path);
    int i;
    if (!f) return -1;
    fprintf(f, "%s\n", BENCH_CSV_HEADER);
    for (i = 0; i < bench_nrows; ++i) bench_print_csv_row(f, &bench_rows[i]);
    return bench_close(f, path);
}

enum { BENCH_AX_EVALS, BENCH_AX_NS, BENCH_AX_RTOL, BENCH_AX_ERROR };

static double bench_axis_value(const bench_row *r, int axis)
{
    switch (axis) {
    case BENCH_AX_EVALS: return (double)r->stats.evals;
    case BENCH_AX_NS: return r->ns_per_ray;
    case BENCH_AX_RTOL: return r->param;
    default:
        if (r->status < 0 || !bench_finite(r->rel_error)) return (double)NAN;
        return r->rel_error > BENCH_PLOT_FLOOR ? r->rel_error : BENCH_PLOT_FLOOR;
    }
}

/* One series per method of scene si under warp w; adaptive_only: only the
   methods swept over rtol. */
static int bench_series(int si, bench_warp_id w, int adaptive_only, int xa, int ya,
                        svg_series *out)
{
    int mi, n = 0, k;
    if (adaptive_only == 2) return 0; /* an empty cell */
    for (mi = 0; mi < bench_method_count; ++mi) {
        const bench_method *me = &bench_methods[mi];
        const bench_sweep *sw = bench_find_sweep(si, mi, w);
        svg_series *s;
        if (!sw || (adaptive_only && me->kind != BENCH_ADAPTIVE)) continue;
        s = &out[n++];
        s->label = me->name;
        s->color = me->color;
        s->dashed = me->kind == BENCH_ADAPTIVE;
        s->marker = me->marker;
        s->n = sw->count < SVG_MAX_POINTS ? sw->count : SVG_MAX_POINTS;
        for (k = 0; k < s->n; ++k) {
            s->x[k] = bench_axis_value(&bench_rows[sw->first + k], xa);
            s->y[k] = bench_axis_value(&bench_rows[sw->first + k], ya);
        }
    }
    return n;
}

static const char *bench_axis_label(int axis)
{
    switch (axis) {
    case BENCH_AX_EVALS: return "evaluations (samples) per ray";
    case BENCH_AX_NS: return "time per ray (ns)";
    case BENCH_AX_RTOL: return "rtol";
    default: return "relative error";
    }
}

/* Layout: cells of plot area PW x PH with margins, a legend on the right. */
#define BENCH_PW 300.0
#define BENCH_PH 210.0
#define BENCH_CW 385.0
#define BENCH_CH 300.0
#define BENCH_X0 72.0
#define BENCH_Y0 86.0
#define BENCH_LEGEND 220.0

typedef struct bench_cell {
    int scene;
    bench_warp_id warp;
    int xa, ya, adaptive_only;
    char title[96];
} bench_cell;

/* The common range of one axis kind over every cell of a figure. */
static void bench_figure_range(const bench_cell *cells, int n, int axis, double *lo, double *hi)
{
    static svg_series s[BENCH_MAX_METHODS];
    double a = HUGE_VAL, b = -HUGE_VAL, l, h;
    int i, ns;
    for (i = 0; i < n; ++i) {
        const bench_cell *c = &cells[i];
        if (c->xa == axis) {
            ns = bench_series(c->scene, c->warp, c->adaptive_only, c->xa, c->ya, s);
            if (!ns) continue;
            svg_range(s, ns, 0, -16, &l, &h);
        } else if (c->ya == axis) {
            ns = bench_series(c->scene, c->warp, c->adaptive_only, c->xa, c->ya, s);
            if (!ns) continue;
            svg_range(s, ns, 1, -16, &l, &h);
        } else {
            continue;
        }
        if (l < a) a = l;
        if (h > b) b = h;
    }
    if (a > b) {
        a = 0;
        b = 1;
    }
    if (axis == BENCH_AX_ERROR && b < 0) b = 0; /* errors up to 10^0 */
    *lo = a;
    *hi = b;
}

static int bench_write_figure(const char *dir, const char *file, const char *title,
                              const bench_cell *cells, int n, int ncols)
{
    static svg_series s[BENCH_MAX_METHODS], legend[BENCH_MAX_METHODS];
    char path[1200];
    double rng[4][2];
    int nrows = (n + ncols - 1) / ncols, i, a, nl = 0, mi;
    int used[BENCH_MAX_METHODS] = {0};
    FILE *f;
    if (n == 0) return 0;
    f = bench_open(dir, file, path, sizeof path);
    if (!f) return -1;
    for (a = 0; a < 4; ++a) bench_figure_range(cells, n, a, &rng[a][0], &rng[a][1]);
    svg_begin(f, BENCH_X0 + ncols * BENCH_CW + BENCH_LEGEND, BENCH_Y0 + nrows * BENCH_CH, title);
    svg_text(f, 16, 46, "start", 0, "fill=\"#555\"",
             "Munoz 2014 relative error |L - Lref| / max(|L|, |Lref|), worst channel; errors "
             "below 1e-16 drawn at 1e-16. Solid: fixed-step methods (one point per N); "
             "dashed: adaptive methods (one point per rtol).");
    for (i = 0; i < n; ++i) {
        const bench_cell *c = &cells[i];
        svg_panel p;
        int ns = bench_series(c->scene, c->warp, c->adaptive_only, c->xa, c->ya, s), k;
        if (c->adaptive_only == 2) continue;
        p.left = BENCH_X0 + (i % ncols) * BENCH_CW;
        p.top = BENCH_Y0 + (i / ncols) * BENCH_CH;
        p.width = BENCH_PW;
        p.height = BENCH_PH;
        p.title = c->title;
        p.xlabel = bench_axis_label(c->xa);
        p.ylabel = bench_axis_label(c->ya);
        p.xlo = rng[c->xa][0];
        p.xhi = rng[c->xa][1];
        p.ylo = rng[c->ya][0];
        p.yhi = rng[c->ya][1];
        p.guides = c->xa == BENCH_AX_RTOL && c->ya == BENCH_AX_ERROR;
        svg_panel_draw(f, &p, s, ns);
        for (k = 0; k < ns; ++k)
            for (mi = 0; mi < bench_method_count; ++mi)
                if (!strcmp(s[k].label, bench_methods[mi].name)) used[mi] = 1;
    }
    for (mi = 0; mi < bench_method_count; ++mi) {
        if (!used[mi]) continue;
        legend[nl].label = bench_methods[mi].name;
        legend[nl].color = bench_methods[mi].color;
        legend[nl].dashed = bench_methods[mi].kind == BENCH_ADAPTIVE;
        legend[nl].marker = bench_methods[mi].marker;
        nl++;
    }
    svg_legend(f, BENCH_X0 + ncols * BENCH_CW - 20, BENCH_Y0 + 10, legend, nl);
    svg_end(f);
    return bench_close(f, path);
}

static int bench_has_kind(int si, bench_warp_id w, int adaptive)
{
    int mi;
    for (mi = 0; mi < bench_method_count; ++mi)
        if (bench_find_sweep(si, mi, w) && (bench_methods[mi].kind == BENCH_ADAPTIVE) == adaptive)
            return 1;
    return 0;
}

static void bench_add_cell(bench_cell *cells, int *n, int si, bench_warp_id w, int xa, int ya,
                           int adaptive_only, const char *what)
{
    bench_cell *c = &cells[(*n)++];
    c->scene = si;
    c->warp = w;
    c->xa = xa;
    c->ya = ya;
    c->adaptive_only = adaptive_only;
    snprintf(c->title, sizeof c->title, "%s, warp %s: %s", bench_scenes[si].name,
             bench_warp_names[w], what);
}

/* Per scene: a row per warp with error vs evaluations, error vs time, and
   for the adaptive methods rtol vs error and rtol vs evaluations. Then
   fig4.svg: Munoz 2014 Fig. 4's scenes, one row each. */
static int bench_write_figures(const bench_config *cfg, const char *dir, int *files)
{
    static bench_cell cells[64];
    char file[64], title[160];
    int si, w, n, bad = 0;
    for (si = 0; si < BENCH_SCENE_COUNT; ++si) {
        int ncols = 0;
        n = 0;
        for (w = 0; w < BENCH_WARP_COUNT; ++w) {
            int fixed = bench_has_kind(si, (bench_warp_id)w, 0);
            int adapt = bench_has_kind(si, (bench_warp_id)w, 1);
            int before = n;
            if (!fixed && !adapt) continue;
            bench_add_cell(cells, &n, si, (bench_warp_id)w, BENCH_AX_EVALS, BENCH_AX_ERROR, 0,
                           "error vs evaluations");
            if (cfg->timed)
                bench_add_cell(cells, &n, si, (bench_warp_id)w, BENCH_AX_NS, BENCH_AX_ERROR, 0,
                               "error vs time");
            if (adapt) {
                bench_add_cell(cells, &n, si, (bench_warp_id)w, BENCH_AX_RTOL, BENCH_AX_ERROR, 1,
                               "rtol vs error");
                bench_add_cell(cells, &n, si, (bench_warp_id)w, BENCH_AX_RTOL, BENCH_AX_EVALS, 1,
                               "rtol vs evaluations");
            }
            if (n - before > ncols) ncols = n - before;
        }
        if (!n) continue;
        { /* pad each warp's row to ncols: rebuild with fixed columns */
            bench_cell grid[64];
            int g = 0, i = 0;
            while (i < n) {
                int j = i, c;
                while (j < n && cells[j].warp == cells[i].warp) ++j;
                for (c = 0; c < ncols; ++c) {
                    if (i + c < j) grid[g] = cells[i + c];
                    else {
                        grid[g] = cells[i];
                        grid[g].adaptive_only = 2; /* empty: no series */
                    }
                    g++;
                }
                i = j;
            }
            memcpy(cells, grid, (size_t)g * sizeof grid[0]);
            n = g;
        }
        snprintf(file, sizeof file, "%s.svg", bench_scenes[si].name);
        snprintf(title, sizeof title, "hrm.h benchmark, scene %s: %s", bench_scenes[si].name,
                 bench_scenes[si].description);
        bad |= bench_write_figure(dir, file, title, cells, n, ncols);
        ++*files;
    }
    /* fig4.svg */
    n = 0;
    for (si = 0; si < BENCH_SCENE_COUNT; ++si) {
        const char *nm = bench_scenes[si].name;
        bench_warp_id nat = bench_scenes[si].natural_warp;
        if (strcmp(nm, "directional") && strcmp(nm, "point") && strcmp(nm, "occluder")) continue;
        if (!bench_has_kind(si, BENCH_WARP_NONE, 0) && !bench_has_kind(si, BENCH_WARP_NONE, 1))
            continue;
        bench_add_cell(cells, &n, si, BENCH_WARP_NONE, BENCH_AX_EVALS, BENCH_AX_ERROR, 0,
                       "error vs evaluations");
        bench_add_cell(cells, &n, si, nat, BENCH_AX_EVALS, BENCH_AX_ERROR, 0,
                       "error vs evaluations");
        bench_add_cell(cells, &n, si, BENCH_WARP_NONE, BENCH_AX_RTOL, BENCH_AX_ERROR, 1,
                       "rtol vs error");
        bench_add_cell(cells, &n, si, BENCH_WARP_NONE, BENCH_AX_RTOL, BENCH_AX_EVALS, 1,
                       "rtol vs evaluations");
    }
    if (n) {
        bad |= bench_write_figure(dir, "fig4.svg",
                                  "hrm.h after Munoz 2014 Fig. 4: directional, point and occluded "
                                  "point light; without and with importance sampling; tolerance "
                                  "vs error and evaluations",
                                  cells, n, 4);
        ++*files;
    }
    return bad;
}

/* ------------------------------------------------------------------------ */
/* Command line                                                             */
/* ------------------------------------------------------------------------ */

static void bench_usage(FILE *out)
{
    fprintf(out,
            "usage: bench [options]\n"
            "Single-ray accuracy and speed of every hrm.h method on every scene: fixed-step\n"
            "methods over N, adaptive methods over rtol, each without a warp and with the\n"
            "scene's natural warp. Tables on stdout, progress on stderr, files in --out.\n"
            "  --scene NAME    run only this scene (repeatable)\n"
            "  --method NAME   run only this method (repeatable); gauss-kronrod selects both\n"
            "                  of its modes\n"
            "  --warp NAME     run only this warp (repeatable): none, natural (the scene's\n"
            "                  own), distance, equiangular (scenes with a point light)\n"
            "  --steps N       fixed-step methods at this N only (repeatable); alone, it\n"
            "                  runs no adaptive method\n"
            "  --tol X         adaptive methods at this rtol only (repeatable); alone, it\n"
            "                  runs no fixed-step method\n"
            "  --control NAME  step control of the Runge-Kutta pairs: pi (default), munoz,\n"
            "                  gonterman\n"
            "  --quick         N = 1..64, rtol = 1e-2..1e-6, %d Monte Carlo seeds, short timing\n"
            "  --no-timing     skip the timing (ns_per_ray is nan; no time plots, no overhead)\n"
            "  --csv           print CSV rows on stdout instead of the tables, under the header\n"
            "                  %s\n"
            "  --out DIR       write bench.csv, SVG figures and summary.md here (default\n"
            "                  bench/out)\n"
            "  --list          list the scenes, methods, warps and controls, then exit\n"
            "  --help          this text\n"
            "Defaults: N = 1..1024 (doubling), rtol = 1e-2..1e-10 (decades), %d seeds,\n"
            "adaptive budget max_evals = %ld.\n"
            "Exit status: 0 ok; 1 a solve returned an error status; 2 usage error;\n"
            "3 an output file could not be written; 4 a consistency check failed (hrm's\n"
            "evaluation counts disagree with the callbacks it made, or a reference is less\n"
            "accurate than %.0Le).\n",
            BENCH_SEEDS_QUICK, BENCH_CSV_HEADER, BENCH_SEEDS, BENCH_MAX_EVALS, BENCH_REF_CHECK);
}

static void bench_list_names(FILE *out, int what)
{
    int i;
    if (what == 0)
        for (i = 0; i < BENCH_SCENE_COUNT; ++i) fprintf(out, "%s%s", i ? ", " : "", bench_scenes[i].name);
    else if (what == 1)
        for (i = 0; i < bench_method_count; ++i) fprintf(out, "%s%s", i ? ", " : "", bench_methods[i].name);
    else if (what == 2)
        fprintf(out, "none, natural, distance, equiangular");
    else
        fprintf(out, "pi, munoz, gonterman");
    fprintf(out, "\n");
}

static void bench_list(void)
{
    int i;
    printf("scenes (natural warp):\n");
    for (i = 0; i < BENCH_SCENE_COUNT; ++i)
        printf("  %-12s %-12s %s\n", bench_scenes[i].name,
               bench_warp_names[bench_scenes[i].natural_warp], bench_scenes[i].description);
    printf("methods:\n");
    for (i = 0; i < bench_method_count; ++i) {
        printf("  %-22s %s", bench_methods[i].name, bench_kind_name(bench_methods[i].kind));
        if (bench_methods[i].order > 0) printf(", order %g", bench_methods[i].order);
        printf("\n");
    }
    printf("warps:\n  none\n  natural      the scene's own (above)\n"
           "  distance     sigma_ref = mean sigma_t at t0\n"
           "  equiangular  toward the scene's point light (point, occluder, thin)\n");
    printf("controls (Runge-Kutta pairs):\n  pi (default)\n  munoz\n  gonterman\n");
}

static int bench_usage_error(const char *fmt, const char *arg, int list)
{
    fprintf(stderr, "bench: ");
    fprintf(stderr, fmt, arg);
    if (list >= 0) {
        fprintf(stderr, "; valid: ");
        bench_list_names(stderr, list);
    } else {
        fprintf(stderr, "\n");
    }
    fprintf(stderr, "run 'bench --help' for usage\n");
    return BENCH_EXIT_USAGE;
}

/* Returns 0, or BENCH_EXIT_USAGE after printing the error. */
static int bench_parse(int argc, char **argv, bench_config *cfg)
{
    static const char *const with_value[] = {"--scene", "--method", "--warp", "--steps",
                                             "--tol", "--control", "--out"};
    int i, k, j;
    memset(cfg, 0, sizeof *cfg);
    cfg->timed = 1;
    cfg->out_dir = "bench/out";
    cfg->control = HRM_CONTROL_PI;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *value = NULL, *opt = a;
        char name[16];
        if (!strcmp(a, "--csv")) { cfg->csv = 1; continue; }
        if (!strcmp(a, "--quick")) { cfg->quick = 1; continue; }
        if (!strcmp(a, "--list")) { cfg->list = 1; continue; }
        if (!strcmp(a, "--no-timing")) { cfg->timed = 0; continue; }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            bench_usage(stdout);
            exit(BENCH_EXIT_OK);
        }
        /* --opt VALUE or --opt=VALUE */
        for (j = 0; j < COUNT_OF(with_value); ++j) {
            size_t l = strlen(with_value[j]);
            if (!strcmp(a, with_value[j])) {
                if (i + 1 >= argc) return bench_usage_error("%s needs a value", a, -1);
                value = argv[++i];
                break;
            }
            if (!strncmp(a, with_value[j], l) && a[l] == '=') {
                value = a + l + 1;
                break;
            }
        }
        if (j == COUNT_OF(with_value)) return bench_usage_error("unknown option '%s'", a, -1);
        snprintf(name, sizeof name, "%s", with_value[j]);
        opt = name;
        if (!strcmp(opt, "--scene")) {
            for (k = 0; k < BENCH_SCENE_COUNT && strcmp(value, bench_scenes[k].name); ++k) {}
            if (k == BENCH_SCENE_COUNT) return bench_usage_error("unknown scene '%s'", value, 0);
            cfg->scene_on[k] = cfg->any_scene = 1;
        } else if (!strcmp(opt, "--method")) {
            int found = 0;
            for (k = 0; k < bench_method_count; ++k)
                if (!strcmp(value, bench_methods[k].name) ||
                    !strcmp(value, hrm_method_name(bench_methods[k].id))) {
                    cfg->method_on[k] = cfg->any_method = 1;
                    found = 1;
                }
            if (!found) return bench_usage_error("unknown method '%s'", value, 1);
        } else if (!strcmp(opt, "--warp")) {
            if (!strcmp(value, "natural")) {
                cfg->natural_on = 1;
            } else {
                for (k = 0; k < BENCH_WARP_COUNT && strcmp(value, bench_warp_names[k]); ++k) {}
                if (k == BENCH_WARP_COUNT) return bench_usage_error("unknown warp '%s'", value, 2);
                cfg->warp_on[k] = 1;
            }
            cfg->any_warp = 1;
        } else if (!strcmp(opt, "--control")) {
            if (!strcmp(value, "pi")) cfg->control = HRM_CONTROL_PI;
            else if (!strcmp(value, "munoz")) cfg->control = HRM_CONTROL_MUNOZ;
            else if (!strcmp(value, "gonterman")) cfg->control = HRM_CONTROL_GONTERMAN;
            else return bench_usage_error("unknown control '%s'", value, 3);
        } else if (!strcmp(opt, "--out")) {
            if (!*value) return bench_usage_error("--out needs a directory%s", "", -1);
            cfg->out_dir = value;
        } else { /* --steps, --tol */
            char *end;
            int steps = !strcmp(opt, "--steps");
            double v = steps ? (double)strtol(value, &end, 10) : strtod(value, &end);
            if (end == value || *end)
                return bench_usage_error(steps ? "--steps needs an integer, not '%s'"
                                               : "--tol needs a number, not '%s'",
                                         value, -1);
            if (steps ? !(v >= 1 && v <= 1 << 20) : !(v > 0 && v < 1))
                return bench_usage_error(steps ? "--steps %s: N must be in 1..1048576"
                                               : "--tol %s: rtol must lie in (0, 1)",
                                         value, -1);
            if ((steps ? cfg->nsteps : cfg->ntols) >= BENCH_MAX_PARAMS)
                return bench_usage_error("too many %s values", opt, -1);
            if (steps) cfg->steps[cfg->nsteps++] = v;
            else cfg->tols[cfg->ntols++] = v;
        }
    }
    cfg->user_steps = cfg->nsteps > 0;
    cfg->user_tols = cfg->ntols > 0;
    if (!cfg->nsteps) {
        const double *d = cfg->quick ? bench_steps_quick : bench_steps_full;
        cfg->nsteps = cfg->quick ? COUNT_OF(bench_steps_quick) : COUNT_OF(bench_steps_full);
        memcpy(cfg->steps, d, (size_t)cfg->nsteps * sizeof d[0]);
    } else {
        qsort(cfg->steps, (size_t)cfg->nsteps, sizeof cfg->steps[0], bench_cmp_double);
    }
    if (!cfg->ntols) {
        const double *d = cfg->quick ? bench_tols_quick : bench_tols_full;
        cfg->ntols = cfg->quick ? COUNT_OF(bench_tols_quick) : COUNT_OF(bench_tols_full);
        memcpy(cfg->tols, d, (size_t)cfg->ntols * sizeof d[0]);
    } else { /* decreasing: the sweep tightens */
        qsort(cfg->tols, (size_t)cfg->ntols, sizeof cfg->tols[0], bench_cmp_double);
        for (k = 0; k < cfg->ntols / 2; ++k) {
            double t = cfg->tols[k];
            cfg->tols[k] = cfg->tols[cfg->ntols - 1 - k];
            cfg->tols[cfg->ntols - 1 - k] = t;
        }
    }
    cfg->seeds = cfg->quick ? BENCH_SEEDS_QUICK : BENCH_SEEDS;
    return 0;
}

/* ------------------------------------------------------------------------ */
/* main                                                                     */
/* ------------------------------------------------------------------------ */

int main(int argc, char **argv)
{
    static bench_totals tot;
    bench_config cfg;
    bench_progress pg;
    ref_rule rule;
    bench_out both;
    char path[1200];
    int si, mi, v = hrm_version(), out_bad = 0, files = 0, rc;
    double start = bench_seconds();

    bench_methods_init();
    rc = bench_parse(argc, argv, &cfg);
    if (rc) return rc;
    if (cfg.list) {
        bench_list();
        return BENCH_EXIT_OK;
    }
    if (cfg.quick) {
        bench_timings = 3;
        bench_batch_seconds = 2e-4;
    }
    ref_rule_init(&rule);
    if (bench_mkdir_p(cfg.out_dir) != 0 || !bench_is_dir(cfg.out_dir)) {
        if (!errno) errno = ENOTDIR;
        fprintf(stderr, "bench: cannot create %s: %s\n", cfg.out_dir, strerror(errno));
        return BENCH_EXIT_OUTPUT;
    }

    /* the work, for the progress line */
    memset(&pg, 0, sizeof pg);
    pg.start = start;
    pg.tty = isatty(2);
    for (si = 0; si < BENCH_SCENE_COUNT; ++si) {
        bench_warp_id w[BENCH_WARP_COUNT];
        int nw;
        if (!bench_scene_selected(&cfg, si)) continue;
        nw = bench_scene_warps(&cfg, &bench_scenes[si], w);
        for (mi = 0; mi < bench_method_count; ++mi) {
            const double *p;
            if (bench_method_selected(&cfg, mi))
                pg.total += (long)nw * bench_params_of(&cfg, &bench_methods[mi], &p);
        }
    }

    if (cfg.csv) {
        printf("%s\n", BENCH_CSV_HEADER);
    } else {
        printf("hrm.h %d.%d.%d single-ray benchmark: fixed-step methods over N = %g..%g, "
               "adaptive methods over rtol = %g..%g\n",
               v / 10000, v / 100 % 100, v % 100, cfg.steps[0], cfg.steps[cfg.nsteps - 1],
               cfg.tols[0], cfg.tols[cfg.ntols - 1]);
        printf("rel_error: |L - Lref| / max(|L|, |Lref|) (Munoz 2014), worst of %d channels;\n"
               "  monte-carlo: RMS over seeds 1..%d (evals and ns_per_ray are per ray)\n"
               "evals: source (Li/Le) evaluations; medium_evals: sigma/transmittance "
               "evaluations\n"
               "adaptive methods: hrm defaults but rtol, max_evals = %ld and control %s\n"
               "ns_per_ray: ",
               HRM_CHANNELS, cfg.seeds, BENCH_MAX_EVALS, bench_control_name(cfg.control));
        if (cfg.timed)
            printf("median of %d batches of repeated solves, each >= %g ms (CLOCK_MONOTONIC)\n",
                   bench_timings, bench_batch_seconds * 1e3);
        else
            printf("not measured (--no-timing)\n");
    }
    for (si = 0; si < BENCH_SCENE_COUNT; ++si) {
        if (!bench_scene_selected(&cfg, si)) continue;
        bench_run_scene(&cfg, si, &rule, &tot, &pg);
        if (!pg.tty)
            fprintf(stderr, "bench: scene %s done (%ld/%ld rows, %.1f s)\n",
                    bench_scenes[si].name, pg.done, pg.total, bench_seconds() - start);
    }

    /* Summaries: on stdout (unless --csv) and in summary.md. */
    both.md = bench_open(cfg.out_dir, "summary.md", path, sizeof path);
    both.quiet = cfg.csv;
    out_bad |= !both.md;
    if (both.md) {
        fprintf(both.md, "# hrm.h benchmark summary\n\n"
                         "Written by `make bench` (bench/bench.c) for hrm.h %d.%d.%d; "
                         "bench/README.md explains the tables. Errors are Munoz 2014's "
                         "|L - Lref| / max(|L|, |Lref|), worst of %d channels, against "
                         "references independent of hrm; times are one machine's.\n",
                v / 10000, v / 100 % 100, v % 100, HRM_CHANNELS);
    }
    if (!cfg.csv) bench_print_orders(&cfg);
    bench_print_proportionality(&cfg, &both);
    if (pg.tty) fprintf(stderr, "\r\033[K[    ] equiangular ratios, library overhead");
    bench_print_equiangular(&cfg, &tot, &both);
    bench_print_overhead(&cfg, &tot, &both);
    bench_section(&both, "Per scene: the fewest evaluations to reach an error");
    bench_both(&both, "For each target, the smallest evaluation count (and the shortest time) "
                      "of any method and warp whose sweep stays at or below the target from "
                      "that N or rtol on (a lucky single N does not count). N doubles and rtol "
                      "moves by decades, so a count is within a factor of about 2 (fixed-step) "
                      "of the least that would do. Fitted orders: over the whole sweep, in "
                      "parentheses its finest %d points.\n",
               BENCH_TAIL);
    for (si = 0; si < BENCH_SCENE_COUNT; ++si)
        if (bench_scene_selected(&cfg, si)) bench_print_scene_summary(si, &both);
    if (both.md) out_bad |= bench_close(both.md, path) != 0;

    out_bad |= bench_write_csv(cfg.out_dir) != 0;
    out_bad |= bench_write_figures(&cfg, cfg.out_dir, &files) != 0;
    if (pg.tty) fprintf(stderr, "\r\033[K");

    if (!cfg.csv) {
        printf("\nevaluation counts: hrm's stats %s the callbacks made in %ld solves",
               bench_count_mismatches ? "disagree with" : "match", tot.solves);
        if (bench_count_mismatches) printf(" (%ld mismatches, see stderr)", bench_count_mismatches);
        printf("\nreferences below the accuracy check (%.0Le): %d\n", BENCH_REF_CHECK, tot.ref_bad);
        printf("rows with an error status: %d\n", tot.errors);
        printf("wrote %s/bench.csv (%d rows), summary.md and %d SVG figures\n", cfg.out_dir,
               bench_nrows, files);
        printf("run time: %.1f s\n", bench_seconds() - start);
    } else if (bench_count_mismatches) {
        fprintf(stderr, "bench: %ld solves with evaluation counts that disagree with the callbacks\n",
                bench_count_mismatches);
    }
    free(bench_rows);
    free(bench_sweeps);
    if (tot.errors) return BENCH_EXIT_SOLVE_ERROR;
    if (out_bad) return BENCH_EXIT_OUTPUT;
    if (bench_count_mismatches || tot.ref_bad) return BENCH_EXIT_CHECK;
    return BENCH_EXIT_OK;
}
