/* sessile — the stationary advected nutrient (O'Hagan et al. §4.3, eq 5 at
 * steady state: u . grad c = D laplacian c) by P1 elements with SUPG
 * (streamline-upwind Petrov-Galerkin) on a general tet mesh.  Assembled on
 * the host into CSR, solved on the GPU with la's Krylov solvers.
 *
 * Units: the mesh is in cm (sessile/mesh/tetmesh.h); the solver works in SI:
 * coordinates x 0.01 -> m, velocity in m/s, D in m^2/s, c in mol m^-3 (the
 * paper's idealised wall value 1).  An optional source (tests) is in
 * mol m^-3 s^-1.
 *
 * Discretisation (docs/advdiff.md): for every tet e with the element-mean
 * velocity u_e,
 *   a(c, v) = sum_e  int D grad c . grad v + v (u . grad c)
 *                  + tau_e (u . grad v)(u . grad c)
 * with u the nodal P1 field (integrals exact), tau_e = h/(2|u_e|) xi(Pe_h),
 * xi(P) = coth(P) - 1/P, Pe_h = |u_e| h / (2 D), and h = 2|u_e| /
 * sum_i |u_e . grad phi_i| the element length along the flow (Tezduyar's
 * h_UGN; on a Kuhn box with flow along an axis it is the cube edge, and the
 * scheme is then nodally exact for the 1-D boundary layer).
 *
 * Dirichlet nodes are eliminated symmetrically (rows and columns identity,
 * the known values moved to the right-hand side), so the reported relative
 * residual is that of the free rows alone (as in docs/fem.md).
 *
 * Ownership: the solver owns its matrix graph, value arrays and GPU vectors;
 * the caller owns the mesh (which must outlive the solver), the la, and every
 * array passed in. */
#ifndef SESSILE_ADVDIFF_H
#define SESSILE_ADVDIFF_H

#include <stdint.h>
#include "sessile/la/la.h"
#include "sessile/la/matrix.h"
#include "sessile/mesh/tetmesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Default (effective, eddy) diffusivity, m^2/s: kappa u* z with kappa 0.41,
 * u* ~ 0.1 x 0.05 m/s and z ~ 5 cm (the sponge's scale).  Molecular
 * diffusion (~1e-9) would put the cell Peclet number near 3e5 on the default
 * box; docs/advdiff.md argues the choice and lists the Peclet numbers. */
#define SESSILE_ADVDIFF_DEFAULT_D 1.0e-4

typedef struct sessile_advdiff sessile_advdiff;

/* Builds the matrix graph of the mesh (self + edge neighbours) and the GPU
 * vectors.  The mesh must stay alive and unchanged while the solver exists. */
sessile_status sessile_advdiff_create(sessile_la *la, const sessile_tetmesh *mesh,
                                      sessile_advdiff **out);
void sessile_advdiff_destroy(sessile_advdiff *ad);

/* Solves -D lap c + u . grad c = f (f from sessile_advdiff_set_source, else 0).
 * velocity: 3 per node, m/s, or NULL (u = 0: the Laplace problem).
 * D > 0, m^2/s.  dirichlet_mask[i] != 0: c_i = dirichlet_values[i].
 * opt: NULL for BiCGSTAB + Jacobi, rtol 1e-6 (CG is refused: the matrix is
 * nonsymmetric unless velocity is NULL).  c: warm start on entry (free nodes;
 * any values), the solution on return.  res: the solve record (its seconds
 * cover assembly, upload and solve; sessile_advdiff_timing splits them). */
sessile_status sessile_advdiff_solve(sessile_advdiff *ad, const double *velocity_or_null, double D,
                                     const uint8_t *dirichlet_mask, const double *dirichlet_values,
                                     const sessile_ksp_options *opt, double *c,
                                     sessile_solve_result *res);

/* A nodal source term f (P1 interpolant, mol m^-3 s^-1; copied) added to the
 * next solves, with its SUPG term; NULL removes it.  For manufactured
 * solutions; the nutrient has no source.  Fails with SESSILE_ERR_NUMERIC on
 * a non-finite value (naming the node) or SESSILE_ERR_NO_MEMORY; on failure
 * the source in force before the call (or none) is kept unchanged. */
sessile_status sessile_advdiff_set_source(sessile_advdiff *ad, const double *f_or_null);

/* Multiplies tau by `scale` (default 1; 0 gives plain Galerkin, which
 * oscillates for cell Peclet numbers above 1: tests only). */
void sessile_advdiff_set_tau_scale(sessile_advdiff *ad, double scale);

/* Wall times (s) of the last solve: host assembly (with elimination), matrix
 * and vector upload, Krylov solve. */
void sessile_advdiff_timing(const sessile_advdiff *ad, double *assemble_s, double *upload_s,
                            double *solve_s);

/* The last assembled system (after elimination), for tests: A and b of the
 * homogenised unknown u = c - g.  Valid until the next solve or destroy. */
const sessile_csr *sessile_advdiff_matrix(const sessile_advdiff *ad);
const double *sessile_advdiff_rhs(const sessile_advdiff *ad);

/* The nutrient's boundary conditions (paper §4.3): c = 1 on every box wall
 * (inlet, outlet, sides, top) except the substratum; c = 0 on the substratum
 * (its edges with the other walls included), on the sponge surface
 * (SESSILE_TAG_SPONGE, conforming meshes) and on every node with
 * solid_or_null[i] != 0 (immersed sponge).  Other nodes: mask 0, value 0.
 * mask and values hold mesh->nnodes entries. */
void sessile_advdiff_nutrient_bc(const sessile_tetmesh *mesh, const uint8_t *solid_or_null,
                                 uint8_t *mask, double *values);

/* The SUPG parameter tau (s) of an element of length h (m) with speed
 * |u| (m/s) and diffusivity D: h/(2|u|) (coth Pe - 1/Pe), Pe = |u| h/(2D);
 * 0 for |u| = 0. */
double sessile_advdiff_tau(double h, double speed, double D);

#ifdef __cplusplus
}
#endif
#endif
