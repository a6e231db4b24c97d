/* bench/figures.c - the benchmark's SVG figures (drawn by svg.c).

   <scene>.svg   one row per warp and medium: error vs evaluations, and for
                 the adaptive methods rtol vs error and rtol vs evaluations
   fig4.svg      Munoz 2014 Fig. 4's scenes (medium as constants), one row
                 each: error vs evaluations without and with the natural
                 warp, rtol vs error, rtol vs evaluations; the occluder has a
                 second row with its natural warp: without breakpoints or the
                 jump search, with the exact breakpoints, with the search
                 alone, and rtol vs error with the breakpoints
   time.svg      (timed runs) error vs time per ray, one row per scene and
                 medium, one column per warp: the only figure with
                 machine-dependent numbers, kept apart so the others are the
                 same on every run */

#include "bench.h"
#include "svg.h"

#include <math.h>
#include <string.h>

enum { BENCH_AX_EVALS, BENCH_AX_NS, BENCH_AX_RTOL, BENCH_AX_ERROR, BENCH_AX_COUNT };

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

static const char *bench_axis_label(int axis)
{
    switch (axis) {
    case BENCH_AX_EVALS: return "evaluations (samples) per ray";
    case BENCH_AX_NS: return "time per ray (ns)";
    case BENCH_AX_RTOL: return "rtol";
    default: return "relative error";
    }
}

/* One panel: a scene, warp and medium, two axes, which methods. */
typedef struct bench_cell {
    int scene;
    bench_warp_id warp;
    bench_medium_id medium;
    int xa, ya;
    int adaptive_only; /* 1: only the methods swept over rtol; 2: an empty cell */
    int way;           /* -1: the scene's sweeps; 0..2: the breakpoint section's way */
    char title[128];
} bench_cell;

/* An axis value of point k of a breakpoint section's sweep (way w). */
static double bench_brk_value(const bench_brk_row *r, int w, int k, int axis)
{
    double e = r->err[w][k];
    switch (axis) {
    case BENCH_AX_EVALS: return (double)r->evals[w][k];
    case BENCH_AX_RTOL: return r->param[k];
    case BENCH_AX_ERROR:
        if (!bench_finite(e)) return (double)NAN;
        return e > BENCH_PLOT_FLOOR ? e : BENCH_PLOT_FLOOR;
    default: return (double)NAN; /* not timed */
    }
}

/* A method's series: its name, colour, line (dashed: adaptive) and
   marker, and n points at most SVG_MAX_POINTS. */
static void bench_series_style(svg_series *s, const bench_method *me, int n)
{
    s->label = me->name;
    s->color = me->color;
    s->dashed = me->kind == BENCH_ADAPTIVE;
    s->marker = me->marker;
    s->n = n < SVG_MAX_POINTS ? n : SVG_MAX_POINTS;
}

/* The series of a cell drawn from the breakpoint section: one per method
   measured there with the cell's warp and medium. */
static int bench_brk_series(const bench_state *st, const bench_cell *c, svg_series *out)
{
    int bi, i, n = 0, k;
    for (bi = 0; bi < BENCH_BRK_SCENES; ++bi) {
        const bench_brk *b = &st->brk[bi];
        if (b->scene != c->scene) continue;
        for (i = 0; i < b->n && n < BENCH_MAX_METHODS; ++i) {
            const bench_brk_row *r = &b->rows[i];
            const bench_method *me = &st->methods[r->method];
            svg_series *s;
            if (r->warp != (int)c->warp || r->medium != (int)c->medium) continue;
            if (c->adaptive_only && me->kind != BENCH_ADAPTIVE) continue;
            s = &out[n++];
            bench_series_style(s, me, r->np);
            for (k = 0; k < s->n; ++k) {
                s->x[k] = bench_brk_value(r, c->way, k, c->xa);
                s->y[k] = bench_brk_value(r, c->way, k, c->ya);
            }
        }
    }
    return n;
}

