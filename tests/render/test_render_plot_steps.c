/* The plot's right-hand y axis and sessile_render_plot_sds_steps (Fig. 12 of
 * the SDS paper from sds/steps.csv): each axis's range from its own series,
 * a right-axis series' markers where the right axis maps them, the widened
 * margin holding the axis's coloured label, a plot without a right axis laid
 * out as before; the steps log drawn (columns by name, ms <= 0 no point),
 * 55 000 steps quickly, and bad logs refused naming the column or line. */
#include <math.h>
#include <sys/stat.h>
#include "render2d_testutil.h"
#include "sessile/render/render2d.h"
#include "testutil.h"


static const unsigned char blue[3] = {0x1f, 0x77, 0xb4}, orange[3] = {0xff, 0x7f, 0x0e}, white[3] = {255, 255, 255};

/* The pixel of data point (x, y) on the left (axis2 0) or right axis, by the
 * affine transform computed here from the layout's corners and ranges. */
static uint32_t px_on(const t_png *p, const sessile_plot_layout *L, int axis2, double x, double y) {
  double a = axis2 ? L->y20 : L->y0, b = axis2 ? L->y21 : L->y1;
  double fx = L->px0 + (x - L->x0) / (L->x1 - L->x0) * (L->px1 - L->px0);
  double fy = L->py0 - (y - a) / (b - a) * (L->py0 - L->py1);
  return t_px(p, (int)floor(fx), (int)floor(fy));
}

/* Pixels of colour rgb (within 8 levels) in columns [x0, x1) of the picture. */
static int count_colour(const t_png *p, int x0, int x1, const unsigned char rgb[3]) {
  int n = 0;
  for (int y = 0; y < p->h; y++)
    for (int x = x0; x < x1 && x < p->w; x++) n += t_rgb_diff(t_px(p, x, y), rgb) <= 8;
  return n;
}

/* Whether px is colour c drawn over white at some coverage (antialiased
 * text): every channel's (255 - px) / (255 - c) the same, at least 0.4. */
static int tinted(uint32_t px, const unsigned char c[3]) {
  double a = -1;
  for (int k = 0; k < 3; k++) {
    int v = (int)(px >> (16 - 8 * k)) & 255;
    double d = 255.0 - c[k];
    if (d < 30) { /* a channel the colour saturates stays near white */
      if (255 - v > 30) return 0;
      continue;
    }
    double ak = (255.0 - v) / d;
    if (a < 0) a = ak;
    if (fabs(ak - a) > 0.2) return 0;
  }
  return a > 0.4;
}

static int count_tinted(const t_png *p, int x0, int x1, const unsigned char rgb[3]) {
  int n = 0;
  for (int y = 0; y < p->h; y++)
    for (int x = x0; x < x1 && x < p->w; x++) n += tinted(t_px(p, x, y), rgb);
  return n;
}

/* Near-black pixels (text) in columns [x0, x1). */
static int count_dark(const t_png *p, int x0, int x1) {
  int n = 0;
  for (int y = 0; y < p->h; y++)
    for (int x = x0; x < x1 && x < p->w; x++) n += (t_px(p, x, y) & 0xffffff) < 0x606060;
  return n;
}

/* Whether step is 1, 2 or 5 times a power of ten. */
static int is125(double step) {
  double m = step / pow(10, floor(log10(step)));
  return fabs(m - 1) < 1e-9 || fabs(m - 2) < 1e-9 || fabs(m - 5) < 1e-9;
}

static void bad(const char *what, sessile_status s, const char *out, const char *must_contain) {
  char msg[600];
  const char *m = sessile_error_message();
  snprintf(msg, sizeof msg, "%s: SESSILE_ERR_USAGE, one line naming \"%s\", nothing written [%s]", what, must_contain,
           m);
  t_true(msg, s == SESSILE_ERR_USAGE && !strchr(m, '\n') && strstr(m, must_contain) && !t_exists(out));
}

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (f) fputs(text, f), fclose(f);
}

static const char *const HEADER = "step,time,dt,cells,tets,ms,divisions,inversions\n";

/* Steps of the test log: time 0.5 k, cells 180 + 10 k, ms 1 + (k % 3); step 4 untimed (ms 0). */
#define NSTEP 20
static double st_time(int k) { return 0.5 * (k + 1); }
static double st_cells(int k) { return 180 + 10 * k; }
static double st_ms(int k) { return k == 4 ? 0 : 1 + (k % 3); }

