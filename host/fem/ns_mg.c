/* The block multigrid's coarse operators for the fluid: the Newton (or
 * Picard) linearisation rediscretised on each coarse box of the hierarchy
 * (sessile_bmg_set_operator), at the fine state injected (coarse node I is
 * fine node 2^l I), with the solid mask injected likewise and the coarse
 * box's own boundary tags, so each level has the stabilisation (tau, PSPG)
 * of its own spacing.  Galerkin products R A P lose it (their PSPG term is
 * the fine one) and the V-cycle diverged with them beyond two levels
 * (docs/fluid.md, "Multigrid"). */
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"
#include "sessile/mesh/box.h"
#include "sessile/mesh/tetmesh.h"

/* The coarse fluids (once per hierarchy). */
static sessile_status coarse_fluids(sessile_fluid *fl) {
  int nl = sessile_bmg_levels(fl->bmg);
  if (fl->ncoarse == nl - 1) return SESSILE_OK;
  SESSILE_CHECK(nl - 1 <= NS_MG_LEVELS, SESSILE_ERR_INTERNAL, "too many multigrid levels (%d)", nl);
  double h = 100.0 * (fl->x[3] - fl->x[0]); /* cm */
  for (int l = 1; l < nl; l++) {
    sessile_box b = {.origin = {100.0 * fl->x[0], 100.0 * fl->x[1], 100.0 * fl->x[2]}, .h = h * (1 << l)};
    b.n[0] = fl->grid[0], b.n[1] = fl->grid[1], b.n[2] = fl->grid[2];
    for (int k = 0; k < l; k++)
      for (int a = 0; a < 3; a++) b.n[a] = (b.n[a] - 1) / 2 + 1;
    SESSILE_CHECK(sessile_box_nodes(&b) == sessile_bmg_level_nodes(fl->bmg, l), SESSILE_ERR_INTERNAL,
                  "multigrid level %d: box and hierarchy disagree", l);
    sessile_tetmesh m = {0};
    sessile_status s = sessile_tetmesh_from_box(&b, &m);
    if (s == SESSILE_OK) s = sessile_fluid_create(fl->la, &m, &fl->coarse[l - 1]);
    sessile_tetmesh_free(&m);
    SESSILE_CALL(s);
    fl->ncoarse = l;
  }
  return SESSILE_OK;
}

void ns_mg_free(sessile_fluid *fl) {
  for (int l = 0; l < fl->ncoarse; l++) sessile_fluid_destroy(fl->coarse[l]);
  fl->ncoarse = 0;
}

sessile_status ns_mg_operators(sessile_fluid *fl, const sessile_fluid_params *p, const uint8_t *solid,
                               const double *up, double newton) {
  SESSILE_CALL(coarse_fluids(fl));
  sessile_status s = SESSILE_OK;
  for (int l = 1; l <= fl->ncoarse && s == SESSILE_OK; l++) {
    sessile_fluid *c = fl->coarse[l - 1];
    uint32_t n = c->nnodes, g0 = c->grid[0], g1 = c->grid[1], st = 1u << l;
    uint8_t *cs = malloc(n), *bc = malloc(n);
    double *u = malloc((size_t)n * 4 * sizeof *u), *r = malloc((size_t)n * 4 * sizeof *r);
    if (!cs || !bc || !u || !r) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    for (uint32_t i = 0; s == SESSILE_OK && i < n; i++) {
      uint32_t ci = i % g0, cj = (i / g0) % g1, ck = i / (g0 * g1);
      uint32_t f = st * ci + fl->grid[0] * (st * cj + fl->grid[1] * st * ck);
      cs[i] = solid ? solid[f] : 0;
      memcpy(u + 4 * (size_t)i, up + 4 * (size_t)f, 4 * sizeof *u);
    }
    if (s == SESSILE_OK) {
      for (uint32_t i = 0; i < n; i++) bc[i] = ns_node_bc(c, cs, p, i);
      ns_impose_bc(c, cs, p, bc, u);
      ns_assemble(c, p, u, newton, 1, r);
      ns_apply_bc_rows(c, bc, 1, r);
      s = sessile_bmg_set_operator(fl->bmg, l, &c->a);
    }
    free(cs), free(bc), free(u), free(r);
  }
  return s;
}
