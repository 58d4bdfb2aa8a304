/* sessile — a per-vertex value's colours, picked the way `sessile render
 * --color-by` picks them: the range is the finite values' (symmetric about
 * 0 for a diverging map on a range across 0), the map viridis, or coolwarm
 * for a range across 0 unless one is named.  The mesh writers colour a
 * PLY's vertices with it, the renderer its meshes, so both agree. */
#ifndef SESSILE_MESH_COLORS_H
#define SESSILE_MESH_COLORS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The range of v[0..n) and the map to use (map NULL: by the sign as above;
 * else map, which must be known).  No finite value: [0, 0]. */
const char *sessile_mesh_colors_range(const float *v, size_t n, const char *map, double *lo, double *hi);
/* The colour of x over [lo, hi] (t = (x - lo) / (hi - lo), 0.5 for an empty
 * range); a non-finite x is grey (128, 128, 128). */
void sessile_mesh_color(const char *map, double lo, double hi, float x, unsigned char rgb[3]);

#ifdef __cplusplus
}
#endif
#endif
