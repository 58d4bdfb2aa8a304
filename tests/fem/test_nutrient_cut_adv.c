/* The advected nutrient at the true surface (sessile_cut_nutrient_solve_advected,
 * docs/nutrient.md, "The advected nutrient"):
 *  - la: the advective cut-cell operator (stencil7_cut_adv.comp) and one
 *    V-cycle of an advective hierarchy equal their plain-C references on
 *    random masks, diagonals and weights;
 *  - the whole advected solve (cutcell_adv.comp on two levels, MG-BiCGSTAB,
 *    the restore and the extension) equals a host solve of the reference
 *    setup's system (CSR BiCGSTAB) on a random solid with random cut
 *    fractions and velocities, both far fields;
 *  - second order: a manufactured solution around an off-grid sphere,
 *    c = sin(1.3x + 0.4) cos(0.9y) e^(z/2), uniform oblique u (cell Peclet
 *    number 2.6 to 0.65), Dirichlet data on the sphere at the crossings and on
 *    the box; the reference setup's weights, the source, and the device's
 *    operator and advective multigrid (BiCGSTAB): rms nodal order >= 1.8 on
 *    h, h/2, h/4;
 *  - a dome on the floor in a uniform current: c = 0 on the solid, in [0, 1]
 *    (the fitted operator is an M-matrix), MG and Jacobi agree, the wake is
 *    depleted downstream;
 *  - the far field PROFILE (also in the reference comparison above): its
 *    inflow wall holds the bare profile z / H, and upstream of the dome the
 *    field keeps it within 1e-3, where the zero-flux wall of HEIGHT lets the
 *    dome's depletion reach the inflow (inflow()). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/growth/growth_gpu.h"
#include "sessile/la/la_ref.h"
#include "sessile/la/mg.h"
#include "sessile/la/pc.h"
#include "sessile/fem/nutrient_cut.h"
#include "testutil.h"
#include "dome.h"

static sessile_la *la;
static double tol_k = 1e-13;

static sessile_vec *vec_of(const double *x, uint32_t n) { return t_vec_of(la, x, n); }

static sessile_buffer *mask_buffer(const uint32_t *m, size_t n) {
  sessile_buffer *b;
  t_must("mask", sessile_buffer_create(sessile_la_gpu(la), n * 4, SESSILE_BUFFER_DEVICE, &b));
  t_must("upload", sessile_buffer_upload(b, 0, m, n * 4));
  return b;
}

/* The operator and a two-level V-cycle on random data vs the references. */
static void la_vs_ref(void) {
  enum { NL = 2 };
  const uint32_t dims[NL][3] = {{13, 11, 9}, {7, 6, 5}};
  const double h0 = 0.3;
  uint32_t *mask[NL];
  double *diag[NL], *coef[NL];
  sessile_buffer *mb[NL];
  sessile_vec *vd[NL], *vc[NL];
  sessile_mg_level lv[NL];
  sessile_ref_mg_level ref[NL];
  memset(lv, 0, sizeof lv);
  for (int l = 0; l < NL; l++) {
    size_t n = (size_t)dims[l][0] * dims[l][1] * dims[l][2];
    mask[l] = calloc(n, 4), diag[l] = t_dalloc(n), coef[l] = t_dalloc(6 * n);
    for (size_t i = 0; i < n; i++) {
      mask[l][i] = urand() < 0.15;
      double d = 0;
      for (int k = 0; k < 6; k++) d += coef[l][6 * i + k] = 0.05 + 2 * urand();
      diag[l][i] = d + urand();
    }
    mb[l] = mask_buffer(mask[l], n), vd[l] = vec_of(diag[l], (uint32_t)n);
    vc[l] = vec_of(coef[l], 6 * (uint32_t)n);
    lv[l] = (sessile_mg_level){{dims[l][0], dims[l][1], dims[l][2]}, h0 * (1 << l), mb[l], vd[l], vc[l]};
    ref[l] = (sessile_ref_mg_level){{dims[l][0], dims[l][1], dims[l][2]}, h0 * (1 << l), mask[l], diag[l], coef[l]};
  }
  size_t n = (size_t)dims[0][0] * dims[0][1] * dims[0][2];
  double *x = t_dalloc(n), *y = t_dalloc(n), *gy = t_dalloc(n);
  for (size_t i = 0; i < n; i++) x[i] = urand() - 0.5;
  sessile_vec *xv = vec_of(x, (uint32_t)n), *yv = vec_of(y, (uint32_t)n);
  sessile_mat *A;
  t_must("operator", sessile_mat_create_stencil7_cut_adv(la, dims[0][0], dims[0][1], dims[0][2], h0,
                                                         mb[0], vd[0], vc[0], &A));
  t_must("mult", sessile_mat_mult(la, A, xv, yv));
  t_must("download", sessile_vec_download(yv, gy));
  sessile_ref_stencil7_cut_adv(dims[0][0], dims[0][1], dims[0][2], h0, mask[0], diag[0], coef[0], x, y);
  t_check("advective cut-cell operator: device vs reference (rel)", t_relerr(gy, y, n), tol_k);
  sessile_mg *mg;
  t_must("mg", sessile_mg_create(la, NL, lv, NULL, &mg));
  t_must("vcycle", sessile_mg_vcycle(mg, xv, yv));
  t_must("download", sessile_vec_download(yv, gy));
  sessile_mg_options o;
  sessile_mg_options_default(&o);
  t_must("ref vcycle", sessile_ref_mg_vcycle(NL, ref, &o, x, y));
  t_check("advective V-cycle: device vs reference (rel)", t_relerr(gy, y, n), 10 * tol_k);
  sessile_solve_result res;
  sessile_ksp_options ko;
  sessile_ksp_options_default(&ko);
  t_true("MG-PCG refuses the nonsymmetric hierarchy",
         sessile_mg_solve(mg, &ko, xv, yv, &res) == SESSILE_ERR_USAGE);
  sessile_mg_destroy(mg);
  sessile_mat_destroy(A);
  sessile_vec_destroy(xv), sessile_vec_destroy(yv);
  for (int l = 0; l < NL; l++) {
    sessile_buffer_destroy(mb[l]);
    sessile_vec_destroy(vd[l]), sessile_vec_destroy(vc[l]);
    free(mask[l]), free(diag[l]), free(coef[l]);
  }
  free(x), free(y), free(gy);
}

