/* The morphogen step on the GPU (shaders/sds/morph_step.comp): buffers
 * kept between calls, nsteps ping-pong dispatches in one submission.  The
 * loop's per-step transfers ride in that submission (gpu.h,
 * sessile_cmd_upload): move_cells and set_phi open the recording with their
 * uploads, step records the dispatches and the amounts' download, and
 * get_phi reads the host copy; on a discrete GPU that is one submission a
 * step where there were six. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds_kernels.h"
#include "sessile/sds/sds_process.h"

enum { B_POS, B_RADIUS, B_OFF, B_NBR, B_COEF, B_SRC, B_PHI0, B_PHI1, B_COUNT };

struct sessile_morph_gpu {
  sessile_gpu *gpu;
  sessile_kernel *k, *k_tex; /* storage reads; texel reads (vector loads on lavapipe, the same bits) */
  int storage;               /* 1: storage reads always (sessile_morph_gpu_set_reads) */
  sessile_cmd *cmd;
  uint32_t real_bytes;
  sessile_buffer *b[B_COUNT];
  int ncells, nmorph, cur; /* cur: which of PHI0/PHI1 holds the amounts */
  double dt_max;
  double *phi_host; /* the amounts as downloaded by the last submission */
  size_t phi_cap;
  int phi_valid;    /* phi_host holds buffer cur's amounts */
};

/* The recording of this step's uploads, opened by the first of them. */
static sessile_status open_rec(sessile_morph_gpu *m) {
  if (sessile_cmd_recording(m->cmd)) return SESSILE_OK;
  return sessile_cmd_begin(m->cmd);
}

/* Ends the open recording with the download of buffer cur's amounts into
 * phi_host, and runs it. */
static sessile_status close_rec(sessile_morph_gpu *m) {
  size_t n = (size_t)m->ncells * m->nmorph;
  m->phi_valid = 0;
  if (m->phi_cap < n) {
    double *p = realloc(m->phi_host, n * sizeof *p);
    SESSILE_CHECK(p, SESSILE_ERR_NO_MEMORY, "out of host memory for %zu morphogen amounts", n);
    m->phi_host = p, m->phi_cap = n;
  }
  SESSILE_CALL(sessile_cmd_download_reals(m->cmd, m->b[m->cur ? B_PHI1 : B_PHI0], 0, m->phi_host, n));
  SESSILE_CALL(sessile_cmd_end(m->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(m->cmd));
  m->phi_valid = 1;
  return SESSILE_OK;
}

static sessile_status ensure(sessile_morph_gpu *m, int i, size_t bytes) {
  return sessile_buffer_reserve(m->gpu, &m->b[i], bytes < 16 ? 16 : bytes, SESSILE_BUFFER_DEVICE);
}

sessile_status sessile_morph_gpu_create(sessile_gpu *g, sessile_morph_gpu **out) {
  *out = NULL;
  sessile_morph_gpu *m = calloc(1, sizeof *m);
  SESSILE_CHECK(m, SESSILE_ERR_NO_MEMORY, "out of host memory for the morphogen kernel");
  m->gpu = g;
  m->real_bytes = sessile_gpu_info_of(g)->precision == 64 ? 8 : 4;
  sessile_status st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_MORPH_STEP], m->real_bytes, 0, &m->k);
  if (st == SESSILE_OK)
    st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_MORPH_STEP_TEX], m->real_bytes, 0, &m->k_tex);
  if (st == SESSILE_OK) st = sessile_cmd_create(g, &m->cmd);
  if (st != SESSILE_OK) {
    sessile_morph_gpu_destroy(m);
    return st;
  }
  *out = m;
  return SESSILE_OK;
}

void sessile_morph_gpu_destroy(sessile_morph_gpu *m) {
  if (!m) return;
  for (int i = 0; i < B_COUNT; i++) sessile_buffer_destroy(m->b[i]);
  sessile_cmd_destroy(m->cmd); /* an open recording is dropped with it */
  free(m->phi_host);
  sessile_kernel_destroy(m->k);
  sessile_kernel_destroy(m->k_tex);
  free(m);
}

