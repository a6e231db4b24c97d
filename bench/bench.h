/* bench/bench.h - what the parts of the benchmark share.

   The benchmark is four parts around one state (bench_state), which main
   creates and passes to each; no part keeps state of its own:

     measure.c  running solves: methods, warps, references, the sweeps
                (rows), the count check, timing, and the measurements of
                the summary sections (equiangular, transmittance, overhead)
     report.c   tables on stdout, summary.md, timing.md, bench.csv
     figures.c  the SVG figures (svg.c draws them)
     main.c     the command line: options, the order of the work, exit status

   with the scenes (scenes.c) and the reference quadrature (reference.c),
   which know nothing of hrm's solvers. bench/README.md says how to read the
   output. */
#ifndef BENCH_H
#define BENCH_H

#include <stdio.h>

#include "hrm.h"
#include "reference.h"
#include "scenes.h"

#define BENCH_SEEDS 32            /* Monte Carlo: RMS error over seeds 1..32 */
#define BENCH_SEEDS_QUICK 8
#define BENCH_MAX_EVALS 100000L   /* adaptive runs: budget, so none runs away */
#define BENCH_FIT_FLOOR 1e-13     /* errors below this are round-off: not fitted */
#define BENCH_PLOT_FLOOR 1e-16    /* errors below this are drawn at it */
#define BENCH_REF_CHECK 1e-13L    /* a reference must be at least this accurate */
#define BENCH_QAG_CHECK 1e-13     /* QAG's rule on the monomials it integrates exactly */
#define BENCH_MAX_PARAMS 16
#define BENCH_MAX_METHODS (HRM_METHOD_COUNT + 12)
#define BENCH_MAX_SCENES 16
#define BENCH_TAIL 4              /* the finest points, for the asymptotic order */
#define BENCH_TARGETS 3           /* the summary's error targets: 1e-2, 1e-4, 1e-6 */
#define BENCH_SECTION_PARAMS 3    /* N or rtol values of the summary sections */
#define BENCH_OVERHEAD_BATCHES 15 /* the overhead table: the fastest of these */
#define BENCH_OVERHEAD_EVALS 1024 /* ... at about this many evaluations */
#define BENCH_BUSY_NS 500.0       /* the dear Li of the overhead table, ns */
#define BENCH_TRANS_COLS 5        /* the transmittance table's columns (a)..(e) */

#define COUNT_OF(a) ((int)(sizeof(a) / sizeof((a)[0])))

enum { /* exit status */
    BENCH_EXIT_OK = 0,
    BENCH_EXIT_SOLVE_ERROR = 1,
    BENCH_EXIT_USAGE = 2,
    BENCH_EXIT_OUTPUT = 3,
    BENCH_EXIT_CHECK = 4
};

extern const double bench_targets[BENCH_TARGETS];
/* N and rtol of the summary sections (equiangular, transmittance) */
extern const double bench_section_steps[BENCH_SECTION_PARAMS];
extern const double bench_section_tols[BENCH_SECTION_PARAMS];
extern const char *const bench_warp_names[BENCH_WARP_COUNT];
extern const char *const bench_medium_names[BENCH_MEDIUM_COUNT];

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
    hrm_gk_rule gk_rule;
    int expo;     /* options.exponential: 1 or 2 for the fitted variants */
    char name[40];
    bench_kind kind;
    double order; /* nominal order for smooth integrands (hrm.h manual); 0: none */
    const char *color;
    int marker;
} bench_method;

/* ------------------------------------------------------------------------ */
/* Configuration (the command line)                                         */
/* ------------------------------------------------------------------------ */

typedef struct bench_config {
    int csv, quick, list, timed;
    int scene_on[BENCH_MAX_SCENES], any_scene;
    int method_on[BENCH_MAX_METHODS], any_method;
    int warp_on[BENCH_WARP_COUNT], natural_on, any_warp;
    int medium_on[BENCH_MEDIUM_COUNT], any_medium;
    double steps[BENCH_MAX_PARAMS], tols[BENCH_MAX_PARAMS];
    int nsteps, ntols;      /* from --steps / --tol; else the defaults */
    int user_steps, user_tols;
    hrm_control control;
    const char *out_dir;
    int seeds;
} bench_config;

/* ------------------------------------------------------------------------ */
/* Measurements                                                             */
/* ------------------------------------------------------------------------ */

typedef struct bench_reference {
    int done;
    long double L[HRM_CHANNELS];
    long double accuracy; /* estimated relative accuracy, worst channel */
    long double splits[REF_MAX_POINTS];
    int nsplits;          /* interior split points used */
    long double panel;
} bench_reference;

/* One solve (Monte Carlo: one per seed) of the sweeps. */
typedef struct bench_row {
    int scene, method;
    bench_warp_id warp;
    bench_medium_id medium;
    double param;        /* N, or rtol */
    hrm_stats stats;     /* of one ray (the first seed) */
    double rel_error;    /* RMS over seeds for random methods */
    double est_error;    /* adaptive methods: hrm's own estimate of it
                            (result.error over |Lref|, the worst channel,
                            first seed); NaN for the fixed-step methods */
    hrm_status status;   /* an error if any seed gave one, else the largest warning */
    double ns_per_ray;   /* NaN: not timed */
} bench_row;

