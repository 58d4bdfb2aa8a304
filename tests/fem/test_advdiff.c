/* The SUPG advection-diffusion solver (host/fem/advdiff*.c).
 *
 * Checks and tolerances (measured values in docs/advdiff.md):
 *  - 1-D boundary layer c = (e^{Pe x} - 1)/(e^{Pe} - 1) on a thin Kuhn box
 *    (20 cubes along x, flow along x, c = 0 at x = 0, 1 at x = 1, rtol 1e-12):
 *    (a) 20x4x4 cubes, the exact profile on the side walls so every interior
 *    x line sees the 1-D problem: SUPG with the optimal tau is nodally exact
 *    at Pe = 1 and Pe = 50 (cell Peclet 1.25) to 1e-8, monotone along x and
 *    within [0,1] to 1e-9; plain Galerkin on the same mesh leaves [0,1] by
 *    more than 0.05 (the check can fail);
 *    (b) 20x2x2 cubes with zero-flux sides: Pe = 1 max error <= 1e-4 and
 *    monotone; Pe = 50 SUPG leaves [0,1] by <= 0.08 (the Kuhn wall rows are
 *    not 1-D consistent, docs/advdiff.md), at least 4x less than Galerkin;
 *  - u = 0 (and a uniform u with its constant source u . grad c): a linear
 *    field on a Kuhn box with perturbed interior nodes (a general mesh) is
 *    reproduced exactly: max error <= 1e-8 (rtol 1e-12);
 *  - manufactured c = sin(pi x) sin(pi y) sin(pi z) + x/2 with
 *    u = U (1, .5, .25), source f = -D lap c + u . grad c (nodal P1), global
 *    Peclet 4, cell Peclet <= 0.3, at h = 1/8, 1/16, 1/32: observed L2
 *    orders (4-point degree-2 rule per tet) > 1.8;
 *  - the nutrient BC helper on a 5x4x3-cube box with 2 solid nodes and one
 *    sponge-tagged node: counts of c = 1 wall nodes, c = 0 sink nodes and
 *    free nodes equal the counts from the node indices.
 * `test_advdiff --bench` (not run by ctest) times the default box at
 * resolution 1 and 2 with uniform flow (0.05, 0, 0) m/s. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/fem/advdiff.h"
#include "testutil.h"

static const double PI = 3.14159265358979323846;
static sessile_gpu *gpu;
static sessile_la *la;

static sessile_box box_of(uint32_t cx, uint32_t cy, uint32_t cz, double h) {
  sessile_box b = {{0, 0, 0}, h, {cx + 1, cy + 1, cz + 1}};
  return b;
}

static sessile_ksp_options tight(double rtol) {
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = SESSILE_KSP_BICGSTAB;
  o.rtol = rtol;
  o.max_it = 5000;
  return o;
}

/* ---------------------------------------------------------------------- */
/* The 1-D layer at Peclet pe on a thin box of unit length (1 cm), 20 cubes
 * along x, `cs` cubes across.  Sides: zero flux (natural), or (dir_sides)
 * Dirichlet with the exact profile, so every interior x line sees the 1-D
 * problem.  Reports the nodal max error on the free nodes, the worst
 * decrease along an x line and the worst excursion outside [0,1]. */
typedef struct { double err, decrease, outside; int it; } layer_out;

