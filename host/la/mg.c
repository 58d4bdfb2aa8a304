/* Geometric multigrid: options, the checks of the level hierarchy, and the
 * objects kept across solves (each level's operator and sweep buffers, the CG
 * vectors, the command recorders).  Recording: mg_record.c; solve:
 * mg_solve.c; plain-C reference: ref_mg.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mg_internal.h"

void sessile_mg_options_default(sessile_mg_options *o) {
  memset(o, 0, sizeof *o);
  o->pre_smooth = 2;
  o->post_smooth = 2;
  o->omega = 6.0 / 7.0;
  o->coarse_sweeps = 8;
}

static sessile_status check_options(const sessile_mg_options *o) {
  SESSILE_CHECK(o->pre_smooth >= 1 && o->pre_smooth <= 100 && o->post_smooth == o->pre_smooth,
                SESSILE_ERR_USAGE,
                "multigrid: pre_smooth and post_smooth must be equal and in 1..100 (got %d and %d): "
                "CG needs a symmetric V-cycle",
                o->pre_smooth, o->post_smooth);
  SESSILE_CHECK(o->omega > 0 && o->omega <= 1, SESSILE_ERR_USAGE,
                "multigrid: omega must be in (0, 1] (got %g): damped Jacobi is then convergent on "
                "every diagonally dominant level, so the V-cycle stays positive definite",
                o->omega);
  SESSILE_CHECK(o->coarse_sweeps >= 1 && o->coarse_sweeps <= 10000, SESSILE_ERR_USAGE,
                "multigrid: coarse_sweeps must be in 1..10000 (got %d)", o->coarse_sweeps);
  return SESSILE_OK;
}

static sessile_status check_level(sessile_la *la, int l, const sessile_mg_level *v,
                                  const sessile_mg_level *finer) {
  const uint32_t *n = v->n;
  SESSILE_CHECK(n[0] >= 2 && n[1] >= 2 && n[2] >= 2, SESSILE_ERR_USAGE,
                "multigrid level %d: needs at least 2 nodes per axis (got %u x %u x %u)", l, n[0],
                n[1], n[2]);
  double nodes = (double)n[0] * n[1] * n[2];
  SESSILE_CHECK(nodes <= 2147483647.0, SESSILE_ERR_TOO_LARGE,
                "multigrid level %d: %u x %u x %u nodes is too large for 32-bit indices", l, n[0],
                n[1], n[2]);
  SESSILE_CHECK(v->h > 0 && isfinite(v->h), SESSILE_ERR_USAGE,
                "multigrid level %d: spacing h must be positive and finite (got %g)", l, v->h);
  if (finer) {
    const uint32_t *f = finer->n;
    for (int a = 0; a < 3; a++)
      SESSILE_CHECK((f[a] - 1) % 2 == 0 && n[a] == (f[a] - 1) / 2 + 1, SESSILE_ERR_USAGE,
                    "multigrid level %d (%u x %u x %u nodes) is not nested in level %d (%u x %u x "
                    "%u): every axis of the finer level needs an odd node count n and the coarser "
                    "(n - 1)/2 + 1 nodes",
                    l, n[0], n[1], n[2], l - 1, f[0], f[1], f[2]);
    SESSILE_CHECK(fabs(v->h - 2 * finer->h) <= 1e-12 * v->h, SESSILE_ERR_USAGE,
                  "multigrid level %d: spacing %g is not twice level %d's %g", l, v->h, l - 1,
                  finer->h);
  }
  SESSILE_CHECK(v->mask, SESSILE_ERR_USAGE, "multigrid level %d: no Dirichlet mask buffer", l);
  SESSILE_CHECK(sessile_buffer_size(v->mask) >= (size_t)nodes * 4, SESSILE_ERR_USAGE,
                "multigrid level %d: the mask buffer has %zu bytes, %u x %u x %u nodes need %zu", l,
                sessile_buffer_size(v->mask), n[0], n[1], n[2], (size_t)nodes * 4);
  SESSILE_CHECK(v->diag, SESSILE_ERR_USAGE, "multigrid level %d: no diag vector", l);
  SESSILE_CHECK(v->diag->la == la && v->diag->n == (uint32_t)nodes, SESSILE_ERR_USAGE,
                "multigrid level %d: diag has %u entries%s, %u x %u x %u nodes need %u", l,
                v->diag->n, v->diag->la == la ? "" : " of another la", n[0], n[1], n[2],
                (uint32_t)nodes);
  SESSILE_CHECK(!v->coef || (v->coef->la == la && v->coef->n == 6 * (uint32_t)nodes),
                SESSILE_ERR_USAGE, "multigrid level %d: coef needs 6 entries per node (%u x %u x %u) "
                "in the same la", l, n[0], n[1], n[2]);
  SESSILE_CHECK(!finer || !finer->coef == !v->coef, SESSILE_ERR_USAGE,
                "multigrid level %d: advective weights on some levels and not others", l);
  /* The multigrid kernels gather through texel buffers (no storage fallback). */
  uint64_t maxt = sessile_gpu_info_of(la->gpu)->max_texel_buffer_elements; /* for the message */
  SESSILE_CHECK(la_texel_fits(la, v->mask, 4) && la_texel_fits(la, v->diag->buf, la->real_bytes),
                SESSILE_ERR_TOO_LARGE,
                "multigrid level %d: %u x %u x %u nodes exceed the device's texel buffer limit "
                "(%llu texels)", l, n[0], n[1], n[2], (unsigned long long)maxt);
  return SESSILE_OK;
}

