/* One venation iteration (Runions et al. 2005, Coralize §3.2; the equations
 * are in docs/venation.md): dart-thrown auxins, each auxin's attracted vein
 * nodes (the nearest node: open; the relative neighbourhood: closed), growth
 * of every attracted node by vein_step along the normalised sum of the unit
 * directions to its auxins, and the removal of consumed auxins.  All in node
 * and auxin index order, so the result depends on the seed alone. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/rng.h"
#include "venation_internal.h"

sessile_status sessile_venation_init(sessile_venation *v, uint64_t seed) {
  memset(v, 0, sizeof *v);
  v->cap = 1024, v->acap = 1024, v->ecap = 64;
  v->pos = malloc((size_t)3 * v->cap * sizeof *v->pos);
  v->parent = malloc((size_t)v->cap * sizeof *v->parent);
  v->ti = malloc((size_t)v->cap * sizeof *v->ti);
  v->aux = malloc((size_t)3 * v->acap * sizeof *v->aux);
  v->edge = malloc((size_t)2 * v->ecap * sizeof *v->edge);
  if (!v->pos || !v->parent || !v->ti || !v->aux || !v->edge) {
    sessile_venation_free(v);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the vein graph");
  }
  v->n = 1; /* the root (seed) at the origin */
  v->pos[0] = v->pos[1] = v->pos[2] = 0;
  v->parent[0] = SESSILE_VENATION_NONE;
  v->ti[0] = 1;
  v->rng = sessile_rng_stream(seed, 0x76656e6174696f6eull); /* "venation" */
  return SESSILE_OK;
}

void sessile_venation_free(sessile_venation *v) {
  if (!v) return;
  free(v->pos);
  free(v->parent);
  free(v->ti);
  free(v->aux);
  free(v->edge);
  memset(v, 0, sizeof *v);
}

/* Nodes are capped so that a run cannot eat the machine (about 60 bytes per
 * node in the graph, its grid and the GPU buffers). */
#define MAX_NODES 20000000u

static sessile_status add_node(sessile_venation *v, const double q[3], uint32_t parent) {
  SESSILE_CHECK(v->n < MAX_NODES, SESSILE_ERR_TOO_LARGE,
                "the vein graph reached %u nodes (about %.1f GB with its grid and buffers): fewer iterations or "
                "auxins", v->n, v->n * 60e-9);
  if (v->n == v->cap) {
    uint32_t nc = 2 * v->cap;
    double *pos = realloc(v->pos, (size_t)3 * nc * sizeof *pos);
    if (pos) v->pos = pos;
    uint32_t *par = pos ? realloc(v->parent, (size_t)nc * sizeof *par) : NULL;
    if (par) v->parent = par;
    uint32_t *ti = par ? realloc(v->ti, (size_t)nc * sizeof *ti) : NULL;
    SESSILE_CHECK(ti, SESSILE_ERR_NO_MEMORY, "out of host memory for %u vein nodes", nc);
    v->ti = ti, v->cap = nc;
  }
  uint32_t i = v->n++;
  memcpy(v->pos + 3 * i, q, 3 * sizeof *q);
  v->parent[i] = parent;
  v->ti[i] = 1;
  /* Coralize §3.2: a new node adds 1 to the thickness index of every ancestor */
  for (uint32_t a = parent; a != SESSILE_VENATION_NONE; a = v->parent[a]) v->ti[a]++;
  return SESSILE_OK;
}

static int has_edge(const sessile_venation *v, uint32_t a, uint32_t b) {
  if (v->parent[a] == b || v->parent[b] == a) return 1;
  for (uint32_t e = 0; e < v->ne; e++)
    if ((v->edge[2 * e] == a && v->edge[2 * e + 1] == b) || (v->edge[2 * e] == b && v->edge[2 * e + 1] == a))
      return 1;
  return 0;
}

