/* The SDS contacts' candidate lists on the GPU (Verlet lists with a skin,
 * docs/sds.md "Collisions"): when they have gone stale, which cells a
 * topology change needs listed anew, and their builds (full or partial). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_gpu_internal.h"

/* Have the contact lists gone stale, with every cell at most far_all and
 * every surface cell at most far_surf from where the lists were built, and
 * the radii grown by at most s->grown?  A list holds the triangles within
 * delta + skin of its cell at the build.  An obstacle triangle does not
 * move: its distance to a cell changes by at most the cell's move, so the
 * obstacle's entries hold while far_all + contact_scale grown <= skin (twice
 * contact_scale with adhesion, whose reach is 2 delta: sds_gpu_reach_scale).  A
 * boundary face's distance changes by at most the cell's move plus its
 * corners' largest move, and both are surface cells (only they query the
 * surface): 2 far_surf + contact_scale grown <= skin.  Interior cells (most
 * daughters of a division) so count once, and only against the obstacle. */
double sds_gpu_reach_scale(const sessile_sds_gpu *s) {
  /* the reach is linear in delta = contact_scale r: 2 delta with adhesion */
  return sessile_sds_obstacle_reach(&s->p, s->p.contact_scale);
}

int sds_gpu_lists_stale(const sessile_sds_gpu *s, double far_all, double far_surf) {
  sds_push p = sds_gpu_push_of(s, 0.0, 0, 0);
  double g = sds_gpu_reach_scale(s) * s->grown;
  return (p.nobs && !(far_all + g <= s->skin)) || (p.tsize && !(2 * far_surf + g <= s->skin));
}

/* The lists' staleness at o's x and r (the same complex as at their build,
 * but for the cells skip marks): the largest moves since the build, every
 * cell's and the surface cells', and the radii's growth (kept in s->grown). */
static int lists_moved_stale(sessile_sds_gpu *s, const sessile_sds *o, const uint8_t *skip) {
  double moved = 0, moved_surf = 0, grown = 0;
  for (size_t c = 0; c < o->ncells; c++) {
    if (skip && skip[c]) continue;
    double d2 = 0;
    for (int i = 0; i < 3; i++) d2 += (o->x[3 * c + i] - s->xb[3 * c + i]) * (o->x[3 * c + i] - s->xb[3 * c + i]);
    if (!(d2 <= moved)) moved = d2;
    if (o->surface[c] && !(d2 <= moved_surf)) moved_surf = d2;
    if (!(o->r[c] - s->rb[c] <= grown)) grown = o->r[c] - s->rb[c];
  }
  s->grown = grown;
  return sds_gpu_lists_stale(s, sqrt(moved), sqrt(moved_surf));
}

void sds_gpu_lists_check_moves(sessile_sds_gpu *s, const sessile_sds *o) {
  if (lists_moved_stale(s, o, NULL)) lists_invalidate(s);
}

/* The neighbours of cell c, sorted, from a topo upload's edges and CSR
 * (kernels.def's layout, entries 2 e + side) into nb (room for its degree). */
static uint32_t topo_neighbours(const uint32_t *topo, uint32_t n, uint32_t E, uint32_t T, uint32_t c, uint32_t *nb) {
  const uint32_t *edge = topo + 4 * (size_t)T, *ceo = edge + 2 * (size_t)E, *ce = ceo + 2 * ((size_t)n + 1);
  uint32_t k = 0;
  for (uint32_t j = ceo[c]; j < ceo[c + 1]; j++) {
    uint32_t w = ce[j], v = edge[2 * (size_t)(w >> 1) + (1 - (w & 1))];
    uint32_t i = k++;
    while (i > 0 && nb[i - 1] > v) nb[i] = nb[i - 1], i--; /* a few entries: insertion */
    nb[i] = v;
  }
  return k;
}

/* After a topology change, can the lists be kept but for a few cells?  Yes
 * when the boundary is the same faces in the same order (boundary faces
 * are sorted by their cells, sds_complex.c, so an unchanged boundary is an
 * unchanged array), the cells were only appended and fit the lists' room,
 * and the other cells are within the skin of their builds: then a list
 * entry still names the same triangle, and only these need listing anew:
 * the new cells, and every cell whose neighbours changed (a surface cell's
 * self list leaves out the faces at its neighbours; a moved dividing cell
 * is among them).  The others' lists are exactly what a full build would
 * make of them while they stay within the skin.  Fills sub; 0 if not. */
