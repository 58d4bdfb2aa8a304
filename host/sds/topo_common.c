/* Shared pieces of the SDS topology: faces, cavity hulls, TetGen filling of
 * a hull (through host/mesh/tetgen_shim.cpp) and the rebuild of the tets. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/intersect.h"
#include "sessile/mesh/mesh_sort.h"
#include "sessile/mesh/tetgen.h"
#include "topo_internal.h"

const int topo_face_of[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

void sessile_sds_topo_complex_free(sessile_sds_topo_complex *c) {
  free(c->x), free(c->tet);
  memset(c, 0, sizeof *c);
}

double sessile_sds_topo_volume(const double *x0, const double *x1, const double *x2, const double *x3) {
  double a[3], b[3], c[3];
  for (int k = 0; k < 3; k++) a[k] = x1[k] - x0[k], b[k] = x2[k] - x0[k], c[k] = x3[k] - x0[k];
  return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
}

void topo_face_make(topo_face *f, uint32_t a, uint32_t b, uint32_t c, uint32_t t) {
  f->v[0] = a, f->v[1] = b, f->v[2] = c, f->t = t;
  uint32_t o[3] = {a, b, c};
  if (o[0] > o[1]) {
    uint32_t s = o[0];
    o[0] = o[1];
    o[1] = s;
  }
  if (o[1] > o[2]) {
    uint32_t s = o[1];
    o[1] = o[2];
    o[2] = s;
  }
  if (o[0] > o[1]) {
    uint32_t s = o[0];
    o[0] = o[1];
    o[1] = s;
  }
  memcpy(f->o, o, sizeof o);
}

int topo_face_cmp(const void *x, const void *y) {
  const topo_face *p = x, *q = y;
  for (int k = 0; k < 3; k++)
    if (p->o[k] != q->o[k]) return p->o[k] < q->o[k] ? -1 : 1;
  return (p->t > q->t) - (p->t < q->t);
}

int topo_face_same(const topo_face *a, const topo_face *b) {
  return a->o[0] == b->o[0] && a->o[1] == b->o[1] && a->o[2] == b->o[2];
}

/* Sorts faces made in ascending t as topo_face_cmp does, by a stable radix
 * sort of their sorted cells (ties keep the order of t); 0 when a cell
 * index does not fit the key or memory is short (then the caller qsorts).
 * A complex of 10 000 tets checked after each division spent most of the
 * check in qsort's comparator calls. */
static int faces_radix(topo_face *f, size_t n) {
  _Static_assert(offsetof(topo_face, o) == 0 && sizeof(topo_face) % sizeof(uint32_t) == 0, "o leads topo_face");
  uint32_t *order = malloc((n + 1) * sizeof *order);
  topo_face *out = malloc((n + 1) * sizeof *out);
  int ok = order && out && mesh_order3((const uint32_t *)f, sizeof *f / sizeof(uint32_t), n, order);
  for (size_t i = 0; ok && i < n; i++) out[i] = f[order[i]];
  if (ok) memcpy(f, out, n * sizeof *f);
  free(order), free(out);
  return ok;
}

topo_face *topo_all_faces(uint32_t nt, const uint32_t *tet) {
  topo_face *f = malloc((4 * (size_t)nt + 1) * sizeof *f);
  if (!f) return NULL;
  for (uint32_t t = 0; t < nt; t++)
    for (int q = 0; q < 4; q++) {
      const int *fo = topo_face_of[q];
      topo_face_make(f + 4 * t + q, tet[4 * t + fo[0]], tet[4 * t + fo[1]], tet[4 * t + fo[2]], t);
    }
  if (4 * (size_t)nt >= UINT32_MAX || !faces_radix(f, 4 * (size_t)nt)) qsort(f, 4 * (size_t)nt, sizeof *f, topo_face_cmp);
  return f;
}

sessile_status topo_cavity_hull(const uint32_t *tet, const uint32_t *list, uint32_t n, uint32_t **faces, uint32_t *nf) {
  topo_face *f = malloc((4 * (size_t)n + 1) * sizeof *f);
  uint32_t *out = malloc((12 * (size_t)n + 1) * sizeof *out);
  if (!f || !out) {
    free(f), free(out);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a cavity of %u tets", n);
  }
  for (uint32_t i = 0; i < n; i++)
    for (int q = 0; q < 4; q++) {
      const uint32_t *t = tet + 4 * (size_t)list[i];
      topo_face_make(f + 4 * i + q, t[topo_face_of[q][0]], t[topo_face_of[q][1]], t[topo_face_of[q][2]], list[i]);
    }
  qsort(f, 4 * (size_t)n, sizeof *f, topo_face_cmp);
  uint32_t k = 0;
  for (size_t i = 0; i < 4 * (size_t)n;) {
    size_t j = i + 1;
    while (j < 4 * (size_t)n && topo_face_same(f + i, f + j)) j++;
    if (j == i + 1) memcpy(out + 3 * k++, f[i].v, 3 * sizeof *out);
    i = j;
  }
  free(f);
  *faces = out, *nf = k;
  return SESSILE_OK;
}