static sessile_status add_edge(sessile_venation *v, uint32_t a, uint32_t b) {
  if (a == b || has_edge(v, a, b)) return SESSILE_OK;
  if (v->ne == v->ecap) {
    uint32_t *e = realloc(v->edge, (size_t)4 * v->ecap * sizeof *e);
    SESSILE_CHECK(e, SESSILE_ERR_NO_MEMORY, "out of host memory for vein edges");
    v->edge = e, v->ecap *= 2;
  }
  v->edge[2 * v->ne] = a, v->edge[2 * v->ne + 1] = b;
  v->ne++;
  return SESSILE_OK;
}

static sessile_status add_aux(sessile_venation *v, const double q[3]) {
  if (v->na == v->acap) {
    double *a = realloc(v->aux, (size_t)6 * v->acap * sizeof *a);
    SESSILE_CHECK(a, SESSILE_ERR_NO_MEMORY, "out of host memory for %u auxins", 2 * v->acap);
    v->aux = a, v->acap *= 2;
  }
  memcpy(v->aux + 3 * v->na++, q, 3 * sizeof *q);
  return SESSILE_OK;
}

static inline double d2of(const double *a, const double *b) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

/* Runions' dart throwing: candidates closer than the birth distance to a vein
 * node or to an auxin (those placed before them included) are dropped. */
static sessile_status place_auxins(sessile_venation *v, const sessile_venation_params *p, double w,
                                   const sessile_venation_grid *g) {
  double b2 = p->birth_distance * p->birth_distance;
  v->placed = 0;
  for (int k = 0; k < p->auxins_per_iteration; k++) {
    double q[3], d2;
    uint32_t j;
    if (!venation_blade_sample(p, w, &v->rng, q)) continue;
    sessile_venation_nearest_grid(g, v->pos, q, 1, &j, &d2);
    if (d2 < b2) continue;
    int near = 0;
    for (uint32_t a = 0; a < v->na && !near; a++) near = d2of(q, v->aux + 3 * a) < b2;
    if (near) continue;
    SESSILE_CALL(add_aux(v, q));
    v->placed++;
  }
  return SESSILE_OK;
}

typedef struct cand {
  double d2;
  uint32_t j;
} cand;
static int cand_cmp(const void *x, const void *y) {
  const cand *a = x, *b = y;
  return a->d2 < b->d2 ? -1 : a->d2 > b->d2 ? 1 : a->j < b->j ? -1 : a->j > b->j;
}

/* Runions §4: v is in the relative neighbourhood of auxin s when no other node
 * u is closer to both s and v than they are to each other.  Candidates: the
 * nodes within influence_radius of s and the nearest node (always a member),
 * sorted by squared distance to s then index; only the entries before v can
 * block it.  All auxins' lists go into one flat array (coff: each auxin's
 * first entry) so the quadratic test can run on the GPU. */
static sessile_status rn_candidates(const sessile_venation *v, const sessile_venation_params *p,
                                    const sessile_venation_grid *g, const uint32_t *nearest, uint32_t **list,
                                    uint32_t *lcap, cand **cs, size_t *ccap, uint32_t *coff) {
  coff[0] = 0;
  for (uint32_t a = 0; a < v->na; a++) {
    const double *s = v->aux + 3 * a;
    uint32_t n = 0;
    SESSILE_CALL(venation_grid_within(g, v->pos, s, p->influence_radius, list, &n, lcap));
    size_t need = (size_t)coff[a] + n + 1;
    SESSILE_CHECK(need < 0xFFFFFFF0u, SESSILE_ERR_TOO_LARGE,
                  "closed venation: %zu relative-neighbourhood candidates (influence_radius too large)", need);
    if (*ccap < need) {
      size_t nc = 2 * need;
      cand *c = realloc(*cs, nc * sizeof *c);
      SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory for %zu candidates", nc);
      *cs = c, *ccap = nc;
    }
    cand *c = *cs + coff[a];
    uint32_t m = 0;
    int have_nearest = 0;
    for (uint32_t k = 0; k < n; k++) {
      uint32_t j = (*list)[k];
      have_nearest |= j == nearest[a];
      c[m++] = (cand){d2of(s, v->pos + 3 * j), j};
    }
    if (!have_nearest) c[m++] = (cand){d2of(s, v->pos + 3 * nearest[a]), nearest[a]};
    qsort(c, m, sizeof *c, cand_cmp);
    coff[a + 1] = coff[a] + m;
  }
  return SESSILE_OK;
}

