/* sessile io — a per-vertex value's colours (sessile/io/mesh_colors.h): the
 * renderer's rule, kept in one place so that a PLY's colours are exactly what
 * `sessile render --color-by` shows for the same property. */
#include <math.h>
#include "sessile/io/colormap.h"
#include "sessile/io/mesh_colors.h"

const char *sessile_mesh_colors_range(const float *v, size_t n, const char *map, double *lo, double *hi) {
  double a = INFINITY, b = -INFINITY;
  for (size_t i = 0; i < n; i++)
    if (isfinite(v[i])) {
      a = fmin(a, v[i]);
      b = fmax(b, v[i]);
    }
  if (!(a <= b)) a = b = 0;
  int across = a < 0 && b > 0;
  if (!map) map = across ? "coolwarm" : "viridis";
  if (sessile_colormap_diverging(map) && across) {
    double m = fmax(-a, b);
    a = -m;
    b = m;
  }
  *lo = a;
  *hi = b;
  return map;
}

void sessile_mesh_color(const char *map, double lo, double hi, float x, unsigned char rgb[3]) {
  if (!isfinite(x)) {
    rgb[0] = rgb[1] = rgb[2] = 128;
    return;
  }
  sessile_colormap(map, hi > lo ? (x - lo) / (hi - lo) : 0.5, rgb);
}
