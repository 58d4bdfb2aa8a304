/* The organism's arrays: allocation, copy, and the derived data (edges,
 * boundary faces, surface flags, incidence) rebuilt from (x, tet). */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/mesh_sort.h"
#include "sds/sds_internal.h"

#define FREE0(p) (free(p), (p) = NULL)

static void free_derived(sessile_sds *o) {
  FREE0(o->surface), FREE0(o->tet_surface), FREE0(o->edge), FREE0(o->edge_sm), FREE0(o->edge_k);
  FREE0(o->edge_surface), FREE0(o->face), FREE0(o->cell_edge_off), FREE0(o->cell_edge);
  FREE0(o->cell_tet_off), FREE0(o->cell_tet);
  o->nedges = o->nfaces = 0;
}

void sessile_sds_free(sessile_sds *o) {
  if (!o) return;
  free_derived(o);
  free(o->x), free(o->v), free(o->r), free(o->m), free(o->phi), free(o->state);
  free(o->attract), free(o->tet), free(o->tet_sm);
  memset(o, 0, sizeof *o);
}

/* realloc of n elements of size sz, zero-filling from old_n. */
static int grow(void **p, size_t old_n, size_t n, size_t sz) {
  if (n == 0) n = 1;
  void *q = realloc(*p, n * sz);
  if (!q) return 0;
  if (n > old_n) memset((char *)q + old_n * sz, 0, (n - old_n) * sz);
  *p = q;
  return 1;
}