/* The blocked flags of entries [b, e) (one auxin's list). */
static void rn_blocked_host(const sessile_venation *v, const cand *c, uint32_t b, uint32_t e, uint32_t *blk) {
  for (uint32_t k = b; k < e; k++) {
    const double *pv = v->pos + 3 * c[k].j;
    uint32_t hit = 0;
    for (uint32_t u = b; u < k && !hit; u++) hit = c[u].d2 < c[k].d2 && d2of(v->pos + 3 * c[u].j, pv) < c[k].d2;
    blk[k] = hit;
  }
}

/* Every auxin's blocked flags: on the GPU (lists of at most RN_MAX_CAND
 * entries) or the host. */
static sessile_status rn_blocked(const sessile_venation *v, sessile_venation_gpu *vg, const cand *c,
                                 const uint32_t *coff, uint32_t *blk) {
  uint32_t total = coff[v->na];
  if (!vg) {
    for (uint32_t a = 0; a < v->na; a++) rn_blocked_host(v, c, coff[a], coff[a + 1], blk);
    return SESSILE_OK;
  }
  uint32_t *j = malloc((size_t)total * sizeof *j), *start = malloc((size_t)total * sizeof *start);
  double *d2 = malloc((size_t)total * sizeof *d2);
  sessile_status s = j && start && d2 ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  for (uint32_t a = 0; a < v->na && s == SESSILE_OK; a++) {
    int host = coff[a + 1] - coff[a] > SESSILE_VENATION_RN_MAX_CAND;
    for (uint32_t k = coff[a]; k < coff[a + 1]; k++)
      j[k] = c[k].j, d2[k] = c[k].d2, start[k] = host ? SESSILE_VENATION_NONE : coff[a];
  }
  if (s == SESSILE_OK) s = sessile_venation_gpu_rn(vg, v->pos, v->n, j, d2, start, total, blk);
  for (uint32_t a = 0; a < v->na && s == SESSILE_OK; a++)
    if (coff[a + 1] - coff[a] > SESSILE_VENATION_RN_MAX_CAND) rn_blocked_host(v, c, coff[a], coff[a + 1], blk);
  free(j), free(start), free(d2);
  return s;
}

typedef struct work {
  uint32_t *near, *cnt, *list, lcap, *rn, rncap, *rnoff, *coff, *blk;
  size_t ccap;
  double *d2, *dir;
  cand *cs;
  unsigned char *dead;
} work;

static void work_free(work *w) {
  free(w->near), free(w->cnt), free(w->list), free(w->rn), free(w->rnoff), free(w->coff), free(w->blk);
  free(w->d2), free(w->dir), free(w->cs), free(w->dead);
}

/* Adds the unit direction from node j to auxin s into dir[j]. */
static void pull(const sessile_venation *v, work *w, uint32_t j, const double *s) {
  const double *pj = v->pos + 3 * j;
  double d[3] = {s[0] - pj[0], s[1] - pj[1], s[2] - pj[2]};
  double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (len <= 0) return;
  for (int a = 0; a < 3; a++) w->dir[3 * j + a] += d[a] / len;
  w->cnt[j]++;
}

/* Closed venation: the relative neighbourhood of every auxin; an auxin whose
 * every member arrived (within kill_radius) is consumed and its members are
 * joined at a node placed on it (the veins meet: a cycle when two or more);
 * otherwise it pulls each member that has not arrived. */