static layer_out layer(double pe, double tau_scale, uint32_t cs, int dir_sides) {
  const uint32_t nx = 20;
  sessile_box b = box_of(nx, cs, cs, 1.0 / nx);
  sessile_tetmesh m;
  t_must("mesh", sessile_tetmesh_from_box(&b, &m));
  uint32_t n = m.nnodes;
  const double L = 0.01, D = 1e-5, U = pe * D / L; /* 1 cm in SI */
  double *vel = t_xalloc(3 * (size_t)n * sizeof *vel), *g = t_xalloc(n * sizeof *g),
         *c = t_xalloc(n * sizeof *c);
  uint8_t *mask = t_xalloc(n);
  for (uint32_t i = 0; i < n; i++) {
    uint32_t ix = i % b.n[0];
    vel[3 * i] = U;
    mask[i] = ix == 0 || ix == nx || (dir_sides && m.node_tags[i] != 0);
    g[i] = expm1(pe * m.xyz[3 * i]) / expm1(pe);
  }
  sessile_advdiff *ad;
  t_must("advdiff create", sessile_advdiff_create(la, &m, &ad));
  sessile_advdiff_set_tau_scale(ad, tau_scale);
  sessile_ksp_options o = tight(1e-12);
  sessile_solve_result r;
  t_must("advdiff solve", sessile_advdiff_solve(ad, vel, D, mask, g, &o, c, &r));
  layer_out out = {0, 0, 0, r.iterations};
  for (uint32_t i = 0; i < n; i++) {
    out.err = fmax(out.err, fabs(c[i] - g[i]));
    out.outside = fmax(out.outside, fmax(-c[i], c[i] - 1));
    if (i % b.n[0] + 1 < b.n[0]) out.decrease = fmax(out.decrease, c[i] - c[i + 1]);
  }
  printf("  layer Pe %g, %s, %ux%ux%u cubes, %s sides: %d it (%s), max err %.3e, worst decrease "
         "%.3e, outside [0,1] %.3e\n", pe, tau_scale ? "SUPG" : "Galerkin", nx, cs, cs,
         dir_sides ? "Dirichlet" : "zero-flux", r.iterations, sessile_solve_status_name(r.status),
         out.err, out.decrease, out.outside);
  sessile_advdiff_destroy(ad);
  sessile_tetmesh_free(&m);
  free(vel);
  free(g);
  free(c);
  free(mask);
  return out;
}

static void test_layer(void) {
  /* (a) sides carrying the exact profile: interior rows are the 1-D scheme,
   * and SUPG with the optimal tau is nodally exact in 1-D */
  layer_out s1 = layer(1.0, 1.0, 4, 1), s50 = layer(50.0, 1.0, 4, 1), g50 = layer(50.0, 0.0, 4, 1);
  t_check("layer Pe 1, SUPG, profile on the sides: nodal max error", s1.err, 1e-8);
  t_check("layer Pe 50 (cell Pe 1.25), SUPG, profile on sides: nodal max error", s50.err, 1e-8);
  t_check("layer Pe 50, SUPG: largest decrease along x", fmax(s50.decrease, 0), 1e-9);
  t_check("layer Pe 50, SUPG: excursion outside [0,1]", fmax(s50.outside, 0), 1e-9);
  t_true("layer Pe 50, plain Galerkin, same mesh: oscillates (excursion > 0.05)", g50.outside > 0.05);
  /* (b) zero-flux sides: the Kuhn wall rows are not symmetric in x (e.g. a
   * side node's hat has twice the volume downstream as upstream), so the
   * discrete solution is not the 1-D profile (docs/advdiff.md) */
  layer_out z1 = layer(1.0, 1.0, 2, 0), z50 = layer(50.0, 1.0, 2, 0), zg = layer(50.0, 0.0, 2, 0);
  t_check("layer Pe 1, SUPG, zero-flux sides: nodal max error", z1.err, 1e-4);
  t_check("layer Pe 1, zero-flux sides: largest decrease along x", fmax(z1.decrease, 0), 1e-9);
  t_check("layer Pe 1, zero-flux sides: excursion outside [0,1]", fmax(z1.outside, 0), 1e-9);
  t_check("layer Pe 50, SUPG, zero-flux sides: excursion outside [0,1] (wall rows)", z50.outside, 0.08);
  t_true("layer Pe 50, zero-flux sides: Galerkin's excursion > 4x SUPG's", zg.outside > 4 * z50.outside);
}

/* ---------------------------------------------------------------------- */
static double lin(const double *p) { return 1.0 + 2.0 * p[0] - p[1] + 0.5 * p[2]; } /* p in cm */

