/* Contacts (docs/sds.md, "Collisions"): the spatial hash of Teschner et al.
 * 2003 on the host (the obstacle's table, uploaded once; the host reference's
 * queries), the brute-force reference over all triangles, and the penalty of
 * a cell against its nearest triangle.  The GPU's mirror is
 * shaders/sds/sds_contact.glsl and gather.comp; operations are written in the
 * same order so that fp64 results agree to the last bit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sds/sds_internal.h"
#include "sds_kernels.h"

int32_t sds_grid_coord(double v, double h) {
  double q = floor(v / h);
  q = q < -1073741824.0 ? -1073741824.0 : (q > 1073741824.0 ? 1073741824.0 : q);
  return (int32_t)q;
}

uint32_t sds_grid_hash(int32_t i, int32_t j, int32_t k, uint32_t T) {
  return (((uint32_t)i * (uint32_t)SDS_P1) ^ ((uint32_t)j * (uint32_t)SDS_P2) ^ ((uint32_t)k * (uint32_t)SDS_P3)) % T;
}

uint32_t sds_prime_at_least(uint32_t n) {
  if (n <= 2) return 2;
  for (uint32_t p = n | 1u;; p += 2) {
    int prime = 1;
    for (uint32_t d = 3; (uint64_t)d * d <= p && prime; d += 2) prime = p % d != 0;
    if (prime) return p;
  }
}

uint32_t sds_table_size(uint32_t n) { return sds_prime_at_least(4 * n + 1); }

void sds_tri_spheres(const double *pos, const uint32_t *tri, uint32_t nf, double *sph) {
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *t = tri + 3 * (size_t)f;
    double *g = sph + 4 * (size_t)f, rho = 0;
    for (int i = 0; i < 3; i++)
      g[i] = (pos[3 * (size_t)t[0] + i] + pos[3 * (size_t)t[1] + i] + pos[3 * (size_t)t[2] + i]) / 3.0;
    for (int k = 0; k < 3; k++) {
      double d[3];
      sds_sub(g, pos + 3 * (size_t)t[k], d);
      double l = sqrt(sds_dot(d, d));
      if (l > rho) rho = l;
    }
    g[3] = rho;
  }
}

double sds_mean_side(const double *pos, const uint32_t *tri, uint32_t nf) {
  double s = 0;
  for (uint32_t f = 0; f < nf; f++)
    for (int k = 0; k < 3; k++) {
      double d[3];
      sds_sub(pos + 3 * (size_t)tri[3 * f + k], pos + 3 * (size_t)tri[3 * f + (k + 1) % 3], d);
      s += sqrt(sds_dot(d, d));
    }
  return nf ? s / (3.0 * nf) : 1.0;
}

void sds_hash_free(sds_hash *hs) {
  free(hs->off), free(hs->ent);
  memset(hs, 0, sizeof *hs);
}

static void centroid(const double *pos, const uint32_t *t, double *g) {
  for (int i = 0; i < 3; i++)
    g[i] = (pos[3 * (size_t)t[0] + i] + pos[3 * (size_t)t[1] + i] + pos[3 * (size_t)t[2] + i]) / 3.0;
}

sessile_status sds_hash_build(sds_hash *hs, const double *pos, const uint32_t *tri, uint32_t nf, double h) {
  memset(hs, 0, sizeof *hs);
  SESSILE_CHECK(h > 0 && isfinite(h), SESSILE_ERR_USAGE, "sds: hash cell size %g is not positive", h);
  SESSILE_CHECK(nf < UINT32_MAX / 2, SESSILE_ERR_TOO_LARGE, "sds: %u triangles are too many to hash", nf);
  hs->tsize = sds_table_size(nf), hs->n = nf, hs->h = h;
  hs->off = calloc((size_t)hs->tsize + 1, sizeof *hs->off);
  hs->ent = malloc((nf ? nf : 1) * sizeof *hs->ent);
  uint32_t *slot = malloc((nf ? nf : 1) * sizeof *slot);
  if (!hs->off || !hs->ent || !slot) {
    free(slot), sds_hash_free(hs);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory hashing %u triangles", nf);
  }
  for (uint32_t f = 0; f < nf; f++) {
    double g[3];
    centroid(pos, tri + 3 * (size_t)f, g);
    int32_t gc[3] = {sds_grid_coord(g[0], h), sds_grid_coord(g[1], h), sds_grid_coord(g[2], h)};
    for (int i = 0; i < 3; i++) {
      if (f == 0 || gc[i] < hs->glo[i]) hs->glo[i] = gc[i];
      if (f == 0 || gc[i] > hs->ghi[i]) hs->ghi[i] = gc[i];
    }
    slot[f] = sds_grid_hash(gc[0], gc[1], gc[2], hs->tsize);
    hs->off[slot[f] + 1]++;
    for (int k = 0; k < 3; k++) {
      double d[3];
      sds_sub(g, pos + 3 * (size_t)tri[3 * f + k], d);
      double l = sqrt(sds_dot(d, d));
      if (l > hs->rho) hs->rho = l;
    }
  }
  for (uint32_t b = 0; b < hs->tsize; b++) hs->off[b + 1] += hs->off[b];
  uint32_t *cur = malloc(hs->tsize * sizeof *cur);
  if (!cur) {
    free(slot), sds_hash_free(hs);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory hashing %u triangles", nf);
  }
  memcpy(cur, hs->off, hs->tsize * sizeof *cur);
  for (uint32_t f = 0; f < nf; f++) hs->ent[cur[slot[f]]++] = f; /* ascending within each bucket */
  free(cur), free(slot);
  return SESSILE_OK;
}

/* Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision
 * Detection §5.1.5: Voronoi regions of the vertices, edges and face).
 * Returns the region: SDS_REGION_FACE, _A, _B, _C (vertices), _AB, _AC, _BC. */
static int closest_on_tri(const double *p, const double *a, const double *b, const double *c, double *q) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  sds_sub(a, b, ab), sds_sub(a, c, ac), sds_sub(a, p, ap);
  double d1 = sds_dot(ab, ap), d2 = sds_dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    memcpy(q, a, 24);
    return SDS_REGION_A;
  }
  sds_sub(b, p, bp);
  double d3 = sds_dot(ab, bp), d4 = sds_dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    memcpy(q, b, 24);
    return SDS_REGION_B;
  }
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    double v = d1 / (d1 - d3);
    for (int i = 0; i < 3; i++) q[i] = a[i] + v * ab[i];
    return SDS_REGION_AB;
  }
  sds_sub(c, p, cp);
  double d5 = sds_dot(ab, cp), d6 = sds_dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    memcpy(q, c, 24);
    return SDS_REGION_C;
  }
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    double w = d2 / (d2 - d6);
    for (int i = 0; i < 3; i++) q[i] = a[i] + w * ac[i];
    return SDS_REGION_AC;
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int i = 0; i < 3; i++) q[i] = b[i] + w * (c[i] - b[i]);
    return SDS_REGION_BC;
  }
  double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
  for (int i = 0; i < 3; i++) q[i] = a[i] + ab[i] * v + ac[i] * w;
  return SDS_REGION_FACE;
}

static double tri_dist2(const double *p, const double *pos, const uint32_t *t) {
  double q[3], d[3];
  closest_on_tri(p, pos + 3 * (size_t)t[0], pos + 3 * (size_t)t[1], pos + 3 * (size_t)t[2], q);
  sds_sub(q, p, d);
  return sds_dot(d, d);
}

/* Distance from p to its nearest triangle t and the unit direction w in
 * which the penalty pushes.  nrm NULL (the organism's surface): unsigned,
 * w = (p - q)/|p - q| away from the closest point q.  nrm (the obstacle's
 * pseudo-normals, SDS_OBS_NRM per triangle): signed by the pseudo-normal of
 * q's region (Baerentzen & Aanaes: the sign is right for a closed mesh),
 * negative inside, w pointing out.  At q = p, w is the face normal. */
static double contact_dist(const double *p, const double *pos, const uint32_t *t, const double *nrm, uint32_t ti,
                           double *w) {
  const double *a = pos + 3 * (size_t)t[0], *b = pos + 3 * (size_t)t[1], *c = pos + 3 * (size_t)t[2];
  double q[3], e1[3], e2[3], n[3], d[3];
  int region = closest_on_tri(p, a, b, c, q);
  for (int i = 0; i < 3; i++) d[i] = p[i] - q[i], e1[i] = b[i] - a[i], e2[i] = c[i] - a[i];
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  /* within 2^-30 of the triangle's size: the face's normal (the shader's
   * contact_add says why) */
  double ln = sqrt(sds_dot(n, n)), dd = sqrt(sds_dot(d, d));
  if (dd > 0x1p-30 * sqrt(ln)) {
    double sg = nrm && sds_dot(d, nrm + SDS_OBS_NRM * (size_t)ti + 3 * region) < 0 ? -1.0 : 1.0;
    for (int i = 0; i < 3; i++) w[i] = sg * d[i] / dd;
    return sg * dd;
  }
  for (int i = 0; i < 3; i++) w[i] = n[i] / ln;
  return 0.0;
}

