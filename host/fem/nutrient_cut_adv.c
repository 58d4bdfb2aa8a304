/* The advected nutrient at the true surface (sessile/fem/nutrient_cut.h,
 * docs/nutrient.md): u·∇c = D ∇²c on the nutrient's box levels with the
 * Laplace nutrient's cut cells, boundary conditions and far field, each edge
 * weight multiplied by its exponentially fitted factor (cutcell_adv.comp),
 * solved by BiCGSTAB (or GMRES) preconditioned by one V-cycle of the same
 * nested levels, each rediscretised with the velocity injected onto it. */
#include <stdlib.h>
#include <string.h>
#include "nutrient_cut_internal.h"

#define M_PER_CM 0.01 /* the box is in cm, the velocity and D in SI */

void nutrient_cut_adv_free(sessile_cut_nutrient *nt) {
  cut_adv *a = nt->adv;
  if (!a) return;
  sessile_pc_destroy(a->pc);
  sessile_mg_destroy(a->mg);
  sessile_mat_destroy(a->a);
  sessile_kernel_destroy(a->k_cut);
  for (int l = 0; l < MAX_LEVELS; l++) {
    sessile_vec_destroy(a->vel[l]);
    sessile_vec_destroy(a->coef[l]);
  }
  free(a->host_vel);
  free(a);
  nt->adv = NULL;
}

static sessile_status adv_make(sessile_cut_nutrient *nt, cut_adv *a) {
  sessile_la *la = nt->la;
  size_t total = 0;
  for (int l = 0; l < nt->nlevels; l++) {
    uint32_t n = sessile_box_nodes(&nt->lv[l].box);
    total += 3 * (size_t)n;
    SESSILE_CALL(sessile_vec_create(la, 3 * n, &a->vel[l]));
    SESSILE_CALL(sessile_vec_create(la, 6 * n, &a->coef[l]));
  }
  a->host_vel = malloc(total * sizeof *a->host_vel);
  SESSILE_CHECK(a->host_vel, SESSILE_ERR_NO_MEMORY, "out of host memory for the nutrient's velocity");
  SESSILE_CALL(sessile_kernel_create_decl(sessile_la_gpu(la), &sessile_fem_kernels[FK_CUTCELL_ADV],
                                          sessile_la_real_bytes(la), 0, &a->k_cut));
  const level *f = &nt->lv[0];
  SESSILE_CALL(sessile_mat_create_stencil7_cut_adv(la, f->box.n[0], f->box.n[1], f->box.n[2],
                                                   f->box.h, f->mask, f->diag, a->coef[0], &a->a));
  if (nt->nlevels == 1) return SESSILE_OK;
  sessile_mg_level ml[MAX_LEVELS];
  nutrient_cut_mg_levels(nt, a->coef, ml);
  SESSILE_CALL(sessile_mg_create(la, nt->nlevels, ml, NULL, &a->mg));
  SESSILE_CALL(sessile_pc_create(la, "mg", &a->pc));
  SESSILE_CALL(sessile_pc_mg_set(a->pc, a->mg));
  return sessile_pc_setup(a->pc, a->a);
}

/* Level l's velocity from level l-1's by injection (node (2I, 2J, 2K)). */
static void inject(const sessile_box *fb, const double *fine, const sessile_box *cb, double *coarse) {
  for (uint32_t k = 0; k < cb->n[2]; k++)
    for (uint32_t j = 0; j < cb->n[1]; j++)
      for (uint32_t i = 0; i < cb->n[0]; i++) {
        size_t c = i + (size_t)cb->n[0] * (j + (size_t)cb->n[1] * k);
        size_t f = 2 * i + (size_t)fb->n[0] * (2 * j + (size_t)fb->n[1] * 2 * k);
        memcpy(coarse + 3 * c, fine + 3 * f, 3 * sizeof *coarse);
      }
}