static void twin_axes(void) {
  /* left: 1.0 down to 0.5; right: 2000 up to 3000 (they cross at x = 5) */
  double x[11], yl[11], yr[11];
  for (int i = 0; i <= 10; i++) x[i] = i, yl[i] = 1.0 - 0.05 * i, yr[i] = 2000 + 100 * i;
  sessile_plot p = {
      .title = "twin",
      .xlabel = "x",
      .ylabel = "left (1)",
      .y2label = "right (cells)",
      .nseries = 2,
      .series = {{.label = "L", .x = x, .y = yl, .n = 11}, {.label = "R", .x = x, .y = yr, .n = 11, .axis2 = 1}}};
  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  sessile_plot_layout L;
  t_ok("twin: layout", sessile_render_plot_layout(&p, &o, &L));
  t_true("twin: a right-hand axis is in use", L.has_y2 == 1);
  t_true("twin: the left axis covers 0.5..1 and not the right's 2000..3000 (y0 <= 0.5, 1 <= y1 < 2)",
         L.y0 <= 0.5 && L.y1 >= 1 && L.y1 < 2);
  t_true("twin: the right axis covers 2000..3000 and not the left's 0.5..1 (1 < y20 <= 2000, y21 >= 3000)",
         L.y20 > 1 && L.y20 <= 2000 && L.y21 >= 3000);
  double k2 = round((L.y21 - L.y20) / L.y2step);
  t_true("twin: the right range holds a whole number (>= 2) of its ticks, a 1-2-5 step",
         k2 >= 2 && fabs(L.y20 + k2 * L.y2step - L.y21) < 1e-9 * L.y21 && is125(L.y2step));
  t_true("twin: the right margin widened (px1 < 800 - 28) but leaves most of the width (px1 > 600)",
         L.px1 < 772 && L.px1 > 600 && L.px0 == 84);
  t_ok("twin: plot", sessile_render_plot(&p, &o, P("twin.png")));
  t_png img = t_png_read(P("twin.png"));
  t_true("twin: the PNG reads back at 800 x 600", img.px && img.w == 800 && img.h == 600);
  if (!img.px) return;
  int worst_r = 0, worst_l = 0;
  for (int i = 0; i <= 10; i++) {
    if (i == 5) continue; /* the lines cross there */
    worst_r = (int)fmax(worst_r, t_rgb_diff(px_on(&img, &L, 1, x[i], yr[i]), orange));
    worst_l = (int)fmax(worst_l, t_rgb_diff(px_on(&img, &L, 0, x[i], yl[i]), blue));
  }
  t_check("twin: the right series' 10 markers at the right axis's pixels, orange (max level diff)", worst_r, 1);
  t_check("twin: the left series' 10 markers at the left axis's pixels, blue (max level diff)", worst_l, 1);
  int px1 = (int)L.px1;
  t_true("twin: the right axis's label is orange, right of the tick labels (> 50 orange pixels beyond px1 + 30)",
         count_tinted(&img, px1 + 30, img.w, orange) > 50);
  t_true("twin: the left axis's label is blue (> 50 blue pixels left of x = 40)", count_tinted(&img, 0, 40, blue) > 50);
  t_true("twin: the right tick labels are drawn in the margin (> 100 dark pixels in px1 + 6 .. px1 + 30)",
         count_dark(&img, px1 + 6, px1 + 30) > 100);
  t_true("twin: nothing is cut off at the right edge (the last 4 columns white)",
         count_colour(&img, img.w - 4, img.w, white) == 4 * img.h);
  free(img.px);

  /* only right-axis series: the left axis is 0..1, the right one the data's */
  sessile_plot pr = p;
  pr.series[0].axis2 = 1;
  t_ok("right-only: layout", sessile_render_plot_layout(&pr, &o, &L));
  t_true("right-only: left axis 0..1, right axis covers 0.5..3000",
         L.y0 == 0 && L.y1 == 1 && L.y20 <= 0.5 && L.y21 >= 3000);
}

