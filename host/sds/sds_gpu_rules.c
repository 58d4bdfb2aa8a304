/* The rules on the device: buffers and dispatches of
 * shaders/sds/rules_vm.comp (sds_gpu_rules.h; docs/sds_rules.md,
 * "Bytecode").  The bytecode and its constants go up once, at create; the
 * cells after each topology change. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "rules_glsl.h"
#include "sessile/sds/sds_run.h"
#include "rules_internal.h"
#include "rules_vm.h"
#include "sds_gpu_internal.h"
#include "sds_gpu_rules.h"

enum { R_PROG, R_KONST, R_MCOEF, R_POS, R_RM, R_OFF, R_NBR, R_SURF, R_PHI, R_STATE, R_SRC, R_PEND, R_PFLAG, R_DIVREQ,
       R_EVENT, R_DCOEF, R_PHI2, R_CNT, R_MRATE, R_RMN, R_RMO, R_GRAD, R_COUNT };

struct sds_gpu_rules {
  sessile_gpu *gpu;
  /* rules_vm; a batch's morph_bound and morph_step_batch (each also through
   * texel buffers), and its rules with their first sub-step (rules_morph:
   * NULL without morphogens); a batch step's flags, check and bound
   * (step_check; step_check_nosl where the batch has no slivers' table) */
  sessile_kernel *k, *k_bound, *k_bound_tex, *k_morph, *k_morph_tex, *k_fused, *k_check, *k_check_nosl;
  /* the oriented growth and convergent extension after each batch step's
   * rules (axial_grad, then axial_grow and axial_extend; each NULL without
   * it): axial_growth A and convergent_extension C along the gradient of
   * morphogen `axis`, C between cells whose state sext is set */
  sessile_kernel *k_axial_grad, *k_axial, *k_extend;
  double axial_A, extend_C;
  uint32_t axis, sext;
  sessile_buffer *b[R_COUNT];
  uint32_t ncells, nmorph, nstate;
  uint32_t tail_cap; /* step_check's most workgroups (sds_gpu_tail_cap) */
  uint32_t nk; /* the code's constants; a batch's control follows them in R_KONST (SDS_CTL) */
  double density;
  /* A batch's results downloaded in its own submission (record_results):
   * the event words, the amounts in R_PHI and R_PHI2, the states; `fresh`
   * from the submission until the next recording or upload on r. */
  uint32_t ev_host[SDS_EV_COUNT];
  double *phi_host, *phi2_host, *state_host;
  int fresh;
};

static sessile_status ensure(sds_gpu_rules *r, int i, size_t bytes) {
  return sessile_buffer_reserve(r->gpu, &r->b[i], bytes < 16 ? 16 : bytes, SESSILE_BUFFER_DEVICE);
}

/* A rules kernel of declaration id (SDS_RULES_VM, or SDS_RULES_MORPH around
 * the shader file `shell`): the generated one (rules_glsl.c) or the
 * interpreter. */
static sessile_status rules_kernel(sessile_gpu *g, const sds_prog *p, int kind, int id, const char *shell,
                                   sessile_kernel **k) {
  if (kind == SESSILE_SDS_RULES_BYTECODE) return sessile_kernel_create_decl(g, &sessile_sds_kernels[id], 8, 0, k);
  char why[320];
  char *body = sds_rules_glsl(p, shell, why, sizeof why);
  SESSILE_CHECK(body, SESSILE_ERR_INTERNAL, "the rules' generated kernel: %s", why);
  sessile_status st = sessile_kernel_create_glsl(g, &sessile_sds_kernels[id], 8, 0, body, k);
  free(body);
  return st;
}

sessile_status sds_gpu_rules_create(sessile_gpu *g, const sessile_sds_model *m, sds_gpu_rules **out) {
  return sds_gpu_rules_create_kind(g, m, SESSILE_SDS_RULES_GENERATED, out);
}