/* CSR of the homogenised system (identity rows on Dirichlet nodes). */
static void csr_of(const sessile_box *b, const uint32_t *mask, const double *diag,
                   const double *coef, sessile_csr *a) {
  uint32_t n = sessile_box_nodes(b);
  a->nrows = a->ncols = n;
  a->rowptr = calloc(n + 1, sizeof *a->rowptr);
  a->col = calloc((size_t)7 * n, sizeof *a->col);
  a->val = t_dalloc((size_t)7 * n);
  uint64_t k = 0;
  const int64_t st[3] = {1, b->n[0], (int64_t)b->n[0] * b->n[1]};
  for (uint32_t i = 0; i < n; i++) {
    uint32_t c[3] = {i % b->n[0], i / b->n[0] % b->n[1], i / (b->n[0] * b->n[1])};
    a->rowptr[i] = k;
    if (mask[i]) {
      a->col[k] = i, a->val[k++] = 1;
      continue;
    }
    a->col[k] = i, a->val[k++] = b->h * diag[i];
    for (int d = 0; d < 6; d++) {
      int ax = d >> 1, plus = d & 1;
      if (plus ? c[ax] + 1 >= b->n[ax] : c[ax] == 0) continue;
      uint32_t m = (uint32_t)(plus ? i + st[ax] : i - st[ax]);
      if (mask[m]) continue;
      double f = 1;
      for (int q = 0; q < 3; q++)
        if (q != ax && (c[q] == 0 || c[q] == b->n[q] - 1)) f *= 0.5;
      a->col[k] = m, a->val[k++] = -b->h * f * coef[6 * (size_t)i + d];
    }
  }
  a->rowptr[n] = k;
  a->nnz = k;
}

