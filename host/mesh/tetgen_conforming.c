/* The conforming water domain: builds TetGen's piecewise linear complex for
 * the box minus the sponge, runs TetGen (tetgen_shim.cpp) and converts its
 * mesh into a sessile_tetmesh (sessile/mesh/tetgen.h; docs/conforming.md).
 *
 * The PLC: the 8 box corners and the sponge vertices that bound the water;
 * one facet per box face (the rectangle, plus as segments the sponge edges
 * lying in that face and as points the sponge vertices touching it, plus one
 * facet hole point per connected patch of sponge triangles lying in the face:
 * the footprint is cut out of the face); one facet per remaining sponge
 * triangle.  A sponge component with a footprint is open to the outside of
 * the box through it, so TetGen's exterior carving removes its inside; a
 * component touching no face gets a volume hole seed found by the winding
 * number. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/tetgen.h"
#include "tetgen_plc.h"

void sessile_tetgen_options_default(sessile_tetgen_options *o) {
  memset(o, 0, sizeof *o);
  o->radius_edge = 1.5;
}

static const uint32_t face_tag[6] = {SESSILE_TAG_INLET, SESSILE_TAG_OUTLET, SESSILE_TAG_SIDE,
                                     SESSILE_TAG_SIDE,  SESSILE_TAG_SUBSTRATUM, SESSILE_TAG_TOP};

/* --- small union-find ---------------------------------------------------- */
static uint32_t uf_find(uint32_t *p, uint32_t x) {
  while (p[x] != x) x = p[x] = p[p[x]];
  return x;
}
static void uf_union(uint32_t *p, uint32_t a, uint32_t b) {
  a = uf_find(p, a), b = uf_find(p, b);
  if (a < b) p[b] = a;
  else if (b < a) p[a] = b;
}

typedef struct edge_key {
  uint32_t a, b, tri, face;
} edge_key;
static int edge_cmp(const void *x, const void *y) {
  const edge_key *p = x, *q = y;
  if (p->face != q->face) return p->face < q->face ? -1 : 1;
  if (p->a != q->a) return p->a < q->a ? -1 : 1;
  if (p->b != q->b) return p->b < q->b ? -1 : 1;
  return (p->tri > q->tri) - (p->tri < q->tri);
}

/* Solid angle of triangle abc seen from p (Van Oosterom & Strackee). */
static double solid_angle(const double *p, const double *a, const double *b, const double *c) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) u[k] = a[k] - p[k], v[k] = b[k] - p[k], w[k] = c[k] - p[k];
  double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  double lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double lw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
               u[2] * (v[0] * w[1] - v[1] * w[0]);
  double den = lu * lv * lw + (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * lw +
               (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) * lv + (v[0] * w[0] + v[1] * w[1] + v[2] * w[2]) * lu;
  return 2.0 * atan2(det, den);
}

/* Winding number of the triangles of component comp at p. */
static double winding(const sessile_surface *s, const double *pos, const uint32_t *tcomp, uint32_t comp,
                      const double *p) {
  double sum = 0;
  for (uint32_t t = 0; t < s->nf; t++)
    if (tcomp[t] == comp) {
      const uint32_t *v = s->tri + 3 * t;
      sum += solid_angle(p, pos + 3 * v[0], pos + 3 * v[1], pos + 3 * v[2]);
    }
  return sum / (4 * 3.14159265358979323846);
}

/* Growable int / double arrays for the PLC. */
typedef struct ivec { int *d; size_t n, cap; } ivec;
typedef struct dvec { double *d; size_t n, cap; } dvec;
static int ipush(ivec *v, int x) {
  if (v->n == v->cap) {
    size_t c = v->cap ? 2 * v->cap : 64;
    int *d = realloc(v->d, c * sizeof *d);
    if (!d) return 0;
    v->d = d, v->cap = c;
  }
  v->d[v->n++] = x;
  return 1;
}
static int dpush(dvec *v, const double *x, int k) {
  for (int i = 0; i < k; i++) {
    if (v->n == v->cap) {
      size_t c = v->cap ? 2 * v->cap : 64;
      double *d = realloc(v->d, c * sizeof *d);
      if (!d) return 0;
      v->d = d, v->cap = c;
    }
    v->d[v->n++] = x[i];
  }
  return 1;
}