/* Every level's velocity, operator and weights, the lift, the homogenised start. */
static sessile_status adv_setup(sessile_cut_nutrient *nt, const double *velocity, double D,
                                sessile_vec *c) {
  cut_adv *a = nt->adv;
  double *hv = a->host_vel;
  memcpy(hv, velocity, 3 * (size_t)sessile_box_nodes(&nt->lv[0].box) * sizeof *hv);
  for (int l = 0; l < nt->nlevels; l++) {
    double *next = hv + 3 * (size_t)sessile_box_nodes(&nt->lv[l].box);
    if (l + 1 < nt->nlevels) inject(&nt->lv[l].box, hv, &nt->lv[l + 1].box, next);
    SESSILE_CALL(sessile_vec_upload(a->vel[l], hv));
    hv = next;
  }
  uint32_t rb = sessile_la_real_bytes(nt->la);
  SESSILE_CALL(sessile_cmd_begin(nt->cmd));
  for (int l = 0; l < nt->nlevels; l++) {
    level *v = &nt->lv[l];
    cut_push cp = nutrient_cut_push(nt, &v->box, l == 0);
    cutadv_push p;
    memset(&p, 0, sizeof p);
    p.n0 = cp.n0, p.n1 = cp.n1, p.n2 = cp.n2, p.far_field = cp.far_field, p.want_lift = cp.want_lift;
    p.h = cp.h, p.oz = cp.oz, p.height = cp.height, p.theta_min = cp.theta_min;
    p.pe = sessile_push_real_of(v->box.h * M_PER_CM / D, rb);
    sessile_buffer *b[8] = {v->solid, v->theta, sessile_vec_buffer(a->vel[l]), v->mask,
                            sessile_vec_buffer(v->diag), sessile_vec_buffer(a->coef[l]),
                            sessile_vec_buffer(nt->lift), sessile_vec_buffer(nt->value)};
    SESSILE_CALL(sessile_cmd_dispatch(nt->cmd, a->k_cut, nutrient_cut_groups(a->k_cut, &v->box), b, &p));
  }
  return nutrient_cut_start(nt, c);
}

sessile_status sessile_cut_nutrient_solve_advected(sessile_cut_nutrient *nt, sessile_cut_solver solver,
                                                   const double *velocity, double D, sessile_vec *c,
                                                   const sessile_ksp_options *opt,
                                                   sessile_solve_result *res) {
  uint32_t n = sessile_box_nodes(&nt->lv[0].box);
  SESSILE_CHECK(sessile_vec_size(c) == n, SESSILE_ERR_USAGE,
                "nutrient field has %u entries, the box %u nodes", sessile_vec_size(c), n);
  SESSILE_CHECK(velocity, SESSILE_ERR_USAGE, "the advected nutrient needs a velocity");
  SESSILE_CHECK(D > 0, SESSILE_ERR_USAGE, "the diffusion coefficient must be positive (got %g)", D);
  double t0 = sessile_wall_seconds();
  sessile_ksp_options o;
  if (opt) o = *opt;
  else sessile_ksp_options_default(&o);
  if (o.type != SESSILE_KSP_GMRES) o.type = SESSILE_KSP_BICGSTAB; /* nonsymmetric: not CG */
  o.pc = SESSILE_PC_JACOBI;
  if (!nt->adv) {
    nt->adv = calloc(1, sizeof *nt->adv);
    SESSILE_CHECK(nt->adv, SESSILE_ERR_NO_MEMORY, "out of host memory");
    sessile_status s = adv_make(nt, nt->adv);
    if (s != SESSILE_OK) {
      nutrient_cut_adv_free(nt);
      return s;
    }
  }
  SESSILE_CALL(adv_setup(nt, velocity, D, c));
  sessile_pc *pc = solver == SESSILE_CUT_SOLVER_MG ? nt->adv->pc : NULL;
  SESSILE_CALL(sessile_ksp_solve_pc(nt->la, &o, nt->adv->a, pc, nt->lift, c, res));
  SESSILE_CALL(nutrient_cut_finish(nt, c, 1));
  res->seconds = sessile_wall_seconds() - t0;
  return SESSILE_OK;
}
