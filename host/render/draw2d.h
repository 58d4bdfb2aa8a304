/* sessile render — Cairo helpers shared by the slice, plot and sheet
 * pictures: the canvas, text, the 1-2-5 tick rule, and the PNG hand-off. */
#ifndef SESSILE_DRAW2D_H
#define SESSILE_DRAW2D_H
#include <cairo.h>
#include <stdint.h>
#include "sessile/render/render2d.h"

#define D2_FONT "DejaVu Sans"

/* A white canvas of w x h pixels (ARGB32) with a context set up for
 * deterministic text (grey antialiasing, no hinting). */
typedef struct d2_canvas {
  cairo_surface_t *s;
  cairo_t *cr;
  int w, h;
} d2_canvas;

sessile_status d2_canvas_create(d2_canvas *c, int w, int h, const char *what);
void d2_canvas_destroy(d2_canvas *c);
/* Writes the canvas as an RGBA PNG (atomic). */
sessile_status d2_canvas_write_png(d2_canvas *c, const char *path);
/* The pixel (x, y) for writing: 0xAARRGGBB (native-endian uint32). */
uint32_t *d2_row(d2_canvas *c, int y);
static inline uint32_t d2_rgb(const unsigned char rgb[3]) {
  return 0xff000000u | (uint32_t)rgb[0] << 16 | (uint32_t)rgb[1] << 8 | rgb[2];
}

/* Checks a requested picture size (0 takes def). */
sessile_status d2_check_size(const char *what, int w, int h);

/* Text at (x, y): hx, vy in {0, 0.5, 1} anchor the text's left/centre/right
 * and top/middle/baseline-bottom at the point; angle in radians (counter-
 * clockwise, e.g. -pi/2 for a vertical axis label reading upwards). */
void d2_text(cairo_t *cr, double x, double y, double size, double hx, double vy, double angle, const char *s);
double d2_text_width(cairo_t *cr, double size, const char *s);

/* The 1-2-5 rule: the smallest step s = {1, 2, 5} x 10^k with at most
 * maxticks ticks over [lo, hi]; *first is the first multiple of s >= lo
 * (with rounding slack), *n the number of ticks in [lo, hi]. */
double d2_tick_step(double lo, double hi, int maxticks);
int d2_ticks(double lo, double hi, int maxticks, double *first, double *step);
/* A tick label for value v on a grid of `step` ("0.25", "1e+06"). */
void d2_tick_label(char *buf, size_t n, double v, double step);
#endif
