/* Point location in an unstructured tet mesh: uniform bin grid built on the
 * host, and the host query (sessile/mesh/locate.h).  shaders/mesh/locate.comp
 * repeats locate_weights and the scan operation by operation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "locate_internal.h"

void sessile_locator_destroy(sessile_locator *l) {
  if (!l) return;
  free(l->cell_off);
  free(l->cell_tet);
  free(l);
}

/* Bin range [i0, i1] of the interval [a, b] on axis k (clamped). */
static void bin_range(const sessile_locator *l, int k, double a, double b, uint32_t *i0, uint32_t *i1) {
  double x0 = floor((a - l->lo[k]) * l->inv_h[k]), x1 = floor((b - l->lo[k]) * l->inv_h[k]);
  double top = (double)(l->dims[k] - 1);
  *i0 = x0 < 0 ? 0 : x0 > top ? (uint32_t)top : (uint32_t)x0;
  *i1 = x1 < 0 ? 0 : x1 > top ? (uint32_t)top : (uint32_t)x1;
}

/* Tet t's bounding box, widened so points within the eps tolerance of its
 * faces fall in its bins. */
static void tet_bbox(const sessile_tetmesh *m, uint32_t t, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
  for (int q = 0; q < 4; q++)
    for (int k = 0; k < 3; k++) {
      double x = m->xyz[3 * m->tet[4 * t + q] + k];
      lo[k] = fmin(lo[k], x), hi[k] = fmax(hi[k], x);
    }
  double w = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2])) * 1e-6;
  for (int k = 0; k < 3; k++) lo[k] -= w, hi[k] += w;
}

sessile_status sessile_locator_build(const sessile_tetmesh *m, double bins_per_tet, sessile_locator **out) {
  *out = NULL;
  SESSILE_CHECK(m && m->ntets > 0 && m->nnodes > 0, SESSILE_ERR_USAGE, "locator needs a non-empty tet mesh");
  if (!(bins_per_tet > 0)) bins_per_tet = 1;
  sessile_locator *l = calloc(1, sizeof *l);
  SESSILE_CHECK(l, SESSILE_ERR_NO_MEMORY, "out of host memory for a locator");
  l->m = m;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t i = 0; i < m->nnodes; i++)
    for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], m->xyz[3 * i + k]), hi[k] = fmax(hi[k], m->xyz[3 * i + k]);
  double ext[3], vol = 1, pad = 0;
  for (int k = 0; k < 3; k++) pad = fmax(pad, hi[k] - lo[k]);
  pad *= 1e-9;
  for (int k = 0; k < 3; k++) {
    lo[k] -= pad, hi[k] += pad;
    ext[k] = hi[k] - lo[k];
    vol *= ext[k];
  }
  /* cubic bins: ntets * bins_per_tet of them over the bounding box */
  double target = fmin((double)m->ntets * bins_per_tet, 1 << 26);
  double hb = cbrt(vol / target);
  uint64_t nb = 1;
  for (int k = 0; k < 3; k++) {
    double d = ceil(ext[k] / hb);
    l->dims[k] = d < 1 ? 1 : (uint32_t)d;
    l->lo[k] = lo[k];
    l->inv_h[k] = l->dims[k] / ext[k];
    nb *= l->dims[k];
  }
  l->nbins = (uint32_t)nb;
  l->cell_off = calloc(nb + 1, sizeof *l->cell_off);
  if (!l->cell_off) {
    sessile_locator_destroy(l);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %llu locator bins",
                             (unsigned long long)nb);
  }
  /* two passes: count, then fill in ascending tet order */
  uint64_t total = 0;
  for (int pass = 0; pass < 2; pass++) {
    for (uint32_t t = 0; t < m->ntets; t++) {
      double a[3], b[3];
      uint32_t i0[3], i1[3];
      tet_bbox(m, t, a, b);
      for (int k = 0; k < 3; k++) bin_range(l, k, a[k], b[k], &i0[k], &i1[k]);
      for (uint32_t z = i0[2]; z <= i1[2]; z++)
        for (uint32_t y = i0[1]; y <= i1[1]; y++)
          for (uint32_t x = i0[0]; x <= i1[0]; x++) {
            uint32_t c = x + l->dims[0] * (y + l->dims[1] * z);
            if (pass == 0) l->cell_off[c + 1]++;
            else l->cell_tet[l->cell_off[c]++] = t;
          }
    }
    if (pass == 0) {
      for (uint32_t c = 0; c < l->nbins; c++) {
        total += l->cell_off[c + 1];
        if (l->cell_off[c + 1] > l->max_per_bin) l->max_per_bin = l->cell_off[c + 1];
      }
      if (total >= UINT32_MAX) {
        sessile_locator_destroy(l);
        return sessile_error_set(SESSILE_ERR_TOO_LARGE, "locator bins hold too many entries");
      }
      for (uint32_t c = 0; c < l->nbins; c++) l->cell_off[c + 1] += l->cell_off[c];
      l->nentries = (uint32_t)total;
      l->cell_tet = malloc((total ? total : 1) * sizeof *l->cell_tet);
      if (!l->cell_tet) {
        sessile_locator_destroy(l);
        return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for locator bins");
      }
    }
  }
  /* filling advanced cell_off[c] to the end of bin c: shift back */
  for (uint32_t c = l->nbins; c > 0; c--) l->cell_off[c] = l->cell_off[c - 1];
  l->cell_off[0] = 0;
  *out = l;
  return SESSILE_OK;
}

