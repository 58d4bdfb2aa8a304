/* Inverted tets (§3.1.2; sds_sim.h): the first inversion of a step
 * rewound to and transformed (case 1 or 2), and the cavities around tets
 * that stay inverted re-tetrahedralised with a backoff (docs/sds.md, "The
 * loop"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_sim.h"
#include "sessile/sds/sds_batch.h"

/* Inverted tets that no transformation removed (they began the step inverted,
 * or their transformation was refused): the cavity around them is
 * re-tetrahedralised (sessile_sds_topo_repair) and the organism takes it if
 * the whole complex is then valid; else the volume springs go on resisting
 * (docs/sds.md, "The loop").  Without it one lasting sliver stopped every
 * division for the rest of a run (they wait for a valid complex). */
/* The backoff table's entry of the inverted tet with hash h, or nsliver. */
static uint32_t sliver_find(const sds_sim *s, uint64_t h) {
  uint32_t e = 0;
  while (e < s->nsliver && s->sliver[3 * e] != h) e++;
  return e;
}

/* A tet named by its cells (cell indices outlive the renumbering of tets by
 * a division elsewhere): an FNV-1a of its sorted cells. */
static uint64_t tet_hash(const uint32_t *v) {
  uint32_t q[4] = {v[0], v[1], v[2], v[3]};
  for (int i = 1; i < 4; i++)
    for (int j = i; j > 0 && q[j - 1] > q[j]; j--) {
      uint32_t w = q[j];
      q[j] = q[j - 1], q[j - 1] = w;
    }
  uint64_t h = 14695981039346656037ull;
  for (int i = 0; i < 4; i++) h = (h ^ q[i]) * 1099511628211ull;
  return h;
}

uint32_t sds_sliver_table(sds_sim *s, uint32_t *pairs) {
  _Static_assert(SESSILE_SDS_SLIVERS_MAX == 64, "one bit an entry; sl_hash, sl_tet");
  uint32_t n = s->nsliver;
  if (n > SESSILE_SDS_SLIVERS_MAX) return UINT32_MAX;
  /* each entry's tet where it was last found, while that tet still has the
   * entry's name (a batch at a time: the whole complex is named only when an
   * entry is new, moved or its tet renumbered) */
  int cached = 1;
  for (uint32_t e = 0; e < n && cached; e++)
    cached = s->sl_hash[e] == s->sliver[3 * e] && s->sl_tet[e] < s->o.ntets &&
             tet_hash(s->o.tet + 4 * (size_t)s->sl_tet[e]) == s->sl_hash[e];
  if (!cached) {
    uint64_t placed = 0; /* one bit per entry: its tet found once */
    for (uint32_t t = 0; t < s->o.ntets && n; t++) {
      uint32_t e = sliver_find(s, tet_hash(s->o.tet + 4 * (size_t)t));
      if (e == n) continue;
      if (placed >> e & 1) return UINT32_MAX; /* two tets of one name: leave them to the host */
      placed |= 1ull << e;
      s->sl_tet[e] = t, s->sl_hash[e] = s->sliver[3 * e];
    }
    uint64_t all = n == 64 ? ~0ull : (1ull << n) - 1;
    if (placed != all) return UINT32_MAX; /* an entry's tet is gone: the host prunes it */
  }
  for (uint32_t e = 0; e < n; e++) {
    uint64_t due = s->sliver[3 * e + 2], now = s->st->steps;
    pairs[2 * e] = s->sl_tet[e];
    pairs[2 * e + 1] = due <= now ? 0 : due - now > UINT32_MAX ? UINT32_MAX : (uint32_t)(due - now);
  }
  return n;
}