typedef struct edge_ref {
  uint32_t lo, hi, face, k;
} edge_ref;
static int edge_cmp(const void *x, const void *y) {
  const edge_ref *a = x, *b = y;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return a->face < b->face ? -1 : (a->face > b->face);
}

sessile_status sds_obstacle_normals(const sessile_sds_obstacle *ob, double **out) {
  size_t nf = ob->nf;
  double *nrm = calloc(nf ? SDS_OBS_NRM * nf : 1, sizeof *nrm),
         *vn = calloc(ob->nv ? 3 * (size_t)ob->nv : 1, sizeof *vn);
  edge_ref *er = malloc((nf ? 3 * nf : 1) * sizeof *er);
  if (!nrm || !vn || !er) {
    free(nrm), free(vn), free(er);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for the normals of %zu obstacle triangles", nf);
  }
  for (size_t f = 0; f < nf; f++) {
    const uint32_t *t = ob->tri + 3 * f;
    double e1[3], e2[3], n[3];
    sds_sub(ob->pos + 3 * (size_t)t[0], ob->pos + 3 * (size_t)t[1], e1);
    sds_sub(ob->pos + 3 * (size_t)t[0], ob->pos + 3 * (size_t)t[2], e2);
    sds_cross(e1, e2, n);
    double l = sqrt(sds_dot(n, n));
    for (int i = 0; i < 3; i++) nrm[SDS_OBS_NRM * f + i] = l > 0 ? n[i] / l : 0;
    for (int k = 0; k < 3; k++) { /* angle-weighted vertex normals */
      double u[3], v[3];
      sds_sub(ob->pos + 3 * (size_t)t[k], ob->pos + 3 * (size_t)t[(k + 1) % 3], u);
      sds_sub(ob->pos + 3 * (size_t)t[k], ob->pos + 3 * (size_t)t[(k + 2) % 3], v);
      double cr[3];
      sds_cross(u, v, cr);
      double ang = atan2(sqrt(sds_dot(cr, cr)), sds_dot(u, v));
      for (int i = 0; i < 3; i++) vn[3 * (size_t)t[k] + i] += ang * nrm[SDS_OBS_NRM * f + i];
      uint32_t x0 = t[k], x1 = t[(k + 1) % 3];
      er[3 * f + k] = (edge_ref){x0 < x1 ? x0 : x1, x0 < x1 ? x1 : x0, (uint32_t)f, (uint32_t)k};
    }
  }
  qsort(er, 3 * nf, sizeof *er, edge_cmp);
  /* edge k of a face (corners k, k+1) is region AB, BC, AC for k = 0, 1, 2 */
  static const int edge_region[3] = {SDS_REGION_AB, SDS_REGION_BC, SDS_REGION_AC};
  for (size_t i = 0; i < 3 * nf;) {
    size_t j = i;
    double sum[3] = {0, 0, 0};
    while (j < 3 * nf && er[j].lo == er[i].lo && er[j].hi == er[i].hi) {
      for (int d = 0; d < 3; d++) sum[d] += nrm[SDS_OBS_NRM * er[j].face + d];
      j++;
    }
    for (size_t k = i; k < j; k++)
      for (int d = 0; d < 3; d++) nrm[SDS_OBS_NRM * er[k].face + 3 * edge_region[er[k].k] + d] = sum[d];
    i = j;
  }
  static const int vertex_region[3] = {SDS_REGION_A, SDS_REGION_B, SDS_REGION_C};
  for (size_t f = 0; f < nf; f++)
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++)
        nrm[SDS_OBS_NRM * f + 3 * vertex_region[k] + d] = vn[3 * (size_t)ob->tri[3 * f + k] + d];
  free(vn), free(er);
  *out = nrm;
  return SESSILE_OK;
}

/* Is cell v the cell c or a neighbour of c (an edge of the complex)? */
static int near_cell(const sessile_sds *o, uint32_t c, uint32_t v) {
  if (v == c) return 1;
  for (uint32_t k = o->cell_edge_off[c]; k < o->cell_edge_off[c + 1]; k++) {
    const uint32_t *e = o->edge + 2 * (size_t)o->cell_edge[k];
    if (e[0] == v || e[1] == v) return 1;
  }
  return 0;
}

