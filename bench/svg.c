/* bench/svg.c - log-log line plots as plain SVG (svg.h). */
#include "svg.h"

#include <math.h>

static void svg_text_escaped(FILE *f, const char *s)
{
    for (; *s; ++s) {
        if (*s == '<') fputs("&lt;", f);
        else if (*s == '>') fputs("&gt;", f);
        else if (*s == '&') fputs("&amp;", f);
        else fputc(*s, f);
    }
}

void svg_begin(FILE *f, double width, double height, const char *title)
{
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
            "viewBox=\"0 0 %.0f %.0f\" font-family=\"Helvetica, Arial, sans-serif\" "
            "font-size=\"12\">\n"
            "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n"
            "<text x=\"%.1f\" y=\"24\" font-size=\"16\" font-weight=\"bold\">",
            width, height, width, height, width, height, 16.0);
    svg_text_escaped(f, title);
    fprintf(f, "</text>\n");
}

void svg_end(FILE *f)
{
    fprintf(f, "</svg>\n");
}

void svg_text(FILE *f, double x, double y, const char *anchor, double rotate,
              const char *extra, const char *s)
{
    fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\"", x, y, anchor);
    if (rotate != 0) fprintf(f, " transform=\"rotate(%.0f %.1f %.1f)\"", rotate, x, y);
    if (extra) fprintf(f, " %s", extra);
    fprintf(f, ">");
    svg_text_escaped(f, s);
    fprintf(f, "</text>\n");
}

/* The decade range [lo, hi] (log10) that holds every positive finite value
   of the series in one coordinate, at least one decade wide; floor_log
   clamps the low end (values below it are drawn at it). */
void svg_range(const svg_series *s, int ns, int use_y, double floor_log,
               double *lo, double *hi)
{
    double a = HUGE_VAL, b = -HUGE_VAL;
    int i, k;
    for (i = 0; i < ns; ++i)
        for (k = 0; k < s[i].n; ++k) {
            double v = use_y ? s[i].y[k] : s[i].x[k], l;
            if (!(v > 0) || v - v != 0) continue;
            l = log10(v);
            if (l < floor_log) l = floor_log;
            if (l < a) a = l;
            if (l > b) b = l;
        }
    if (a > b) { /* no data */
        a = 0;
        b = 1;
    }
    *lo = floor(a + 1e-9);
    *hi = ceil(b - 1e-9);
    if (*hi <= *lo) *hi = *lo + 1;
}

static double svg_px(const svg_panel *p, double v, int use_y)
{
    double l = log10(v), lo = use_y ? p->ylo : p->xlo, hi = use_y ? p->yhi : p->xhi;
    double u;
    if (l < lo) l = lo;
    if (l > hi) l = hi;
    u = (l - lo) / (hi - lo);
    return use_y ? p->top + p->height * (1 - u) : p->left + p->width * u;
}

static void svg_marker(FILE *f, int marker, double x, double y, const char *color)
{
    const double r = 3.2;
    switch (marker % 5) {
    case 1:
        fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"%s\"/>\n",
                x - r, y - r, 2 * r, 2 * r, color);
        break;
    case 2:
        fprintf(f, "<path d=\"M%.1f %.1fL%.1f %.1fL%.1f %.1fZ\" fill=\"%s\"/>\n", x, y - r - 0.6,
                x + r + 0.6, y + r, x - r - 0.6, y + r, color);
        break;
    case 3:
        fprintf(f, "<path d=\"M%.1f %.1fL%.1f %.1fL%.1f %.1fL%.1f %.1fZ\" fill=\"%s\"/>\n", x,
                y - r - 0.8, x + r + 0.8, y, x, y + r + 0.8, x - r - 0.8, y, color);
        break;
    case 4:
        fprintf(f, "<path d=\"M%.1f %.1fL%.1f %.1fL%.1f %.1fZ\" fill=\"%s\"/>\n", x, y + r + 0.6,
                x + r + 0.6, y - r, x - r - 0.6, y - r, color);
        break;
    default:
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\"/>\n", x, y, r, color);
    }
}

