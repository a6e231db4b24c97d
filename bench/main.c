/* bench/main.c - the command line of hrm.h's single-ray benchmark.

   Parses the options into bench_state.cfg, then runs the parts in order:
   the sweeps of every scene (measure.c), each scene's tables as it finishes
   (report.c), the measurements of the summary sections, the summaries on
   stdout and in summary.md / timing.md, bench.csv and the figures
   (figures.c). Run with --help for the options and the exit status;
   bench/README.md says how to read the output. */

#define _POSIX_C_SOURCE 200809L /* mkdir */
#include "bench.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const double bench_steps_full[] = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024};
static const double bench_steps_quick[] = {1, 2, 4, 8, 16, 32, 64};
static const double bench_tols_full[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
static const double bench_tols_quick[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6};

enum { BENCH_PARSE_HELP = -1 }; /* --help printed: exit 0 */

static void bench_usage(FILE *out)
{
    fprintf(out,
            "usage: bench [options]\n"
            "Single-ray accuracy and speed of every hrm.h method on every scene: fixed-step\n"
            "methods over N, adaptive methods over rtol, each without a warp and with the\n"
            "scene's natural warp, a homogeneous scene's medium both as constants and as\n"
            "sigma callbacks. Tables on stdout, progress on stderr, files in --out.\n"
            "  --scene NAME    run only this scene (repeatable)\n"
            "  --method NAME   run only this method (repeatable); gauss-kronrod selects all three\n"
            "                  of its modes\n"
            "  --warp NAME     run only this warp (repeatable): none, natural (the scene's\n"
            "                  own), distance, equiangular (scenes with a point light)\n"
            "  --medium NAME   give the medium only this way (repeatable): const (homogeneous\n"
            "                  scenes only), sigma (callbacks)\n"
            "  --steps N       fixed-step methods at this N only (repeatable); alone, it\n"
            "                  runs no adaptive method\n"
            "  --tol X         adaptive methods at this rtol only (repeatable); alone, it\n"
            "                  runs no fixed-step method\n"
            "  --control NAME  step control of the Runge-Kutta pairs: pi (default), munoz,\n"
            "                  gonterman\n"
            "  --quick         N = 1..64, rtol = 1e-2..1e-6, %d Monte Carlo seeds, short timing\n"
            "  --no-timing     skip the timing (ns_per_ray is nan; no time plot, no overhead)\n"
            "  --csv           print CSV rows on stdout instead of the tables, under the header\n"
            "                  %s\n"
            "  --out DIR       write bench.csv, summary.md, timing.md and the SVG figures here\n"
            "                  (default bench/out)\n"
            "  --list          list the scenes, methods, warps, media and controls, then exit\n"
            "  --help          this text\n"
            "Defaults: N = 1..1024 (doubling), rtol = 1e-2..1e-10 (decades), %d seeds,\n"
            "adaptive budget max_evals = %ld.\n"
            "Exit status: 0 ok; 1 a solve returned an error status; 2 usage error;\n"
            "3 an output file could not be written; 4 a consistency check failed (hrm's\n"
            "evaluation counts disagree with the callbacks it made, or a reference is less\n"
            "accurate than %.0Le).\n",
            BENCH_SEEDS_QUICK, BENCH_CSV_HEADER, BENCH_SEEDS, BENCH_MAX_EVALS, BENCH_REF_CHECK);
}

static void bench_list_names(const bench_state *st, FILE *out, int what)
{
    int i;
    if (what == 0)
        for (i = 0; i < bench_scene_count; ++i)
            fprintf(out, "%s%s", i ? ", " : "", bench_scenes[i].name);
    else if (what == 1)
        for (i = 0; i < st->nmethods; ++i) fprintf(out, "%s%s", i ? ", " : "", st->methods[i].name);
    else if (what == 2)
        fprintf(out, "none, natural, distance, equiangular");
    else if (what == 3)
        fprintf(out, "pi, munoz, gonterman");
    else
        fprintf(out, "const, sigma");
    fprintf(out, "\n");
}

static void bench_list(const bench_state *st)
{
    int i;
    printf("scenes (natural warp):\n");
    for (i = 0; i < bench_scene_count; ++i)
        printf("  %-12s %-12s %s\n", bench_scenes[i].name,
               bench_warp_names[bench_scenes[i].natural_warp], bench_scenes[i].description);
    printf("methods:\n");
    for (i = 0; i < st->nmethods; ++i) {
        printf("  %-22s %s", st->methods[i].name, bench_kind_name(st->methods[i].kind));
        if (st->methods[i].order > 0) printf(", order %g", st->methods[i].order);
        printf("\n");
    }
    printf("warps:\n  none\n  natural      the scene's own (above)\n"
           "  distance     sigma_ref 0: hrm's choice, the thinnest channel's mean extinction over the ray\n"
           "  equiangular  toward the scene's point light (point, occluder, thin, smoke)\n");
    printf("media:\n  const        homogeneous constants (HRM_MEDIUM_HOMOGENEOUS); homogeneous "
           "scenes only\n  sigma        sigma_a/sigma_s callbacks (homogeneous scenes: the same "
           "constants)\n");
    printf("controls (Runge-Kutta pairs):\n  pi (default)\n  munoz\n  gonterman\n");
}

static int bench_usage_error(const bench_state *st, const char *fmt, const char *arg, int list)
{
    fprintf(stderr, "bench: ");
    fprintf(stderr, fmt, arg);
    if (list >= 0) {
        fprintf(stderr, "; valid: ");
        bench_list_names(st, stderr, list);
    } else {
        fprintf(stderr, "\n");
    }
    fprintf(stderr, "run 'bench --help' for usage\n");
    return BENCH_EXIT_USAGE;
}

/* Fills st->cfg. Returns 0, BENCH_PARSE_HELP, or BENCH_EXIT_USAGE after
   printing the error. */
static int bench_parse(int argc, char **argv, bench_state *st)
{
    static const char *const with_value[] = {"--scene", "--method", "--warp", "--medium",
                                             "--steps", "--tol",    "--control", "--out"};
    bench_config *cfg = &st->cfg;
    int i, k, j;
    memset(cfg, 0, sizeof *cfg);
    cfg->timed = 1;
    cfg->out_dir = "bench/out";
    cfg->control = HRM_CONTROL_PI;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *value = NULL, *opt;
        if (!strcmp(a, "--csv")) { cfg->csv = 1; continue; }
        if (!strcmp(a, "--quick")) { cfg->quick = 1; continue; }
        if (!strcmp(a, "--list")) { cfg->list = 1; continue; }
        if (!strcmp(a, "--no-timing")) { cfg->timed = 0; continue; }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            bench_usage(stdout);
            return BENCH_PARSE_HELP;
        }
        /* --opt VALUE or --opt=VALUE */
        for (j = 0; j < COUNT_OF(with_value); ++j) {
            size_t l = strlen(with_value[j]);
            if (!strcmp(a, with_value[j])) {
                if (i + 1 >= argc) return bench_usage_error(st, "%s needs a value", a, -1);
                value = argv[++i];
                break;
            }
            if (!strncmp(a, with_value[j], l) && a[l] == '=') {
                value = a + l + 1;
                break;
            }
        }
        if (j == COUNT_OF(with_value)) return bench_usage_error(st, "unknown option '%s'", a, -1);
        opt = with_value[j];
        if (!strcmp(opt, "--scene")) {
            k = bench_find_scene(value);
            if (k < 0) return bench_usage_error(st, "unknown scene '%s'", value, 0);
            cfg->scene_on[k] = cfg->any_scene = 1;
        } else if (!strcmp(opt, "--method")) {
            int found = 0;
            for (k = 0; k < st->nmethods; ++k)
                if (!strcmp(value, st->methods[k].name) ||
                    !strcmp(value, hrm_method_name(st->methods[k].id))) {
                    cfg->method_on[k] = cfg->any_method = 1;
                    found = 1;
                }
            if (!found) return bench_usage_error(st, "unknown method '%s'", value, 1);
        } else if (!strcmp(opt, "--warp")) {
            if (!strcmp(value, "natural")) {
                cfg->natural_on = 1;
            } else {
                for (k = 0; k < BENCH_WARP_COUNT && strcmp(value, bench_warp_names[k]); ++k) {}
                if (k == BENCH_WARP_COUNT)
                    return bench_usage_error(st, "unknown warp '%s'", value, 2);
                cfg->warp_on[k] = 1;
            }
            cfg->any_warp = 1;
        } else if (!strcmp(opt, "--medium")) {
            for (k = 0; k < BENCH_MEDIUM_COUNT && strcmp(value, bench_medium_names[k]); ++k) {}
            if (k == BENCH_MEDIUM_COUNT)
                return bench_usage_error(st, "unknown medium '%s'", value, 4);
            cfg->medium_on[k] = cfg->any_medium = 1;
        } else if (!strcmp(opt, "--control")) {
            if (!strcmp(value, "pi")) cfg->control = HRM_CONTROL_PI;
            else if (!strcmp(value, "munoz")) cfg->control = HRM_CONTROL_MUNOZ;
            else if (!strcmp(value, "gonterman")) cfg->control = HRM_CONTROL_GONTERMAN;
            else return bench_usage_error(st, "unknown control '%s'", value, 3);
        } else if (!strcmp(opt, "--out")) {
            if (!*value) return bench_usage_error(st, "--out needs a directory%s", "", -1);
            cfg->out_dir = value;
        } else { /* --steps, --tol */
            char *end;
            int steps = !strcmp(opt, "--steps");
            double v = steps ? (double)strtol(value, &end, 10) : strtod(value, &end);
            if (end == value || *end)
                return bench_usage_error(st, steps ? "--steps needs an integer, not '%s'"
                                                   : "--tol needs a number, not '%s'",
                                         value, -1);
            if (steps ? !(v >= 1 && v <= 1 << 20) : !(v > 0 && v < 1))
                return bench_usage_error(st, steps ? "--steps %s: N must be in 1..1048576"
                                                   : "--tol %s: rtol must lie in (0, 1)",
                                         value, -1);
            if ((steps ? cfg->nsteps : cfg->ntols) >= BENCH_MAX_PARAMS)
                return bench_usage_error(st, "too many %s values", opt, -1);
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
    struct stat sb;
    errno = 0;
    if (stat(dir, &sb) != 0) return 0;
    if (!S_ISDIR(sb.st_mode)) {
        errno = ENOTDIR;
        return 0;
    }
    return 1;
}

/* Opens dir/name as a summary destination; quiet: nothing on stdout. */
static int bench_out_open(bench_out *o, const char *dir, const char *name, char *path, size_t n,
                          int quiet)
{
    o->quiet = quiet;
    o->md = bench_open(dir, name, path, n);
    return o->md != NULL;
}

static int bench_run(bench_state *st)
{
    const bench_config *cfg = &st->cfg;
    bench_out summary, timing;
    char spath[1200], tpath[1200];
    double start = bench_seconds();
    int si, out_bad = 0, files = 0;

    if (cfg->quick) {
        st->timings = 3;
        st->batch_seconds = 2e-4;
    }
    if (bench_mkdir_p(cfg->out_dir) != 0 || !bench_is_dir(cfg->out_dir)) {
        if (!errno) errno = ENOTDIR;
        fprintf(stderr, "bench: cannot create %s: %s\n", cfg->out_dir, strerror(errno));
        return BENCH_EXIT_OUTPUT;
    }

    bench_progress_start(st, start);
    bench_report_header(st);
    for (si = 0; si < bench_scene_count; ++si) {
        if (!bench_scene_selected(cfg, si)) continue;
        bench_run_scene(st, si);
        bench_report_scene(st, si);
        if (!st->progress.tty)
            fprintf(stderr, "bench: scene %s done (%ld/%ld rows, %.1f s)\n", bench_scenes[si].name,
                    st->progress.done, st->progress.total, bench_seconds() - start);
    }

    if (st->progress.tty)
        fprintf(stderr, "\r\033[K[    ] equiangular ratios, transmittance, library overhead");
    bench_measure_equiangular(st);
    bench_measure_transmittance(st);
    bench_measure_cutoff(st);
    bench_measure_qag(st);
    bench_measure_breaks(st);
    bench_measure_overhead(st);
    if (!st->progress.tty)
        fprintf(stderr, "bench: summary sections done (%.1f s)\n", bench_seconds() - start);

    /* Summaries: on stdout (unless --csv), in summary.md and timing.md. */
    bench_report_orders(st);
    out_bad |= !bench_out_open(&summary, cfg->out_dir, "summary.md", spath, sizeof spath, cfg->csv);
    out_bad |= !bench_out_open(&timing, cfg->out_dir, "timing.md", tpath, sizeof tpath, cfg->csv);
    bench_report_summaries(st, &summary, &timing);
    if (summary.md) out_bad |= bench_close(summary.md, spath) != 0;
    if (timing.md) out_bad |= bench_close(timing.md, tpath) != 0;

    out_bad |= bench_write_csv(st, cfg->out_dir) != 0;
    out_bad |= bench_write_figures(st, cfg->out_dir, &files) != 0;
    if (st->progress.tty) fprintf(stderr, "\r\033[K");
    bench_report_footer(st, files, bench_seconds() - start);

    if (st->errors) return BENCH_EXIT_SOLVE_ERROR;
    if (out_bad) return BENCH_EXIT_OUTPUT;
    if (st->count_mismatches || st->ref_bad) return BENCH_EXIT_CHECK;
    return BENCH_EXIT_OK;
}

int main(int argc, char **argv)
{
    bench_state *st = (bench_state *)malloc(sizeof *st);
    int rc;
    if (!st) {
        fprintf(stderr, "bench: out of memory\n");
        return BENCH_EXIT_OUTPUT;
    }
    bench_state_init(st);
    if (bench_scene_count > BENCH_MAX_SCENES) { /* a new scene: raise the limit */
        fprintf(stderr, "bench: %d scenes, BENCH_MAX_SCENES is %d\n", bench_scene_count,
                BENCH_MAX_SCENES);
        free(st);
        return BENCH_EXIT_CHECK;
    }
    rc = bench_parse(argc, argv, st);
    if (rc == BENCH_PARSE_HELP) rc = BENCH_EXIT_OK;
    else if (!rc && st->cfg.list) bench_list(st);
    else if (!rc) rc = bench_run(st);
    bench_state_free(st);
    free(st);
    return rc;
}