/* The whole advected solve on random data vs a host solve of the reference system. */
static void solve_vs_ref(sessile_far_field ff) {
  const double o[3] = {0, 0, 0}, D = 2e-4;
  const uint32_t cells[3] = {16, 16, 12};
  sessile_box b;
  t_must("box", sessile_box_make(o, 0.9, cells, 1, &b));
  sessile_cut_bc bc;
  sessile_cut_bc_default(&bc);
  bc.far_field = ff;
  bc.height = 0.9 * 10.5;
  sessile_cut_nutrient *nt;
  t_must("create", sessile_cut_nutrient_create(la, &b, &bc, 4, &nt));
  t_true("two levels", sessile_cut_nutrient_levels(nt) == 2);
  size_t n = sessile_box_nodes(&b);
  double *vel = t_dalloc(3 * n), *theta = NULL;
  for (size_t i = 0; i < 3 * n; i++) vel[i] = (i % 3 == 0 ? 0.04 : 0) + 0.02 * (urand() - 0.5);
  uint32_t *solid0 = NULL;
  for (int l = 0; l < 2; l++) { /* random solid blob and fractions on each level */
    sessile_box lb;
    sessile_buffer *sb, *tb;
    sessile_cut_nutrient_level(nt, l, &lb, &sb, &tb);
    size_t ln = sessile_box_nodes(&lb);
    uint32_t *solid = calloc(ln, 4);
    double *th = t_dalloc(6 * ln);
    for (size_t i = 0; i < ln; i++) {
      double p[3];
      sessile_box_node_pos(&lb, (uint32_t)i, p);
      double r2 = (p[0] - 7) * (p[0] - 7) + (p[1] - 7.5) * (p[1] - 7.5) + (p[2] - 1) * (p[2] - 1);
      solid[i] = r2 < 9.0 + 2 * urand();
      for (int d = 0; d < 6; d++) th[6 * i + d] = urand() < 0.5 ? 1.0 : urand() * 1.1;
    }
    t_must("upload", sessile_buffer_upload(sb, 0, solid, ln * 4));
    t_must("upload", sessile_buffer_upload_reals(tb, 0, th, 6 * ln));
    if (l == 0) solid0 = solid, theta = th;
    else free(solid), free(th);
  }
  uint32_t *mask = calloc(n, 4);
  double *diag = t_dalloc(n), *coef = t_dalloc(6 * n), *lift = t_dalloc(n), *val = t_dalloc(n);
  double *x = t_dalloc(n), *gx = t_dalloc(n), *ext = t_dalloc(n), *gext = t_dalloc(n);
  sessile_cut_ref_setup_adv(&b, &bc, solid0, theta, vel, b.h * 0.01 / D, mask, diag, coef, lift, val);
  sessile_csr a;
  csr_of(&b, mask, diag, coef, &a);
  sessile_ref_result rr = sessile_ref_bicgstab(&a, NULL, lift, x, 1e-14, 20000);
  for (size_t i = 0; i < n; i++)
    if (mask[i]) x[i] = val[i];
  sessile_cut_ref_ghost(&b, &bc, mask, theta, x, ext);
  sessile_vec *cv;
  t_must("c", sessile_vec_create(la, (uint32_t)n, &cv));
  sessile_ksp_options ko;
  sessile_ksp_options_default(&ko);
  ko.rtol = 1e-12;
  ko.max_it = 2000;
  sessile_solve_result res;
  const char *nm = t_far_name(ff);
  for (int s = 0; s < 2; s++) {
    sessile_cut_solver solver = s ? SESSILE_CUT_SOLVER_JACOBI : SESSILE_CUT_SOLVER_MG;
    t_must("fill", sessile_vec_fill(la, 0.5, cv));
    t_must("solve", sessile_cut_nutrient_solve_advected(nt, solver, vel, D, cv, &ko, &res));
    t_must("download", sessile_vec_download(cv, gx));
    t_must("download", sessile_vec_download((sessile_vec *)sessile_cut_nutrient_extended(nt), gext));
    printf("   random solid, far field %s, %s: %d BiCGSTAB iterations (host reference %d), "
           "true relres %.1e\n", nm, s ? "jacobi" : "mg", res.iterations, rr.iterations, res.true_relres);
    char what[160];
    snprintf(what, sizeof what, "far field %s, %s: advected solve vs host reference (rel)", nm,
             s ? "jacobi" : "mg");
    t_check(what, t_relerr(gx, x, n), 1e-9);
    snprintf(what, sizeof what, "far field %s, %s: extension vs host reference (rel)", nm,
             s ? "jacobi" : "mg");
    t_check(what, t_relerr(gext, ext, n), 1e-9);
  }
  t_true("host reference converged", rr.status == SESSILE_REF_CONVERGED);
  sessile_vec_destroy(cv);
  sessile_cut_nutrient_destroy(nt);
  free(a.rowptr), free(a.col), free(a.val);
  free(vel), free(theta), free(solid0), free(mask), free(diag), free(coef), free(lift), free(val);
  free(x), free(gx), free(ext), free(gext);
}

