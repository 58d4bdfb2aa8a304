/* Block multigrid (sessile/la/bmg.h): options, the levels and their Kuhn
 * block patterns, destruction and a stand-alone V-cycle.  The operators are
 * built by bmg_setup.c, the V-cycle recorded by bmg_record.c, the plain-C
 * reference is ref_bmg.c; docs/la.md, "Block multigrid". */
#include <stdlib.h>
#include <string.h>
#include "bmg_internal.h"

void sessile_bmg_options_default(sessile_bmg_options *o) {
  memset(o, 0, sizeof *o);
  o->smoother = SESSILE_BMG_GAUSS_SEIDEL;
  o->pre = o->post = 2;
  o->cycle = 2;
  o->omega = 0.9;
  o->max_levels = BMG_MAX_LEVELS;
  o->coarse_dense_max = 160;
  o->coarse_sweeps = 20;
  o->wg_max_nodes = 1024;
  o->precision = 64;
}

void bmg_offsets(const uint32_t n[3], int off[BMG_NOFF][3]) {
  static const int e[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  int k = 0;
  off[k][0] = off[k][1] = off[k][2] = 0;
  k++;
  for (int i = 0; i < 7; i++)
    for (int s = -1; s <= 1; s += 2, k++)
      for (int a = 0; a < 3; a++) off[k][a] = s * e[i][a];
  /* insertion sort by index displacement: in-range neighbours then come in column order */
  for (int i = 1; i < BMG_NOFF; i++)
    for (int j = i; j > 0; j--) {
      long dj = off[j][0] + (long)n[0] * (off[j][1] + (long)n[1] * off[j][2]);
      long dp = off[j - 1][0] + (long)n[0] * (off[j - 1][1] + (long)n[1] * off[j - 1][2]);
      if (dp <= dj) break;
      for (int a = 0; a < 3; a++) {
        int t = off[j][a];
        off[j][a] = off[j - 1][a];
        off[j - 1][a] = t;
      }
    }
}

/* The Kuhn block pattern of level l (the coarse operators' pattern). */
static sessile_status build_pattern(bmg_level *v) {
  const uint32_t *n = v->n;
  uint64_t nnzb = 0;
  for (int pass = 0; pass < 2; pass++) {
    if (pass) SESSILE_CALL(sessile_bcsr4_alloc(v->nodes, v->nodes, nnzb, &v->a));
    uint64_t k = 0;
    for (uint32_t i = 0; i < v->nodes; i++) {
      long c[3] = {i % n[0], (i / n[0]) % n[1], i / (n[0] * n[1])};
      if (pass) v->a.rowptr[i] = k;
      for (int o = 0; o < BMG_NOFF; o++) {
        long q[3] = {c[0] + v->off[o][0], c[1] + v->off[o][1], c[2] + v->off[o][2]};
        if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= n[0] || q[1] >= n[1] || q[2] >= n[2]) continue;
        if (pass) v->a.col[k] = (uint32_t)(q[0] + n[0] * (q[1] + (long)n[1] * q[2]));
        k++;
      }
    }
    if (pass) v->a.rowptr[v->nodes] = k;
    nnzb = k;
  }
  return SESSILE_OK;
}

void sessile_bmg_destroy(sessile_bmg *mg) {
  if (!mg) return;
  for (int l = 0; l < mg->nl; l++) {
    bmg_level *v = &mg->lv[l];
    sessile_bcsr4_free(&v->a);
    sessile_bcsr4_free(&v->copy);
    sessile_mat_destroy(v->own);
    for (uint32_t c = 0; c < v->ndinv; c++) sessile_buffer_destroy(v->dinvb[c]);
    free(v->dinvb);
    free(v->dinv);
    free(v->fixed);
    sessile_buffer_destroy(v->mask);
    sessile_vec_destroy(v->x);
    sessile_vec_destroy(v->b);
    sessile_vec_destroy(v->r);
    sessile_buffer_destroy(v->x32);
    sessile_buffer_destroy(v->b32);
    sessile_buffer_destroy(v->r32);
  }
  for (int k = 0; k < K_COUNT; k++) sessile_kernel_destroy(mg->k32[k]);
  sessile_buffer_destroy(mg->stop32);
  sessile_buffer_destroy(mg->zero32);
  free(mg->cinv);
  sessile_mat_destroy(mg->cinvm);
  free(mg);
}

/* Level v's cycle vectors: x, b (below the finest) and r in the context's
 * precision, or x32, b32, r32 on every level for the fp32 cycle. */
static sessile_status level_vectors(sessile_bmg *mg, bmg_level *v) {
  sessile_la *la = mg->la;
  if (mg->f32) {
    size_t bytes = (size_t)v->nodes * 16;
    SESSILE_CALL(sessile_buffer_create(la->gpu, bytes, SESSILE_BUFFER_DEVICE, &v->x32));
    SESSILE_CALL(sessile_buffer_create(la->gpu, bytes, SESSILE_BUFFER_DEVICE, &v->b32));
    SESSILE_CALL(sessile_buffer_create(la->gpu, bytes, SESSILE_BUFFER_DEVICE, &v->r32));
    v->vx.buf = v->x32, v->vb.buf = v->b32, v->vr.buf = v->r32;
    return SESSILE_OK;
  }
  SESSILE_CALL(sessile_vec_create(la, 4 * v->nodes, &v->r));
  v->vr = vref_of(v->r);
  if (mg->nl == 1) return SESSILE_OK; /* the finest level's x and b are the caller's */
  SESSILE_CALL(sessile_vec_create(la, 4 * v->nodes, &v->x));
  SESSILE_CALL(sessile_vec_create(la, 4 * v->nodes, &v->b));
  v->vx = vref_of(v->x), v->vb = vref_of(v->b);
  return SESSILE_OK;
}

