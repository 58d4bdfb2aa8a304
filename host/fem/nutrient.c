/* The stationary nutrient field (O'Hagan et al. §4.3, eq 5 with u = 0,
 * "diffusion limited"): -Laplace c = 0 by P1 elements on the Kuhn box, solved
 * matrix-free on the GPU.  On the uniform Kuhn box the assembled P1 stiffness
 * is the 7-point stencil times h (tests/fem/test_nutrient.c checks it element
 * by element), so the operator is sessile_mat_create_stencil7 with the solid
 * mask as its Dirichlet mask, and PCG runs on it directly.
 *
 * Symmetric Dirichlet elimination, homogenised: with c = u + g (g the
 * Dirichlet data on Dirichlet nodes, 0 elsewhere) the solve is A u = b with
 * u = 0 and b = 0 on Dirichlet nodes and b = -K_fD g on free ones.  The warm
 * start is the caller's c on the free nodes.  The reported residual is thus
 * that of the free rows alone, not diluted by the trivially satisfied
 * Dirichlet rows (docs/fem.md). */
#include <stdlib.h>
#include "fem_kernels.h"
#include "sessile/fem/nutrient.h"

struct sessile_nutrient {
  sessile_la *la;
  sessile_box box;
  sessile_kernel *bc;  /* shaders/fem/dirichlet.comp */
  sessile_cmd *cmd;
  sessile_vec *walls;  /* the nutrient's wall values */
  sessile_vec *b;      /* right-hand side of the homogenised system */
};

static sessile_status nutrient_init(sessile_nutrient *nt) {
  sessile_gpu *g = sessile_la_gpu(nt->la);
  uint32_t n = sessile_box_nodes(&nt->box);
  SESSILE_CALL(sessile_kernel_create_decl(g, &sessile_fem_kernels[FK_DIRICHLET],
                                          sessile_la_real_bytes(nt->la), 0, &nt->bc));
  SESSILE_CALL(sessile_cmd_create(g, &nt->cmd));
  SESSILE_CALL(sessile_vec_create(nt->la, n, &nt->walls));
  SESSILE_CALL(sessile_vec_create(nt->la, n, &nt->b));
  double *w = malloc((size_t)n * sizeof *w);
  SESSILE_CHECK(w, SESSILE_ERR_NO_MEMORY, "out of host memory");
  const sessile_box *b = &nt->box;
  for (uint32_t k = 0; k < b->n[2]; k++)
    for (uint32_t j = 0; j < b->n[1]; j++)
      for (uint32_t i = 0; i < b->n[0]; i++)
        w[sessile_box_index(b, i, j, k)] = sessile_nutrient_wall_value(b, i, j, k);
  sessile_status s = sessile_vec_upload(nt->walls, w);
  free(w);
  return s;
}

sessile_status sessile_nutrient_create(sessile_la *la, const sessile_box *box,
                                       sessile_nutrient **out) {
  *out = NULL;
  SESSILE_CHECK(box->n[0] >= 3 && box->n[1] >= 3 && box->n[2] >= 3, SESSILE_ERR_USAGE,
                "nutrient box needs at least 3 nodes per axis (got %u x %u x %u)", box->n[0],
                box->n[1], box->n[2]);
  sessile_nutrient *nt = calloc(1, sizeof *nt);
  SESSILE_CHECK(nt, SESSILE_ERR_NO_MEMORY, "out of host memory");
  nt->la = la;
  nt->box = *box;
  sessile_status s = nutrient_init(nt);
  if (s != SESSILE_OK) {
    sessile_nutrient_destroy(nt);
    return s;
  }
  *out = nt;
  return SESSILE_OK;
}

void sessile_nutrient_destroy(sessile_nutrient *nt) {
  if (!nt) return;
  sessile_vec_destroy(nt->b);
  sessile_vec_destroy(nt->walls);
  sessile_cmd_destroy(nt->cmd);
  sessile_kernel_destroy(nt->bc);
  free(nt);
}

/* One pass of dirichlet.comp: mode 0 lifts (b, homogenised c), 1 restores. */
static sessile_status run_bc(sessile_nutrient *nt, uint32_t mode, sessile_buffer *mask,
                             const sessile_vec *g, sessile_vec *c, int zero_masked) {
  const sessile_box *b = &nt->box;
  dir_push p = {.n0 = b->n[0], .n1 = b->n[1], .n2 = b->n[2], .mode = mode,
                .zero_masked = (uint32_t)zero_masked,
                .h = sessile_push_real_of(b->h, sessile_la_real_bytes(nt->la))};
  sessile_buffer *bufs[4] = {mask, sessile_vec_buffer(g), sessile_vec_buffer(c),
                             sessile_vec_buffer(nt->b)};
  uint32_t n = sessile_box_nodes(b), local = sessile_kernel_local_size(nt->bc);
  SESSILE_CALL(sessile_cmd_begin(nt->cmd));
  SESSILE_CALL(sessile_cmd_dispatch(nt->cmd, nt->bc, (n + local - 1) / local, bufs, &p));
  SESSILE_CALL(sessile_cmd_end(nt->cmd));
  return sessile_cmd_submit_wait(nt->cmd);
}

static sessile_status solve(sessile_nutrient *nt, sessile_buffer *mask, const sessile_vec *g,
                            int zero_masked, sessile_vec *c, const sessile_ksp_options *opt,
                            sessile_solve_result *res) {
  const sessile_box *b = &nt->box;
  uint32_t n = sessile_box_nodes(b);
  SESSILE_CHECK(sessile_vec_size(c) == n && sessile_vec_size(g) == n, SESSILE_ERR_USAGE,
                "nutrient field has %u entries, Dirichlet values %u, the box %u nodes",
                sessile_vec_size(c), sessile_vec_size(g), n);
  SESSILE_CHECK(mask && sessile_buffer_size(mask) >= (size_t)n * 4, SESSILE_ERR_USAGE,
                "solid mask must hold %u uint32 (one per box node), has %zu bytes", n,
                mask ? sessile_buffer_size(mask) : (size_t)0);
  double t0 = sessile_wall_seconds();
  sessile_mat *a = NULL;
  SESSILE_CALL(sessile_mat_create_stencil7(nt->la, b->n[0], b->n[1], b->n[2], b->h, mask, &a));
  sessile_status s = run_bc(nt, 0, mask, g, c, zero_masked);
  if (s == SESSILE_OK) s = sessile_ksp_solve(nt->la, opt, a, nt->b, c, res);
  if (s == SESSILE_OK) s = run_bc(nt, 1, mask, g, c, zero_masked);
  sessile_mat_destroy(a);
  if (s == SESSILE_OK) res->seconds = sessile_wall_seconds() - t0;
  return s;
}

sessile_status sessile_nutrient_solve(sessile_nutrient *nt, sessile_buffer *solid,
                                      sessile_vec *c, const sessile_ksp_options *opt,
                                      sessile_solve_result *res) {
  return solve(nt, solid, nt->walls, 1, c, opt, res);
}

sessile_status sessile_nutrient_solve_dirichlet(sessile_nutrient *nt, sessile_buffer *mask,
                                                const sessile_vec *values, sessile_vec *c,
                                                const sessile_ksp_options *opt,
                                                sessile_solve_result *res) {
  return solve(nt, mask, values, 0, c, opt, res);
}