/* One series per method of the cell's sweeps. */
static int bench_series(const bench_state *st, const bench_cell *c, svg_series *out)
{
    int mi, n = 0, k;
    if (c->adaptive_only == 2) return 0;
    if (c->way >= 0) return bench_brk_series(st, c, out);
    for (mi = 0; mi < st->nmethods; ++mi) {
        const bench_method *me = &st->methods[mi];
        const bench_sweep *sw = bench_find_sweep(st, c->scene, mi, c->warp, c->medium);
        svg_series *s;
        if (!sw || (c->adaptive_only && me->kind != BENCH_ADAPTIVE)) continue;
        s = &out[n++];
        bench_series_style(s, me, sw->count);
        for (k = 0; k < s->n; ++k) {
            s->x[k] = bench_axis_value(&st->rows[sw->first + k], c->xa);
            s->y[k] = bench_axis_value(&st->rows[sw->first + k], c->ya);
        }
    }
    return n;
}

/* Layout: cells of plot area PW x PH with margins, a legend on the right. */
#define BENCH_PW 300.0
#define BENCH_PH 210.0
#define BENCH_CW 385.0
#define BENCH_CH 300.0
#define BENCH_X0 72.0
#define BENCH_Y0 86.0
#define BENCH_LEGEND 220.0
#define BENCH_MAX_CELLS 96

