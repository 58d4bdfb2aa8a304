/* The conforming flow of the growth loop: TetGen's mesh of the box minus the
 * current sponge (host/mesh/tetgen_*), the stationary Navier-Stokes solve on
 * it (host/fem), and the transfer of the flow to the nutrient box's nodes by
 * the uniform-grid point locator on the GPU (shaders/mesh/locate.comp):
 * ~200 000 box nodes per iteration, each a bin scan and a barycentric
 * interpolation.  The small warm-start transfer (old conforming mesh to the
 * new one, a few thousand nodes) uses the same kernel.  docs/conforming.md. */
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"
#include "sessile/mesh/locate.h"
#include "sessile/mesh/tetgen.h"

/* The P1 interpolant of the 4 nodal fields f4 (ux, uy, uz, p interleaved,
 * 4 per node of loc's mesh) at the n points pts (3 n, cm), on the GPU:
 * out4 (4 n) and *outside, the points in no tet (they get 0). */
static sessile_status interp_gpu(grow_run *r, const sessile_locator *loc, const double *f4,
                                 uint32_t nnodes, const double *pts, uint32_t n, double *out4,
                                 uint32_t *outside) {
  const size_t rb = sessile_gpu_info_of(r->gpu)->precision == 64 ? 8 : 4;
  sessile_locate_gpu *lg = NULL;
  sessile_buffer *bp = NULL, *bt = NULL, *bf[4] = {0}, *bv[4] = {0};
  sessile_cmd *cmd = NULL;
  double *tmp = malloc((size_t)(nnodes > n ? nnodes : n) * sizeof *tmp);
  uint32_t *tets = malloc((size_t)n * sizeof *tets);
  sessile_status s = tmp && tets ? SESSILE_OK
                                 : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the flow transfer");
  if (s == SESSILE_OK) s = sessile_locate_gpu_create(r->gpu, loc, &lg);
  if (s == SESSILE_OK) s = sessile_buffer_create(r->gpu, 3 * (size_t)n * rb, SESSILE_BUFFER_DEVICE, &bp);
  if (s == SESSILE_OK) s = sessile_buffer_create(r->gpu, (size_t)n * 4, SESSILE_BUFFER_DEVICE, &bt);
  for (int a = 0; a < 4 && s == SESSILE_OK; a++) {
    s = sessile_buffer_create(r->gpu, (size_t)nnodes * rb, SESSILE_BUFFER_DEVICE, &bf[a]);
    if (s == SESSILE_OK) s = sessile_buffer_create(r->gpu, (size_t)n * rb, SESSILE_BUFFER_DEVICE, &bv[a]);
    for (uint32_t i = 0; s == SESSILE_OK && i < nnodes; i++) tmp[i] = f4[4 * (size_t)i + a];
    if (s == SESSILE_OK) s = sessile_buffer_upload_reals(bf[a], 0, tmp, nnodes);
  }
  if (s == SESSILE_OK) s = sessile_buffer_upload_reals(bp, 0, pts, 3 * (size_t)n);
  if (s == SESSILE_OK) s = sessile_cmd_create(r->gpu, &cmd);
  if (s == SESSILE_OK) s = sessile_cmd_begin(cmd);
  for (int a = 0; a < 4 && s == SESSILE_OK; a++)
    s = sessile_locate_gpu_record(lg, cmd, bp, n, bf[a], bv[a], bt, 0.0);
  if (s == SESSILE_OK) s = sessile_cmd_end(cmd);
  if (s == SESSILE_OK) s = sessile_cmd_submit_wait(cmd);
  for (int a = 0; a < 4 && s == SESSILE_OK; a++) {
    s = sessile_buffer_download_reals(bv[a], 0, tmp, n);
    for (uint32_t i = 0; s == SESSILE_OK && i < n; i++) out4[4 * (size_t)i + a] = tmp[i];
  }
  if (s == SESSILE_OK) s = sessile_buffer_download(bt, 0, tets, (size_t)n * 4);
  if (s == SESSILE_OK) {
    *outside = 0;
    for (uint32_t i = 0; i < n; i++) *outside += tets[i] == SESSILE_LOCATE_OUTSIDE;
  }
  sessile_cmd_destroy(cmd);
  for (int a = 0; a < 4; a++) sessile_buffer_destroy(bf[a]), sessile_buffer_destroy(bv[a]);
  sessile_buffer_destroy(bp);
  sessile_buffer_destroy(bt);
  sessile_locate_gpu_destroy(lg);
  free(tmp);
  free(tets);
  return s;
}