static sessile_status repair(sds_sim *s) {
  sessile_sds *o = &s->o;
  uint32_t *bad = malloc(((size_t)o->ntets + 1) * sizeof *bad), nbad = 0, ntry = 0;
  uint64_t *hb = malloc(((size_t)o->ntets + 1) * sizeof *hb);
  if (!bad || !hb) {
    free(bad), free(hb);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  }
  /* the inverted tets, each named by its cells (tet_hash) */
  for (uint32_t t = 0; t < o->ntets; t++) {
    const uint32_t *v = o->tet + 4 * (size_t)t;
    if (sessile_sds_topo_volume(o->x + 3 * (size_t)v[0], o->x + 3 * (size_t)v[1], o->x + 3 * (size_t)v[2],
                                o->x + 3 * (size_t)v[3]) > 0)
      continue;
    hb[nbad] = tet_hash(v), bad[nbad++] = t;
  }
  /* The backoff, per inverted tet: after k failed tries in a row it waits
   * 2^k steps (at most 128) before the next.  A sliver can last thousands
   * of steps, and a try copies and checks the whole complex and calls
   * TetGen up to three times: tried at every step it was 40 % of the rock
   * model's run, and keyed on the whole set of inverted tets (which changes
   * every few steps late in that run, with 40 slivers) a try every 8 steps
   * still cost 12 ms each, 2.5 ms per step.  A try takes the tets that are
   * due, alone, so that a new sliver is not held back by old ones that
   * TetGen cannot mesh.  Entries of tets no longer inverted are dropped. */
  uint32_t keep = 0;
  for (uint32_t e = 0; e < s->nsliver; e++) {
    uint32_t i = 0;
    while (i < nbad && hb[i] != s->sliver[3 * e]) i++;
    if (i < nbad) memmove(s->sliver + 3 * keep++, s->sliver + 3 * e, 3 * sizeof *s->sliver);
  }
  s->nsliver = keep;
  for (uint32_t i = 0; i < nbad; i++) {
    uint32_t e = sliver_find(s, hb[i]);
    if (e == s->nsliver || s->st->steps >= s->sliver[3 * e + 2]) hb[ntry] = hb[i], bad[ntry++] = bad[i];
  }
  sessile_status st = SESSILE_OK;
  if (ntry) {
    sessile_sds_topo_complex cx;
    sessile_sds_topo_transform tr;
    memset(&tr, 0, sizeof tr);
    st = sds_complex_of(o, &cx);
    sessile_status rst = st == SESSILE_OK ? sessile_sds_topo_repair(&cx, bad, ntry, &tr) : st;
    /* inverted tets left out of the try may stay as they were */
    sessile_status kst = st == SESSILE_OK && rst == SESSILE_OK
                             ? sessile_sds_topo_check_kept(o->x, o->ntets, o->tet, &cx, tr.tet_from)
                             : SESSILE_OK;
    if (kst == SESSILE_ERR_NO_MEMORY) rst = kst; /* a failure, not a repair to leave out */
    int ok = st == SESSILE_OK && rst == SESSILE_OK && kst == SESSILE_OK;
    if (ok) {
      st = sds_take_complex(s, &cx, tr.tet_from);
      if (st == SESSILE_OK) s->st->repairs++;
    } else if (st == SESSILE_OK && rst == SESSILE_ERR_NO_MEMORY)
      st = rst;
    else
      for (uint32_t i = 0; i < ntry && st == SESSILE_OK; i++) {
        uint32_t e = sliver_find(s, hb[i]);
        if (e == s->nsliver) {
          if (s->nsliver == s->sliver_cap) {
            uint32_t cap = s->sliver_cap ? 2 * s->sliver_cap : 16;
            uint64_t *w = realloc(s->sliver, 3 * (size_t)cap * sizeof *w);
            if (!w) {
              st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
              break;
            }
            s->sliver = w, s->sliver_cap = cap;
          }
          s->sliver[3 * e] = hb[i], s->sliver[3 * e + 1] = 0, s->nsliver++;
        }
        uint64_t k = ++s->sliver[3 * e + 1];
        s->sliver[3 * e + 2] = s->st->steps + (1u << (k < 7 ? k : 7));
      }
    free(tr.tet_from);
    sessile_sds_topo_complex_free(&cx);
  }
  free(bad), free(hb);
  return st;
}

/* The tets inverted by the last step: rewind every cell to the first
 * inversion time among them and transform that tet; the others are not
 * inverted at that time and are found again by the next step's check. */
