/* sessile render — line plots of number series (render2d.h): axes with
 * ticks by the 1-2-5 rule, the ranges extended to whole ticks, grid lines,
 * labels (with units), markers joined by lines, interval bars (confidence
 * intervals) where a series has them, a legend above the plot,
 * and optionally a right-hand y axis for series of another scale. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "draw2d.h"

#define MARGIN_L 84
#define MARGIN_R 28
#define MARGIN_T 62 /* title and legend */
#define MARGIN_B 58
#define MARKER_R 3.5
#define BAR_CAP 5       /* half the width of an interval bar's caps */
#define MAX_MARKERS 200 /* more points than this: lines only */
#define TICK_GAP 8      /* from the frame to a tick label */
#define LABEL_GAP 10    /* from the widest tick label to the axis label */
#define AXIS_LABEL_PT 13
#define TICK_LABEL_PT 12

/* matplotlib's "tab10" first colours: distinct, and readable on white */
static const double series_rgb[SESSILE_PLOT_MAX_SERIES][3] = {
    {0x1f / 255.0, 0x77 / 255.0, 0xb4 / 255.0}, {0xff / 255.0, 0x7f / 255.0, 0x0e / 255.0},
    {0x2c / 255.0, 0xa0 / 255.0, 0x2c / 255.0}, {0xd6 / 255.0, 0x27 / 255.0, 0x28 / 255.0},
    {0x94 / 255.0, 0x67 / 255.0, 0xbd / 255.0}, {0x8c / 255.0, 0x56 / 255.0, 0x4b / 255.0},
    {0xe3 / 255.0, 0x77 / 255.0, 0xc2 / 255.0}, {0x7f / 255.0, 0x7f / 255.0, 0x7f / 255.0}};

/* lo..hi widened to whole ticks; a single value gets a range around it */
static void nice_range(double lo, double hi, int maxticks, double *a, double *b, double *step) {
  if (!(hi > lo)) {
    double d = lo != 0 ? 0.5 * fabs(lo) : 1;
    lo -= d, hi += d;
  }
  double s = d2_tick_step(lo, hi, maxticks);
  *a = floor(lo / s + 1e-9) * s;
  *b = ceil(hi / s - 1e-9) * s;
  *step = s;
}

/* An axis's range from its data's extent; no data (lo > hi): 0..1. */
static void axis_range(double lo, double hi, int maxticks, double *a, double *b, double *step) {
  if (lo > hi) lo = 0, hi = 1;
  nice_range(lo, hi, maxticks, a, b, step);
}

/* The number of tick intervals from a to b (a whole number by nice_range). */
static int axis_ticks(double a, double b, double step) { return (int)floor((b - a) / step + 0.5); }

/* The right margin a right-hand axis needs: its tick labels as wide as they
 * measure in the plot's font, then its rotated label (the left margin is
 * fixed, but the right axis's numbers, cells by the thousand say, vary). */
static sessile_status right_margin(const sessile_plot_layout *L, const sessile_plot *p, double *margin) {
  d2_canvas cv;
  SESSILE_CALL(d2_canvas_create(&cv, 1, 1, "plot"));
  double wmax = 0;
  char lab[32];
  for (int k = 0; k <= axis_ticks(L->y20, L->y21, L->y2step); k++) {
    d2_tick_label(lab, sizeof lab, L->y20 + k * L->y2step, L->y2step);
    wmax = fmax(wmax, d2_text_width(cv.cr, TICK_LABEL_PT, lab));
  }
  double label = 0;
  if (p->y2label && p->y2label[0]) {
    cairo_font_extents_t fe;
    cairo_set_font_size(cv.cr, AXIS_LABEL_PT);
    cairo_font_extents(cv.cr, &fe);
    label = LABEL_GAP + ceil(fe.ascent + fe.descent);
  }
  d2_canvas_destroy(&cv);
  *margin = fmax(MARGIN_R, TICK_GAP + ceil(wmax) + label + 8);
  return SESSILE_OK;
}

/* Point i of a series has an interval bar (both bounds finite). */
static int has_bar(const sessile_plot_series *ser, size_t i) {
  return ser->ylo && ser->yhi && isfinite(ser->ylo[i]) && isfinite(ser->yhi[i]);
}