sessile_status sds_gpu_rules_create_kind(sessile_gpu *g, const sessile_sds_model *m, int kind, sds_gpu_rules **out) {
  *out = NULL;
  const char *why = sessile_sds_model_bytecode_refusal(m, 1);
  SESSILE_CHECK(!why, SESSILE_ERR_USAGE, "the rules on the device: %s", why);
  SESSILE_CHECK(sessile_gpu_info_of(g)->precision == 64, SESSILE_ERR_USAGE,
                "the rules on the device need fp64 (they equal the host's doubles)");
  sds_gpu_rules *r = calloc(1, sizeof *r);
  SESSILE_CHECK(r, SESSILE_ERR_NO_MEMORY, "out of host memory for the rules on the device");
  r->gpu = g, r->nmorph = (uint32_t)m->nmorph, r->nstate = (uint32_t)m->nstate;
  r->tail_cap = sds_gpu_tail_cap(g);
  const sds_prog *p = m->prog;
  r->nk = (uint32_t)p->nk;
  double mc[2 * SDS_MAX_MORPH], dc[3 * SDS_MAX_MORPH];
  for (int k = 0; k < m->nmorph; k++) mc[2 * k] = m->capped[k] ? 1 : 0, mc[2 * k + 1] = m->mstart[k];
  /* the morphogens' coefficients as sessile_morph_gpu_set_cells lays them out */
  sessile_morph_coef co = sessile_sds_model_coef(m);
  for (int k = 0; k < m->nmorph; k++)
    dc[3 * k] = co.diffusion[k], dc[3 * k + 1] = co.decay[k], dc[3 * k + 2] = (!co.capped || co.capped[k]) ? 1 : 0;
  sessile_status st = rules_kernel(g, p, kind, SDS_RULES_VM, "rules_vm.glsl", &r->k);
  if (st == SESSILE_OK && m->nmorph) st = rules_kernel(g, p, kind, SDS_RULES_MORPH, "rules_morph.glsl", &r->k_fused);
  if (st == SESSILE_OK) st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_MORPH_BOUND], 8, 0, &r->k_bound);
  if (st == SESSILE_OK)
    st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_MORPH_BOUND_TEX], 8, 0, &r->k_bound_tex);
  if (st == SESSILE_OK)
    st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_MORPH_STEP_BATCH], 8, 0, &r->k_morph);
  if (st == SESSILE_OK)
    st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_MORPH_STEP_BATCH_TEX], 8, 0, &r->k_morph_tex);
  if (st == SESSILE_OK) st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_STEP_CHECK], 8, 0, &r->k_check);
  if (st == SESSILE_OK)
    st = sessile_kernel_create_decl(g, &sessile_sds_kernels[SDS_STEP_CHECK_NOSL], 8, 0, &r->k_check_nosl);
  if (st == SESSILE_OK) st = ensure(r, R_CNT, 16);
  if (st == SESSILE_OK) { /* step_check's counter: zero between its dispatches (last_group.glsl) */
    const uint32_t zero[4] = {0, 0, 0, 0};
    st = sessile_buffer_upload(r->b[R_CNT], 0, zero, sizeof zero);
  }
  if (st == SESSILE_OK) st = ensure(r, R_PROG, (size_t)p->nw * 4);
  if (st == SESSILE_OK) st = ensure(r, R_KONST, ((size_t)p->nk + SDS_CTL) * 8);
  if (st == SESSILE_OK) st = ensure(r, R_MCOEF, sizeof mc);
  if (st == SESSILE_OK) st = ensure(r, R_DCOEF, sizeof dc);
  if (st == SESSILE_OK && m->nmorph) st = sessile_buffer_upload_reals(r->b[R_DCOEF], 0, dc, 3 * (size_t)m->nmorph);
  if (st == SESSILE_OK) st = ensure(r, R_EVENT, SDS_EV_COUNT * 4);
  if (st == SESSILE_OK) st = sessile_buffer_upload(r->b[R_PROG], 0, p->w, (size_t)p->nw * 4);
  if (st == SESSILE_OK && p->nk) st = sessile_buffer_upload_reals(r->b[R_KONST], 0, p->k, p->nk);
  if (st == SESSILE_OK && m->nmorph) st = sessile_buffer_upload_reals(r->b[R_MCOEF], 0, mc, 2 * (size_t)m->nmorph);
  if (st != SESSILE_OK) {
    sds_gpu_rules_destroy(r);
    return st;
  }
  *out = r;
  return SESSILE_OK;
}

