/* A starting ball with the mirror symmetry of n tips round its equator
 * (Porter & McCormack §3.7, Figure 12: the limbs divide "more or less
 * simultaneously, due to the symmetric initial conditions"; docs/sds.md, "A
 * symmetric start").  The wedge 0 <= phi <= pi/n of the ball (phi the angle
 * about z) is bounded by hand-made triangles (its sphere part in latitude
 * rows, its two half-discs in half-rings) and meshed once by TetGen, keeping
 * that boundary; its 2n images under the mirrors of the dihedral group D_n
 * tile the ball.  Two neighbouring images are mirror images of each other
 * across the plane they share, so they triangulate it alike, whatever
 * TetGen did inside: the complex is conforming with no matching step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/tetgen.h"
#include "sds/sds_internal.h"

enum { CLS_INNER, CLS_A, CLS_B, CLS_AXIS }; /* inside; on the plane phi = 0, phi = alpha; on the z axis */

typedef struct {
  double *p;       /* 3 nv, the wedge about the origin */
  uint8_t *cls;    /* nv */
  uint32_t nv, cv; /* points, capacity */
  uint32_t *tri;   /* 3 nt */
  uint32_t nt, ct;
  uint32_t nt_sphere; /* the first nt_sphere triangles are on the sphere */
} wedge;

static void wedge_free(wedge *w) {
  free(w->p), free(w->cls), free(w->tri);
  memset(w, 0, sizeof *w);
}

static int add_point(wedge *w, double x, double y, double z, int cls, uint32_t *id) {
  if (w->nv == w->cv) {
    uint32_t c = w->cv ? 2 * w->cv : 64;
    double *p = realloc(w->p, 3 * (size_t)c * sizeof *p);
    if (p) w->p = p;
    uint8_t *k = realloc(w->cls, c);
    if (k) w->cls = k;
    if (!p || !k) return 0;
    w->cv = c;
  }
  w->p[3 * (size_t)w->nv] = x, w->p[3 * (size_t)w->nv + 1] = y, w->p[3 * (size_t)w->nv + 2] = z;
  w->cls[w->nv] = (uint8_t)cls;
  *id = w->nv++;
  return 1;
}

static int add_tri(wedge *w, uint32_t a, uint32_t b, uint32_t c) {
  if (w->nt == w->ct) {
    uint32_t n = w->ct ? 2 * w->ct : 128;
    uint32_t *t = realloc(w->tri, 3 * (size_t)n * sizeof *t);
    if (!t) return 0;
    w->tri = t, w->ct = n;
  }
  w->tri[3 * (size_t)w->nt] = a, w->tri[3 * (size_t)w->nt + 1] = b, w->tri[3 * (size_t)w->nt + 2] = c;
  w->nt++;
  return 1;
}

/* Triangles between two polylines running the same way (na, nb >= 1, not
 * both 1): always advance along the one whose next point comes first by
 * its fraction of the way. */
static int strip(wedge *w, const uint32_t *a, int na, const uint32_t *b, int nb) {
  int i = 0, j = 0;
  while (i < na - 1 || j < nb - 1) {
    int on_a = j == nb - 1 || (i < na - 1 && (double)(i + 1) / (na - 1) <= (double)(j + 1) / (nb - 1));
    if (on_a ? !add_tri(w, a[i], a[i + 1], b[j]) : !add_tri(w, a[i], b[j + 1], b[j])) return 0;
    on_a ? i++ : j++;
  }
  return 1;
}

