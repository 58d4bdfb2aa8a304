/* sessile — the stationary nutrient field on the box mesh (O'Hagan et al.
 * §4.3, eq 5 with u = 0: "diffusion limited", Table 1's default), by P1 finite
 * elements on the Kuhn tetrahedra, solved on the GPU.
 *
 * Boundary conditions: c = 1 on every box wall except the substratum; c = 0
 * on the substratum (z-min; nodes on its edges with the other walls too) and
 * on every solid node (a box node inside the sponge).  The field has one value
 * per box node (index as sessile_box_index), stored in a sessile_vec.
 *
 * Ownership: the nutrient solver owns its operator and work vectors; the
 * caller owns the box, the solid mask buffer and the field vector. */
#ifndef SESSILE_NUTRIENT_H
#define SESSILE_NUTRIENT_H

#include "sessile/box.h"
#include "sessile/la.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_nutrient sessile_nutrient;

sessile_status sessile_nutrient_create(sessile_la *la, const sessile_box *box,
                                       sessile_nutrient **out);
void sessile_nutrient_destroy(sessile_nutrient *nt);

/* Solves for c.  solid: a device buffer of sessile_box_nodes(box) uint32
 * (non-zero = solid node, c = 0).  c: the warm start on entry (e.g. the
 * previous growth iteration's field; any values, Dirichlet nodes are reset),
 * the solution on return.  opt: NULL for PCG + Jacobi, rtol 1e-6.  res gets
 * the solve record (iterations, true relative residual, status, time). */
sessile_status sessile_nutrient_solve(sessile_nutrient *nt, sessile_buffer *solid,
                                      sessile_vec *c, const sessile_ksp_options *opt,
                                      sessile_solve_result *res);

#ifdef __cplusplus
}
#endif
#endif