typedef struct build {
  ivec facet_poly, poly_vert, verts, facet_hole, marker;
  dvec fholes, holes;
  double *xyz, *size;
  uint32_t *mask, *plc_of, *tcomp, *uf;
  int8_t *flat;
  edge_key *edges;
} build;

static void build_free(build *b) {
  free(b->facet_poly.d), free(b->poly_vert.d), free(b->verts.d), free(b->facet_hole.d);
  free(b->marker.d), free(b->fholes.d), free(b->holes.d), free(b->xyz), free(b->size);
  free(b->mask), free(b->plc_of), free(b->tcomp), free(b->uf), free(b->flat), free(b->edges);
}

#define NOMEM() sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory building TetGen's input")

/* Adds polygon with n vertices to the facet being built. */
static int add_poly(build *b, const int *v, int n) {
  for (int i = 0; i < n; i++)
    if (!ipush(&b->verts, v[i])) return 0;
  return ipush(&b->poly_vert, (int)b->verts.n);
}

static sessile_status make_plc(const sessile_box *box, const sessile_surface *s,
                               const sessile_tetgen_options *o, build *b, tg_plc *plc) {
  double lo[3], hi[3], ext = 0;
  memcpy(lo, box->origin, sizeof lo);
  sessile_box_max(box, hi);
  for (int a = 0; a < 3; a++) ext = fmax(ext, hi[a] - lo[a]);
  const double tol = 1e-9 * ext;
  uint32_t nv = s->nv, nf = s->nf;
  double *pos = malloc((size_t)3 * nv * sizeof *pos);
  b->mask = calloc(nv, sizeof *b->mask);
  b->plc_of = malloc((size_t)nv * sizeof *b->plc_of);
  b->flat = malloc(nf ? nf : 1);
  b->tcomp = malloc((size_t)nf * sizeof *b->tcomp);
  b->uf = malloc((size_t)(nv > nf ? nv : nf) * sizeof *b->uf);
  b->edges = malloc((size_t)3 * nf * sizeof *b->edges);
  b->xyz = pos;
  if (!pos || !b->mask || !b->plc_of || !b->flat || !b->tcomp || !b->uf || !b->edges) return NOMEM();
  /* Vertices: inside the box, snapped onto the faces they touch. */
  for (uint32_t v = 0; v < nv; v++) {
    for (int a = 0; a < 3; a++) {
      double x = s->pos[3 * v + a];
      SESSILE_CHECK(isfinite(x), SESSILE_ERR_NUMERIC, "sponge vertex %u has a non-finite coordinate", v);
      SESSILE_CHECK(x >= lo[a] - tol && x <= hi[a] + tol, SESSILE_ERR_USAGE,
                    "sponge vertex %u at (%g, %g, %g) lies outside the box; the conforming mesh needs "
                    "the sponge inside the box", v, s->pos[3 * v], s->pos[3 * v + 1], s->pos[3 * v + 2]);
      if (fabs(x - lo[a]) <= tol) x = lo[a], b->mask[v] |= 1u << (2 * a);
      else if (fabs(x - hi[a]) <= tol) x = hi[a], b->mask[v] |= 1u << (2 * a + 1);
      pos[3 * v + a] = x;
    }
    uint32_t m = b->mask[v];
    SESSILE_CHECK((m & (m - 1)) == 0, SESSILE_ERR_USAGE,
                  "sponge vertex %u at (%g, %g, %g) lies on a box edge or corner; the conforming mesh "
                  "needs the sponge to touch at most one box face at each vertex", v,
                  s->pos[3 * v], s->pos[3 * v + 1], s->pos[3 * v + 2]);
  }
  for (uint32_t t = 0; t < nf; t++) {
    const uint32_t *v = s->tri + 3 * t;
    SESSILE_CHECK(v[0] < nv && v[1] < nv && v[2] < nv, SESSILE_ERR_USAGE,
                  "sponge triangle %u has a vertex index out of range", t);
    uint32_t m = b->mask[v[0]] & b->mask[v[1]] & b->mask[v[2]];
    b->flat[t] = m ? (int8_t)__builtin_ctz(m) : (int8_t)-1;
  }
  /* PLC points: 8 corners, then the vertices of the non-flat triangles. */
  for (uint32_t v = 0; v < nv; v++) b->plc_of[v] = UINT32_MAX;
  int np = 8;
  for (uint32_t t = 0; t < nf; t++)
    if (b->flat[t] < 0)
      for (int q = 0; q < 3; q++) b->plc_of[s->tri[3 * t + q]] = 1;
  for (uint32_t v = 0; v < nv; v++)
    if (b->plc_of[v] != UINT32_MAX) b->plc_of[v] = (uint32_t)np++;
  SESSILE_CHECK(np > 8, SESSILE_ERR_USAGE, "the sponge has no triangle off the box faces");
  plc->npoints = np;
  plc->xyz = malloc((size_t)3 * np * sizeof *plc->xyz);
  b->size = malloc((size_t)np * sizeof *b->size);
  double *ecount = calloc((size_t)np, sizeof *ecount);
  if (!plc->xyz || !b->size || !ecount) {
    free(ecount);
    free(plc->xyz), plc->xyz = NULL;
    return NOMEM();
  }
  double far = o->size_far > 0 ? o->size_far : 4 * box->h;
  for (int c = 0; c < 8; c++) {
    plc->xyz[3 * c] = (c & 1) ? hi[0] : lo[0];
    plc->xyz[3 * c + 1] = (c & 2) ? hi[1] : lo[1];
    plc->xyz[3 * c + 2] = (c & 4) ? hi[2] : lo[2];
    b->size[c] = far;
  }
  for (int i = 8; i < np; i++) b->size[i] = 0;
  for (uint32_t v = 0; v < nv; v++)
    if (b->plc_of[v] != UINT32_MAX) memcpy(plc->xyz + 3 * b->plc_of[v], pos + 3 * v, 3 * sizeof(double));
  /* Sizes: mean incident edge length (each edge seen from both triangles). */
  for (uint32_t t = 0; t < nf; t++)
    for (int q = 0; q < 3; q++) {
      uint32_t a = s->tri[3 * t + q], c = s->tri[3 * t + (q + 1) % 3];
      double d = sqrt(pow(pos[3 * a] - pos[3 * c], 2) + pow(pos[3 * a + 1] - pos[3 * c + 1], 2) +
                      pow(pos[3 * a + 2] - pos[3 * c + 2], 2));
      for (int e = 0; e < 2; e++) {
        uint32_t w = e ? c : a;
        if (b->plc_of[w] == UINT32_MAX) continue;
        b->size[b->plc_of[w]] += d;
        ecount[b->plc_of[w]] += 1;
      }
    }
  for (int i = 8; i < np; i++) b->size[i] = o->size_sponge > 0 ? o->size_sponge : b->size[i] / ecount[i];
  free(ecount);
  plc->size = b->size;

  /* Edges lying in a box face (both ends on it) from the non-flat triangles:
   * segments of that face's facet; edges of the flat triangles: patches. */
  size_t ne = 0;
  for (uint32_t t = 0; t < nf; t++)
    for (int q = 0; q < 3; q++) {
      uint32_t a = s->tri[3 * t + q], c = s->tri[3 * t + (q + 1) % 3];
      uint32_t m = b->mask[a] & b->mask[c];
      if (!m) continue;
      edge_key k = {a < c ? a : c, a < c ? c : a, t, (uint32_t)__builtin_ctz(m)};
      b->edges[ne++] = k;
    }
  qsort(b->edges, ne, sizeof *b->edges, edge_cmp);
  for (uint32_t t = 0; t < nf; t++) b->uf[t] = t;
  for (size_t i = 0; i + 1 < ne; i++) {
    const edge_key *p = b->edges + i, *q = p + 1;
    if (p->a == q->a && p->b == q->b && p->face == q->face && b->flat[p->tri] >= 0 && b->flat[q->tri] >= 0)
      uf_union(b->uf, p->tri, q->tri);
  }
  if (!ipush(&b->facet_poly, 0) || !ipush(&b->poly_vert, 0) || !ipush(&b->facet_hole, 0)) return NOMEM();
  for (int f = 0; f < 6; f++) {
    int a = f / 2, side = f % 2, bb = (a + 1) % 3, cc = (a + 2) % 3;
    int ring[4];
    static const int rb[4] = {0, 1, 1, 0}, rc[4] = {0, 0, 1, 1};
    for (int r = 0; r < 4; r++) ring[r] = (side << a) | (rb[r] << bb) | (rc[r] << cc);
    if (!add_poly(b, ring, 4)) return NOMEM();
    /* segments: unique edges in face f with at least one non-flat triangle */
    for (size_t i = 0; i < ne;) {
      size_t j = i;
      int nonflat = 0;
      while (j < ne && b->edges[j].a == b->edges[i].a && b->edges[j].b == b->edges[i].b &&
             b->edges[j].face == b->edges[i].face)
        nonflat |= b->flat[b->edges[j].tri] < 0, j++;
      if ((int)b->edges[i].face == f && nonflat) {
        int seg[2] = {(int)b->plc_of[b->edges[i].a], (int)b->plc_of[b->edges[i].b]};
        if (!add_poly(b, seg, 2)) return NOMEM();
      }
      i = j;
    }
    /* points: PLC vertices on face f on no segment (the sponge touches the face there) */
    for (uint32_t v = 0; v < nv; v++) {
      if (b->plc_of[v] == UINT32_MAX || !(b->mask[v] & (1u << f))) continue;
      int on_edge = 0;
      for (size_t i = 0; i < ne && !on_edge; i++)
        on_edge = (int)b->edges[i].face == f && (b->edges[i].a == v || b->edges[i].b == v);
      if (!on_edge) {
        int pt = (int)b->plc_of[v];
        if (!add_poly(b, &pt, 1)) return NOMEM();
      }
    }
    /* facet holes: the centroid of one flat triangle per patch */
    for (uint32_t t = 0; t < nf; t++)
      if (b->flat[t] == f && uf_find(b->uf, t) == t) {
        double c[3] = {0, 0, 0};
        for (int q = 0; q < 3; q++)
          for (int k = 0; k < 3; k++) c[k] += pos[3 * s->tri[3 * t + q] + k] / 3;
        if (!dpush(&b->fholes, c, 3)) return NOMEM();
      }
    if (!ipush(&b->facet_poly, (int)b->poly_vert.n - 1) || !ipush(&b->facet_hole, (int)(b->fholes.n / 3)) ||
        !ipush(&b->marker, (int)face_tag[f]))
      return NOMEM();
  }
  for (uint32_t t = 0; t < nf; t++) {
    if (b->flat[t] >= 0) continue;
    int tv[3] = {(int)b->plc_of[s->tri[3 * t]], (int)b->plc_of[s->tri[3 * t + 1]],
                 (int)b->plc_of[s->tri[3 * t + 2]]};
    if (!add_poly(b, tv, 3) || !ipush(&b->facet_poly, (int)b->poly_vert.n - 1) ||
        !ipush(&b->facet_hole, (int)(b->fholes.n / 3)) || !ipush(&b->marker, (int)SESSILE_TAG_SPONGE))
      return NOMEM();
  }
  /* Volume holes: components (triangles joined through shared vertices)
   * without a flat triangle are closed off from the outside. */
  for (uint32_t v = 0; v < nv; v++) b->uf[v] = v;
  for (uint32_t t = 0; t < nf; t++) {
    uf_union(b->uf, s->tri[3 * t], s->tri[3 * t + 1]);
    uf_union(b->uf, s->tri[3 * t], s->tri[3 * t + 2]);
  }
  for (uint32_t t = 0; t < nf; t++) b->tcomp[t] = uf_find(b->uf, s->tri[3 * t]);
  for (uint32_t t = 0; t < nf; t++) /* mark components with a footprint */
    if (b->flat[t] >= 0) b->mask[b->tcomp[t]] |= 1u << 8;
  for (uint32_t t = 0; t < nf; t++) {
    uint32_t comp = b->tcomp[t];
    if (b->mask[comp] & (3u << 8)) continue; /* open, or seeded already */
    b->mask[comp] |= 1u << 9;
    /* Seed: just inside the centroid of one of its triangles, checked by the
     * winding number of the component (1 inside, 0 outside). */
    int found = 0;
    for (uint32_t u = t; u < nf && !found; u++) {
      if (b->tcomp[u] != comp) continue;
      const double *p0 = pos + 3 * s->tri[3 * u], *p1 = pos + 3 * s->tri[3 * u + 1], *p2 = pos + 3 * s->tri[3 * u + 2];
      double e1[3], e2[3], n[3], c[3];
      for (int k = 0; k < 3; k++) e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k], c[k] = (p0[k] + p1[k] + p2[k]) / 3;
      n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
      double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(len > 0)) continue;
      double h = sqrt(len / 2); /* ~ the triangle's size */
      for (double eps = 0.1 * h; eps > 1e-4 * h && !found; eps *= 0.25) {
        double p[3] = {c[0] - eps * n[0] / len, c[1] - eps * n[1] / len, c[2] - eps * n[2] / len};
        if (fabs(winding(s, pos, b->tcomp, comp, p) - 1) < 0.25) {
          if (!dpush(&b->holes, p, 3)) return NOMEM();
          found = 1;
        }
      }
      if (u > t + 64) break;
    }
    SESSILE_CHECK(found, SESSILE_ERR_NUMERIC,
                  "found no point inside the sponge component of triangle %u (is it closed and "
                  "oriented outward?)", t);
  }
  plc->nfacets = (int)b->marker.n;
  plc->facet_poly = b->facet_poly.d;
  plc->poly_vert = b->poly_vert.d;
  plc->verts = b->verts.d;
  plc->facet_hole = b->facet_hole.d;
  plc->fholes = b->fholes.d;
  plc->facet_marker = b->marker.d;
  plc->nholes = (int)(b->holes.n / 3);
  plc->holes = b->holes.d;
  return SESSILE_OK;
}