static sessile_status closed_pulls(sessile_venation *v, const sessile_venation_params *p,
                                   const sessile_venation_grid *g, sessile_venation_gpu *vg, work *w) {
  double k2 = p->kill_radius * p->kill_radius;
  uint32_t na = v->na;
  w->coff = malloc(((size_t)na + 1) * sizeof *w->coff);
  SESSILE_CHECK(w->coff, SESSILE_ERR_NO_MEMORY, "out of host memory");
  SESSILE_CALL(rn_candidates(v, p, g, w->near, &w->list, &w->lcap, &w->cs, &w->ccap, w->coff));
  w->blk = malloc(((size_t)w->coff[na] + 1) * sizeof *w->blk);
  SESSILE_CHECK(w->blk, SESSILE_ERR_NO_MEMORY, "out of host memory");
  SESSILE_CALL(rn_blocked(v, vg, w->cs, w->coff, w->blk));
  for (uint32_t s = 0; s < na; s++) {
    const double *ps = v->aux + 3 * s;
    /* the members, in the list's order, compacted in place */
    cand *c = w->cs + w->coff[s];
    uint32_t m = 0;
    for (uint32_t k = w->coff[s]; k < w->coff[s + 1]; k++)
      if (!w->blk[k]) c[m++] = w->cs[k];
    int arrived = 1;
    for (uint32_t k = 0; k < m; k++) arrived &= c[k].d2 < k2;
    if (arrived) {
      w->dead[s] = 1;
      if (m >= 2) {
        /* remember the members: joined after growth, in auxin order */
        if (w->rnoff[s] + m > w->rncap) {
          uint32_t nc = 2 * (w->rncap + m);
          uint32_t *r = realloc(w->rn, (size_t)nc * sizeof *r);
          SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory");
          w->rn = r, w->rncap = nc;
        }
        for (uint32_t k = 0; k < m; k++) w->rn[w->rnoff[s] + k] = c[k].j;
        w->rnoff[s + 1] = w->rnoff[s] + m;
        continue;
      }
    } else {
      for (uint32_t k = 0; k < m; k++)
        if (c[k].d2 >= k2) pull(v, w, c[k].j, ps);
    }
    w->rnoff[s + 1] = w->rnoff[s];
  }
  return SESSILE_OK;
}

/* Grows every pulled node (ascending index) by vein_step along its normalised
 * direction.  Closed: a new node within merge_distance of a node other than
 * its parent joins that node instead (a cycle). */
static sessile_status grow(sessile_venation *v, const sessile_venation_params *p, const sessile_venation_grid *g,
                           work *w, uint32_t n0) {
  double m2 = p->merge_distance * p->merge_distance;
  v->grown = v->merged = 0;
  for (uint32_t j = 0; j < n0; j++) {
    if (!w->cnt[j]) continue;
    double *d = w->dir + 3 * j, len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len < 1e-9) continue; /* pulls that cancel: no direction */
    double q[3];
    for (int a = 0; a < 3; a++) q[a] = v->pos[3 * j + a] + p->vein_step * d[a] / len;
    if (!p->open && m2 > 0) {
      uint32_t hit = SESSILE_VENATION_NONE, n = 0;
      double best = m2;
      SESSILE_CALL(venation_grid_within(g, v->pos, q, p->merge_distance, &w->list, &n, &w->lcap));
      for (uint32_t k = 0; k < n; k++) {
        uint32_t u = w->list[k];
        double dd = d2of(q, v->pos + 3 * u);
        if (u != j && (dd < best || (dd == best && u < hit))) best = dd, hit = u;
      }
      for (uint32_t u = n0; u < v->n; u++) { /* this iteration's new nodes */
        double dd = d2of(q, v->pos + 3 * u);
        if (dd < best || (dd == best && u < hit)) best = dd, hit = u;
      }
      if (hit != SESSILE_VENATION_NONE) {
        if (!has_edge(v, j, hit)) {
          SESSILE_CALL(add_edge(v, j, hit));
          v->merged++;
        }
        continue;
      }
    }
    SESSILE_CALL(add_node(v, q, j));
    v->grown++;
  }
  return SESSILE_OK;
}

