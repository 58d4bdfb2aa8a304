/* The linear systems of the Newton (or Picard) steps as a copy, for tests
 * and for other solvers: J at a state with the boundary rows, and -R. */
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"

sessile_status sessile_fluid_jacobian(sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                                      const double *up, int picard, sessile_bcsr4 *jac, double *rhs) {
  SESSILE_CHECK(fl && p && up && jac, SESSILE_ERR_USAGE, "fluid jacobian needs a solver, parameters, a state and an output");
  memset(jac, 0, sizeof *jac);
  size_t n4 = (size_t)fl->nnodes * 4;
  uint8_t *bc = malloc(fl->nnodes);
  double *u = malloc(n4 * sizeof *u), *r = malloc(n4 * sizeof *r);
  sessile_status s = bc && u && r ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    memcpy(u, up, n4 * sizeof *u);
    for (uint32_t i = 0; i < fl->nnodes; i++) bc[i] = ns_node_bc(fl, solid, p, i);
    ns_impose_bc(fl, solid, p, bc, u);
    ns_assemble(fl, p, u, picard ? 0.0 : 1.0, 1, r);
    ns_apply_bc_rows(fl, bc, 1, r);
    s = sessile_bcsr4_alloc(fl->a.nbrows, fl->a.nbcols, fl->a.nnzb, jac);
  }
  if (s == SESSILE_OK) {
    memcpy(jac->rowptr, fl->a.rowptr, ((size_t)fl->a.nbrows + 1) * sizeof *jac->rowptr);
    memcpy(jac->col, fl->a.col, (size_t)fl->a.nnzb * sizeof *jac->col);
    memcpy(jac->val, fl->a.val, (size_t)fl->a.nnzb * 16 * sizeof *jac->val);
    if (rhs)
      for (size_t k = 0; k < n4; k++) rhs[k] = -r[k];
  }
  free(bc), free(u), free(r);
  return s;
}