/* A triangle: o = its nodes sorted (the key), v = in the original order. */
typedef struct face_key {
  uint32_t o[3], v[3], tag;
} face_key;
static void face_sort(face_key *e) {
  memcpy(e->v, e->o, sizeof e->v);
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2 - a; b++)
      if (e->o[b] > e->o[b + 1]) {
        uint32_t x = e->o[b];
        e->o[b] = e->o[b + 1];
        e->o[b + 1] = x;
      }
}
static int face_cmp(const void *x, const void *y) {
  const face_key *p = x, *q = y;
  for (int c = 0; c < 3; c++)
    if (p->o[c] != q->o[c]) return p->o[c] < q->o[c] ? -1 : 1;
  return 0;
}

/* TetGen's mesh -> sessile_tetmesh: unused points dropped, tets positively
 * oriented, boundary faces oriented outward from the water. */
static sessile_status convert(const tg_result *r, sessile_tetmesh *m) {
  uint32_t *map = malloc((size_t)(r->npoints ? r->npoints : 1) * sizeof *map);
  if (!map) return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory converting TetGen's mesh");
  for (int i = 0; i < r->npoints; i++) map[i] = UINT32_MAX;
  for (size_t i = 0; i < 4 * (size_t)r->ntets; i++) {
    if (r->tet[i] < 0 || r->tet[i] >= r->npoints) {
      free(map);
      return sessile_error_set(SESSILE_ERR_INTERNAL, "TetGen returned a tet corner out of range");
    }
    map[r->tet[i]] = 0;
  }
  uint32_t nn = 0;
  for (int i = 0; i < r->npoints; i++)
    if (map[i] == 0) map[i] = nn++;
  m->xyz = malloc((size_t)3 * nn * sizeof *m->xyz);
  m->tet = malloc((size_t)4 * r->ntets * sizeof *m->tet);
  m->node_tags = calloc(nn, sizeof *m->node_tags);
  if (!m->xyz || !m->tet || !m->node_tags) {
    free(map);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for a %u-node tet mesh", nn);
  }
  m->nnodes = nn;
  for (int i = 0; i < r->npoints; i++)
    if (map[i] != UINT32_MAX) memcpy(m->xyz + 3 * map[i], r->xyz + 3 * i, 3 * sizeof(double));
  m->ntets = (uint32_t)r->ntets;
  for (uint32_t t = 0; t < m->ntets; t++) {
    for (int q = 0; q < 4; q++) m->tet[4 * t + q] = map[r->tet[4 * t + q]];
    if (sessile_tetmesh_tet_volume(m, t) < 0) {
      uint32_t x = m->tet[4 * t + 1];
      m->tet[4 * t + 1] = m->tet[4 * t + 2];
      m->tet[4 * t + 2] = x;
    }
  }
  /* Boundary faces: the tet faces that occur once, oriented outward (the
   * outward faces of a positively oriented tet), each tagged with the marker
   * of TetGen's facet subface on the same three nodes. */
  static const int fo[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  size_t nk = 4 * (size_t)m->ntets;
  face_key *k = malloc((nk + (size_t)r->nfaces + 1) * sizeof *k);
  if (!k) {
    free(map);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory converting TetGen's mesh");
  }
  face_key *sub = k + nk;
  for (uint32_t t = 0; t < m->ntets; t++)
    for (int q = 0; q < 4; q++) {
      face_key *e = k + 4 * (size_t)t + q;
      for (int c = 0; c < 3; c++) e->o[c] = m->tet[4 * t + fo[q][c]];
      face_sort(e);
    }
  for (int f = 0; f < r->nfaces; f++) {
    for (int c = 0; c < 3; c++) sub[f].o[c] = map[r->face[3 * f + c]];
    sub[f].tag = (uint32_t)r->face_marker[f];
    face_sort(&sub[f]);
  }
  qsort(k, nk, sizeof *k, face_cmp);
  qsort(sub, (size_t)r->nfaces, sizeof *sub, face_cmp);
  size_t nb = 0;
  for (size_t i = 0; i < nk;) {
    size_t j = i + 1;
    while (j < nk && face_cmp(k + i, k + j) == 0) j++;
    if (j - i == 1) k[nb++] = k[i];
    else if (j - i != 2) {
      free(k), free(map);
      return sessile_error_set(SESSILE_ERR_INTERNAL, "TetGen's mesh has a face shared by %zu tets", j - i);
    }
    i = j;
  }
  m->bface = malloc(3 * (nb ? nb : 1) * sizeof *m->bface);
  m->bface_tag = malloc((nb ? nb : 1) * sizeof *m->bface_tag);
  sessile_status st = SESSILE_OK;
  if (!m->bface || !m->bface_tag)
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %zu boundary faces", nb);
  for (size_t f = 0; f < nb && st == SESSILE_OK; f++) {
    face_key *hit = bsearch(k + f, sub, (size_t)r->nfaces, sizeof *sub, face_cmp);
    uint32_t mk = hit ? hit->tag : 0;
    int valid = mk == SESSILE_TAG_SPONGE;
    for (int q = 0; q < 6; q++) valid |= mk == face_tag[q];
    if (!valid) {
      st = sessile_error_set(SESSILE_ERR_INTERNAL, "a boundary face of TetGen's mesh has no facet marker (%u)", mk);
      break;
    }
    memcpy(m->bface + 3 * f, k[f].v, sizeof k[f].v);
    m->bface_tag[f] = mk;
    for (int q = 0; q < 3; q++) m->node_tags[k[f].v[q]] |= mk;
  }
  m->nbfaces = (uint32_t)nb;
  free(k);
  free(map);
  return st;
}

sessile_status sessile_tetgen_conforming(const sessile_box *box, const sessile_surface *sponge,
                                         const sessile_tetgen_options *opt, sessile_tetmesh *out) {
  memset(out, 0, sizeof *out);
  sessile_tetgen_options o;
  if (opt) o = *opt;
  else sessile_tetgen_options_default(&o);
  SESSILE_CHECK(box && sponge && box->n[0] >= 2 && box->n[1] >= 2 && box->n[2] >= 2 && box->h > 0,
                SESSILE_ERR_USAGE, "conforming mesh needs a box of at least one cell per axis");
  SESSILE_CHECK(sponge->nv >= 4 && sponge->nf >= 4 && sponge->nv < INT32_MAX / 4 && sponge->nf < INT32_MAX / 4,
                SESSILE_ERR_USAGE, "conforming mesh needs a closed sponge surface (got %u vertices, %u triangles)",
                sponge->nv, sponge->nf);
  SESSILE_CHECK(o.radius_edge == 0 || o.radius_edge >= 1.0, SESSILE_ERR_USAGE,
                "TetGen radius-edge bound must be 0 (off) or at least 1 (got %g)", o.radius_edge);
  SESSILE_CHECK(o.max_volume >= 0 && o.size_far >= 0 && o.size_sponge >= 0, SESSILE_ERR_USAGE,
                "TetGen volume and size options must be >= 0");
  build b;
  tg_plc plc;
  memset(&b, 0, sizeof b);
  memset(&plc, 0, sizeof plc);
  sessile_status st = make_plc(box, sponge, &o, &b, &plc);
  if (st != SESSILE_OK) {
    free(plc.xyz);
    build_free(&b);
    return st;
  }
  char sw[128];
  int n = snprintf(sw, sizeof sw, "pz%s", o.verbose ? "V" : "Q");
  if (o.radius_edge > 0) n += snprintf(sw + n, sizeof sw - n, "q%.6gm", o.radius_edge);
  if (o.max_volume > 0) n += snprintf(sw + n, sizeof sw - n, "a%.9g", o.max_volume);
  if (o.preserve_surface) snprintf(sw + n, sizeof sw - n, "Y");
  if (o.radius_edge == 0) plc.size = NULL;
  tg_result r;
  char msg[256];
  int code = tg_tetrahedralize(&plc, sw, &r, msg, sizeof msg);
  free(plc.xyz);
  build_free(&b);
  if (code != 0) {
    /* Only TetGen's verdicts on the input geometry are SESSILE_ERR_NUMERIC
     * (callers may fall back to another domain on those), and a failed
     * assert() in TetGen (-3), which an input it cannot mesh trips; running
     * out of memory and TetGen's internal errors are not about the input. */
    sessile_status st_tg = code == 1 || code == -2                         ? SESSILE_ERR_NO_MEMORY
                           : code == 3 || code == 4 || code == 5 || code == 10 || code == -3 ? SESSILE_ERR_NUMERIC
                                                                              : SESSILE_ERR_INTERNAL;
    return sessile_error_set(st_tg, "conforming mesh of the box minus the sponge (%u vertices, %u triangles): %s",
                             sponge->nv, sponge->nf, msg);
  }
  st = convert(&r, out);
  tg_result_free(&r);
  if (st != SESSILE_OK) sessile_tetmesh_free(out);
  return st;
}