void locate_weights(const double *x0, const double *x1, const double *x2, const double *x3,
                    const double p[3], double w[4]) {
  double d1[3], d2[3], d3[3], q[3];
  for (int k = 0; k < 3; k++) d1[k] = x1[k] - x0[k], d2[k] = x2[k] - x0[k], d3[k] = x3[k] - x0[k], q[k] = p[k] - x0[k];
  double c23[3] = {d2[1] * d3[2] - d2[2] * d3[1], d2[2] * d3[0] - d2[0] * d3[2], d2[0] * d3[1] - d2[1] * d3[0]};
  double cq3[3] = {q[1] * d3[2] - q[2] * d3[1], q[2] * d3[0] - q[0] * d3[2], q[0] * d3[1] - q[1] * d3[0]};
  double c2q[3] = {d2[1] * q[2] - d2[2] * q[1], d2[2] * q[0] - d2[0] * q[2], d2[0] * q[1] - d2[1] * q[0]};
  double det = d1[0] * c23[0] + d1[1] * c23[1] + d1[2] * c23[2];
  w[1] = (q[0] * c23[0] + q[1] * c23[1] + q[2] * c23[2]) / det;
  w[2] = (d1[0] * cq3[0] + d1[1] * cq3[1] + d1[2] * cq3[2]) / det;
  w[3] = (d1[0] * c2q[0] + d1[1] * c2q[1] + d1[2] * c2q[2]) / det;
  w[0] = 1.0 - w[1] - w[2] - w[3];
}

uint32_t sessile_locator_find(const sessile_locator *l, const double p[3], double w[4]) {
  uint32_t c[3];
  for (int k = 0; k < 3; k++) {
    double x = (p[k] - l->lo[k]) * l->inv_h[k];
    /* a margin of 1e-3 bin, clamped: points on the bounding box's faces
     * still find their bin when lo and inv_h are rounded to fp32 */
    if (!(x >= -1e-3 && x <= (double)l->dims[k] + 1e-3)) return SESSILE_LOCATE_OUTSIDE; /* NaN too */
    c[k] = x <= 0 ? 0 : x >= (double)(l->dims[k] - 1) ? l->dims[k] - 1 : (uint32_t)x;
  }
  uint32_t b = c[0] + l->dims[0] * (c[1] + l->dims[1] * c[2]);
  const sessile_tetmesh *m = l->m;
  for (uint32_t e = l->cell_off[b]; e < l->cell_off[b + 1]; e++) {
    uint32_t t = l->cell_tet[e];
    const uint32_t *v = m->tet + 4 * (size_t)t;
    double ww[4];
    locate_weights(m->xyz + 3 * v[0], m->xyz + 3 * v[1], m->xyz + 3 * v[2], m->xyz + 3 * v[3], p, ww);
    if (ww[0] >= -SESSILE_LOCATE_EPS && ww[1] >= -SESSILE_LOCATE_EPS && ww[2] >= -SESSILE_LOCATE_EPS &&
        ww[3] >= -SESSILE_LOCATE_EPS) {
      memcpy(w, ww, sizeof ww);
      return t;
    }
  }
  return SESSILE_LOCATE_OUTSIDE;
}

double sessile_locator_interpolate(const sessile_locator *l, const double *field, const double p[3],
                                   double outside_value) {
  double w[4];
  uint32_t t = sessile_locator_find(l, p, w);
  if (t == SESSILE_LOCATE_OUTSIDE) return outside_value;
  const uint32_t *v = l->m->tet + 4 * (size_t)t;
  return w[0] * field[v[0]] + w[1] * field[v[1]] + w[2] * field[v[2]] + w[3] * field[v[3]];
}

void sessile_locator_grid_of(const sessile_locator *l, sessile_locator_grid *g) {
  memcpy(g->lo, l->lo, sizeof g->lo);
  memcpy(g->inv_h, l->inv_h, sizeof g->inv_h);
  memcpy(g->dims, l->dims, sizeof g->dims);
  g->nbins = l->nbins;
  g->nentries = l->nentries;
  g->cell_off = l->cell_off;
  g->cell_tet = l->cell_tet;
  g->mean_per_bin = (double)l->nentries / l->nbins;
  g->max_per_bin = l->max_per_bin;
}
