/* bench/bench.c - single-ray convergence and speed benchmark of hrm.h.

   For every scene (scenes.h), method and step count N it solves one ray with
   hrm_solve and compares L with an independent reference (reference.h):
   the error is Munoz 2014's |L - Lref| / max(|L|, |Lref|), worst channel.
   Run with --help for the options. Exit status: 0 ok, 1 a solve returned an
   error status, 2 usage error.

   The program is three tables and a loop: scenes (scenes.h), methods (built
   from hrm_method_name, so a new method appears by itself), warps (only
   "none" so far), and bench_run_scene() walking them. */

#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#define HRM_IMPLEMENTATION
#include "hrm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "reference.h"
#include "scenes.h"

#define BENCH_SEEDS 32          /* Monte Carlo: RMS error over seeds 1..32 */
#define BENCH_BATCH_SECONDS 1e-3 /* a timed batch lasts at least this long */
#define BENCH_TIMINGS 5         /* timed batches; the median is reported */
#define BENCH_FIT_FLOOR 1e-13   /* errors below this are round-off: not fitted */
#define BENCH_MAX_PARAMS 16

static const int bench_steps_full[] = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024};
static const int bench_steps_quick[] = {1, 2, 4, 8, 16, 32, 64};

/* ------------------------------------------------------------------------ */
/* Methods                                                                  */
/* ------------------------------------------------------------------------ */

typedef enum bench_kind {
    BENCH_FIXED,  /* deterministic, swept over N */
    BENCH_RANDOM, /* swept over N, error as RMS over seeds */
    BENCH_OTHER   /* no sweep written for it yet: listed, not run */
} bench_kind;

typedef struct bench_method {
    hrm_method id;
    const char *name;
    bench_kind kind;
    double order; /* nominal order for smooth integrands (hrm.h manual); 0: unknown */
} bench_method;

static bench_method bench_methods[HRM_METHOD_COUNT];
static int bench_method_count;

static void bench_methods_init(void)
{
    int m;
    for (m = 1; m < (int)HRM_METHOD_COUNT; ++m) {
        bench_method *b = &bench_methods[bench_method_count++];
        b->id = (hrm_method)m;
        b->name = hrm_method_name(b->id);
        b->kind = BENCH_FIXED;
        b->order = 0;
        switch (b->id) {
        case HRM_RECTANGLE: b->order = 2; break;
        case HRM_SIMPSON: b->order = 4; break;
        case HRM_MONTE_CARLO: b->kind = BENCH_RANDOM; b->order = 0.5; break;
        case HRM_EULER: b->order = 1; break;
        case HRM_RK4: b->order = 4; break;
        case HRM_ADAMS_BASHFORTH: b->order = 4; break;
        default: b->kind = BENCH_OTHER; break;
        }
    }
}

static const char *bench_kind_name(bench_kind k)
{
    return k == BENCH_FIXED    ? "fixed-step"
           : k == BENCH_RANDOM ? "fixed-step, random (error: RMS over seeds)"
                               : "no sweep in the bench yet: listed, not run";
}

/* ------------------------------------------------------------------------ */
/* Warps (importance sampling as a change of variable): a column to come    */
/* ------------------------------------------------------------------------ */

typedef struct bench_warp {
    const char *name;
    void (*apply)(const bench_scene *scene, hrm_options *options);
} bench_warp;

static void bench_warp_none(const bench_scene *scene, hrm_options *options)
{
    (void)scene;
    (void)options;
}

static const bench_warp bench_warps[] = {{"none", bench_warp_none}};
#define BENCH_WARP_COUNT ((int)(sizeof bench_warps / sizeof bench_warps[0]))

/* ------------------------------------------------------------------------ */
/* References                                                               */
/* ------------------------------------------------------------------------ */

typedef struct bench_reference {
    long double L[HRM_CHANNELS];
    long double accuracy; /* estimated relative accuracy, worst channel */
    long double splits[REF_MAX_POINTS];
    int nsplits;          /* interior split points used */
} bench_reference;

