/* Repair of inverted tets (sessile_sds_topo_repair): an interior cell of a
 * TetGen ball pushed out of its star (past a neighbour) inverts tets; the
 * repair re-tetrahedralises the cavity around them.  After it: a valid
 * complex, the same cells, the same boundary, the same total volume (the
 * signed volumes of a tangled complex still sum to the enclosed volume), the
 * tets outside the cavity untouched.  A tangled hull (a surface cell pushed
 * through the far side) is refused with an error, not a TetGen abort. */
#include "test_topo_fixture.h"

static uint32_t inverted(const sessile_sds_topo_complex *cx, uint32_t *bad) {
  uint32_t n = 0;
  for (uint32_t t = 0; t < cx->nt; t++) {
    const uint32_t *v = cx->tet + 4 * t;
    if (!(sessile_sds_topo_volume(cx->x + 3 * v[0], cx->x + 3 * v[1], cx->x + 3 * v[2], cx->x + 3 * v[3]) > 0))
      bad[n++] = t;
  }
  return n;
}

int main(void) {
  sessile_sds_topo_complex cx = {0};
  fx_ball(3, 0.005, &cx);
  uint32_t *bad = t_xalloc(((size_t)cx.nt + 1) * sizeof *bad);
  int repaired = 0;
  /* interior cells pushed 60 % of the way to a neighbour and beyond it */
  for (uint32_t v = 0, tries = 0; v < cx.nv && tries < 6; v++) {
    if (fx_on_boundary(&cx, v)) continue;
    uint32_t w = UINT32_MAX;
    for (uint32_t t = 0; t < cx.nt && w == UINT32_MAX; t++)
      for (int q = 0; q < 4; q++)
        if (cx.tet[4 * t + q] == v) {
          uint32_t u = cx.tet[4 * t + (q + 1) % 4];
          if (!fx_on_boundary(&cx, u)) w = u;
          break;
        }
    if (w == UINT32_MAX) continue;
    tries++;
    double v0 = fx_volume(&cx), save[3];
    memcpy(save, cx.x + 3 * v, sizeof save);
    for (int k = 0; k < 3; k++) cx.x[3 * v + k] += 1.3 * (cx.x[3 * w + k] - cx.x[3 * v + k]);
    uint32_t nbad = inverted(&cx, bad);
    if (!nbad) { /* the push kept every tet positive: nothing to repair */
      memcpy(cx.x + 3 * v, save, sizeof save);
      continue;
    }
    sessile_sds_topo_complex old;
    fx_copy(&cx, &old);
    uint32_t nb0, *b0 = fx_boundary(&cx, &nb0);
    double vt = fx_volume(&cx);
    sessile_sds_topo_transform tr;
    sessile_status st = sessile_sds_topo_repair(&cx, bad, nbad, &tr);
    printf("cell %u pushed past %u: %u inverted tets; repair %s, %u tets out, %u in\n", v, w, nbad,
           st == SESSILE_OK ? "made" : sessile_error_message(), tr.n_removed, tr.n_added);
    if (st == SESSILE_OK) {
      repaired++;
      sessile_sds_topo_report rep;
      t_ok("the repaired complex passes the check", sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0, &rep));
      t_check("the total volume is unchanged by the repair (rel)", fabs(rep.volume - vt) / vt, 1e-12);
      t_check("the signed volumes summed to the enclosed volume before (rel)", fabs(vt - v0) / v0, 1e-12);
      uint32_t nb1, *b1 = fx_boundary(&cx, &nb1);
      t_true("the boundary is unchanged", nb0 == nb1 && !memcmp(b0, b1, 3 * (size_t)nb0 * sizeof *b0));
      t_true("no cell added or lost", cx.nv == old.nv);
      int same = 1;
      for (uint32_t t = 0; t < cx.nt; t++)
        if (tr.tet_from[t] != SESSILE_SDS_TOPO_NEW_TET)
          same &= !memcmp(cx.tet + 4 * t, old.tet + 4 * tr.tet_from[t], 4 * sizeof *cx.tet);
      t_true("kept tets unchanged", same);
      t_true("the inverted tets are gone", inverted(&cx, bad) == 0);
      free(b1);
    } else {
      t_true("a failed repair leaves the complex untouched",
             cx.nt == old.nt && !memcmp(cx.tet, old.tet, 4 * (size_t)cx.nt * sizeof *cx.tet));
      memcpy(cx.x + 3 * v, save, sizeof save);
    }
    free(tr.tet_from), free(b0);
    sessile_sds_topo_complex_free(&old);
  }
  t_true("at least three pushed cells repaired", repaired >= 3);
  /* a surface cell pushed through the ball to the far side: the cavity's
   * hull is tangled; refused (an error), no abort */
  double *p = cx.x;
  for (int k = 0; k < 3; k++) p[k] = -1.5 * p[k];
  uint32_t nbad = inverted(&cx, bad);
  t_true("the pushed surface cell inverts tets", nbad > 0);
  sessile_sds_topo_transform tr;
  uint32_t nt0 = cx.nt;
  sessile_status st = sessile_sds_topo_repair(&cx, bad, nbad, &tr);
  printf("surface cell through the ball: %s\n", st == SESSILE_OK ? "repaired" : sessile_error_message());
  int valid = st == SESSILE_OK && sessile_sds_topo_check(cx.nv, cx.x, cx.nt, cx.tet, 0, NULL) == SESSILE_OK;
  t_true("a tangled surface is not made valid by a repair (refused, or left for the check to refuse)",
         st != SESSILE_OK ? cx.nt == nt0 : !valid);
  free(tr.tet_from);
  t_true("no tet named: usage error", sessile_sds_topo_repair(&cx, bad, 0, &tr) == SESSILE_ERR_USAGE);
  free(bad);
  sessile_sds_topo_complex_free(&cx);
  return t_finish(NULL);
}