int topo_face_on_boundary(uint32_t nt, const uint32_t *tet, uint32_t a, uint32_t b, uint32_t c) {
  int count = 0;
  for (uint32_t t = 0; t < nt; t++) {
    const uint32_t *v = tet + 4 * (size_t)t;
    int has = 0;
    for (int q = 0; q < 4; q++) has += v[q] == a || v[q] == b || v[q] == c;
    count += has == 3;
  }
  return count == 1;
}

/* Local index of global vertex g in the sorted list (binary search). */
static int local_of(const uint32_t *sorted, int n, uint32_t g) {
  int lo = 0, hi = n - 1;
  while (lo <= hi) {
    int m = (lo + hi) / 2;
    if (sorted[m] == g) return m;
    if (sorted[m] < g)
      lo = m + 1;
    else
      hi = m - 1;
  }
  return -1;
}
static int u32_cmp(const void *a, const void *b) {
  uint32_t p = *(const uint32_t *)a, q = *(const uint32_t *)b;
  return (p > q) - (p < q);
}

sessile_status topo_fill_hull(const double *x, const uint32_t *faces, uint32_t nf, const uint32_t *pts, uint32_t npts,
                              uint32_t **out, uint32_t *nout) {
  sessile_status st = SESSILE_OK;
  uint32_t *hv = malloc((3 * (size_t)nf + 1) * sizeof *hv);
  uint32_t *verts = malloc((3 * (size_t)nf + 1) * sizeof *verts);
  double *xyz = NULL;
  uint32_t *glob = NULL, *res = NULL;
  topo_face *hf = NULL, *rf = NULL;
  sessile_tetgen_mesh r;
  memset(&r, 0, sizeof r);
  if (!hv || !verts) goto nomem;
  /* PLC points: the hull's vertices (sorted, unique), then the interior points. */
  memcpy(hv, faces, 3 * (size_t)nf * sizeof *hv);
  qsort(hv, 3 * (size_t)nf, sizeof *hv, u32_cmp);
  int nh = 0;
  for (size_t i = 0; i < 3 * (size_t)nf; i++)
    if (i == 0 || hv[i] != hv[i - 1]) hv[nh++] = hv[i];
  int np = nh + (int)npts;
  xyz = malloc(3 * (size_t)np * sizeof *xyz);
  glob = malloc((size_t)np * sizeof *glob);
  if (!xyz || !glob) goto nomem;
  for (int i = 0; i < np; i++) {
    glob[i] = i < nh ? hv[i] : pts[i - nh];
    memcpy(xyz + 3 * i, x + 3 * (size_t)glob[i], 3 * sizeof *xyz);
  }
  for (uint32_t f = 0; f < nf; f++)
    for (int k = 0; k < 3; k++) verts[3 * f + k] = (uint32_t)local_of(hv, nh, faces[3 * f + k]);
  /* TetGen 1.5.0 asserts (aborts the process) on some self-intersecting
   * PLCs: a tangled hull (a repair cavity around inverted tets, a split fan
   * folded over its star) is refused here instead.  O(nf^2) with box
   * rejection: hulls have tens to a few hundred faces. */
  for (uint32_t f = 0; f < nf; f++) {
    double a[9], lo[3], hi[3];
    for (int q = 0; q < 9; q++) a[q] = x[3 * (size_t)faces[3 * f + q / 3] + q % 3];
    for (int k = 0; k < 3; k++)
      lo[k] = fmin(a[k], fmin(a[3 + k], a[6 + k])), hi[k] = fmax(a[k], fmax(a[3 + k], a[6 + k]));
    for (uint32_t g = f + 1; g < nf; g++) {
      double b[9];
      int apart = 0;
      for (int q = 0; q < 9; q++) b[q] = x[3 * (size_t)faces[3 * g + q / 3] + q % 3];
      for (int k = 0; k < 3 && !apart; k++)
        apart = fmax(b[k], fmax(b[3 + k], b[6 + k])) < lo[k] || fmin(b[k], fmin(b[3 + k], b[6 + k])) > hi[k];
      if (!apart && sessile_triangles_intersect(a, faces + 3 * f, b, faces + 3 * g)) {
        st = sessile_error_set(SESSILE_ERR_NUMERIC, "re-tetrahedralising a hull of %u faces: faces %u and %u cross",
                               nf, f, g);
        goto done;
      }
    }
  }
  char msg[256];
  /* p: a PLC; Y: no Steiner point on its facets; z: zero-based; Q: quiet.
   * No q/a: no quality or size refinement, so no interior Steiner point
   * either unless the hull needs one (then refused below). */
  sessile_status ts = sessile_tetgen_surface(xyz, np, verts, (int)nf, "pYzQ", &r, msg, sizeof msg);
  if (ts == SESSILE_ERR_NO_MEMORY) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory re-tetrahedralising a hull of %u faces: %s", nf, msg);
    goto done;
  }
  if (ts != SESSILE_OK) {
    st = sessile_error_set(SESSILE_ERR_NUMERIC, "out of host memory re-tetrahedralising a hull of %u faces: %s", nf, msg);
    goto done;
  }
  if (r.npoints != np) {
    st = sessile_error_set(SESSILE_ERR_NUMERIC,
                           "re-tetrahedralising a hull of %u faces: TetGen added %d Steiner point(s)", nf,
                           r.npoints - np);
    goto done;
  }
  res = malloc((4 * (size_t)r.ntets + 1) * sizeof *res);
  if (!res) goto nomem;
  for (int t = 0; t < r.ntets; t++) {
    for (int q = 0; q < 4; q++) {
      int l = r.tet[4 * t + q];
      if (l < 0 || l >= np) {
        st = sessile_error_set(SESSILE_ERR_INTERNAL, "TetGen returned a tet corner out of range");
        goto done;
      }
      res[4 * t + q] = glob[l];
    }
    if (topo_vol4(x, res + 4 * t) < 0) {
      uint32_t s = res[4 * t + 1];
      res[4 * t + 1] = res[4 * t + 2], res[4 * t + 2] = s;
    }
  }
  /* Every interior point used, and the result's hull exactly the input's. */
  for (uint32_t i = 0; i < npts; i++) {
    int used = 0;
    for (size_t k = 0; k < 4 * (size_t)r.ntets && !used; k++) used = res[k] == pts[i];
    if (!used) {
      st = sessile_error_set(SESSILE_ERR_NUMERIC, "TetGen left the interior point %u out of the hull", pts[i]);
      goto done;
    }
  }
  uint32_t nrf = 0;
  uint32_t *all = NULL;
  {
    uint32_t *list = malloc(((size_t)r.ntets + 1) * sizeof *list);
    if (!list) goto nomem;
    for (int t = 0; t < r.ntets; t++) list[t] = (uint32_t)t;
    st = topo_cavity_hull(res, list, (uint32_t)r.ntets, &all, &nrf);
    free(list);
    if (st != SESSILE_OK) goto done;
  }
  hf = malloc(((size_t)nf + 1) * sizeof *hf);
  rf = malloc(((size_t)nrf + 1) * sizeof *rf);
  if (!hf || !rf) {
    free(all);
    goto nomem;
  }
  for (uint32_t f = 0; f < nf; f++) topo_face_make(hf + f, faces[3 * f], faces[3 * f + 1], faces[3 * f + 2], 0);
  for (uint32_t f = 0; f < nrf; f++) topo_face_make(rf + f, all[3 * f], all[3 * f + 1], all[3 * f + 2], 0);
  free(all);
  qsort(hf, nf, sizeof *hf, topo_face_cmp);
  qsort(rf, nrf, sizeof *rf, topo_face_cmp);
  int same = nrf == nf;
  for (uint32_t f = 0; f < nf && same; f++) same = topo_face_same(hf + f, rf + f);
  /* orientation: the same cyclic order (both outward) */
  for (uint32_t f = 0; f < nf && same; f++) {
    const uint32_t *a = hf[f].v, *b = rf[f].v;
    int k = b[0] == a[0] ? 0 : b[1] == a[0] ? 1 : 2;
    same = b[(k + 1) % 3] == a[1];
  }
  if (!same) {
    st = sessile_error_set(SESSILE_ERR_NUMERIC,
                           "TetGen's mesh of a hull of %u faces has a different boundary (%u faces)", nf, nrf);
    goto done;
  }
  *out = res, *nout = (uint32_t)r.ntets;
  res = NULL;
  goto done;
