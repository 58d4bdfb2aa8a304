/* sessile render — text over a mesh picture (render_run.h): the ground
 * grid's spacing in cm in the lower left corner and, when coloured by a
 * property, a colour bar with the property's range on the right.
 *
 * The renderer's pixels are straight-alpha RGBA (a transparent background
 * is allowed) and Cairo's are premultiplied, so Cairo draws on a layer of
 * its own (transparent elsewhere) and the layer is composited here with
 * integer arithmetic: pixels the layer does not touch keep their bytes, and
 * the same picture always gets the same result. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "draw2d.h"
#include "sessile/io/colormap.h"
#include "sessile/render/render_run.h"

static void text_setup(cairo_t *cr) {
  cairo_font_options_t *fo = cairo_font_options_create();
  cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
  cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
  cairo_set_font_options(cr, fo);
  cairo_font_options_destroy(fo);
  cairo_select_font_face(cr, D2_FONT, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
}

/* Text on a white box (80 % opaque) so it reads over the mesh or the grid;
 * (x, y) is the box's corner on the side hx (0 left, 1 right), its bottom. */
static void boxed_text(cairo_t *cr, double x, double y, double fs, double hx, const char *s) {
  double pad = 0.35 * fs, tw = d2_text_width(cr, fs, s);
  cairo_font_extents_t fe;
  cairo_set_font_size(cr, fs);
  cairo_font_extents(cr, &fe);
  double bw = tw + 2 * pad, bh = fe.ascent + fe.descent + 2 * pad;
  double bx = floor(x - hx * bw), by = floor(y - bh);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
  cairo_rectangle(cr, bx, by, ceil(bw), ceil(bh));
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  d2_text(cr, bx + pad, by + pad, fs, 0, 0, 0, s);
}

static void colour_bar(cairo_t *cr, int w, int h, double fs, const sessile_render_result *res, const char *name) {
  int bw = (int)lround(fs), bh = (int)lround(0.45 * h);
  char top[32], bot[32];
  snprintf(top, sizeof top, "%.4g", res->prop_max);
  snprintf(bot, sizeof bot, "%.4g", res->prop_min);
  double lw = fmax(d2_text_width(cr, 0.9 * fs, top), d2_text_width(cr, 0.9 * fs, bot));
  int margin = (int)lround(0.8 * fs);
  int x = w - margin - (int)ceil(lw) - (int)lround(0.5 * fs) - bw, y = (h - bh) / 2;
  if (x < margin || bh < 8) return;
  /* white backing for the bar, its labels and title */
  double tw = d2_text_width(cr, 0.9 * fs, name);
  double left = fmin(x - 0.4 * fs, w - margin - tw - 0.4 * fs);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
  cairo_rectangle(cr, floor(left), y - 2.0 * fs, w - floor(left) - margin + 0.4 * fs, bh + 2.8 * fs);
  cairo_fill(cr);
  for (int r = 0; r < bh; r++) { /* row r from the top: t = 1 at the top (max), 0 at the bottom */
    unsigned char rgb[3];
    sessile_colormap(res->colormap, bh > 1 ? (double)(bh - 1 - r) / (bh - 1) : 0.5, rgb);
    cairo_set_source_rgb(cr, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
    cairo_rectangle(cr, x, y + r, bw, 1);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, x - 0.5, y - 0.5, bw + 1, bh + 1);
  cairo_stroke(cr);
  double lx = x + bw + 0.5 * fs;
  d2_text(cr, lx, y, 0.9 * fs, 0, 0.5, 0, top);
  d2_text(cr, lx, y + bh, 0.9 * fs, 0, 0.5, 0, bot);
  d2_text(cr, fmin(x, w - margin - tw), y - 0.6 * fs, 0.9 * fs, 0, 1, 0, name);
}

/* out = layer over rgba (premultiplied layer, straight-alpha picture). */
static void composite(unsigned char *rgba, int w, int h, cairo_surface_t *s) {
  const unsigned char *d = cairo_image_surface_get_data(s);
  int stride = cairo_image_surface_get_stride(s);
  for (int y = 0; y < h; y++) {
    const uint32_t *row = (const uint32_t *)(d + (size_t)y * stride);
    for (int x = 0; x < w; x++) {
      uint32_t p = row[x];
      unsigned a = p >> 24;
      if (!a) continue;
      unsigned char *o = rgba + ((size_t)y * w + x) * 4;
      unsigned src[3] = {(p >> 16) & 255, (p >> 8) & 255, p & 255};
      unsigned da = o[3], keep = 255 - a;
      unsigned oa = a + (da * keep + 127) / 255;
      for (int k = 0; k < 3; k++) {
        unsigned dp = (o[k] * da + 127) / 255; /* the picture's premultiplied value */
        unsigned op = src[k] + (dp * keep + 127) / 255;
        unsigned v = oa ? (op * 255 + oa / 2) / oa : 0;
        o[k] = (unsigned char)(v > 255 ? 255 : v);
      }
      o[3] = (unsigned char)(oa > 255 ? 255 : oa);
    }
  }
}

sessile_status sessile_render_annotate(unsigned char *rgba, int w, int h, const sessile_render_result *res,
                                       const char *color_by) {
  if (!res || !rgba) return SESSILE_OK;
  int grid = res->grid_spacing_cm > 0, bar = color_by && color_by[0] && res->colormap[0];
  if ((!grid && !bar) || w < 64 || h < 48) return SESSILE_OK;
  cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  SESSILE_CHECK(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS, SESSILE_ERR_NO_MEMORY,
                "out of host memory: cannot allocate a %d x %d annotation layer", w, h);
  cairo_t *cr = cairo_create(s);
  text_setup(cr);
  /* text size: a 40th of the height, 10..28 px */
  double fs = fmin(fmax(h / 40.0, 10), 28);
  if (grid) {
    char t[64];
    snprintf(t, sizeof t, "grid %g cm", res->grid_spacing_cm);
    boxed_text(cr, round(0.6 * fs), h - round(0.6 * fs), fs, 0, t);
  }
  if (bar) {
    char t[96];
    snprintf(t, sizeof t, "%s (%s)", color_by, res->colormap);
    colour_bar(cr, w, h, fs, res, t);
  }
  cairo_surface_flush(s);
  cairo_status_t cs = cairo_status(cr);
  if (cs == CAIRO_STATUS_SUCCESS) composite(rgba, w, h, s);
  cairo_destroy(cr);
  cairo_surface_destroy(s);
  SESSILE_CHECK(cs == CAIRO_STATUS_SUCCESS, SESSILE_ERR_INTERNAL, "annotation failed: %s", cairo_status_to_string(cs));
  return SESSILE_OK;
}