sessile_status sds_inversions(sds_sim *s, int *handled, double *frac) {
  *handled = 0;
  *frac = 1;
  uint32_t *list = NULL, n = 0;
  SESSILE_CALL(sessile_sds_gpu_inverted(s->pg, &list, &n));
  if (n == 0) {
    free(list);
    return SESSILE_OK;
  }
  sessile_sds *o = &s->o;
  double best = INFINITY;
  uint32_t bt = UINT32_MAX;
  sessile_sds_topo_inversion binv;
  memset(&binv, 0, sizeof binv);
  for (uint32_t i = 0; i < n; i++) {
    const uint32_t *t = o->tet + 4 * (size_t)list[i];
    double p[12], q[12];
    for (int k = 0; k < 4; k++)
      for (int a = 0; a < 3; a++) p[3 * k + a] = s->xprev[3 * (size_t)t[k] + a], q[3 * k + a] = o->x[3 * (size_t)t[k] + a];
    sessile_sds_topo_inversion inv;
    if (sessile_sds_topo_inversion_time(p, q, 0, 1, &inv) && inv.s < best) best = inv.s, bt = list[i], binv = inv;
  }
  free(list);
  if (bt == UINT32_MAX) {
    /* inverted, but with no sign change over the step: they began the step
     * inverted, slivers a re-tetrahedralisation made flat to rounding or
     * ones an earlier step left.  Their volume springs push them back open
     * (E grows with (V - R')^2 for V < 0 too); the step stands and they
     * are counted (docs/sds.md, "The loop"). */
    s->st->slivers += n;
    return repair(s);
  }
  /* the transformation is made just before the flat moment, so that the
   * flat tet's four cells are not coplanar for TetGen (relative 1e-6 of the
   * step; the paper makes it at the moment itself) */
  best *= 1 - 1e-6;
  /* rewind to the inversion time (linear motion over the step) */
  size_t n3 = 3 * (size_t)o->ncells;
  double *xnew = malloc(n3 * sizeof *xnew);
  SESSILE_CHECK(xnew, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  memcpy(xnew, o->x, n3 * sizeof *xnew);
  for (size_t i = 0; i < n3; i++) o->x[i] = s->xprev[i] + best * (xnew[i] - s->xprev[i]);
  sessile_sds_topo_complex cx;
  sessile_status st = sds_complex_of(o, &cx);
  sessile_sds_topo_transform tr;
  memset(&tr, 0, sizeof tr);
  sessile_status tst = SESSILE_OK; /* the transformation's own answer */
  if (st == SESSILE_OK) tst = sessile_sds_topo_apply_inversion(&cx, bt, &binv, &tr);
  /* the result must be a valid complex before the organism takes it (an
   * inverted sliver elsewhere, or a covering tet that overlaps the body,
   * would otherwise spread): a refusal like the transformation's own */
  if (st == SESSILE_OK && tst == SESSILE_OK) {
    sessile_status cst = sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0, NULL);
    if (cst != SESSILE_OK) tst = cst == SESSILE_ERR_NO_MEMORY ? cst : SESSILE_ERR_UNSUPPORTED;
  }
  if (st == SESSILE_OK && tst == SESSILE_OK) st = sds_take_complex(s, &cx, tr.tet_from);
  free(tr.tet_from);
  sessile_sds_topo_complex_free(&cx);
  if (st == SESSILE_OK && tst != SESSILE_OK && tst != SESSILE_ERR_UNSUPPORTED && tst != SESSILE_ERR_NUMERIC) st = tst;
  if (st == SESSILE_OK && tst != SESSILE_OK) {
    /* No transformation for this one (both v and f on the surface, a ridge,
     * a hull TetGen cannot mesh without a new point): the paper leaves such
     * cases open.  The step stands as it was and the tet's volume spring
     * (E grows with (V - R')^2 for V < 0 too) pushes it back open; counted
     * as resisted (docs/sds.md, "The loop"). */
    memcpy(o->x, xnew, n3 * sizeof *xnew);
    s->st->resisted++;
    free(xnew);
    return repair(s);
  }
  free(xnew);
  if (st != SESSILE_OK)
    return sessile_error_set(st, "sds: the inversion of tet %u at t = %g could not be handled: %s", bt, s->time,
                             sessile_error_message());
  s->st->inversions++, s->inv_interval++;
  *handled = 1;
  *frac = best;
  return SESSILE_OK;
}
