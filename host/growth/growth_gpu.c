/* The growth kernels' context: kernels, parameter buffer, the uploaded
 * surface and the conversions between host doubles and the stored REAL. */
#include <stdlib.h>
#include <string.h>
#include "growth_internal.h"

void sessile_growth_gpu_destroy(sessile_growth_gpu *g) {
  if (!g) return;
  for (int i = 0; i < GK_COUNT; i++) sessile_kernel_destroy(g->k[i]);
  sessile_cmd_destroy(g->cmd);
  sessile_buffer *bufs[] = {g->params, g->status, g->pos, g->tri, g->vf_off, g->vf, g->nbr_off,
                            g->nbr, g->nrm, g->probed, g->ctr[0], g->ctr[1], g->new_pos,
                            g->len, g->dir, g->col_off[0], g->col_off[1], g->col_off[2],
                            g->col_tri[0], g->col_tri[1], g->col_tri[2], g->theta_dummy};
  for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++) sessile_buffer_destroy(bufs[i]);
  free(g->host_nbr_off), free(g->host_nbr);
  free(g);
}

sessile_status sessile_growth_gpu_create(sessile_la *la, sessile_growth_gpu **out) {
  *out = NULL;
  sessile_growth_gpu *g = calloc(1, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory");
  g->la = la;
  g->gpu = sessile_la_gpu(la);
  g->real_bytes = sessile_la_real_bytes(la);
  sessile_status s = SESSILE_OK;
  for (int i = 0; i < GK_COUNT && s == SESSILE_OK; i++)
    s = sessile_kernel_create_decl(g->gpu, &sessile_growth_kernels[i], g->real_bytes, 0, &g->k[i]);
  if (s == SESSILE_OK) s = sessile_cmd_create(g->gpu, &g->cmd);
  if (s == SESSILE_OK)
    s = sessile_buffer_create(g->gpu, 32 * 8, SESSILE_BUFFER_MAPPED, &g->params);
  if (s == SESSILE_OK) s = sessile_buffer_create(g->gpu, 16, SESSILE_BUFFER_MAPPED, &g->status);
  if (s != SESSILE_OK) {
    sessile_growth_gpu_destroy(g);
    return s;
  }
  *out = g;
  return SESSILE_OK;
}

uint32_t growth_groups(uint32_t items) { return (items + GROWTH_LOCAL - 1) / GROWTH_LOCAL; }

void growth_set_params(sessile_growth_gpu *g, const sessile_box *box, const sessile_growth_params *p) {
  double v[P_COUNT] = {0};
  double mx[3];
  sessile_box_max(box, mx);
  for (int a = 0; a < 3; a++) v[P_OX + a] = box->origin[a], v[P_MX + a] = mx[a];
  v[P_H] = box->h;
  if (p && p->ceiling > 0 && p->ceiling < v[P_MZ]) v[P_MZ] = p->ceiling;
  if (p) {
    v[P_DELTA] = p->probe_distance;
    v[P_FLUXREF] = p->flux_ref;
    v[P_CMAX] = sessile_growth_translocate_cmax(p);
    v[P_OFFSET] = p->probe_offset;
    v[P_TGIVE] = p->t_give;
    v[P_NTHR] = p->nutrient_threshold;
    v[P_GTHR] = p->growth_threshold;
    v[P_GR] = p->growth_rate;
    v[P_LMAX] = p->l_max;
    v[P_N] = p->kinetic_order;
    v[P_K] = p->growth_constant;
    v[P_MAXG] = p->max_growth;
    v[P_R] = p->normal_offset_radius;
  }
  void *dst = sessile_buffer_host_ptr(g->params);
  if (g->real_bytes == 8) {
    memcpy(dst, v, sizeof v);
  } else {
    float *f = dst;
    for (int i = 0; i < P_COUNT; i++) f[i] = (float)v[i];
  }
}

growth_push growth_push_of(const sessile_growth_gpu *g, const sessile_box *box) {
  growth_push p = {.nv = g->nv, .nf = g->nf, .n0 = box->n[0], .n1 = box->n[1], .n2 = box->n[2]};
  p.ncols = box->n[0] * box->n[1];
  return p;
}

sessile_status growth_ensure(sessile_growth_gpu *g, sessile_buffer **b, size_t bytes) {
  return sessile_buffer_reserve(g->gpu, b, bytes < 16 ? 16 : bytes, SESSILE_BUFFER_DEVICE);
}

/* The uploaded surface and its per-vertex work buffers, sized exactly. */
sessile_status sessile_growth_gpu_set_surface(sessile_growth_gpu *g, const sessile_surface *s) {
  SESSILE_CHECK(s->nv > 0 && s->nf > 0, SESSILE_ERR_USAGE, "the sponge surface is empty");
  sessile_buffer **all[] = {&g->pos, &g->tri, &g->vf_off, &g->vf, &g->nbr_off, &g->nbr,
                            &g->nrm, &g->probed, &g->ctr[0], &g->ctr[1], &g->new_pos,
                            &g->len, &g->dir};
  for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
    sessile_buffer_destroy(*all[i]);
    *all[i] = NULL;
  }
  g->nv = g->nf = 0;
  free(g->host_nbr_off), free(g->host_nbr);
  g->host_nbr_off = g->host_nbr = NULL;
  uint32_t *vf_off = NULL, *vf = NULL, *nb_off = NULL, *nb = NULL;
  sessile_status st = sessile_surface_vertex_faces(s, &vf_off, &vf);
  if (st == SESSILE_OK) st = sessile_surface_vertex_neighbours(s, &nb_off, &nb);
  const size_t nv = s->nv, rb = g->real_bytes;
  struct { sessile_buffer **b; size_t bytes; const void *u32; } spec[] = {
      {&g->pos, 3 * nv * rb, NULL},
      {&g->tri, (size_t)s->nf * 3 * 4, s->tri},
      {&g->vf_off, (nv + 1) * 4, vf_off},
      {&g->vf, (size_t)s->nf * 3 * 4, vf},
      {&g->nbr_off, (nv + 1) * 4, nb_off},
      {&g->nbr, (nb_off ? (size_t)nb_off[nv] : 0) * 4 + 4, nb},
      {&g->nrm, 3 * nv * rb, NULL},
      {&g->probed, nv * rb, NULL},
      {&g->ctr[0], nv * rb, NULL},
      {&g->ctr[1], nv * rb, NULL},
      {&g->new_pos, 3 * nv * rb, NULL},
      {&g->len, nv * rb, NULL},
      {&g->dir, 3 * nv * rb, NULL}};
  for (size_t i = 0; st == SESSILE_OK && i < sizeof spec / sizeof spec[0]; i++) {
    st = sessile_buffer_create(g->gpu, spec[i].bytes, SESSILE_BUFFER_DEVICE, spec[i].b);
    if (st == SESSILE_OK && spec[i].u32) {
      size_t bytes = spec[i].bytes;
      if (spec[i].b == &g->nbr) bytes -= 4; /* padded by one entry for an empty list */
      if (bytes) st = sessile_buffer_upload(*spec[i].b, 0, spec[i].u32, bytes);
    }
  }
  if (st == SESSILE_OK) st = sessile_buffer_upload_reals(g->pos, 0, s->pos, 3 * nv);
  free(vf_off), free(vf);
  if (st != SESSILE_OK) {
    free(nb_off), free(nb);
    return st;
  }
  g->host_nbr_off = nb_off, g->host_nbr = nb;
  g->nv = s->nv;
  g->nf = s->nf;
  return SESSILE_OK;
}