static void bench_reference_compute(const bench_scene *sc, const ref_rule *rule,
                                    bench_reference *ref)
{
    long double pts[REF_MAX_POINTS], cut[REF_MAX_POINTS], coarse[HRM_CHANNELS],
        fine[HRM_CHANNELS];
    int n = 0, k = 0, i, j;

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

    ref_integrate(rule, sc->integrand, sc->params, pts, n, REF_PANEL, coarse);
    ref_integrate(rule, sc->integrand, sc->params, pts, n, REF_PANEL / 2, fine);
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
        fprintf(out, "    closed form in long double; the independent quadrature agrees to %.1Le\n",
                ref->accuracy);
        return;
    }
    fprintf(out, "    %d-point Gauss-Legendre panels in long double", REF_GL_POINTS);
    if (ref->nsplits) {
        fprintf(out, ", split at s =");
        for (i = 0; i < ref->nsplits; ++i)
            fprintf(out, "%s %.19Lg", i ? "," : "", ref->splits[i]);
    }
    fprintf(out, "\n    estimated relative accuracy %.1Le (panels <= %Lg vs <= %Lg)\n",
            ref->accuracy, REF_PANEL, REF_PANEL / 2);
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
/* One measurement: a row of the table                                      */
/* ------------------------------------------------------------------------ */

typedef struct bench_row {
    int scene, method, warp;
    long param;          /* N */
    hrm_stats stats;     /* of one ray (the first seed) */
    double rel_error;    /* RMS over seeds for random methods */
    hrm_status status;   /* an error if any seed gave one, else the largest warning */
    double ns_per_ray;
} bench_row;

typedef struct bench_case {
    const hrm_medium *medium;
    bench_calls *calls;
    double t0, t1;
    hrm_options options;
    int seeds;
} bench_case;

static double bench_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static volatile double bench_sink; /* keeps timed solves from being optimised away */

static double bench_time_batch(const bench_case *bc, long reps)
{
    hrm_options opt = bc->options;
    hrm_result res;
    double start = bench_seconds(), sum = 0;
    long r;
    for (r = 0; r < reps; ++r) {
        opt.seed = (uint64_t)(r % bc->seeds) + 1;
        hrm_solve(bc->medium, (hrm_real)bc->t0, (hrm_real)bc->t1, &opt, &res);
        sum += (double)res.L[0];
    }
    bench_sink = sum;
    return bench_seconds() - start;
}

static int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median over BENCH_TIMINGS batches, each repeated until it lasts
   BENCH_BATCH_SECONDS, of the time per solve. */
static double bench_time(const bench_case *bc)
{
    double t[BENCH_TIMINGS], batch;
    long reps = 1;
    int i;
    for (;;) {
        batch = bench_time_batch(bc, reps);
        if (batch >= BENCH_BATCH_SECONDS || reps >= (1L << 28)) break;
        /* Jump close to the target, at most x16 at a time. */
        if (batch > BENCH_BATCH_SECONDS / 16)
            reps = (long)ceil((double)reps * 1.1 * BENCH_BATCH_SECONDS / batch);
        else
            reps *= 16;
    }
    for (i = 0; i < BENCH_TIMINGS; ++i) t[i] = 1e9 * bench_time_batch(bc, reps) / (double)reps;
    qsort(t, BENCH_TIMINGS, sizeof t[0], bench_cmp_double);
    return t[BENCH_TIMINGS / 2];
}

static long bench_count_mismatches;

/* hrm's stats against the callbacks it made: every source evaluation calls
   Li (each scene scatters everywhere), and Le where there is emission;
   every medium evaluation calls sigma_a and sigma_s, where they exist. */