/* The common range of one axis kind over every cell of a figure. */
static void bench_figure_range(const bench_state *st, const bench_cell *cells, int n, int axis,
                               double *lo, double *hi)
{
    svg_series s[BENCH_MAX_METHODS];
    double a = HUGE_VAL, b = -HUGE_VAL, l, h;
    int i, ns;
    for (i = 0; i < n; ++i) {
        const bench_cell *c = &cells[i];
        if (c->xa != axis && c->ya != axis) continue;
        ns = bench_series(st, c, s);
        if (!ns) continue;
        svg_range(s, ns, c->xa != axis, -16, &l, &h);
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

static int bench_write_figure(const bench_state *st, const char *dir, const char *file,
                              const char *title, const bench_cell *cells, int n, int ncols)
{
    svg_series s[BENCH_MAX_METHODS], legend[BENCH_MAX_METHODS];
    char path[1200];
    double rng[BENCH_AX_COUNT][2];
    int nrows = (n + ncols - 1) / ncols, i, a, nl = 0, mi;
    int used[BENCH_MAX_METHODS] = {0};
    FILE *f;
    if (n == 0) return 0;
    f = bench_open(dir, file, path, sizeof path);
    if (!f) return -1;
    for (a = 0; a < BENCH_AX_COUNT; ++a) bench_figure_range(st, cells, n, a, &rng[a][0], &rng[a][1]);
    svg_begin(f, BENCH_X0 + ncols * BENCH_CW + BENCH_LEGEND, BENCH_Y0 + nrows * BENCH_CH, title);
    svg_text(f, 16, 46, "start", 0, "fill=\"#555\"",
             "Munoz 2014 relative error |L - Lref| / max(|L|, |Lref|), worst channel; errors "
             "below 1e-16 drawn at 1e-16. Solid: fixed-step methods (one point per N); "
             "dashed: adaptive methods (one point per rtol).");
    for (i = 0; i < n; ++i) {
        const bench_cell *c = &cells[i];
        svg_panel p;
        int ns = bench_series(st, c, s), k;
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
            for (mi = 0; mi < st->nmethods; ++mi)
                if (!strcmp(s[k].label, st->methods[mi].name)) used[mi] = 1;
    }
    for (mi = 0; mi < st->nmethods; ++mi) {
        if (!used[mi]) continue;
        bench_series_style(&legend[nl++], &st->methods[mi], 0);
    }
    svg_legend(f, BENCH_X0 + ncols * BENCH_CW - 20, BENCH_Y0 + 10, legend, nl);
    svg_end(f);
    return bench_close(f, path);
}

/* Whether scene si has sweeps of that warp and medium (adaptive or not). */
static int bench_has_kind(const bench_state *st, int si, bench_warp_id w, bench_medium_id md,
                          int adaptive)
{
    int mi;
    for (mi = 0; mi < st->nmethods; ++mi)
        if (bench_find_sweep(st, si, mi, w, md) &&
            (st->methods[mi].kind == BENCH_ADAPTIVE) == adaptive)
            return 1;
    return 0;
}

static void bench_add_cell(const bench_state *st, bench_cell *cells, int *n, int si,
                           bench_warp_id w, bench_medium_id md, int xa, int ya, int adaptive_only,
                           const char *what)
{
    bench_cell *c;
    int two = 0, k;
    if (*n >= BENCH_MAX_CELLS) return;
    c = &cells[(*n)++];
    c->scene = si;
    c->warp = w;
    c->medium = md;
    c->xa = xa;
    c->ya = ya;
    c->adaptive_only = adaptive_only;
    c->way = -1;
    for (k = 0; k < BENCH_MEDIUM_COUNT; ++k) /* name the medium where the scene has two */
        two += (int)md != k && (bench_has_kind(st, si, w, (bench_medium_id)k, 0) ||
                                bench_has_kind(st, si, w, (bench_medium_id)k, 1));
    snprintf(c->title, sizeof c->title, "%s, warp %s%s%s: %s", bench_scenes[si].name,
             bench_warp_names[w], two ? ", " : "", two ? bench_medium_names[md] : "", what);
}

/* Pads each run of cells of one warp and medium to ncols with empty cells. */
static int bench_pad_rows(bench_cell *cells, int n, int ncols)
{
    bench_cell grid[BENCH_MAX_CELLS];
    int g = 0, i = 0, c;
    while (i < n) {
        int j = i;
        while (j < n && cells[j].warp == cells[i].warp && cells[j].medium == cells[i].medium) ++j;
        for (c = 0; c < ncols && g < BENCH_MAX_CELLS; ++c) {
            grid[g] = cells[i + c < j ? i + c : i];
            if (i + c >= j) grid[g].adaptive_only = 2; /* empty: no series */
            g++;
        }
        i = j;
    }
    memcpy(cells, grid, (size_t)g * sizeof grid[0]);
    return g;
}

/* The occluder's second row in fig4.svg: the three ways of the breakpoint
   section (none, the exact breakpoints, the jump search alone) with the
   natural warp, then rtol vs error with the breakpoints. */
static void bench_add_brk_row(const bench_state *st, bench_cell *cells, int *n, int si,
                              bench_warp_id w)
{
    static const char *const what[3] = {"no breakpoints, no search", "with breakpoints",
                                        "jump search alone"};
    int bi, way, any = 0;
    for (bi = 0; bi < BENCH_BRK_SCENES; ++bi) any |= st->brk[bi].scene == si;
    if (!any) return;
    for (way = 0; way < 4 && *n < BENCH_MAX_CELLS; ++way) {
        bench_add_cell(st, cells, n, si, w, BENCH_MEDIUM_CONST, way < 3 ? BENCH_AX_EVALS : BENCH_AX_RTOL,
                       BENCH_AX_ERROR, way == 3, way < 3 ? what[way] : "rtol vs error, breakpoints");
        cells[*n - 1].way = way < 3 ? way : 1;
    }
}

int bench_write_figures(const bench_state *st, const char *dir, int *files)
{
    bench_cell cells[BENCH_MAX_CELLS];
    char file[64], title[200];
    int si, w, k, n, bad = 0;

    for (si = 0; si < bench_scene_count; ++si) {
        int ncols = 0;
        n = 0;
        for (w = 0; w < BENCH_WARP_COUNT; ++w)
            for (k = 0; k < BENCH_MEDIUM_COUNT; ++k) {
                bench_warp_id wid = (bench_warp_id)w;
                bench_medium_id md = (bench_medium_id)k;
                int fixed = bench_has_kind(st, si, wid, md, 0);
                int adapt = bench_has_kind(st, si, wid, md, 1);
                int before = n;
                if (!fixed && !adapt) continue;
                bench_add_cell(st, cells, &n, si, wid, md, BENCH_AX_EVALS, BENCH_AX_ERROR, 0,
                               "error vs evaluations");
                if (adapt) {
                    bench_add_cell(st, cells, &n, si, wid, md, BENCH_AX_RTOL, BENCH_AX_ERROR, 1,
                                   "rtol vs error");
                    bench_add_cell(st, cells, &n, si, wid, md, BENCH_AX_RTOL, BENCH_AX_EVALS, 1,
                                   "rtol vs evaluations");
                }
                if (n - before > ncols) ncols = n - before;
            }
        if (!n) continue;
        n = bench_pad_rows(cells, n, ncols);
        snprintf(file, sizeof file, "%s.svg", bench_scenes[si].name);
        snprintf(title, sizeof title, "hrm.h benchmark, scene %s: %s", bench_scenes[si].name,
                 bench_scenes[si].description);
        bad |= bench_write_figure(st, dir, file, title, cells, n, ncols);
        ++*files;
    }

    /* fig4.svg */
    n = 0;
    for (si = 0; si < bench_scene_count; ++si) {
        const char *nm = bench_scenes[si].name;
        bench_warp_id nat = bench_scenes[si].natural_warp;
        if (strcmp(nm, "directional") && strcmp(nm, "point") && strcmp(nm, "occluder")) continue;
        if (!bench_has_kind(st, si, BENCH_WARP_NONE, BENCH_MEDIUM_CONST, 0) &&
            !bench_has_kind(st, si, BENCH_WARP_NONE, BENCH_MEDIUM_CONST, 1))
            continue;
        bench_add_cell(st, cells, &n, si, BENCH_WARP_NONE, BENCH_MEDIUM_CONST, BENCH_AX_EVALS,
                       BENCH_AX_ERROR, 0, "error vs evaluations");
        bench_add_cell(st, cells, &n, si, nat, BENCH_MEDIUM_CONST, BENCH_AX_EVALS, BENCH_AX_ERROR,
                       0, "error vs evaluations");
        bench_add_cell(st, cells, &n, si, BENCH_WARP_NONE, BENCH_MEDIUM_CONST, BENCH_AX_RTOL,
                       BENCH_AX_ERROR, 1, "rtol vs error");
        bench_add_cell(st, cells, &n, si, BENCH_WARP_NONE, BENCH_MEDIUM_CONST, BENCH_AX_RTOL,
                       BENCH_AX_EVALS, 1, "rtol vs evaluations");
        if (!strcmp(nm, "occluder")) bench_add_brk_row(st, cells, &n, si, nat);
    }
    if (n) {
        bad |= bench_write_figure(st, dir, "fig4.svg",
                                  "hrm.h after Munoz 2014 Fig. 4: directional, point and occluded "
                                  "point light; without and with importance sampling; tolerance "
                                  "vs error and evaluations; the occluder without and with "
                                  "breakpoints and with the jump search",
                                  cells, n, 4);
        ++*files;
    }

    /* time.svg: a row per scene and medium, a column per warp */
    if (!st->cfg.timed) return bad;
    n = 0;
    for (si = 0; si < bench_scene_count; ++si)
        for (k = 0; k < BENCH_MEDIUM_COUNT; ++k) {
            bench_medium_id md = (bench_medium_id)k;
            bench_warp_id ws[2];
            int j;
            ws[0] = BENCH_WARP_NONE;
            ws[1] = bench_scenes[si].natural_warp;
            if (!bench_has_kind(st, si, ws[0], md, 0) && !bench_has_kind(st, si, ws[0], md, 1) &&
                !bench_has_kind(st, si, ws[1], md, 0) && !bench_has_kind(st, si, ws[1], md, 1))
                continue;
            for (j = 0; j < 2; ++j)
                bench_add_cell(st, cells, &n, si, ws[j], md, BENCH_AX_NS, BENCH_AX_ERROR, 0,
                               "error vs time");
        }
    if (n) {
        bad |= bench_write_figure(st, dir, "time.svg",
                                  "hrm.h benchmark: error vs time per ray (one machine's "
                                  "numbers), without and with each scene's natural warp",
                                  cells, n, 2);
        ++*files;
    }
    return bad;
}
