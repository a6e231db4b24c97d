/* bench/svg.h - log-log line plots as plain SVG, for the benchmark's
   figures (no plotting dependency: the files open in any browser).

   A figure is a grid of panels and one legend. Each panel has decade
   axes, a title, axis labels and any number of series (a polyline with
   markers; a point whose x or y is not positive and finite breaks the line,
   which is how missing values are drawn). Ranges snap outward to whole
   decades. */

#ifndef BENCH_SVG_H
#define BENCH_SVG_H

#include <stdio.h>

#define SVG_MAX_POINTS 32

typedef struct svg_series {
    const char *label;
    const char *color;
    int dashed;
    int marker; /* 0 circle, 1 square, 2 triangle, 3 diamond, 4 inverted triangle */
    int n;
    double x[SVG_MAX_POINTS], y[SVG_MAX_POINTS];
} svg_series;

typedef struct svg_panel {
    double left, top, width, height; /* the plot area, in px */
    const char *title, *xlabel, *ylabel;
    double xlo, xhi, ylo, yhi;       /* log10 of the axis ends (whole decades) */
    int guides;                      /* 1: draw y = x and y = 10 x (tolerance plots) */
} svg_panel;

void svg_begin(FILE *f, double width, double height, const char *title);
void svg_end(FILE *f);
void svg_text(FILE *f, double x, double y, const char *anchor, double rotate,
              const char *extra, const char *s);

/* The decade range [lo, hi] (log10) that holds every positive finite value
   of the series in one coordinate, at least one decade wide; floor_log
   clamps the low end (values below it are drawn at it). */
void svg_range(const svg_series *s, int ns, int use_y, double floor_log,
               double *lo, double *hi);

void svg_panel_draw(FILE *f, const svg_panel *p, const svg_series *s, int ns);

/* One row per series: line sample, marker, label. */
void svg_legend(FILE *f, double x, double y, const svg_series *s, int ns);

#endif