void sds_gpu_rules_destroy(sds_gpu_rules *r) {
  if (!r) return;
  for (int i = 0; i < R_COUNT; i++) sessile_buffer_destroy(r->b[i]);
  free(r->phi_host), free(r->phi2_host), free(r->state_host);
  sessile_kernel_destroy(r->k);
  sessile_kernel_destroy(r->k_bound);
  sessile_kernel_destroy(r->k_bound_tex);
  sessile_kernel_destroy(r->k_morph);
  sessile_kernel_destroy(r->k_morph_tex);
  sessile_kernel_destroy(r->k_fused);
  sessile_kernel_destroy(r->k_check);
  sessile_kernel_destroy(r->k_check_nosl);
  sessile_kernel_destroy(r->k_axial_grad);
  sessile_kernel_destroy(r->k_axial);
  sessile_kernel_destroy(r->k_extend);
  free(r);
}

sessile_status sds_gpu_rules_set_cells(sds_gpu_rules *r, const sessile_morph_cells *cl, const double *phi,
                                       const double *state, double density) {
  SESSILE_CHECK(cl->ncells > 0, SESSILE_ERR_USAGE, "the rules on the device: no cells");
  size_t n = (size_t)cl->ncells, ne = cl->nbr_off[n], nm = r->nmorph, ns = r->nstate;
  r->fresh = 0;
  double **h[3] = {&r->phi_host, &r->phi2_host, &r->state_host};
  for (int i = 0; i < 3; i++) {
    double *g = realloc(*h[i], (n * (i < 2 ? nm : ns) + 1) * sizeof *g);
    SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "out of host memory for %zu cells", n);
    *h[i] = g;
  }
  double *rm = malloc(2 * n * sizeof *rm);
  uint32_t *surf = malloc(n * sizeof *surf);
  sessile_status st =
      rm && surf ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %zu cells", n);
  for (size_t c = 0; st == SESSILE_OK && c < n; c++)
    rm[2 * c] = cl->radius[c], rm[2 * c + 1] = 0, surf[c] = cl->surface && cl->surface[c] ? 1u : 0u;
  const int sized[] = {R_POS,   R_RM,   R_OFF,    R_NBR,  R_SURF, R_PHI,  R_STATE,
                       R_SRC,   R_PEND, R_PFLAG,  R_DIVREQ, R_PHI2, R_MRATE, R_RMN, R_RMO, R_GRAD};
  const size_t bytes[] = {3 * n * 8, 2 * n * 8, (n + 1) * 4, ne * 4, n * 4, n * nm * 8, n * ns * 8, n * nm * 8,
                          n * (1 + nm + ns) * 8, 2 * n * 4, SDS_REQ * n * 8, n * nm * 8, n * 8, 2 * n * 8,
                          (r->k_axial ? 2 * n : 1) * 8, (r->k_axial_grad ? 3 * n : 1) * 8};
  for (size_t i = 0; st == SESSILE_OK && i < sizeof sized / sizeof *sized; i++) st = ensure(r, sized[i], bytes[i]);
  if (st == SESSILE_OK) st = sessile_buffer_upload_reals(r->b[R_POS], 0, cl->pos, 3 * n);
  if (st == SESSILE_OK) st = sessile_buffer_upload_reals(r->b[R_RM], 0, rm, 2 * n);
  if (st == SESSILE_OK) st = sessile_buffer_upload(r->b[R_OFF], 0, cl->nbr_off, (n + 1) * 4);
  if (st == SESSILE_OK && ne) st = sessile_buffer_upload(r->b[R_NBR], 0, cl->nbr, ne * 4);
  if (st == SESSILE_OK) st = sessile_buffer_upload(r->b[R_SURF], 0, surf, n * 4);
  if (st == SESSILE_OK && nm) st = sessile_buffer_upload_reals(r->b[R_PHI], 0, phi, n * nm);
  if (st == SESSILE_OK && ns) st = sessile_buffer_upload_reals(r->b[R_STATE], 0, state, n * ns);
  free(rm), free(surf);
  SESSILE_CALL(st);
  r->ncells = (uint32_t)n, r->density = density;
  return SESSILE_OK;
}