/* Offers triangle t at squared distance dd: the nearest wins, ties to the
 * lower index (so the result does not depend on the order of the visit). */
static void offer(double dd, uint32_t t, double *best, int32_t *bt) {
  if (dd < *best || (dd == *best && *bt >= 0 && t < (uint32_t)*bt)) *best = dd, *bt = (int32_t)t;
}

/* Nearest triangle of (pos, tri) to p closer than delta; excl (may be NULL):
 * skip triangles with a corner at cell c or a neighbour of c.  hs NULL: all
 * triangles (brute force); else the buckets within delta + rho. */
static int32_t nearest(const double *pos, const uint32_t *tri, uint32_t nf, const sds_hash *hs, const double *p,
                       double delta, const sessile_sds *excl, uint32_t c) {
  double best = delta * delta;
  int32_t bt = -1;
  if (!hs) {
    for (uint32_t t = 0; t < nf; t++) {
      const uint32_t *q = tri + 3 * (size_t)t;
      double dd = tri_dist2(p, pos, q);
      if ((dd < best || (dd == best && bt >= 0 && t < (uint32_t)bt)) &&
          !(excl && (near_cell(excl, c, q[0]) || near_cell(excl, c, q[1]) || near_cell(excl, c, q[2]))))
        offer(dd, t, &best, &bt);
    }
    return bt;
  }
  double reach = (delta + hs->rho) * 1.000000001;
  int32_t lo[3], hi[3];
  for (int i = 0; i < 3; i++) {
    lo[i] = sds_grid_coord(p[i] - reach, hs->h), hi[i] = sds_grid_coord(p[i] + reach, hs->h);
    /* no centroid outside [glo, ghi]: the box's other buckets hold only other cells' collisions */
    if (lo[i] < hs->glo[i]) lo[i] = hs->glo[i];
    if (hi[i] > hs->ghi[i]) hi[i] = hs->ghi[i];
  }
  for (int32_t gi = lo[0]; gi <= hi[0]; gi++)
    for (int32_t gj = lo[1]; gj <= hi[1]; gj++)
      for (int32_t gk = lo[2]; gk <= hi[2]; gk++) {
        uint32_t b = sds_grid_hash(gi, gj, gk, hs->tsize);
        for (uint32_t k = hs->off[b]; k < hs->off[b + 1]; k++) {
          uint32_t t = hs->ent[k];
          const uint32_t *q = tri + 3 * (size_t)t;
          double dd = tri_dist2(p, pos, q);
          if ((dd < best || (dd == best && bt >= 0 && t < (uint32_t)bt)) &&
              !(excl && (near_cell(excl, c, q[0]) || near_cell(excl, c, q[1]) || near_cell(excl, c, q[2]))))
            offer(dd, t, &best, &bt);
        }
      }
  return bt;
}

static void contact_of(const sessile_sds *o, const sessile_sds_params *p, uint32_t c, const double *xc,
                       const sds_hash *hself, const sds_hash *hobs, const double *onrm, int brute,
                       sessile_sds_contact *ct) {
  double delta = p->contact_scale * o->r[c], w[3];
  ct->tri = -1, ct->obs = -1, ct->s = 0, ct->s_obs = 0;
  if (p->obstacle.nf) {
    ct->obs = nearest(p->obstacle.pos, p->obstacle.tri, p->obstacle.nf, brute ? NULL : hobs, xc,
                      sessile_sds_obstacle_reach(p, delta), NULL, 0);
    if (ct->obs >= 0)
      ct->s_obs = contact_dist(xc, p->obstacle.pos, p->obstacle.tri + 3 * (size_t)ct->obs, onrm, (uint32_t)ct->obs, w);
  }
  if (p->self_collide && o->nfaces && o->surface[c]) {
    ct->tri = nearest(o->x, o->face, o->nfaces, brute ? NULL : hself, xc, delta, o, c);
    if (ct->tri >= 0) ct->s = contact_dist(xc, o->x, o->face + 3 * (size_t)ct->tri, NULL, 0, w);
  }
}

