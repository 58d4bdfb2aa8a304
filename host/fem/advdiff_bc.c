/* The nutrient's boundary conditions on a tet mesh (paper §4.3): the walls
 * carry the idealised 1 mol m^-3, the substratum and the sponge absorb
 * everything (0). */
#include "sessile/fem/advdiff.h"

void sessile_advdiff_nutrient_bc(const sessile_tetmesh *mesh, const uint8_t *solid_or_null,
                                 uint8_t *mask, double *values) {
  const uint32_t walls = SESSILE_TAG_INLET | SESSILE_TAG_OUTLET | SESSILE_TAG_SIDE | SESSILE_TAG_TOP;
  const uint32_t sinks = SESSILE_TAG_SUBSTRATUM | SESSILE_TAG_SPONGE;
  for (uint32_t i = 0; i < mesh->nnodes; i++) {
    uint32_t t = mesh->node_tags[i];
    int solid = solid_or_null && solid_or_null[i];
    if (solid || (t & sinks)) { /* sinks win over walls: substratum edges are 0 */
      mask[i] = 1;
      values[i] = 0.0;
    } else if (t & walls) {
      mask[i] = 1;
      values[i] = 1.0;
    } else {
      mask[i] = 0;
      values[i] = 0.0;
    }
  }
}
