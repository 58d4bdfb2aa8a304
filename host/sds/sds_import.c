/* Importing an organism (§3.2.1): TetGen of a closed surface, or given
 * tets; radii from the edge lengths, masses from the radii, spring
 * multipliers s_m = V/R so that the imported shape is at rest. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/mesh/tetgen.h"
#include "sds/sds_internal.h"

sessile_status sessile_sds_from_tets(const double *x, uint32_t n, const uint32_t *tet, uint32_t nt,
                                     uint32_t nmorph, uint32_t nstate, double density,
                                     sessile_sds *out) {
  SESSILE_CHECK(n >= 4 && nt >= 1, SESSILE_ERR_USAGE,
                "sds: an organism needs at least 4 cells and 1 tetrahedron (got %u, %u)", n, nt);
  SESSILE_CHECK(density > 0, SESSILE_ERR_USAGE, "sds: density must be positive (got %g)", density);
  SESSILE_CALL(sessile_sds_alloc(out, n, nt, nmorph, nstate));
  memcpy(out->x, x, 3 * (size_t)n * sizeof(double));
  memcpy(out->tet, tet, 4 * (size_t)nt * sizeof(uint32_t));
  for (uint32_t t = 0; t < nt; t++) out->tet_sm[t] = 1.0; /* set below */
  sessile_status st = sessile_sds_rebuild(out, SESSILE_SDS_NEW_UNIT);
  for (uint32_t c = 0; st == SESSILE_OK && c < n; c++)
    if (out->cell_tet_off[c] == out->cell_tet_off[c + 1])
      st = sessile_error_set(SESSILE_ERR_USAGE, "sds: cell %u is in no tetrahedron", c);
  if (st != SESSILE_OK) {
    sessile_sds_free(out);
    return st;
  }
  sessile_sds_radii_from_edges(out, density);
  sessile_sds_relax_multipliers(out);
  return SESSILE_OK;
}

sessile_status sessile_sds_from_surface(const sessile_surface *s, const char *switches,
                                        double max_volume, uint32_t nmorph, uint32_t nstate,
                                        double density, sessile_sds *out) {
  SESSILE_CHECK(s && s->nv >= 4 && s->nf >= 4, SESSILE_ERR_USAGE,
                "sds: a closed surface needs at least 4 vertices and 4 triangles");
  char sw[96];
  if (switches) snprintf(sw, sizeof sw, "%s", switches);
  else if (max_volume > 0) snprintf(sw, sizeof sw, "%sa%.17g", SESSILE_SDS_TETGEN_SWITCHES, max_volume);
  else snprintf(sw, sizeof sw, "%s", SESSILE_SDS_TETGEN_SWITCHES);
  sessile_tetgen_mesh r = {0};
  char msg[256] = "";
  sessile_status ts = sessile_tetgen_surface(s->pos, (int)s->nv, s->tri, (int)s->nf, sw, &r, msg, sizeof msg);
  if (ts == SESSILE_ERR_NO_MEMORY) /* no verdict on the surface */
    return sessile_error_set(ts, "sds: TetGen (switches %s): %s", sw, msg);
  if (ts != SESSILE_OK)
    return sessile_error_set(SESSILE_ERR_USAGE, "sds: TetGen (switches %s) rejected the surface: %s", sw, msg);
  uint32_t *tet = malloc(4 * (size_t)r.ntets * sizeof *tet);
  if (!tet) {
    sessile_tetgen_mesh_free(&r);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of memory for %d tetrahedra", r.ntets);
  }
  for (size_t i = 0; i < 4 * (size_t)r.ntets; i++) tet[i] = (uint32_t)r.tet[i];
  sessile_status st = sessile_sds_from_tets(r.xyz, (uint32_t)r.npoints, tet, (uint32_t)r.ntets, nmorph,
                                            nstate, density, out);
  free(tet);
  sessile_tetgen_mesh_free(&r);
  return st;
}

sessile_status sessile_sds_from_icosphere(int level, double radius, const double center[3],
                                          double max_volume, uint32_t nmorph, uint32_t nstate,
                                          double density, sessile_sds *out) {
  sessile_surface s = {0};
  SESSILE_CALL(sessile_surface_icosphere(level, radius, center, &s));
  sessile_status st = sessile_sds_from_surface(&s, NULL, max_volume, nmorph, nstate, density, out);
  sessile_surface_free(&s);
  return st;
}
