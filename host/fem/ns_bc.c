/* Navier-Stokes boundary conditions: which nodes carry Dirichlet values,
 * the values, and the identity rows of the Jacobian (blocks stay 4x4). */
#include <math.h>

#include "fem/ns_internal.h"

/* Dirichlet flags per node: bit 0 velocity, bit 1 pressure. */
uint8_t ns_node_bc(const sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                   uint32_t i) {
  uint8_t f = 0;
  if ((fl->tags[i] & p->velocity_tags) || (solid && solid[i])) f |= 1;
  if (fl->tags[i] & p->pressure_tags) f |= 2;
  return f;
}

/* Writes the Dirichlet values into up. */
void ns_impose_bc(const sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                  const uint8_t *bc, double *up) {
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    const double *x = fl->x + 3 * (size_t)i;
    if (bc[i] & 1) {
      double u[3] = {0, 0, 0};
      int solid_node = solid && solid[i];
      if (solid_node) { /* immersed sponge: no-slip */
      } else if (p->velocity_fn) p->velocity_fn(x, fl->tags[i], u, p->bc_ctx);
      else if (!(fl->tags[i] & p->noslip_tags))
        for (int k = 0; k < 3; k++) u[k] = p->inlet[k];
      for (int k = 0; k < 3; k++) up[4 * (size_t)i + k] = u[k];
    }
    if (bc[i] & 2) up[4 * (size_t)i + 3] = p->pressure_fn ? p->pressure_fn(x, fl->tags[i], p->bc_ctx) : 0.0;
  }
}

/* Zeroes the residual's Dirichlet rows (their values are imposed) and, when
 * jac, makes them identity rows; returns ||r|| of the rest. */
double ns_apply_bc_rows(sessile_fluid *fl, const uint8_t *bc, int jac, double *r) {
  double ss = 0;
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    for (int k = 0; k < 4; k++) {
      int fixed = (k < 3) ? (bc[i] & 1) : (bc[i] & 2);
      if (fixed) r[4 * (size_t)i + k] = 0;
      else ss += r[4 * (size_t)i + k] * r[4 * (size_t)i + k];
      if (!fixed || !jac) continue;
      for (uint64_t e = fl->a.rowptr[i]; e < fl->a.rowptr[i + 1]; e++) {
        double *row = fl->a.val + 16 * e + 4 * k;
        row[0] = row[1] = row[2] = row[3] = 0;
        if (fl->a.col[e] == i) row[k] = 1.0;
      }
    }
  }
  return sqrt(ss);
}