static void unchanged_without_axis2(void) {
  /* a zero-initialised plot (no axis2, no y2label), as callers before the right axis wrote it */
  double x[3] = {0, 1, 2}, y[3] = {3, 1, 2};
  sessile_plot p = {0};
  p.title = "one axis", p.xlabel = "x (cm)", p.ylabel = "y (s)";
  p.nseries = 1, p.series[0] = (sessile_plot_series){.label = "a", .x = x, .y = y, .n = 3};
  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  sessile_plot_layout L;
  t_ok("one axis: layout", sessile_render_plot_layout(&p, &o, &L));
  t_true("one axis: no right axis (has_y2 0, its range and step 0)",
         L.has_y2 == 0 && L.y20 == 0 && L.y21 == 0 && L.y2step == 0);
  t_true("one axis: the plot area of before (84..772 by 542..62 on 800 x 600)",
         L.px0 == 84 && L.px1 == 800 - 28 && L.py0 == 600 - 58 && L.py1 == 62);
  t_true("one axis: x 0..2 and y 1..3 on whole ticks", L.x0 == 0 && L.x1 == 2 && L.y0 == 1 && L.y1 == 3);
  t_ok("one axis: plot", sessile_render_plot(&p, &o, P("one.png")));
  p.y2label = "unused";
  t_ok("one axis with a y2label but no series on it: plot", sessile_render_plot(&p, &o, P("one_label.png")));
  t_true("... identical bytes: a y2label alone draws nothing", t_same_bytes(P("one.png"), P("one_label.png")));
  t_png img = t_png_read(P("one.png"));
  if (img.px) {
    t_true("one axis: the y label stays black (no blue left of x = 40, some dark)",
           count_tinted(&img, 0, 40, blue) == 0 && count_dark(&img, 0, 40) > 50);
    free(img.px);
  } else {
    t_true("one axis: PNG reads back", 0);
  }
}

