/* The cut-cell nutrient (sessile/fem/nutrient_cut.h, docs/nutrient.md): the
 * level hierarchy and its buffers, the boundary setup kernel per level, the
 * MG-PCG (or Jacobi-PCG) solve of the homogenised system, and the extension
 * across the surface for the probe. */
#include <stdlib.h>
#include <string.h>

#include "nutrient_cut_internal.h"

void sessile_cut_bc_default(sessile_cut_bc *bc) {
  bc->far_field = SESSILE_FAR_FIELD_HEIGHT;
  bc->height = 0; /* the caller sets it */
  bc->theta_min = 1e-3;
}

static int coarsens(const sessile_box *b) {
  for (int a = 0; a < 3; a++)
    if ((b->n[a] - 1) % 2 != 0 || (b->n[a] - 1) / 2 < 4) return 0;
  return 1;
}

static sessile_status make_levels(sessile_cut_nutrient *nt, const sessile_box *box, int max_levels) {
  sessile_gpu *g = sessile_la_gpu(nt->la);
  uint32_t rb = sessile_la_real_bytes(nt->la);
  nt->lv[0].box = *box;
  nt->nlevels = 1;
  while (nt->nlevels < max_levels && nt->nlevels < MAX_LEVELS && coarsens(&nt->lv[nt->nlevels - 1].box)) {
    sessile_box c = nt->lv[nt->nlevels - 1].box;
    for (int a = 0; a < 3; a++) c.n[a] = (c.n[a] - 1) / 2 + 1;
    c.h *= 2;
    nt->lv[nt->nlevels++].box = c;
  }
  for (int l = 0; l < nt->nlevels; l++) {
    level *v = &nt->lv[l];
    size_t n = sessile_box_nodes(&v->box);
    SESSILE_CALL(sessile_buffer_create(g, n * 4, SESSILE_BUFFER_DEVICE, &v->solid));
    SESSILE_CALL(sessile_buffer_create(g, n * 6 * rb, SESSILE_BUFFER_DEVICE, &v->theta));
    SESSILE_CALL(sessile_buffer_create(g, n * 4, SESSILE_BUFFER_DEVICE, &v->mask));
    SESSILE_CALL(sessile_vec_create(nt->la, (uint32_t)n, &v->diag));
  }
  return SESSILE_OK;
}

void nutrient_cut_mg_levels(const sessile_cut_nutrient *nt, sessile_vec *const *coef,
                            sessile_mg_level *ml) {
  memset(ml, 0, (size_t)nt->nlevels * sizeof *ml);
  for (int l = 0; l < nt->nlevels; l++) {
    const level *v = &nt->lv[l];
    memcpy(ml[l].n, v->box.n, sizeof ml[l].n);
    ml[l].h = v->box.h;
    ml[l].mask = v->mask;
    ml[l].diag = v->diag;
    ml[l].coef = coef ? coef[l] : NULL;
  }
}

static sessile_status init(sessile_cut_nutrient *nt, const sessile_box *box, int max_levels) {
  sessile_gpu *g = sessile_la_gpu(nt->la);
  uint32_t rb = sessile_la_real_bytes(nt->la);
  SESSILE_CALL(make_levels(nt, box, max_levels));
  uint32_t n = sessile_box_nodes(box);
  SESSILE_CALL(sessile_vec_create(nt->la, n, &nt->lift));
  SESSILE_CALL(sessile_vec_create(nt->la, n, &nt->value));
  SESSILE_CALL(sessile_vec_create(nt->la, n, &nt->ext));
  SESSILE_CALL(sessile_kernel_create_decl(g, &sessile_fem_kernels[FK_CUTCELL], rb, 0, &nt->k_cut));
  SESSILE_CALL(sessile_kernel_create_decl(g, &sessile_fem_kernels[FK_GHOST], rb, 0, &nt->k_ghost));
  SESSILE_CALL(sessile_kernel_create_decl(g, &sessile_fem_kernels[FK_CUT_BC], rb, 0, &nt->k_bc));
  SESSILE_CALL(sessile_cmd_create(g, &nt->cmd));
  const level *f = &nt->lv[0];
  SESSILE_CALL(sessile_mat_create_stencil7_cut(nt->la, f->box.n[0], f->box.n[1], f->box.n[2],
                                               f->box.h, f->mask, f->diag, &nt->a));
  if (nt->nlevels > 1) {
    sessile_mg_level ml[MAX_LEVELS];
    nutrient_cut_mg_levels(nt, NULL, ml);
    sessile_mg_options mo;
    sessile_mg_options_default(&mo);
    SESSILE_CALL(sessile_mg_create(nt->la, nt->nlevels, ml, &mo, &nt->mg));
  }
  return SESSILE_OK;
}