nomem:
  st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory re-tetrahedralising a hull of %u faces", nf);
done:
  sessile_tetgen_mesh_free(&r);
  free(hv), free(verts);
  free(xyz), free(glob), free(res), free(hf), free(rf);
  return st;
}

sessile_status topo_replace(sessile_sds_topo_complex *cx, const uint8_t *remove, const uint32_t *add, uint32_t nadd,
                            uint32_t **tet_from, uint32_t *n_removed) {
  uint32_t keep = 0;
  for (uint32_t t = 0; t < cx->nt; t++) keep += !remove[t];
  uint32_t nt = keep + nadd;
  uint32_t *tet = malloc((4 * (size_t)nt + 1) * sizeof *tet), *from = malloc(((size_t)nt + 1) * sizeof *from);
  if (!tet || !from) {
    free(tet), free(from);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u tets", nt);
  }
  uint32_t k = 0;
  for (uint32_t t = 0; t < cx->nt; t++)
    if (!remove[t]) memcpy(tet + 4 * (size_t)k, cx->tet + 4 * (size_t)t, 4 * sizeof *tet), from[k++] = t;
  if (nadd) memcpy(tet + 4 * (size_t)k, add, 4 * (size_t)nadd * sizeof *tet);
  for (uint32_t i = 0; i < nadd; i++) from[k + i] = SESSILE_SDS_TOPO_NEW_TET;
  *n_removed = cx->nt - keep;
  free(cx->tet);
  cx->tet = tet, cx->nt = nt;
  *tet_from = from;
  return SESSILE_OK;
}