/* Decade ticks with labels 10^k; with many decades, every other label. */
static void svg_axes(FILE *f, const svg_panel *p)
{
    double d;
    int xstep = p->xhi - p->xlo > 8 ? 2 : 1, ystep = p->yhi - p->ylo > 8 ? 2 : 1;
    fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
               "stroke=\"#444\"/>\n",
            p->left, p->top, p->width, p->height);
    for (d = p->xlo; d <= p->xhi + 1e-9; d += 1) {
        double x = p->left + p->width * (d - p->xlo) / (p->xhi - p->xlo);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#e4e4e4\"/>\n",
                x, p->top, x, p->top + p->height);
        if (((int)(d - p->xlo)) % xstep == 0) {
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">10<tspan "
                       "dy=\"-6\" font-size=\"9\">%d</tspan></text>\n",
                    x, p->top + p->height + 16, (int)d);
        }
    }
    for (d = p->ylo; d <= p->yhi + 1e-9; d += 1) {
        double y = p->top + p->height * (1 - (d - p->ylo) / (p->yhi - p->ylo));
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#e4e4e4\"/>\n",
                p->left, y, p->left + p->width, y);
        if (((int)(d - p->ylo)) % ystep == 0)
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">10<tspan dy=\"-6\" "
                       "font-size=\"9\">%d</tspan></text>\n",
                    p->left - 4, y + 4, (int)d);
    }
    svg_text(f, p->left + p->width / 2, p->top - 8, "middle", 0, "font-weight=\"bold\"", p->title);
    svg_text(f, p->left + p->width / 2, p->top + p->height + 34, "middle", 0, NULL, p->xlabel);
    svg_text(f, p->left - 38, p->top + p->height / 2, "middle", -90, NULL, p->ylabel);
}

/* y = x (solid grey) and y = 10 x (dotted) over the panel, clipped, with a
   key in the panel's lower right corner (the tolerance plots). */
static void svg_guides(FILE *f, const svg_panel *p)
{
    int k;
    for (k = 0; k < 2; ++k) {
        double lo = p->xlo > p->ylo - k ? p->xlo : p->ylo - k;
        double hi = p->xhi < p->yhi - k ? p->xhi : p->yhi - k;
        double x0, x1, y0, y1;
        if (hi <= lo) continue;
        x0 = p->left + p->width * (lo - p->xlo) / (p->xhi - p->xlo);
        x1 = p->left + p->width * (hi - p->xlo) / (p->xhi - p->xlo);
        y0 = p->top + p->height * (1 - (lo + k - p->ylo) / (p->yhi - p->ylo));
        y1 = p->top + p->height * (1 - (hi + k - p->ylo) / (p->yhi - p->ylo));
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#999\" "
                   "stroke-width=\"1\"%s/>\n",
                x0, y0, x1, y1, k ? " stroke-dasharray=\"2 3\"" : "");
    }
    svg_text(f, p->left + p->width - 4, p->top + p->height - 6, "end", 0,
             "fill=\"#777\" font-size=\"10\"", "grey: error = rtol; dotted: 10 rtol");
}

void svg_panel_draw(FILE *f, const svg_panel *p, const svg_series *s, int ns)
{
    int i, k;
    svg_axes(f, p);
    if (p->guides) svg_guides(f, p);
    for (i = 0; i < ns; ++i) {
        int open = 0;
        for (k = 0; k < s[i].n; ++k) {
            double x = s[i].x[k], y = s[i].y[k];
            int ok = x > 0 && y > 0 && x - x == 0 && y - y == 0;
            if (!ok) {
                if (open) fprintf(f, "\"/>\n");
                open = 0;
                continue;
            }
            if (!open)
                fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\"%s "
                           "points=\"",
                        s[i].color, s[i].dashed ? " stroke-dasharray=\"6 3\"" : "");
            fprintf(f, "%.1f,%.1f ", svg_px(p, x, 0), svg_px(p, y, 1));
            open = 1;
        }
        if (open) fprintf(f, "\"/>\n");
        for (k = 0; k < s[i].n; ++k) {
            double x = s[i].x[k], y = s[i].y[k];
            if (x > 0 && y > 0 && x - x == 0 && y - y == 0)
                svg_marker(f, s[i].marker, svg_px(p, x, 0), svg_px(p, y, 1), s[i].color);
        }
    }
}

/* One row per series: line sample, marker, label. */
void svg_legend(FILE *f, double x, double y, const svg_series *s, int ns)
{
    int i;
    for (i = 0; i < ns; ++i) {
        double yy = y + 18 * i;
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                   "stroke-width=\"1.5\"%s/>\n",
                x, yy, x + 28, yy, s[i].color, s[i].dashed ? " stroke-dasharray=\"6 3\"" : "");
        svg_marker(f, s[i].marker, x + 14, yy, s[i].color);
        svg_text(f, x + 36, yy + 4, "start", 0, NULL, s[i].label);
    }
}
