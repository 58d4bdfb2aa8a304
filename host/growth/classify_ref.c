/* Solid classification on the host: column binning (shared with the GPU
 * path) and the reference of shaders/growth/classify.comp.  The watertight
 * rule is explained in docs/growth.md; the arithmetic below is mirrored
 * operation by operation in the kernel so the masks are identical. */
#include <math.h>
#include <stdlib.h>
#include "sessile/growth/growth_ref.h"

/* Lines along axis a are indexed by the two other axes in cyclic order
 * (u, v) = (a+1, a+2) mod 3, so (u, v, a) is right-handed and axis 2 is the
 * original vertical classification exactly. */
static void line_axes(int a, int *u, int *v) {
  *u = (a + 1) % 3;
  *v = (a + 2) % 3;
}

/* Twice the signed uv-area of triangle f (0 for a triangle parallel to the line). */
static double tri_area2_uv(const double *pos, const uint32_t *t, int u, int v) {
  const double *a = pos + 3 * t[0], *b = pos + 3 * t[1], *c = pos + 3 * t[2];
  return (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
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

static int tri_cols(const sessile_box *box, const double *pos, const uint32_t *t, int u, int v,
                    uint32_t r[4]) {
  int ax[2] = {u, v};
  double mn[2], mx[2];
  for (int a = 0; a < 2; a++) {
    mn[a] = mx[a] = pos[3 * t[0] + ax[a]];
    for (int q = 1; q < 3; q++) {
      double x = pos[3 * t[q] + ax[a]];
      mn[a] = x < mn[a] ? x : mn[a];
      mx[a] = x > mx[a] ? x : mx[a];
    }
  }
  return col_range(mn[0], mx[0], box->origin[u], box->h, box->n[u], &r[0], &r[1]) &&
         col_range(mn[1], mx[1], box->origin[v], box->h, box->n[v], &r[2], &r[3]);
}

sessile_status sessile_growth_bin_columns(const sessile_box *box, const sessile_surface *s,
                                          uint32_t **off_out, uint32_t **tri_out) {
  return sessile_growth_bin_lines(box, s, 2, off_out, tri_out);
}

sessile_status sessile_growth_bin_lines(const sessile_box *box, const sessile_surface *s, int axis,
                                        uint32_t **off_out, uint32_t **tri_out) {
  *off_out = NULL;
  *tri_out = NULL;
  SESSILE_CHECK(axis >= 0 && axis < 3, SESSILE_ERR_USAGE, "line axis must be 0, 1 or 2 (got %d)", axis);
  int u, v;
  line_axes(axis, &u, &v);
  size_t ncol = (size_t)box->n[u] * box->n[v];
  uint32_t *off = calloc(ncol + 1, sizeof *off);
  SESSILE_CHECK(off, SESSILE_ERR_NO_MEMORY, "out of host memory binning %zu columns", ncol);
  /* Two passes (count, fill): O(T + entries). */
  uint64_t total = 0;
  for (int pass = 0; pass < 2; pass++) {
    uint32_t *list = pass ? *tri_out : NULL;
    for (uint32_t f = 0; f < s->nf; f++) {
      const uint32_t *t = s->tri + 3 * f;
      uint32_t r[4];
      if (tri_area2_uv(s->pos, t, u, v) == 0 || !tri_cols(box, s->pos, t, u, v, r)) continue;
      for (uint32_t j = r[2]; j <= r[3]; j++)
        for (uint32_t i = r[0]; i <= r[1]; i++) {
          size_t c = i + (size_t)box->n[u] * j;
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
static double edge_fn(const double *pos, int u, int v, uint32_t i, uint32_t j, double qx, double qy,
                      int *sgn) {
  uint32_t lo = i < j ? i : j, hi = i < j ? j : i;
  double ax = pos[3 * lo + u], ay = pos[3 * lo + v];
  double dx = pos[3 * hi + u] - ax, dy = pos[3 * hi + v] - ay;
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
  return sessile_growth_line_crossings(pos, tri, list, count, 2, x, y, z);
}

int sessile_growth_line_crossings(const double *pos, const uint32_t *tri, const uint32_t *list,
                                  uint32_t count, int axis, double x, double y,
                                  double z[SESSILE_GROWTH_MAX_CROSSINGS]) {
  int u, v, n = 0;
  line_axes(axis, &u, &v);
  for (uint32_t q = 0; q < count; q++) {
    const uint32_t *t = tri + 3 * list[q];
    int s0, s1, s2;
    double e0 = edge_fn(pos, u, v, t[0], t[1], x, y, &s0); /* opposite t[2] */
    double e1 = edge_fn(pos, u, v, t[1], t[2], x, y, &s1); /* opposite t[0] */
    double e2 = edge_fn(pos, u, v, t[2], t[0], x, y, &s2); /* opposite t[1] */
    if (s0 != s1 || s1 != s2) continue;
    if (n == SESSILE_GROWTH_MAX_CROSSINGS) return -1;
    /* Height of the plane at q: barycentric weights from the same edge
     * values (all of one sign or zero, so z lies within the triangle's). */
    double sum = e0 + e1 + e2;
    double za = pos[3 * t[0] + axis], zb = pos[3 * t[1] + axis], zc = pos[3 * t[2] + axis];
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

/* One line along `axis` through column (iu, iv): its crossings, the parity
 * of each node (axis 2 only: that is the solid mask) and the fractions of h
 * from each node to the nearest crossing towards its neighbours.  Crossings
 * in (t_k, t_k+1] separate node k from k+1 (a node exactly on the surface
 * counts the crossing at its own coordinate as below it, as the parity
 * does): theta+ of k is the first of them, theta- of k+1 the last; 1 where
 * the interval has none.  Mirrored operation by operation in
 * shaders/growth/classify.comp. */
static int cut_line(const sessile_box *box, const sessile_surface *s, const uint32_t *list,
                    uint32_t count, int axis, uint32_t iu, uint32_t iv, uint32_t *solid,
                    double *theta) {
  int u, v;
  line_axes(axis, &u, &v);
  double x = box->origin[u] + box->h * iu, y = box->origin[v] + box->h * iv;
  double z[SESSILE_GROWTH_MAX_CROSSINGS];
  int n = sessile_growth_line_crossings(s->pos, s->tri, list, count, axis, x, y, z);
  if (n < 0) return -1;
  sort_small(z, n);
  uint32_t c[3];
  c[u] = iu, c[v] = iv;
  int below = 0;
  for (uint32_t k = 0; k < box->n[axis]; k++) {
    c[axis] = k;
    size_t node = c[0] + (size_t)box->n[0] * (c[1] + (size_t)box->n[1] * c[2]);
    double tk = box->origin[axis] + box->h * k;
    int prev = below;
    while (below < n && z[below] <= tk) below++;
    if (axis == 2 && solid) solid[node] = (uint32_t)(below & 1);
    if (!theta) continue;
    theta[6 * node + 2 * axis] = 1;
    theta[6 * node + 2 * axis + 1] = 1;
    if (k > 0 && below > prev) {
      /* this node's minus side and the previous node's plus side */
      size_t pn = node - (axis == 0 ? 1 : axis == 1 ? box->n[0] : (size_t)box->n[0] * box->n[1]);
      double tp = box->origin[axis] + box->h * (k - 1);
      theta[6 * pn + 2 * axis + 1] = (z[prev] - tp) / box->h;
      theta[6 * node + 2 * axis] = (tk - z[below - 1]) / box->h;
    }
  }
  return 0;
}

sessile_status sessile_growth_ref_cut(const sessile_box *box, const sessile_surface *s,
                                      uint32_t *solid, double *theta) {
  for (int axis = theta ? 0 : 2; axis < 3; axis++) {
    uint32_t *off, *list;
    int u, v;
    line_axes(axis, &u, &v);
    SESSILE_CALL(sessile_growth_bin_lines(box, s, axis, &off, &list));
    sessile_status st = SESSILE_OK;
    for (uint32_t iv = 0; iv < box->n[v] && st == SESSILE_OK; iv++)
      for (uint32_t iu = 0; iu < box->n[u]; iu++) {
        uint32_t c = iu + box->n[u] * iv;
        if (cut_line(box, s, list + off[c], off[c + 1] - off[c], axis, iu, iv, solid, theta) < 0) {
          static const char *const name[3] = {"x", "y", "z"};
          st = sessile_error_set(SESSILE_ERR_NUMERIC,
                                 "the box line along %s through node (%u, %u) crosses the sponge "
                                 "surface more than %d times; the surface is too folded for solid "
                                 "classification", name[axis], iu, iv, SESSILE_GROWTH_MAX_CROSSINGS);
          break;
        }
      }
    free(off);
    free(list);
    SESSILE_CALL(st);
  }
  return SESSILE_OK;
}

sessile_status sessile_growth_ref_classify(const sessile_box *box, const sessile_surface *s,
                                           uint32_t *solid) {
  return sessile_growth_ref_cut(box, s, solid, NULL);
}