sessile_status sessile_render_plot_layout(const sessile_plot *p, const sessile_render2d_opts *o,
                                          sessile_plot_layout *L) {
  sessile_render2d_opts def;
  if (!o) sessile_render2d_opts_default(&def), o = &def;
  SESSILE_CALL(d2_check_size("plot", o->width, o->height));
  SESSILE_CHECK(o->width >= 240 && o->height >= 160, SESSILE_ERR_USAGE,
                "a plot of %d x %d pixels leaves no room for its axes (at least 240 x 160)", o->width, o->height);
  SESSILE_CHECK(p && p->nseries >= 1 && p->nseries <= SESSILE_PLOT_MAX_SERIES, SESSILE_ERR_USAGE,
                "a plot needs 1..%d series (got %d)", SESSILE_PLOT_MAX_SERIES, p ? p->nseries : 0);
  /* y extents per axis: [0] the left, [1] the right */
  double xlo = INFINITY, xhi = -INFINITY, ylo[2] = {INFINITY, INFINITY}, yhi[2] = {-INFINITY, -INFINITY};
  int has_y2 = 0;
  for (int s = 0; s < p->nseries; s++) {
    const sessile_plot_series *ser = &p->series[s];
    SESSILE_CHECK(ser->n == 0 || (ser->x && ser->y), SESSILE_ERR_USAGE, "plot series %d has no values", s);
    int a = ser->axis2 != 0;
    has_y2 |= a;
    for (size_t i = 0; i < ser->n; i++)
      if (isfinite(ser->x[i]) && isfinite(ser->y[i])) {
        xlo = fmin(xlo, ser->x[i]), xhi = fmax(xhi, ser->x[i]);
        ylo[a] = fmin(ylo[a], ser->y[i]), yhi[a] = fmax(yhi[a], ser->y[i]);
        if (has_bar(ser, i)) ylo[a] = fmin(ylo[a], ser->ylo[i]), yhi[a] = fmax(yhi[a], ser->yhi[i]);
      }
  }
  SESSILE_CHECK(xlo <= xhi, SESSILE_ERR_USAGE, "nothing to plot: no series has a finite point");
  memset(L, 0, sizeof *L);
  L->width = o->width, L->height = o->height;
  L->py0 = o->height - MARGIN_B, L->py1 = MARGIN_T;
  int yticks = (int)((L->py0 - L->py1) / 50) + 2;
  axis_range(ylo[0], yhi[0], yticks, &L->y0, &L->y1, &L->ystep);
  double margin_r = MARGIN_R;
  if (has_y2) {
    L->has_y2 = 1;
    axis_range(ylo[1], yhi[1], yticks, &L->y20, &L->y21, &L->y2step);
    SESSILE_CALL(right_margin(L, p, &margin_r));
  }
  L->px0 = MARGIN_L, L->px1 = o->width - margin_r;
  SESSILE_CHECK(L->px1 - L->px0 >= 40, SESSILE_ERR_USAGE,
                "a plot %d pixels wide leaves no room for its right-hand axis's labels (%.0f pixels)", o->width,
                margin_r);
  nice_range(xlo, xhi, (int)((L->px1 - L->px0) / 80) + 2, &L->x0, &L->x1, &L->xstep);
  return SESSILE_OK;
}

static double map_x(const sessile_plot_layout *L, double x) { return L->px0 + (x - L->x0) / (L->x1 - L->x0) * (L->px1 - L->px0); }
static double map_y(const sessile_plot_layout *L, double y) { return L->py0 + (y - L->y0) / (L->y1 - L->y0) * (L->py1 - L->py0); }
static double map_y2(const sessile_plot_layout *L, double y) {
  return L->py0 + (y - L->y20) / (L->y21 - L->y20) * (L->py1 - L->py0);
}
/* y of a series through its own axis */
static double map_ys(const sessile_plot_layout *L, const sessile_plot_series *ser, double y) {
  return L->has_y2 && ser->axis2 ? map_y2(L, y) : map_y(L, y);
}

/* An axis label's colour: with two y axes, that of the axis's first series
 * (which line reads against which axis); else black. */
static void axis_label_colour(cairo_t *cr, const sessile_plot_layout *L, const sessile_plot *p, int axis2) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  if (!L->has_y2) return;
  for (int s = 0; s < p->nseries; s++)
    if ((p->series[s].axis2 != 0) == axis2) {
      cairo_set_source_rgb(cr, series_rgb[s][0], series_rgb[s][1], series_rgb[s][2]);
      return;
    }
}