sessile_status sessile_cut_nutrient_create(sessile_la *la, const sessile_box *box,
                                           const sessile_cut_bc *bc, int max_levels,
                                           sessile_cut_nutrient **out) {
  *out = NULL;
  SESSILE_CHECK(box->n[0] >= 3 && box->n[1] >= 3 && box->n[2] >= 3, SESSILE_ERR_USAGE,
                "nutrient box needs at least 3 nodes per axis (got %u x %u x %u)", box->n[0],
                box->n[1], box->n[2]);
  double top = box->h * (box->n[2] - 1);
  SESSILE_CHECK(bc->far_field == SESSILE_FAR_FIELD_HEIGHT || bc->far_field == SESSILE_FAR_FIELD_WALLS ||
                    bc->far_field == SESSILE_FAR_FIELD_INLET || bc->far_field == SESSILE_FAR_FIELD_PROFILE,
                SESSILE_ERR_USAGE, "unknown far field %d", (int)bc->far_field);
  SESSILE_CHECK(bc->far_field == SESSILE_FAR_FIELD_WALLS ||
                    (bc->height > box->h && bc->height <= top * (1 + 1e-12)),
                SESSILE_ERR_USAGE,
                "the far-field height (%g cm) must lie above the first grid layer (%g cm) and at "
                "or below the box top (%g cm)", bc->height, box->h, top);
  SESSILE_CHECK(bc->theta_min > 0 && bc->theta_min < 1, SESSILE_ERR_USAGE,
                "theta_min must lie in (0, 1) (got %g)", bc->theta_min);
  SESSILE_CHECK(max_levels >= 1, SESSILE_ERR_USAGE, "max_levels must be at least 1");
  sessile_cut_nutrient *nt = calloc(1, sizeof *nt);
  SESSILE_CHECK(nt, SESSILE_ERR_NO_MEMORY, "out of host memory");
  nt->la = la;
  nt->bc = *bc;
  sessile_status s = init(nt, box, max_levels);
  if (s != SESSILE_OK) {
    sessile_cut_nutrient_destroy(nt);
    return s;
  }
  *out = nt;
  return SESSILE_OK;
}

void sessile_cut_nutrient_destroy(sessile_cut_nutrient *nt) {
  if (!nt) return;
  nutrient_cut_adv_free(nt);
  sessile_mg_destroy(nt->mg);
  sessile_mat_destroy(nt->a);
  sessile_cmd_destroy(nt->cmd);
  sessile_kernel_destroy(nt->k_cut);
  sessile_kernel_destroy(nt->k_ghost);
  sessile_kernel_destroy(nt->k_bc);
  sessile_vec_destroy(nt->lift);
  sessile_vec_destroy(nt->value);
  sessile_vec_destroy(nt->ext);
  for (int l = 0; l < nt->nlevels; l++) {
    sessile_buffer_destroy(nt->lv[l].solid);
    sessile_buffer_destroy(nt->lv[l].theta);
    sessile_buffer_destroy(nt->lv[l].mask);
    sessile_vec_destroy(nt->lv[l].diag);
  }
  free(nt);
}

int sessile_cut_nutrient_levels(const sessile_cut_nutrient *nt) { return nt->nlevels; }

void sessile_cut_nutrient_level(sessile_cut_nutrient *nt, int l, sessile_box *box,
                                sessile_buffer **solid, sessile_buffer **theta) {
  if (box) *box = nt->lv[l].box;
  if (solid) *solid = nt->lv[l].solid;
  if (theta) *theta = nt->lv[l].theta;
}

sessile_buffer *sessile_cut_nutrient_mask(sessile_cut_nutrient *nt) { return nt->lv[0].mask; }
const sessile_vec *sessile_cut_nutrient_extended(const sessile_cut_nutrient *nt) { return nt->ext; }

cut_push nutrient_cut_push(const sessile_cut_nutrient *nt, const sessile_box *b, uint32_t flag) {
  uint32_t rb = sessile_la_real_bytes(nt->la);
  cut_push p = {.n0 = b->n[0], .n1 = b->n[1], .n2 = b->n[2],
                .far_field = nt->bc.far_field == SESSILE_FAR_FIELD_WALLS   ? FAR_WALLS
                             : nt->bc.far_field == SESSILE_FAR_FIELD_INLET ? FAR_INLET
                             : nt->bc.far_field == SESSILE_FAR_FIELD_PROFILE ? FAR_PROFILE
                                                                           : FAR_HEIGHT,
                .want_lift = flag,
                .h = sessile_push_real_of(b->h, rb),
                .oz = sessile_push_real_of(b->origin[2], rb),
                .height = sessile_push_real_of(nt->bc.height, rb),
                .theta_min = sessile_push_real_of(nt->bc.theta_min, rb)};
  return p;
}

uint32_t nutrient_cut_groups(const sessile_kernel *k, const sessile_box *b) {
  uint32_t local = sessile_kernel_local_size(k);
  return (sessile_box_nodes(b) + local - 1) / local;
}

