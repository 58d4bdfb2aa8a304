/* sessile render — one channel of an EXR slice as a picture (render2d.h):
 * the field colour-mapped at every picture pixel (bilinear between the
 * slice's node samples), a colour bar, the physical axes in cm, the sponge's
 * outline.  The image is written pixel by pixel into the Cairo surface (no
 * scaling filter in between), so a test can predict every pixel; Cairo draws
 * the text, ticks, frames and the outline. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "draw2d.h"
#include "sessile/io/colormap.h"
#include "slice_internal.h"

#define MARGIN_L 72
#define MARGIN_R 150 /* the colour bar, its ticks and label */
#define MARGIN_T 54  /* title and the values line */
#define MARGIN_B 52
#define BAR_GAP 24
#define BAR_W 22
#define MIN_W 320
#define MIN_H 200
#define HALF_PI 1.57079632679489662

void sessile_render2d_opts_default(sessile_render2d_opts *o) {
  memset(o, 0, sizeof *o);
  o->width = 800, o->height = 600;
}

/* The unit of the channels sessile writes (host/growth/grow_output.c). */
static const char *channel_unit(const char *ch) {
  if (!strcmp(ch, "ux") || !strcmp(ch, "uy") || !strcmp(ch, "uz") || !strcmp(ch, "umag")) return "m/s";
  if (!strcmp(ch, "p")) return "Pa";
  return NULL; /* c is dimensionless (0 on the sponge, 1 far away) */
}

typedef struct slice_pic {
  slice_image im;
  sessile_slice_layout lay;
  double lo, hi; /* the finite data range */
  double ext_u, ext_v;
} slice_pic;

/* The value at in-plane (u, v): bilinear between the four nodes around it. */
static double sample(const slice_image *im, double u, double v) {
  double fi = (u - im->u0) / im->su, fj = (v - im->v0) / im->sv;
  fi = fmin(fmax(fi, 0), im->w - 1);
  fj = fmin(fmax(fj, 0), im->h - 1);
  int i = (int)fi, j = (int)fj;
  if (i > im->w - 2) i = im->w > 1 ? im->w - 2 : 0;
  if (j > im->h - 2) j = im->h > 1 ? im->h - 2 : 0;
  double a = im->w > 1 ? fi - i : 0, b = im->h > 1 ? fj - j : 0;
  int i1 = im->w > 1 ? i + 1 : i, j1 = im->h > 1 ? j + 1 : j;
  const float *f = im->val;
  double f00 = f[(size_t)j * im->w + i], f10 = f[(size_t)j * im->w + i1];
  double f01 = f[(size_t)j1 * im->w + i], f11 = f[(size_t)j1 * im->w + i1];
  return (1 - b) * ((1 - a) * f00 + a * f10) + b * ((1 - a) * f01 + a * f11);
}

/* Reads the slice and decides the map, range and geometry. */
static sessile_status slice_prepare(const char *exr_path, const char *channel, const sessile_render2d_opts *o,
                                    slice_pic *sp) {
  memset(sp, 0, sizeof *sp);
  sessile_render2d_opts def;
  if (!o) sessile_render2d_opts_default(&def), o = &def;
  int W = o->width, H = o->height;
  char what[96];
  snprintf(what, sizeof what, "slice picture");
  SESSILE_CALL(d2_check_size(what, W, H));
  SESSILE_CHECK(W >= MIN_W && H >= MIN_H, SESSILE_ERR_USAGE,
                "a slice picture of %d x %d pixels leaves no room for the axes and colour bar (at least %d x %d)", W,
                H, MIN_W, MIN_H);
  const char *cmap = o->colormap && o->colormap[0] && strcmp(o->colormap, "auto") ? o->colormap : NULL;
  SESSILE_CHECK(!cmap || sessile_colormap_known(cmap), SESSILE_ERR_USAGE, "unknown colour map '%s' (known: auto, %s)",
                cmap, sessile_colormap_names());
  SESSILE_CHECK(!o->fixed_range || (isfinite(o->vmin) && isfinite(o->vmax) && o->vmin < o->vmax), SESSILE_ERR_USAGE,
                "the colour range [%g, %g] needs finite ends with min < max", o->vmin, o->vmax);
  SESSILE_CALL(slice_read(exr_path, channel, o, &sp->im));
  slice_image *im = &sp->im;
  double lo = INFINITY, hi = -INFINITY;
  for (size_t q = 0; q < (size_t)im->w * im->h; q++)
    if (isfinite(im->val[q])) lo = fmin(lo, im->val[q]), hi = fmax(hi, im->val[q]);
  if (!(lo <= hi)) {
    slice_image_free(im);
    return sessile_error_set(SESSILE_ERR_USAGE, "channel '%s' of '%s' has no finite value", channel, exr_path);
  }
  sp->lo = lo, sp->hi = hi;

  sessile_slice_layout *L = &sp->lay;
  L->width = W, L->height = H;
  /* signed: both signs with the smaller side at least 1 % of the larger, so
   * float noise around 0 (c = -1e-9 next to the sponge) keeps one-signed */
  int is_signed = lo < 0 && hi > 0 && fmin(-lo, hi) >= 0.01 * fmax(-lo, hi);
  const char *use = cmap ? cmap : is_signed ? "coolwarm" : "viridis";
  snprintf(L->colormap, sizeof L->colormap, "%s", use);
  if (o->fixed_range) L->vmin = o->vmin, L->vmax = o->vmax;
  else if (!strcmp(use, "coolwarm")) {
    double m = fmax(fabs(lo), fabs(hi)); /* 0 at the map's centre */
    L->vmin = -m, L->vmax = m;
  } else L->vmin = lo, L->vmax = hi;
  if (!(L->vmax > L->vmin)) { /* a constant field: a range around it */
    double d = L->vmin != 0 ? 0.5 * fabs(L->vmin) : 1;
    L->vmin -= d, L->vmax += d;
  }

  sp->ext_u = im->w > 1 ? (im->w - 1) * im->su : im->su;
  sp->ext_v = im->h > 1 ? (im->h - 1) * im->sv : im->sv;
  L->u0 = im->w > 1 ? im->u0 : im->u0 - 0.5 * im->su;
  L->v0 = im->h > 1 ? im->v0 : im->v0 - 0.5 * im->sv;
  L->u1 = L->u0 + sp->ext_u, L->v1 = L->v0 + sp->ext_v;
  int aw = W - MARGIN_L - MARGIN_R, ah = H - MARGIN_T - MARGIN_B;
  double scale = fmin(aw / sp->ext_u, ah / sp->ext_v); /* same cm per pixel on both axes */
  L->img_w = (int)fmax(1, fmin(aw, lround(sp->ext_u * scale)));
  L->img_h = (int)fmax(1, fmin(ah, lround(sp->ext_v * scale)));
  L->img_x = MARGIN_L + (aw - L->img_w) / 2;
  L->img_y = MARGIN_T + (ah - L->img_h) / 2;
  L->bar_x = L->img_x + L->img_w + BAR_GAP, L->bar_y = L->img_y, L->bar_w = BAR_W, L->bar_h = L->img_h;
  return SESSILE_OK;
}