static int lists_partial(sessile_sds_gpu *s, const sessile_sds *o, const uint32_t *topo) {
  uint32_t n0 = s->ncells, E0 = s->nedges, T0 = s->ntets, F = s->nfaces, n = o->ncells;
  /* valid lists, or lists valid but for a partial build not made yet */
  if (!(s->lists_valid || s->lists_part) || !s->topo_up || n < n0 || n > s->lbase || o->nfaces != F) return 0;
  size_t f0 = 4 * (size_t)T0 + 2 * (size_t)E0 + 2 * ((size_t)n0 + 1) + 2 * (size_t)E0 + 4 * (size_t)T0 + T0 + E0;
  size_t f1 = 4 * (size_t)o->ntets + 2 * (size_t)o->nedges + 2 * ((size_t)n + 1) + 2 * (size_t)o->nedges +
              4 * (size_t)o->ntets + o->ntets + o->nedges;
  if (F && memcmp(s->topo_up + f0, topo + f1, 3 * (size_t)F * 4)) return 0;
  size_t cap = n + n + 2;
  if (s->sub_cap < cap) {
    uint32_t *q = realloc(s->sub, cap * sizeof *q);
    if (!q) return 0;
    s->sub = q, s->sub_cap = cap;
  }
  uint32_t dmax = 0;
  for (uint32_t c = 0; c < n; c++)
    if (o->cell_edge_off[c + 1] - o->cell_edge_off[c] > dmax) dmax = o->cell_edge_off[c + 1] - o->cell_edge_off[c];
  const uint32_t *ceo0 = s->topo_up + 4 * (size_t)T0 + 2 * (size_t)E0;
  for (uint32_t c = 0; c < n0; c++)
    if (ceo0[c + 1] - ceo0[c] > dmax) dmax = ceo0[c + 1] - ceo0[c];
  uint32_t *nb = malloc(2 * ((size_t)dmax + 1) * sizeof *nb);
  uint8_t *redo_of = calloc(n ? n : 1, 1); /* the pending partial build's cells are redone too */
  if (!nb || !redo_of) {
    free(nb), free(redo_of);
    return 0;
  }
  if (s->lists_part)
    for (size_t i = 0; i < s->nsub; i++)
      if (s->sub[i] < n0) redo_of[s->sub[i]] = 1;
  size_t k = 0;
  for (uint32_t c = 0; c < n; c++) {
    int redo = c >= n0 || redo_of[c];
    if (!redo) {
      uint32_t a = topo_neighbours(s->topo_up, n0, E0, T0, c, nb);
      uint32_t b = topo_neighbours(topo, n, o->nedges, o->ntets, c, nb + dmax + 1);
      redo = a != b || memcmp(nb, nb + dmax + 1, a * sizeof *nb);
    }
    if (redo) s->sub[k++] = c, redo_of[c] = 1;
  }
  free(nb);
  int stale = lists_moved_stale(s, o, redo_of); /* the kept lists: still within the skin? */
  free(redo_of);
  if (stale) return 0;
  size_t ns = 0;
  for (size_t i = 0; i < k; i++)
    if (o->surface[s->sub[i]]) s->sub[k + ns++] = s->sub[i];
  s->nsub = k, s->nsub_surf = ns;
  return 1;
}

/* Are the contact lists still complete for the organism about to be
 * uploaded?  After a topology change, complete but for the cells of a
 * partial build (lists_partial) or not at all; else lists_stale with the
 * host's x and r.  Takes topo (malloc'd, ntopo words) as the new reference. */
