/* Shared by tests/sds/test_topo_*.c: a TetGen ball as an SDS complex, the
 * sorted boundary of a complex, timing. */
#ifndef TEST_TOPO_FIXTURE_H
#define TEST_TOPO_FIXTURE_H
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "mesh/tetgen_plc.h"
#include "sessile/sds/sds_topo.h"
#include "sessile/mesh/surface.h"
#include "testutil.h"

static inline double fx_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* A unit ball: the icosphere of the given level meshed by TetGen with a
 * quality bound and a volume cap (interior vertices), positively oriented. */
static inline void fx_ball(int level, double max_vol, sessile_sds_topo_complex *cx) {
  sessile_surface s;
  memset(&s, 0, sizeof s);
  double c0[3] = {0, 0, 0};
  t_must("icosphere", sessile_surface_icosphere(level, 1.0, c0, &s));
  int nf = (int)s.nf;
  int *fp = t_xalloc((nf + 1) * sizeof(int)), *pv = t_xalloc((nf + 1) * sizeof(int));
  int *vs = t_xalloc(3 * nf * sizeof(int)), *fh = t_xalloc((nf + 1) * sizeof(int)), *mk = t_xalloc(nf * sizeof(int));
  for (int f = 0; f <= nf; f++) fp[f] = f, pv[f] = 3 * f;
  for (int i = 0; i < 3 * nf; i++) vs[i] = (int)s.tri[i];
  for (int f = 0; f < nf; f++) mk[f] = 1;
  tg_plc plc = {(int)s.nv, s.pos, NULL, nf, fp, pv, vs, fh, NULL, mk, 0, NULL};
  char sw[64], msg[256];
  snprintf(sw, sizeof sw, "pq1.4a%gYzQ", max_vol);
  tg_result r;
  int code = tg_tetrahedralize(&plc, sw, &r, msg, sizeof msg);
  if (code) {
    fprintf(stderr, "TetGen: %s\n", msg);
    exit(1);
  }
  cx->nv = (uint32_t)r.npoints, cx->nt = (uint32_t)r.ntets;
  cx->x = r.xyz, r.xyz = NULL;
  cx->tet = t_xalloc(4 * (size_t)cx->nt * sizeof *cx->tet);
  for (size_t i = 0; i < 4 * (size_t)cx->nt; i++) cx->tet[i] = (uint32_t)r.tet[i];
  for (uint32_t t = 0; t < cx->nt; t++) {
    uint32_t *v = cx->tet + 4 * t;
    if (sessile_sds_topo_volume(cx->x + 3 * v[0], cx->x + 3 * v[1], cx->x + 3 * v[2], cx->x + 3 * v[3]) < 0) {
      uint32_t x = v[1];
      v[1] = v[2], v[2] = x;
    }
  }
  tg_result_free(&r);
  free(fp), free(pv), free(vs), free(fh), free(mk);
  sessile_surface_free(&s);
}

static inline double fx_volume(const sessile_sds_topo_complex *cx) {
  double v = 0;
  for (uint32_t t = 0; t < cx->nt; t++) {
    const uint32_t *q = cx->tet + 4 * t;
    v += sessile_sds_topo_volume(cx->x + 3 * q[0], cx->x + 3 * q[1], cx->x + 3 * q[2], cx->x + 3 * q[3]);
  }
  return v;
}

/* Boundary faces as sorted (rotated so the smallest index leads) triples,
 * sorted: two complexes with the same boundary give equal arrays. */
static inline int fx_u3cmp(const void *a, const void *b) { return memcmp(a, b, 3 * sizeof(uint32_t)); }
static inline uint32_t *fx_boundary(const sessile_sds_topo_complex *cx, uint32_t *nb) {
  uint32_t n4 = 4 * cx->nt, *all = t_xalloc((size_t)n4 * 4 * sizeof *all),
           *out = t_xalloc((size_t)n4 * 3 * sizeof *out);
  static const int fo[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (uint32_t t = 0; t < cx->nt; t++)
    for (int q = 0; q < 4; q++) {
      uint32_t *k = all + 4 * (4 * t + q), v[3];
      for (int i = 0; i < 3; i++) v[i] = cx->tet[4 * t + fo[q][i]];
      int m = v[0] < v[1] ? (v[0] < v[2] ? 0 : 2) : (v[1] < v[2] ? 1 : 2);
      for (int i = 0; i < 3; i++) k[i] = v[(m + i) % 3];
      /* unordered key in k[3]-less form: sort copies for matching below */
      k[3] = 0;
    }
  /* a face is on the boundary when its vertex set occurs once */
  uint32_t *key = t_xalloc((size_t)n4 * 4 * sizeof *key);
  for (uint32_t i = 0; i < n4; i++) {
    uint32_t a = all[4 * i], b = all[4 * i + 1], c = all[4 * i + 2], s;
    if (a > b) s = a, a = b, b = s;
    if (b > c) s = b, b = c, c = s;
    if (a > b) s = a, a = b, b = s;
    key[4 * i] = a, key[4 * i + 1] = b, key[4 * i + 2] = c, key[4 * i + 3] = i;
  }
  qsort(key, n4, 4 * sizeof *key, fx_u3cmp);
  uint32_t k = 0;
  for (uint32_t i = 0; i < n4;) {
    uint32_t j = i + 1;
    while (j < n4 && !memcmp(key + 4 * i, key + 4 * j, 3 * sizeof *key)) j++;
    if (j == i + 1) memcpy(out + 3 * k++, all + 4 * key[4 * i + 3], 3 * sizeof *out);
    i = j;
  }
  qsort(out, k, 3 * sizeof *out, fx_u3cmp);
  free(all), free(key);
  *nb = k;
  return out;
}

/* Is vertex v on the boundary of cx? */
static inline int fx_on_boundary(const sessile_sds_topo_complex *cx, uint32_t v) {
  uint32_t nb, *b = fx_boundary(cx, &nb);
  int on = 0;
  for (uint32_t i = 0; i < 3 * nb; i++) on |= b[i] == v;
  free(b);
  return on;
}

static inline void fx_copy(const sessile_sds_topo_complex *a, sessile_sds_topo_complex *b) {
  b->nv = a->nv, b->nt = a->nt;
  b->x = t_xalloc(3 * (size_t)a->nv * sizeof *b->x);
  b->tet = t_xalloc(4 * (size_t)a->nt * sizeof *b->tet);
  memcpy(b->x, a->x, 3 * (size_t)a->nv * sizeof *b->x);
  memcpy(b->tet, a->tet, 4 * (size_t)a->nt * sizeof *b->tet);
}
#endif