/* Manufactured solution around the sphere |x - sc| = SR. */
#define SR 0.5
static const double sc[3] = {0.013, -0.021, 0.007};
static const double U[3] = {16, 9.6, -4.8}, DIFF = 1;
static double exact(const double p[3]) {
  return sin(1.3 * p[0] + 0.4) * cos(0.9 * p[1]) * exp(0.5 * p[2]);
}
static double source(const double p[3]) { /* u·∇c − D ∇²c */
  double e = exp(0.5 * p[2]), sx = sin(1.3 * p[0] + 0.4), cx = cos(1.3 * p[0] + 0.4);
  double sy = sin(0.9 * p[1]), cy = cos(0.9 * p[1]);
  double gx = 1.3 * cx * cy * e, gy = -0.9 * sx * sy * e, gz = 0.5 * sx * cy * e;
  return U[0] * gx + U[1] * gy + U[2] * gz + DIFF * 2.25 * sx * cy * e;
}
/* Distance in units of h from x along s e_a to the sphere within one step (1: none). */
static double cross(const double x[3], int a, int sign, double h) {
  double d[3], best = 1;
  for (int q = 0; q < 3; q++) d[q] = x[q] - sc[q];
  double bq = sign * d[a], cq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - SR * SR;
  double disc = bq * bq - cq;
  if (disc < 0) return 1;
  for (int k = -1; k <= 1; k += 2) {
    double t = (-bq + k * sqrt(disc)) / h;
    if (t > 0 && t < best) best = t;
  }
  return best;
}

typedef struct {
  sessile_box b;
  uint32_t *solid, *mask;
  double *theta, *vel, *diag, *coef, *lift, *val;
  sessile_buffer *mb;
  sessile_vec *vd, *vc;
} mlevel;

static void mlevel_make(mlevel *v, sessile_box b, const sessile_cut_bc *bc) {
  v->b = b;
  size_t n = sessile_box_nodes(&b);
  v->solid = calloc(n, 4), v->mask = calloc(n, 4);
  v->theta = t_dalloc(6 * n), v->vel = t_dalloc(3 * n), v->diag = t_dalloc(n);
  v->coef = t_dalloc(6 * n), v->lift = t_dalloc(n), v->val = t_dalloc(n);
  for (size_t i = 0; i < n; i++) {
    double p[3], r2 = 0;
    sessile_box_node_pos(&b, (uint32_t)i, p);
    for (int q = 0; q < 3; q++) r2 += (p[q] - sc[q]) * (p[q] - sc[q]), v->vel[3 * i + q] = U[q];
    v->solid[i] = r2 < SR * SR;
    for (int d = 0; d < 6; d++) v->theta[6 * i + d] = cross(p, d >> 1, d & 1 ? 1 : -1, b.h);
  }
  sessile_cut_ref_setup_adv(&b, bc, v->solid, v->theta, v->vel, b.h / DIFF, v->mask, v->diag,
                            v->coef, v->lift, v->val);
  v->mb = mask_buffer(v->mask, n);
  v->vd = vec_of(v->diag, (uint32_t)n), v->vc = vec_of(v->coef, 6 * (uint32_t)n);
}

static void mlevel_free(mlevel *v) {
  sessile_buffer_destroy(v->mb);
  sessile_vec_destroy(v->vd), sessile_vec_destroy(v->vc);
  free(v->solid), free(v->mask), free(v->theta), free(v->vel), free(v->diag), free(v->coef);
  free(v->lift), free(v->val);
}

