/* Solid classification on the host: column binning (shared with the GPU
 * path) and the reference of shaders/growth/classify.comp.  The watertight
 * rule is explained in docs/growth.md; the arithmetic below is mirrored
 * operation by operation in the kernel so the masks are identical. */
#include <math.h>
#include <stdlib.h>
#include "sessile/growth_ref.h"

/* Twice the signed xy-area of triangle f (0 for a vertical triangle). */
static double tri_area2_xy(const double *pos, const uint32_t *t) {
  const double *a = pos + 3 * t[0], *b = pos + 3 * t[1], *c = pos + 3 * t[2];
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* Column index range [lo, hi] of the nodes with coordinate in [mn, mx]
 * along an axis; conservative by one column on each side of a rounding
 * boundary.  Returns 0 when the range misses the box. */
static int col_range(double mn, double mx, double o, double h, uint32_t n, uint32_t *lo,
                     uint32_t *hi) {
  double a = floor((mn - o) / h), b = ceil((mx - o) / h);
  if (!(b >= 0) || !(a <= (double)(n - 1))) return 0;
  *lo = a < 0 ? 0 : (uint32_t)a;
  *hi = b > (double)(n - 1) ? n - 1 : (uint32_t)b;
  return 1;
}

static int tri_cols(const sessile_box *box, const double *pos, const uint32_t *t, uint32_t r[4]) {
  double mn[2], mx[2];
  for (int a = 0; a < 2; a++) {
    mn[a] = mx[a] = pos[3 * t[0] + a];
    for (int q = 1; q < 3; q++) {
      double v = pos[3 * t[q] + a];
      mn[a] = v < mn[a] ? v : mn[a];
      mx[a] = v > mx[a] ? v : mx[a];
    }
  }
  return col_range(mn[0], mx[0], box->origin[0], box->h, box->n[0], &r[0], &r[1]) &&
         col_range(mn[1], mx[1], box->origin[1], box->h, box->n[1], &r[2], &r[3]);
}

sessile_status sessile_growth_bin_columns(const sessile_box *box, const sessile_surface *s,
                                          uint32_t **off_out, uint32_t **tri_out) {
  *off_out = NULL;
  *tri_out = NULL;
  size_t ncol = (size_t)box->n[0] * box->n[1];
  uint32_t *off = calloc(ncol + 1, sizeof *off);
  SESSILE_CHECK(off, SESSILE_ERR_NO_MEMORY, "out of host memory binning %zu columns", ncol);
  /* Two passes (count, fill): O(T + entries). */
  uint64_t total = 0;
  for (int pass = 0; pass < 2; pass++) {
    uint32_t *list = pass ? *tri_out : NULL;
    for (uint32_t f = 0; f < s->nf; f++) {
      const uint32_t *t = s->tri + 3 * f;
      uint32_t r[4];
      if (tri_area2_xy(s->pos, t) == 0 || !tri_cols(box, s->pos, t, r)) continue;
      for (uint32_t j = r[2]; j <= r[3]; j++)
        for (uint32_t i = r[0]; i <= r[1]; i++) {
          size_t c = i + (size_t)box->n[0] * j;
          if (pass == 0) off[c + 1]++, total++;
          else list[off[c]++] = f;
        }
    }
    if (pass == 0) {
      if (total > UINT32_MAX - 1) {
        free(off);
        return sessile_error_set(SESSILE_ERR_TOO_LARGE,
                                 "%llu column-triangle pairs are too many; lower the box resolution",
                                 (unsigned long long)total);
      }
      for (size_t c = 0; c < ncol; c++) off[c + 1] += off[c];
      *tri_out = malloc((total + 1) * sizeof **tri_out);
      if (!*tri_out) {
        free(off);
        return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory binning triangles");
      }
    }
  }
  /* The fill pass advanced off[c] to the end of column c: shift back. */
  for (size_t c = ncol; c > 0; c--) off[c] = off[c - 1];
  off[0] = 0;
  *off_out = off;
  return SESSILE_OK;
}

/* The edge function of directed edge (i -> j) at q, evaluated with the lower
 * vertex index first and negated for the other direction, so the two
 * triangles sharing an edge see exactly opposite values.  *sgn gets the sign,
 * zeros broken as if q were moved by (eps, eps^2): the same infinitesimal
 * shift for every edge, which is a consistent perturbation. */
static double edge_fn(const double *pos, uint32_t i, uint32_t j, double qx, double qy, int *sgn) {
  uint32_t lo = i < j ? i : j, hi = i < j ? j : i;
  double ax = pos[3 * lo], ay = pos[3 * lo + 1];
  double dx = pos[3 * hi] - ax, dy = pos[3 * hi + 1] - ay;
  double px = qx - ax, py = qy - ay;
  double l = dx * py, r = dy * px;
  double e = l - r;
  int s = e > 0 ? 1 : (e < 0 ? -1 : (dy != 0 ? (dy > 0 ? -1 : 1) : (dx > 0 ? 1 : -1)));
  if (i > j) e = -e, s = -s;
  *sgn = s;
  return e;
}

int sessile_growth_column_crossings(const double *pos, const uint32_t *tri, const uint32_t *list,
                                    uint32_t count, double x, double y,
                                    double z[SESSILE_GROWTH_MAX_CROSSINGS]) {
  int n = 0;
  for (uint32_t q = 0; q < count; q++) {
    const uint32_t *t = tri + 3 * list[q];
    int s0, s1, s2;
    double e0 = edge_fn(pos, t[0], t[1], x, y, &s0); /* opposite t[2] */
    double e1 = edge_fn(pos, t[1], t[2], x, y, &s1); /* opposite t[0] */
    double e2 = edge_fn(pos, t[2], t[0], x, y, &s2); /* opposite t[1] */
    if (s0 != s1 || s1 != s2) continue;
    if (n == SESSILE_GROWTH_MAX_CROSSINGS) return -1;
    /* Height of the plane at q: barycentric weights from the same edge
     * values (all of one sign or zero, so z lies within the triangle's). */
    double sum = e0 + e1 + e2;
    double za = pos[3 * t[0] + 2], zb = pos[3 * t[1] + 2], zc = pos[3 * t[2] + 2];
    double num = e1 * za + e2 * zb;
    num = num + e0 * zc;
    z[n++] = sum != 0 ? num / sum : (za + zb + zc) / 3.0;
  }
  return n;
}

/* Insertion sort (at most 64 values). */
static void sort_small(double *z, int n) {
  for (int a = 1; a < n; a++) {
    double v = z[a];
    int b = a - 1;
    while (b >= 0 && z[b] > v) z[b + 1] = z[b], b--;
    z[b + 1] = v;
  }
}

sessile_status sessile_growth_ref_classify(const sessile_box *box, const sessile_surface *s,
                                           uint32_t *solid) {
  uint32_t *off, *list;
  SESSILE_CALL(sessile_growth_bin_columns(box, s, &off, &list));
  const uint32_t n0 = box->n[0], n1 = box->n[1], n2 = box->n[2];
  sessile_status st = SESSILE_OK;
  for (uint32_t j = 0; j < n1 && st == SESSILE_OK; j++)
    for (uint32_t i = 0; i < n0; i++) {
      uint32_t c = i + n0 * j;
      double x = box->origin[0] + box->h * i, y = box->origin[1] + box->h * j;
      double z[SESSILE_GROWTH_MAX_CROSSINGS];
      int n = sessile_growth_column_crossings(s->pos, s->tri, list + off[c], off[c + 1] - off[c],
                                              x, y, z);
      if (n < 0) {
        st = sessile_error_set(SESSILE_ERR_NUMERIC,
                               "the vertical line through box column (%u, %u) crosses the sponge "
                               "surface more than %d times; the surface is too folded for solid "
                               "classification",
                               i, j, SESSILE_GROWTH_MAX_CROSSINGS);
        break;
      }
      sort_small(z, n);
      int below = 0;
      for (uint32_t k = 0; k < n2; k++) {
        double zk = box->origin[2] + box->h * k;
        while (below < n && z[below] <= zk) below++;
        solid[c + (size_t)n0 * n1 * k] = (uint32_t)(below & 1);
      }
    }
  free(off);
  free(list);
  return st;
}
