/* The venation model (sessile/coral/venation.h) against its invariants:
 *   open venation is a tree (every node's parent precedes it, no extra edge:
 *   |E| = |V| - 1, connected); closed venation has cycles (|E| >= |V|) and
 *   stays connected (union-find over every edge); the root's thickness index
 *   equals the node count and every node's equals 1 + its descendants
 *   (recounted from the parents); after every open iteration no auxin lies
 *   within the kill radius of a node (brute force); the first iteration's
 *   auxins lie in the blade and at least the birth distance from the root
 *   and from each other; the GPU search grows the same graph bit for bit as
 *   the host search; same seed, same graph; the thickness curve through its
 *   control points; the skeleton's frames normal to each segment and its
 *   tubes closed; every parameter out of range and an empty blade refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/skeleton.h"
#include "sessile/coral/venation.h"
#include "testutil.h"

static double d2of(const double *a, const double *b) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

static uint32_t find(uint32_t *u, uint32_t x) {
  while (u[x] != x) x = u[x] = u[u[x]];
  return x;
}

/* 1 when the graph (parents and extra edges) is connected. */
static int connected(const sessile_venation *v) {
  uint32_t *u = t_xalloc((size_t)v->n * sizeof *u), comps = v->n;
  for (uint32_t i = 0; i < v->n; i++) u[i] = i;
  for (uint32_t i = 1; i < v->n; i++) {
    uint32_t a = find(u, i), b = find(u, v->parent[i]);
    if (a != b) u[a] = b, comps--;
  }
  for (uint32_t e = 0; e < v->ne; e++) {
    uint32_t a = find(u, v->edge[2 * e]), b = find(u, v->edge[2 * e + 1]);
    if (a != b) u[a] = b, comps--;
  }
  free(u);
  return comps == 1;
}

/* Thickness indices recounted: 1 + descendants, children after parents. */
static int ti_ok(const sessile_venation *v) {
  uint32_t *t = t_xalloc((size_t)v->n * sizeof *t);
  for (uint32_t i = 0; i < v->n; i++) t[i] = 1;
  for (uint32_t i = v->n; i-- > 1;) t[v->parent[i]] += t[i];
  int ok = 1;
  for (uint32_t i = 0; i < v->n; i++) ok &= t[i] == v->ti[i];
  free(t);
  return ok;
}

static int parents_precede(const sessile_venation *v) {
  int ok = v->parent[0] == SESSILE_VENATION_NONE;
  for (uint32_t i = 1; i < v->n; i++) ok &= v->parent[i] < i;
  return ok;
}

static void grow(sessile_venation *v, const sessile_venation_params *p, sessile_venation_gpu *vg, uint64_t seed,
                 int its) {
  t_must("init", sessile_venation_init(v, seed));
  for (int k = 0; k < its; k++) t_must("step", sessile_venation_step(v, p, vg));
}

static int same_graph(const sessile_venation *a, const sessile_venation *b) {
  return a->n == b->n && a->ne == b->ne && a->na == b->na && a->rng == b->rng &&
         !memcmp(a->pos, b->pos, 3 * a->n * sizeof *a->pos) && !memcmp(a->parent, b->parent, a->n * 4) &&
         !memcmp(a->edge, b->edge, 2 * a->ne * 4) && !memcmp(a->aux, b->aux, 3 * a->na * sizeof *a->aux);
}