/* The right-hand side of the finest level with the exact Dirichlet data. */
static void manufactured_rhs(const mlevel *v, double *rhs) {
  const sessile_box *b = &v->b;
  size_t n = sessile_box_nodes(b);
  const int64_t st[3] = {1, b->n[0], (int64_t)b->n[0] * b->n[1]};
  for (size_t i = 0; i < n; i++) {
    double p[3];
    sessile_box_node_pos(b, (uint32_t)i, p);
    if (v->mask[i]) {
      rhs[i] = 0;
      continue;
    }
    double s = b->h * b->h * b->h * source(p) / DIFF;
    for (int d = 0; d < 6; d++) { /* WALLS far field: every free node is interior */
      int a = d >> 1, sign = d & 1 ? 1 : -1;
      size_t m = (size_t)((int64_t)i + sign * st[a]);
      if (v->mask[m] == SESSILE_CUT_FREE) continue;
      double q[3] = {p[0], p[1], p[2]};
      double t = v->mask[m] == SESSILE_CUT_SOLID ? fmax(v->theta[6 * i + d], 1e-3) : 1;
      q[a] += sign * t * b->h;
      s += b->h * v->coef[6 * i + d] * exact(q);
    }
    rhs[i] = s;
  }
}

static double manufactured(uint32_t cells, int *its) {
  sessile_cut_bc bc;
  sessile_cut_bc_default(&bc);
  bc.far_field = SESSILE_FAR_FIELD_WALLS;
  const double o[3] = {-1, -1, -1};
  mlevel lv[8];
  sessile_mg_level ml[8];
  memset(ml, 0, sizeof ml);
  int nl = 0;
  for (uint32_t c = cells; c >= 4 && nl < 8; c /= 2, nl++) {
    sessile_box b = {{o[0], o[1], o[2]}, 2.0 / c, {c + 1, c + 1, c + 1}};
    mlevel_make(&lv[nl], b, &bc);
    ml[nl] = (sessile_mg_level){{c + 1, c + 1, c + 1}, b.h, lv[nl].mb, lv[nl].vd, lv[nl].vc};
  }
  size_t n = sessile_box_nodes(&lv[0].b);
  double *rhs = t_dalloc(n), *x = t_dalloc(n);
  manufactured_rhs(&lv[0], rhs);
  sessile_vec *bv = vec_of(rhs, (uint32_t)n), *xv = vec_of(x, (uint32_t)n);
  sessile_mat *A;
  const uint32_t *nn = lv[0].b.n;
  t_must("operator", sessile_mat_create_stencil7_cut_adv(la, nn[0], nn[1], nn[2], lv[0].b.h, lv[0].mb,
                                                         lv[0].vd, lv[0].vc, &A));
  sessile_mg *mg;
  t_must("mg", sessile_mg_create(la, nl, ml, NULL, &mg));
  sessile_pc *pc;
  t_must("pc", sessile_pc_create(la, "mg", &pc));
  t_must("pc mg", sessile_pc_mg_set(pc, mg));
  t_must("pc setup", sessile_pc_setup(pc, A));
  sessile_ksp_options ko;
  sessile_ksp_options_default(&ko);
  ko.type = SESSILE_KSP_BICGSTAB;
  ko.rtol = 1e-10;
  ko.max_it = 500;
  sessile_solve_result res;
  t_must("solve", sessile_ksp_solve_pc(la, &ko, A, pc, bv, xv, &res));
  *its = res.iterations;
  t_true("manufactured: MG-BiCGSTAB converged", res.status == SESSILE_SOLVE_CONVERGED);
  t_must("download", sessile_vec_download(xv, x));
  double e2 = 0;
  size_t nf = 0;
  for (size_t i = 0; i < n; i++) {
    if (lv[0].mask[i]) continue;
    double p[3];
    sessile_box_node_pos(&lv[0].b, (uint32_t)i, p);
    double d = x[i] - exact(p);
    e2 += d * d, nf++;
  }
  sessile_pc_destroy(pc);
  sessile_mg_destroy(mg);
  sessile_mat_destroy(A);
  sessile_vec_destroy(bv), sessile_vec_destroy(xv);
  for (int l = 0; l < nl; l++) mlevel_free(&lv[l]);
  free(rhs), free(x);
  return sqrt(e2 / nf);
}

static void convergence(void) {
  uint32_t cs[3] = {16, 32, 64};
  double er[3];
  for (int i = 0; i < 3; i++) {
    int its;
    er[i] = manufactured(cs[i], &its);
    double pe = sqrt(U[0] * U[0] + U[1] * U[1] + U[2] * U[2]) * 2.0 / cs[i] / DIFF;
    printf("   manufactured, %u^3 cells (cell Peclet |u|h/D = %.2f): rms nodal error %.3e "
           "(%d MG-BiCGSTAB iterations)\n", cs[i], pe, er[i], its);
  }
  for (int i = 0; i < 2; i++) {
    char what[160];
    snprintf(what, sizeof what, "manufactured: order of the rms nodal error, h/%d -> h/%d (>= 1.8)",
             1 << i, 2 << i);
    t_check(what, fmax(1.8 - log2(er[i] / er[i + 1]), 0), 0);
  }
}