sessile_status grow_flow_conforming(grow_run *r, sessile_fluid_result *res, cJSON *fl, int *fell_back) {
  *fell_back = 0;
  sessile_tetgen_options to;
  sessile_tetgen_options_default(&to);
  to.radius_edge = r->p->conforming_quality;
  to.size_far = r->p->conforming_size_far;
  sessile_tetmesh m = {0};
  double t0 = sessile_wall_seconds();
  sessile_status s = sessile_tetgen_conforming(&r->box, &r->surf, &to, &m);
  cJSON_AddNumberToObject(fl, "tetgen_seconds", sessile_wall_seconds() - t0);
  if (s != SESSILE_OK) {
    /* Fall back to the immersed domain only where the sponge's geometry was
     * refused (TetGen's verdict on the input: SESSILE_ERR_NUMERIC; a vertex
     * outside the box or on a box edge: SESSILE_ERR_USAGE).  Out of memory,
     * TetGen's internal errors and anything else stop the run. */
    if (s != SESSILE_ERR_NUMERIC && s != SESSILE_ERR_USAGE) return s;
    *fell_back = 1;
    cJSON_AddStringToObject(fl, "fallback", sessile_error_message());
    return SESSILE_OK;
  }
  cJSON_AddNumberToObject(fl, "tetrahedra", m.ntets);
  /* Warm start: the previous conforming flow interpolated onto the new mesh
   * (nodes that were inside the old sponge start at rest). */
  double *up = calloc((size_t)m.nnodes * 4, sizeof *up);
  sessile_locator *loc = NULL;
  uint32_t outside = 0;
  if (!up) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the conforming flow");
  if (s == SESSILE_OK && r->cup && r->cmesh.nnodes) {
    s = sessile_locator_build(&r->cmesh, 0, &loc);
    if (s == SESSILE_OK) s = interp_gpu(r, loc, r->cup, r->cmesh.nnodes, m.xyz, m.nnodes, up, &outside);
    sessile_locator_destroy(loc);
    loc = NULL;
  }
  sessile_fluid *fluid = NULL;
  sessile_fluid_params fp;
  grow_fluid_params(r, &fp);
  if (s == SESSILE_OK) s = sessile_fluid_create(r->la, &m, &fluid);
  if (s == SESSILE_OK) s = sessile_fluid_solve(fluid, NULL, &fp, up, res);
  sessile_fluid_destroy(fluid);
  if (s != SESSILE_OK) {
    free(up);
    sessile_tetmesh_free(&m);
    return s;
  }
  /* Keep this mesh and flow for the next warm start. */
  sessile_tetmesh_free(&r->cmesh);
  r->cmesh = m;
  free(r->cup);
  r->cup = up;
  /* To the nutrient box's nodes: zero inside the sponge (outside the water). */
  uint32_t nb = sessile_box_nodes(&r->box);
  double *xb = malloc((size_t)nb * 3 * sizeof *xb), *v4 = malloc((size_t)nb * 4 * sizeof *v4);
  if (!xb || !v4) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for the flow transfer");
  for (uint32_t i = 0; s == SESSILE_OK && i < nb; i++) sessile_box_node_pos(&r->box, i, xb + 3 * (size_t)i);
  double t1 = sessile_wall_seconds();
  if (s == SESSILE_OK) s = sessile_locator_build(&r->cmesh, 0, &loc);
  if (s == SESSILE_OK) s = interp_gpu(r, loc, r->cup, r->cmesh.nnodes, xb, nb, v4, &outside);
  for (uint32_t i = 0; s == SESSILE_OK && i < nb; i++) {
    memcpy(r->ufine + 3 * (size_t)i, v4 + 4 * (size_t)i, 3 * sizeof *v4);
    r->pfine[i] = v4[4 * (size_t)i + 3];
  }
  if (s == SESSILE_OK) {
    cJSON_AddNumberToObject(fl, "transfer_seconds", sessile_wall_seconds() - t1);
    cJSON_AddNumberToObject(fl, "box_nodes_outside_water", outside);
  }
  sessile_locator_destroy(loc);
  free(xb);
  free(v4);
  r->flow_domain = "conforming";
  return s;
}
