/* bench/plot.h - a hand-written SVG scatter plot: log x, linear or log y, markers
   per series, a step line for a Pareto front, a legend.  C99, stdio only.

     plot_begin(f, width, height, title)   ...   plot_end(f)
     plot_panel(f, &panel, series, count)  one set of axes at panel.left/top
     plot_legend(f, x, y, series, count)   one entry per named series
     plot_pareto(x, y, n, keep)            keep[i] = 1 on the lower-left front */
#ifndef MANYLODS_BENCH_PLOT_H
#define MANYLODS_BENCH_PLOT_H

#include <math.h>
#include <stdio.h>

enum { PLOT_CIRCLE, PLOT_SQUARE, PLOT_TRIANGLE, PLOT_DIAMOND, PLOT_STAR, PLOT_FRONT };

typedef struct plot_series {
    const char *name;  /* legend text; NULL: no legend entry */
    const char *color; /* SVG colour */
    int marker;        /* PLOT_*; PLOT_FRONT draws a dashed step line */
    const double *x, *y;
    int count;
} plot_series;

typedef struct plot_panel_desc {
    double left, top, width, height; /* the plotting area, pixels */
    const char *title, *x_label, *y_label;
    double x_min, x_max, y_max; /* x_min, x_max > 0 (log axis); y from 0 */
    double y_min;               /* > 0: a log y axis from y_min to y_max; 0: linear from 0 */
} plot_panel_desc;

static inline void plot_begin(FILE *f, int width, int height, const char *title)
{
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
               "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"12\">\n", width, height, width, height);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    fprintf(f, "<text x=\"%d\" y=\"22\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">%s</text>\n",
            width / 2, title);
}

static inline void plot_end(FILE *f) { fprintf(f, "</svg>\n"); }

static inline void plot_marker(FILE *f, int marker, double x, double y, const char *color)
{
    switch (marker) {
    case PLOT_SQUARE:
        fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"8\" height=\"8\" fill=\"%s\" fill-opacity=\"0.85\" "
                   "stroke=\"black\" stroke-width=\"0.5\"/>\n", x - 4, y - 4, color);
        break;
    case PLOT_TRIANGLE:
        fprintf(f, "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" fill-opacity=\"0.85\" "
                   "stroke=\"black\" stroke-width=\"0.5\"/>\n", x, y - 5.5, x - 5, y + 4, x + 5, y + 4, color);
        break;
    case PLOT_DIAMOND:
        fprintf(f, "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"%s\" fill-opacity=\"0.85\" "
                   "stroke=\"black\" stroke-width=\"0.5\"/>\n", x, y - 5.5, x + 5.5, y, x, y + 5.5, x - 5.5, y, color);
        break;
    case PLOT_STAR: {
        int k;
        fprintf(f, "<polygon points=\"");
        for (k = 0; k < 10; k++) {
            double a = -1.5707963 + k * 0.6283185, r = (k & 1) ? 3.0 : 7.0;
            fprintf(f, "%.1f,%.1f ", x + r * cos(a), y + r * sin(a));
        }
        fprintf(f, "\" fill=\"%s\" stroke=\"black\" stroke-width=\"0.5\"/>\n", color);
        break;
    }
    default:
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"%s\" fill-opacity=\"0.75\" stroke=\"black\" "
                   "stroke-width=\"0.4\"/>\n", x, y, color);
    }
}

/* keep[i] = 1 when no other point is at most as slow and as wrong and
   strictly better in one of the two. */
static inline void plot_pareto(const double *x, const double *y, int n, int *keep)
{
    int i, j;
    for (i = 0; i < n; i++) {
        keep[i] = isfinite(x[i]) && isfinite(y[i]);
        for (j = 0; j < n && keep[i]; j++)
            if (j != i && isfinite(x[j]) && isfinite(y[j]) && x[j] <= x[i] && y[j] <= y[i] &&
                (x[j] < x[i] || y[j] < y[i]))
                keep[i] = 0;
    }
}

/* The nearest of 1, 2, 5 times a power of ten at or beyond x, downwards
   (up = 0) or upwards (up = 1): tight log-axis bounds. */
static inline double plot_nice(double x, int up)
{
    static const double steps[4] = {1, 2, 5, 10};
    double decade = pow(10.0, floor(log10(x)));
    int k;
    if (up) {
        for (k = 0; k < 4; k++)
            if (steps[k] * decade >= x * 0.999) return steps[k] * decade;
        return 10 * decade;
    }
    for (k = 2; k >= 0; k--)
        if (steps[k] * decade <= x * 1.001) return steps[k] * decade;
    return decade;
}

