/* Self-intersection of a triangle surface: a bounding-volume hierarchy over
 * the triangles and the pairs it finds (sessile/mesh/intersect.h).
 *
 * Build: top down, each node's triangles split at the median of their
 * centroids along the longest axis of the centroids' box, ties broken by the
 * triangle index (a total order, so quickselect gives the same tree whatever
 * its pivots do); leaves of at most 4.  Query: the tree against itself
 * (pairs of nodes whose boxes overlap, so every triangle pair is met once);
 * pairs are normalised to f < g and radix-sorted, so the list does not
 * depend on visiting order. */
#include <stdlib.h>
#include <string.h>
#include "mesh/intersect_internal.h"
#include "mesh/mesh_internal.h"

#define LEAF 4

/* A triangle while building: its centroid beside its index, so the
 * partitions move contiguous data. */
typedef struct {
  double c[3];
  uint32_t id, pad;
} item;

/* Order of triangles by (centroid on axis, index). */
static int before(const item *a, const item *b, int ax) {
  return a->c[ax] < b->c[ax] || (a->c[ax] == b->c[ax] && a->id < b->id);
}

/* Rearranges it[0..n) so it[k] is the k-th in that order, with the smaller
 * ones before it and the larger after (Hoare, median-of-3 pivot). */
static void select_kth(item *it, uint32_t n, uint32_t k, int ax) {
  uint32_t lo = 0, hi = n - 1;
  while (hi > lo) {
    const item *a = &it[lo], *b = &it[lo + (hi - lo) / 2], *c = &it[hi];
    item pv = before(a, b, ax) ? (before(b, c, ax) ? *b : before(a, c, ax) ? *c : *a)
                               : (before(a, c, ax) ? *a : before(b, c, ax) ? *c : *b);
    uint32_t i = lo, j = hi;
    while (i <= j) {
      while (before(&it[i], &pv, ax)) i++;
      while (before(&pv, &it[j], ax)) j--;
      if (i <= j) {
        item t = it[i];
        it[i] = it[j], it[j] = t;
        i++;
        if (j == 0) break;
        j--;
      }
    }
    if (k <= j && j < hi) hi = j;
    else if (k >= i) lo = i;
    else break;
  }
}

/* Top down: the split; leaves get their boxes here, inner nodes after. */
static void build(isect_bvh *b, uint32_t n, item *it, uint32_t first, uint32_t count) {
  isect_node *nd = &b->node[n];
  if (count <= LEAF) {
    nd->first = first, nd->count = count;
    for (int k = 0; k < 3; k++) nd->box[k] = 1e300, nd->box[3 + k] = -1e300;
    for (uint32_t i = first; i < first + count; i++) {
      const double *bx = b->box + 6 * it[i].id;
      for (int k = 0; k < 3; k++) {
        if (bx[k] < nd->box[k]) nd->box[k] = bx[k];
        if (bx[3 + k] > nd->box[3 + k]) nd->box[3 + k] = bx[3 + k];
      }
    }
    return;
  }
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (uint32_t i = first; i < first + count; i++)
    for (int k = 0; k < 3; k++) {
      if (it[i].c[k] < lo[k]) lo[k] = it[i].c[k];
      if (it[i].c[k] > hi[k]) hi[k] = it[i].c[k];
    }
  int ax = 0;
  for (int k = 1; k < 3; k++)
    if (hi[k] - lo[k] > hi[ax] - lo[ax]) ax = k;
  uint32_t half = count / 2, child = b->nnode;
  select_kth(it + first, count, half, ax);
  b->nnode += 2;
  nd->first = child, nd->count = 0;
  build(b, child, it, first, half);
  build(b, child + 1, it, first + half, count - half);
}

void isect_bvh_free(isect_bvh *b) {
  free(b->node), free(b->order), free(b->box);
  memset(b, 0, sizeof *b);
}