/* The right-hand axis: ticks out of the frame, labels right of them, the
 * label rotated as the left one is. */
static void draw_axis2(cairo_t *cr, const sessile_plot_layout *L, const sessile_plot *p) {
  char lab[32];
  double wmax = 0;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  for (int k = 0; k <= axis_ticks(L->y20, L->y21, L->y2step); k++) {
    double v = L->y20 + k * L->y2step, y = floor(map_y2(L, v)) + 0.5;
    cairo_move_to(cr, L->px1 + 0.5, y), cairo_line_to(cr, L->px1 + 5.5, y);
    d2_tick_label(lab, sizeof lab, v, L->y2step);
    d2_text(cr, L->px1 + TICK_GAP, map_y2(L, v), TICK_LABEL_PT, 0, 0.5, 0, lab);
    wmax = fmax(wmax, d2_text_width(cr, TICK_LABEL_PT, lab));
  }
  cairo_stroke(cr);
  if (!p->y2label || !p->y2label[0]) return;
  axis_label_colour(cr, L, p, 1);
  d2_text(cr, L->px1 + TICK_GAP + ceil(wmax) + LABEL_GAP, 0.5 * (L->py0 + L->py1), AXIS_LABEL_PT, 0.5, 0,
          -1.57079632679489662, p->y2label);
}

static void draw_axes(cairo_t *cr, const sessile_plot_layout *L, const sessile_plot *p) {
  char lab[32];
  int nx = (int)floor((L->x1 - L->x0) / L->xstep + 0.5), ny = (int)floor((L->y1 - L->y0) / L->ystep + 0.5);
  /* grid lines on pixel centres */
  cairo_set_line_width(cr, 1);
  cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
  for (int k = 1; k < nx; k++) {
    double x = floor(map_x(L, L->x0 + k * L->xstep)) + 0.5;
    cairo_move_to(cr, x, L->py1), cairo_line_to(cr, x, L->py0);
  }
  for (int k = 1; k < ny; k++) {
    double y = floor(map_y(L, L->y0 + k * L->ystep)) + 0.5;
    cairo_move_to(cr, L->px0, y), cairo_line_to(cr, L->px1, y);
  }
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, floor(L->px0) - 0.5, floor(L->py1) - 0.5, L->px1 - L->px0 + 1, L->py0 - L->py1 + 1);
  for (int k = 0; k <= nx; k++) {
    double v = L->x0 + k * L->xstep, x = floor(map_x(L, v)) + 0.5;
    cairo_move_to(cr, x, L->py0 + 0.5), cairo_line_to(cr, x, L->py0 + 5.5);
    d2_tick_label(lab, sizeof lab, v, L->xstep);
    d2_text(cr, map_x(L, v), L->py0 + 8, 12, 0.5, 0, 0, lab);
  }
  for (int k = 0; k <= ny; k++) {
    double v = L->y0 + k * L->ystep, y = floor(map_y(L, v)) + 0.5;
    cairo_move_to(cr, L->px0 - 0.5, y), cairo_line_to(cr, L->px0 - 5.5, y);
    d2_tick_label(lab, sizeof lab, v, L->ystep);
    d2_text(cr, L->px0 - 8, map_y(L, v), 12, 1, 0.5, 0, lab);
  }
  cairo_stroke(cr);
  if (p->xlabel) d2_text(cr, 0.5 * (L->px0 + L->px1), L->py0 + 28, 13, 0.5, 0, 0, p->xlabel);
  if (p->ylabel) {
    axis_label_colour(cr, L, p, 0);
    d2_text(cr, 16, 0.5 * (L->py0 + L->py1), 13, 0.5, 0, -1.57079632679489662, p->ylabel);
    cairo_set_source_rgb(cr, 0, 0, 0);
  }
  if (p->title) d2_text(cr, 0.5 * L->width, 8, 15, 0.5, 0, 0, p->title);
  if (L->has_y2) draw_axis2(cr, L, p);
}