static inline double plot_px(const plot_panel_desc *p, double x)
{
    return p->left + p->width * (log10(x) - log10(p->x_min)) / (log10(p->x_max) - log10(p->x_min));
}

static inline double plot_py(const plot_panel_desc *p, double y)
{
    double v = y > p->y_max ? p->y_max : y < 0 ? 0 : y;
    if (p->y_min > 0) {
        v = v < p->y_min ? p->y_min : v;
        return p->top + p->height * (1.0 - (log10(v) - log10(p->y_min)) / (log10(p->y_max) - log10(p->y_min)));
    }
    return p->top + p->height * (1.0 - v / p->y_max);
}

static inline void plot_panel(FILE *f, const plot_panel_desc *p, const plot_series *series, int count)
{
    double decade, t;
    int s, i, k;
    fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"#444\"/>\n", p->left,
            p->top, p->width, p->height);
    fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-weight=\"bold\">%s</text>\n",
            p->left + p->width / 2, p->top - 8, p->title);
    /* x: decades with 2 and 5 between them */
    for (decade = pow(10.0, floor(log10(p->x_min))); decade <= p->x_max; decade *= 10.0) {
        static const double steps[3] = {1, 2, 5};
        for (k = 0; k < 3; k++) {
            double x = decade * steps[k], px;
            if (x < p->x_min * 0.999 || x > p->x_max * 1.001) continue;
            px = plot_px(p, x);
            fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", px, p->top, px,
                    p->top + p->height);
            if (x >= 1000)
                fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"10\">%gk</text>\n", px,
                        p->top + p->height + 14, x / 1000);
            else
                fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"10\">%g</text>\n", px,
                        p->top + p->height + 14, x);
        }
    }
    /* y: 5 steps from 0, or the decades of a log axis */
    for (i = 0; i <= 5 || (p->y_min > 0 && p->y_min * pow(10.0, i) <= p->y_max * 1.001); i++) {
        double y = p->y_min > 0 ? p->y_min * pow(10.0, i) : p->y_max * i / 5.0, py;
        if (p->y_min > 0 && y > p->y_max * 1.001) break;
        py = plot_py(p, y);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", p->left, py,
                p->left + p->width, py);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\" font-size=\"10\">%.3g</text>\n", p->left - 4,
                py + 3, y);
    }
    fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%s</text>\n", p->left + p->width / 2,
            p->top + p->height + 32, p->x_label);
    t = p->top + p->height / 2;
    fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" transform=\"rotate(-90 %.1f %.1f)\">%s</text>\n",
            p->left - 42, t, p->left - 42, t, p->y_label);
    for (s = 0; s < count; s++) {
        const plot_series *q = &series[s];
        if (q->marker == PLOT_FRONT) { /* points sorted by x: a staircase */
            double prev_x = 0, prev_y = 0;
            fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\" points=\"",
                    q->color);
            for (i = 0; i < q->count; i++) {
                double px = plot_px(p, q->x[i]), py = plot_py(p, q->y[i]);
                if (i > 0) fprintf(f, "%.1f,%.1f ", px, prev_y);
                fprintf(f, "%.1f,%.1f ", px, py);
                prev_x = px;
                prev_y = py;
            }
            (void)prev_x;
            fprintf(f, "\"/>\n");
            continue;
        }
        for (i = 0; i < q->count; i++) {
            if (!(q->x[i] > 0) || !isfinite(q->y[i])) continue;
            if (q->x[i] < p->x_min || q->x[i] > p->x_max) continue;
            plot_marker(f, q->marker, plot_px(p, q->x[i]), plot_py(p, q->y[i]), q->color);
        }
    }
}

static inline void plot_legend(FILE *f, double x, double y, const plot_series *series, int count)
{
    int s, row = 0;
    for (s = 0; s < count; s++) {
        double ty = y + 18.0 * row;
        if (!series[s].name) continue;
        if (series[s].marker == PLOT_FRONT)
            fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"1.5\" "
                       "stroke-dasharray=\"5,3\"/>\n", x - 8, ty, x + 8, ty, series[s].color);
        else
            plot_marker(f, series[s].marker, x, ty, series[s].color);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\">%s</text>\n", x + 14, ty + 4, series[s].name);
        row++;
    }
}

#endif /* MANYLODS_BENCH_PLOT_H */