sessile_status isect_bvh_build(isect_bvh *b, const uint32_t *tri, uint32_t nf, const double *pos) {
  memset(b, 0, sizeof *b);
  b->node = malloc(((size_t)nf * 2 + 1) * sizeof *b->node);
  b->order = malloc(((size_t)nf + 1) * sizeof *b->order);
  b->box = malloc(((size_t)nf * 6 + 1) * sizeof *b->box);
  item *it = malloc(((size_t)nf + 1) * sizeof *it);
  if (!b->node || !b->order || !b->box || !it) {
    free(it);
    isect_bvh_free(b);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the triangle "
                             "hierarchy of %u triangles", nf);
  }
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *t = tri + 3 * f;
    isect_tri_box(pos, t, b->box + 6 * f);
    for (int k = 0; k < 3; k++)
      it[f].c[k] = (pos[3 * t[0] + k] + pos[3 * t[1] + k] + pos[3 * t[2] + k]) / 3.0;
    it[f].id = f, it[f].pad = 0;
  }
  b->nnode = 1;
  if (nf) build(b, 0, it, 0, nf);
  for (uint32_t f = 0; f < nf; f++) b->order[f] = it[f].id;
  free(it);
  /* Inner boxes bottom up: children come after their parent. */
  for (uint32_t n = b->nnode; n-- > 0;) {
    isect_node *nd = &b->node[n];
    if (nd->count || !nf) continue;
    const double *l = b->node[nd->first].box, *r = b->node[nd->first + 1].box;
    for (int k = 0; k < 3; k++) {
      nd->box[k] = l[k] < r[k] ? l[k] : r[k];
      nd->box[3 + k] = l[3 + k] > r[3 + k] ? l[3 + k] : r[3 + k];
    }
  }
  return SESSILE_OK;
}