/* The advected solve from c = 0 to rtol (at most 3000 iterations) into x. */
static sessile_solve_result adv_solve(sessile_cut_nutrient *nt, sessile_cut_solver solver, const double *vel,
                                      double D, double rtol, double *x) {
  sessile_box b;
  sessile_cut_nutrient_level(nt, 0, &b, NULL, NULL);
  sessile_vec *c;
  t_must("vec", sessile_vec_create(la, (uint32_t)sessile_box_nodes(&b), &c));
  sessile_ksp_options ko;
  sessile_ksp_options_default(&ko);
  ko.rtol = rtol;
  ko.max_it = 3000;
  sessile_solve_result res;
  t_must("fill", sessile_vec_fill(la, 0, c));
  t_must("solve", sessile_cut_nutrient_solve_advected(nt, solver, vel, D, c, &ko, &res));
  t_must("download", sessile_vec_download(c, x));
  sessile_vec_destroy(c);
  return res;
}

/* A dome on the floor in a uniform current along x. */
static void dome(void) {
  t_dome dm;
  t_dome_make(la, 5.0, &dm);
  const sessile_box b = dm.b;
  sessile_cut_nutrient *nt = dm.nt;
  const double D = 1e-4;
  size_t n = sessile_box_nodes(&b);
  double *vel = t_dalloc(3 * n), *x[2] = {t_dalloc(n), t_dalloc(n)};
  for (size_t i = 0; i < n; i++) vel[3 * i] = 0.05;
  int its[2];
  uint32_t *m = calloc(n, 4);
  for (int k = 0; k < 2; k++) {
    sessile_solve_result res =
        adv_solve(nt, k ? SESSILE_CUT_SOLVER_JACOBI : SESSILE_CUT_SOLVER_MG, vel, D, 1e-9, x[k]);
    t_true(k ? "dome, jacobi: converged to 1e-9" : "dome, mg: converged to 1e-9",
           res.status == SESSILE_SOLVE_CONVERGED && res.true_relres <= 1e-9);
    its[k] = res.iterations;
  }
  t_must("download", sessile_buffer_download(sessile_cut_nutrient_mask(nt), 0, m, n * 4));
  double lo = INFINITY, hi = -INFINITY, smax = 0;
  for (size_t i = 0; i < n; i++) {
    lo = fmin(lo, x[0][i]), hi = fmax(hi, x[0][i]);
    if (m[i] == SESSILE_CUT_SOLID) smax = fmax(smax, fabs(x[0][i]));
  }
  /* upstream and downstream of the dome at mid-height of its side */
  double up[3] = {2.4, 9.6, 3.0}, down[3] = {16.8, 9.6, 3.0};
  double cu = sessile_box_trilinear(&b, x[0], up), cd = sessile_box_trilinear(&b, x[0], down);
  printf("   dome in a 5 cm/s current: %d MG-BiCGSTAB / %d Jacobi-BiCGSTAB iterations, c in [%g, %g], "
         "c upstream %.4f, downstream %.4f\n", its[0], its[1], lo, hi, cu, cd);
  t_check("dome: MG and Jacobi solutions agree (rel)", t_relerr(x[0], x[1], n), 1e-7);
  t_check("dome: c = 0 on solid nodes", smax, 0);
  t_true("dome: 0 <= c <= 1 (M-matrix: discrete maximum principle)", lo >= -1e-12 && hi <= 1 + 1e-12);
  t_true("dome: the wake is depleted (c downstream < c upstream)", cd < cu);
  t_true("dome: MG needs fewer iterations than Jacobi", its[0] < its[1]);
  free(vel), free(x[0]), free(x[1]), free(m);
  t_dome_free(&dm);
}