static void bench_check_counts(const bench_scene *sc, const bench_method *me, int N,
                               const hrm_medium *m, const bench_calls *calls, const hrm_stats *st)
{
    int ok = calls->li == st->evals;
    if (m->Le) ok &= calls->le == st->evals;
    if (m->sigma_a) ok &= calls->sigma_a == st->medium_evals;
    if (m->sigma_s) ok &= calls->sigma_s == st->medium_evals;
    if (ok) return;
    if (++bench_count_mismatches <= 10)
        fprintf(stderr,
                "bench: count mismatch: %s %s N=%d: stats evals=%ld medium_evals=%ld, "
                "callbacks Li=%ld Le=%ld sigma_a=%ld sigma_s=%ld\n",
                sc->name, me->name, N, st->evals, st->medium_evals, calls->li, calls->le,
                calls->sigma_a, calls->sigma_s);
}

static void bench_run_case(const bench_scene *sc, const bench_reference *ref,
                           const bench_method *me, const bench_case *bc, bench_row *row)
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
            bench_check_counts(sc, me, opt.steps, bc->medium, bc->calls, &res.stats);
        if (i == 0) row->stats = res.stats;
        if (st < 0 ? row->status >= 0 : row->status >= 0 && st > row->status) row->status = st;
        err = bench_rel_error(res.L, ref->L);
        sumsq += err * err;
    }
    row->rel_error = bc->seeds > 1 ? sqrt(sumsq / bc->seeds) : err;
    row->ns_per_ray = bench_time(bc);
}

/* ------------------------------------------------------------------------ */
/* Convergence order                                                        */
/* ------------------------------------------------------------------------ */

#define BENCH_TAIL 4 /* the finest points, for the asymptotic order */

typedef struct bench_fit {
    int scene, method, warp;
    int points;          /* rows above the floor */
    double order;        /* -(least-squares slope of log error vs log evals) */
    double tail;         /* the same over the last BENCH_TAIL of those rows */
    long evals_lo, evals_hi;
} bench_fit;

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

static void bench_fit_rows(const bench_row *rows, int n, bench_fit *fit)
{
    double x[BENCH_MAX_PARAMS], y[BENCH_MAX_PARAMS];
    int i, k = 0, t;
    fit->evals_lo = fit->evals_hi = 0;
    for (i = 0; i < n; ++i) {
        const bench_row *r = &rows[i];
        if (!(r->rel_error > BENCH_FIT_FLOOR) || r->rel_error - r->rel_error != 0 ||
            r->stats.evals <= 0)
            continue;
        x[k] = log((double)r->stats.evals);
        y[k] = log(r->rel_error);
        if (!k || r->stats.evals < fit->evals_lo) fit->evals_lo = r->stats.evals;
        if (!k || r->stats.evals > fit->evals_hi) fit->evals_hi = r->stats.evals;
        ++k;
    }
    fit->points = k;
    fit->order = bench_order(x, y, k);
    t = k < BENCH_TAIL ? k : BENCH_TAIL;
    fit->tail = bench_order(x + (k - t), y + (k - t), t);
}

/* ------------------------------------------------------------------------ */
/* Output                                                                   */
/* ------------------------------------------------------------------------ */

#define BENCH_CSV_HEADER \
    "scene,method,warp,param,evals,medium_evals,steps,rejected,rel_error,status,ns_per_ray"

static void bench_print_row(const bench_row *r, int csv)
{
    const char *scene = bench_scenes[r->scene].name, *method = bench_methods[r->method].name;
    const char *warp = bench_warps[r->warp].name;
    if (csv) {
        printf("%s,%s,%s,%ld,%ld,%ld,%ld,%ld,%.6e,%d,%.1f\n", scene, method, warp, r->param,
               r->stats.evals, r->stats.medium_evals, r->stats.steps, r->stats.rejected,
               r->rel_error, (int)r->status, r->ns_per_ray);
        return;
    }
    printf("%-12s %-16s %-5s %5ld %7ld %12ld %10.3e %11.1f", scene, method, warp, r->param,
           r->stats.evals, r->stats.medium_evals, r->rel_error, r->ns_per_ray);
    if (r->status != HRM_OK)
        printf("  status %d: %s", (int)r->status, hrm_status_string(r->status));
    printf("\n");
}

