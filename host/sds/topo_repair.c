/* Repair of inverted tetrahedra that no movement transformation removed
 * (docs/sds_topology.md, "Repair"): the stars of their cells cut out and the
 * cavity re-tetrahedralised by TetGen over its hull, grown by a ring of cells
 * when TetGen cannot mesh it. */
#include <stdlib.h>
#include <string.h>
#include "topo_internal.h"

/* Rings of cells the cavity may grow by before the repair gives up. */
#define REPAIR_RINGS 3

sessile_status sessile_sds_topo_repair(sessile_sds_topo_complex *cx, const uint32_t *bad, uint32_t nbad,
                                       sessile_sds_topo_transform *tr) {
  memset(tr, 0, sizeof *tr);
  SESSILE_CHECK(nbad > 0, SESSILE_ERR_USAGE, "repair: no tetrahedron named");
  for (uint32_t i = 0; i < nbad; i++)
    SESSILE_CHECK(bad[i] < cx->nt, SESSILE_ERR_USAGE, "repair: tet %u of %u", bad[i], cx->nt);
  uint8_t *mark = calloc((size_t)cx->nv + 1, 1), *onhull = calloc((size_t)cx->nv + 1, 1);
  uint8_t *rm = calloc((size_t)cx->nt + 1, 1);
  uint32_t *list = malloc(((size_t)cx->nt + 1) * sizeof *list), *pts = malloc(((size_t)cx->nv + 1) * sizeof *pts);
  uint32_t *hull = NULL, nf = 0, *add = NULL, nadd = 0;
  sessile_status st = SESSILE_OK;
  if (!mark || !onhull || !rm || !list || !pts) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory repairing %u tets", nbad);
    goto done;
  }
  for (uint32_t i = 0; i < nbad; i++)
    for (int q = 0; q < 4; q++) mark[cx->tet[4 * (size_t)bad[i] + q]] = 1;
  for (int ring = 0; ring < REPAIR_RINGS; ring++) {
    /* the cavity: every tet through a marked cell */
    uint32_t n = 0, np = 0;
    memset(rm, 0, cx->nt);
    for (uint32_t t = 0; t < cx->nt; t++) {
      const uint32_t *v = cx->tet + 4 * (size_t)t;
      if (mark[v[0]] || mark[v[1]] || mark[v[2]] || mark[v[3]]) list[n++] = t, rm[t] = 1;
    }
    free(hull), hull = NULL;
    st = topo_cavity_hull(cx->tet, list, n, &hull, &nf);
    if (st != SESSILE_OK) goto done;
    /* the cells inside the cavity (on no hull face) become TetGen's points */
    memset(onhull, 0, cx->nv);
    for (uint32_t f = 0; f < 3 * nf; f++) onhull[hull[f]] = 1;
    for (uint32_t i = 0; i < n; i++)
      for (int q = 0; q < 4; q++) {
        uint32_t v = cx->tet[4 * (size_t)list[i] + q];
        if (!onhull[v]) onhull[v] = 2, pts[np++] = v;
      }
    free(add), add = NULL;
    st = topo_fill_hull(cx->x, hull, nf, pts, np, &add, &nadd);
    if (st == SESSILE_OK) break;
    if (st == SESSILE_ERR_NO_MEMORY) goto done;
    /* grow by a ring: every cell of the cavity is marked */
    for (uint32_t i = 0; i < n; i++)
      for (int q = 0; q < 4; q++) mark[cx->tet[4 * (size_t)list[i] + q]] = 1;
  }
  if (st != SESSILE_OK) {
    st = sessile_error_set(SESSILE_ERR_NUMERIC, "repair of %u inverted tets: %s", nbad, sessile_error_message());
    goto done;
  }
  uint32_t nrm = 0;
  st = topo_replace(cx, rm, add, nadd, &tr->tet_from, &nrm);
  if (st == SESSILE_OK) tr->n_removed = nrm, tr->n_added = nadd;
done:
  free(mark), free(onhull), free(rm), free(list), free(pts), free(hull), free(add);
  return st;
}