sessile_status sessile_bmg_create(sessile_la *la, const uint32_t n[3], const sessile_bmg_options *o,
                                  sessile_bmg **out) {
  *out = NULL;
  sessile_bmg_options def;
  if (!o) sessile_bmg_options_default(&def), o = &def;
  SESSILE_CHECK(la && n && n[0] >= 2 && n[1] >= 2 && n[2] >= 2, SESSILE_ERR_USAGE,
                "block multigrid needs an la and a grid of at least 2 nodes per axis");
  SESSILE_CHECK((uint64_t)n[0] * n[1] * n[2] <= UINT32_MAX / 16, SESSILE_ERR_TOO_LARGE,
                "block multigrid: grid %u x %u x %u is too large", n[0], n[1], n[2]);
  SESSILE_CHECK(o->pre >= 0 && o->post >= 0 && o->pre + o->post >= 1 && o->omega > 0 && o->omega <= 2 &&
                    o->max_levels >= 1 && o->coarse_sweeps >= 1 && o->cycle >= 1 && o->cycle <= 3 &&
                    (o->smoother == SESSILE_BMG_GAUSS_SEIDEL || o->smoother == SESSILE_BMG_JACOBI),
                SESSILE_ERR_USAGE,
                "block multigrid: bad options (pre %d, post %d, at least one sweep; omega %g in (0, 2]; "
                "max_levels %d >= 1; coarse_sweeps %d >= 1; cycle %d: 1, 2 or 3; smoother %d)",
                o->pre, o->post, o->omega, o->max_levels, o->coarse_sweeps, o->cycle, (int)o->smoother);
  SESSILE_CHECK(o->precision == 64 || o->precision == 32, SESSILE_ERR_USAGE,
                "block multigrid: precision %d: the cycle runs in 64 (the default) or 32 bits", o->precision);
  sessile_bmg *mg = calloc(1, sizeof *mg);
  SESSILE_CHECK(mg, SESSILE_ERR_NO_MEMORY, "out of host memory");
  mg->la = la;
  mg->o = *o;
  mg->f32 = o->precision == 32 && la->real_bytes == 8; /* an fp32 context: the same path */
  mg->rb = mg->f32 ? 4 : la->real_bytes;
  uint32_t g[3] = {n[0], n[1], n[2]};
  sessile_status s = SESSILE_OK;
  while (s == SESSILE_OK) {
    bmg_level *v = &mg->lv[mg->nl++];
    memcpy(v->n, g, sizeof g);
    v->nodes = g[0] * g[1] * g[2];
    bmg_offsets(g, v->off);
    v->fixed = calloc(v->nodes, 1);
    v->dinv = malloc((size_t)v->nodes * 16 * sizeof *v->dinv);
    if (!v->fixed || !v->dinv) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    if (s == SESSILE_OK && mg->nl > 1) s = build_pattern(v);
    if (s == SESSILE_OK) s = sessile_buffer_create(la->gpu, (size_t)v->nodes * 4, SESSILE_BUFFER_DEVICE, &v->mask);
    if (s == SESSILE_OK) s = level_vectors(mg, v);
    int halves = g[0] >= 3 && g[1] >= 3 && g[2] >= 3 && (g[0] - 1) % 2 == 0 && (g[1] - 1) % 2 == 0 &&
                 (g[2] - 1) % 2 == 0;
    if (v->nodes <= o->coarse_dense_max || !halves || mg->nl >= o->max_levels || mg->nl >= BMG_MAX_LEVELS)
      break;
    for (int a = 0; a < 3; a++) g[a] = (g[a] - 1) / 2 + 1;
  }
  if (s == SESSILE_OK && mg->f32) s = sessile_buffer_create(la->gpu, 16, SESSILE_BUFFER_DEVICE, &mg->stop32);
  if (s == SESSILE_OK && mg->f32)
    s = sessile_buffer_create(la->gpu, (size_t)mg->lv[mg->nl - 1].nodes * 16, SESSILE_BUFFER_DEVICE, &mg->zero32);
  if (s != SESSILE_OK) {
    sessile_bmg_destroy(mg);
    return s;
  }
  *out = mg;
  return SESSILE_OK;
}

int sessile_bmg_levels(const sessile_bmg *mg) { return mg->nl; }
uint32_t sessile_bmg_level_nodes(const sessile_bmg *mg, int l) {
  return l >= 0 && l < mg->nl ? mg->lv[l].nodes : 0;
}
unsigned sessile_bmg_rebuilds(const sessile_bmg *mg) { return mg->rebuilds; }

sessile_status sessile_bmg_vcycle(sessile_bmg *mg, const sessile_vec *r, sessile_vec *z) {
  SESSILE_CHECK(mg && r && z && r != z, SESSILE_ERR_USAGE, "bmg vcycle needs a hierarchy and distinct r, z");
  SESSILE_CHECK(mg->ready, SESSILE_ERR_USAGE, "bmg vcycle: not set up (sessile_bmg_setup)");
  SESSILE_CHECK(r->n == 4 * mg->lv[0].nodes && z->n == r->n, SESSILE_ERR_USAGE,
                "bmg vcycle: vectors of %u and %u reals for %u nodes", r->n, z->n, mg->lv[0].nodes);
  sessile_la *la = mg->la;
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(bmg_rec_cycle(mg, la->cmd, vref_of(r), vref_of(z), -1));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}
