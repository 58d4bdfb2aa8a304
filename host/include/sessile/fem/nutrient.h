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

#include "sessile/mesh/box.h"
#include "sessile/la/la.h"
#include "sessile/la/matrix.h"

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

/* The nutrient's wall value at node (i,j,k): 0 on the substratum (z-min,
 * its edges included), 1 on the other walls, 0 inside the box (unused). */
static inline double sessile_nutrient_wall_value(const sessile_box *b, uint32_t i, uint32_t j,
                                                 uint32_t k) {
  uint32_t t = sessile_box_node_tags(b, i, j, k);
  return (t == 0 || (t & SESSILE_TAG_SUBSTRATUM)) ? 0.0 : 1.0;
}

/* The same solve with arbitrary Dirichlet data (tests: patch test,
 * manufactured solutions): Dirichlet nodes are the wall nodes and the nodes
 * with mask != 0, their values are taken from `values` (one per node; other
 * entries ignored).  res->true_relres is the relative residual of the
 * homogenised system on the free nodes (docs/fem.md). */
sessile_status sessile_nutrient_solve_dirichlet(sessile_nutrient *nt, sessile_buffer *mask,
                                                const sessile_vec *values, sessile_vec *c,
                                                const sessile_ksp_options *opt,
                                                sessile_solve_result *res);

/* --- host references (double, plain C) ------------------------------------ */
/* The P1 stiffness matrix of -Laplace on the Kuhn box, assembled element by
 * element (6 tets per cube, sessile_box_tet) without boundary conditions:
 * sessile_box_nodes(box) rows, the Kuhn graph (self + 14 neighbours; entries
 * that cancel are stored as explicit zeros). */
sessile_status sessile_p1_laplace_assemble(const sessile_box *box, sessile_csr *out);

/* Symmetric Dirichlet elimination of K u = 0: rows and columns of nodes with
 * dir[i] != 0 become the identity (entries dropped), b_i = g_i there and
 * b_i = -sum_{j Dirichlet} K_ij g_j on free rows.  b has K's row count. */
sessile_status sessile_p1_dirichlet(const sessile_csr *k, const uint8_t *dir, const double *g,
                                    sessile_csr *a, double *b);

#ifdef __cplusplus
}
#endif
#endif