void sessile_sds_contact_brute(const sessile_sds *o, const sessile_sds_params *p, uint32_t c, const double *xc,
                               sessile_sds_contact *ct) {
  double *onrm = NULL;
  if (p->obstacle.nf && sds_obstacle_normals(&p->obstacle, &onrm) != SESSILE_OK) onrm = NULL;
  contact_of(o, p, c, xc, NULL, NULL, onrm, 1, ct);
  if (p->obstacle.nf && !onrm) ct->obs = -1, ct->s_obs = 0; /* out of memory: reported as no contact */
  free(onrm);
}

sessile_status sessile_sds_contacts(const sessile_sds *o, const sessile_sds_params *p, sessile_sds_contact *ct) {
  sds_hash hself = {0}, hobs = {0};
  int self = p->self_collide && o->nfaces;
  double *onrm = NULL;
  sessile_status st = p->obstacle.nf ? sds_obstacle_normals(&p->obstacle, &onrm) : SESSILE_OK;
  if (st == SESSILE_OK && self)
    st = sds_hash_build(&hself, o->x, o->face, o->nfaces, SDS_HASH_CELL * sds_mean_side(o->x, o->face, o->nfaces));
  if (st == SESSILE_OK && p->obstacle.nf)
    st = sds_hash_build(&hobs, p->obstacle.pos, p->obstacle.tri, p->obstacle.nf,
                        SDS_HASH_CELL * sds_mean_side(p->obstacle.pos, p->obstacle.tri, p->obstacle.nf));
  if (st == SESSILE_OK)
    for (uint32_t c = 0; c < o->ncells; c++) contact_of(o, p, c, o->x + 3 * (size_t)c, &hself, &hobs, onrm, 0, &ct[c]);
  sds_hash_free(&hself), sds_hash_free(&hobs);
  free(onrm);
  return st;
}

double sessile_sds_obstacle_reach(const sessile_sds_params *p, double delta) {
  return p->obstacle.nf && p->adhesion > 0 ? 2 * delta : delta;
}

/* The signed distance of xc from its obstacle triangle and the outward unit
 * direction w: the sign is the contact's (found with the pseudo-normals). */
static double obstacle_dist(const sessile_sds_params *p, const double *xc, const sessile_sds_contact *ct, double *w) {
  double s = contact_dist(xc, p->obstacle.pos, p->obstacle.tri + 3 * (size_t)ct->obs, NULL, 0, w);
  if (ct->s_obs < 0 && s > 0) {
    s = -s;
    for (int i = 0; i < 3; i++) w[i] = -w[i];
  }
  return s;
}

int sessile_sds_friction_normal(const sessile_sds_params *p, const double *xc, const sessile_sds_contact *ct,
                                double *n) {
  if (!(p->friction > 0) || ct->obs < 0) return 0;
  obstacle_dist(p, xc, ct, n);
  return 1;
}

double sessile_sds_contact_accel(const sessile_sds *o, const sessile_sds_params *p, uint32_t c, const double *xc,
                                 const sessile_sds_contact *ct, double *acc) {
  double delta = p->contact_scale * o->r[c], w[3], u = 0;
  if (ct->obs >= 0) {
    double s = obstacle_dist(p, xc, ct, w);
    if (s < delta) {
      for (int i = 0; i < 3; i++) acc[i] += p->k_wall * (delta - s) * w[i];
      u += 0.5 * p->k_wall * (delta - s) * (delta - s);
      if (p->adhesion > 0) u -= 0.5 * p->adhesion * delta; /* the well's floor: continuous at delta */
    } else if (p->adhesion > 0) {
      /* adhesion: a tent of height A over delta <= s <= 2 delta (as
       * shaders/sds/gather.glsl); its potential rises from -A delta / 2 to 0 */
      double e = s - delta, a = p->adhesion, pull;
      if (e < 0.5 * delta) {
        pull = 2 * a * e / delta;
        u += a * e * e / delta - 0.5 * a * delta;
      } else {
        double g = delta - e > 0 ? delta - e : 0;
        pull = 2 * a * g / delta;
        u -= a * g * g / delta;
      }
      for (int i = 0; i < 3; i++) acc[i] -= pull * w[i];
    }
  }
  if (ct->tri >= 0) {
    double s = contact_dist(xc, o->x, o->face + 3 * (size_t)ct->tri, NULL, 0, w);
    for (int i = 0; i < 3; i++) acc[i] += p->k_contact * (delta - s) * w[i];
    u += 0.5 * p->k_contact * (delta - s) * (delta - s);
  }
  return u;
}