static void test_patch(void) {
  sessile_box b = box_of(6, 5, 4, 0.25);
  sessile_tetmesh m;
  t_must("mesh", sessile_tetmesh_from_box(&b, &m));
  uint32_t n = m.nnodes;
  /* perturb interior nodes by up to 0.1 h (deterministic): a general mesh */
  double *rnd = t_xalloc(3 * (size_t)n * sizeof *rnd);
  sessile_fill_random(rnd, 3 * (uint64_t)n, -0.1 * b.h, 0.1 * b.h, 7);
  for (uint32_t i = 0; i < n; i++)
    if (!m.node_tags[i])
      for (int a = 0; a < 3; a++) m.xyz[3 * i + a] += rnd[3 * i + a];
  double *g = t_xalloc(n * sizeof *g), *c = t_xalloc(n * sizeof *c), *vel = t_xalloc(3 * (size_t)n * sizeof *vel),
         *f = t_xalloc(n * sizeof *f);
  uint8_t *mask = t_xalloc(n);
  const double u[3] = {2e-3, -1e-3, 5e-4}; /* m/s */
  for (uint32_t i = 0; i < n; i++) {
    mask[i] = m.node_tags[i] != 0;
    g[i] = lin(m.xyz + 3 * i);
    for (int a = 0; a < 3; a++) vel[3 * i + a] = u[a];
    /* u . grad c with grad c in 1/m: (2, -1, 0.5) per cm = 100x per m */
    f[i] = 100.0 * (u[0] * 2.0 - u[1] * 1.0 + u[2] * 0.5);
  }
  sessile_advdiff *ad;
  t_must("advdiff create", sessile_advdiff_create(la, &m, &ad));
  sessile_ksp_options o = tight(1e-12);
  sessile_solve_result r;
  double err = 0;
  t_must("advdiff solve u = 0", sessile_advdiff_solve(ad, NULL, 1e-4, mask, g, &o, c, &r));
  for (uint32_t i = 0; i < n; i++) err = fmax(err, fabs(c[i] - lin(m.xyz + 3 * i)));
  printf("  patch u = 0: %d it, relres %.2e\n", r.iterations, r.true_relres);
  t_check("u = 0, perturbed mesh: linear field reproduced (max error)", err, 1e-8);
  /* Laplace does not depend on D */
  memset(c, 0, n * sizeof *c);
  o.type = SESSILE_KSP_CG;
  t_must("advdiff solve u = 0, CG", sessile_advdiff_solve(ad, NULL, 3e-7, mask, g, &o, c, &r));
  err = 0;
  for (uint32_t i = 0; i < n; i++) err = fmax(err, fabs(c[i] - lin(m.xyz + 3 * i)));
  t_check("u = 0, other D, CG: linear field reproduced", err, 1e-8);
  /* uniform flow, SUPG, constant source u . grad c: still exact */
  o.type = SESSILE_KSP_GMRES;
  t_must("set source", sessile_advdiff_set_source(ad, f));
  memset(c, 0, n * sizeof *c);
  t_must("advdiff solve uniform u", sessile_advdiff_solve(ad, vel, 1e-6, mask, g, &o, c, &r));
  err = 0;
  for (uint32_t i = 0; i < n; i++) err = fmax(err, fabs(c[i] - lin(m.xyz + 3 * i)));
  printf("  patch uniform u (cell Pe ~%.1f), GMRES: %d it, relres %.2e\n",
         sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * 0.0025 / 2e-6, r.iterations, r.true_relres);
  t_check("uniform u + source u.grad c, SUPG, GMRES: linear field reproduced", err, 1e-8);
  t_true("CG with a velocity is refused",
         (o.type = SESSILE_KSP_CG, sessile_advdiff_solve(ad, vel, 1e-6, mask, g, &o, c, &r)) ==
             SESSILE_ERR_USAGE);
  sessile_error_clear();
  t_true("D = 0 is refused", sessile_advdiff_solve(ad, vel, 0.0, mask, g, NULL, c, &r) == SESSILE_ERR_USAGE);
  sessile_error_clear();
  sessile_advdiff_destroy(ad);
  sessile_tetmesh_free(&m);
  free(rnd);
  free(g);
  free(c);
  free(vel);
  free(f);
  free(mask);
}

