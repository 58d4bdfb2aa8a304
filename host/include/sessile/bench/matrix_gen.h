/* sessile — the matrices the tests and benchmarks use (host/bench/matrix_gen.c,
 * cut_sphere.c): structured PDE matrices, deterministic random ones, the
 * cut-cell sphere problem.  In the bench layer, not la: no library code
 * needs them (docs/design.md, "Benchmarks and test matrices"). */
#ifndef SESSILE_MATRIX_GEN_H
#define SESSILE_MATRIX_GEN_H

#include <stdint.h>
#include "sessile/la/matrix.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 7-point finite-difference Laplacian (-∇², scaled by h² so entries are 6, -1)
 * on the n = nx*ny*nz interior nodes of a grid with homogeneous Dirichlet
 * walls eliminated: SPD. Node (i,j,k) has index i + nx*(j + ny*k). */
sessile_status sessile_csr_laplacian7(uint32_t nx, uint32_t ny, uint32_t nz, sessile_csr *out);

/* P1 tetrahedral stiffness + mass (K + M) on the nodes of a box of nx*ny*nz
 * cubes of spacing (hx,hy,hz), each cube cut into the 6 Kuhn tetrahedra
 * around its main diagonal (0,0,0)-(1,1,1).  (nx+1)(ny+1)(nz+1) rows, the
 * 15-point graph (self + 14 neighbours); entries that cancel are stored as
 * explicit zeros so the graph is the full 15-point one.  SPD. */
sessile_status sessile_csr_p1tet(uint32_t nx, uint32_t ny, uint32_t nz, double hx, double hy,
                                 double hz, sessile_csr *out);

/* Central-difference convection-diffusion -∇²u + (w·∇)u on the interior
 * nodes of an nx*ny*nz grid (Dirichlet walls eliminated), scaled by h²,
 * with constant wind w = (1, 0.5, 0.25)·|w| chosen so the cell Péclet number
 * |w|h/2 equals `peclet` along x.  Nonsymmetric. */
sessile_status sessile_csr_convdiff(uint32_t nx, uint32_t ny, uint32_t nz, double peclet,
                                    sessile_csr *out);

/* Random square n*n matrix with about `per_row` entries per row (always the
 * diagonal), values uniform in [-1,1], diagonal made dominant by `dominance`
 * times the row's absolute off-diagonal sum (dominance > 1: nonsingular).
 * Deterministic from `seed`. */
sessile_status sessile_csr_random(uint32_t n, uint32_t per_row, double dominance, uint64_t seed,
                                  sessile_csr *out);

/* Block matrix on the graph of `pattern` (square), blocks random in [-1,1]
 * with diagonal blocks made dominant; deterministic from `seed`.
 * (Each scalar diagonal entry is 2x the absolute sum of the rest of its scalar
 * row; every pattern row must contain its diagonal, else SESSILE_ERR_USAGE.) */
sessile_status sessile_bcsr4_random_on(const sessile_csr *pattern, uint64_t seed,
                                       sessile_bcsr4 *out);

/* The cut-cell sphere problem of the multigrid tests and `sessile bench la`, on an
 * nx*ny*nz vertex grid of spacing h, node (i,j,k) at (i h, j h, k h): a solid sphere
 * (centre, radius), zero-flux side walls, Dirichlet bottom (k = 0) and top (k = nz-1)
 * planes.  Writes mask (1 on nodes inside the sphere or on the bottom or top plane, else 0),
 * diag (the cut-cell diagonal of sessile_mat_create_stencil7_cut, theta from the exact
 * intersection of each grid edge with the sphere, clamped to >= 1e-3; 1 on Dirichlet nodes)
 * and, when b is not NULL, the homogenised right-hand side of u = 1 on the top plane and
 * u = 0 on the sphere and the bottom plane: b_n = h sum f_nm w_nm g_m over the Dirichlet
 * neighbours m of a free node n, 0 on Dirichlet nodes. */
void sessile_cut_sphere(uint32_t nx, uint32_t ny, uint32_t nz, double h, const double centre[3],
                        double radius, uint32_t *mask, double *diag, double *b);
/* Deterministic uniform doubles in [lo,hi) (splitmix64 stream from seed). */
void sessile_fill_random(double *v, uint64_t n, double lo, double hi, uint64_t seed);

#ifdef __cplusplus
}
#endif
#endif