static void bench_print_table_header(void)
{
    printf("%-12s %-16s %-5s %5s %7s %12s %10s %11s\n", "scene", "method", "warp", "N", "evals",
           "medium_evals", "rel_error", "ns_per_ray");
}

static void bench_print_order(double order)
{
    if (order == order) printf(" %7.2f", order);
    else printf(" %7s", "n/a");
}

static void bench_print_fits(const bench_fit *fits, int n)
{
    int i;
    printf("\nFitted convergence order: -(least-squares slope of log rel_error vs log evals)\n"
           "over the N whose rel_error is above %g (monte-carlo: of the RMS error);\n"
           "tail: the same over the last %d of those N only (the asymptotic order).\n",
           BENCH_FIT_FLOOR, BENCH_TAIL);
    printf("%-12s %-16s %-5s %7s %7s %8s %7s  %s\n", "scene", "method", "warp", "order", "tail",
           "nominal", "points", "evals");
    for (i = 0; i < n; ++i) {
        const bench_fit *f = &fits[i];
        const bench_method *me = &bench_methods[f->method];
        printf("%-12s %-16s %-5s", bench_scenes[f->scene].name, me->name,
               bench_warps[f->warp].name);
        bench_print_order(f->order);
        bench_print_order(f->tail);
        if (me->order > 0) printf(" %8g", me->order);
        else printf(" %8s", "?");
        printf(" %7d  ", f->points);
        if (f->points) printf("%ld..%ld", f->evals_lo, f->evals_hi);
        printf("\n");
    }
    printf("(nominal: hrm.h's order for smooth integrands; a sharp shadow drags fixed-step\n"
           "methods to first order)\n");
}

/* ------------------------------------------------------------------------ */
/* The run                                                                  */
/* ------------------------------------------------------------------------ */

typedef struct bench_config {
    int csv, quick, list;
    int scene_on[BENCH_SCENE_COUNT], any_scene;
    int method_on[HRM_METHOD_COUNT], any_method;
} bench_config;

typedef struct bench_totals {
    int errors;           /* rows in which a solve returned an error status */
    long solves;
    bench_fit fits[BENCH_SCENE_COUNT * HRM_METHOD_COUNT * BENCH_WARP_COUNT];
    int nfits;
} bench_totals;

static void bench_run_scene(const bench_config *cfg, int si, const ref_rule *rule,
                            const int *steps, int nsteps, bench_totals *tot)
{
    const bench_scene *sc = &bench_scenes[si];
    bench_reference ref;
    bench_calls calls;
    hrm_medium medium;
    int mi, wi, k, skipped = 0;

    bench_reference_compute(sc, rule, &ref);
    memset(&calls, 0, sizeof calls);
    calls.params = sc->params;
    memset(&medium, 0, sizeof medium);
    sc->build(sc->params, &medium);
    medium.user = &calls;

    if (!cfg->csv) {
        printf("\n== scene %s: %s\n", sc->name, sc->description);
        printf("  ray t0 = %g, t1 = %g\n", sc->t0, sc->t1);
        sc->print_params(stdout, sc->params);
        bench_reference_print(stdout, sc, &ref);
        bench_print_table_header();
    }
    for (mi = 0; mi < bench_method_count; ++mi) {
        const bench_method *me = &bench_methods[mi];
        if (cfg->any_method && !cfg->method_on[mi]) continue;
        if (me->kind == BENCH_OTHER) {
            skipped++;
            continue;
        }
        for (wi = 0; wi < BENCH_WARP_COUNT; ++wi) {
            bench_row rows[BENCH_MAX_PARAMS];
            bench_fit *fit = &tot->fits[tot->nfits++];
            for (k = 0; k < nsteps; ++k) {
                bench_case bc;
                bench_row *r = &rows[k];
                bc.medium = &medium;
                bc.calls = &calls;
                bc.t0 = sc->t0;
                bc.t1 = sc->t1;
                bc.options = hrm_default_options(me->id);
                bc.options.steps = steps[k];
                bc.seeds = me->kind == BENCH_RANDOM ? BENCH_SEEDS : 1;
                bench_warps[wi].apply(sc, &bc.options);
                r->scene = si;
                r->method = mi;
                r->warp = wi;
                r->param = steps[k];
                bench_run_case(sc, &ref, me, &bc, r);
                tot->solves += bc.seeds;
                if (r->status < 0) tot->errors++;
                bench_print_row(r, cfg->csv);
            }
            fit->scene = si;
            fit->method = mi;
            fit->warp = wi;
            bench_fit_rows(rows, nsteps, fit);
            fflush(stdout);
        }
    }
    if (skipped && !cfg->csv) {
        printf("not run (no sweep for them in the bench yet):");
        for (mi = 0; mi < bench_method_count; ++mi)
            if (bench_methods[mi].kind == BENCH_OTHER && (!cfg->any_method || cfg->method_on[mi]))
                printf(" %s", bench_methods[mi].name);
        printf("\n");
    }
}