/* ---------------------------------------------------------------------- */
/* Manufactured solution in the mesh's cm coordinates X; SI x = 0.01 X. */
static const double MS_U = 4e-3, MS_D = 1e-5; /* global Peclet U L / D = 4 with L = 1 cm */
static const double MS_DIR[3] = {1.0, 0.5, 0.25};

static double ms_c(const double *p) {
  return sin(PI * p[0]) * sin(PI * p[1]) * sin(PI * p[2]) + 0.5 * p[0];
}
static double ms_f(const double *p) {
  double sx = sin(PI * p[0]), sy = sin(PI * p[1]), sz = sin(PI * p[2]);
  double cx = cos(PI * p[0]), cy = cos(PI * p[1]), cz = cos(PI * p[2]);
  double lap = -3.0 * PI * PI * sx * sy * sz * 1e4; /* 1/m^2 */
  double grad[3] = {(PI * cx * sy * sz + 0.5) * 100.0, PI * sx * cy * sz * 100.0,
                    PI * sx * sy * cz * 100.0};
  return -MS_D * lap + MS_U * (MS_DIR[0] * grad[0] + MS_DIR[1] * grad[1] + MS_DIR[2] * grad[2]);
}

static double ms_solve(uint32_t cells, int *iters) {
  sessile_box b = box_of(cells, cells, cells, 1.0 / cells);
  sessile_tetmesh m;
  t_must("mesh", sessile_tetmesh_from_box(&b, &m));
  uint32_t n = m.nnodes;
  double *g = t_xalloc(n * sizeof *g), *c = t_xalloc(n * sizeof *c), *vel = t_xalloc(3 * (size_t)n * sizeof *vel),
         *f = t_xalloc(n * sizeof *f);
  uint8_t *mask = t_xalloc(n);
  for (uint32_t i = 0; i < n; i++) {
    const double *p = m.xyz + 3 * i;
    mask[i] = m.node_tags[i] != 0;
    g[i] = ms_c(p);
    f[i] = ms_f(p);
    for (int a = 0; a < 3; a++) vel[3 * i + a] = MS_U * MS_DIR[a];
  }
  sessile_advdiff *ad;
  t_must("advdiff create", sessile_advdiff_create(la, &m, &ad));
  t_must("set source", sessile_advdiff_set_source(ad, f));
  sessile_ksp_options o = tight(1e-10);
  sessile_solve_result r;
  t_must("advdiff solve", sessile_advdiff_solve(ad, vel, MS_D, mask, g, &o, c, &r));
  *iters = r.iterations;
  /* L2 error (cm^3 units; only ratios matter): 4-point degree-2 rule */
  const double qa = 0.5854101966249685, qb = 0.1381966011250105;
  double e2 = 0, n2 = 0;
  for (uint32_t t = 0; t < m.ntets; t++) {
    const uint32_t *v = m.tet + 4 * (size_t)t;
    double vol = sessile_tetmesh_tet_volume(&m, t);
    for (int q = 0; q < 4; q++) {
      double p[3] = {0, 0, 0}, ch = 0;
      for (int k = 0; k < 4; k++) {
        double w = k == q ? qa : qb;
        for (int a = 0; a < 3; a++) p[a] += w * m.xyz[3 * (size_t)v[k] + a];
        ch += w * c[v[k]];
      }
      double ce = ms_c(p);
      e2 += vol / 4 * (ce - ch) * (ce - ch);
      n2 += vol / 4 * ce * ce;
    }
  }
  sessile_advdiff_destroy(ad);
  sessile_tetmesh_free(&m);
  free(g);
  free(c);
  free(vel);
  free(f);
  free(mask);
  return sqrt(e2 / n2);
}

