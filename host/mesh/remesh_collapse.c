/* Remesh, phase 2 (§4.6 vertex fusion, small-triangle deletion): half-edge
 * collapses, each allowed only when
 *   (a) no edge of the result is longer than insert_len (so a fusion never
 *       calls for a new split: the phases cannot oscillate),
 *   (b) the link condition holds and neither vertex opposite the edge has
 *       valence 3 (the result stays a closed 2-manifold without duplicate
 *       triangles: Dey et al.'s condition for triangulated surfaces),
 *   (c) no remaining triangle's normal turns by more than max_turn_deg and
 *       none degenerates (no fold-overs),
 *   (d) with guard_intersections, no new triangle crosses the surface
 *       (remesh_contact.c).
 * Candidates are visited shortest first; sweeps repeat, re-visiting only
 * candidates near a change (dirty 2-rings), until a sweep changes nothing.
 * Every decision depends on the mesh alone (the normals used here are
 * recomputed from it, summed in triangle order), so a second remesh of the
 * output makes exactly the same decisions and changes nothing.
 *
 * Storage while collapsing: triangles stay in place (dead ones flagged);
 * each vertex has a singly linked list of its corners (3 f + c), relabelled
 * and spliced on a collapse; dead corners are unlinked when met. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/mesh_internal.h"

#define NONE UINT32_MAX

typedef struct {
  sessile_surface *s;
  const sessile_remesh_options *o;
  uint32_t *head, *next, *mark, epoch;
  uint8_t *falive, *valive, *dirty, *ndirty;
  uint32_t *fa, *fb, *fc; /* scratch face lists, nf each */
  double *nrm;             /* cached vertex normals, valid where nok[v] */
  uint8_t *nok;
  double L2, cos_turn, deg_area;
  remesh_contact *contact; /* (d), NULL when guard_intersections is off */
} cctx;

typedef struct { uint32_t a, b; } cand;

/* Sort key: the float32 bits of a non-negative length or area (monotone as
 * an integer) above the candidate's index, which breaks ties in the order
 * the candidates were listed (triangle order: deterministic). */
static uint64_t sort_key(double x, size_t i) {
  float f = (float)x;
  uint32_t u;
  memcpy(&u, &f, sizeof u);
  return (uint64_t)u << 32 | (uint32_t)i;
}

static double dist2(const double *p, const double *q) {
  double x = p[0] - q[0], y = p[1] - q[1], z = p[2] - q[2];
  return x * x + y * y + z * z;
}