/* The inflow wall (docs/nutrient.md, "The inflow"): the dome in a 5 cm/s
 * current along +x, under PROFILE and under HEIGHT (zero flux through x = 0),
 * max |c - z/H| over the wall x = 0 and over the column plane x = 2h (1.2 cm
 * downstream of it, 3.4 cm upstream of the dome):
 *  - level flow (w = 0): z / H solves the bare box exactly and the dome's
 *    depletion reaches upstream over D/U = 2 mm only, so both keep the bare
 *    profile there (PROFILE within 1e-3);
 *  - a gentle updraft w = 2.5 mm/s (the flow rising over a sponge): PROFILE's
 *    wall holds z / H exactly and x = 2h is lifted by w/U x 1.2 cm = 0.6 mm
 *    (|c - z/H| <= 0.01); the zero-flux wall takes its neighbour's value, so
 *    the inflow settles where w c_z = D c_zz (w H / D = 3.6: far from linear),
 *    set by the grid next to the wall (the resolution and box dependence of
 *    grow's advected runs before PROFILE): at least 5x PROFILE's deviation. */
static void inflow(void) {
  const double D = 1e-4, H = 1.2 * 12;
  double dev[2][2], wall[2][2];
  for (int up = 0; up < 2; up++)
    for (int k = 0; k < 2; k++) {
      t_dome dm;
      t_dome_make_far(la, 5.0, k ? SESSILE_FAR_FIELD_HEIGHT : SESSILE_FAR_FIELD_PROFILE, &dm);
      const sessile_box b = dm.b;
      size_t n = sessile_box_nodes(&b);
      double *vel = t_dalloc(3 * n), *x = t_dalloc(n);
      for (size_t i = 0; i < n; i++) vel[3 * i] = 0.05, vel[3 * i + 2] = up ? 0.0025 : 0;
      sessile_solve_result res = adv_solve(dm.nt, SESSILE_CUT_SOLVER_MG, vel, D, 1e-10, x);
      t_true("inflow: the solve converged", res.status == SESSILE_SOLVE_CONVERGED);
      wall[up][k] = dev[up][k] = 0;
      for (uint32_t kk = 0; kk < b.n[2]; kk++)
        for (uint32_t j = 0; j < b.n[1]; j++) {
          double bare = fmin(b.h * kk / H, 1);
          size_t w = (size_t)b.n[0] * (j + (size_t)b.n[1] * kk); /* x = 0; w + 2: x = 2h */
          wall[up][k] = fmax(wall[up][k], fabs(x[w] - bare));
          dev[up][k] = fmax(dev[up][k], fabs(x[w + 2] - bare));
        }
      free(vel), free(x);
      t_dome_free(&dm);
    }
  for (int up = 0; up < 2; up++)
    printf("   inflow, %s: max |c - z/H| profile: %.1e on the wall, %.2e at x = 2h; zero flux: %.2e on the wall, "
           "%.2e at x = 2h\n", up ? "updraft 2.5 mm/s" : "level flow", wall[up][0], dev[up][0], wall[up][1], dev[up][1]);
  t_check("inflow, profile, level flow: the wall holds z / H", wall[0][0], tol_k);
  t_check("inflow, profile, level flow: max |c - z/H| at x = 2h", dev[0][0], 1e-3);
  t_check("inflow, profile, updraft: the wall holds z / H", wall[1][0], tol_k);
  t_check("inflow, profile, updraft: max |c - z/H| at x = 2h (lifted 0.6 mm)", dev[1][0], 1e-2);
  t_true("inflow, updraft: the zero-flux wall drifts at least 5x further from z / H", dev[1][1] >= 5 * dev[1][0]);
}

int main(int argc, char **argv) {
  int prec = argc > 1 && strcmp(argv[1], "--fp32") == 0 ? 32 : 0;
  sessile_gpu *g = t_gpu(prec);
  if (sessile_gpu_info_of(g)->precision == 32) tol_k = 1e-6;
  t_must("la", sessile_la_create(g, &la));
  la_vs_ref();
  solve_vs_ref(SESSILE_FAR_FIELD_HEIGHT);
  solve_vs_ref(SESSILE_FAR_FIELD_WALLS);
  solve_vs_ref(SESSILE_FAR_FIELD_INLET);
  solve_vs_ref(SESSILE_FAR_FIELD_PROFILE);
  dome();
  inflow();
  convergence();
  sessile_la_destroy(la);
  return t_finish(g);
}
