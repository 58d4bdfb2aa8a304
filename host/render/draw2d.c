/* sessile render — Cairo helpers (draw2d.h).
 *
 * Text goes through Cairo's "toy" font API with DejaVu Sans (Debian's
 * fonts-dejavu-core): no Pango, one font, grey antialiasing and no hinting,
 * so glyph positions do not depend on the screen's font settings.  The PNG is
 * written by sessile_png_write_rgba8 from the unpremultiplied pixels, not by
 * cairo_surface_write_to_png (which is not atomic). */
#include "draw2d.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/png.h"

sessile_status d2_check_size(const char *what, int w, int h) {
  SESSILE_CHECK(w >= SESSILE_RENDER2D_MIN_SIZE && h >= SESSILE_RENDER2D_MIN_SIZE && w <= SESSILE_RENDER2D_MAX_SIZE &&
                    h <= SESSILE_RENDER2D_MAX_SIZE,
                SESSILE_ERR_USAGE, "%s: a picture of %d x %d pixels is outside %d..%d per side", what, w, h,
                SESSILE_RENDER2D_MIN_SIZE, SESSILE_RENDER2D_MAX_SIZE);
  return SESSILE_OK;
}

sessile_status d2_canvas_create(d2_canvas *c, int w, int h, const char *what) {
  c->s = NULL;
  c->cr = NULL;
  c->w = w, c->h = h;
  c->s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  if (cairo_surface_status(c->s) != CAIRO_STATUS_SUCCESS) {
    d2_canvas_destroy(c);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "%s: out of host memory: cannot allocate a %d x %d picture (%.0f MB)", what, w,
                             h, 4.0 * w * h / 1e6);
  }
  c->cr = cairo_create(c->s);
  if (cairo_status(c->cr) != CAIRO_STATUS_SUCCESS) {
    d2_canvas_destroy(c);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "%s: out of host memory: cannot create a Cairo context", what);
  }
  cairo_font_options_t *fo = cairo_font_options_create();
  cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
  cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
  cairo_set_font_options(c->cr, fo);
  cairo_font_options_destroy(fo);
  cairo_select_font_face(c->cr, D2_FONT, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_source_rgb(c->cr, 1, 1, 1);
  cairo_paint(c->cr);
  cairo_surface_flush(c->s);
  return SESSILE_OK;
}

void d2_canvas_destroy(d2_canvas *c) {
  if (c->cr) cairo_destroy(c->cr);
  if (c->s) cairo_surface_destroy(c->s);
  c->cr = NULL;
  c->s = NULL;
}

uint32_t *d2_row(d2_canvas *c, int y) {
  unsigned char *d = cairo_image_surface_get_data(c->s);
  return (uint32_t *)(d + (size_t)y * (size_t)cairo_image_surface_get_stride(c->s));
}

sessile_status d2_canvas_write_png(d2_canvas *c, const char *path) {
  cairo_surface_flush(c->s);
  SESSILE_CHECK(cairo_status(c->cr) == CAIRO_STATUS_SUCCESS, SESSILE_ERR_INTERNAL, "drawing '%s' failed: %s",
                path, cairo_status_to_string(cairo_status(c->cr)));
  unsigned char *rgba = malloc((size_t)c->w * (size_t)c->h * 4);
  SESSILE_CHECK(rgba, SESSILE_ERR_NO_MEMORY, "out of memory writing '%s'", path);
  for (int y = 0; y < c->h; y++) {
    const uint32_t *row = d2_row(c, y);
    unsigned char *o = rgba + (size_t)y * c->w * 4;
    for (int x = 0; x < c->w; x++) {
      uint32_t p = row[x];
      unsigned a = p >> 24;
      unsigned rgb[3] = {(p >> 16) & 255, (p >> 8) & 255, p & 255};
      for (int k = 0; k < 3; k++) /* Cairo premultiplies; our canvases are opaque, so a = 255 */
        o[4 * x + k] = (unsigned char)(a ? (rgb[k] * 255 + a / 2) / a : 0);
      o[4 * x + 3] = (unsigned char)a;
    }
  }
  sessile_status s = sessile_png_write_rgba8(path, c->w, c->h, rgba);
  free(rgba);
  return s;
}

double d2_text_width(cairo_t *cr, double size, const char *s) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t te;
  cairo_text_extents(cr, s, &te);
  return te.x_advance;
}

void d2_text(cairo_t *cr, double x, double y, double size, double hx, double vy, double angle, const char *s) {
  cairo_save(cr);
  cairo_set_font_size(cr, size);
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  cairo_text_extents_t te;
  cairo_text_extents(cr, s, &te);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  /* vy: 0 puts the ascent line at y, 1 the descent line, 0.5 between */
  cairo_move_to(cr, -hx * te.x_advance, fe.ascent * (1 - vy) - fe.descent * vy);
  cairo_show_text(cr, s);
  cairo_restore(cr);
}

double d2_tick_step(double lo, double hi, int maxticks) {
  double span = hi - lo;
  if (!(span > 0) || !isfinite(span)) return 1;
  double e = pow(10, floor(log10(span / maxticks)));
  static const double m[] = {1, 2, 5, 10, 20};
  for (int i = 0; i < 5; i++) {
    double s = m[i] * e;
    /* ticks: the multiples of s in [lo, hi] */
    double n = floor(hi / s + 1e-9) - ceil(lo / s - 1e-9) + 1;
    if (n <= maxticks) return s;
  }
  return 50 * e;
}

int d2_ticks(double lo, double hi, int maxticks, double *first, double *step) {
  double s = d2_tick_step(lo, hi, maxticks);
  double k0 = ceil(lo / s - 1e-9), k1 = floor(hi / s + 1e-9);
  *first = k0 * s;
  *step = s;
  return k1 >= k0 ? (int)(k1 - k0) + 1 : 0;
}

void d2_tick_label(char *buf, size_t n, double v, double step) {
  if (fabs(v) < 1e-9 * step) v = 0; /* no "-0" or "1e-17" at zero */
  double a = fmax(fabs(v), step);
  if (a >= 1e5 || step < 1e-4) {
    snprintf(buf, n, "%.3g", v);
    return;
  }
  int dec = (int)ceil(-log10(step) - 1e-9);
  if (dec < 0) dec = 0;
  snprintf(buf, n, "%.*f", dec, v);
}