static double face_area(const sessile_surface *s, uint32_t f) {
  double c[3];
  mesh_face_cross(s->pos, s->tri + 3 * f, c);
  return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

/* Live triangles of v, ascending. */
static uint32_t gather(cctx *c, uint32_t v, uint32_t *out) {
  uint32_t n = 0, *link = &c->head[v];
  while (*link != NONE) {
    uint32_t k = *link;
    if (!c->falive[k / 3]) {
      *link = c->next[k];
      continue;
    }
    out[n++] = k / 3;
    link = &c->next[k];
  }
  for (uint32_t i = 1; i < n; i++) /* insertion sort: valences are small */
    for (uint32_t j = i; j > 0 && out[j - 1] > out[j]; j--) {
      uint32_t t = out[j];
      out[j] = out[j - 1];
      out[j - 1] = t;
    }
  return n;
}

/* Area-weighted normal of a vertex from its triangles (ascending order). */
static void vertex_normal(const sessile_surface *s, const uint32_t *faces, uint32_t n,
                          double out[3]) {
  out[0] = out[1] = out[2] = 0;
  for (uint32_t i = 0; i < n; i++) {
    double x[3];
    mesh_face_cross(s->pos, s->tri + 3 * faces[i], x);
    for (int a = 0; a < 3; a++) out[a] += x[a];
  }
  double l = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  if (l > 0) out[0] /= l, out[1] /= l, out[2] /= l;
}

static const double *cached_normal(cctx *c, uint32_t v, const uint32_t *faces, uint32_t n) {
  if (!c->nok[v]) vertex_normal(c->s, faces, n, c->nrm + 3 * v), c->nok[v] = 1;
  return c->nrm + 3 * v;
}

static int on_box_face(const sessile_remesh_options *o, const double *p) {
  for (int a = 0; a < 3; a++)
    if ((isfinite(o->clamp_lo[a]) && p[a] == o->clamp_lo[a]) ||
        (isfinite(o->clamp_hi[a]) && p[a] == o->clamp_hi[a]))
      return 1;
  return 0;
}

/* Collapses edge (a, b) into its lower-indexed end.  Returns 1 when done, 0
 * when (a, b) is no edge, -1 when a guard refuses. */
static int try_collapse(cctx *c, uint32_t a, uint32_t b) {
  sessile_surface *s = c->s;
  uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
  uint32_t na = gather(c, lo, c->fa), nb = gather(c, hi, c->fb);
  uint32_t sh[2] = {NONE, NONE}, opp[2] = {NONE, NONE}, ns = 0;
  for (uint32_t i = 0; i < nb; i++) {
    const uint32_t *t = s->tri + 3 * c->fb[i];
    if (t[0] != lo && t[1] != lo && t[2] != lo) continue;
    if (ns < 2) {
      sh[ns] = c->fb[i];
      for (int k = 0; k < 3; k++)
        if (t[k] != lo && t[k] != hi) opp[ns] = t[k];
    }
    ns++;
  }
  if (ns == 0) return 0;
  if (ns != 2 || opp[0] == opp[1]) return -1;
  const double *plo = s->pos + 3 * lo, *phi = s->pos + 3 * hi;
  /* (a), cheaply first: the merged point is within |d|/4 of the chord
   * midpoint m (|t0 - t1|/8 <= |d|/4), so a neighbour farther than
   * insert_len + |d|/4 from m refuses without computing normals.  Most
   * refusals on a grown surface end here.  (A box-face vertex kept in
   * place is |d|/2 from m.) */
  int flo = on_box_face(c->o, plo), fhi = on_box_face(c->o, phi);
  {
    double m[3], slack = (flo != fhi ? 0.5 : 0.25) * sqrt(dist2(plo, phi)) + sqrt(c->L2);
    for (int k = 0; k < 3; k++) m[k] = 0.5 * (plo[k] + phi[k]);
    for (int side = 0; side < 2; side++) {
      const uint32_t *fl = side ? c->fb : c->fa;
      uint32_t nl = side ? nb : na;
      for (uint32_t i = 0; i < nl; i++)
        for (int k = 0; k < 3; k++) {
          uint32_t w = s->tri[3 * fl[i] + k];
          if (w != lo && w != hi && dist2(m, s->pos + 3 * w) > slack * slack) return -1;
        }
    }
  }
  /* The merged position: a vertex on a box face stays where it is when its
   * partner is off the faces; otherwise the curve midpoint. */
  double p[3];
  if (flo != fhi) memcpy(p, flo ? plo : phi, sizeof p);
  else
    remesh_edge_point(plo, cached_normal(c, lo, c->fa, na), phi, cached_normal(c, hi, c->fb, nb),
                      c->o, p);
  for (int side = 0; side < 2; side++) {
    const uint32_t *fl = side ? c->fb : c->fa;
    uint32_t nl = side ? nb : na;
    for (uint32_t i = 0; i < nl; i++)
      for (int k = 0; k < 3; k++) {
        uint32_t w = s->tri[3 * fl[i] + k];
        if (w != lo && w != hi && dist2(p, s->pos + 3 * w) > c->L2) return -1;
      }
  }
  /* (b) no valence-3 pinch, then the link condition: the only common
   * neighbours of lo and hi are the two opposite vertices. */
  if (gather(c, opp[0], c->fc) <= 3 || gather(c, opp[1], c->fc) <= 3) return -1;
  uint32_t ep = ++c->epoch;
  for (uint32_t i = 0; i < na; i++)
    for (int k = 0; k < 3; k++) c->mark[s->tri[3 * c->fa[i] + k]] = ep;
  for (uint32_t i = 0; i < nb; i++)
    for (int k = 0; k < 3; k++) {
      uint32_t w = s->tri[3 * c->fb[i] + k];
      if (w != lo && w != hi && w != opp[0] && w != opp[1] && c->mark[w] == ep) return -1;
    }
  /* (c) over every triangle that survives. */
  for (int side = 0; side < 2; side++) {
    const uint32_t *fl = side ? c->fb : c->fa;
    uint32_t nl = side ? nb : na;
    for (uint32_t i = 0; i < nl; i++) {
      uint32_t f = fl[i];
      if (f == sh[0] || f == sh[1]) continue;
      const uint32_t *t = s->tri + 3 * f;
      double q[9], co[3], cn[3];
      static const uint32_t loc[3] = {0, 1, 2};
      for (int k = 0; k < 3; k++) {
        const double *src = (t[k] == lo || t[k] == hi) ? p : s->pos + 3 * t[k];
        memcpy(q + 3 * k, src, 3 * sizeof *q);
      }
      mesh_face_cross(s->pos, t, co);
      mesh_face_cross(q, loc, cn);
      double ln = sqrt(cn[0] * cn[0] + cn[1] * cn[1] + cn[2] * cn[2]);
      double lo_ = sqrt(co[0] * co[0] + co[1] * co[1] + co[2] * co[2]);
      if (!(0.5 * ln > c->deg_area)) return -1;
      if (!(cn[0] * co[0] + cn[1] * co[1] + cn[2] * co[2] >= c->cos_turn * ln * lo_)) return -1;
    }
  }
  /* (d) last, the dearest: no new triangle crosses the surface. */
  if (c->contact && remesh_contact_blocks(c->contact, s, c->falive, lo, hi, p, c->fa, na, c->fb,
                                          nb, sh))
    return -1;
  /* Commit: drop the two triangles of the edge, hand hi's corners to lo. */
  c->falive[sh[0]] = c->falive[sh[1]] = 0;
  uint32_t *tail = &c->head[lo];
  while (*tail != NONE) tail = &c->next[*tail];
  for (uint32_t k = c->head[hi]; k != NONE; k = c->next[k]) s->tri[k] = lo;
  *tail = c->head[hi];
  c->head[hi] = NONE;
  c->valive[hi] = 0;
  memcpy(s->pos + 3 * lo, p, sizeof p);
  /* Decisions within the 2-ring of lo may change: re-examine them next sweep
   * (and refusals by (d) whose fan is near the change). */
  na = gather(c, lo, c->fa);
  if (c->contact) remesh_contact_commit(c->contact, s, c->fa, na, c->ndirty);
  for (uint32_t i = 0; i < na; i++)
    for (int k = 0; k < 3; k++) {
      uint32_t w = s->tri[3 * c->fa[i] + k];
      c->nok[w] = 0; /* the normals of the closed 1-ring changed */
      uint32_t nw = gather(c, w, c->fb);
      for (uint32_t j = 0; j < nw; j++)
        for (int q = 0; q < 3; q++) c->ndirty[s->tri[3 * c->fb[j] + q]] = 1;
    }
  return 1;
}

/* One face's edges, shortest first (ties: corner order). */
static int collapse_face(cctx *c, uint32_t f) {
  const uint32_t *t = c->s->tri + 3 * f;
  double l[3];
  int ord[3] = {0, 1, 2};
  for (int e = 0; e < 3; e++) l[e] = dist2(c->s->pos + 3 * t[e], c->s->pos + 3 * t[(e + 1) % 3]);
  for (int i = 1; i < 3; i++)
    for (int j = i; j > 0 && l[ord[j - 1]] > l[ord[j]]; j--) {
      int x = ord[j];
      ord[j] = ord[j - 1];
      ord[j - 1] = x;
    }
  for (int i = 0; i < 3; i++) {
    uint32_t a = t[ord[i]], b = t[(ord[i] + 1) % 3];
    if (try_collapse(c, a, b) == 1) return 1;
  }
  return 0;
}

static sessile_status compact(cctx *c) {
  sessile_surface *s = c->s;
  uint32_t *map = malloc(((size_t)s->nv + 1) * sizeof *map);
  SESSILE_CHECK(map, SESSILE_ERR_NO_MEMORY, "out of host memory compacting the surface");
  uint32_t nv = 0, nf = 0;
  for (uint32_t v = 0; v < s->nv; v++)
    if (c->valive[v]) {
      map[v] = nv;
      memmove(s->pos + 3 * nv, s->pos + 3 * v, 3 * sizeof *s->pos);
      nv++;
    }
  for (uint32_t f = 0; f < s->nf; f++)
    if (c->falive[f]) {
      for (int k = 0; k < 3; k++) s->tri[3 * nf + k] = map[s->tri[3 * f + k]];
      nf++;
    }
  s->nv = nv;
  s->nf = nf;
  free(map);
  return SESSILE_OK;
}

sessile_status remesh_collapse(sessile_surface *s, const sessile_remesh_options *o,
                               sessile_remesh_stats *st) {
  cctx c = {.s = s, .o = o};
  remesh_contact contact;
  memset(&contact, 0, sizeof contact);
  c.L2 = o->insert_len * o->insert_len;
  c.cos_turn = cos(o->max_turn_deg * acos(-1.0) / 180.0);
  /* "Degenerate": far below any area the thresholds care about. */
  c.deg_area = 1e-6 * o->insert_len * o->insert_len;
  size_t nv = s->nv, nf = s->nf, nc = 3 * nf;
  c.head = malloc((nv + 1) * sizeof *c.head);
  c.next = malloc((nc + 1) * sizeof *c.next);
  c.mark = calloc(nv + 1, sizeof *c.mark);
  c.falive = malloc(nf + 1);
  c.valive = malloc(nv + 1);
  c.dirty = malloc(nv + 1);
  c.ndirty = calloc(nv + 1, 1);
  c.fa = malloc((nf + 1) * sizeof *c.fa);
  c.fb = malloc((nf + 1) * sizeof *c.fb);
  c.fc = malloc((nf + 1) * sizeof *c.fc);
  c.nrm = malloc((nv + 1) * 3 * sizeof *c.nrm);
  c.nok = calloc(nv + 1, 1);
  cand *ec = malloc((nc + 1) * sizeof *ec), *fcand = malloc((nf + 1) * sizeof *fcand);
  uint64_t *ekey = malloc((nc + 1) * sizeof *ekey), *fkey = malloc((nf + 1) * sizeof *fkey);
  uint64_t *ktmp = malloc((nc + 1) * sizeof *ktmp);
  sessile_status r = SESSILE_OK;
  if (!c.head || !c.next || !c.mark || !c.falive || !c.valive || !c.dirty || !c.ndirty || !c.fa ||
      !c.fb || !c.fc || !c.nrm || !c.nok || !ec || !ekey || !fkey || !ktmp || !fcand) {
    r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory remeshing %zu triangles", nf);
    goto done;
  }
  if (o->guard_intersections) {
    if ((r = remesh_contact_begin(&contact, s)) != SESSILE_OK) goto done;
    c.contact = &contact;
  }
  memset(c.falive, 1, nf);
  memset(c.valive, 1, nv);
  memset(c.dirty, 1, nv);
  for (size_t v = 0; v < nv; v++) c.head[v] = NONE;
  for (size_t k = nc; k-- > 0;) { /* lists in ascending corner order */
    c.next[k] = c.head[s->tri[k]];
    c.head[s->tri[k]] = (uint32_t)k;
  }
  const double F2 = o->fuse_len * o->fuse_len;
  for (;;) {
    size_t ne = 0, nfc = 0;
    for (uint32_t f = 0; f < nf; f++) {
      if (!c.falive[f]) continue;
      const uint32_t *t = s->tri + 3 * f;
      int dirty = c.dirty[t[0]] | c.dirty[t[1]] | c.dirty[t[2]];
      if (!dirty) continue;
      for (int e = 0; e < 3; e++) {
        uint32_t a = t[e], b = t[(e + 1) % 3];
        double l2 = dist2(s->pos + 3 * a, s->pos + 3 * b);
        if (a < b && (c.dirty[a] | c.dirty[b]) && l2 < F2) {
          ekey[ne] = sort_key(l2, ne);
          ec[ne++] = (cand){a, b};
        }
      }
      double ar = face_area(s, f);
      if (ar < o->min_area) {
        fkey[nfc] = sort_key(ar, nfc);
        fcand[nfc++] = (cand){f, 0};
      }
    }
    mesh_sort_u64(ekey, ktmp, ne);
    mesh_sort_u64(fkey, ktmp, nfc);
    memset(c.ndirty, 0, nv);
    int changed = 0;
    for (size_t i = 0; i < ne; i++) {
      uint32_t a = ec[(uint32_t)ekey[i]].a, b = ec[(uint32_t)ekey[i]].b;
      if (!c.valive[a] || !c.valive[b] || dist2(s->pos + 3 * a, s->pos + 3 * b) >= F2) continue;
      if (try_collapse(&c, a, b) == 1) st->fusions++, changed = 1;
    }
    for (size_t i = 0; i < nfc; i++) {
      uint32_t f = fcand[(uint32_t)fkey[i]].a;
      if (!c.falive[f] || face_area(s, f) >= o->min_area) continue;
      if (collapse_face(&c, f)) st->area_collapses++, changed = 1;
    }
    uint8_t *t = c.dirty;
    c.dirty = c.ndirty;
    c.ndirty = t;
    if (contact.failed) {
      r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the contact guard of "
                            "%zu triangles", nf);
      goto done;
    }
    if (!changed) break;
  }
  st->contact_refusals = contact.refusals;
  /* What is left below the thresholds was refused by a guard. */
  for (uint32_t f = 0; f < nf; f++) {
    if (!c.falive[f]) continue;
    const uint32_t *t = s->tri + 3 * f;
    for (int e = 0; e < 3; e++)
      if (t[e] < t[(e + 1) % 3] && dist2(s->pos + 3 * t[e], s->pos + 3 * t[(e + 1) % 3]) < F2)
        st->rejected++;
    if (face_area(s, f) < o->min_area) st->rejected++;
  }
  r = compact(&c);
done:
  remesh_contact_end(&contact);
  free(c.head), free(c.next), free(c.mark), free(c.falive), free(c.valive), free(c.dirty);
  free(c.ndirty), free(c.fa), free(c.fb), free(c.fc), free(c.nrm), free(c.nok), free(ec), free(fcand);
  free(ekey), free(fkey), free(ktmp);
  return r;
}
