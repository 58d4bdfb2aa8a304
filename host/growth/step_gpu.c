/* The per-iteration growth chain on the GPU: normals -> probe -> translocate
 * passes -> grow, recorded in one command buffer (one submit), then the
 * downloads.  The paper's sequential translocation runs on the host between
 * two submits. */
#include <stdlib.h>
#include "growth_internal.h"

sessile_status growth_record_normals(sessile_growth_gpu *g, const sessile_box *box) {
  growth_push p = growth_push_of(g, box);
  sessile_buffer *b[6] = {g->params, g->pos, g->tri, g->vf_off, g->vf, g->nrm};
  return sessile_cmd_dispatch(g->cmd, g->k[GK_NORMALS], growth_groups(g->nv), b, &p);
}

sessile_status sessile_growth_gpu_normals(sessile_growth_gpu *g, double *normals) {
  SESSILE_CHECK(g->nv > 0, SESSILE_ERR_USAGE, "normals: no surface uploaded (call set_surface)");
  /* The normals kernel reads no box parameter: any box will do. */
  sessile_box box = {.h = 1, .n = {2, 2, 2}};
  SESSILE_CALL(sessile_cmd_begin(g->cmd));
  SESSILE_CALL(growth_record_normals(g, &box));
  SESSILE_CALL(sessile_cmd_end(g->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(g->cmd));
  return sessile_buffer_download_reals(g->nrm, 0, normals, 3 * (size_t)g->nv);
}

/* probed -> the paper's sequential sweeps -> ctr[0]. */
static sessile_status translocate_on_host(sessile_growth_gpu *g, const sessile_growth_params *prm) {
  double *c = malloc((size_t)g->nv * sizeof *c);
  SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", g->nv);
  sessile_status st = sessile_buffer_download_reals(g->probed, 0, c, g->nv);
  double cmax = sessile_growth_translocate_cmax(prm);
  for (int sweep = 0; st == SESSILE_OK && sweep < prm->translocate_passes; sweep++)
    sessile_growth_ref_translocate_sequential(g->host_nbr_off, g->host_nbr, g->nv, prm->t_give, cmax, c);
  if (st == SESSILE_OK) st = sessile_buffer_upload_reals(g->ctr[0], 0, c, g->nv);
  free(c);
  return st;
}

sessile_status sessile_growth_gpu_step(sessile_growth_gpu *g, const sessile_box *box,
                                       const sessile_vec *c, const sessile_growth_params *prm,
                                       uint64_t seed, uint32_t iteration, double *new_pos,
                                       double *probed, double *translocated, double *length) {
  SESSILE_CHECK(g->nv > 0, SESSILE_ERR_USAGE, "growth step: no surface uploaded (call set_surface)");
  SESSILE_CALL(sessile_growth_params_check(prm));
  SESSILE_CHECK(sessile_vec_size(c) == sessile_box_nodes(box), SESSILE_ERR_USAGE,
                "growth step: the nutrient field has %u values, the box has %u nodes",
                sessile_vec_size(c), sessile_box_nodes(box));
  growth_set_params(g, box, prm);
  growth_push p = growth_push_of(g, box);
  p.samples = prm->probe_samples;
  p.halichondrid = prm->halichondrid ? 1u : 0u;
  p.seed_lo = (uint32_t)seed;
  p.seed_hi = (uint32_t)(seed >> 32);
  p.iteration = iteration;
  p.probe_flux = prm->probe_flux ? 1u : 0u;
  uint32_t groups = growth_groups(g->nv);

  SESSILE_CALL(sessile_cmd_begin(g->cmd));
  SESSILE_CALL(growth_record_normals(g, box));
  sessile_buffer *bp[5] = {g->params, g->pos, g->nrm, sessile_vec_buffer(c), g->probed};
  SESSILE_CALL(sessile_cmd_dispatch(g->cmd, g->k[GK_PROBE], groups, bp, &p));
  sessile_buffer *cur = g->probed;
  if (prm->translocate_sequential && prm->translocate_passes > 0) {
    /* The paper's sweep depends on the vertex order, one vertex after the
     * other: it runs on the host between the probe and the grow kernel. */
    SESSILE_CALL(sessile_cmd_end(g->cmd));
    SESSILE_CALL(sessile_cmd_submit_wait(g->cmd));
    SESSILE_CALL(translocate_on_host(g, prm));
    SESSILE_CALL(sessile_cmd_begin(g->cmd));
    cur = g->ctr[0];
  }
  /* translocate_passes sweeps, each SESSILE_TRANSLOCATE_SWEEP simultaneous
   * passes (translocate.comp). */
  uint32_t k = 0;
  for (int sweep = 0; sweep < (prm->translocate_sequential ? 0 : prm->translocate_passes); sweep++)
    for (int pass = 0; pass < SESSILE_TRANSLOCATE_SWEEP; pass++, k++) {
      sessile_buffer *dst = g->ctr[k & 1];
      sessile_buffer *bt[5] = {g->params, g->nbr_off, g->nbr, cur, dst};
      SESSILE_CALL(sessile_cmd_dispatch(g->cmd, g->k[GK_TRANSLOCATE], groups, bt, &p));
      cur = dst;
    }
  sessile_buffer *bg[7] = {g->params, g->pos, g->nrm, cur, g->new_pos, g->len, g->dir};
  SESSILE_CALL(sessile_cmd_dispatch(g->cmd, g->k[GK_GROW], groups, bg, &p));
  SESSILE_CALL(sessile_cmd_end(g->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(g->cmd));

  size_t nv = g->nv;
  SESSILE_CALL(sessile_buffer_download_reals(g->new_pos, 0, new_pos, 3 * nv));
  if (probed) SESSILE_CALL(sessile_buffer_download_reals(g->probed, 0, probed, nv));
  if (translocated) SESSILE_CALL(sessile_buffer_download_reals(cur, 0, translocated, nv));
  if (length) SESSILE_CALL(sessile_buffer_download_reals(g->len, 0, length, nv));
  return SESSILE_OK;
}

sessile_status sessile_growth_gpu_directions(sessile_growth_gpu *g, double *dir) {
  SESSILE_CHECK(g->nv > 0, SESSILE_ERR_USAGE, "directions: no surface uploaded (call set_surface)");
  return sessile_buffer_download_reals(g->dir, 0, dir, 3 * (size_t)g->nv);
}