sessile_status sessile_render_slice_layout(const char *exr_path, const char *channel,
                                           const sessile_render2d_opts *o, sessile_slice_layout *lay) {
  slice_pic sp;
  SESSILE_CALL(slice_prepare(exr_path, channel, o, &sp));
  *lay = sp.lay;
  slice_image_free(&sp.im);
  return SESSILE_OK;
}

/* Ticks along one side of a rectangle: horizontal (bottom) or vertical (left
 * or right, labels on that side).  lo..hi maps onto p0..p1 pixels. */
static double axis_ticks(cairo_t *cr, double lo, double hi, double p0, double p1, double at, int side, int maxticks) {
  double first, step, widest = 0;
  int n = d2_ticks(lo, hi, maxticks, &first, &step);
  for (int k = 0; k < n; k++) {
    double val = first + k * step, p = p0 + (val - lo) / (hi - lo) * (p1 - p0);
    char lab[32];
    d2_tick_label(lab, sizeof lab, val, step);
    widest = fmax(widest, d2_text_width(cr, 12, lab));
    if (side == 0) { /* bottom */
      double x = floor(p) + 0.5;
      cairo_move_to(cr, x, at), cairo_line_to(cr, x, at + 5);
      d2_text(cr, p, at + 7, 12, 0.5, 0, 0, lab);
    } else { /* 1 left, 2 right */
      double y = floor(p) + 0.5, dir = side == 1 ? -1 : 1;
      cairo_move_to(cr, at, y), cairo_line_to(cr, at + 5 * dir, y);
      d2_text(cr, at + 7 * dir, p, 12, side == 1 ? 1 : 0, 0.5, 0, lab);
    }
  }
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  return widest;
}

static void draw_outline(cairo_t *cr, const sessile_slice_layout *L, const seg_list *s) {
  if (!s->n) return;
  cairo_save(cr);
  cairo_rectangle(cr, L->img_x, L->img_y, L->img_w, L->img_h);
  cairo_clip(cr);
  double kx = L->img_w / (L->u1 - L->u0), ky = L->img_h / (L->v1 - L->v0);
  for (int pass = 0; pass < 2; pass++) { /* a white halo, then black: visible on every map */
    for (size_t k = 0; k < s->n; k++) {
      const double *q = s->p + 4 * k;
      cairo_move_to(cr, L->img_x + (q[0] - L->u0) * kx, L->img_y + (L->v1 - q[1]) * ky);
      cairo_line_to(cr, L->img_x + (q[2] - L->u0) * kx, L->img_y + (L->v1 - q[3]) * ky);
    }
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_width(cr, pass ? 1.5 : 3.5);
    cairo_set_source_rgb(cr, pass ? 0 : 1, pass ? 0 : 1, pass ? 0 : 1);
    cairo_stroke(cr);
  }
  cairo_restore(cr);
}