sessile_status nutrient_cut_start(sessile_cut_nutrient *nt, sessile_vec *c) {
  const level *f = &nt->lv[0];
  cut_push p = nutrient_cut_push(nt, &f->box, 0);
  sessile_buffer *b[3] = {f->mask, sessile_vec_buffer(nt->value), sessile_vec_buffer(c)};
  SESSILE_CALL(sessile_cmd_dispatch(nt->cmd, nt->k_bc, nutrient_cut_groups(nt->k_bc, &f->box), b, &p));
  SESSILE_CALL(sessile_cmd_end(nt->cmd));
  return sessile_cmd_submit_wait(nt->cmd);
}

/* Every level's operator, the lift, and the homogenised start (Dirichlet
 * entries of c zeroed); one submission. */
static sessile_status setup(sessile_cut_nutrient *nt, sessile_vec *c) {
  SESSILE_CALL(sessile_cmd_begin(nt->cmd));
  for (int l = 0; l < nt->nlevels; l++) {
    level *v = &nt->lv[l];
    cut_push p = nutrient_cut_push(nt, &v->box, l == 0);
    sessile_buffer *b[6] = {v->solid, v->theta, v->mask, sessile_vec_buffer(v->diag),
                            sessile_vec_buffer(nt->lift), sessile_vec_buffer(nt->value)};
    SESSILE_CALL(sessile_cmd_dispatch(nt->cmd, nt->k_cut, nutrient_cut_groups(nt->k_cut, &v->box), b, &p));
  }
  return nutrient_cut_start(nt, c);
}

/* c = value on Dirichlet nodes (restore), then the extension. */
sessile_status nutrient_cut_finish(sessile_cut_nutrient *nt, const sessile_vec *c, int restore) {
  const level *f = &nt->lv[0];
  SESSILE_CALL(sessile_cmd_begin(nt->cmd));
  cut_push p = nutrient_cut_push(nt, &f->box, 1);
  sessile_buffer *b[3] = {f->mask, sessile_vec_buffer(nt->value), sessile_vec_buffer(c)};
  if (restore) SESSILE_CALL(sessile_cmd_dispatch(nt->cmd, nt->k_bc, nutrient_cut_groups(nt->k_bc, &f->box), b, &p));
  sessile_buffer *gb[4] = {f->mask, f->theta, sessile_vec_buffer(c), sessile_vec_buffer(nt->ext)};
  SESSILE_CALL(sessile_cmd_dispatch(nt->cmd, nt->k_ghost, nutrient_cut_groups(nt->k_ghost, &f->box), gb, &p));
  SESSILE_CALL(sessile_cmd_end(nt->cmd));
  return sessile_cmd_submit_wait(nt->cmd);
}

sessile_status sessile_cut_nutrient_solve(sessile_cut_nutrient *nt, sessile_cut_solver solver,
                                          sessile_vec *c, const sessile_ksp_options *opt,
                                          sessile_solve_result *res) {
  uint32_t n = sessile_box_nodes(&nt->lv[0].box);
  SESSILE_CHECK(sessile_vec_size(c) == n, SESSILE_ERR_USAGE,
                "nutrient field has %u entries, the box %u nodes", sessile_vec_size(c), n);
  double t0 = sessile_wall_seconds();
  sessile_ksp_options o;
  if (opt) o = *opt;
  else sessile_ksp_options_default(&o);
  o.type = SESSILE_KSP_CG;
  o.pc = SESSILE_PC_JACOBI;
  SESSILE_CALL(setup(nt, c));
  if (solver == SESSILE_CUT_SOLVER_MG && nt->mg) SESSILE_CALL(sessile_mg_solve(nt->mg, &o, nt->lift, c, res));
  else SESSILE_CALL(sessile_ksp_solve(nt->la, &o, nt->a, nt->lift, c, res));
  SESSILE_CALL(nutrient_cut_finish(nt, c, 1));
  res->seconds = sessile_wall_seconds() - t0;
  return SESSILE_OK;
}

sessile_status sessile_cut_nutrient_extend(sessile_cut_nutrient *nt, const sessile_vec *c) {
  const level *f = &nt->lv[0];
  SESSILE_CHECK(sessile_vec_size(c) == sessile_box_nodes(&f->box), SESSILE_ERR_USAGE,
                "nutrient field has %u entries, the box %u nodes", sessile_vec_size(c),
                sessile_box_nodes(&f->box));
  SESSILE_CALL(sessile_cmd_begin(nt->cmd));
  cut_push p = nutrient_cut_push(nt, &f->box, 1);
  sessile_buffer *b[6] = {f->solid, f->theta, f->mask, sessile_vec_buffer(f->diag),
                          sessile_vec_buffer(nt->lift), sessile_vec_buffer(nt->value)};
  SESSILE_CALL(sessile_cmd_dispatch(nt->cmd, nt->k_cut, nutrient_cut_groups(nt->k_cut, &f->box), b, &p));
  SESSILE_CALL(sessile_cmd_end(nt->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(nt->cmd));
  return nutrient_cut_finish(nt, c, 0);
}