sessile_status sessile_morph_gpu_set_cells(sessile_morph_gpu *m, const sessile_morph_cells *cl,
                                           const sessile_morph_coef *co) {
  SESSILE_CHECK(cl->ncells > 0 && co->nmorph > 0 && co->nmorph <= SDS_MORPH_MAX, SESSILE_ERR_USAGE,
                "morphogen kernel: %d cells and %d morphogens (cells > 0, 1 to %d morphogens)", cl->ncells,
                co->nmorph, SDS_MORPH_MAX);
  /* uploads of the old cells not yet run (a set_phi without a step): run
   * them, before the buffers may be replaced */
  if (sessile_cmd_recording(m->cmd)) SESSILE_CALL(close_rec(m));
  m->phi_valid = 0;
  size_t nc = (size_t)cl->ncells, ne = cl->nbr_off[nc], rb = m->real_bytes, nm = (size_t)co->nmorph;
  double *coef = malloc(3 * nm * sizeof *coef);
  SESSILE_CHECK(coef, SESSILE_ERR_NO_MEMORY, "out of host memory for the morphogen coefficients");
  for (size_t k = 0; k < nm; k++) {
    coef[3 * k] = co->diffusion[k];
    coef[3 * k + 1] = co->decay[k];
    coef[3 * k + 2] = (!co->capped || co->capped[k]) ? 1.0 : 0.0;
  }
  sessile_status st = ensure(m, B_POS, 3 * nc * rb);
  if (st == SESSILE_OK) st = ensure(m, B_RADIUS, nc * rb);
  if (st == SESSILE_OK) st = ensure(m, B_OFF, (nc + 1) * 4);
  if (st == SESSILE_OK) st = ensure(m, B_NBR, ne * 4);
  if (st == SESSILE_OK) st = ensure(m, B_COEF, 3 * nm * rb);
  if (st == SESSILE_OK) st = ensure(m, B_SRC, nc * nm * rb);
  if (st == SESSILE_OK) st = ensure(m, B_PHI0, nc * nm * rb);
  if (st == SESSILE_OK) st = ensure(m, B_PHI1, nc * nm * rb);
  if (st == SESSILE_OK) st = sessile_buffer_upload_reals(m->b[B_POS], 0, cl->pos, 3 * nc);
  if (st == SESSILE_OK) st = sessile_buffer_upload_reals(m->b[B_RADIUS], 0, cl->radius, nc);
  if (st == SESSILE_OK) st = sessile_buffer_upload(m->b[B_OFF], 0, cl->nbr_off, (nc + 1) * 4);
  if (st == SESSILE_OK && ne) st = sessile_buffer_upload(m->b[B_NBR], 0, cl->nbr, ne * 4);
  if (st == SESSILE_OK) st = sessile_buffer_upload_reals(m->b[B_COEF], 0, coef, 3 * nm);
  free(coef);
  SESSILE_CALL(st);
  m->ncells = cl->ncells, m->nmorph = co->nmorph;
  m->dt_max = sessile_morph_dt_max(cl, co);
  SESSILE_CHECK(m->dt_max > 0, SESSILE_ERR_NUMERIC, "morphogen kernel: two adjacent cells coincide");
  return SESSILE_OK;
}

sessile_status sessile_morph_gpu_move_cells(sessile_morph_gpu *m, const sessile_morph_cells *cl,
                                            const sessile_morph_coef *co) {
  SESSILE_CHECK(m->ncells > 0 && cl->ncells == m->ncells && co->nmorph == m->nmorph, SESSILE_ERR_USAGE,
                "morphogen kernel: move_cells needs set_cells first with the same %d cells and %d morphogens",
                cl->ncells, co->nmorph);
  size_t nc = (size_t)cl->ncells;
  SESSILE_CALL(open_rec(m));
  SESSILE_CALL(sessile_cmd_upload_reals(m->cmd, m->b[B_POS], 0, cl->pos, 3 * nc));
  SESSILE_CALL(sessile_cmd_upload_reals(m->cmd, m->b[B_RADIUS], 0, cl->radius, nc));
  m->dt_max = sessile_morph_dt_max(cl, co);
  SESSILE_CHECK(m->dt_max > 0, SESSILE_ERR_NUMERIC, "morphogen kernel: two adjacent cells coincide");
  return SESSILE_OK;
}