int main(void) {
  sessile_gpu *g = t_gpu(64);
  sessile_venation_gpu *vg = NULL;
  t_must("create the search", sessile_venation_gpu_create(g, &vg));
  sessile_venation_params p;
  sessile_params_defaults(&sessile_venation_param_table, &p);
  t_ok("the defaults pass their checks", sessile_params_check(&sessile_venation_param_table, &p));

  /* the first iteration's dart throwing */
  sessile_venation v;
  grow(&v, &p, NULL, 5, 1);
  double w1 = sessile_venation_width(&p, 1), b2 = p.birth_distance * p.birth_distance;
  int in = 1, apart = 1;
  for (uint32_t a = 0; a < v.na; a++) {
    const double *q = v.aux + 3 * a;
    in &= q[1] == 0 && sessile_venation_in_blade(&p, w1, q[0], q[2]);
    for (uint32_t b = 0; b < a; b++) apart &= d2of(q, v.aux + 3 * b) >= b2;
    apart &= d2of(q, v.pos) >= b2; /* the root, the only node before growth */
  }
  t_true("iteration 1: auxins were placed", v.placed > 0);
  t_true("iteration 1: every auxin in the blade (y = 0)", in);
  t_true("iteration 1: auxins at least the birth distance from the root and each other", apart);
  sessile_venation_free(&v);

  /* open venation, step by step: the kill radius after every iteration */
  t_must("init", sessile_venation_init(&v, 7));
  double k2 = p.kill_radius * p.kill_radius;
  int killed_ok = 1, removed_any = 0;
  for (int it = 0; it < 50; it++) {
    t_must("step", sessile_venation_step(&v, &p, vg));
    removed_any |= v.removed > 0;
    for (uint32_t a = 0; a < v.na; a++)
      for (uint32_t j = 0; j < v.n; j++) killed_ok &= d2of(v.aux + 3 * a, v.pos + 3 * j) >= k2;
  }
  t_true("open: auxins were consumed", removed_any);
  t_true("open: after every iteration no auxin within the kill radius of a node", killed_ok);
  t_true("open: a tree: parents precede children and no extra edge (|E| = |V| - 1)", parents_precede(&v) && v.ne == 0);
  t_true("open: connected", connected(&v));
  char msg[160];
  snprintf(msg, sizeof msg, "open: the root's thickness index equals the node count (%u)", v.n);
  t_true(msg, v.ti[0] == v.n && v.n > 100);
  t_true("open: every thickness index is 1 + the node's descendants", ti_ok(&v));

  /* the GPU and host searches grow the same coral */
  sessile_venation h;
  grow(&h, &p, NULL, 7, 50);
  t_true("open: the GPU search grows the host search's graph, bit for bit", same_graph(&v, &h));
  sessile_venation_free(&h);
  grow(&h, &p, NULL, 8, 50);
  t_true("open: another seed grows another graph", !same_graph(&v, &h));
  sessile_venation_free(&h);

  /* the skeleton and its tubes */
  sessile_skeleton sk = {0};
  t_must("skeleton", sessile_venation_skeleton(&v, &p, &sk));
  t_true("skeleton: one segment per edge", sk.n == v.n - 1 + v.ne);
  double worst = 0;
  for (uint32_t s = 0; s < sk.n; s++) {
    double d[3] = {sk.b[3 * s] - sk.a[3 * s], sk.b[3 * s + 1] - sk.a[3 * s + 1], sk.b[3 * s + 2] - sk.a[3 * s + 2]};
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    worst = fmax(worst, fabs(sk.up[3 * s] * d[0] + sk.up[3 * s + 1] * d[1] + sk.up[3 * s + 2] * d[2]) / l);
  }
  t_check("skeleton: every frame's up normal to its segment (|cos|)", worst, 1e-12);
  double rmax = 0;
  for (uint32_t s = 0; s < sk.n; s++) rmax = fmax(rmax, fmax(sk.ra[s], sk.rb[s]));
  t_check("skeleton: the root's radius is thickness_3", fabs(rmax - p.thickness[3]), 1e-15);
  sessile_surface m = {0};
  t_must("tubes", sessile_skeleton_tubes(&sk, p.mesh_detail, &m, NULL));
  t_true("tubes: mesh_detail sides, each tube closed (Euler 2 per segment)",
         m.nv == sk.n * (2u * p.mesh_detail + 2) && sessile_surface_check(&m, 2 * (int)sk.n, 0) == SESSILE_OK);
  sessile_surface_free(&m);
  sessile_skeleton_free(&sk);
  sessile_venation_free(&v);

  /* closed venation: cycles, connected, thickness */
  p.open = 0;
  grow(&v, &p, vg, 3, 60);
  snprintf(msg, sizeof msg, "closed: cycles, |E| = %u >= |V| = %u", v.n - 1 + v.ne, v.n);
  t_true(msg, v.n - 1 + v.ne >= v.n);
  t_true("closed: connected, parents precede children", connected(&v) && parents_precede(&v));
  t_true("closed: the root's thickness index equals the node count", v.ti[0] == v.n);
  t_true("closed: every thickness index is 1 + the node's descendants", ti_ok(&v));
  grow(&h, &p, NULL, 3, 60);
  t_true("closed: the GPU search grows the host search's graph, bit for bit", same_graph(&v, &h));
  sessile_venation_free(&h);
  sessile_venation_free(&v);

  /* a 3-D box */
  p.open = 1, p.planar = 0;
  grow(&v, &p, vg, 4, 40);
  int off_plane = 0;
  for (uint32_t i = 0; i < v.n; i++) off_plane |= v.pos[3 * i + 1] != 0;
  t_true("3-D box: a tree that leaves the plane", off_plane && parents_precede(&v) && v.ne == 0 && v.ti[0] == v.n);
  sessile_venation_free(&v);
  p.planar = 1;

  /* the thickness curve */
  double e = 0;
  for (int k = 0; k < 4; k++) e = fmax(e, fabs(sessile_venation_radius(&p, k / 3.0) - p.thickness[k]));
  e = fmax(e, fabs(sessile_venation_radius(&p, 0.5) - 0.5 * (p.thickness[1] + p.thickness[2])));
  t_check("thickness curve: through its control points, linear between", e, 1e-15);

  /* every parameter out of range, and the cross checks */
  const sessile_param_table *t = &sessile_venation_param_table;
  int refused = 1;
  for (int i = 0; i < t->count; i++) {
    const sessile_param_desc *d = &t->params[i];
    sessile_venation_params q;
    sessile_params_defaults(t, &q);
    char bad[64];
    snprintf(bad, sizeof bad, "%.17g", d->type == SESSILE_PT_ENUM || d->type == SESSILE_PT_BOOL ? 7.0 : d->hi * 2 + 1);
    int r1 = sessile_params_set_text(t, &q, d->name, bad) == SESSILE_ERR_USAGE;
    snprintf(bad, sizeof bad, "%.17g", d->lo - 1);
    int r2 = d->type == SESSILE_PT_ENUM || d->type == SESSILE_PT_BOOL ||
             sessile_params_set_text(t, &q, d->name, bad) == SESSILE_ERR_USAGE;
    if (!(r1 && r2)) printf("  not refused: %s\n", d->name);
    refused &= r1 && r2;
  }
  t_true("every parameter refuses values above and below its range", refused);
  struct {
    const char *what, *kv[4];
  } cross[] = {
      {"an empty blade (all inner x at 0)", {"left_1x=0", "left_2x=0", "right_1x=0", "right_2x=0"}},
      {"crossed curves (left right of right)", {"left_1x=0.7", "left_2x=0.75", "right_1x=-0.7", "right_2x=-0.75"}},
      {"a falling curve", {"left_1z=0.9", "left_2z=0.1", NULL, NULL}},
      {"birth distance below the kill radius", {"birth_distance=0.1", NULL, NULL, NULL}},
      {"vein step above the kill radius", {"vein_step=0.3", NULL, NULL, NULL}},
      {"merge distance not below the vein step", {"merge_distance=0.2", NULL, NULL, NULL}},
  };
  for (size_t c = 0; c < sizeof cross / sizeof cross[0]; c++) {
    sessile_venation_params q;
    sessile_params_defaults(t, &q);
    for (int k = 0; k < 4 && cross[c].kv[k]; k++) t_must("set", sessile_params_set_kv(t, &q, cross[c].kv[k]));
    snprintf(msg, sizeof msg, "refused: %s", cross[c].what);
    t_true(msg, sessile_params_check(t, &q) == SESSILE_ERR_USAGE);
  }
  sessile_venation_gpu_destroy(vg);
  return t_finish(g);
}