static void test_convergence(void) {
  const uint32_t cells[3] = {8, 16, 32};
  double err[3];
  for (int k = 0; k < 3; k++) {
    int it;
    err[k] = ms_solve(cells[k], &it);
    double pe_h = MS_U * sqrt(1.3125) * 0.01 / cells[k] / (2 * MS_D);
    printf("  manufactured h = 1/%u (cell Pe %.3f): %d it, relative L2 error %.4e\n", cells[k], pe_h,
           it, err[k]);
  }
  for (int k = 0; k < 2; k++) {
    double order = log(err[k] / err[k + 1]) / log(2.0);
    char what[96];
    snprintf(what, sizeof what, "L2 order h = 1/%u -> 1/%u is %.3f; shortfall below 2", cells[k],
             cells[k + 1], order);
    t_check(what, fmax(2.0 - order, 0), 0.2);
  }
}

/* ---------------------------------------------------------------------- */
static void test_bc(void) {
  sessile_box b = box_of(5, 4, 3, 0.5);
  sessile_tetmesh m;
  t_must("mesh", sessile_tetmesh_from_box(&b, &m));
  uint32_t n = m.nnodes;
  uint8_t *solid = t_xalloc(n), *mask = t_xalloc(n);
  double *val = t_xalloc(n * sizeof *val);
  /* two interior solid nodes, one interior node tagged as sponge surface */
  uint32_t s1 = sessile_box_index(&b, 2, 2, 1), s2 = sessile_box_index(&b, 3, 2, 1),
           sp = sessile_box_index(&b, 2, 1, 2);
  solid[s1] = solid[s2] = 1;
  m.node_tags[sp] |= SESSILE_TAG_SPONGE;
  sessile_advdiff_nutrient_bc(&m, solid, mask, val);
  uint32_t ones = 0, zeros = 0, freen = 0, want_ones = 0, want_zeros = 0, want_free = 0, wrong = 0;
  for (uint32_t k = 0; k < b.n[2]; k++)
    for (uint32_t j = 0; j < b.n[1]; j++)
      for (uint32_t i = 0; i < b.n[0]; i++) {
        uint32_t q = sessile_box_index(&b, i, j, k);
        int wall = i == 0 || i == b.n[0] - 1 || j == 0 || j == b.n[1] - 1 || k == b.n[2] - 1;
        int sink = k == 0 || q == s1 || q == s2 || q == sp;
        if (sink) want_zeros++;
        else if (wall) want_ones++;
        else want_free++;
        if (mask[q] && val[q] == 1.0) ones++;
        else if (mask[q] && val[q] == 0.0) zeros++;
        else if (!mask[q]) freen++;
        int expect_mask = sink || wall;
        double expect_val = !sink && wall ? 1.0 : 0.0;
        if (mask[q] != expect_mask || val[q] != expect_val) wrong++;
      }
  printf("  nutrient BC on 6x5x4 nodes: %u walls at 1, %u sinks at 0, %u free\n", ones, zeros, freen);
  t_true("nutrient BC: 96 boundary - 30 substratum = 66 wall nodes at c = 1", ones == want_ones && ones == 66);
  t_true("nutrient BC: 30 substratum + 2 solid + 1 sponge = 33 nodes at c = 0",
         zeros == want_zeros && zeros == 33);
  t_true("nutrient BC: 24 interior - 3 = 21 free nodes", freen == want_free && freen == 21);
  t_true("nutrient BC: every node as expected", wrong == 0);
  /* without a solid mask */
  sessile_advdiff_nutrient_bc(&m, NULL, mask, val);
  uint32_t nmask = 0;
  for (uint32_t q = 0; q < n; q++) nmask += mask[q] != 0;
  t_true("nutrient BC without solid: 96 boundary + 1 sponge node masked", nmask == 97);
  sessile_tetmesh_free(&m);
  free(solid);
  free(mask);
  free(val);
}

/* ---------------------------------------------------------------------- */
/* --bench: the default box (32 x 32 x 24 cubes of 1.2 cm at resolution 1),
 * uniform flow (0.05, 0, 0) m/s, D = SESSILE_ADVDIFF_DEFAULT_D, the nutrient
 * BCs with a 6 cm ball of solid nodes at (19.2, 19.2, 6) cm. */