sessile_status sessile_morph_gpu_set_phi(sessile_morph_gpu *m, const double *phi, const double *src) {
  SESSILE_CHECK(m->ncells > 0, SESSILE_ERR_USAGE, "morphogen kernel: set_cells first");
  size_t n = (size_t)m->ncells * m->nmorph;
  SESSILE_CALL(open_rec(m));
  m->cur = 0, m->phi_valid = 0;
  SESSILE_CALL(sessile_cmd_upload_reals(m->cmd, m->b[B_PHI0], 0, phi, n));
  if (src) return sessile_cmd_upload_reals(m->cmd, m->b[B_SRC], 0, src, n);
  double *z = calloc(n, sizeof *z);
  SESSILE_CHECK(z, SESSILE_ERR_NO_MEMORY, "out of host memory for zero sources");
  sessile_status st = sessile_cmd_upload_reals(m->cmd, m->b[B_SRC], 0, z, n);
  free(z);
  return st;
}

double sessile_morph_gpu_dt_max(const sessile_morph_gpu *m) { return m->dt_max; }

void sessile_morph_gpu_set_reads(sessile_morph_gpu *m, int storage) { m->storage = storage != 0; }

/* The texel variant when allowed and every view it reads fits the device's
 * maxTexelBufferElements (texels of one real or one uint). */
static sessile_kernel *kernel_of(const sessile_morph_gpu *m) {
  static const int reals[] = {B_POS, B_RADIUS, B_SRC, B_PHI0, B_PHI1}, words[] = {B_OFF, B_NBR};
  if (m->storage) return m->k;
  for (size_t i = 0; i < sizeof reals / sizeof *reals; i++)
    if (!sessile_buffer_texels_fit(m->b[reals[i]], m->real_bytes)) return m->k;
  for (size_t i = 0; i < sizeof words / sizeof *words; i++)
    if (!sessile_buffer_texels_fit(m->b[words[i]], 4)) return m->k;
  return m->k_tex;
}

sessile_status sessile_morph_gpu_step(sessile_morph_gpu *m, double dt, int nsteps) {
  SESSILE_CHECK(m->ncells > 0, SESSILE_ERR_USAGE, "morphogen kernel: set_cells first");
  SESSILE_CHECK(dt > 0 && isfinite(dt) && nsteps >= 0, SESSILE_ERR_USAGE,
                "morphogen kernel: dt = %g, %d steps (dt must be positive, steps >= 0)", dt, nsteps);
  SESSILE_CHECK(dt <= m->dt_max * (1 + 1e-12), SESSILE_ERR_USAGE,
                "morphogen kernel: dt = %g exceeds the explicit Euler bound %g; sub-step with dt <= %g", dt,
                m->dt_max, m->dt_max);
  if (nsteps == 0) return sessile_cmd_recording(m->cmd) ? close_rec(m) : SESSILE_OK;
  uint32_t local = sessile_kernel_local_size(m->k);
  uint32_t groups = ((uint32_t)m->ncells + local - 1) / local;
  sds_morph_push p = {0};
  p.ncells = (uint32_t)m->ncells;
  p.nmorph = (uint32_t)m->nmorph;
  p.dt = sessile_push_real_of(dt, m->real_bytes);
  SESSILE_CALL(open_rec(m));
  for (int s = 0; s < nsteps; s++) {
    int in = (m->cur + s) & 1;
    sessile_buffer *b[8] = {m->b[B_POS], m->b[B_RADIUS], m->b[B_OFF], m->b[B_NBR], m->b[B_COEF],
                            m->b[B_SRC], m->b[in ? B_PHI1 : B_PHI0], m->b[in ? B_PHI0 : B_PHI1]};
    SESSILE_CALL(sessile_cmd_dispatch(m->cmd, kernel_of(m), groups, b, &p));
  }
  m->cur = (m->cur + nsteps) & 1;
  return close_rec(m);
}

sessile_status sessile_morph_gpu_get_phi(sessile_morph_gpu *m, double *phi) {
  SESSILE_CHECK(m->ncells > 0, SESSILE_ERR_USAGE, "morphogen kernel: set_cells first");
  if (sessile_cmd_recording(m->cmd)) SESSILE_CALL(close_rec(m)); /* uploads not yet run */
  size_t n = (size_t)m->ncells * m->nmorph;
  if (m->phi_valid) {
    memcpy(phi, m->phi_host, n * sizeof *phi);
    return SESSILE_OK;
  }
  return sessile_buffer_download_reals(m->b[m->cur ? B_PHI1 : B_PHI0], 0, phi, n);
}