static sessile_status push_pair(isect_pairs *o, uint32_t f, uint32_t g) {
  if (o->n == o->cap) {
    size_t cap = o->cap ? 2 * o->cap : 256;
    uint32_t *p = realloc(o->p, cap * 2 * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for %zu intersecting pairs", cap);
    o->p = p, o->cap = cap;
  }
  o->p[2 * o->n] = f < g ? f : g;
  o->p[2 * o->n + 1] = f < g ? g : f;
  o->n++;
  return SESSILE_OK;
}

static void corners(const double *pos, const uint32_t *t, double out[9]) {
  for (int i = 0; i < 3; i++) memcpy(out + 3 * i, pos + 3 * t[i], 3 * sizeof *out);
}

/* The pairs of two leaves (the same leaf: each pair once). */
static sessile_status leaf_pairs(const isect_bvh *b, const isect_node *x, const isect_node *y,
                                 const uint32_t *tri, const double *pos, const uint8_t *active,
                                 isect_pairs *out) {
  for (uint32_t i = x->first; i < x->first + x->count; i++) {
    uint32_t f = b->order[i];
    double pf[9], pg[9];
    int loaded = 0;
    for (uint32_t j = x == y ? i + 1 : y->first; j < y->first + y->count; j++) {
      uint32_t g = b->order[j];
      if (active && !active[f] && !active[g]) continue;
      if (!isect_box_overlap(b->box + 6 * f, b->box + 6 * g)) continue;
      if (!loaded) corners(pos, tri + 3 * f, pf), loaded = 1;
      corners(pos, tri + 3 * g, pg);
      if (isect_tri_tri(pf, tri + 3 * f, pg, tri + 3 * g)) SESSILE_CALL(push_pair(out, f, g));
    }
  }
  return SESSILE_OK;
}

static double extent(const double *box) {
  double e = box[3] - box[0];
  if (box[4] - box[1] > e) e = box[4] - box[1];
  if (box[5] - box[2] > e) e = box[5] - box[2];
  return e;
}

/* The hierarchy against itself: node pairs whose boxes overlap, from
 * (root, root) down; a pair is opened on its larger node.  Subtrees without
 * an active triangle are skipped. */
static sessile_status self_walk(const isect_bvh *b, const uint32_t *tri, const double *pos,
                                const uint8_t *active, const uint8_t *live, isect_pairs *out) {
  size_t cap = 256, sp = 0;
  uint32_t *st = malloc(cap * 2 * sizeof *st);
  SESSILE_CHECK(st, SESSILE_ERR_NO_MEMORY, "out of host memory walking the triangle hierarchy");
  sessile_status r = SESSILE_OK;
  st[sp * 2] = st[sp * 2 + 1] = 0, sp++;
  while (sp && r == SESSILE_OK) {
    sp--;
    uint32_t x = st[2 * sp], y = st[2 * sp + 1];
    const isect_node *nx = &b->node[x], *ny = &b->node[y];
    if (live && !live[x] && !live[y]) continue;
    if (x != y && !isect_box_overlap(nx->box, ny->box)) continue;
    if (nx->count && ny->count) {
      r = leaf_pairs(b, nx, ny, tri, pos, active, out);
      continue;
    }
    if (sp + 3 > cap) {
      uint32_t *t = realloc(st, cap * 4 * sizeof *t);
      if (!t) {
        r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory walking the hierarchy");
        break;
      }
      st = t, cap *= 2;
    }
    if (x == y) { /* an inner node against itself: its children, each and both */
      uint32_t l = nx->first;
      st[2 * sp] = l, st[2 * sp + 1] = l + 1, sp++;
      st[2 * sp] = l + 1, st[2 * sp + 1] = l + 1, sp++;
      st[2 * sp] = l, st[2 * sp + 1] = l, sp++;
    } else if (ny->count || (!nx->count && extent(nx->box) >= extent(ny->box))) {
      st[2 * sp] = nx->first + 1, st[2 * sp + 1] = y, sp++;
      st[2 * sp] = nx->first, st[2 * sp + 1] = y, sp++;
    } else {
      st[2 * sp] = x, st[2 * sp + 1] = ny->first + 1, sp++;
      st[2 * sp] = x, st[2 * sp + 1] = ny->first, sp++;
    }
  }
  free(st);
  return r;
}

sessile_status isect_self_pairs(const uint32_t *tri, uint32_t nf, const double *pos,
                                const uint8_t *active, isect_pairs *out) {
  out->n = 0;
  if (nf < 2) return SESSILE_OK;
  isect_bvh b;
  SESSILE_CALL(isect_bvh_build(&b, tri, nf, pos));
  /* live: the subtree holds an active triangle (bottom up). */
  uint8_t *live = NULL;
  sessile_status r = SESSILE_OK;
  if (active) {
    live = malloc(b.nnode);
    if (!live) r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u nodes", b.nnode);
    for (uint32_t n = b.nnode; live && n-- > 0;) {
      const isect_node *nd = &b.node[n];
      live[n] = 0;
      if (nd->count)
        for (uint32_t i = nd->first; i < nd->first + nd->count; i++) live[n] |= active[b.order[i]];
      else live[n] = live[nd->first] | live[nd->first + 1];
    }
  }
  if (r == SESSILE_OK) r = self_walk(&b, tri, pos, active, live, out);
  free(live);
  isect_bvh_free(&b);
  if (r != SESSILE_OK || out->n < 2) return r;
  uint64_t *key = malloc(out->n * 2 * sizeof *key);
  SESSILE_CHECK(key, SESSILE_ERR_NO_MEMORY, "out of host memory sorting %zu pairs", out->n);
  for (size_t i = 0; i < out->n; i++) key[i] = (uint64_t)out->p[2 * i] << 32 | out->p[2 * i + 1];
  mesh_sort_u64(key, key + out->n, out->n);
  for (size_t i = 0; i < out->n; i++) {
    out->p[2 * i] = (uint32_t)(key[i] >> 32);
    out->p[2 * i + 1] = (uint32_t)key[i];
  }
  free(key);
  return SESSILE_OK;
}

sessile_status sessile_surface_self_intersections(const sessile_surface *s, uint32_t max_pairs,
                                                  uint32_t *pairs, uint64_t *count) {
  SESSILE_CHECK(s && count, SESSILE_ERR_USAGE, "self-intersections: no surface or count given");
  for (size_t k = 0; k < (size_t)s->nf * 3; k++)
    SESSILE_CHECK(s->tri[k] < s->nv, SESSILE_ERR_USAGE,
                  "self-intersections: triangle %zu refers to vertex %u of %u", k / 3, s->tri[k],
                  s->nv);
  isect_pairs p = {0};
  sessile_status r = isect_self_pairs(s->tri, s->nf, s->pos, NULL, &p);
  *count = r == SESSILE_OK ? p.n : 0;
  if (r == SESSILE_OK && pairs && p.n) /* p.p is NULL when there are none */
    memcpy(pairs, p.p, (p.n < max_pairs ? p.n : max_pairs) * 2 * sizeof *pairs);
  free(p.p);
  return r;
}