sessile_status sds_gpu_lists_check_upload(sessile_sds_gpu *s, const sessile_sds *o, uint32_t *topo, size_t ntopo) {
  size_t n = o->ncells;
  int same = s->topo_up && s->ntopo_up == ntopo && n == s->ncells && !memcmp(s->topo_up, topo, ntopo * 4);
  int part = !same && lists_partial(s, o, topo);
  free(s->topo_up);
  s->topo_up = topo, s->ntopo_up = ntopo;
  double *ru = realloc(s->r_up, (n ? n : 1) * sizeof *ru);
  SESSILE_CHECK(ru, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  s->r_up = ru;
  memcpy(ru, o->r, n * sizeof *ru);
  if (part) {
    s->lists_valid = 0, s->lists_part = 1;
    return SESSILE_OK;
  }
  if (!same || !s->lists_valid) {
    lists_invalidate(s);
    return SESSILE_OK;
  }
  sds_gpu_lists_check_moves(s, o);
  return SESSILE_OK;
}

/* Records the surface hash of pair c's x (if self-collision is on) and the
 * contact lists' build (kernels.def, "The contact lists"). */
/* Records a build of the lists: every cell's (lsub 0) or those of a
 * partial build (lsub cells in lmax, kernels.def). */
sessile_status sds_gpu_record_lists(sessile_sds_gpu *s, int c, uint32_t lsub) {
  sds_push p = sds_gpu_push_of(s, 0.0, 0, 0);
  p.lsub = lsub;
  if (p.tsize) { /* the surface hash of x (kernels.def, "The surface hash") */
    sessile_buffer *bh[] = {s->b[B_HASH]};
    sessile_buffer *bc[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_TOPO], s->b[B_HASH]};
    sessile_buffer *bs[] = {s->b[B_SP], s->b[B_X0 + c], s->b[B_TOPO], s->b[B_HASH], s->b[B_FSPH]};
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_CLEAR], sds_gpu_groups(s, SDS_HASH_CLEAR, p.tsize), bh, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_COUNT], sds_gpu_groups(s, SDS_HASH_COUNT, p.nfaces), bs, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_SCAN], 1, bh, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_FILL], sds_gpu_groups(s, SDS_HASH_FILL, p.nfaces), bc, &p));
    SESSILE_CALL(sessile_cmd_dispatch(s->cmd, s->k[SDS_HASH_SORT], sds_gpu_groups(s, SDS_HASH_SORT, p.tsize), bh, &p));
  }
  sessile_buffer *b[] = {s->b[B_SP],   s->b[B_X0 + c], s->b[B_RM],   s->b[B_TOPO], s->b[B_WORLD], s->b[B_OBSTRI],
                         s->b[B_HASH], s->b[B_FSPH],   s->b[B_LIST], s->b[B_XB],   s->b[B_LMAX]};
  SESSILE_CALL(sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_CONTACT_LIST),
                                    sds_gpu_groups(s, SDS_CONTACT_LIST, lsub ? lsub : s->ncells), b, &p));
  uint32_t nsurf = lsub ? (uint32_t)s->nsub_surf : s->nsurf;
  if (!p.tsize || !nsurf) return SESSILE_OK;
  sessile_buffer *bs[] = {s->b[B_SP],   s->b[B_X0 + c], s->b[B_RM],   s->b[B_TOPO],
                          s->b[B_HASH], s->b[B_FSPH],   s->b[B_LIST], s->b[B_LMAX]};
  return sessile_cmd_dispatch(s->cmd, sds_gpu_kern(s, SDS_CONTACT_SELF), sds_gpu_groups(s, SDS_CONTACT_SELF, nsurf), bs, &p);
}

int sds_gpu_contacts_on(const sessile_sds_gpu *s) {
  sds_push p = sds_gpu_push_of(s, 0.0, 0, 0);
  return p.lcap != 0;
}

/* The skin of the next build: SDS_SKIN_FRAC x contact_scale x the mean radius. */
static double skin_now(const sessile_sds_gpu *s) {
  double sum = 0;
  for (uint32_t c = 0; c < s->ncells; c++) sum += s->r_up[c];
  return SDS_SKIN_FRAC * s->p.contact_scale * (s->ncells ? sum / s->ncells : 1.0);
}

/* A partial build (lists_partial): lists only the cells in sub, the others
 * untouched; *ok 0 when a list overflowed (then a full build follows). */
