/* The stationary Navier-Stokes solver (O'Hagan et al. §4.2): parameters,
 * creation and destruction.  The pieces: the block pattern (ns_graph.c),
 * the tet colouring (ns_colour.c), the box detection for the multigrid
 * preconditioner (ns_box.c), the assembly (ns_assemble.c, element
 * ns_element.c), the boundary rows (ns_bc.c), the linear solve with la's
 * preconditioners (ns_linear.c) and the Newton loop (ns_newton.c);
 * decisions and measurements are in docs/fluid.md. */
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"

void sessile_fluid_params_default(sessile_fluid_params *p) {
  memset(p, 0, sizeof *p);
  p->rho = 1000.0;
  p->eta = 5.0e-2;
  p->inlet[0] = 0.05;
  p->velocity_tags = SESSILE_TAG_INLET | SESSILE_TAG_SUBSTRATUM | SESSILE_TAG_SPONGE;
  p->noslip_tags = SESSILE_TAG_SUBSTRATUM | SESSILE_TAG_SPONGE;
  p->pressure_tags = SESSILE_TAG_OUTLET;
  p->lsic = 1;
  p->newton_rtol = 1e-3;
  p->newton_max = 100;
  p->picard_steps = 0;
  p->linear_rtol = 1e-6;
  p->linear_max = 100;
  p->forcing = SESSILE_FLUID_FORCING_FIXED;
  p->ksp = SESSILE_KSP_GMRES;
  p->pc = SESSILE_PC_MG; /* 10-12 GMRES iterations per Newton step on the default box
                            (ILU(0): 47-100), 2x faster (docs/fluid.md, "Multigrid") */
  p->restart = 50;
  p->nested = 1;
  sessile_bmg_options_default(&p->mg);
  p->mg.precision = 32; /* the cycle in fp32 inside the fp64 GMRES: 7-19 % faster (docs/fluid.md, "Multigrid") */
  p->mg.pre = p->mg.post = 3; /* W(3,3): 8 GMRES iterations a Newton step at box levels 1 and 2
                                 where W(2,2) took 11 and 14, and less time (docs/fluid.md, "Multigrid") */
}

void sessile_fluid_destroy(sessile_fluid *fl) {
  if (!fl) return;
  sessile_fluid_destroy(fl->nest);
  free(fl->x);
  free(fl->tet);
  free(fl->tags);
  free(fl->pos);
  free(fl->corder);
  free(fl->cstart);
  ns_mg_free(fl);
  sessile_pc_destroy(fl->mgpc);
  sessile_bmg_destroy(fl->bmg);
  sessile_mat_destroy(fl->dev);
  sessile_bcsr4_free(&fl->a);
  free(fl);
}

sessile_status sessile_fluid_create(sessile_la *la, const sessile_tetmesh *m, sessile_fluid **out) {
  *out = NULL;
  SESSILE_CHECK(m && m->nnodes >= 4 && m->ntets >= 1 && m->xyz && m->tet, SESSILE_ERR_USAGE,
                "fluid mesh needs at least one tetrahedron");
  SESSILE_CHECK(m->nnodes <= UINT32_MAX / 4, SESSILE_ERR_TOO_LARGE, "fluid mesh too large");
  for (uint64_t k = 0; k < 4ull * m->ntets; k++)
    SESSILE_CHECK(m->tet[k] < m->nnodes, SESSILE_ERR_USAGE, "tet %llu names node %u of %u",
                  (unsigned long long)(k / 4), m->tet[k], m->nnodes);
  sessile_fluid *fl = calloc(1, sizeof *fl);
  SESSILE_CHECK(fl, SESSILE_ERR_NO_MEMORY, "out of host memory");
  fl->la = la;
  fl->nnodes = m->nnodes;
  fl->ntets = m->ntets;
  fl->x = malloc((size_t)m->nnodes * 3 * sizeof *fl->x);
  fl->tet = malloc((size_t)m->ntets * 4 * sizeof *fl->tet);
  fl->tags = malloc((size_t)m->nnodes * sizeof *fl->tags);
  sessile_status s = SESSILE_OK;
  if (!fl->x || !fl->tet || !fl->tags) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    for (size_t k = 0; k < (size_t)m->nnodes * 3; k++) fl->x[k] = 0.01 * m->xyz[k]; /* cm -> m */
    memcpy(fl->tet, m->tet, (size_t)m->ntets * 4 * sizeof *fl->tet);
    if (m->node_tags) memcpy(fl->tags, m->node_tags, (size_t)m->nnodes * sizeof *fl->tags);
    else memset(fl->tags, 0, (size_t)m->nnodes * sizeof *fl->tags);
    ns_detect_box(fl);
    /* a box keeps its order (the multigrid's); any other mesh is sorted so
     * that consecutive tets are near (ns_colour.c) */
    if (!fl->grid[0]) s = ns_order_tets(fl);
  }
  if (s == SESSILE_OK) s = ns_build_graph(fl);
  if (s == SESSILE_OK) s = ns_build_colours(fl);
  if (s != SESSILE_OK) {
    sessile_fluid_destroy(fl);
    return s;
  }
  *out = fl;
  return SESSILE_OK;
}
