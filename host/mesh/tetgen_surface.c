/* sessile_tetgen_surface: a closed triangulated surface as TetGen's PLC (one
 * facet per triangle), so that other layers (sds) mesh through the public
 * API instead of the internal tg_tetrahedralize. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/tetgen.h"
#include "tetgen_plc.h"

void sessile_tetgen_mesh_free(sessile_tetgen_mesh *m) {
  if (!m) return;
  free(m->xyz);
  free(m->tet);
  memset(m, 0, sizeof *m);
}

sessile_status sessile_tetgen_surface(const double *xyz, int npoints, const uint32_t *tri, int ntri,
                                      const char *switches, sessile_tetgen_mesh *out, char *msg,
                                      size_t msglen) {
  memset(out, 0, sizeof *out);
  size_t nf = ntri > 0 ? (size_t)ntri : 0;
  int *facet_poly = malloc((nf + 1) * sizeof(int)), *poly_vert = malloc((nf + 1) * sizeof(int));
  int *verts = malloc((3 * nf + 1) * sizeof(int)), *facet_hole = calloc(nf + 1, sizeof(int));
  int *marker = malloc((nf + 1) * sizeof(int));
  int code = -2;
  tg_result r;
  memset(&r, 0, sizeof r);
  if (facet_poly && poly_vert && verts && facet_hole && marker) {
    for (size_t f = 0; f <= nf; f++) facet_poly[f] = (int)f, poly_vert[f] = 3 * (int)f;
    for (size_t f = 0; f < nf; f++) {
      marker[f] = 1;
      for (int i = 0; i < 3; i++) verts[3 * f + i] = (int)tri[3 * f + i];
    }
    tg_plc plc = {npoints, (double *)xyz, NULL, ntri, facet_poly, poly_vert, verts, facet_hole, NULL, marker, 0, NULL};
    code = tg_tetrahedralize(&plc, switches, &r, msg, msglen);
  } else if (msglen) {
    snprintf(msg, msglen, "out of host memory for TetGen's input");
  }
  free(facet_poly), free(poly_vert), free(verts), free(facet_hole), free(marker);
  if (code != 0) {
    tg_result_free(&r);
    return sessile_error_set(code == 1 || code == -2 ? SESSILE_ERR_NO_MEMORY : SESSILE_ERR_NUMERIC,
                             "TetGen (switches %s): %s", switches, msglen ? msg : "failed");
  }
  out->npoints = r.npoints, out->ntets = r.ntets;
  out->xyz = r.xyz, out->tet = r.tet; /* moved: the rest of r is freed */
  r.xyz = NULL, r.tet = NULL;
  tg_result_free(&r);
  return SESSILE_OK;
}
