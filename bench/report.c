/* bench/report.c - the benchmark's tables: per scene on stdout as the
   sweeps finish, then the summaries on stdout and in two markdown files,
   and bench.csv.

   summary.md holds what is the same on every run of the same build (errors,
   evaluation counts, orders); timing.md holds every machine-dependent
   number (the overhead tables, the fastest method per target). Nothing here
   measures: it reads bench_state. */

#include "bench.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

const double bench_targets[BENCH_TARGETS] = {1e-2, 1e-4, 1e-6};

/* ------------------------------------------------------------------------ */
/* Output helpers                                                           */
/* ------------------------------------------------------------------------ */

static void bench_both(const bench_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* A line to stdout and, when o->md is set, to the markdown file too. */
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

static char bench_flag(hrm_status s)
{
    return s < 0 ? '!' : s > 0 ? '*' : ' ';
}

/* N as an integer, rtol as a power of ten. */
static const char *bench_param_str(const bench_method *me, double param, char *buf, size_t n)
{
    if (bench_is_swept_over_n(me)) snprintf(buf, n, "%.0f", param);
    else snprintf(buf, n, "%.0e", param);
    return buf;
}

/* How many ways the scene's medium was given in the sweeps (1 or 2): the
   tables show the medium where there are two. */
static int bench_scene_nmedia(const bench_state *st, int si)
{
    int seen[BENCH_MEDIUM_COUNT] = {0}, i, n = 0;
    for (i = 0; i < st->nsweeps; ++i)
        if (st->sweeps[i].scene == si) seen[st->sweeps[i].medium] = 1;
    for (i = 0; i < BENCH_MEDIUM_COUNT; ++i) n += seen[i];
    return n;
}

/* "method, warp[, medium] (N or rtol)" */
static void bench_row_label(const bench_state *st, const bench_row *r, char *buf, size_t n)
{
    const bench_method *me = &st->methods[r->method];
    char p[24];
    int media = bench_scene_nmedia(st, r->scene) > 1;
    snprintf(buf, n, "%s, %s%s%s (%s%s)", me->name, bench_warp_names[r->warp], media ? ", " : "",
             media ? bench_medium_names[r->medium] : "", bench_is_swept_over_n(me) ? "N " : "rtol ",
             bench_param_str(me, r->param, p, sizeof p));
}

/* ------------------------------------------------------------------------ */
/* Tables: aligned on stdout, markdown in the summary                       */
/* ------------------------------------------------------------------------ */

#define BENCH_TCOLS 12
#define BENCH_TCELL 64

typedef struct bench_table {
    int ncols, nrows, cap;
    char (*cell)[BENCH_TCOLS][BENCH_TCELL]; /* row 0 is the header */
} bench_table;

static void bench_table_init(bench_table *t, int ncols)
{
    t->ncols = ncols < BENCH_TCOLS ? ncols : BENCH_TCOLS;
    t->nrows = t->cap = 0;
    t->cell = NULL;
}

/* Appends an empty row; cells are filled with bench_table_cell. */
static void bench_table_row(bench_table *t)
{
    if (t->nrows == t->cap) {
        void *p;
        t->cap = t->cap ? 2 * t->cap : 32;
        p = realloc(t->cell, (size_t)t->cap * sizeof *t->cell);
        if (!p) {
            fprintf(stderr, "bench: out of memory\n");
            exit(BENCH_EXIT_OUTPUT);
        }
        t->cell = (char (*)[BENCH_TCOLS][BENCH_TCELL])p;
    }
    memset(t->cell[t->nrows], 0, sizeof *t->cell);
    t->nrows++;
}

static void bench_table_cell(bench_table *t, int col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void bench_table_cell(bench_table *t, int col, const char *fmt, ...)
{
    va_list ap;
    if (t->nrows == 0 || col >= BENCH_TCOLS) return;
    va_start(ap, fmt);
    vsnprintf(t->cell[t->nrows - 1][col], BENCH_TCELL, fmt, ap);
    va_end(ap);
}

/* Prints the table and frees its cells. */
static void bench_table_emit(bench_table *t, const bench_out *o)
{
    int w[BENCH_TCOLS], r, c;
    for (c = 0; c < t->ncols; ++c) {
        w[c] = 0;
        for (r = 0; r < t->nrows; ++r) {
            int l = (int)strlen(t->cell[r][c]);
            if (l > w[c]) w[c] = l;
        }
    }
    if (!o->quiet)
        for (r = 0; r < t->nrows; ++r) {
            printf(" ");
            for (c = 0; c < t->ncols; ++c)
                printf(" %-*s", c + 1 < t->ncols ? w[c] + 1 : 0, t->cell[r][c]);
            printf("\n");
        }
    if (o->md) {
        for (r = 0; r < t->nrows; ++r) {
            fprintf(o->md, "|");
            for (c = 0; c < t->ncols; ++c) fprintf(o->md, " %s |", t->cell[r][c]);
            fprintf(o->md, "\n");
            if (r == 0) {
                fprintf(o->md, "|");
                for (c = 0; c < t->ncols; ++c) fprintf(o->md, "---|");
                fprintf(o->md, "\n");
            }
        }
        fprintf(o->md, "\n");
    }
    free(t->cell);
    t->cell = NULL;
    t->nrows = t->cap = 0;
}

/* ------------------------------------------------------------------------ */
/* The run's header and each scene's tables (stdout)                        */
/* ------------------------------------------------------------------------ */

void bench_report_header(const bench_state *st)
{
    const bench_config *cfg = &st->cfg;
    int v = hrm_version();
    if (cfg->csv) {
        printf("%s\n", BENCH_CSV_HEADER);
        return;
    }
    printf("hrm.h %d.%d.%d single-ray benchmark: fixed-step methods over N = %g..%g, "
           "adaptive methods over rtol = %g..%g\n",
           v / 10000, v / 100 % 100, v % 100, cfg->steps[0], cfg->steps[cfg->nsteps - 1],
           cfg->tols[0], cfg->tols[cfg->ntols - 1]);
    printf("rel_error: |L - Lref| / max(|L|, |Lref|) (Munoz 2014), worst of %d channels;\n"
           "  monte-carlo: RMS over seeds 1..%d (evals and ns_per_ray are per ray)\n"
           "evals: source (Li/Le) evaluations; medium_evals: sigma/transmittance "
           "evaluations\n"
           "medium: const = homogeneous constants (HRM_MEDIUM_HOMOGENEOUS, closed-form Tr);\n"
           "  sigma = sigma_a/sigma_s callbacks (for a homogeneous scene: the same constants)\n"
           "adaptive methods: hrm defaults but rtol, max_evals = %ld and control %s\n"
           "ns_per_ray: ",
           HRM_CHANNELS, cfg->seeds, BENCH_MAX_EVALS, bench_control_name(cfg->control));
    if (cfg->timed)
        printf("median of %d batches of repeated solves, each >= %g ms (CLOCK_MONOTONIC)\n",
               st->timings, st->batch_seconds * 1e3);
    else
        printf("not measured (--no-timing)\n");
}

static void bench_reference_print(const bench_scene *sc, const bench_reference *ref)
{
    int i;
    printf("  reference L = (%.19Lg, %.19Lg, %.19Lg)\n", ref->L[0], ref->L[1], ref->L[2]);
    if (sc->closed_form) {
        printf("    closed form in long double; an independent %d-point Gauss-Legendre "
               "quadrature agrees to %.1Le\n",
               REF_GL_POINTS, ref->accuracy);
        return;
    }
    printf("    %d-point Gauss-Legendre panels in long double", REF_GL_POINTS);
    if (ref->nsplits) {
        printf(", split at s =");
        for (i = 0; i < ref->nsplits; ++i) printf("%s %.19Lg", i ? "," : "", ref->splits[i]);
    }
    printf("\n    estimated relative accuracy %.1Le (panels <= %Lg vs <= %Lg)\n", ref->accuracy,
           ref->panel, ref->panel / 2);
}

/* One matrix per kind of sweep: rows method x warp (x medium), columns the
   parameter; value 0: rel_error, 1: evals, 2: medium evaluations (the
   sweeps whose medium is given by callbacks). */
static void bench_print_matrix(const bench_state *st, int si, int adaptive, int value)
{
    const bench_config *cfg = &st->cfg;
    const double *params = adaptive ? cfg->tols : cfg->steps;
    int n = adaptive ? cfg->ntols : cfg->nsteps, i, k, any = 0;
    int media = bench_scene_nmedia(st, si) > 1;
    for (i = 0; i < st->nsweeps; ++i) {
        const bench_sweep *sw = &st->sweeps[i];
        const bench_method *me = &st->methods[sw->method];
        if (sw->scene != si || (me->kind == BENCH_ADAPTIVE) != adaptive) continue;
        if (value == 2 && sw->medium == BENCH_MEDIUM_CONST) continue;
        if (!any) {
            printf("  %s\n  %-22s %-11s",
                   value == 2 ? (adaptive ? "adaptive methods: medium (sigma) evaluations by rtol"
                                          : "fixed-step methods: medium (sigma) evaluations by N")
                   : adaptive ? (value ? "adaptive methods: evaluations by rtol"
                                       : "adaptive methods: achieved rel_error "
                                         "by rtol (Munoz 2014 Fig. 4, "
                                         "columns 4-5)")
                              : "fixed-step methods: rel_error by N "
                                "(monte-carlo: RMS over seeds)",
                   "method", "warp");
            if (media) printf(" %-6s", "medium");
            for (k = 0; k < n; ++k) {
                if (adaptive) printf(" %8.0e", params[k]);
                else printf(" %8.0f", params[k]);
            }
            printf("\n");
            any = 1;
        }
        printf("  %-22s %-11s", me->name, bench_warp_names[sw->warp]);
        if (media) printf(" %-6s", bench_medium_names[sw->medium]);
        for (k = 0; k < sw->count; ++k) {
            const bench_row *r = &st->rows[sw->first + k];
            if (value == 2) printf(" %7ld%c", r->stats.medium_evals, bench_flag(r->status));
            else if (value) printf(" %7ld%c", r->stats.evals, bench_flag(r->status));
            else if (r->status < 0 || !bench_finite(r->rel_error)) printf(" %8s", "error!");
            else printf(" %7.1e%c", r->rel_error, bench_flag(r->status));
        }
        printf("\n");
    }
}

void bench_report_scene(const bench_state *st, int si)
{
    const bench_scene *sc = &bench_scenes[si];
    bench_warp_id warps[BENCH_WARP_COUNT];
    bench_medium_id media[BENCH_MEDIUM_COUNT];
    int nw = bench_scene_warps(&st->cfg, sc, warps), nm = bench_scene_media(&st->cfg, si, media);
    int wi;
    if (st->cfg.csv) {
        int i;
        for (i = 0; i < st->nrows; ++i)
            if (st->rows[i].scene == si) bench_report_csv_row(stdout, st, &st->rows[i]);
        fflush(stdout);
        return;
    }
    printf("\n== scene %s: %s\n", sc->name, sc->description);
    printf("  ray t0 = %g, t1 = %g; %s\n", sc->t0, sc->t1,
           sc->smooth ? "smooth integrand" : "integrand with jumps (shadow edges)");
    sc->print_params(stdout, sc->params);
    bench_reference_print(sc, &st->refs[si]);
    printf("  warps:");
    for (wi = 0; wi < nw; ++wi) {
        hrm_options o;
        bench_warp_apply(sc, warps[wi], &o);
        printf("%s %s", wi ? "," : "", bench_warp_names[warps[wi]]);
        if (warps[wi] == BENCH_WARP_DISTANCE) printf(" (sigma_ref 0: hrm's choice, the mean extinction over the ray)");
        if (warps[wi] == BENCH_WARP_EQUIANGULAR)
            printf(" (delta = %g, D = %g, from hrm_equiangular_warp)", (double)o.warp.delta,
                   (double)o.warp.D);
    }
    printf("\n  medium given as:%s", nm ? "" : " none (--medium leaves no way for this scene)");
    for (wi = 0; wi < nm; ++wi)
        printf("%s %s", wi ? "," : "",
               media[wi] == BENCH_MEDIUM_CONST ? "const (HRM_MEDIUM_HOMOGENEOUS)"
               : nm > 1 ? "sigma (the same constants through sigma_a/sigma_s callbacks)"
                        : "sigma (callbacks)");
    printf("\n");
    bench_print_matrix(st, si, 0, 0);
    bench_print_matrix(st, si, 1, 0);
    bench_print_matrix(st, si, 1, 1);
    bench_print_matrix(st, si, 0, 2);
    bench_print_matrix(st, si, 1, 2);
    printf("  (* a warning status: the budget of %ld evaluations, h_min or storage ran out, "
           "best estimate shown; ! an error status)\n",
           BENCH_MAX_EVALS);
    fflush(stdout);
}

/* ------------------------------------------------------------------------ */
/* CSV                                                                      */
/* ------------------------------------------------------------------------ */

void bench_report_csv_row(FILE *f, const bench_state *st, const bench_row *r)
{
    fprintf(f, "%s,%s,%s,%s,%g,%ld,%ld,%ld,%ld,%.6e,%d,%.1f,%.3e\n", bench_scenes[r->scene].name,
            st->methods[r->method].name, bench_warp_names[r->warp],
            bench_medium_names[r->medium], r->param, r->stats.evals, r->stats.medium_evals,
            r->stats.steps, r->stats.rejected, r->rel_error, (int)r->status, r->ns_per_ray,
            r->est_error);
}

FILE *bench_open(const char *dir, const char *name, char *path, size_t n)
{
    FILE *f;
    snprintf(path, n, "%s/%s", dir, name);
    f = fopen(path, "w");
    if (!f) fprintf(stderr, "bench: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

int bench_close(FILE *f, const char *path)
{
    int bad = ferror(f);
    if (fclose(f) != 0 || bad) {
        fprintf(stderr, "bench: error writing %s\n", path);
        return -1;
    }
    return 0;
}

int bench_write_csv(const bench_state *st, const char *dir)
{
    char path[1200];
    FILE *f = bench_open(dir, "bench.csv", path, sizeof path);
    int i;
    if (!f) return -1;
    fprintf(f, "%s\n", BENCH_CSV_HEADER);
    for (i = 0; i < st->nrows; ++i) bench_report_csv_row(f, st, &st->rows[i]);
    return bench_close(f, path);
}

/* ------------------------------------------------------------------------ */
/* Fitted orders (stdout)                                                   */
/* ------------------------------------------------------------------------ */

static void bench_order_cell(bench_table *t, int col, const bench_sweep *sw)
{
    char a[16], b[16];
    if (!sw) {
        bench_table_cell(t, col, "-");
        return;
    }
    bench_fmt_order(a, sizeof a, sw->order);
    bench_fmt_order(b, sizeof b, sw->tail);
    bench_table_cell(t, col, "%s (%s)", a, b);
}

void bench_report_orders(const bench_state *st)
{
    int si, mi, w, col, k;
    bench_out o = {NULL, 0};
    if (st->cfg.csv) return;
    printf("\n== Fitted convergence order of the fixed-step methods: -(least-squares slope of\n"
           "log rel_error vs log evals) over the N whose error is above %g; in parentheses\n"
           "over the finest %d of them only (the asymptotic order). Nominal:",
           BENCH_FIT_FLOOR, BENCH_TAIL);
    for (mi = 0; mi < st->nmethods; ++mi)
        if (bench_is_swept_over_n(&st->methods[mi]))
            printf(" %s %g%s", st->methods[mi].name, st->methods[mi].order,
                   mi + 1 < st->nmethods && bench_is_swept_over_n(&st->methods[mi + 1]) ? ","
                                                                                       : "");
    printf(".\n");
    for (w = 0; w < 2; ++w) {
        bench_table t;
        int nc = 3;
        bench_table_init(&t, BENCH_TCOLS);
        bench_table_row(&t);
        bench_table_cell(&t, 0, "scene");
        bench_table_cell(&t, 1, "warp");
        bench_table_cell(&t, 2, "medium");
        for (mi = 0; mi < st->nmethods; ++mi)
            if (bench_is_swept_over_n(&st->methods[mi]) && bench_method_selected(st, mi) &&
                nc < BENCH_TCOLS)
                bench_table_cell(&t, nc++, "%s", st->methods[mi].name);
        t.ncols = nc;
        for (si = 0; si < bench_scene_count; ++si) {
            bench_warp_id wid = w ? bench_scenes[si].natural_warp : BENCH_WARP_NONE;
            for (k = 0; k < BENCH_MEDIUM_COUNT; ++k) {
                int found = 0;
                for (mi = 0; mi < st->nmethods; ++mi)
                    found |= bench_is_swept_over_n(&st->methods[mi]) &&
                             bench_find_sweep(st, si, mi, wid, (bench_medium_id)k) != NULL;
                if (!found) continue;
                bench_table_row(&t);
                bench_table_cell(&t, 0, "%s", bench_scenes[si].name);
                bench_table_cell(&t, 1, "%s", bench_warp_names[wid]);
                bench_table_cell(&t, 2, "%s", bench_medium_names[k]);
                col = 3;
                for (mi = 0; mi < st->nmethods; ++mi)
                    if (bench_is_swept_over_n(&st->methods[mi]) && bench_method_selected(st, mi) &&
                        col < BENCH_TCOLS)
                        bench_order_cell(&t, col++,
                                         bench_find_sweep(st, si, mi, wid, (bench_medium_id)k));
            }
        }
        if (t.nrows > 1) printf("%s\n", w ? "natural warp:" : "no warp:");
        if (t.nrows > 1) bench_table_emit(&t, &o);
        else free(t.cell);
    }
    printf("(a sharp shadow, as in occluder, drags every fixed-step method to first order)\n");
}

/* ------------------------------------------------------------------------ */
/* Tolerance proportionality (adaptive methods)                             */
/* ------------------------------------------------------------------------ */

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
    double warned_est;   /* that row's own estimate of it (result.error) / rtol */
    int errors;          /* rows with an error status */
} bench_prop;

static int bench_status_ok(hrm_status s)
{
    return s == HRM_OK || s == HRM_WARN_RTOL_CLIPPED;
}

/* achieved / rtol over the smooth scenes' rows of one adaptive method;
   group 0: no warp, 1: the scenes' natural warps; scene >= 0: that scene
   alone (smooth or not); medium >= 0: that way of giving it alone. */
static void bench_prop_collect(const bench_state *st, int mi, int group, int scene, int medium,
                               bench_prop *p)
{
    double v[1024];
    int i, k, n = 0;
    memset(p, 0, sizeof *p);
    p->lo = p->med = p->hi = p->warned_hi = p->warned_est = (double)NAN;
    for (i = 0; i < st->nsweeps; ++i) {
        const bench_sweep *sw = &st->sweeps[i];
        const bench_scene *sc = &bench_scenes[sw->scene];
        if (sw->method != mi || (sw->warp != BENCH_WARP_NONE) != group) continue;
        if (scene >= 0 ? sw->scene != scene : !sc->smooth) continue;
        if (medium >= 0 && (int)sw->medium != medium) continue;
        for (k = 0; k < sw->count; ++k) {
            const bench_row *r = &st->rows[sw->first + k];
            double q;
            if (r->status < 0 || !bench_finite(r->rel_error)) {
                p->errors++;
                continue;
            }
            q = r->rel_error / r->param;
            if (!bench_status_ok(r->status)) {
                if (!p->warned || q > p->warned_hi) {
                    p->warned_hi = q;
                    p->warned_est = r->est_error / r->param;
                }
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

/* "max [worst warned] error!" of one scene and medium, into buf. */
static void bench_prop_cell(const bench_prop *p, char *buf, size_t n)
{
    char a[24] = "-", b[40] = "";
    if (p->rows) snprintf(a, sizeof a, "%.2g (%.2g)", p->hi, p->med);
    if (p->warned && (!p->rows || p->warned_hi > p->hi))
        snprintf(b, sizeof b, " [%.2g]", p->warned_hi);
    if (p->errors) snprintf(b + strlen(b), sizeof b - strlen(b), " error!");
    snprintf(buf, n, "%s%s", a, b);
}

static void bench_report_proportionality(const bench_state *st, const bench_out *o)
{
    const bench_config *cfg = &st->cfg;
    int mi, g, si, any = 0, nc;
    bench_table t;
    for (mi = 0; mi < st->nmethods; ++mi)
        any |= st->methods[mi].kind == BENCH_ADAPTIVE && bench_method_selected(st, mi);
    if (!any || !cfg->ntols) return;
    bench_section(o, "Tolerance proportionality of the adaptive methods");
    bench_both(o, "achieved rel_error / rtol on the smooth scenes (all but occluder), every medium, "
                  "rtol = %.0e..%.0e, control %s, budget %ld evaluations.\n"
                  "Goal: a median in [0.01, 1] (no effort wasted) and at most 3 over the runs "
                  "that returned HRM_OK (rtol means the error you get), on both medium paths.\n"
                  "rows: runs that returned HRM_OK, over which min/median/max are taken and "
                  ">1, >10, <0.1 counted; warned: runs that returned a warning (budget, h_min, "
                  "storage: the method reports it missed rtol), with their largest ratio and, "
                  "in brackets, that run's own estimate of its miss (result.error / |L|) over rtol.\n\n",
               cfg->tols[0], cfg->tols[cfg->ntols - 1], bench_control_name(cfg->control),
               BENCH_MAX_EVALS);
    bench_table_init(&t, 12);
    bench_table_row(&t);
    bench_table_cell(&t, 0, "method");
    bench_table_cell(&t, 1, "warp");
    bench_table_cell(&t, 2, "medium");
    bench_table_cell(&t, 3, "rows");
    bench_table_cell(&t, 4, "min");
    bench_table_cell(&t, 5, "median");
    bench_table_cell(&t, 6, "max");
    bench_table_cell(&t, 7, ">1");
    bench_table_cell(&t, 8, ">10");
    bench_table_cell(&t, 9, "<0.1");
    bench_table_cell(&t, 10, "warned");
    bench_table_cell(&t, 11, "worst warned (its estimate)");
    for (mi = 0; mi < st->nmethods; ++mi) {
        int md;
        if (st->methods[mi].kind != BENCH_ADAPTIVE || !bench_method_selected(st, mi)) continue;
        for (g = 0; g < 2; ++g)
            for (md = 0; md < BENCH_MEDIUM_COUNT; ++md) {
                bench_prop p;
                bench_prop_collect(st, mi, g, -1, md, &p);
                if (!p.rows && !p.warned && !p.errors) continue;
                bench_table_row(&t);
                bench_table_cell(&t, 0, "%s", st->methods[mi].name);
                bench_table_cell(&t, 1, "%s", g ? "natural" : "none");
                bench_table_cell(&t, 2, "%s", bench_medium_names[md]);
                bench_table_cell(&t, 3, "%d", p.rows);
                bench_table_cell(&t, 4, "%.2g", p.lo);
                bench_table_cell(&t, 5, "%.2g", p.med);
                bench_table_cell(&t, 6, "%.2g", p.hi);
                bench_table_cell(&t, 7, "%d", p.above1);
                bench_table_cell(&t, 8, "%d", p.above10);
                bench_table_cell(&t, 9, "%d", p.below01);
                bench_table_cell(&t, 10, "%d", p.warned);
                if (p.warned) bench_table_cell(&t, 11, "%.2g (%.2g)", p.warned_hi, p.warned_est);
                else bench_table_cell(&t, 11, "-");
            }
    }
    bench_table_emit(&t, o);

    for (g = 0; g < 2; ++g) {
        bench_both(o, "Largest achieved/rtol per scene over the runs that returned HRM_OK, %s, "
                      "with the median in parentheses (in brackets: the largest over runs that "
                      "returned a warning, where it is larger; two values: medium as constants / "
                      "as sigma callbacks):\n\n",
                   g ? "natural warp" : "no warp");
        bench_table_init(&t, BENCH_TCOLS);
        bench_table_row(&t);
        bench_table_cell(&t, 0, "method");
        nc = 1;
        for (si = 0; si < bench_scene_count && nc < BENCH_TCOLS; ++si)
            if (bench_scene_selected(cfg, si))
                bench_table_cell(&t, nc++, "%s%s", bench_scenes[si].name,
                                 bench_scenes[si].smooth ? "" : " (jumps)");
        t.ncols = nc;
        for (mi = 0; mi < st->nmethods; ++mi) {
            int col = 1;
            if (st->methods[mi].kind != BENCH_ADAPTIVE || !bench_method_selected(st, mi)) continue;
            bench_table_row(&t);
            bench_table_cell(&t, 0, "%s", st->methods[mi].name);
            for (si = 0; si < bench_scene_count && col < BENCH_TCOLS; ++si) {
                char cells[BENCH_MEDIUM_COUNT][64];
                int k, nk = 0;
                if (!bench_scene_selected(cfg, si)) continue;
                for (k = 0; k < BENCH_MEDIUM_COUNT; ++k) {
                    bench_prop p;
                    bench_prop_collect(st, mi, g, si, k, &p);
                    if (!p.rows && !p.warned && !p.errors) continue;
                    bench_prop_cell(&p, cells[nk++], sizeof cells[0]);
                }
                if (nk == 2) bench_table_cell(&t, col++, "%s / %s", cells[0], cells[1]);
                else bench_table_cell(&t, col++, "%s", nk ? cells[0] : "-");
            }
        }
        bench_table_emit(&t, o);
    }
}

/* ------------------------------------------------------------------------ */
/* Equiangular gain, transmittance                                          */
/* ------------------------------------------------------------------------ */

static void bench_report_equiangular(const bench_state *st, const bench_out *o)
{
    const bench_equi *eq = &st->equi;
    bench_table t;
    int i, k;
    if (eq->scene < 0) return;
    bench_section(o, "Equiangular sampling on the point scene");
    bench_both(o, "error(no warp) / error(equiangular) at equal N (above 1: equiangular helps), "
                  "medium as constants; monte-carlo: RMS over seeds 1..%d.\n\n",
               st->cfg.seeds);
    bench_table_init(&t, 1 + BENCH_SECTION_PARAMS);
    bench_table_row(&t);
    bench_table_cell(&t, 0, "method");
    for (k = 0; k < BENCH_SECTION_PARAMS; ++k) bench_table_cell(&t, 1 + k, "N = %.0f", bench_section_steps[k]);
    for (i = 0; i < eq->n; ++i) {
        bench_table_row(&t);
        bench_table_cell(&t, 0, "%s", st->methods[eq->method[i]].name);
        for (k = 0; k < BENCH_SECTION_PARAMS; ++k) {
            if (bench_finite(eq->ratio[i][k])) bench_table_cell(&t, 1 + k, "%.3g", eq->ratio[i][k]);
            else bench_table_cell(&t, 1 + k, "n/a");
        }
    }
    bench_table_emit(&t, o);
}

static void bench_report_breaks(const bench_state *st, const bench_out *o)
{
    static const char *const heads[3] = {"without", "with breakpoints", "jump search"};
    int bi, i, w, any = 0;
    for (bi = 0; bi < BENCH_BRK_SCENES; ++bi) any |= st->brk[bi].scene >= 0;
    if (!any) return;
    bench_section(o, "Breakpoints: shadow edges and medium boundaries");
    bench_both(o, "The fewest evaluations from which a sweep stays within a relative error of 1e-2 / "
                  "1e-4 / 1e-6 (- : not reached in the sweep): without breakpoints or the jump "
                  "search (find_jumps = -1), with options.breaks set to the scene's jumps, and with "
                  "the jump search alone (find_jumps = 1: every method scans the medium for jumps, "
                  "nested Simpson and global Gauss-Kronrod also search the source; the default, 0, "
                  "is the same except that fixed-step methods do not scan). Fixed-step methods over "
                  "N, adaptive ones over rtol.\n\n");
    for (bi = 0; bi < BENCH_BRK_SCENES; ++bi) {
        const bench_brk *b = &st->brk[bi];
        bench_table t;
        if (b->scene < 0) continue;
        bench_both(o, "%s: breakpoints at %.9g, %.9g%s.\n\n", bench_scenes[b->scene].name,
                   b->nbreaks > 0 ? b->breaks[0] : (double)NAN, b->nbreaks > 1 ? b->breaks[1] : (double)NAN,
                   bi == 0 ? " (hrm_sphere_breaks)" : " (the slab's faces)");
        bench_table_init(&t, 6);
        bench_table_row(&t);
        bench_table_cell(&t, 0, "method");
        bench_table_cell(&t, 1, "warp");
        bench_table_cell(&t, 2, "medium");
        for (w = 0; w < 3; ++w) bench_table_cell(&t, 3 + w, "%s", heads[w]);
        for (i = 0; i < b->n; ++i) {
            const bench_brk_row *r = &b->rows[i];
            bench_table_row(&t);
            bench_table_cell(&t, 0, "%s", st->methods[r->method].name);
            bench_table_cell(&t, 1, "%s", bench_warp_names[r->warp]);
            bench_table_cell(&t, 2, "%s", bench_medium_names[r->medium]);
            for (w = 0; w < 3; ++w) {
                char part[3][24];
                int k;
                for (k = 0; k < 3; ++k) {
                    if (r->fewest[w][k] < 0) snprintf(part[k], sizeof part[k], "-");
                    else snprintf(part[k], sizeof part[k], "%ld", r->fewest[w][k]);
                }
                bench_table_cell(&t, 3 + w, "%s / %s / %s", part[0], part[1], part[2]);
            }
        }
        bench_table_emit(&t, o);
    }
}

static void bench_report_transmittance(const bench_state *st, const bench_out *o)
{
    static const char *const heads[BENCH_TRANS_COLS] = {
        "(a) point, const", "(b) point, sigma", "(c) smoke, default", "(d) smoke, coupled",
        "(e) smoke, exact Tr"};
    const bench_trans *tr = &st->trans;
    bench_table t;
    int i, col;
    if (tr->point < 0 && tr->smoke < 0) return;
    bench_section(o, "Transmittance: the error that tau adds");
    bench_both(o,
               "rel_error of L with the equiangular warp; fixed-step methods at N = %.0f, %.0f, "
               "%.0f, adaptive ones at rtol = %.0e, %.0e, %.0e; monte-carlo: RMS over seeds "
               "1..%d; * a warning status, ! an error.\n"
               "(a) point scene, homogeneous medium as constants: Tr in closed form, no tau "
               "to integrate.\n"
               "(b) point scene, the same sigma through sigma_a/sigma_s callbacks: hrm "
               "integrates a constant sigma_t (b = a when that costs nothing).\n"
               "(c) smoke scene (sigma varies +-50%% along the ray), tau_mode 0, each method's "
               "default: the transmittance layer (medium-only samples placed for tau by their "
               "own control, tau_tol default); for the rectangle rule, Monte Carlo and Euler, "
               "the stream (tau from sigma_t at their nodes and at most 16 extra samples in t "
               "where the warp leaves the nodes sparsest: 2N + 8 sigma samples at most).\n"
               "(d) smoke scene, tau_mode = HRM_TAU_COUPLED: tau from the sigma_t samples at "
               "the source abscissae, as the papers do.\n"
               "(e) smoke scene with its exact Tr(ta, tb) as the medium's transmittance "
               "callback: the error of the source quadrature alone, the floor for (c) and "
               "(d).\n"
               "evals and medium_evals are those of (c) (Monte Carlo: seed 1): its cost in "
               "shadow rays and in sigma evaluations.\n\n",
               bench_section_steps[0], bench_section_steps[1], bench_section_steps[2],
               bench_section_tols[0], bench_section_tols[1], bench_section_tols[2], st->cfg.seeds);
    bench_table_init(&t, 3 + BENCH_TRANS_COLS + 1);
    bench_table_row(&t);
    bench_table_cell(&t, 0, "method");
    bench_table_cell(&t, 1, "N or rtol");
    for (col = 0; col < BENCH_TRANS_COLS; ++col) bench_table_cell(&t, 2 + col, "%s", heads[col]);
    bench_table_cell(&t, 2 + BENCH_TRANS_COLS, "evals (c)");
    bench_table_cell(&t, 3 + BENCH_TRANS_COLS, "medium_evals (c)");
    for (i = 0; i < tr->n; ++i) {
        const bench_trans_row *r = &tr->rows[i];
        const bench_method *me = &st->methods[r->method];
        char p[24];
        bench_table_row(&t);
        /* the method's name on its first row only: one block per method */
        if (i == 0 || tr->rows[i - 1].method != r->method) bench_table_cell(&t, 0, "%s", me->name);
        bench_table_cell(&t, 1, "%s", bench_param_str(me, r->param, p, sizeof p));
        for (col = 0; col < BENCH_TRANS_COLS; ++col) {
            if (!r->ran[col]) bench_table_cell(&t, 2 + col, "-");
            else if (r->status[col] < 0 || !bench_finite(r->err[col]))
                bench_table_cell(&t, 2 + col, "error!");
            else
                bench_table_cell(&t, 2 + col, "%.1e%s", r->err[col],
                                 r->status[col] > 0 ? "*" : "");
        }
        if (r->ran[2]) {
            bench_table_cell(&t, 2 + BENCH_TRANS_COLS, "%ld", r->stats_c.evals);
            bench_table_cell(&t, 3 + BENCH_TRANS_COLS, "%ld", r->stats_c.medium_evals);
        } else {
            bench_table_cell(&t, 2 + BENCH_TRANS_COLS, "-");
            bench_table_cell(&t, 3 + BENCH_TRANS_COLS, "-");
        }
    }
    bench_table_emit(&t, o);
}

/* Early ray termination on sigma callbacks: per scene, method and rtol,
   the costs and errors without and with options.cutoff. */
static void bench_report_cutoff(const bench_state *st, const bench_out *o)
{
    const bench_cut *cu = &st->cut;
    int i, c, scene = -1;
    bench_table t;
    if (!cu->n) return;
    bench_section(o, "Early ray termination on sigma callbacks");
    bench_both(o,
               "options.cutoff = %.0e against none, the medium through sigma callbacks, no warp: "
               "the medium scan ends the ray at its first sample whose trapezoid tau passes "
               "ln(1 / cutoff) in every channel (t_cut). Errors against the whole ray's "
               "reference (what the cut drops included), with the method's own estimate "
               "(result.error / |Lref|, the remainder's estimate in it) in parentheses; "
               "* a warning status, ! an error.\n",
               BENCH_CUTOFF);
    for (i = 0; i <= cu->n; ++i) {
        const bench_cut_row *r = i < cu->n ? &cu->rows[i] : NULL;
        if (!r || r->scene != scene) {
            if (scene >= 0) bench_table_emit(&t, o);
            if (!r) break;
            scene = r->scene;
            bench_both(o, "\n%s: %s.\n\n", bench_scenes[scene].name, bench_scenes[scene].description);
            bench_table_init(&t, 9);
            bench_table_row(&t);
            bench_table_cell(&t, 0, "method");
            bench_table_cell(&t, 1, "rtol");
            bench_table_cell(&t, 2, "evals");
            bench_table_cell(&t, 3, "medium_evals");
            bench_table_cell(&t, 4, "rel_error (estimate)");
            bench_table_cell(&t, 5, "t_cut");
            bench_table_cell(&t, 6, "evals, cut");
            bench_table_cell(&t, 7, "medium_evals, cut");
            bench_table_cell(&t, 8, "rel_error (estimate), cut");
        }
        bench_table_row(&t);
        if (i == 0 || cu->rows[i - 1].method != r->method || cu->rows[i - 1].scene != r->scene)
            bench_table_cell(&t, 0, "%s", st->methods[r->method].name);
        bench_table_cell(&t, 1, "%.0e", r->param);
        for (c = 0; c < 2; ++c) {
            const bench_row *w = &r->r[c];
            int col = c ? 6 : 2;
            bench_table_cell(&t, col, "%ld", w->stats.evals);
            bench_table_cell(&t, col + 1, "%ld", w->stats.medium_evals);
            if (w->status < 0 || !bench_finite(w->rel_error))
                bench_table_cell(&t, col + 2, "error!");
            else
                bench_table_cell(&t, col + 2, "%.1e (%.1e)%s", w->rel_error, w->est_error, w->status > 0 ? "*" : "");
        }
        bench_table_cell(&t, 5, "%.3g", (double)r->r[1].stats.t_cut);
    }
}

/* ------------------------------------------------------------------------ */
/* Library overhead (timing.md)                                             */
/* ------------------------------------------------------------------------ */

static void bench_report_overhead(const bench_state *st, const bench_out *o)
{
    int s, i;
    if (!st->cfg.timed) return;
    for (s = 0; s < 2; ++s) {
        const bench_overhead *ov = &st->overhead[s];
        const bench_scene *sc;
        char title[128];
        bench_table t;
        int homog;
        if (ov->scene < 0) continue;
        sc = &bench_scenes[ov->scene];
        homog = !strcmp(sc->name, "directional");
        snprintf(title, sizeof title, "Library overhead on the %s scene (%s)", sc->name,
                 homog ? "medium as constants" : "sigma callbacks");
        bench_section(o, title);
        bench_both(o,
                   "Time per evaluation at about %d evaluations, warp none; each time is the "
                   "fastest of %d timed batches (not the median: other processes' interference "
                   "only ever adds time).\n"
                   "Two Li costs in the same process: the scene's own Li (cheap), and the same Li "
                   "made dearer by %ld dependent multiply-adds whose result feeds its output "
                   "(calibrated at startup to about %.0f ns; measured here: %.0f ns more per "
                   "evaluation), as a renderer's shadow ray would.\n"
                   "Callbacks alone (%s): %.1f ns | %.1f ns per evaluation (cheap | dear Li). "
                   "Hand-written ray march (rectangle rule, the same callbacks, %s): "
                   "%.1f ns | %.1f ns per evaluation (its rel_error %.1e).\n"
                   "'beyond callbacks' is ns/eval minus the callbacks' own cost and 'ratio' "
                   "divides it by the hand-written loop's; 'total ratio' is ns/eval, callbacks "
                   "included, over the hand-written loop's (1: no slower than a minimal loop).\n\n",
                   BENCH_OVERHEAD_EVALS, BENCH_OVERHEAD_BATCHES, st->busy_iters, BENCH_BUSY_NS,
                   ov->callbacks_ns[1] - ov->callbacks_ns[0],
                   homog ? "Li" : "sigma_a, sigma_s, Le, Li", ov->callbacks_ns[0],
                   ov->callbacks_ns[1], homog ? "Tr in closed form" : "tau by the trapezoid rule",
                   ov->loop_ns[0], ov->loop_ns[1], ov->loop_error);
        bench_table_init(&t, 9);
        bench_table_row(&t);
        bench_table_cell(&t, 0, "method");
        bench_table_cell(&t, 1, "param");
        bench_table_cell(&t, 2, "evals");
        bench_table_cell(&t, 3, "cheap Li: ns/eval");
        bench_table_cell(&t, 4, "beyond callbacks");
        bench_table_cell(&t, 5, "ratio");
        bench_table_cell(&t, 6, "total ratio");
        bench_table_cell(&t, 7, "%.0f ns Li: ns/eval", BENCH_BUSY_NS);
        bench_table_cell(&t, 8, "total ratio");
        for (i = 0; i < ov->n; ++i) {
            const bench_overhead_row *r = &ov->rows[i];
            const bench_method *me = &st->methods[r->method];
            double per0 = r->ns_per_ray[0] / (double)r->evals;
            double per1 = r->ns_per_ray[1] / (double)r->evals;
            double beyond_loop = ov->loop_ns[0] - ov->callbacks_ns[0];
            bench_table_row(&t);
            bench_table_cell(&t, 0, "%s", me->name);
            if (bench_is_swept_over_n(me)) bench_table_cell(&t, 1, "N = %.0f", r->param);
            else bench_table_cell(&t, 1, "rtol = %.0e", r->param);
            bench_table_cell(&t, 2, "%ld", r->evals);
            bench_table_cell(&t, 3, "%.1f", per0);
            bench_table_cell(&t, 4, "%.1f", per0 - ov->callbacks_ns[0]);
            if (beyond_loop > 0)
                bench_table_cell(&t, 5, "%.1f", (per0 - ov->callbacks_ns[0]) / beyond_loop);
            else
                bench_table_cell(&t, 5, "n/a");
            bench_table_cell(&t, 6, "%.2f", per0 / ov->loop_ns[0]);
            bench_table_cell(&t, 7, "%.1f", per1);
            bench_table_cell(&t, 8, "%.3f", per1 / ov->loop_ns[1]);
        }
        bench_table_emit(&t, o);
    }
}

/* ------------------------------------------------------------------------ */
/* Per scene: the fewest evaluations (summary.md), the shortest time         */
/* (timing.md) to reach an error                                            */
/* ------------------------------------------------------------------------ */

/* The rows of sw that reach target reliably: the first row from which every
   later row of the sweep (larger N, tighter rtol) has an error at most
   target and no error status. Returns that row's index in the sweep, or
   count if none. */
static int bench_reliable_from(const bench_state *st, const bench_sweep *sw, double target)
{
    int k = sw->count;
    while (k > 0) {
        const bench_row *r = &st->rows[sw->first + k - 1];
        if (r->status < 0 || !(r->rel_error <= target)) break;
        --k;
    }
    return k;
}

/* The row of scene si that reaches target reliably with the fewest
   evaluations (by_time 0) or in the shortest time (1); NULL if none. Ties:
   the first found, the loosest N or rtol of the earlier method. */
static const bench_row *bench_best_row(const bench_state *st, int si, double target, int by_time)
{
    const bench_row *best = NULL;
    int i, k;
    for (i = 0; i < st->nsweeps; ++i) {
        const bench_sweep *sw = &st->sweeps[i];
        if (sw->scene != si) continue;
        for (k = bench_reliable_from(st, sw, target); k < sw->count; ++k) {
            const bench_row *r = &st->rows[sw->first + k];
            if (by_time ? bench_finite(r->ns_per_ray) &&
                              (!best || r->ns_per_ray < best->ns_per_ray)
                        : !best || r->stats.evals < best->stats.evals)
                best = r;
        }
    }
    return best;
}

static void bench_scene_heading(const bench_scene *sc, const bench_out *o)
{
    if (!o->quiet) printf("\n-- %s: %s\n", sc->name, sc->description);
    if (o->md) fprintf(o->md, "\n### %s\n\n%s.\n\n", sc->name, sc->description);
}

/* QAG's fewest evaluations on scene si from which its sweep stays within
   target (as bench_reliable_from), into out; "-" where it never does. */
static void bench_qag_fewest_text(const bench_state *st, int si, double target, char *out, size_t size)
{
    const bench_qag *q = &st->qag[si];
    long best = -1;
    int k = q->n;
    while (k > 0 && q->err[k - 1] <= target) --k;
    for (; k < q->n; ++k)
        if (best < 0 || q->evals[k] < best) best = q->evals[k];
    if (best < 0) snprintf(out, size, "-");
    else snprintf(out, size, "%ld", best);
}

static void bench_report_scene_summary(const bench_state *st, int si, const bench_out *o)
{
    const bench_scene *sc = &bench_scenes[si];
    char label[160], qtext[24];
    bench_table t;
    int tg, mi, w, k, nc = 1;
    bench_scene_heading(sc, o);
    bench_table_init(&t, 5);
    bench_table_row(&t);
    bench_table_cell(&t, 0, "rel. error");
    bench_table_cell(&t, 1, "fewest evals");
    bench_table_cell(&t, 2, "its medium evals");
    bench_table_cell(&t, 3, "method, warp%s (N or rtol)",
                     bench_scene_nmedia(st, si) > 1 ? ", medium" : "");
    bench_table_cell(&t, 4, "QUADPACK QAG (GK15), exact Tr");
    for (tg = 0; tg < BENCH_TARGETS; ++tg) {
        const bench_row *be = bench_best_row(st, si, bench_targets[tg], 0);
        bench_table_row(&t);
        bench_table_cell(&t, 0, "%.0e", bench_targets[tg]);
        bench_qag_fewest_text(st, si, bench_targets[tg], qtext, sizeof qtext);
        bench_table_cell(&t, 4, "%s", qtext);
        if (!be) {
            bench_table_cell(&t, 1, "not reached");
            continue;
        }
        bench_table_cell(&t, 1, "%ld", be->stats.evals);
        bench_table_cell(&t, 2, "%ld", be->stats.medium_evals);
        bench_row_label(st, be, label, sizeof label);
        bench_table_cell(&t, 3, "%s", label);
    }
    bench_table_emit(&t, o);

    /* fitted orders of the fixed-step methods: a column per warp and medium */
    bench_table_init(&t, BENCH_TCOLS);
    bench_table_row(&t);
    bench_table_cell(&t, 0, "fixed-step method");
    for (w = 0; w < 2; ++w)
        for (k = 0; k < BENCH_MEDIUM_COUNT; ++k) {
            bench_warp_id wid = w ? sc->natural_warp : BENCH_WARP_NONE;
            int any = 0;
            for (mi = 0; mi < st->nmethods; ++mi)
                any |= bench_is_swept_over_n(&st->methods[mi]) &&
                       bench_find_sweep(st, si, mi, wid, (bench_medium_id)k) != NULL;
            if (!any || nc >= BENCH_TCOLS - 1) continue;
            if (bench_scene_nmedia(st, si) > 1)
                bench_table_cell(&t, nc++, "order, warp %s, %s", bench_warp_names[wid],
                                 bench_medium_names[k]);
            else
                bench_table_cell(&t, nc++, "order, warp %s", bench_warp_names[wid]);
        }
    bench_table_cell(&t, nc, "nominal");
    t.ncols = nc + 1;
    for (mi = 0; mi < st->nmethods; ++mi) {
        int col = 1, any = 0;
        if (!bench_is_swept_over_n(&st->methods[mi])) continue;
        for (w = 0; w < 2; ++w)
            for (k = 0; k < BENCH_MEDIUM_COUNT; ++k)
                any |= bench_find_sweep(st, si, mi, w ? sc->natural_warp : BENCH_WARP_NONE,
                                        (bench_medium_id)k) != NULL;
        if (!any) continue;
        bench_table_row(&t);
        bench_table_cell(&t, 0, "%s", st->methods[mi].name);
        for (w = 0; w < 2; ++w)
            for (k = 0; k < BENCH_MEDIUM_COUNT; ++k) {
                bench_warp_id wid = w ? sc->natural_warp : BENCH_WARP_NONE;
                int j, present = 0;
                for (j = 0; j < st->nmethods; ++j)
                    present |= bench_is_swept_over_n(&st->methods[j]) &&
                               bench_find_sweep(st, si, j, wid, (bench_medium_id)k) != NULL;
                if (present && col < nc)
                    bench_order_cell(&t, col++, bench_find_sweep(st, si, mi, wid, (bench_medium_id)k));
            }
        bench_table_cell(&t, nc, "%g", st->methods[mi].order);
    }
    if (t.nrows > 1) bench_table_emit(&t, o);
    else free(t.cell);
}

static void bench_report_scene_times(const bench_state *st, int si, const bench_out *o)
{
    char label[160];
    bench_table t;
    int tg;
    bench_scene_heading(&bench_scenes[si], o);
    bench_table_init(&t, 5);
    bench_table_row(&t);
    bench_table_cell(&t, 0, "rel. error");
    bench_table_cell(&t, 1, "fastest ns/ray");
    bench_table_cell(&t, 2, "method, warp%s (N or rtol)",
                     bench_scene_nmedia(st, si) > 1 ? ", medium" : "");
    bench_table_cell(&t, 3, "its evals");
    bench_table_cell(&t, 4, "ns/ray of the fewest-evals row");
    for (tg = 0; tg < BENCH_TARGETS; ++tg) {
        const bench_row *bt = bench_best_row(st, si, bench_targets[tg], 1);
        const bench_row *be = bench_best_row(st, si, bench_targets[tg], 0);
        bench_table_row(&t);
        bench_table_cell(&t, 0, "%.0e", bench_targets[tg]);
        if (!bt) {
            bench_table_cell(&t, 1, "not reached");
            continue;
        }
        bench_table_cell(&t, 1, "%.0f", bt->ns_per_ray);
        bench_row_label(st, bt, label, sizeof label);
        bench_table_cell(&t, 2, "%s", label);
        bench_table_cell(&t, 3, "%ld", bt->stats.evals);
        if (be && bench_finite(be->ns_per_ray)) bench_table_cell(&t, 4, "%.0f", be->ns_per_ray);
    }
    bench_table_emit(&t, o);
}

/* ------------------------------------------------------------------------ */
/* Exponential fitting: each fitted variant against its plain rule and the  */
/* production baseline                                                      */
/* ------------------------------------------------------------------------ */

static int bench_method_named(const bench_state *st, const char *name)
{
    int mi;
    for (mi = 0; mi < st->nmethods; ++mi)
        if (strcmp(st->methods[mi].name, name) == 0) return mi;
    return -1;
}

/* The fewest evaluations from which sw stays at or below target, as a
   cell ("-": never, "": no sweep). */
static void bench_fewest_text(const bench_state *st, const bench_sweep *sw, double target,
                              char *out, size_t size)
{
    long best = -1;
    int k;
    if (!sw) {
        snprintf(out, size, " ");
        return;
    }
    for (k = bench_reliable_from(st, sw, target); k < sw->count; ++k) {
        long e = st->rows[sw->first + k].stats.evals;
        if (best < 0 || e < best) best = e;
    }
    if (best < 0) snprintf(out, size, "-");
    else snprintf(out, size, "%ld", best);
}

static void bench_report_expo(const bench_state *st, const bench_out *o)
{
    static const char *const scenes[] = {"thick", "cloud"};
    static const char *const families[] = {
        "simpson", "gauss-kronrod-global", "gauss-kronrod-k7", "gauss-kronrod-local",
        "bogacki-shampine", "dormand-prince"};
    static const char *const suffix[3] = {"", "-exp", "-exp2"};
    static const double targets[2] = {1e-3, 1e-6};
    int s, f, v, w, k, march = bench_method_named(st, "analytic-march"), any = 0;
    for (s = 0; s < (int)COUNT_OF(scenes); ++s) {
        int si = bench_find_scene(scenes[s]);
        any |= si >= 0 && bench_scene_selected(&st->cfg, si);
    }
    if (!any) return;
    bench_section(o, "Exponential fitting on the thick scenes and the cloud");
    bench_both(o, "The fewest evaluations from which a sweep stays within a relative error of "
                  "1e-3 / 1e-6 (- : not reached in the sweep; blank: not run): each rule plain, "
                  "fitted to tau's exponential (options.exponential = 1, -exp) and to the whole "
                  "integrand's (2, -exp2), against the production baseline (analytic-march). "
                  "Fixed-step methods over N, adaptive ones over rtol.\n\n");
    for (s = 0; s < (int)COUNT_OF(scenes); ++s) {
        int si = bench_find_scene(scenes[s]);
        const bench_scene *sc;
        bench_medium_id mids[BENCH_MEDIUM_COUNT];
        int nm;
        bench_table t;
        if (si < 0 || !bench_scene_selected(&st->cfg, si)) continue;
        sc = &bench_scenes[si];
        nm = bench_scene_media(&st->cfg, si, mids);
        bench_both(o, "%s: %s.\n\n", sc->name, sc->description);
        bench_table_init(&t, 6);
        bench_table_row(&t);
        bench_table_cell(&t, 0, "rule");
        bench_table_cell(&t, 1, "warp");
        bench_table_cell(&t, 2, "medium");
        bench_table_cell(&t, 3, "plain");
        bench_table_cell(&t, 4, "-exp");
        bench_table_cell(&t, 5, "-exp2");
        for (f = -1; f < (int)COUNT_OF(families); ++f)
            for (w = 0; w < 2; ++w)
                for (k = 0; k < nm; ++k) {
                    bench_warp_id wid = w ? sc->natural_warp : BENCH_WARP_NONE;
                    int shown = 0;
                    char name[64], cell[2][24];
                    for (v = 0; v < 3 && (f >= 0 || v == 0); ++v) {
                        int mi, j;
                        const bench_sweep *sw;
                        if (f < 0) mi = march;
                        else {
                            snprintf(name, sizeof name, "%s%s", families[f], suffix[v]);
                            mi = bench_method_named(st, name);
                        }
                        sw = mi >= 0 ? bench_find_sweep(st, si, mi, wid, mids[k]) : NULL;
                        if (!sw && v == 0) break;
                        if (!shown) {
                            bench_table_row(&t);
                            bench_table_cell(&t, 0, "%s", f < 0 ? "analytic-march" : families[f]);
                            bench_table_cell(&t, 1, "%s", bench_warp_names[wid]);
                            bench_table_cell(&t, 2, "%s", bench_medium_names[mids[k]]);
                            shown = 1;
                        }
                        for (j = 0; j < 2; ++j)
                            bench_fewest_text(st, sw, targets[j], cell[j], sizeof cell[j]);
                        bench_table_cell(&t, 3 + v, "%s / %s", cell[0], cell[1]);
                    }
                }
        bench_table_emit(&t, o);
    }
}

/* ------------------------------------------------------------------------ */
/* The summaries                                                            */
/* ------------------------------------------------------------------------ */

void bench_report_summaries(const bench_state *st, const bench_out *summary,
                            const bench_out *timing)
{
    int si, v = hrm_version();
    if (summary->md)
        fprintf(summary->md,
                "# hrm.h benchmark summary\n\n"
                "Written by `make bench` (bench/) for hrm.h %d.%d.%d; bench/README.md explains "
                "the tables. Errors are Munoz 2014's |L - Lref| / max(|L|, |Lref|), worst of %d "
                "channels, against references independent of hrm. No timings here: the same "
                "build gives the same file (timing.md has the machine-dependent numbers).\n",
                v / 10000, v / 100 % 100, v % 100, HRM_CHANNELS);
    if (timing->md)
        fprintf(timing->md,
                "# hrm.h benchmark timings\n\n"
                "Written by `make bench` (bench/) for hrm.h %d.%d.%d: one machine's numbers, "
                "different on every run; compare methods with each other, not across machines. "
                "bench/README.md explains the tables.\n",
                v / 10000, v / 100 % 100, v % 100);

    bench_report_proportionality(st, summary);
    bench_report_equiangular(st, summary);
    bench_report_transmittance(st, summary);
    bench_report_breaks(st, summary);
    bench_report_expo(st, summary);
    bench_report_cutoff(st, summary);
    bench_section(summary, "Per scene: the fewest evaluations to reach an error");
    bench_both(summary,
               "For each target, the smallest evaluation count of any method, warp and medium "
               "whose sweep stays at or below the target from that N or rtol on (a lucky single "
               "N does not count). N doubles and rtol moves by decades, so a count is within a "
               "factor of about 2 (fixed-step) of the least that would do. Beside it, a "
               "general-purpose quadrature: QUADPACK's QAG with the 15-point Gauss-Kronrod rule "
               "(GSL's gsl_integration_qag, written in bench/qag.c), given the scene's integrand "
               "with the exact Tr and nothing else, over the same rtol ladder as epsrel (vector "
               "form: one evaluation gives every channel). Fitted orders: over "
               "the whole sweep, in parentheses its finest %d points.\n",
               BENCH_TAIL);
    for (si = 0; si < bench_scene_count; ++si)
        if (bench_scene_selected(&st->cfg, si)) bench_report_scene_summary(st, si, summary);

    if (!st->cfg.timed) {
        if (timing->md) fprintf(timing->md, "\nNot measured: the run had --no-timing.\n");
        return;
    }
    bench_report_overhead(st, timing);
    bench_section(timing, "Per scene: the shortest time to reach an error");
    bench_both(timing, "As the fewest evaluations above, by ns_per_ray (the median of %d "
                       "batches of repeated solves).\n",
               st->timings);
    for (si = 0; si < bench_scene_count; ++si)
        if (bench_scene_selected(&st->cfg, si)) bench_report_scene_times(st, si, timing);
}

void bench_report_footer(const bench_state *st, int files, double seconds)
{
    if (st->cfg.csv) {
        if (st->count_mismatches)
            fprintf(stderr,
                    "bench: %ld solves with evaluation counts that disagree with the callbacks\n",
                    st->count_mismatches);
        return;
    }
    printf("\nevaluation counts: hrm's stats %s the callbacks made in %ld solves",
           st->count_mismatches ? "disagree with" : "match", st->solves);
    if (st->count_mismatches) printf(" (%ld mismatches, see stderr)", st->count_mismatches);
    printf("\nreferences below the accuracy check (%.0Le): %d (QAG's rule on exact monomials: %.1e, at most %.0e)\n",
           BENCH_REF_CHECK, st->ref_bad, st->qag_check, BENCH_QAG_CHECK);
    printf("rows with an error status: %d\n", st->errors);
    printf("wrote %s/bench.csv (%d rows), summary.md, %s%d SVG figures\n", st->cfg.out_dir,
           st->nrows, st->cfg.timed ? "timing.md and " : "", files);
    printf("run time: %.1f s\n", seconds);
}