static void bench_one(int res, sessile_ksp_type type) {
  const double o0[3] = {0, 0, 0};
  const uint32_t cells[3] = {32, 32, 24};
  sessile_box b;
  t_must("box", sessile_box_make(o0, 1.2, cells, res, &b));
  sessile_tetmesh m;
  t_must("mesh", sessile_tetmesh_from_box(&b, &m));
  uint32_t n = m.nnodes;
  double *vel = t_xalloc(3 * (size_t)n * sizeof *vel), *g = t_xalloc(n * sizeof *g), *c = t_xalloc(n * sizeof *c);
  uint8_t *solid = t_xalloc(n), *mask = t_xalloc(n);
  for (uint32_t i = 0; i < n; i++) {
    const double *p = m.xyz + 3 * i;
    vel[3 * i] = 0.05;
    double d2 = (p[0] - 19.2) * (p[0] - 19.2) + (p[1] - 19.2) * (p[1] - 19.2) + (p[2] - 6) * (p[2] - 6);
    solid[i] = d2 <= 5.7 * 5.7;
  }
  double t0 = sessile_wall_seconds();
  sessile_advdiff *ad;
  t_must("advdiff create", sessile_advdiff_create(la, &m, &ad));
  double tc = sessile_wall_seconds() - t0;
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = type;
  o.max_it = 5000;
  for (int pass = 0; pass < 2; pass++) {
    if (pass == 1) /* the sponge grew: 5.7 -> 6 cm; warm start from the old field */
      for (uint32_t i = 0; i < n; i++) {
        const double *p = m.xyz + 3 * i;
        double d2 = (p[0] - 19.2) * (p[0] - 19.2) + (p[1] - 19.2) * (p[1] - 19.2) + (p[2] - 6) * (p[2] - 6);
        solid[i] = d2 <= 36.0;
      }
    sessile_advdiff_nutrient_bc(&m, solid, mask, g);
    sessile_solve_result r;
    t_must("advdiff solve", sessile_advdiff_solve(ad, vel, SESSILE_ADVDIFF_DEFAULT_D, mask, g, &o, c, &r));
    double ta, tu, ts, cmin = INFINITY, cmax = -INFINITY;
    sessile_advdiff_timing(ad, &ta, &tu, &ts);
    for (uint32_t i = 0; i < n; i++) cmin = fmin(cmin, c[i]), cmax = fmax(cmax, c[i]);
    printf("bench res %d (%ux%ux%u nodes, %u tets, nnz %llu, create %.3f s) %s+jacobi %s: %d it (%s), "
           "relres %.2e, assemble %.3f s, upload %.3f s, solve %.3f s; c in [%.4f, %.4f]\n",
           res, b.n[0], b.n[1], b.n[2], m.ntets, (unsigned long long)sessile_advdiff_matrix(ad)->nnz, tc,
           sessile_ksp_type_name(type), pass ? "warm (5.7 -> 6 cm ball)" : "cold", r.iterations,
           sessile_solve_status_name(r.status), r.true_relres, ta, tu, ts, cmin, cmax);
    fflush(stdout);
  }
  sessile_advdiff_destroy(ad);
  sessile_tetmesh_free(&m);
  free(vel);
  free(g);
  free(c);
  free(solid);
  free(mask);
}

int main(int argc, char **argv) {
  int do_bench = argc > 1 && strcmp(argv[1], "--bench") == 0;
  if (do_bench) { /* timings without the validation layer */
    sessile_gpu_options go;
    sessile_gpu_options_default(&go);
    go.validation = 0;
    t_must("gpu", sessile_gpu_create(&go, &gpu));
    printf("device: %s, driver %s\n", sessile_gpu_info_of(gpu)->name, sessile_gpu_info_of(gpu)->driver);
  } else {
    gpu = t_gpu(0);
  }
  t_must("la", sessile_la_create(gpu, &la));
  if (do_bench) {
    int res_max = argc > 2 ? atoi(argv[2]) : 2;
    for (int res = 1; res <= res_max; res++) {
      bench_one(res, SESSILE_KSP_BICGSTAB);
      bench_one(res, SESSILE_KSP_GMRES);
    }
  } else {
    test_bc();
    test_layer();
    test_patch();
    test_convergence();
  }
  sessile_la_destroy(la);
  return t_finish(gpu);
}