/* ------------------------------------------------------------------------ */
/* Command line                                                             */
/* ------------------------------------------------------------------------ */

static void bench_usage(FILE *out)
{
    fprintf(out,
            "usage: bench [--csv] [--quick] [--scene NAME]... [--method NAME]... [--list] [--help]\n"
            "Single-ray convergence and speed of every hrm.h method on every scene.\n"
            "  --csv          print CSV rows instead of the tables, under the header\n"
            "                 %s\n"
            "  --quick        N = 1..64 instead of 1..1024\n"
            "  --scene NAME   run only this scene (repeatable)\n"
            "  --method NAME  run only this method (repeatable)\n"
            "  --list         list the scenes and methods, then exit\n"
            "  --help         this text\n"
            "Exit status: 0 ok, 1 a solve returned an error status, 2 usage error.\n",
            BENCH_CSV_HEADER);
}

static void bench_list_names(FILE *out, int scenes)
{
    int i;
    if (scenes)
        for (i = 0; i < BENCH_SCENE_COUNT; ++i) fprintf(out, "%s%s", i ? ", " : "", bench_scenes[i].name);
    else
        for (i = 0; i < bench_method_count; ++i) fprintf(out, "%s%s", i ? ", " : "", bench_methods[i].name);
    fprintf(out, "\n");
}

static void bench_list(void)
{
    int i;
    printf("scenes:\n");
    for (i = 0; i < BENCH_SCENE_COUNT; ++i)
        printf("  %-12s %s\n", bench_scenes[i].name, bench_scenes[i].description);
    printf("methods:\n");
    for (i = 0; i < bench_method_count; ++i) {
        printf("  %-16s %s", bench_methods[i].name, bench_kind_name(bench_methods[i].kind));
        if (bench_methods[i].order > 0) printf(", order %g", bench_methods[i].order);
        printf("\n");
    }
    printf("warps:\n");
    for (i = 0; i < BENCH_WARP_COUNT; ++i) printf("  %s\n", bench_warps[i].name);
}