static sessile_status lists_build_part(sessile_sds_gpu *s, int *ok) {
  *ok = 0;
  SESSILE_CALL(sds_gpu_ensure(s, B_LMAX, (2 + s->nsub + s->nsub_surf) * 4)); /* rewritten below */
  uint32_t *lmax = sessile_buffer_host_ptr(s->b[B_LMAX]);
  SESSILE_CHECK(lmax, SESSILE_ERR_INTERNAL, "sds: the contact-list count buffer is not mapped");
  lmax[0] = 0, lmax[1] = (uint32_t)s->nsub_surf;
  memcpy(lmax + 2, s->sub, (s->nsub + s->nsub_surf) * sizeof *lmax);
  if (s->nsub) {
    SESSILE_CALL(sds_gpu_begin(s));
    SESSILE_CALL(sds_gpu_record_lists(s, s->cur, (uint32_t)s->nsub));
    SESSILE_CALL(sessile_cmd_end(s->cmd));
    SESSILE_CALL(sds_gpu_submit(s));
  }
  s->builds++, s->partial_builds++;
  if (lmax[0] > s->lcap) return SESSILE_OK;
  size_t n = s->ncells;
  double *xb = realloc(s->xb, (n ? 3 * n : 1) * sizeof *xb), *rb = realloc(s->rb, (n ? n : 1) * sizeof *rb);
  if (xb) s->xb = xb;
  if (rb) s->rb = rb;
  SESSILE_CHECK(xb && rb, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  SESSILE_CALL(sessile_buffer_download_reals(s->b[B_XB], 0, xb, 3 * n)); /* the others' are unchanged */
  for (size_t i = 0; i < s->nsub; i++) rb[s->sub[i]] = s->r_up[s->sub[i]];
  s->lists_valid = 1, s->lists_part = 0;
  *ok = 1;
  return SESSILE_OK;
}

/* Builds the contact lists at the current x (pair cur) when they are stale,
 * growing them until every count fits; keeps xb and the radii on the host.
 * The lists get room for a quarter more cells than there are, so that a
 * division's daughters can be listed by a partial build. */
sessile_status sds_gpu_lists_ensure(sessile_sds_gpu *s) {
  if (s->lists_valid || !sds_gpu_contacts_on(s)) return SESSILE_OK;
  if (s->lists_part) {
    int ok = 0;
    SESSILE_CALL(lists_build_part(s, &ok));
    if (ok) return SESSILE_OK;
    lists_invalidate(s); /* an overflow: grow and build every list */
  }
  double skin = skin_now(s);
  SESSILE_CALL(sessile_buffer_upload_reals(s->b[B_SP], SP_SKIN, &skin, 1));
  size_t lbase = (size_t)s->ncells + s->ncells / 4 + 16;
  SESSILE_CHECK(lbase * ((size_t)s->lcap + 1) < UINT32_MAX, SESSILE_ERR_TOO_LARGE,
                "sds: contact lists of %zu cells x %u entries are too many for 32-bit indices", lbase, s->lcap);
  s->lbase = (uint32_t)lbase;
  SESSILE_CALL(sds_gpu_ensure(s, B_LIST, (lbase + lbase * (size_t)s->lcap) * 4));
  SESSILE_CALL(sds_gpu_ensure(s, B_XB, 3 * lbase * s->real_bytes));
  SESSILE_CALL(sds_gpu_ensure(s, B_LMAX, 16));
  uint32_t *lmax = sessile_buffer_host_ptr(s->b[B_LMAX]);
  SESSILE_CHECK(lmax, SESSILE_ERR_INTERNAL, "sds: the contact-list count buffer is not mapped");
  for (;;) {
    lmax[0] = 0;
    SESSILE_CALL(sds_gpu_begin(s));
    SESSILE_CALL(sds_gpu_record_lists(s, s->cur, 0));
    SESSILE_CALL(sessile_cmd_end(s->cmd));
    SESSILE_CALL(sds_gpu_submit(s));
    s->builds++;
    if (lmax[0] <= s->lcap) break;
    uint32_t cap = s->lcap;
    while (cap < lmax[0]) {
      SESSILE_CHECK(cap <= (1u << 20), SESSILE_ERR_TOO_LARGE, "sds: %u contact candidates for one cell", lmax[0]);
      cap *= 2;
    }
    SESSILE_CHECK(lbase * ((size_t)cap + 1) < UINT32_MAX, SESSILE_ERR_TOO_LARGE,
                  "sds: contact lists of %zu cells x %u entries are too many for 32-bit indices", lbase, cap);
    s->lcap = cap;
    SESSILE_CALL(sds_gpu_ensure(s, B_LIST, (lbase + lbase * (size_t)cap) * 4));
  }
  size_t n = s->ncells;
  double *xb = realloc(s->xb, (n ? 3 * n : 1) * sizeof *xb), *rb = realloc(s->rb, (n ? n : 1) * sizeof *rb);
  if (xb) s->xb = xb;
  if (rb) s->rb = rb;
  SESSILE_CHECK(xb && rb, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %zu cells", n);
  SESSILE_CALL(sessile_buffer_download_reals(s->b[B_XB], 0, xb, 3 * n));
  memcpy(rb, s->r_up, n * sizeof *rb);
  s->skin = skin, s->lists_valid = 1, s->grown = 0;
  return SESSILE_OK;
}