static sessile_status create_objects(sessile_mg *mg, const sessile_mg_level *levels) {
  sessile_la *la = mg->la;
  for (int l = 0; l < mg->nl; l++) {
    mg_level *v = &mg->lv[l];
    memcpy(v->n, levels[l].n, sizeof v->n);
    v->nodes = v->n[0] * v->n[1] * v->n[2];
    v->h = levels[l].h;
    v->mask = levels[l].mask;
    v->diag = levels[l].diag;
    v->coef = levels[l].coef;
    if (v->coef)
      SESSILE_CALL(sessile_mat_create_stencil7_cut_adv(la, v->n[0], v->n[1], v->n[2], v->h,
                                                       v->mask, v->diag, v->coef, &v->a));
    else
      SESSILE_CALL(sessile_mat_create_stencil7_cut(la, v->n[0], v->n[1], v->n[2], v->h, v->mask,
                                                   v->diag, &v->a));
    SESSILE_CALL(sessile_vec_create(la, v->nodes, &v->t));
    if (l > 0) {
      SESSILE_CALL(sessile_vec_create(la, v->nodes, &v->x));
      SESSILE_CALL(sessile_vec_create(la, v->nodes, &v->b));
    }
  }
  uint32_t n = mg->lv[0].nodes;
  SESSILE_CALL(sessile_vec_create(la, n, &mg->r));
  SESSILE_CALL(sessile_vec_create(la, n, &mg->z));
  SESSILE_CALL(sessile_vec_create(la, n, &mg->p));
  SESSILE_CALL(sessile_vec_create(la, n, &mg->q));
  SESSILE_CALL(sessile_vec_create(la, n, &mg->w));
  SESSILE_CALL(sessile_cmd_create(la->gpu, &mg->start));
  SESSILE_CALL(sessile_cmd_create(la->gpu, &mg->iter));
  SESSILE_CALL(sessile_cmd_create(la->gpu, &mg->resid));
  SESSILE_CALL(sessile_cmd_create(la->gpu, &mg->misc));
  /* Every kernel now: la_groups reads their local sizes while recording. */
  static const la_kernel_id ids[] = {
      K_MG_SMOOTH, K_MG_SMOOTH_DOT, K_MG_RESIDUAL, K_MG_RESTRICT, K_MG_PROLONG, K_MG_UPDATE,
      K_CG_SCALAR, K_DOT,           K_REDUCE,      K_WAXPY,       K_AYPX,      K_FILL,
      K_STENCIL7_CUT, K_STENCIL7_CUT_DOT, K_STENCIL7_CUT_TEX, K_STENCIL7_CUT_TEX_DOT,
      K_STENCIL7_CUT_JACOBI};
  sessile_kernel *k;
  for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++) SESSILE_CALL(la_kernel(la, ids[i], &k));
  static const la_kernel_id adv[] = {K_MG_SMOOTH_ADV, K_MG_RESIDUAL_ADV, K_STENCIL7_CUT_ADV,
                                     K_STENCIL7_CUT_ADV_DOT};
  for (size_t i = 0; mg->lv[0].coef && i < sizeof adv / sizeof adv[0]; i++)
    SESSILE_CALL(la_kernel(la, adv[i], &k));
  return SESSILE_OK;
}

sessile_status sessile_mg_create(sessile_la *la, int nlevels, const sessile_mg_level *levels,
                                 const sessile_mg_options *o, sessile_mg **out) {
  *out = NULL;
  sessile_mg_options opt;
  if (o) opt = *o;
  else sessile_mg_options_default(&opt);
  SESSILE_CHECK(nlevels >= 1 && nlevels <= MG_MAX_LEVELS, SESSILE_ERR_USAGE,
                "multigrid needs 1..%d levels (got %d)", MG_MAX_LEVELS, nlevels);
  SESSILE_CHECK(levels, SESSILE_ERR_USAGE, "multigrid: no levels given");
  SESSILE_CALL(check_options(&opt));
  for (int l = 0; l < nlevels; l++)
    SESSILE_CALL(check_level(la, l, &levels[l], l ? &levels[l - 1] : NULL));
  sessile_mg *mg = calloc(1, sizeof *mg);
  SESSILE_CHECK(mg, SESSILE_ERR_NO_MEMORY, "out of host memory");
  mg->la = la;
  mg->nl = nlevels;
  mg->o = opt;
  sessile_status s = create_objects(mg, levels);
  if (s != SESSILE_OK) {
    sessile_mg_destroy(mg);
    return s;
  }
  *out = mg;
  return SESSILE_OK;
}

void sessile_mg_destroy(sessile_mg *mg) {
  if (!mg) return;
  for (int l = 0; l < mg->nl; l++) {
    sessile_mat_destroy(mg->lv[l].a);
    sessile_vec_destroy(mg->lv[l].t);
    sessile_vec_destroy(mg->lv[l].x);
    sessile_vec_destroy(mg->lv[l].b);
  }
  sessile_vec_destroy(mg->r);
  sessile_vec_destroy(mg->z);
  sessile_vec_destroy(mg->p);
  sessile_vec_destroy(mg->q);
  sessile_vec_destroy(mg->w);
  sessile_vec_destroy(mg->rb);
  sessile_vec_destroy(mg->dx);
  sessile_cmd_destroy(mg->start);
  sessile_cmd_destroy(mg->iter);
  sessile_cmd_destroy(mg->resid);
  sessile_cmd_destroy(mg->misc);
  free(mg);
}