_Static_assert(offsetof(sds_check_push, batch) == offsetof(sds_push, batch) &&
                   offsetof(sds_check_push, ncells) == offsetof(sds_push, ncells) &&
                   offsetof(sds_check_push, lsub) == offsetof(sds_push, lsub),
               "step_check's push begins with sds_push's fields");

static const uint32_t ev_zero[SDS_EV_COUNT] = {0, 0, 0xffffffffu, 0, 0, 0}; /* BAD starts above every cell */

sessile_status sds_gpu_rules_record_clear(sds_gpu_rules *r, sessile_cmd *cmd) {
  r->fresh = 0;
  return sessile_cmd_upload(cmd, r->b[R_EVENT], 0, ev_zero, sizeof ev_zero);
}

static sds_rules_push push_of(const sds_gpu_rules *r, double time, double dt, uint32_t mode, uint32_t batch) {
  sds_rules_push p;
  memset(&p, 0, sizeof p);
  p.time = sessile_push_real_of(time, 8), p.dt = sessile_push_real_of(dt, 8);
  p.density = sessile_push_real_of(r->density, 8);
  p.ncells = r->ncells, p.nmorph = r->nmorph, p.nstate = r->nstate, p.mode = mode;
  p.batch = batch, p.kctl = r->nk;
  return p;
}

sessile_status sds_gpu_rules_record_batch_start(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *rm) {
  SESSILE_CALL(sds_gpu_rules_record_clear(r, cmd));
  return r->k_fused ? sessile_cmd_copy(cmd, rm, r->b[R_RMN], 2 * (size_t)r->ncells * 8) : SESSILE_OK;
}

static sessile_status dispatch(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *rm,
                               sessile_buffer *phi, double time, double dt, uint32_t mode, uint32_t batch) {
  SESSILE_CHECK(r->ncells > 0, SESSILE_ERR_USAGE, "the rules on the device: set_cells first");
  r->fresh = 0;
  sds_rules_push p = push_of(r, time, dt, mode, batch);
  sessile_buffer *b[R_EVENT + 1]; /* the kernel's bindings: R_PROG .. R_EVENT */
  for (int i = 0; i <= R_EVENT; i++) b[i] = r->b[i];
  if (pos) b[R_POS] = pos;
  if (rm) b[R_RM] = rm;
  if (phi) b[R_PHI] = phi;
  uint32_t l = sessile_kernel_local_size(r->k);
  return sessile_cmd_dispatch(cmd, r->k, (r->ncells + l - 1) / l, b, &p);
}

sessile_status sds_gpu_rules_record_eval(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *rm,
                                         double time) {
  return dispatch(r, cmd, pos, rm, NULL, time, 0, 0, 0);
}

sessile_status sds_gpu_rules_record_apply(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *rm,
                                          double dt) {
  return dispatch(r, cmd, pos, rm, NULL, 0, dt, 1, 0);
}

sessile_buffer *sds_gpu_rules_buffer(const sds_gpu_rules *r, int which) {
  static const int map[] = {R_PHI, R_STATE, R_SRC, R_EVENT, R_DIVREQ, R_POS, R_RM};
  return which >= 0 && which < (int)(sizeof map / sizeof *map) ? r->b[map[which]] : NULL;
}

