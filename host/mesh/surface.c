/* The sponge surface: storage, icosphere, adjacency, normals, statistics.
 * Remeshing lives in remesh.c, invariant checks in surface_check.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/mesh_internal.h"
#include "sessile/mesh/surface.h"

void sessile_surface_free(sessile_surface *s) {
  if (!s) return;
  free(s->pos);
  free(s->tri);
  memset(s, 0, sizeof *s);
}

sessile_status sessile_surface_reserve(sessile_surface *s, uint32_t nv, uint32_t nf) {
  if (nv > s->cap_v) {
    uint32_t cap = s->cap_v ? s->cap_v : 64;
    while (cap < nv) cap = cap > UINT32_MAX / 2 ? nv : cap * 2;
    double *p = realloc(s->pos, (size_t)cap * 3 * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for %u surface vertices", cap);
    s->pos = p;
    s->cap_v = cap;
  }
  if (nf > s->cap_f) {
    uint32_t cap = s->cap_f ? s->cap_f : 64;
    while (cap < nf) cap = cap > UINT32_MAX / 2 ? nf : cap * 2;
    uint32_t *t = realloc(s->tri, (size_t)cap * 3 * sizeof *t);
    SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory for %u surface triangles", cap);
    s->tri = t;
    s->cap_f = cap;
  }
  return SESSILE_OK;
}

sessile_status sessile_surface_copy(const sessile_surface *src, sessile_surface *dst) {
  sessile_surface_free(dst);
  sessile_status s = sessile_surface_reserve(dst, src->nv, src->nf);
  if (s != SESSILE_OK) {
    sessile_surface_free(dst); /* a failed copy leaves dst empty, nothing for the caller to free */
    return s;
  }
  if (src->nv) memcpy(dst->pos, src->pos, (size_t)src->nv * 3 * sizeof *dst->pos);
  if (src->nf) memcpy(dst->tri, src->tri, (size_t)src->nf * 3 * sizeof *dst->tri);
  dst->nv = src->nv;
  dst->nf = src->nf;
  return SESSILE_OK;
}

/* --- icosphere ---------------------------------------------------------------- */

/* Midpoint vertex of edge (a,b), created once: edges are looked up in a
 * per-vertex list of (other end, midpoint) pairs. */
typedef struct { uint32_t other, mid; } mid_entry;

static void unit(double *p) {
  double l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  p[0] /= l, p[1] /= l, p[2] /= l;
}

