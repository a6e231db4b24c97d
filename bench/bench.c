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

/* Nanoseconds per repetition of fn: the median over bench_timings batches,
   each repeated until it lasts bench_batch_seconds. */
static double bench_time(bench_batch_fn fn, void *ctx)
{
    double t[16], batch, start;
    long reps = 1;
    int i, n = bench_timings < 16 ? bench_timings : 16;
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
    return t[n / 2];
}

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
    double start;
    int tty;
    int last_scene;
} bench_progress;

static void bench_progress_show(bench_progress *pg, const char *scene, const char *method,
                                const char *warp)
{
    double pct = pg->total ? 100.0 * (double)pg->done / (double)pg->total : 100.0;
    double el = bench_seconds() - pg->start;
    if (pg->tty) {
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

#include <stdarg.h>
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

static void bench_fmt_order(char *buf, size_t n, double v)
{
    if (bench_finite(v)) snprintf(buf, n, "%.2f", v);
    else snprintf(buf, n, "n/a");
}