/* The wedge's boundary: radius r, angle alpha, target edge h. */
static sessile_status wedge_boundary(double r, double alpha, double h, wedge *w) {
  const double ca = cos(alpha), sa = sin(alpha);
  int N = 2 * (int)fmax(1.0, lround(SDS_PI * r / (2 * h))); /* even: a row on the equator, where the tips are */
  /* half-rings of each half-disc, the rim included, 2h apart: the ball's
   * inside as coarse as TetGen makes the icosphere's (two edges) */
  int K = (int)fmax(2.0, lround(r / (2 * h)));
  int cap = 4 * N + 64;
  uint32_t *row = malloc(2 * (size_t)cap * sizeof *row), *arc_a = malloc((size_t)(N + 1) * sizeof *arc_a),
           *arc_b = malloc((size_t)(N + 1) * sizeof *arc_b);
  int ok = row && arc_a && arc_b;
  uint32_t *prev = row, *cur = row + cap;
  int nprev = 0;
  /* the sphere: rows of latitude theta_i = i pi / N, from the north pole */
  for (int i = 0; ok && i <= N; i++) {
    double th = SDS_PI * i / N, st = i == 0 || i == N ? 0 : sin(th), ct = i == 0 ? 1 : i == N ? -1 : cos(th);
    int m = i == 0 || i == N ? 0 : (int)fmax(1.0, lround(alpha * r * st / h));
    int ncur = m + 1;
    for (int j = 0; ok && j <= m; j++) {
      int cls = m == 0 ? CLS_AXIS : j == 0 ? CLS_A : j == m ? CLS_B : CLS_INNER;
      double ph = alpha * j / (m ? m : 1);
      double cp = j == 0 ? 1 : j == m ? ca : cos(ph), sp = j == 0 ? 0 : j == m ? sa : sin(ph);
      ok = add_point(w, r * st * cp, r * st * sp, r * ct, cls, &cur[j]);
    }
    if (ok) arc_a[i] = cur[0], arc_b[i] = cur[m];
    if (ok && i > 0) ok = strip(w, prev, nprev, cur, ncur);
    uint32_t *t = prev;
    prev = cur, cur = t, nprev = ncur;
  }
  w->nt_sphere = w->nt;
  /* the half-discs: the centre, half-rings of radius r k / K (k < K) from
   * the +z axis to the -z axis, and the rim (the sphere's arc) */
  uint32_t centre = 0;
  if (ok) ok = add_point(w, 0, 0, 0, CLS_AXIS, &centre);
  uint32_t *ring_a = row, *ring_b = row + cap; /* reused: the rows are done */
  int nring = 1;
  ring_a[0] = ring_b[0] = centre;
  uint32_t *next_a = malloc(2 * (size_t)cap * sizeof *next_a), *next_b = next_a ? next_a + cap : NULL;
  ok = ok && next_a;
  for (int k = 1; ok && k <= K; k++) {
    int M = k == K ? N : (int)fmax(2.0, lround(SDS_PI * r * k / K / (2 * h)));
    double rk = r * k / K;
    for (int j = 0; ok && j <= M; j++) {
      if (k == K) {
        next_a[j] = arc_a[j], next_b[j] = arc_b[j];
        continue;
      }
      double th = SDS_PI * j / M, st = j == 0 || j == M ? 0 : sin(th), ct = j == 0 ? 1 : j == M ? -1 : cos(th);
      if (j == 0 || j == M) {
        ok = add_point(w, 0, 0, rk * ct, CLS_AXIS, &next_a[j]);
        next_b[j] = next_a[j];
      } else {
        ok = add_point(w, rk * st, 0, rk * ct, CLS_A, &next_a[j]) &&
             add_point(w, rk * st * ca, rk * st * sa, rk * ct, CLS_B, &next_b[j]);
      }
    }
    ok = ok && strip(w, ring_a, nring, next_a, M + 1) && strip(w, ring_b, nring, next_b, M + 1);
    memcpy(ring_a, next_a, (size_t)(M + 1) * sizeof *ring_a);
    memcpy(ring_b, next_b, (size_t)(M + 1) * sizeof *ring_b);
    nring = M + 1;
  }
  free(next_a), free(row), free(arc_a), free(arc_b);
  if (!ok) return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the symmetric start");
  /* outward: away from a point inside the (convex) wedge */
  const double q[3] = {0.5 * r * cos(alpha / 2), 0.5 * r * sin(alpha / 2), 0};
  for (uint32_t t = 0; t < w->nt; t++) {
    uint32_t *v = w->tri + 3 * (size_t)t;
    const double *a = w->p + 3 * (size_t)v[0], *b = w->p + 3 * (size_t)v[1], *c = w->p + 3 * (size_t)v[2];
    double e1[3], e2[3], n[3], g[3];
    sds_sub(a, b, e1), sds_sub(a, c, e2), sds_cross(e1, e2, n);
    for (int d = 0; d < 3; d++) g[d] = (a[d] + b[d] + c[d]) / 3 - q[d];
    if (sds_dot(n, g) < 0) {
      uint32_t s = v[1];
      v[1] = v[2], v[2] = s;
    }
  }
  return SESSILE_OK;
}

/* Copy k of the wedge: rotation by 2 alpha (k / 2), after the mirror in the
 * plane phi = alpha for odd k.  Where its points of class A and B land:
 * the plane index j of phi = 2 alpha j (A) or 2 alpha j + alpha (B). */
static void image(double alpha, int k, const double *p, double *out) {
  double x = p[0], y = p[1];
  if (k & 1) {
    double c2 = cos(2 * alpha), s2 = sin(2 * alpha);
    double xm = x * c2 + y * s2, ym = x * s2 - y * c2;
    x = xm, y = ym;
  }
  double th = 2 * alpha * (k / 2), c = k / 2 ? cos(th) : 1, s = k / 2 ? sin(th) : 0;
  out[0] = x * c - y * s, out[1] = x * s + y * c, out[2] = p[2];
}

