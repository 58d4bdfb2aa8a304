/* sessile — the stationary incompressible Navier-Stokes flow of the water
 * around the sponge (O'Hagan et al. §4.2, eqs 3-4 with du/dt = 0, F = 0).
 *
 * Equal-order P1-P1 tetrahedra with SUPG/PSPG (+ LSIC) stabilisation: one
 * block of 4 unknowns (ux, uy, uz, p) per mesh node.  The Newton Jacobian and
 * residual are assembled on the host into a 4x4 block-CSR matrix; each Newton
 * linear system is solved on the GPU by la's Krylov solvers (docs/fluid.md).
 *
 * Units: the mesh is in centimetres; the flow is solved in SI (positions
 * scaled by 0.01 to metres): velocities in m/s, pressure in Pa, rho in
 * kg/m^3, eta in Pa s, body forces in N/m^3.
 *
 * Boundary conditions (defaults; the tag sets are parameters):
 *  - velocity Dirichlet on nodes tagged INLET (u = inlet velocity) and
 *    SUBSTRATUM / SPONGE (no-slip), and on every node of the solid mask
 *    (immersed sponge, u = 0); a node with both no-slip and inlet tags is
 *    no-slip;
 *  - p = 0 imposed strongly on OUTLET nodes (their continuity row replaced);
 *  - every face without a velocity condition gets the natural "do-nothing"
 *    condition of the Laplacian form, eta du/dn - p n = 0 (zero viscous
 *    stress with the ambient pressure 0).
 * Dirichlet rows are identity rows of the block system (blocks stay 4x4).
 *
 * Ownership: sessile_fluid keeps a pointer to the la (which must outlive it)
 * and a copy of the mesh's connectivity. */
#ifndef SESSILE_FLUID_H
#define SESSILE_FLUID_H

#include <stdint.h>
#include "sessile/la/bmg.h"
#include "sessile/la/la.h"
#include "sessile/mesh/tetmesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_fluid sessile_fluid;

/* Optional boundary data (tests, other scenes): x in metres, tags the node's
 * SESSILE_TAG_* bits (0 for a solid-mask node off the boundary), ctx the
 * params' bc_ctx. */
typedef void (*sessile_fluid_velocity_fn)(const double x[3], uint32_t tags, double u[3], void *ctx);
typedef double (*sessile_fluid_pressure_fn)(const double x[3], uint32_t tags, void *ctx);
/* Optional body force f (N/m^3) at x (metres); the paper has F = 0. */
typedef void (*sessile_fluid_force_fn)(const double x[3], double f[3], void *ctx);

/* How tightly each Newton step's linear system is solved.  FIXED: to
 * linear_rtol every step (the paper's 1e-6).  EW: Eisenstat and Walker's
 * choice 2 (SIAM J. Sci. Comput. 17, 1996), with PETSc's defaults: 0.3 on the
 * first step, then (|R_k| / |R_k-1|)^1.618, kept at least eta_k-1^1.618
 * when that exceeds 0.1, at most 0.9 and at least linear_rtol: loose while
 * the residual falls slowly, tight as Newton converges.  The stopping rule is
 * the same newton_rtol either way. */
typedef enum { SESSILE_FLUID_FORCING_FIXED = 0, SESSILE_FLUID_FORCING_EW = 1 } sessile_fluid_forcing;

typedef struct sessile_fluid_params {
  double rho;          /* kg/m^3, default 1000 (0: Stokes flow, no convection) */
  double eta;          /* Pa s, default 5.0e-2 */
  double inlet[3];     /* m/s, default (0.05, 0, 0) */
  uint32_t velocity_tags; /* Dirichlet velocity faces, default INLET|SUBSTRATUM|SPONGE */
  uint32_t noslip_tags;   /* of those, u = 0 (default SUBSTRATUM|SPONGE) */
  uint32_t pressure_tags; /* p imposed (default OUTLET, p = 0) */
  int lsic;            /* grad-div (LSIC) stabilisation on (default 1) */
  double newton_rtol;  /* on ||R|| / ||R(u0)||, default 1e-3 */
  int newton_max;      /* default 100 (Table 1 "max nvs iterations") */
  double max_seconds;  /* wall-clock bound of one solve (0: none, the default); past it, after
                          5 Newton steps running without a residual decrease, and when 20
                          steps leave the residual above 10 newton_rtol of the rest state's
                          (Newton converges in ~6 from rest when it converges), the solve
                          fails with SESSILE_ERR_NUMERIC and a message */
  int picard_steps;    /* Picard (Oseen) steps before Newton, default 0 */
  double newton_atol;  /* stop also when ||R|| <= atol (default 0) */
  double linear_rtol;  /* default 1e-6; with forcing EW the floor of each step's tolerance */
  sessile_fluid_forcing forcing; /* each Newton step's linear tolerance: FIXED (linear_rtol,
                          the paper's; the default) or EW (Eisenstat-Walker, docs/fluid.md) */
  int linear_max;      /* default 100 */
  sessile_ksp_type ksp;/* default GMRES */
  sessile_pc_type pc;  /* la's preconditioner (sessile/la/pc.h), default MG; ILU0:
                          Jacobi is used instead on a matrix stored in several
                          chunks (la's ILU(0) needs one); BLOCK_JACOBI inverts
                          each node's 4x4 diagonal block (couples u and p);
                          MG is the block multigrid W-cycle (sessile/la/bmg.h)
                          on a structured box mesh (sessile_tetmesh_from_box),
                          ILU(0) on any other */
  sessile_bmg_options mg; /* pc MG's options (default sessile_bmg_options_default) */
  int mg_galerkin;     /* pc MG: Galerkin coarse operators R A P instead of the
                          rediscretised linearisation (default 0; comparisons) */
  int restart;         /* GMRES(m), default 50 */
  int nested;          /* on a box mesh whose grid halves to at least 1000 nodes, a start
                          whose residual is above a fifth of the rest state's (from rest, or
                          a growth step's warm start) is replaced by the solution on the box
                          of twice the spacing (solved the same way, recursively),
                          interpolated, when that has the smaller residual (default 1;
                          docs/fluid.md, "Nested start") */
  /* Progress: one line per Newton/Picard step and one at the end (and the
   * check_linear lines) to monitor(monitor_user, line); NULL (default):
   * silent.  The library itself never prints. */
  sessile_monitor_fn monitor;
  void *monitor_user;
  int check_linear;    /* after each linear solve, recompute |J du + r|/|r| on
                          the host in double and report it through monitor
                          (diagnostics; default 0) */
  /* Optional: Dirichlet values other than the defaults above, and a force. */
  sessile_fluid_velocity_fn velocity_fn;
  sessile_fluid_pressure_fn pressure_fn;
  sessile_fluid_force_fn force_fn;
  void *bc_ctx;
} sessile_fluid_params;

