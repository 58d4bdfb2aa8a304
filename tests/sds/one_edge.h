/* Two cells of radius 1 and mass 4/3 pi joined by one edge of rest length 2,
 * stretched to L along x: the SDS tests' smallest organism. */
#ifndef SDS_ONE_EDGE_H
#define SDS_ONE_EDGE_H
#include "sessile/sds/sds.h"
#include "testutil.h"

static inline void one_edge(sessile_sds *o, double L) {
  t_must("alloc", sessile_sds_alloc(o, 2, 0, 0, 0));
  o->x[3] = L;
  o->r[0] = o->r[1] = 1;
  o->m[0] = o->m[1] = 4.0 / 3.0 * 3.14159265358979323846;
  o->nedges = 1;
  o->edge = t_xalloc(8), o->edge[0] = 0, o->edge[1] = 1;
  o->edge_sm = t_dalloc(1), o->edge_sm[0] = 1;
  o->edge_surface = t_xalloc(1);
  o->surface = t_xalloc(2);
  o->cell_edge_off = t_xalloc(12), o->cell_edge_off[1] = 1, o->cell_edge_off[2] = 2;
  o->cell_edge = t_xalloc(8);
  o->cell_tet_off = t_xalloc(12);
  o->cell_tet = t_xalloc(4);
}
#endif