sessile_status sessile_render_slice(const char *exr_path, const char *channel, const sessile_render2d_opts *o,
                                    const char *png_out) {
  SESSILE_CHECK(png_out && png_out[0], SESSILE_ERR_USAGE, "no output picture given");
  slice_pic sp;
  SESSILE_CALL(slice_prepare(exr_path, channel, o, &sp));
  const slice_image *im = &sp.im;
  const sessile_slice_layout *L = &sp.lay;
  seg_list segs = {0};
  sessile_status st = SESSILE_OK;
  if (o && o->outline_ply && o->outline_ply[0]) st = slice_cut_ply(im, o->outline_ply, &segs);
  else if (im->aux) st = slice_contour(im, im->aux, im->aux_level, &segs);
  d2_canvas cv = {0};
  if (st == SESSILE_OK) st = d2_canvas_create(&cv, L->width, L->height, png_out);
  if (st != SESSILE_OK) {
    seg_list_free(&segs);
    slice_image_free(&sp.im);
    return st;
  }
  cairo_t *cr = cv.cr;
  /* the field: picture pixel centres mapped to the plane, v upwards */
  double span = L->vmax - L->vmin;
  for (int py = 0; py < L->img_h; py++) {
    uint32_t *row = d2_row(&cv, L->img_y + py);
    double v = L->v1 - (py + 0.5) / L->img_h * (L->v1 - L->v0);
    for (int px = 0; px < L->img_w; px++) {
      double u = L->u0 + (px + 0.5) / L->img_w * (L->u1 - L->u0);
      unsigned char rgb[3];
      sessile_colormap(L->colormap, (sample(im, u, v) - L->vmin) / span, rgb); /* NaN: grey */
      row[L->img_x + px] = d2_rgb(rgb);
    }
  }
  /* the colour bar: exact map ends at its top (vmax) and bottom (vmin) rows */
  for (int r = 0; r < L->bar_h; r++) {
    uint32_t *row = d2_row(&cv, L->bar_y + r);
    unsigned char rgb[3];
    sessile_colormap(L->colormap, L->bar_h > 1 ? (double)(L->bar_h - 1 - r) / (L->bar_h - 1) : 0.5, rgb);
    for (int x = 0; x < L->bar_w; x++) row[L->bar_x + x] = d2_rgb(rgb);
  }
  cairo_surface_mark_dirty(cv.s);

  seg_list *sg = &segs;
  draw_outline(cr, L, sg);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  /* frames just outside the image and the bar, so no field pixel is touched */
  cairo_rectangle(cr, L->img_x - 0.5, L->img_y - 0.5, L->img_w + 1, L->img_h + 1);
  cairo_rectangle(cr, L->bar_x - 0.5, L->bar_y - 0.5, L->bar_w + 1, L->bar_h + 1);
  cairo_stroke(cr);
  axis_ticks(cr, L->u0, L->u1, L->img_x, L->img_x + L->img_w, L->img_y + L->img_h + 0.5, 0, L->img_w / 70 + 2);
  axis_ticks(cr, L->v0, L->v1, L->img_y + L->img_h, L->img_y, L->img_x - 0.5, 1, L->img_h / 45 + 2);
  double bar_labels = axis_ticks(cr, L->vmin, L->vmax, L->bar_y + L->bar_h, L->bar_y, L->bar_x + L->bar_w + 0.5, 2,
                                 L->bar_h / 40 + 2);

  char buf[256];
  snprintf(buf, sizeof buf, "%s (cm)", im->uname);
  d2_text(cr, L->img_x + 0.5 * L->img_w, L->img_y + L->img_h + 26, 13, 0.5, 0, 0, buf);
  snprintf(buf, sizeof buf, "%s (cm)", im->vname);
  d2_text(cr, L->img_x - 50, L->img_y + 0.5 * L->img_h, 13, 0.5, 1, -HALF_PI, buf);
  const char *unit = channel_unit(channel);
  if (unit) snprintf(buf, sizeof buf, "%s (%s)", channel, unit);
  else snprintf(buf, sizeof buf, "%s", channel);
  d2_text(cr, fmin(L->bar_x + L->bar_w + 12 + bar_labels + 4, L->width - 20), L->bar_y + 0.5 * L->bar_h, 13, 0.5, 1, HALF_PI, buf);
  if (o && o->title && o->title[0]) snprintf(buf, sizeof buf, "%s", o->title);
  else if (im->iteration >= 0) snprintf(buf, sizeof buf, "%s on %s, iteration %d", channel, im->plane, im->iteration);
  else snprintf(buf, sizeof buf, "%s on %s", channel, im->plane);
  d2_text(cr, 0.5 * L->width, 8, 15, 0.5, 0, 0, buf);
  snprintf(buf, sizeof buf, "values %.4g to %.4g, map %s%s%s", sp.lo, sp.hi, L->colormap,
           segs.n ? ", outline: " : "", segs.n ? (o && o->outline_ply && o->outline_ply[0] ? "surface mesh" : im->aux_name) : "");
  d2_text(cr, 0.5 * L->width, 30, 12, 0.5, 0, 0, buf);

  st = d2_canvas_write_png(&cv, png_out);
  d2_canvas_destroy(&cv);
  seg_list_free(&segs);
  slice_image_free(&sp.im);
  return st;
}
