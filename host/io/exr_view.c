/* sessile io — the colour view of an EXR slice: R, G, B from one data
 * channel through the colour map `sessile render --color-by` uses, so that
 * image viewers, compositors and Blender show the field without knowing
 * its channels (docs/io.md "Slices").
 *
 * The choice follows --color-by: the finite values' range, coolwarm
 * symmetric about 0 when the range crosses 0, else viridis; a constant
 * field at the map's middle; NaN grey.  The tables hold 8-bit sRGB, while
 * EXR pixels are linear light: each entry is decoded to linear, so a viewer
 * that encodes for display shows the map's own colours. */
#include <math.h>
#include "exr_view.h"
#include "sessile/io/colormap.h"

/* The sRGB transfer function's inverse (IEC 61966-2-1). */
static float srgb_to_linear(unsigned char c) {
  double v = c / 255.0;
  return (float)(v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4));
}

void exr_view_pick(const float *v, size_t n, exr_view *out) {
  double lo = INFINITY, hi = -INFINITY;
  for (size_t q = 0; q < n; q++)
    if (isfinite(v[q])) lo = fmin(lo, v[q]), hi = fmax(hi, v[q]);
  if (!(lo <= hi)) lo = hi = 0;
  int across = lo < 0 && hi > 0;
  out->map = across ? "coolwarm" : "viridis";
  if (across) {
    double a = fmax(-lo, hi);
    lo = -a, hi = a;
  }
  out->lo = lo, out->hi = hi;
}

void exr_view_fill(const exr_view *view, const float *v, size_t n, float *r, float *g, float *b) {
  for (size_t q = 0; q < n; q++) {
    unsigned char c[3] = {128, 128, 128};
    if (isfinite(v[q])) {
      double t = view->hi > view->lo ? (v[q] - view->lo) / (view->hi - view->lo) : 0.5;
      sessile_colormap(view->map, t, c);
    }
    r[q] = srgb_to_linear(c[0]), g[q] = srgb_to_linear(c[1]), b[q] = srgb_to_linear(c[2]);
  }
}