sessile_status sessile_surface_icosphere(int level, double radius, const double center[3],
                                         sessile_surface *out) {
  SESSILE_CHECK(level >= 1 && level <= 9, SESSILE_ERR_USAGE,
                "sponge resolution must be between 1 and 9 (got %d)", level);
  SESSILE_CHECK(radius > 0 && isfinite(radius), SESSILE_ERR_USAGE,
                "sponge radius must be positive (got %g)", radius);
  sessile_surface_free(out);
  uint32_t nv_final = 10u * (1u << (2 * (level - 1))) + 2u;
  uint32_t nf_final = 20u * (1u << (2 * (level - 1)));
  SESSILE_CALL(sessile_surface_reserve(out, nv_final, nf_final));
  const double t = (1.0 + sqrt(5.0)) / 2.0;
  const double v0[12][3] = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                            {0, -1, t}, {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                            {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  const uint32_t f0[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int i = 0; i < 12; i++) {
    memcpy(out->pos + 3 * i, v0[i], sizeof v0[i]);
    unit(out->pos + 3 * i);
  }
  memcpy(out->tri, f0, sizeof f0);
  out->nv = 12;
  out->nf = 20;
  /* Each vertex has at most 6 incident edges in an icosphere. */
  mid_entry *mids = malloc((size_t)nv_final * 6 * sizeof *mids);
  uint8_t *nmid = malloc(nv_final);
  uint32_t *newtri = malloc((size_t)nf_final * 3 * sizeof *newtri);
  if (!mids || !nmid || !newtri) {
    free(mids), free(nmid), free(newtri);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory building the icosphere");
  }
  for (int l = 1; l < level; l++) {
    memset(nmid, 0, nv_final);
    uint32_t nf = 0;
    for (uint32_t f = 0; f < out->nf; f++) {
      uint32_t v[3], m[3];
      memcpy(v, out->tri + 3 * f, sizeof v);
      for (int e = 0; e < 3; e++) {
        uint32_t a = v[e], b = v[(e + 1) % 3], lo = a < b ? a : b, hi = a < b ? b : a;
        uint32_t found = UINT32_MAX;
        for (uint8_t q = 0; q < nmid[lo]; q++)
          if (mids[6 * lo + q].other == hi) found = mids[6 * lo + q].mid;
        if (found == UINT32_MAX) {
          found = out->nv++;
          double *p = out->pos + 3 * found;
          for (int c = 0; c < 3; c++) p[c] = out->pos[3 * a + c] + out->pos[3 * b + c];
          unit(p);
          mids[6 * lo + nmid[lo]++] = (mid_entry){hi, found};
        }
        m[e] = found;
      }
      const uint32_t sub[4][3] = {{v[0], m[0], m[2]}, {v[1], m[1], m[0]}, {v[2], m[2], m[1]},
                                  {m[0], m[1], m[2]}};
      memcpy(newtri + 3 * nf, sub, sizeof sub);
      nf += 4;
    }
    memcpy(out->tri, newtri, (size_t)nf * 3 * sizeof *newtri);
    out->nf = nf;
  }
  free(mids), free(nmid), free(newtri);
  for (uint32_t i = 0; i < out->nv; i++)
    for (int c = 0; c < 3; c++) out->pos[3 * i + c] = center[c] + radius * out->pos[3 * i + c];
  return SESSILE_OK;
}

/* --- adjacency ------------------------------------------------------------------ */

static int cmp_u32(const void *a, const void *b) {
  uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
  return (x > y) - (x < y);
}

sessile_status sessile_surface_vertex_faces(const sessile_surface *s, uint32_t **off_out,
                                            uint32_t **faces_out) {
  *off_out = NULL;
  *faces_out = NULL;
  uint32_t *off = calloc((size_t)s->nv + 1, sizeof *off);
  uint32_t *faces = malloc(((size_t)s->nf * 3 + 1) * sizeof *faces);
  uint32_t *fill = calloc((size_t)s->nv + 1, sizeof *fill);
  if (!off || !faces || !fill) {
    free(off), free(faces), free(fill);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for mesh adjacency");
  }
  for (uint32_t k = 0; k < 3 * s->nf; k++) off[s->tri[k] + 1]++;
  for (uint32_t v = 0; v < s->nv; v++) off[v + 1] += off[v];
  /* Faces in ascending order because f ascends. */
  for (uint32_t f = 0; f < s->nf; f++)
    for (int c = 0; c < 3; c++) {
      uint32_t v = s->tri[3 * f + c];
      faces[off[v] + fill[v]++] = f;
    }
  free(fill);
  *off_out = off;
  *faces_out = faces;
  return SESSILE_OK;
}

sessile_status sessile_surface_vertex_neighbours(const sessile_surface *s, uint32_t **off_out,
                                                 uint32_t **nbr_out) {
  *off_out = NULL;
  *nbr_out = NULL;
  uint32_t *foff, *faces;
  SESSILE_CALL(sessile_surface_vertex_faces(s, &foff, &faces));
  /* Each incident face contributes its two other corners; duplicates removed
   * after sorting.  Upper bound: 2 per incident face. */
  uint32_t *off = calloc((size_t)s->nv + 1, sizeof *off);
  uint32_t *nbr = malloc(((size_t)foff[s->nv] * 2 + 1) * sizeof *nbr);
  if (!off || !nbr) {
    free(foff), free(faces), free(off), free(nbr);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for mesh adjacency");
  }
  uint32_t n = 0;
  for (uint32_t v = 0; v < s->nv; v++) {
    uint32_t start = n;
    for (uint32_t q = foff[v]; q < foff[v + 1]; q++) {
      const uint32_t *t = s->tri + 3 * faces[q];
      for (int c = 0; c < 3; c++)
        if (t[c] != v) nbr[n++] = t[c];
    }
    qsort(nbr + start, n - start, sizeof *nbr, cmp_u32);
    uint32_t w = start;
    for (uint32_t r = start; r < n; r++)
      if (r == start || nbr[r] != nbr[w - 1]) nbr[w++] = nbr[r];
    n = w;
    off[v + 1] = n;
  }
  free(foff), free(faces);
  *off_out = off;
  *nbr_out = nbr;
  return SESSILE_OK;
}

/* --- normals and statistics ---------------------------------------------------- */

static void face_cross(const sessile_surface *s, uint32_t f, double c[3]) {
  mesh_face_cross(s->pos, s->tri + 3 * f, c);
}

void sessile_surface_normals(const sessile_surface *s, double *n) {
  memset(n, 0, (size_t)s->nv * 3 * sizeof *n);
  for (uint32_t f = 0; f < s->nf; f++) {
    double c[3];
    face_cross(s, f, c); /* |c| = 2 area: area weighting */
    for (int q = 0; q < 3; q++)
      for (int a = 0; a < 3; a++) n[3 * s->tri[3 * f + q] + a] += c[a];
  }
  for (uint32_t v = 0; v < s->nv; v++) {
    double *p = n + 3 * v, l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (l > 0) p[0] /= l, p[1] /= l, p[2] /= l;
  }
}

void sessile_surface_stats_of(const sessile_surface *s, sessile_surface_stats *st) {
  memset(st, 0, sizeof *st);
  st->nv = s->nv;
  st->nf = s->nf;
  st->ne = s->nf * 3 / 2; /* closed manifold */
  st->edge_min = st->tri_area_min = INFINITY;
  double esum = 0;
  for (int a = 0; a < 3; a++) st->bbox_min[a] = INFINITY, st->bbox_max[a] = -INFINITY;
  for (uint32_t v = 0; v < s->nv; v++)
    for (int a = 0; a < 3; a++) {
      double x = s->pos[3 * v + a];
      if (x < st->bbox_min[a]) st->bbox_min[a] = x;
      if (x > st->bbox_max[a]) st->bbox_max[a] = x;
    }
  for (uint32_t f = 0; f < s->nf; f++) {
    double c[3];
    face_cross(s, f, c);
    double ar = 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    st->area += ar;
    if (ar < st->tri_area_min) st->tri_area_min = ar;
    const double *a = s->pos + 3 * s->tri[3 * f];
    st->volume += (a[0] * c[0] + a[1] * c[1] + a[2] * c[2]) / 6.0;
    for (int e = 0; e < 3; e++) {
      /* each interior edge is seen twice, once per direction: count a < b */
      uint32_t i = s->tri[3 * f + e], j = s->tri[3 * f + (e + 1) % 3];
      if (i > j) continue;
      const double *p = s->pos + 3 * i, *q = s->pos + 3 * j;
      double l = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                      (p[2] - q[2]) * (p[2] - q[2]));
      esum += l;
      if (l < st->edge_min) st->edge_min = l;
      if (l > st->edge_max) st->edge_max = l;
    }
  }
  if (st->ne) st->edge_mean = esum / st->ne;
  if (!s->nf) st->edge_min = st->tri_area_min = 0;
}