static void draw_series(cairo_t *cr, const sessile_plot_layout *L, const sessile_plot *p) {
  cairo_save(cr);
  /* markers on the axes' ends may overhang the frame, as in matplotlib */
  double m = MARKER_R + 1;
  cairo_rectangle(cr, L->px0 - m, L->py1 - m, L->px1 - L->px0 + 2 * m, L->py0 - L->py1 + 2 * m);
  cairo_clip(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (int s = 0; s < p->nseries; s++) { /* lines first, then every marker on top */
    const sessile_plot_series *ser = &p->series[s];
    int pen = 0;
    for (size_t i = 0; i < ser->n; i++) {
      if (!isfinite(ser->x[i]) || !isfinite(ser->y[i])) { /* a gap */
        pen = 0;
        continue;
      }
      if (pen) cairo_line_to(cr, map_x(L, ser->x[i]), map_ys(L, ser, ser->y[i]));
      else cairo_move_to(cr, map_x(L, ser->x[i]), map_ys(L, ser, ser->y[i]));
      pen = 1;
    }
    cairo_set_source_rgb(cr, series_rgb[s][0], series_rgb[s][1], series_rgb[s][2]);
    cairo_set_line_width(cr, 1.5);
    cairo_stroke(cr);
  }
  for (int s = 0; s < p->nseries; s++) { /* interval bars under the markers */
    const sessile_plot_series *ser = &p->series[s];
    int any = 0;
    for (size_t i = 0; i < ser->n; i++)
      if (isfinite(ser->x[i]) && isfinite(ser->y[i]) && has_bar(ser, i)) {
        double x = floor(map_x(L, ser->x[i])) + 0.5, a = map_ys(L, ser, ser->ylo[i]), b = map_ys(L, ser, ser->yhi[i]);
        cairo_move_to(cr, x, a), cairo_line_to(cr, x, b);
        cairo_move_to(cr, x - BAR_CAP, a), cairo_line_to(cr, x + BAR_CAP, a);
        cairo_move_to(cr, x - BAR_CAP, b), cairo_line_to(cr, x + BAR_CAP, b);
        any = 1;
      }
    if (!any) continue;
    cairo_set_source_rgb(cr, series_rgb[s][0], series_rgb[s][1], series_rgb[s][2]);
    cairo_set_line_width(cr, 1.5);
    cairo_stroke(cr);
  }
  for (int s = 0; s < p->nseries; s++) {
    const sessile_plot_series *ser = &p->series[s];
    if (ser->n > MAX_MARKERS) continue;
    for (size_t i = 0; i < ser->n; i++)
      if (isfinite(ser->x[i]) && isfinite(ser->y[i])) {
        cairo_new_sub_path(cr);
        cairo_arc(cr, map_x(L, ser->x[i]), map_ys(L, ser, ser->y[i]), MARKER_R, 0, 6.28318530717958648);
      }
    cairo_set_source_rgb(cr, series_rgb[s][0], series_rgb[s][1], series_rgb[s][2]);
    cairo_fill(cr);
  }
  cairo_restore(cr);
}

static void draw_legend(cairo_t *cr, const sessile_plot_layout *L, const sessile_plot *p) {
  double x = L->px0, y = 40;
  for (int s = 0; s < p->nseries; s++) {
    const char *label = p->series[s].label ? p->series[s].label : "";
    cairo_set_source_rgb(cr, series_rgb[s][0], series_rgb[s][1], series_rgb[s][2]);
    cairo_set_line_width(cr, 1.5);
    cairo_move_to(cr, x, y), cairo_line_to(cr, x + 22, y);
    cairo_stroke(cr);
    cairo_arc(cr, x + 11, y, MARKER_R, 0, 6.28318530717958648);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    d2_text(cr, x + 28, y, 12, 0, 0.5, 0, label);
    x += 28 + d2_text_width(cr, 12, label) + 18;
  }
}

sessile_status sessile_render_plot(const sessile_plot *p, const sessile_render2d_opts *o, const char *png_out) {
  SESSILE_CHECK(png_out && png_out[0], SESSILE_ERR_USAGE, "no output picture given");
  sessile_plot_layout L;
  SESSILE_CALL(sessile_render_plot_layout(p, o, &L));
  d2_canvas cv;
  SESSILE_CALL(d2_canvas_create(&cv, L.width, L.height, png_out));
  draw_axes(cv.cr, &L, p);
  draw_series(cv.cr, &L, p);
  draw_legend(cv.cr, &L, p);
  sessile_status st = d2_canvas_write_png(&cv, png_out);
  d2_canvas_destroy(&cv);
  return st;
}
