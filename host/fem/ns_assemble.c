/* The Navier-Stokes residual and Jacobian, assembled in parallel colour by
 * colour, a chunk of consecutive tets per thread at a time (ns_colour.c),
 * into the 4x4 block CSR pattern (ns_graph.c); the element is ns_element.c. */
#include <string.h>

#include "fem/ns_internal.h"

/* Adds tet t's residual to r and, when jac, its Jacobian to fl->a.val. */
static void assemble_tet(sessile_fluid *fl, const sessile_fluid_params *p, const ns_coef *c,
                         const double *up, int jac, uint32_t t, double *r) {
  double Ke[256], Re[16];
  const uint32_t *v = fl->tet + 4 * (size_t)t;
  double X[4][3], U[16], F[4][3];
  for (int a = 0; a < 4; a++)
    for (int i = 0; i < 4; i++) {
      if (i < 3) X[a][i] = fl->x[3 * (size_t)v[a] + i];
      U[4 * a + i] = up[4 * (size_t)v[a] + i];
    }
  if (p->force_fn)
    for (int q = 0; q < 4; q++) {
      double xq[3];
      for (int i = 0; i < 3; i++) {
        xq[i] = NS_QB * (X[0][i] + X[1][i] + X[2][i] + X[3][i]) + (NS_QA - NS_QB) * X[q][i];
      }
      p->force_fn(xq, F[q], p->bc_ctx);
    }
  ns_element((const double(*)[3])X, U, p->force_fn ? (const double(*)[3])F : NULL, c, Re,
             jac ? Ke : NULL);
  for (int a = 0; a < 4; a++) {
    for (int i = 0; i < 4; i++) r[4 * (size_t)v[a] + i] += Re[4 * a + i];
    if (!jac) continue;
    for (int b = 0; b < 4; b++) {
      double *blk = fl->a.val + 16 * (size_t)fl->pos[16 * (size_t)t + 4 * a + b];
      for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) blk[4 * i + j] += Ke[(4 * a + i) * 16 + 4 * b + j];
    }
  }
}

/* Residual r (4 per node) and, when jac, the Jacobian into fl->a.val. */
void ns_assemble(sessile_fluid *fl, const sessile_fluid_params *p, const double *up, double newton,
                 int jac, double *r) {
  ns_coef c = {p->rho, p->eta, p->lsic, newton};
  memset(r, 0, (size_t)fl->nnodes * 4 * sizeof *r);
  if (jac) memset(fl->a.val, 0, (size_t)fl->a.nnzb * 16 * sizeof *fl->a.val);
#pragma omp parallel
  for (uint32_t col = 0; col < fl->ncolours; col++) {
    /* the barrier at each loop's end keeps colours apart */
#pragma omp for schedule(dynamic, 1)
    for (uint32_t k = fl->cstart[col]; k < fl->cstart[col + 1]; k++) {
      uint64_t t0 = (uint64_t)fl->corder[k] * fl->chunk, t1 = t0 + fl->chunk;
      if (t1 > fl->ntets) t1 = fl->ntets;
      for (uint64_t t = t0; t < t1; t++) assemble_tet(fl, p, &c, up, jac, (uint32_t)t, r);
    }
  }
}

sessile_status sessile_fluid_residual(sessile_fluid *fl, const sessile_fluid_params *p,
                                      const double *up, double *r) {
  SESSILE_CHECK(fl && p && up && r, SESSILE_ERR_USAGE,
                "fluid residual needs a solver, parameters, a state and an output");
  ns_assemble(fl, p, up, 1.0, 0, r);
  return SESSILE_OK;
}