static void steps_log(void) {
  char *text = t_xalloc(64 * (NSTEP + 8)), *reordered = t_xalloc(64 * (NSTEP + 8));
  size_t n = (size_t)sprintf(text, "%s", HEADER), m = (size_t)sprintf(reordered, "\r\ncells, extra ,ms,time\r\n");
  for (int k = 0; k < NSTEP; k++) {
    n += (size_t)sprintf(text + n, "%d,%.17g,0.5,%g,%g,%.17g,%d,0\n", k + 1, st_time(k), st_cells(k), 4 * st_cells(k),
                         st_ms(k), k % 7 == 0);
    if (k == 10) n += (size_t)sprintf(text + n, "\n  \n"); /* blank lines are skipped */
    m += (size_t)sprintf(reordered + m, "%g,7,%g,%g\r\n", st_cells(k), st_ms(k), st_time(k));
  }
  write_text(P("steps.csv"), text);
  write_text(P("reordered.csv"), reordered);
  /* a running run's log read mid-append: its unterminated last row is left out */
  sprintf(text + n, "%d,%.17g,0.5,99", NSTEP + 1, st_time(NSTEP));
  write_text(P("growing.csv"), text);
  free(text), free(reordered);
  sessile_render2d_opts o;
  sessile_render2d_opts_default(&o);
  t_ok("steps.csv: drawn", sessile_render_plot_sds_steps(P("steps.csv"), &o, P("steps.png")));
  t_ok("steps.csv with NULL options: drawn", sessile_render_plot_sds_steps(P("steps.csv"), NULL, P("steps_def.png")));
  t_png img = t_png_read(P("steps_def.png"));
  t_true("steps.csv: a PNG of the default 800 x 600", img.px && img.w == 800 && img.h == 600);
  free(img.px);
  t_ok("columns in another order, an extra one, CRLF and a leading blank line: drawn",
       sessile_render_plot_sds_steps(P("reordered.csv"), &o, P("reordered.png")));
  t_true("... the same picture, byte for byte (columns found by name)",
         t_same_bytes(P("steps.png"), P("reordered.png")));
  t_ok("a last row without its newline (a log being appended): drawn",
       sessile_render_plot_sds_steps(P("growing.csv"), &o, P("growing.png")));
  t_true("... without that row, byte for byte", t_same_bytes(P("steps.png"), P("growing.png")));

  /* where the points must be: the same data laid out here, ms 0 as no point */
  double t[NSTEP], ms[NSTEP], cells[NSTEP];
  for (int k = 0; k < NSTEP; k++) t[k] = st_time(k), cells[k] = st_cells(k), ms[k] = st_ms(k) > 0 ? st_ms(k) : NAN;
  sessile_plot p = {.y2label = "cells",
                    .nseries = 2,
                    .series = {{.x = t, .y = ms, .n = NSTEP}, {.x = t, .y = cells, .n = NSTEP, .axis2 = 1}}};
  sessile_plot_layout L;
  t_ok("steps: layout of the same points", sessile_render_plot_layout(&p, &o, &L));
  t_true("steps: x is the time (0.5..10 within 0..10), the left axis ms 1..3 (not 0: the untimed step is no point)",
         L.x0 == 0 && L.x1 == 10 && L.y0 == 1 && L.y1 == 3);
  t_true("steps: the right axis holds the cells (180..370)", L.has_y2 && L.y20 <= 180 && L.y21 >= 370 && L.y20 > 3);
  img = t_png_read(P("steps.png"));
  if (img.px) {
    int worst_ms = 0, worst_cells = 0, nms = 0;
    for (int k = 0; k < NSTEP; k++) {
      /* an ms marker the cells marker covers (both at one height) is not checked */
      double hl = (ms[k] - L.y0) / (L.y1 - L.y0), hr = (cells[k] - L.y20) / (L.y21 - L.y20);
      if (k != 4 && fabs(hl - hr) * (L.py0 - L.py1) > 10)
        worst_ms = (int)fmax(worst_ms, t_rgb_diff(px_on(&img, &L, 0, t[k], ms[k]), blue)), nms++;
      worst_cells = (int)fmax(worst_cells, t_rgb_diff(px_on(&img, &L, 1, t[k], cells[k]), orange));
    }
    char what[160];
    snprintf(what, sizeof what,
             "steps: %d ms markers (blue, none covered) where the left axis maps them (max level diff)", nms);
    t_check(what, nms >= 15 ? worst_ms : 999, 1);
    t_check("steps: 20 cells markers (orange) where the right axis maps them (max level diff)", worst_cells, 1);
    free(img.px);
  } else {
    t_true("steps PNG reads back", 0);
  }

  /* a long run: 55 000 steps (the rock model's log) are read and drawn */
  FILE *f = fopen(P("long.csv"), "w");
  if (f) {
    fputs(HEADER, f);
    for (int k = 0; k < 55000; k++)
      fprintf(f, "%d,%.17g,0.002,%d,%d,%.17g,0,0\n", k + 1, 0.002 * (k + 1), 180 + k / 250, 4 * (180 + k / 250),
              1 + 0.5 * sin(k * 0.37) + (k % 997 == 0 ? 20 : 0));
    fclose(f);
  }
  /* (tests assert no wall times: the drawing's speed is not checked here) */
  t_ok("55 000 steps: drawn", sessile_render_plot_sds_steps(P("long.csv"), &o, P("long.png")));
  struct stat lst;
  t_true("55 000 steps: a PNG written", stat(P("long.png"), &lst) == 0 && lst.st_size > 1000);

  /* bad logs: nothing written, the message names the problem */
  write_text(P("no_ms.csv"), "step,time,dt,cells,tets,divisions,inversions\n1,0.5,0.5,180,720,0,0\n");
  bad("a header without ms", sessile_render_plot_sds_steps(P("no_ms.csv"), &o, P("b1.png")), P("b1.png"),
      "column 'ms'");
  bad("... and names the file", sessile_render_plot_sds_steps(P("no_ms.csv"), &o, P("b1.png")), P("b1.png"),
      "no_ms.csv");
  write_text(P("no_cells.csv"), "time,ms\n0.5,1\n");
  bad("a header without cells", sessile_render_plot_sds_steps(P("no_cells.csv"), &o, P("b2.png")), P("b2.png"),
      "column 'cells'");
  write_text(P("word.csv"),
             "step,time,dt,cells,tets,ms,divisions,inversions\n1,0.5,0.5,180,720,1.2,0,0\n\n"
             "2,1.0,0.5,180,720,fast,0,0\n");
  bad("a row with a word for ms (line 4)", sessile_render_plot_sds_steps(P("word.csv"), &o, P("b3.png")), P("b3.png"),
      "line 4");
  write_text(P("short.csv"),
             "step,time,dt,cells,tets,ms,divisions,inversions\n1,0.5,0.5,180,720,1.2,0,0\n"
             "2,1.0,0.5,180,720,1.3\n");
  bad("a row of 6 fields (line 3)", sessile_render_plot_sds_steps(P("short.csv"), &o, P("b4.png")), P("b4.png"),
      "line 3: 6 fields");
  write_text(P("nan.csv"), "time,ms,cells\n0.5,1,180\n1.0,nan,190\n");
  bad("a NaN field (line 3)", sessile_render_plot_sds_steps(P("nan.csv"), &o, P("b5.png")), P("b5.png"), "line 3");
  write_text(P("header_only.csv"), HEADER);
  bad("a header and no steps", sessile_render_plot_sds_steps(P("header_only.csv"), &o, P("b6.png")), P("b6.png"),
      "no steps");
  bad("a missing log", sessile_render_plot_sds_steps(P("none.csv"), &o, P("b7.png")), P("b7.png"), "none.csv");
  o.width = 100000;
  bad("a picture of 100000 pixels", sessile_render_plot_sds_steps(P("steps.csv"), &o, P("b8.png")), P("b8.png"),
      "100000");
}

int main(void) {
  dir = t_scratch("test_render_plot_steps");
  twin_axes();
  unchanged_without_axis2();
  steps_log();
  return t_finish(NULL);
}