sessile_status sessile_sds_reserve(sessile_sds *o, uint32_t ncells, uint32_t ntets) {
  if (ncells > o->cap_cells) {
    size_t a = o->cap_cells, b = ncells;
    int ok = grow((void **)&o->x, 3 * a, 3 * b, sizeof(double)) &&
             grow((void **)&o->v, 3 * a, 3 * b, sizeof(double)) &&
             grow((void **)&o->r, a, b, sizeof(double)) && grow((void **)&o->m, a, b, sizeof(double)) &&
             grow((void **)&o->phi, a * o->nmorph, b * o->nmorph, sizeof(double)) &&
             grow((void **)&o->state, a * o->nstate, b * o->nstate, sizeof(double)) &&
             grow((void **)&o->attract, a, b, sizeof(int32_t));
    SESSILE_CHECK(ok, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %u cells", ncells);
    for (size_t c = a; c < b; c++) o->attract[c] = -1;
    o->cap_cells = ncells;
  }
  if (ntets > o->cap_tets) {
    size_t a = o->cap_tets, b = ntets;
    int ok = grow((void **)&o->tet, 4 * a, 4 * b, sizeof(uint32_t)) &&
             grow((void **)&o->tet_sm, a, b, sizeof(double));
    SESSILE_CHECK(ok, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %u tetrahedra", ntets);
    o->cap_tets = ntets;
  }
  return SESSILE_OK;
}

sessile_status sessile_sds_alloc(sessile_sds *o, uint32_t ncells, uint32_t ntets, uint32_t nmorph,
                                 uint32_t nstate) {
  sessile_sds_free(o);
  o->nmorph = nmorph, o->nstate = nstate;
  sessile_status st = sessile_sds_reserve(o, ncells, ntets);
  if (st != SESSILE_OK) {
    sessile_sds_free(o);
    return st;
  }
  o->ncells = ncells, o->ntets = ntets;
  return SESSILE_OK;
}

static void *dup(const void *p, size_t bytes, int *ok) {
  if (!p || !bytes) return NULL;
  void *q = malloc(bytes);
  if (!q) *ok = 0;
  else memcpy(q, p, bytes);
  return q;
}

sessile_status sessile_sds_copy(const sessile_sds *s, sessile_sds *d) {
  sessile_sds_free(d);
  SESSILE_CALL(sessile_sds_alloc(d, s->ncells, s->ntets, s->nmorph, s->nstate));
  size_t n = s->ncells, t = s->ntets, E = s->nedges, F = s->nfaces;
  if (n) {
    memcpy(d->x, s->x, 3 * n * sizeof(double)), memcpy(d->v, s->v, 3 * n * sizeof(double));
    memcpy(d->r, s->r, n * sizeof(double)), memcpy(d->m, s->m, n * sizeof(double));
    if (s->nmorph) memcpy(d->phi, s->phi, n * s->nmorph * sizeof(double));
    if (s->nstate) memcpy(d->state, s->state, n * s->nstate * sizeof(double));
    memcpy(d->attract, s->attract, n * sizeof(int32_t));
  }
  if (t) memcpy(d->tet, s->tet, 4 * t * sizeof(uint32_t)), memcpy(d->tet_sm, s->tet_sm, t * sizeof(double));
  int ok = 1;
  d->surface = dup(s->surface, n, &ok);
  d->tet_surface = dup(s->tet_surface, t, &ok);
  d->edge = dup(s->edge, 2 * E * sizeof(uint32_t), &ok);
  d->edge_sm = dup(s->edge_sm, E * sizeof(double), &ok);
  d->edge_k = dup(s->edge_k, E * sizeof(double), &ok);
  d->edge_k_defer = s->edge_k_defer;
  d->edge_surface = dup(s->edge_surface, E, &ok);
  d->face = dup(s->face, 3 * F * sizeof(uint32_t), &ok);
  d->cell_edge_off = dup(s->cell_edge_off, (n + 1) * sizeof(uint32_t), &ok);
  d->cell_edge = dup(s->cell_edge, 2 * E * sizeof(uint32_t), &ok);
  d->cell_tet_off = dup(s->cell_tet_off, (n + 1) * sizeof(uint32_t), &ok);
  d->cell_tet = dup(s->cell_tet, 4 * t * sizeof(uint32_t), &ok);
  d->nedges = s->nedges, d->nfaces = s->nfaces;
  if (!ok) {
    sessile_sds_free(d);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory copying an organism");
  }
  return SESSILE_OK;
}

/* --- rebuild --------------------------------------------------------------- */
typedef struct face_rec {
  uint32_t s[3]; /* sorted cells */
  uint32_t o[3]; /* outward orientation */
  uint32_t tet;
} face_rec;

static int face_cmp(const void *a, const void *b) {
  const face_rec *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x->s[i] != y->s[i]) return x->s[i] < y->s[i] ? -1 : 1;
  return x->tet < y->tet ? -1 : (x->tet > y->tet);
}

static void sort3(const uint32_t *in, uint32_t *s) {
  uint32_t a = in[0], b = in[1], c = in[2], t;
  if (a > b) t = a, a = b, b = t;
  if (b > c) t = b, b = c, c = t;
  if (a > b) t = a, a = b, b = t;
  s[0] = a, s[1] = b, s[2] = c;
}

/* Index of edge (a, b), a < b, in the sorted list, or -1. */
static int64_t edge_find(const uint32_t *edge, uint32_t ne, uint32_t a, uint32_t b) {
  uint64_t key = (uint64_t)a << 32 | b;
  size_t lo = 0, hi = ne;
  while (lo < hi) {
    size_t mid = (lo + hi) / 2;
    uint64_t k = (uint64_t)edge[2 * mid] << 32 | edge[2 * mid + 1];
    if (k == key) return (int64_t)mid;
    if (k < key) lo = mid + 1;
    else hi = mid;
  }
  return -1;
}

static sessile_status orient(sessile_sds *o) {
  for (uint32_t t = 0; t < o->ntets; t++) {
    uint32_t *q = o->tet + 4 * (size_t)t;
    for (int i = 0; i < 4; i++)
      SESSILE_CHECK(q[i] < o->ncells, SESSILE_ERR_USAGE,
                    "sds: tetrahedron %u names cell %u of %u", t, q[i], o->ncells);
    double vol = sessile_sds_tet_volume(o, t);
    SESSILE_CHECK(vol != 0.0 && vol == vol, SESSILE_ERR_NUMERIC,
                  "sds: tetrahedron %u (cells %u %u %u %u) has zero volume", t, q[0], q[1], q[2], q[3]);
    if (vol < 0) {
      uint32_t s = q[2];
      q[2] = q[3], q[3] = s;
    }
  }
  return SESSILE_OK;
}

/* Unique sorted edges of the tets; keeps s_m and k of edges in the old list. */
static sessile_status build_edges(sessile_sds *o, sessile_sds_new_sm new_sm) {
  static const int pair[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  size_t nk = 6 * (size_t)o->ntets;
  uint64_t *key = malloc((nk ? nk : 1) * sizeof *key), *tmp = malloc((nk ? nk : 1) * sizeof *tmp);
  if (!key || !tmp) {
    free(key), free(tmp);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu edge keys", nk);
  }
  for (size_t t = 0; t < o->ntets; t++)
    for (int k = 0; k < 6; k++) {
      uint32_t a = o->tet[4 * t + pair[k][0]], b = o->tet[4 * t + pair[k][1]];
      if (a > b) {
        uint32_t s = a;
        a = b, b = s;
      }
      key[6 * t + k] = (uint64_t)a << 32 | b;
    }
  mesh_sort_u64(key, tmp, nk);
  size_t ne = 0;
  for (size_t i = 0; i < nk; i++)
    if (i == 0 || key[i] != key[i - 1]) key[ne++] = key[i];
  free(tmp);
  uint32_t *edge = malloc((ne ? 2 * ne : 1) * sizeof *edge);
  double *sm = malloc((ne ? ne : 1) * sizeof *sm), *kk = malloc((ne ? ne : 1) * sizeof *kk);
  if (!edge || !sm || !kk) {
    free(key), free(edge), free(sm), free(kk);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu edges", ne);
  }
  for (size_t e = 0; e < ne; e++) {
    uint32_t a = (uint32_t)(key[e] >> 32), b = (uint32_t)key[e];
    edge[2 * e] = a, edge[2 * e + 1] = b;
    int64_t old = o->edge ? edge_find(o->edge, o->nedges, a, b) : -1;
    kk[e] = old >= 0 && o->edge_k ? o->edge_k[old] : (o->edge_k_defer ? 0.0 : 1.0);
    if (old >= 0) sm[e] = o->edge_sm[old];
    else if (new_sm == SESSILE_SDS_NEW_RELAXED) {
      double d[3];
      sds_sub(o->x + 3 * (size_t)a, o->x + 3 * (size_t)b, d);
      sm[e] = sqrt(sds_dot(d, d)) / (o->r[a] + o->r[b]);
    } else sm[e] = 1.0;
  }
  free(key);
  free(o->edge), free(o->edge_sm), free(o->edge_k);
  o->edge = edge, o->edge_sm = sm, o->edge_k = kk, o->nedges = (uint32_t)ne;
  return SESSILE_OK;
}

/* Sorts records made in ascending tet as face_cmp does: a stable radix
 * sort of their sorted cells (ties keep the tets' order); 0 when a cell
 * index does not fit the key or memory is short (then the caller qsorts).
 * Every division rebuilds the organism, and qsort's comparator calls were
 * most of a rebuild. */
static int faces_radix(face_rec *r, size_t n) {
  _Static_assert(offsetof(face_rec, s) == 0 && sizeof(face_rec) % sizeof(uint32_t) == 0, "s leads face_rec");
  uint32_t *order = malloc((n + 1) * sizeof *order);
  face_rec *out = malloc((n + 1) * sizeof *out);
  int ok = order && out && mesh_order3((const uint32_t *)r, sizeof *r / sizeof(uint32_t), n, order);
  for (size_t i = 0; ok && i < n; i++) out[i] = r[order[i]];
  if (ok) memcpy(r, out, n * sizeof *r);
  free(order), free(out);
  return ok;
}

/* Boundary faces (in one tet), the closedness check, surface flags. */
static sessile_status build_faces(sessile_sds *o) {
  /* outward faces of a positive tet (0, 1, 2, 3) */
  static const int fv[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  size_t nr = 4 * (size_t)o->ntets;
  face_rec *rec = malloc((nr ? nr : 1) * sizeof *rec);
  o->surface = calloc(o->ncells ? o->ncells : 1, 1);
  o->tet_surface = calloc(o->ntets ? o->ntets : 1, 1);
  o->edge_surface = calloc(o->nedges ? o->nedges : 1, 1);
  if (!rec || !o->surface || !o->tet_surface || !o->edge_surface) {
    free(rec);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu faces", nr);
  }
  for (size_t t = 0; t < o->ntets; t++)
    for (int f = 0; f < 4; f++) {
      face_rec *r = rec + 4 * t + f;
      for (int i = 0; i < 3; i++) r->o[i] = o->tet[4 * t + fv[f][i]];
      sort3(r->o, r->s);
      r->tet = (uint32_t)t;
    }
  if (!faces_radix(rec, nr)) qsort(rec, nr, sizeof *rec, face_cmp);
  size_t nb = 0;
  for (size_t i = 0; i < nr;) {
    size_t j = i + 1;
    while (j < nr && !memcmp(rec[j].s, rec[i].s, sizeof rec[i].s)) j++;
    if (j - i > 2) {
      uint32_t a = rec[i].s[0], b = rec[i].s[1], c = rec[i].s[2];
      free(rec);
      return sessile_error_set(SESSILE_ERR_NUMERIC, "sds: face (%u %u %u) is in %zu tetrahedra (at most 2)",
                               a, b, c, j - i);
    }
    if (j - i == 1) rec[nb++] = rec[i];
    i = j;
  }
  o->face = malloc((nb ? 3 * nb : 1) * sizeof *o->face);
  if (!o->face) {
    free(rec);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu faces", nb);
  }
  for (size_t f = 0; f < nb; f++) {
    const uint32_t *q = rec[f].o;
    int k = q[0] == rec[f].s[0] ? 0 : (q[1] == rec[f].s[0] ? 1 : 2); /* smallest first */
    for (int i = 0; i < 3; i++) {
      uint32_t c = q[(k + i) % 3], d = q[(k + i + 1) % 3];
      o->face[3 * f + i] = c;
      o->surface[c] = 1;
      int64_t e = edge_find(o->edge, o->nedges, c < d ? c : d, c < d ? d : c);
      if (e >= 0) o->edge_surface[e] = 1;
    }
    o->tet_surface[rec[f].tet] = 1;
  }
  o->nfaces = (uint32_t)nb;
  free(rec);
  return SESSILE_OK;
}

/* CSR cell -> elements (k cells per element), ascending element index. */
static sessile_status build_csr(uint32_t ncells, const uint32_t *elem, uint32_t nelem, int k,
                                uint32_t **off_out, uint32_t **list_out) {
  uint32_t *off = calloc((size_t)ncells + 1, sizeof *off);
  size_t nl = (size_t)k * nelem;
  uint32_t *list = malloc((nl ? nl : 1) * sizeof *list);
  if (!off || !list) {
    free(off), free(list);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for the incidence");
  }
  for (size_t i = 0; i < (size_t)k * nelem; i++) off[elem[i] + 1]++;
  for (uint32_t c = 0; c < ncells; c++) off[c + 1] += off[c];
  uint32_t *fill = malloc(((size_t)ncells + 1) * sizeof *fill);
  if (!fill) {
    free(off), free(list);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for the incidence");
  }
  memcpy(fill, off, ((size_t)ncells + 1) * sizeof *fill);
  for (uint32_t e = 0; e < nelem; e++)
    for (int j = 0; j < k; j++) list[fill[elem[(size_t)k * e + j]]++] = e;
  free(fill);
  *off_out = off, *list_out = list;
  return SESSILE_OK;
}

sessile_status sessile_sds_rebuild(sessile_sds *o, sessile_sds_new_sm new_sm) {
  SESSILE_CALL(orient(o));
  return sessile_sds_rebuild_oriented(o, new_sm);
}

sessile_status sessile_sds_rebuild_oriented(sessile_sds *o, sessile_sds_new_sm new_sm) {
  for (uint32_t t = 0; t < o->ntets; t++)
    for (int i = 0; i < 4; i++)
      SESSILE_CHECK(o->tet[4 * (size_t)t + i] < o->ncells, SESSILE_ERR_USAGE, "sds: tetrahedron %u names cell %u of %u",
                    t, o->tet[4 * (size_t)t + i], o->ncells);
  /* the old edge list (for s_m) survives until build_edges replaces it */
  free(o->surface), free(o->tet_surface), free(o->edge_surface), free(o->face);
  free(o->cell_edge_off), free(o->cell_edge), free(o->cell_tet_off), free(o->cell_tet);
  o->surface = o->tet_surface = o->edge_surface = NULL;
  o->face = o->cell_edge_off = o->cell_edge = o->cell_tet_off = o->cell_tet = NULL;
  o->nfaces = 0;
  sessile_status st = build_edges(o, new_sm);
  if (st == SESSILE_OK) st = build_faces(o);
  if (st == SESSILE_OK) st = build_csr(o->ncells, o->edge, o->nedges, 2, &o->cell_edge_off, &o->cell_edge);
  if (st == SESSILE_OK) st = build_csr(o->ncells, o->tet, o->ntets, 4, &o->cell_tet_off, &o->cell_tet);
  if (st != SESSILE_OK) {
    free_derived(o);
    return st;
  }
  for (uint32_t t = 0; t < o->ntets; t++)
    if (!(o->tet_sm[t] > 0)) {
      double R = sessile_sds_tet_rest_of(o, t);
      o->tet_sm[t] = new_sm == SESSILE_SDS_NEW_RELAXED ? sessile_sds_tet_volume(o, t) / R : 1.0;
    }
  return SESSILE_OK;
}