/* The cells of the tiling: each point of the meshed wedge in each copy,
 * made once (shared points once for all the copies that meet them). */
typedef struct {
  int n;
  double alpha;
  uint32_t nw;        /* points of the meshed wedge (its Steiner points included) */
  const uint8_t *cls; /* nw */
  const double *p;    /* 3 nw */
  uint32_t *shared;   /* the cell of each point: n x nw A points by plane, n x nw B points by plane,
                         nw axis points, then 2n x nw inner points by copy (UINT32_MAX: not yet made) */
  double *x;          /* 3 x cells so far */
  uint32_t ncells;
} tiling;

static uint32_t cell_of(tiling *tl, int k, uint32_t v) {
  int j = k / 2, cls = tl->cls[v];
  uint32_t *slot;
  if (cls == CLS_AXIS) slot = tl->shared + 2 * (size_t)tl->n * tl->nw + v;
  else if (cls == CLS_A) slot = tl->shared + (size_t)((j + (k & 1)) % tl->n) * tl->nw + v;
  else if (cls == CLS_B) slot = tl->shared + (size_t)(tl->n + j) * tl->nw + v;
  else slot = tl->shared + (size_t)(2 * tl->n + 1 + k) * tl->nw + v;
  if (*slot != UINT32_MAX) return *slot;
  /* a shared point takes its plane's rotation of the wedge's point (the
   * same whichever copy meets it first) */
  int kk = cls == CLS_AXIS ? 0 : cls == CLS_A ? 2 * ((j + (k & 1)) % tl->n) : cls == CLS_B ? 2 * j : k;
  image(tl->alpha, kk, tl->p + 3 * (size_t)v, tl->x + 3 * (size_t)tl->ncells);
  *slot = tl->ncells;
  return tl->ncells++;
}

/* The n-fold symmetric ball's complex (cells x, tets: srf NULL), or its
 * sphere's triangles alone (srf: the symmetric rock, no mesh inside; x
 * then holds the cells the triangles use, and no tets). */
static sessile_status tile(int n, double radius, double h, const double center[3], double **x_out,
                           uint32_t *ncells, uint32_t **tet_out, uint32_t *ntets, sessile_surface *srf) {
  const double alpha = SDS_PI / n;
  wedge w = {0};
  sessile_status st = wedge_boundary(radius, alpha, h, &w);
  if (st != SESSILE_OK) {
    wedge_free(&w);
    return st;
  }
  sessile_tetgen_mesh m = {0};
  uint32_t nw = w.nv;    /* the wedge's points: its boundary's, then TetGen's inside */
  const double *pw = w.p;
  if (!srf) {
    char msg[256] = "";
    st = sessile_tetgen_surface(w.p, (int)w.nv, w.tri, (int)w.nt, SESSILE_SDS_TETGEN_SWITCHES, &m, msg, sizeof msg);
    if (st != SESSILE_OK) {
      wedge_free(&w);
      return sessile_error_set(st, "sds: TetGen could not mesh the symmetric start's wedge: %s", msg);
    }
    nw = (uint32_t)m.npoints, pw = m.xyz;
  }
  /* TetGen keeps the input points first and in order, and (switch Y) adds
   * none on the boundary: a Steiner point on a mirror plane would have no
   * partner in the next copy */
  uint8_t *cls = malloc(nw);
  st = cls ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the symmetric start");
  for (uint32_t v = 0; st == SESSILE_OK && v < nw; v++) {
    const double *p = pw + 3 * (size_t)v;
    if (v < w.nv) {
      cls[v] = w.cls[v];
      if (fabs(p[0] - w.p[3 * v]) + fabs(p[1] - w.p[3 * v + 1]) + fabs(p[2] - w.p[3 * v + 2]) > 1e-12 * radius)
        st = sessile_error_set(SESSILE_ERR_NUMERIC, "sds: TetGen moved the symmetric wedge's point %u", v);
    } else {
      cls[v] = CLS_INNER;
      double da = fabs(p[1]), db = fabs(-sin(alpha) * p[0] + cos(alpha) * p[1]);
      if (fmin(da, db) < 1e-9 * radius)
        st = sessile_error_set(SESSILE_ERR_NUMERIC, "sds: TetGen put a point on the symmetric wedge's mirror plane");
    }
  }
  tiling tl = {n, alpha, nw, cls, pw, NULL, NULL, 0};
  uint32_t *tet = NULL;
  size_t nshared = (4 * (size_t)n + 1) * nw;
  if (st == SESSILE_OK) {
    tl.shared = malloc(nshared * sizeof *tl.shared);
    tl.x = malloc(3 * (size_t)2 * n * nw * sizeof *tl.x);
    if (!srf) tet = malloc(4 * (size_t)2 * n * (size_t)m.ntets * sizeof *tet);
    if (!tl.shared || !tl.x || (!srf && !tet))
      st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the symmetric start (%d x %u cells)",
                             2 * n, nw);
  }
  if (st == SESSILE_OK) {
    for (size_t i = 0; i < nshared; i++) tl.shared[i] = UINT32_MAX;
    for (int k = 0; k < 2 * n; k++)
      for (int t = 0; t < m.ntets; t++)
        for (int c = 0; c < 4; c++)
          tet[4 * ((size_t)k * m.ntets + t) + c] = cell_of(&tl, k, (uint32_t)m.tet[4 * (size_t)t + c]);
    for (int k = 0; srf && k < 2 * n; k++) /* the sphere alone: its cells */
      for (uint32_t t = 0; t < 3 * w.nt_sphere; t++) (void)cell_of(&tl, k, w.tri[t]);
    for (uint32_t c = 0; c < tl.ncells; c++)
      for (int d = 0; d < 3; d++) tl.x[3 * (size_t)c + d] += center[d];
  }
  if (st == SESSILE_OK && srf) {
    /* the sphere's triangles of every copy, over the cells they use */
    uint32_t *idx = malloc((size_t)tl.ncells * sizeof *idx);
    st = idx ? sessile_surface_reserve(srf, tl.ncells, 2 * (uint32_t)n * w.nt_sphere)
             : sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for the symmetric sphere");
    if (st == SESSILE_OK) {
      for (uint32_t c = 0; c < tl.ncells; c++) idx[c] = UINT32_MAX;
      srf->nv = srf->nf = 0;
      for (int k = 0; k < 2 * n; k++)
        for (uint32_t t = 0; t < w.nt_sphere; t++) {
          uint32_t *f = srf->tri + 3 * (size_t)srf->nf++;
          for (int c = 0; c < 3; c++) {
            uint32_t g = cell_of(&tl, k, w.tri[3 * (size_t)t + c]);
            if (idx[g] == UINT32_MAX) {
              idx[g] = srf->nv;
              memcpy(srf->pos + 3 * (size_t)srf->nv++, tl.x + 3 * (size_t)g, 3 * sizeof(double));
            }
            f[c] = idx[g];
          }
          if (k & 1) { /* a mirror turns the triangle's winding */
            uint32_t s = f[1];
            f[1] = f[2], f[2] = s;
          }
        }
    }
    free(idx);
  }
  uint32_t nt = (uint32_t)(2 * n * m.ntets);
  free(cls), free(tl.shared), sessile_tetgen_mesh_free(&m), wedge_free(&w);
  if (st != SESSILE_OK) {
    free(tl.x), free(tet);
    return st;
  }
  *x_out = tl.x, *ncells = tl.ncells, *tet_out = tet, *ntets = nt;
  return SESSILE_OK;
}