void sessile_fluid_params_default(sessile_fluid_params *p);

enum { SESSILE_FLUID_MAX_STEPS = 128 };

typedef struct sessile_fluid_step {
  double residual;       /* ||R|| of the free rows before this step's update */
  int picard;            /* 1 for a Picard step */
  double step_length;    /* backtracking factor taken (1 = full Newton step) */
  int lin_iterations;
  double lin_rtol;       /* the relative tolerance it aimed at (params.forcing) */
  double lin_relres;     /* true relative residual of the linear solve */
  sessile_solve_status lin_status;
  sessile_ksp_type lin_ksp; /* the Krylov method used (params.ksp) */
  sessile_pc_type lin_pc;  /* the preconditioner used (see params.pc) */
  uint32_t lin_chunks;     /* row chunks the block matrix was stored in (la) */
  double assembly_s, solve_s;
  double pc_setup_s;       /* of solve_s: the preconditioner's setup (host factors,
                              Galerkin products, uploads) */
} sessile_fluid_step;

typedef struct sessile_fluid_result {
  int nsteps;                 /* Newton/Picard updates taken */
  sessile_fluid_step step[SESSILE_FLUID_MAX_STEPS];
  double residual0, residual; /* initial and final ||R|| */
  double residual_rest;       /* ||R|| of the rest state (boundary values,
                                 zero elsewhere): Newton's reference */
  int converged;
  int lin_iterations;         /* totals */
  double assembly_s, solve_s, seconds;
  /* The nested start (params.nested): tried when coarse_tried; its solve's
   * Newton steps, linear iterations and seconds (its own coarser ones
   * included); started_coarse when it was taken. */
  int coarse_tried, started_coarse, coarse_steps, coarse_lin_iterations;
  double coarse_seconds;
} sessile_fluid_result;

sessile_status sessile_fluid_create(sessile_la *la, const sessile_tetmesh *mesh, sessile_fluid **out);
void sessile_fluid_destroy(sessile_fluid *fl);

/* Solves for up (4 per node: ux, uy, uz in m/s, p in Pa): warm start in,
 * solution out.  Converged when ||R|| <= newton_rtol * ||R(rest)||, the
 * residual of the rest state (the boundary values with zero velocity and
 * pressure elsewhere): from rest that is the paper's relative tolerance, and
 * a warm start stops at the same absolute accuracy instead of chasing 1e-3
 * of an already small residual (docs/fluid.md).  solid (nnodes, non-zero = solid) may be NULL.  Returns
 * SESSILE_OK whenever the iteration ran; res->converged says whether Newton
 * met its tolerance.  Non-finite residuals are SESSILE_ERR_NUMERIC. */
sessile_status sessile_fluid_solve(sessile_fluid *fl, const uint8_t *solid,
                                   const sessile_fluid_params *p, double *up,
                                   sessile_fluid_result *res);

/* The residual R(up) of the momentum rows (4 per node, continuity in slot 3)
 * with no boundary rows replaced: at Dirichlet velocity nodes it is the
 * reaction, the force (N) the wall exerts on the fluid.  Drag on a body =
 * minus the sum over its nodes. */
sessile_status sessile_fluid_residual(sessile_fluid *fl, const sessile_fluid_params *p,
                                      const double *up, double *r);

/* The linear system of a Newton step (picard = 0) or a Picard (Oseen) step
 * (picard = 1) at the state up (its boundary values imposed on a copy):
 * the Jacobian with the Dirichlet rows as unit rows into jac (allocated
 * here; free with sessile_bcsr4_free) and, when rhs is not NULL, -R (4 per
 * node, zero on the Dirichlet rows).  Tests and other solvers use it. */
sessile_status sessile_fluid_jacobian(sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                                      const double *up, int picard, sessile_bcsr4 *jac, double *rhs);

#ifdef __cplusplus
}
#endif
#endif
