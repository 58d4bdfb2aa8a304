/* sessile — the stationary nutrient with the sponge surface as its true
 * Dirichlet boundary (docs/nutrient.md): -Laplace c = 0 on the box grid by
 * the symmetric cut-cell finite differences of Gibou et al. (2002): c = 0
 * exactly on the surface, at the fractions of the grid edges where it
 * crosses them (sessile_growth_gpu_cut), second order, matrix-free on the
 * GPU, solved by multigrid-preconditioned CG on the nested box levels (each
 * level's operator rediscretised from its own cut fractions).
 *
 * Boundary conditions: c = 0 on the substratum (z = origin) and on the
 * sponge; the far field either
 *  - HEIGHT: c = 1 at and above a set height over the substratum, zero flux
 *    through the side walls (the box size is then a convergence parameter), or
 *  - WALLS: c = 1 on every wall but the substratum (the paper's box).
 *
 * Ownership: the object owns every level's buffers (solid mask and cut
 * fractions, which the caller's classifier fills; the operator's mask and
 * diagonal; the multigrid's work vectors); the caller owns the field. */
#ifndef SESSILE_NUTRIENT_CUT_H
#define SESSILE_NUTRIENT_CUT_H

#include "sessile/mesh/box.h"
#include "sessile/la/la.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Mask codes of the operator (shaders/fem/kernels.def). */
enum { SESSILE_CUT_FREE = 0, SESSILE_CUT_SOLID = 1, SESSILE_CUT_NODE = 2 };

/* HEIGHT: c = 1 at and above the plane, zero-flux side walls; WALLS: c = 1 on
 * every wall but the substratum; INLET: HEIGHT, and c = 1 on the wall x = 0
 * above the substratum (fresh water arriving with a current along +x);
 * PROFILE: HEIGHT, and on the wall x = 0 the bare substratum's profile
 * c = min(z / height, 1): the water a current along +x brings, undisturbed by
 * the sponge (the advected nutrient's inflow, docs/nutrient.md). */
typedef enum {
  SESSILE_FAR_FIELD_HEIGHT = 0,
  SESSILE_FAR_FIELD_WALLS = 1,
  SESSILE_FAR_FIELD_INLET = 2,
  SESSILE_FAR_FIELD_PROFILE = 3
} sessile_far_field;

typedef struct sessile_cut_bc {
  sessile_far_field far_field;
  double height;    /* HEIGHT, INLET, PROFILE: the far-field plane, cm above the substratum (<= the box top) */
  double theta_min; /* cut fractions are raised to at least this (default 1e-3) */
} sessile_cut_bc;
void sessile_cut_bc_default(sessile_cut_bc *bc); /* WALLS off: HEIGHT at the caller's top */

typedef enum { SESSILE_CUT_SOLVER_MG = 0, SESSILE_CUT_SOLVER_JACOBI = 1 } sessile_cut_solver;

typedef struct sessile_cut_nutrient sessile_cut_nutrient;

/* box: the finest level (the nutrient's grid, origin at the substratum);
 * coarser levels halve it while every axis has an even number of cells and
 * at least 4, up to max_levels levels in all (1: no multigrid). */
sessile_status sessile_cut_nutrient_create(sessile_la *la, const sessile_box *box,
                                           const sessile_cut_bc *bc, int max_levels,
                                           sessile_cut_nutrient **out);
void sessile_cut_nutrient_destroy(sessile_cut_nutrient *nt);
int sessile_cut_nutrient_levels(const sessile_cut_nutrient *nt);
/* Level l (0 finest): its box, and the buffers its classifier fills before a
 * solve: solid (uint32 per node, 1 inside the sponge) and theta (6 reals per
 * node), as sessile_growth_gpu_cut writes them. */
void sessile_cut_nutrient_level(sessile_cut_nutrient *nt, int l, sessile_box *box,
                                sessile_buffer **solid, sessile_buffer **theta);
/* The operator's mask of the finest level after a solve (SESSILE_CUT_*). */
sessile_buffer *sessile_cut_nutrient_mask(sessile_cut_nutrient *nt);

/* Solves for c on the finest level: builds every level's operator from its
 * solid and theta, then MG-PCG (or Jacobi-PCG, the baseline) from the warm
 * start c to the true relative residual opt->rtol (opt: type and pc are
 * ignored).  On return c holds the solution (0 on the sponge's solid nodes,
 * the far-field and substratum values on theirs), and the extended field
 * (sessile_cut_nutrient_extended) the same with the linear extrapolation
 * across the surface on solid nodes next to the water. */
sessile_status sessile_cut_nutrient_solve(sessile_cut_nutrient *nt, sessile_cut_solver solver,
                                          sessile_vec *c, const sessile_ksp_options *opt,
                                          sessile_solve_result *res);
const sessile_vec *sessile_cut_nutrient_extended(const sessile_cut_nutrient *nt);
/* The extension of a field solved elsewhere (the advected nutrient, whose
 * solid nodes hold 0): builds the finest level's mask from its solid and
 * theta, then extends c as the solve does. */
sessile_status sessile_cut_nutrient_extend(sessile_cut_nutrient *nt, const sessile_vec *c);

/* The advected nutrient u·∇c = D ∇²c (docs/nutrient.md) with the same cut
 * cells, boundary conditions and far field: each edge weight w carries the
 * exponentially fitted factor B(±P θ) (B(x) = x/(e^x − 1), P = u h / D, the
 * velocity component along the edge at the node), so the operator is an
 * M-matrix (no over- or undershoots) and second order.  velocity: 3 per
 * finest node (x, y, z), m/s; D in m²/s (the box is in cm).  Solved by
 * BiCGSTAB (GMRES when opt->type says so; CG is replaced by BiCGSTAB)
 * preconditioned by one V-cycle of the advective hierarchy (solver MG, with
 * every coarse level rediscretised from its own crossings and the velocity
 * injected onto it) or by Jacobi, to opt->rtol from the warm start c.  On
 * return c and the extended field are as sessile_cut_nutrient_solve leaves
 * them.  The classifier fills the levels' solid and theta first, as for the
 * Laplace solve. */
sessile_status sessile_cut_nutrient_solve_advected(sessile_cut_nutrient *nt, sessile_cut_solver solver,
                                                   const double *velocity, double D, sessile_vec *c,
                                                   const sessile_ksp_options *opt,
                                                   sessile_solve_result *res);

/* --- host references (double; the tests compare the kernels with them) --- */
/* cutcell.comp: mask, diag, and (lift, value when lift != NULL). */
void sessile_cut_ref_setup(const sessile_box *box, const sessile_cut_bc *bc, const uint32_t *solid,
                           const double *theta, uint32_t *mask, double *diag, double *lift,
                           double *value);
/* cutcell_adv.comp: also coef (6 per node, the edge weights w, 0 where there is no edge or
 * on Dirichlet nodes); vel 3 per node, pe = h / D in the velocity's units (the object uses
 * h in m: box h × 0.01). */
void sessile_cut_ref_setup_adv(const sessile_box *box, const sessile_cut_bc *bc,
                               const uint32_t *solid, const double *theta, const double *vel,
                               double pe, uint32_t *mask, double *diag, double *coef, double *lift,
                               double *value);
/* B(x) = x / (e^x - 1) as the kernels evaluate it (B(0) = 1). */
double sessile_cut_bernoulli(double x);
/* ghost.comp: ext from c. */
void sessile_cut_ref_ghost(const sessile_box *box, const sessile_cut_bc *bc, const uint32_t *mask,
                           const double *theta, const double *c, double *ext);

#ifdef __cplusplus
}
#endif
#endif