sessile_status sessile_sds_symmetric_ball_tets(int nfold, double radius, double h, const double center[3],
                                               double **x, uint32_t *ncells, uint32_t **tet, uint32_t *ntets) {
  SESSILE_CHECK(nfold >= 2 && nfold <= 12 && radius > 0 && h > 0 && h <= radius, SESSILE_ERR_USAGE,
                "sds: a symmetric start needs 2..12 mirrors and 0 < edge <= radius (got %d, %g, %g)", nfold, h, radius);
  return tile(nfold, radius, h, center, x, ncells, tet, ntets, NULL);
}

sessile_status sessile_sds_symmetric_ball(int nfold, double radius, double h, const double center[3],
                                          uint32_t nmorph, uint32_t nstate, double density, sessile_sds *out) {
  double *x = NULL;
  uint32_t n = 0, nt = 0, *tet = NULL;
  SESSILE_CALL(sessile_sds_symmetric_ball_tets(nfold, radius, h, center, &x, &n, &tet, &nt));
  sessile_status st = sessile_sds_from_tets(x, n, tet, nt, nmorph, nstate, density, out);
  free(x), free(tet);
  return st;
}

sessile_status sessile_sds_symmetric_sphere(int nfold, double radius, double h, const double center[3],
                                           sessile_surface *out) {
  SESSILE_CHECK(nfold >= 2 && nfold <= 12 && radius > 0 && h > 0 && h <= radius, SESSILE_ERR_USAGE,
                "sds: a symmetric sphere needs 2..12 mirrors and 0 < edge <= radius (got %d, %g, %g)", nfold, h, radius);
  double *x = NULL;
  uint32_t n = 0, nt = 0, *tet = NULL;
  sessile_surface s = {0};
  sessile_status st = tile(nfold, radius, h, center, &x, &n, &tet, &nt, &s);
  free(x);
  if (st != SESSILE_OK) {
    sessile_surface_free(&s);
    return st;
  }
  *out = s;
  return SESSILE_OK;
}