/* Returns 0, or 2 after printing the error. */
static int bench_parse(int argc, char **argv, bench_config *cfg)
{
    int i, k;
    memset(cfg, 0, sizeof *cfg);
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *value = NULL;
        int is_scene = 0, is_method = 0;
        if (!strcmp(a, "--csv")) cfg->csv = 1;
        else if (!strcmp(a, "--quick")) cfg->quick = 1;
        else if (!strcmp(a, "--list")) cfg->list = 1;
        else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            bench_usage(stdout);
            exit(0);
        } else if (!strcmp(a, "--scene") || !strcmp(a, "--method")) {
            is_scene = a[2] == 's';
            is_method = !is_scene;
            if (i + 1 >= argc) {
                fprintf(stderr, "bench: %s needs a name\n", a);
                bench_usage(stderr);
                return 2;
            }
            value = argv[++i];
        } else if (!strncmp(a, "--scene=", 8)) {
            is_scene = 1;
            value = a + 8;
        } else if (!strncmp(a, "--method=", 9)) {
            is_method = 1;
            value = a + 9;
        } else {
            fprintf(stderr, "bench: unknown option '%s'\n", a);
            bench_usage(stderr);
            return 2;
        }
        if (is_scene) {
            for (k = 0; k < BENCH_SCENE_COUNT && strcmp(value, bench_scenes[k].name); ++k) {}
            if (k == BENCH_SCENE_COUNT) {
                fprintf(stderr, "bench: unknown scene '%s'; valid scenes: ", value);
                bench_list_names(stderr, 1);
                return 2;
            }
            cfg->scene_on[k] = cfg->any_scene = 1;
        }
        if (is_method) {
            for (k = 0; k < bench_method_count && strcmp(value, bench_methods[k].name); ++k) {}
            if (k == bench_method_count) {
                fprintf(stderr, "bench: unknown method '%s'; valid methods: ", value);
                bench_list_names(stderr, 0);
                return 2;
            }
            cfg->method_on[k] = cfg->any_method = 1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    static bench_totals tot;
    bench_config cfg;
    ref_rule rule;
    const int *steps = bench_steps_full;
    int nsteps = (int)(sizeof bench_steps_full / sizeof bench_steps_full[0]);
    int si, v = hrm_version();
    double start = bench_seconds();

    bench_methods_init();
    if (bench_parse(argc, argv, &cfg)) return 2;
    if (cfg.list) {
        bench_list();
        return 0;
    }
    if (cfg.quick) {
        steps = bench_steps_quick;
        nsteps = (int)(sizeof bench_steps_quick / sizeof bench_steps_quick[0]);
    }
    ref_rule_init(&rule);

    if (cfg.csv) {
        printf("%s\n", BENCH_CSV_HEADER);
    } else {
        printf("hrm.h %d.%d.%d single-ray benchmark, N = %d..%d (doubling), warp none\n",
               v / 10000, v / 100 % 100, v % 100, steps[0], steps[nsteps - 1]);
        printf("rel_error: |L - Lref| / max(|L|, |Lref|) (Munoz 2014), worst of %d channels;\n"
               "  monte-carlo: RMS over seeds 1..%d (evals and ns_per_ray are per ray)\n"
               "evals: source (Li/Le) evaluations; medium_evals: sigma/transmittance evaluations\n"
               "ns_per_ray: median of %d batches of repeated solves, each >= %g ms "
               "(CLOCK_MONOTONIC)\n",
               HRM_CHANNELS, BENCH_SEEDS, BENCH_TIMINGS, BENCH_BATCH_SECONDS * 1e3);
    }
    for (si = 0; si < BENCH_SCENE_COUNT; ++si) {
        if (cfg.any_scene && !cfg.scene_on[si]) continue;
        bench_run_scene(&cfg, si, &rule, steps, nsteps, &tot);
    }
    if (!cfg.csv) {
        bench_print_fits(tot.fits, tot.nfits);
        printf("\nevaluation counts: hrm's stats %s the callbacks made in %ld solves",
               bench_count_mismatches ? "disagree with" : "match", tot.solves);
        if (bench_count_mismatches) printf(" (%ld mismatches, see stderr)", bench_count_mismatches);
        printf("\nrows with an error status: %d\n", tot.errors);
        printf("run time: %.1f s\n", bench_seconds() - start);
    } else if (bench_count_mismatches) {
        fprintf(stderr, "bench: %ld solves with evaluation counts that disagree with the callbacks\n",
                bench_count_mismatches);
    }
    return tot.errors ? 1 : 0;
}