/* The rows of one scene x method x warp x medium, in sweep order (N
   increasing, or rtol decreasing). */
typedef struct bench_sweep {
    int scene, method;
    bench_warp_id warp;
    bench_medium_id medium;
    int first, count;    /* into bench_state.rows */
    /* fixed-step methods: the fitted convergence order */
    int points;          /* rows above the fit floor */
    double order;        /* -(least-squares slope of log error vs log evals) */
    double tail;         /* the same over the last BENCH_TAIL of those rows */
} bench_sweep;

/* Equiangular gain on the point scene: error(none) / error(equiangular). */
typedef struct bench_equi {
    int scene;                         /* -1: not measured */
    int n;
    int method[BENCH_MAX_METHODS];     /* rectangle and monte-carlo first */
    double ratio[BENCH_MAX_METHODS][BENCH_SECTION_PARAMS]; /* NaN: n/a */
} bench_equi;

/* The transmittance table: one row per method and N or rtol, equiangular
   warp; columns (a) point as constants, (b) point as sigma callbacks,
   (c) smoke with HRM_TAU_DECOUPLED, (d) HRM_TAU_COUPLED, (e) smoke with its
   exact transmittance callback. */
typedef struct bench_trans_row {
    int method;
    double param;
    double err[BENCH_TRANS_COLS];      /* NaN: not run (scene not selected) */
    hrm_status status[BENCH_TRANS_COLS];
    int ran[BENCH_TRANS_COLS];
    hrm_stats stats_c;                 /* column (c)'s */
} bench_trans_row;

typedef struct bench_trans {
    int point, smoke;                  /* scene indices; -1: not selected */
    int n;
    bench_trans_row rows[BENCH_MAX_METHODS * BENCH_SECTION_PARAMS];
} bench_trans;

/* QUADPACK's QAG with the 15-point rule (qag.h), given each scene's
   integrand with the exact Tr, over the adaptive methods' tolerances:
   its evaluations and error (NaN where it stopped short of epsrel). */
typedef struct bench_qag {
    int n;
    long evals[BENCH_MAX_PARAMS];
    double err[BENCH_MAX_PARAMS];
} bench_qag;

/* Early ray termination on sigma callbacks: the thick scene and the
   cloud, no warp, each adaptive method at the section's tolerances,
   [0] without options.cutoff, [1] with BENCH_CUTOFF. */
#define BENCH_CUT_SCENES 2
#define BENCH_CUTOFF 1e-3
typedef struct bench_cut_row {
    int scene, method;
    double param;
    bench_row r[2];
} bench_cut_row;

typedef struct bench_cut {
    int n;
    bench_cut_row rows[BENCH_CUT_SCENES * BENCH_MAX_METHODS * BENCH_SECTION_PARAMS];
} bench_cut;

/* Breakpoints on the occluder and slab scenes: per method, warp and
   medium, the fewest evaluations from which the sweep stays within 1e-2,
   1e-4, 1e-6 (-1: not reached), [0] without breakpoints or the jump
   search, [1] with the exact breakpoints (the occluder's from
   hrm_sphere_breaks, the slab's faces), [2] with the jump search alone
   (find_jumps = 1: the medium scan in every method, the source's search
   in nested Simpson and global Gauss-Kronrod). */
#define BENCH_BRK_ROWS (BENCH_MAX_METHODS * 4)
#define BENCH_BRK_SCENES 2
typedef struct bench_brk_row {
    int method, warp, medium;
    long fewest[3][3];
    int np;                            /* the sweep of each way, for fig4.svg */
    double param[BENCH_MAX_PARAMS];
    long evals[3][BENCH_MAX_PARAMS];
    double err[3][BENCH_MAX_PARAMS];   /* NaN: error status */
} bench_brk_row;

typedef struct bench_brk {
    int scene;                         /* -1: not measured */
    int nbreaks;
    double breaks[2];
    int n;
    bench_brk_row rows[BENCH_BRK_ROWS];
} bench_brk;

/* Library overhead against a hand-written loop, at two Li costs:
   [0] the scene's cheap callbacks, [1] Li made about BENCH_BUSY_NS dearer. */
typedef struct bench_overhead_row {
    int method;
    double param;
    long evals;
    double ns_per_ray[2];
} bench_overhead_row;

typedef struct bench_overhead {
    int scene;                         /* -1: not measured */
    double callbacks_ns[2];            /* per evaluation, the callbacks alone */
    double loop_ns[2];                 /* per evaluation, the hand-written loop */
    double loop_error;                 /* the loop's rel_error (cheap Li) */
    int n;
    bench_overhead_row rows[BENCH_MAX_METHODS];
} bench_overhead;

/* Progress on stderr: a line redrawn on a terminal, one per scene if not. */
typedef struct bench_progress {
    long done, total;
    double start, shown; /* when the run started, when the line was last drawn */
    int tty;
} bench_progress;