/* Closed: the members of each consumed auxin meet at a node placed on it: its
 * parent is the first member (lowest index), the others join it by edges. */
static sessile_status join_consumed(sessile_venation *v, const work *w, uint32_t na) {
  for (uint32_t s = 0; s < na; s++) {
    uint32_t b = w->rnoff[s], e = w->rnoff[s + 1];
    if (e - b < 2) continue;
    uint32_t first = w->rn[b];
    for (uint32_t k = b + 1; k < e; k++) first = w->rn[k] < first ? w->rn[k] : first;
    SESSILE_CALL(add_node(v, v->aux + 3 * s, first));
    uint32_t c = v->n - 1;
    for (uint32_t k = b; k < e; k++)
      if (w->rn[k] != first) SESSILE_CALL(add_edge(v, w->rn[k], c));
    v->merged++;
  }
  return SESSILE_OK;
}

static sessile_status step(sessile_venation *v, const sessile_venation_params *p, sessile_venation_gpu *vg,
                           work *w) {
  int it = v->iteration + 1;
  double width = sessile_venation_width(p, it);
  sessile_venation_grid g;
  SESSILE_CALL(sessile_venation_grid_build(v->pos, v->n, &g));
  sessile_status s = place_auxins(v, p, width, &g);
  uint32_t na = v->na, n0 = v->n;
  if (s == SESSILE_OK && na) {
    w->near = malloc((size_t)na * sizeof *w->near);
    w->d2 = malloc((size_t)na * sizeof *w->d2);
    w->dead = calloc(na, 1);
    w->rnoff = calloc((size_t)na + 1, sizeof *w->rnoff);
    w->cnt = calloc(n0, sizeof *w->cnt);
    w->dir = calloc((size_t)3 * n0, sizeof *w->dir);
    if (!w->near || !w->d2 || !w->dead || !w->rnoff || !w->cnt || !w->dir)
      s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u auxins", na);
  }
  /* the O(auxins x nodes) step: each auxin's nearest vein node */
  if (s == SESSILE_OK && na) {
    if (vg) s = sessile_venation_gpu_nearest(vg, &g, v->pos, v->aux, na, w->near, w->d2, NULL);
    else sessile_venation_nearest_grid(&g, v->pos, v->aux, na, w->near, w->d2);
  }
  if (s == SESSILE_OK && na) {
    if (p->open)
      for (uint32_t a = 0; a < na; a++) pull(v, w, w->near[a], v->aux + 3 * a);
    else s = closed_pulls(v, p, &g, vg, w);
  }
  if (s == SESSILE_OK && na) s = grow(v, p, &g, w, n0);
  if (s == SESSILE_OK && na && !p->open) s = join_consumed(v, w, na);
  /* open: auxins within the kill radius of any node (old: their nearest; new:
   * each one) are consumed */
  if (s == SESSILE_OK && na && p->open) {
    double k2 = p->kill_radius * p->kill_radius;
    for (uint32_t a = 0; a < na; a++) {
      int dead = w->d2[a] < k2;
      for (uint32_t u = n0; u < v->n && !dead; u++) dead = d2of(v->aux + 3 * a, v->pos + 3 * u) < k2;
      w->dead[a] = (unsigned char)dead;
    }
  }
  if (s == SESSILE_OK) {
    uint32_t keep = 0;
    for (uint32_t a = 0; a < na; a++)
      if (!w->dead[a]) memmove(v->aux + 3 * keep++, v->aux + 3 * a, 3 * sizeof *v->aux);
    v->removed = na - keep;
    v->na = keep;
    v->iteration = it;
  }
  sessile_venation_grid_free(&g);
  return s;
}

sessile_status sessile_venation_step(sessile_venation *v, const sessile_venation_params *p,
                                     sessile_venation_gpu *vg) {
  work w = {0};
  sessile_status s = step(v, p, vg, &w);
  work_free(&w);
  return s;
}