static int by_cell(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

sessile_status sds_gpu_rules_read_events(sds_gpu_rules *r, uint32_t ev[SDS_EV_COUNT], double *req, uint32_t *nreq) {
  if (r->fresh) memcpy(ev, r->ev_host, sizeof r->ev_host);
  else SESSILE_CALL(sessile_buffer_download(r->b[R_EVENT], 0, ev, SDS_EV_COUNT * 4));
  *nreq = ev[SDS_EV_NREQ] < r->ncells ? ev[SDS_EV_NREQ] : r->ncells;
  if (!*nreq || !req) return SESSILE_OK; /* req NULL: the event words only */
  SESSILE_CALL(sessile_buffer_download_reals(r->b[R_DIVREQ], 0, req, (size_t)SDS_REQ * *nreq));
  qsort(req, *nreq, SDS_REQ * sizeof *req, by_cell); /* one request per cell: the host's order */
  return SESSILE_OK;
}

void sds_gpu_rules_attach(sessile_sds_gpu *s, sds_gpu_rules *r) { s->rules = r; }

sessile_status sds_gpu_rules_record(sessile_sds_gpu *s, double time, double dt) {
  SESSILE_CHECK(s->rules && sessile_cmd_recording(s->cmd), SESSILE_ERR_USAGE,
                "the rules on the device: none attached, or no open recording");
  s->rules_dt = dt;
  return sds_gpu_rules_record_eval(s->rules, s->cmd, s->b[B_X0 + s->cur], s->b[B_RM], time);
}

sessile_status sds_gpu_rules_record_apply_s(sessile_sds_gpu *s) {
  SESSILE_CHECK(s->rules && sessile_cmd_recording(s->cmd), SESSILE_ERR_USAGE,
                "the rules on the device: none attached, or no open recording");
  return sds_gpu_rules_record_apply(s->rules, s->cmd, s->b[B_X0 + s->cur], s->b[B_RM], s->rules_dt);
}

/* --- inside a batch of physics steps (sds_gpu_batch_rules.c) ------------- */
/* Do the views of a batch's rules' inputs (pos, rm when given, the
 * sources, amounts and neighbour lists) fit maxTexelBufferElements?  Then
 * morph_bound and the sub-steps read them as texels (vector loads on
 * lavapipe); else through storage buffers, the same bits. */
static int texels_fit(const sds_gpu_rules *r, const sessile_buffer *pos, const sessile_buffer *rm) {
  const sessile_buffer *reals[] = {pos, rm, r->b[R_SRC], r->b[R_PHI], r->b[R_PHI2]};
  int fit = sessile_buffer_texels_fit(r->b[R_OFF], 4) && sessile_buffer_texels_fit(r->b[R_NBR], 4);
  for (size_t i = 0; i < 5; i++) fit = fit && sessile_buffer_texels_fit(reals[i], 8);
  return fit;
}

sessile_status sds_gpu_rules_record_bound(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *step,
                                          sessile_buffer *pev, uint32_t batch, uint32_t nsub_max) {
  sds_mbound_push p;
  memset(&p, 0, sizeof p);
  p.fudge = sessile_push_real_of(1 + 1e-9, 8); /* sds_rules' sub-step count, rounded as there */
  p.ncells = r->ncells, p.nmorph = r->nmorph, p.batch = batch, p.nsub_max = nsub_max, p.ctl = r->nk;
  r->fresh = 0;
  sessile_buffer *b[] = {pos, r->b[R_OFF], r->b[R_NBR], r->b[R_DCOEF], step, pev, r->b[R_EVENT], r->b[R_KONST]};
  return sessile_cmd_dispatch(cmd, texels_fit(r, pos, NULL) ? r->k_bound_tex : r->k_bound, 1, b, &p);
}

/* The amounts' buffer after j sub-steps of a batch (0: R_PHI, where the
 * batch began; the sub-steps ping-pong with R_PHI2). */
static sessile_buffer *phi_after(const sds_gpu_rules *r, uint32_t j) { return r->b[j & 1u ? R_PHI2 : R_PHI]; }

/* Rules mode 0 and the first sub-step in one dispatch (rules_morph.glsl);
 * with the apply too (mode 2: the step's only sub-step), its radii and
 * masses then copied from R_RMN into rm. */
static sessile_status dispatch_fused(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos, sessile_buffer *rm,
                                     uint32_t j0, uint32_t batch, int with_apply) {
  r->fresh = 0;
  sds_rules_push p = push_of(r, 0, 0, with_apply ? 2 : 0, batch);
  sessile_buffer *b[] = {r->b[R_PROG],  r->b[R_KONST], r->b[R_MCOEF], pos,
                         rm,            r->b[R_OFF],   r->b[R_NBR],   r->b[R_SURF],
                         phi_after(r, j0), r->b[R_STATE], r->b[R_SRC],  r->b[R_PEND],
                         r->b[R_PFLAG], r->b[R_DIVREQ], r->b[R_EVENT], r->b[R_DCOEF],
                         phi_after(r, j0 + 1), r->b[R_RMN]};
  uint32_t l = sessile_kernel_local_size(r->k_fused);
  SESSILE_CALL(sessile_cmd_dispatch(cmd, r->k_fused, (r->ncells + l - 1) / l, b, &p));
  return with_apply ? sessile_cmd_copy(cmd, r->b[R_RMN], rm, 2 * (size_t)r->ncells * 8) : SESSILE_OK;
}

sessile_status sds_gpu_rules_record_batch_step(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *pos,
                                               sessile_buffer *rm, uint32_t batch, uint32_t nsub) {
  uint32_t j0 = (batch - 1) * nsub; /* sub-steps recorded before this step's */
  /* the radii at the step's start, for the oriented growth after it */
  if (r->k_axial) SESSILE_CALL(sessile_cmd_copy(cmd, rm, r->b[R_RMO], 2 * (size_t)r->ncells * 8));
  int tex = texels_fit(r, pos, rm), fused = r->k_fused && tex && nsub >= 1;
  if (fused && nsub == 1) return dispatch_fused(r, cmd, pos, rm, j0, batch, 1); /* the whole rules' step */
  if (fused) SESSILE_CALL(dispatch_fused(r, cmd, pos, rm, j0, batch, 0));
  else SESSILE_CALL(dispatch(r, cmd, pos, rm, phi_after(r, j0), 0, 0, 0, batch));
  if (r->nmorph) {
    sds_morph_push mp;
    memset(&mp, 0, sizeof mp);
    mp.ncells = r->ncells, mp.nmorph = r->nmorph, mp.ctl = r->nk;
    sessile_kernel *k = tex ? r->k_morph_tex : r->k_morph;
    uint32_t l = sessile_kernel_local_size(k);
    for (uint32_t j = fused ? 1 : 0; j < nsub; j++) {
      mp.sub = j + 1;
      sessile_buffer *b[] = {pos,           rm,          r->b[R_OFF], r->b[R_NBR],        r->b[R_DCOEF],
                             r->b[R_SRC],   phi_after(r, j0 + j), phi_after(r, j0 + j + 1), r->b[R_KONST],
                             r->b[R_EVENT]};
      SESSILE_CALL(sessile_cmd_dispatch(cmd, k, (r->ncells + l - 1) / l, b, &mp));
    }
  }
  return dispatch(r, cmd, pos, rm, phi_after(r, j0 + nsub), 0, 0, 1, batch);
}

sessile_status sds_gpu_rules_set_axial(sds_gpu_rules *r, int axis, double A, double C, int sext) {
  sessile_kernel_destroy(r->k_axial_grad);
  sessile_kernel_destroy(r->k_axial);
  sessile_kernel_destroy(r->k_extend);
  r->k_axial_grad = r->k_axial = r->k_extend = NULL, r->axial_A = A, r->extend_C = C;
  r->axis = axis < 0 ? 0u : (uint32_t)axis, r->sext = sext < 0 ? 0u : (uint32_t)sext;
  if (A == 0 && C == 0) return SESSILE_OK;
  SESSILE_CHECK(axis >= 0 && (uint32_t)axis < r->nmorph, SESSILE_ERR_USAGE,
                "the oriented growth and convergent extension on the device need a morphogen declared axis=1");
  SESSILE_CHECK(C == 0 || (sext >= 0 && (uint32_t)sext < r->nstate), SESSILE_ERR_USAGE,
                "convergent extension on the device needs a state `extending`");
  SESSILE_CHECK(r->ncells == 0, SESSILE_ERR_INTERNAL, "the oriented growth set after the cells (its buffers' sizes)");
  SESSILE_CALL(sessile_kernel_create_decl(r->gpu, &sessile_sds_kernels[SDS_AXIAL_GRAD], 8, 0, &r->k_axial_grad));
  if (C != 0)
    SESSILE_CALL(sessile_kernel_create_decl(r->gpu, &sessile_sds_kernels[SDS_AXIAL_EXTEND], 8, 0, &r->k_extend));
  return A != 0 ? sessile_kernel_create_decl(r->gpu, &sessile_sds_kernels[SDS_AXIAL_GROW], 8, 0, &r->k_axial)
                : SESSILE_OK;
}

sessile_status sds_gpu_rules_record_axial(sds_gpu_rules *r, sessile_cmd *cmd, sessile_buffer *topo, sessile_buffer *sm,
                                          sessile_buffer *pos, sessile_buffer *rm, uint32_t ntets, uint32_t nedges,
                                          uint32_t batch, uint32_t nsub) {
  if (!r->k_axial_grad || !nedges) return SESSILE_OK;
  sds_axial_push p;
  memset(&p, 0, sizeof p);
  p.growth = sessile_push_real_of(r->axial_A, 8), p.extend = sessile_push_real_of(r->extend_C, 8);
  p.ncells = r->ncells, p.nedges = nedges, p.ntets = ntets, p.nmorph = r->nmorph, p.axis = r->axis;
  p.nstate = r->nstate, p.sext = r->sext, p.kctl = r->nk;
  r->fresh = 0;
  /* the amounts after the step's rules: its sub-steps' last buffer */
  sessile_buffer *bg[] = {pos, r->b[R_OFF], r->b[R_NBR], phi_after(r, batch * nsub), r->b[R_GRAD]};
  uint32_t l = sessile_kernel_local_size(r->k_axial_grad);
  SESSILE_CALL(sessile_cmd_dispatch(cmd, r->k_axial_grad, (r->ncells + l - 1) / l, bg, &p));
  if (r->k_axial) {
    sessile_buffer *b[] = {topo, pos, rm, r->b[R_RMO], r->b[R_GRAD], sm};
    l = sessile_kernel_local_size(r->k_axial);
    SESSILE_CALL(sessile_cmd_dispatch(cmd, r->k_axial, (nedges + l - 1) / l, b, &p));
  }
  if (!r->k_extend) return SESSILE_OK;
  /* after the growth, as the host's sds_rules: both scale s_m */
  sessile_buffer *b[] = {topo, pos, r->b[R_STATE], r->b[R_GRAD], r->b[R_KONST], r->b[R_EVENT], sm};
  l = sessile_kernel_local_size(r->k_extend);
  return sessile_cmd_dispatch(cmd, r->k_extend, (nedges + l - 1) / l, b, &p);
}

/* step_check's workgroups: one invocation per tet and per cell, or on a CPU
 * device at most tail_cap workgroups looping over them */
static uint32_t check_groups(const sds_gpu_rules *r, uint32_t ntets) {
  uint32_t n = ntets > r->ncells ? ntets : r->ncells;
  return sds_gpu_tail_groups(sessile_kernel_local_size(r->k_check), n, r->tail_cap);
}

void sds_gpu_rules_groups(const sds_gpu_rules *r, uint32_t ntets, uint32_t out[3]) {
  uint32_t l = sessile_kernel_local_size(r->k), m = sessile_kernel_local_size(r->k_morph);
  out[0] = (r->ncells + l - 1) / l, out[1] = (r->ncells + m - 1) / m, out[2] = check_groups(r, ntets);
}

void sds_gpu_rules_batch_done(sds_gpu_rules *r, uint32_t steps, uint32_t nsub) {
  if (!r->nmorph || !((steps * nsub) & 1u)) return;
  sessile_buffer *t = r->b[R_PHI]; /* the amounts are in R_PHI2: it becomes R_PHI */
  r->b[R_PHI] = r->b[R_PHI2], r->b[R_PHI2] = t;
  double *h = r->phi_host; /* and its download with it */
  r->phi_host = r->phi2_host, r->phi2_host = h;
}

sessile_status sds_gpu_rules_record_results(sds_gpu_rules *r, sessile_cmd *cmd) {
  size_t n = r->ncells;
  r->fresh = 0;
  SESSILE_CALL(sessile_cmd_download(cmd, r->b[R_EVENT], 0, r->ev_host, sizeof r->ev_host));
  if (r->nmorph) {
    SESSILE_CALL(sessile_cmd_download_reals(cmd, r->b[R_PHI], 0, r->phi_host, n * r->nmorph));
    SESSILE_CALL(sessile_cmd_download_reals(cmd, r->b[R_PHI2], 0, r->phi2_host, n * r->nmorph));
  }
  if (r->nstate) SESSILE_CALL(sessile_cmd_download_reals(cmd, r->b[R_STATE], 0, r->state_host, n * r->nstate));
  return SESSILE_OK;
}

void sds_gpu_rules_results_ready(sds_gpu_rules *r) { r->fresh = 1; }

sessile_status sds_gpu_rules_get_cells(sds_gpu_rules *r, double *phi, double *state) {
  size_t n = r->ncells;
  if (r->fresh) {
    if (r->nmorph) memcpy(phi, r->phi_host, n * r->nmorph * sizeof *phi);
    if (r->nstate) memcpy(state, r->state_host, n * r->nstate * sizeof *state);
    return SESSILE_OK;
  }
  if (r->nmorph) SESSILE_CALL(sessile_buffer_download_reals(r->b[R_PHI], 0, phi, n * r->nmorph));
  if (r->nstate) SESSILE_CALL(sessile_buffer_download_reals(r->b[R_STATE], 0, state, n * r->nstate));
  return SESSILE_OK;
}

/* A batch step's inverted flags, check and morphogens' bound in one dispatch
 * (step_check.comp) for step k, whose result is pair c: when the physics
 * reads texels (its inverted kernel's _tex variant) and the rules' views fit;
 * *done 0 otherwise (the caller records the three). */
sessile_status sds_gpu_rules_record_check(sessile_sds_gpu *s, uint32_t k, int c, int *done) {
  sds_gpu_rules *r = s->rules;
  *done = 0;
  if (!r || !r->k_check || !sds_gpu_fused_tail(s, s->ntets, SDS_FUSE_CHECK_TETS) ||
      sds_gpu_kern(s, SDS_INVERTED) != s->k[SDS_INVERTED_TEX] || !texels_fit(r, s->b[B_X0 + c], NULL))
    return SESSILE_OK;
  sds_push q = sds_gpu_push_of(s, 0.0, 1, 3);
  sds_check_push p;
  memset(&p, 0, sizeof p);
  memcpy(&p, &q, offsetof(sds_push, batch) + sizeof q.batch); /* sds_push's fields come first, in its order */
  p.batch = (k + 2) | SDS_BATCH_SPLIT;
  p.fudge = sessile_push_real_of(1 + 1e-9, 8); /* as sds_gpu_rules_record_bound */
  p.nmorph = r->nmorph, p.nsub_max = s->nsub_max, p.ctl = r->nk;
  r->fresh = 0;
  sessile_buffer *b[] = {s->b[B_SP],   s->b[B_STAB], s->b[B_STEP],  s->b[B_EVENT], s->b[B_MOVE], s->b[B_TOPO],
                         s->b[B_DISP], s->b[B_X0 + c], s->b[B_TOPO], s->b[B_FLAG],  r->b[R_OFF],  r->b[R_NBR],
                         r->b[R_DCOEF], r->b[R_EVENT], r->b[R_KONST], r->b[R_CNT], r->b[R_MRATE],
                         s->b[B_SLIVER], s->b[B_X0 + 1 - c], s->b[B_X0 + c]};
  /* without a table the cubic's code would only cost every subgroup its
   * masked run on llvmpipe (docs/sds.md, "Tails that every subgroup runs") */
  sessile_kernel *kc = s->batch_slivers ? r->k_check : r->k_check_nosl;
  SESSILE_CALL(sessile_cmd_dispatch(s->cmd, kc, check_groups(r, s->ntets), b, &p));
  *done = 1;
  return SESSILE_OK;
}