/* Everything a run holds. main owns it; every part works on it. */
typedef struct bench_state {
    bench_config cfg;
    bench_method methods[BENCH_MAX_METHODS];
    int nmethods;
    ref_rule rule;
    bench_reference refs[BENCH_MAX_SCENES];

    bench_row *rows;
    int nrows, rows_cap;
    bench_sweep *sweeps;
    int nsweeps, sweeps_cap;

    int timings;             /* timed batches per row; the median is reported */
    double batch_seconds;    /* a timed batch lasts at least this long */
    long busy_iters;         /* bench_busy iterations that take BENCH_BUSY_NS */

    long solves, count_mismatches;
    int errors;              /* rows in which a solve returned an error status */
    int ref_bad;             /* references failing their self-check */
    bench_progress progress;

    bench_equi equi;
    bench_trans trans;
    bench_cut cut;
    bench_qag qag[BENCH_MAX_SCENES];
    double qag_check;        /* qag_rule_check(): its rule's worst error on exact monomials */
    bench_brk brk[BENCH_BRK_SCENES];
    bench_overhead overhead[2]; /* directional (constants), hetero (callbacks) */
} bench_state;

/* ------------------------------------------------------------------------ */
/* measure.c                                                                */
/* ------------------------------------------------------------------------ */

void bench_state_init(bench_state *st);   /* methods, defaults; cfg is zeroed */
void bench_state_free(bench_state *st);
double bench_seconds(void);
int bench_cmp_double(const void *a, const void *b);
int bench_finite(double x);
int bench_find_scene(const char *name);   /* -1: none */

int bench_is_swept_over_n(const bench_method *me);
const char *bench_kind_name(bench_kind k);
const char *bench_control_name(hrm_control c);
int bench_scene_selected(const bench_config *cfg, int si);
int bench_method_selected(const bench_state *st, int mi);
/* The warps a scene runs with: none and its natural warp, or those asked. */
int bench_scene_warps(const bench_config *cfg, const bench_scene *sc,
                      bench_warp_id out[BENCH_WARP_COUNT]);
/* The ways a scene's medium is given: constants and callbacks for a
   homogeneous scene, callbacks only otherwise (less with --medium). */
int bench_scene_media(const bench_config *cfg, int si, bench_medium_id out[BENCH_MEDIUM_COUNT]);
int bench_params_of(const bench_config *cfg, const bench_method *me, const double **p);
/* Sets options->warp; returns 0 if the warp does not apply to the scene. */
int bench_warp_apply(const bench_scene *sc, bench_warp_id w, hrm_options *o);

const bench_reference *bench_reference_get(bench_state *st, int si);
const bench_sweep *bench_find_sweep(const bench_state *st, int scene, int method,
                                    bench_warp_id warp, bench_medium_id medium);

void bench_progress_start(bench_state *st, double start);
void bench_progress_show(bench_state *st, const char *what);

/* The sweeps of one scene: rows and sweeps appended to st. */
void bench_run_scene(bench_state *st, int si);
/* The summary sections' measurements, after the sweeps. */
void bench_measure_equiangular(bench_state *st);
void bench_measure_transmittance(bench_state *st);
void bench_measure_cutoff(bench_state *st);
void bench_measure_qag(bench_state *st);
void bench_measure_breaks(bench_state *st);
void bench_measure_overhead(bench_state *st); /* only when timed */

/* ------------------------------------------------------------------------ */
/* report.c                                                                 */
/* ------------------------------------------------------------------------ */

/* Where a summary section goes: stdout (unless quiet) and a markdown file. */
typedef struct bench_out {
    FILE *md;
    int quiet; /* --csv: no tables on stdout */
} bench_out;

#define BENCH_CSV_HEADER \
    "scene,method,warp,medium,param,evals,medium_evals,steps,rejected,rel_error,status,ns_per_ray,est_error"

void bench_report_header(const bench_state *st);
void bench_report_scene(const bench_state *st, int si);   /* after bench_run_scene */
void bench_report_csv_row(FILE *f, const bench_state *st, const bench_row *r);
void bench_report_orders(const bench_state *st);          /* stdout only */
/* The summaries: `summary` gets what is the same on every run,
   `timing` the machine-dependent numbers. */
void bench_report_summaries(const bench_state *st, const bench_out *summary,
                            const bench_out *timing);
void bench_report_footer(const bench_state *st, int files, double seconds);
int bench_write_csv(const bench_state *st, const char *dir);

/* Files in the output directory. */
FILE *bench_open(const char *dir, const char *name, char *path, size_t n);
int bench_close(FILE *f, const char *path);

/* ------------------------------------------------------------------------ */
/* figures.c                                                                */
/* ------------------------------------------------------------------------ */

/* <scene>.svg, fig4.svg and (timed runs) time.svg; counts them in *files.
   Returns nonzero if one could not be written. */
int bench_write_figures(const bench_state *st, const char *dir, int *files);

#endif
