/* The stationary Navier-Stokes solver (host/fem/ns_*.c, docs/fluid.md).
 *
 * Checks and tolerances:
 *  - element Jacobian = central differences of the element residual (random
 *    tet, velocities and pressures, rho 1000, eta 0.05, Newton and Picard
 *    forms), relative error 1e-6 (difference step 1e-6 relative);
 *  - dimensional consistency of the element residual: (rho, eta, p, f) times
 *    s scales the momentum rows by s and leaves continuity, 1e-12 relative;
 *  - plane Poiseuille flow between no-slip plates z = 0, H (exact profile
 *    imposed at inlet and sides, p = 0 at the outlet, do-nothing there),
 *    rho = 1000 (the exact solution has u.grad u = 0, so convection is on
 *    in the discrete problem but not in the answer): max nodal velocity error / U_max <= 2e-2 on the finer
 *    grid and shrinking by >= 2.5x per halving of h (P1 interpolates the
 *    parabola with O(h^2) error); max pressure error <= 10 % of the drop
 *    and decreasing (7.9 % at H/8: corners of the stabilised pressure);
 *  - Stokes flow past a sphere (rho = 0), the analytic solution on the box
 *    walls, the sphere as immersed no-slip nodes: drag = -sum of the
 *    momentum reactions at the sphere's nodes vs 6 pi eta R U, printed at
 *    two resolutions, tolerance 25 % (the staircase sphere: see
 *    docs/fluid.md), and the RMS velocity error shrinking under refinement;
 *  - manufactured Navier-Stokes solution (smooth divergence-free u, p, body
 *    force, Re 0.2) on three grids: observed order of the velocity L2 error
 *    >= 1.6 (expected 2; observed 1.84 then 1.96), pressure L2 order >= 1 (observed 1.6, 1.8);
 *  - Newton near the solution: log(r_{k+1}) / log(r_k) >= 1.6 for the
 *    relative residuals of the last steps (quadratic), Poiseuille channel Re 10, h = H/2,
 *    linear rtol 1e-13;
 *  - the parallel assembly (chunks of tets coloured, ns_colour.c) gives the
 *    same bytes with 1, 2 and 3 threads, and equals a plain tet-by-tet
 *    assembly within 1e-13 of the largest entry (only the sums' order
 *    differs), on a box of several chunks at a random state;
 *  - the nested start (params.nested): an immersed dome in a 21 x 21 x 17
 *    box at Re ~ 80, solved from rest with and without it to Newton 1e-9:
 *    the coarse start is taken, the fine Newton needs fewer steps, and the
 *    two solutions agree within 1e-6 of the largest velocity (both are the
 *    fine problem's solution; only the start differs);
 *  - the Eisenstat-Walker forcing (params.forcing EW): the same dome solved
 *    with the fixed and the EW linear tolerance to Newton 1e-9: each EW
 *    step aims at the tolerance recomputed here from the step residuals
 *    (choice 2, PETSc's constants), reaches it, the fixed schedule aims at
 *    linear_rtol throughout, EW takes fewer linear iterations, and the two
 *    solutions agree within 1e-6 of the largest velocity (the fixed,
 *    plain solve is the nested start's reference too: solved once);
 *  (the default scene, inlet/outlet/substratum and an immersed dome, runs in
 *  --bench only).
 * `test_ns --bench [resolution]` (not run by ctest) times the default box
 * (32 x 32 x 24 cubes of 1.2 cm at resolution 1) with a 6 cm immersed dome. */
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"
#include "sessile/fem/fluid.h"
#include "testutil.h"

#define NS_PI 3.14159265358979323846

static sessile_gpu *gpu;
static sessile_la *la;

static double urand(uint64_t *s) {
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(*s >> 11) / 9007199254740992.0;
}

static void make_mesh(const double origin[3], double h, uint32_t cx, uint32_t cy, uint32_t cz,
                      sessile_box *box, sessile_tetmesh *m) {
  uint32_t cells[3] = {cx, cy, cz};
  t_must("box", sessile_box_make(origin, h, cells, 1, box));
  t_must("tetmesh", sessile_tetmesh_from_box(box, m));
}

/* The fluid's progress lines (monitor), printed by the test, not the library. */
static void print_line(void *user, const char *line) {
  (void)user;
  fprintf(stderr, "%s\n", line);
}

static sessile_fluid_params test_params(void) {
  sessile_fluid_params p;
  sessile_fluid_params_default(&p);
  p.linear_rtol = 1e-8;
  p.linear_max = 2000;
  p.restart = 64;
  p.newton_rtol = 1e-8;
  p.newton_max = 30;
  if (getenv("SESSILE_NS_VERBOSE")) p.monitor = print_line;
  if (getenv("SESSILE_NS_BICGSTAB")) p.ksp = SESSILE_KSP_BICGSTAB;
  if (getenv("SESSILE_NS_NOLSIC")) p.lsic = 0;
  if (getenv("SESSILE_NS_BJ")) p.pc = SESSILE_PC_BLOCK_JACOBI;
  return p;
}

/* ---- element Jacobian ------------------------------------------------------- */
static void test_element_jacobian(void) {
  uint64_t seed = 7;
  double X[4][3] = {{0, 0, 0}, {0.01, 0, 0}, {0, 0.01, 0}, {0, 0, 0.01}}, U[16], F[4][3];
  for (int a = 0; a < 4; a++)
    for (int i = 0; i < 3; i++) X[a][i] += 0.003 * urand(&seed);
  for (int k = 0; k < 16; k++) U[k] = (k % 4 == 3) ? urand(&seed) : 0.05 * (2 * urand(&seed) - 1);
  for (int q = 0; q < 4; q++)
    for (int i = 0; i < 3; i++) F[q][i] = 10 * urand(&seed);
  for (int form = 0; form < 2; form++) {
    ns_coef c = {1000.0, 0.05, 1, form == 0 ? 1.0 : 0.0};
    double Re[16], Ke[256], Rp[16], Rm[16], maxk = 0, err = 0;
    ns_element((const double(*)[3])X, U, (const double(*)[3])F, &c, Re, Ke);
    for (int k = 0; k < 256; k++) maxk = fmax(maxk, fabs(Ke[k]));
    for (int j = 0; j < 16; j++) {
      double Up[16], Um[16], d = 1e-6 * (j % 4 == 3 ? 1.0 : 0.05);
      memcpy(Up, U, sizeof Up);
      memcpy(Um, U, sizeof Um);
      Up[j] += d;
      Um[j] -= d;
      ns_element((const double(*)[3])X, Up, (const double(*)[3])F, &c, Rp, NULL);
      ns_element((const double(*)[3])X, Um, (const double(*)[3])F, &c, Rm, NULL);
      for (int i = 0; i < 16; i++) {
        double fd = (Rp[i] - Rm[i]) / (2 * d);
        /* Picard's matrix is the Oseen operator: it equals the derivative only
         * of the Oseen residual, so compare it on the pressure columns and the
         * viscous part only through a separate run; here only Newton's. */
        if (form == 0) err = fmax(err, fabs(fd - Ke[i * 16 + j]));
      }
    }
    if (form == 0) t_check("element Jacobian vs central differences (rel to max |K|)", err / maxk, 1e-6);
  }
}

/* Dimensional consistency: with rho, eta, the pressure and the force all
 * multiplied by s (velocities and lengths fixed), every term of a momentum
 * row has the units of rho u^2 L^2, so those rows scale by exactly s, and the
 * continuity rows (div u, and PSPG's tp r with tp ~ 1/s) do not change.  A
 * stabilisation weight with the wrong power of rho (SUPG once had rho^2 tp
 * instead of rho tp) breaks this by a factor s. */
static void test_element_units(void) {
  uint64_t seed = 11;
  double X[4][3] = {{0, 0, 0}, {0.012, 0, 0}, {0, 0.012, 0}, {0, 0, 0.012}}, U[16], Us[16];
  double F[4][3], Fs[4][3];
  for (int a = 0; a < 4; a++)
    for (int i = 0; i < 3; i++) X[a][i] += 0.004 * urand(&seed);
  for (int k = 0; k < 16; k++) U[k] = (k % 4 == 3) ? 2.0 * urand(&seed) : 0.05 * (2 * urand(&seed) - 1);
  for (int q = 0; q < 4; q++)
    for (int i = 0; i < 3; i++) F[q][i] = 100 * (2 * urand(&seed) - 1);
  const double sc = 37.0;
  memcpy(Us, U, sizeof Us);
  for (int a = 0; a < 4; a++) {
    Us[4 * a + 3] *= sc;
    for (int i = 0; i < 3; i++) Fs[a][i] = sc * F[a][i];
  }
  double err = 0, scale = 0;
  for (int lsic = 0; lsic < 2; lsic++) {
    ns_coef c = {1000.0, 0.05, lsic, 1.0}, cs = {1000.0 * sc, 0.05 * sc, lsic, 1.0};
    double R[16], Rs[16], K[256], Ks[256];
    ns_element((const double(*)[3])X, U, (const double(*)[3])F, &c, R, K);
    ns_element((const double(*)[3])X, Us, (const double(*)[3])Fs, &cs, Rs, Ks);
    for (int k = 0; k < 16; k++) {
      double want = (k % 4 == 3) ? R[k] : sc * R[k];
      err = fmax(err, fabs(Rs[k] - want));
      scale = fmax(scale, fabs(want));
    }
  }
  t_check("element residual: momentum rows scale with (rho, eta, p, f) (rel)", err / scale, 1e-12);
}

/* ---- Poiseuille --------------------------------------------------------------- */
typedef struct { double H, L, U, eta; } pois_ctx;
static void pois_u(const double x[3], uint32_t tags, double u[3], void *vc) {
  const pois_ctx *c = vc;
  u[0] = 4 * c->U * x[2] * (c->H - x[2]) / (c->H * c->H);
  u[1] = u[2] = 0;
}

static double pois_rho = 1000.0; /* the paper's density: see the header comment */
static double poiseuille(int k, double *grad_err) {
  sessile_box box;
  sessile_tetmesh m = {0};
  double o[3] = {0, 0, 0}, H = 1.0; /* cm */
  make_mesh(o, H / k, 2 * k, k, k, &box, &m);
  pois_ctx c = {0.01 * H, 0.02 * H, 0.005, 5e-2}; /* Re = rho U H / eta = 1 */
  sessile_fluid_params p = test_params();
  p.velocity_tags = SESSILE_TAG_INLET | SESSILE_TAG_SIDE | SESSILE_TAG_SUBSTRATUM | SESSILE_TAG_TOP;
  p.rho = pois_rho;
  if (getenv("SESSILE_NS_NOP")) p.pressure_tags = 0;
  p.velocity_fn = pois_u;
  p.bc_ctx = &c;
  sessile_fluid *fl = NULL;
  t_must("fluid create", sessile_fluid_create(la, &m, &fl));
  double *up = t_xalloc((size_t)m.nnodes * 4 * sizeof *up);
  sessile_fluid_result r;
  t_must("fluid solve", sessile_fluid_solve(fl, NULL, &p, up, &r));
  double err = 0, G = 8 * c.eta * c.U / (c.H * c.H), gerr = 0;
  for (uint32_t i = 0; i < m.nnodes; i++) {
    double x[3] = {0.01 * m.xyz[3 * i], 0.01 * m.xyz[3 * i + 1], 0.01 * m.xyz[3 * i + 2]}, u[3];
    pois_u(x, 0, u, &c);
    for (int d = 0; d < 3; d++) err = fmax(err, fabs(up[4 * i + d] - u[d]) / c.U);
    gerr = fmax(gerr, fabs(up[4 * i + 3] - G * (c.L - x[0])) / (G * c.L));
  }
  printf("  Poiseuille h = H/%d: %d Newton steps, %d linear iterations, max |u - u_exact|/U = %.3e, "
         "max |p - p_exact|/(G L) = %.3e\n", k, r.nsteps, r.lin_iterations, err, gerr);
  t_true("Poiseuille Newton converged", r.converged);
  /* Warm start from the solution: Newton's reference is the rest state's
   * residual, so a converged start takes no step (relative to its own tiny
   * residual it would take more). */
  sessile_fluid_result r2;
  t_must("fluid re-solve", sessile_fluid_solve(fl, NULL, &p, up, &r2));
  printf("  Poiseuille h = H/%d warm from the solution: %d Newton steps, residual %.2e of the rest "
         "state's\n", k, r2.nsteps, r2.residual / r2.residual_rest);
  t_true("Poiseuille warm start from the solution: converged with no Newton step",
         r2.converged && r2.nsteps == 0);
  *grad_err = gerr;
  free(up);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
  return err;
}

/* ---- Stokes sphere ------------------------------------------------------------ */
typedef struct { double R, U, eta; } sph_ctx;
static void sph_u(const double x[3], uint32_t tags, double u[3], void *vc) {
  const sph_ctx *c = vc;
  double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2], r = sqrt(r2), R = c->R;
  if (r <= R) {
    u[0] = u[1] = u[2] = 0;
    return;
  }
  double ux = c->U * x[0]; /* U . x with U = (U, 0, 0) */
  for (int i = 0; i < 3; i++) {
    double Ui = i == 0 ? c->U : 0;
    u[i] = Ui - 0.75 * R * (Ui / r + ux * x[i] / (r2 * r)) -
           0.25 * R * R * R * (Ui / (r2 * r) - 3 * ux * x[i] / (r2 * r2 * r));
  }
}
static double sph_p(const double x[3], uint32_t tags, void *vc) {
  const sph_ctx *c = vc;
  double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  return -1.5 * c->eta * c->R * c->U * x[0] / (r * r * r);
}

static void stokes_sphere(int k, double *drag_err, double *u_rms) {
  sessile_box box;
  sessile_tetmesh m = {0};
  double Lh = 3.0, o[3] = {-Lh, -Lh, -Lh}; /* cm, sphere radius 1 cm at the centre */
  make_mesh(o, 2 * Lh / k, k, k, k, &box, &m);
  sph_ctx c = {0.01, 1e-3, 5e-2};
  sessile_fluid_params p = test_params();
  p.rho = 0;
  p.velocity_tags = SESSILE_TAG_INLET | SESSILE_TAG_OUTLET | SESSILE_TAG_SIDE | SESSILE_TAG_SUBSTRATUM |
                    SESSILE_TAG_TOP;
  p.pressure_tags = SESSILE_TAG_OUTLET;
  p.velocity_fn = sph_u;
  p.pressure_fn = sph_p;
  p.bc_ctx = &c;
  uint8_t *solid = t_xalloc(m.nnodes);
  uint32_t nsolid = 0;
  for (uint32_t i = 0; i < m.nnodes; i++) {
    const double *x = m.xyz + 3 * i;
    solid[i] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] <= 1.0 + 1e-12;
    nsolid += solid[i];
  }
  sessile_fluid *fl = NULL;
  t_must("fluid create", sessile_fluid_create(la, &m, &fl));
  double *up = t_xalloc((size_t)m.nnodes * 4 * sizeof *up), *rr = t_xalloc((size_t)m.nnodes * 4 * sizeof *rr);
  sessile_fluid_result r;
  t_must("fluid solve", sessile_fluid_solve(fl, solid, &p, up, &r));
  t_must("fluid residual", sessile_fluid_residual(fl, &p, up, rr));
  double F[3] = {0, 0, 0}, se = 0;
  uint32_t nf = 0;
  for (uint32_t i = 0; i < m.nnodes; i++) {
    if (solid[i]) {
      for (int d = 0; d < 3; d++) F[d] -= rr[4 * i + d];
      continue;
    }
    double x[3] = {0.01 * m.xyz[3 * i], 0.01 * m.xyz[3 * i + 1], 0.01 * m.xyz[3 * i + 2]}, u[3];
    sph_u(x, 0, u, &c);
    for (int d = 0; d < 3; d++) se += (up[4 * i + d] - u[d]) * (up[4 * i + d] - u[d]);
    nf++;
  }
  double D = 6 * NS_PI * c.eta * c.R * c.U;
  *drag_err = fabs(F[0] - D) / D;
  *u_rms = sqrt(se / nf) / c.U;
  printf("  Stokes sphere h = R/%.2g (%u solid nodes): %d linear iterations, drag %.4e N vs 6 pi eta R U "
         "= %.4e N (rel err %.3f; lateral %.1e, %.1e), RMS velocity error / U = %.3e\n",
         k / (2 * Lh), nsolid, r.lin_iterations, F[0], D, *drag_err, F[1] / D, F[2] / D, *u_rms);
  t_true("Stokes sphere solve converged", r.converged);
  free(up);
  free(rr);
  free(solid);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
}

/* ---- manufactured solution -------------------------------------------------- */
typedef struct { double a, U, P, rho, eta; } mms_ctx;
static void mms_eval(const mms_ctx *c, const double x[3], double u[3], double Du[3][3], double *p,
                     double gp[3]) {
  double a = c->a, sx = sin(a * x[0]), cx = cos(a * x[0]), sy = sin(a * x[1]), cy = cos(a * x[1]),
         sz = sin(a * x[2]), cz = cos(a * x[2]), U = c->U;
  u[0] = U * sx * cy * cz;
  u[1] = U * cx * sy * cz;
  u[2] = -2 * U * cx * cy * sz;
  if (Du) { /* Du[i][j] = d u_i / d x_j */
    Du[0][0] = U * a * cx * cy * cz, Du[0][1] = -U * a * sx * sy * cz, Du[0][2] = -U * a * sx * cy * sz;
    Du[1][0] = -U * a * sx * sy * cz, Du[1][1] = U * a * cx * cy * cz, Du[1][2] = -U * a * cx * sy * sz;
    Du[2][0] = 2 * U * a * sx * cy * sz, Du[2][1] = 2 * U * a * cx * sy * sz, Du[2][2] = -2 * U * a * cx * cy * cz;
  }
  if (p) *p = c->P * cx * sy * cz;
  if (gp) {
    gp[0] = -c->P * a * sx * sy * cz;
    gp[1] = c->P * a * cx * cy * cz;
    gp[2] = -c->P * a * cx * sy * sz;
  }
}
static void mms_u(const double x[3], uint32_t tags, double u[3], void *vc) { mms_eval(vc, x, u, NULL, NULL, NULL); }
static double mms_p(const double x[3], uint32_t tags, void *vc) {
  double u[3], p;
  mms_eval(vc, x, u, NULL, &p, NULL);
  return p;
}
/* f = rho (u.grad) u - eta Lap u + grad p, with Lap u = -3 a^2 u */
static void mms_f(const double x[3], double f[3], void *vc) {
  const mms_ctx *c = vc;
  double u[3], Du[3][3], p, gp[3];
  mms_eval(c, x, u, Du, &p, gp);
  for (int i = 0; i < 3; i++)
    f[i] = c->rho * (Du[i][0] * u[0] + Du[i][1] * u[1] + Du[i][2] * u[2]) + 3 * c->eta * c->a * c->a * u[i] + gp[i];
}

static void mms_setup(int k, double U, sessile_tetmesh *m, sessile_fluid_params *p, mms_ctx *c) {
  sessile_box box;
  double o[3] = {0, 0, 0};
  make_mesh(o, 1.0 / k, k, k, k, &box, m); /* the unit cube in cm: 0.01 m */
  *c = (mms_ctx){NS_PI / 0.01, U, 1000.0 * U * U + 5e-2 * U / 0.01, 1000.0, 5e-2};
  *p = test_params();
  p->velocity_tags = SESSILE_TAG_INLET | SESSILE_TAG_OUTLET | SESSILE_TAG_SIDE | SESSILE_TAG_SUBSTRATUM |
                     SESSILE_TAG_TOP;
  p->pressure_tags = SESSILE_TAG_OUTLET;
  p->velocity_fn = mms_u;
  p->pressure_fn = mms_p;
  p->force_fn = mms_f;
  p->bc_ctx = c;
}

static void mms(int k, double *eu, double *ep) {
  sessile_tetmesh m = {0};
  sessile_fluid_params p;
  mms_ctx c;
  mms_setup(k, 0.001, &m, &p, &c); /* Re 0.2 */
  sessile_fluid *fl = NULL;
  t_must("fluid create", sessile_fluid_create(la, &m, &fl));
  double *up = t_xalloc((size_t)m.nnodes * 4 * sizeof *up);
  sessile_fluid_result r;
  t_must("fluid solve", sessile_fluid_solve(fl, NULL, &p, up, &r));
  /* L2 errors by the degree-2 rule; the mean pressure is fixed by the outlet data */
  double su = 0, sp = 0;
  for (uint32_t t = 0; t < m.ntets; t++) {
    const uint32_t *v = m.tet + 4 * t;
    double V = 1e-6 * sessile_tetmesh_tet_volume(&m, t);
    for (int q = 0; q < 4; q++) {
      double x[3], uh[4] = {0, 0, 0, 0}, u[3], pe;
      for (int i = 0; i < 3; i++) {
        x[i] = 0;
        for (int a = 0; a < 4; a++) x[i] += 0.01 * m.xyz[3 * v[a] + i] * (a == q ? NS_QA : NS_QB);
      }
      for (int a = 0; a < 4; a++)
        for (int i = 0; i < 4; i++) uh[i] += up[4 * v[a] + i] * (a == q ? NS_QA : NS_QB);
      mms_eval(&c, x, u, NULL, &pe, NULL);
      for (int i = 0; i < 3; i++) su += V / 4 * (uh[i] - u[i]) * (uh[i] - u[i]);
      sp += V / 4 * (uh[3] - pe) * (uh[3] - pe);
    }
  }
  double vol = 1e-6;
  *eu = sqrt(su / vol) / c.U;
  *ep = sqrt(sp / vol) / c.P;
  printf("  MMS h = 1/%d cm: %d Newton steps, %d linear iterations, velocity L2 / U = %.4e, pressure L2 / P = %.4e\n",
         k, r.nsteps, r.lin_iterations, *eu, *ep);
  t_true("MMS Newton converged", r.converged);
  free(up);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
}

/* ---- Newton's quadratic convergence ------------------------------------------------ */
static void newton_quadratic(void) {
  sessile_box box;
  sessile_tetmesh m = {0};
  double o[3] = {0, 0, 0};
  make_mesh(o, 0.5, 4, 2, 2, &box, &m); /* the Poiseuille channel, H = 1 cm, h = H/2 */
  pois_ctx c = {0.01, 0.02, 0.05, 5e-2}; /* Re = rho U H / eta = 10 */
  sessile_fluid_params p = test_params();
  p.velocity_tags = SESSILE_TAG_INLET | SESSILE_TAG_SIDE | SESSILE_TAG_SUBSTRATUM | SESSILE_TAG_TOP;
  p.velocity_fn = pois_u;
  p.bc_ctx = &c;
  p.newton_rtol = 1e-13;
  p.newton_atol = 0;
  p.linear_rtol = 1e-13;
  p.linear_max = 4000;
  sessile_fluid *fl = NULL;
  t_must("fluid create", sessile_fluid_create(la, &m, &fl));
  double *up = t_xalloc((size_t)m.nnodes * 4 * sizeof *up);
  sessile_fluid_result r;
  t_must("fluid solve", sessile_fluid_solve(fl, NULL, &p, up, &r));
  printf("  Newton from rest, Poiseuille channel h = H/2, Re 10, relative residuals:");
  double rel[SESSILE_FLUID_MAX_STEPS + 1];
  int n = r.nsteps;
  for (int s = 0; s < n; s++) rel[s] = r.step[s].residual / r.residual0;
  rel[n] = r.residual / r.residual0;
  for (int s = 0; s <= n; s++) printf(" %.2e", rel[s]);
  printf("\n");
  /* the last ratio taken where both residuals are above the linear solves' floor */
  double worst = 1e9;
  int used = 0;
  for (int s = 0; s < n; s++)
    if (rel[s] < 1e-2 && rel[s + 1] > 1e-11) {
      worst = fmin(worst, log(rel[s + 1]) / log(rel[s]));
      used++;
    }
  t_true("Newton: at least one step in the quadratic range", used >= 1);
  t_check("Newton: 1.6 - min log(r_{k+1})/log(r_k) (<= 0: quadratic)", 1.6 - worst, 0.0);
  free(up);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
}

/* ---- the parallel assembly ----------------------------------------------------- */
static void assembly_threads(int shuffle) {
  sessile_box box;
  sessile_tetmesh m = {0};
  double o[3] = {0, 0, 0};
  make_mesh(o, 0.5, 14, 12, 10, &box, &m); /* 10 080 tets: several chunks and colours */
  uint64_t mix = 5;
  for (uint32_t t = m.ntets - 1; shuffle && t > 0; t--) { /* tets in no spatial order */
    uint32_t u = (uint32_t)(urand(&mix) * (t + 1)), tmp[4];
    memcpy(tmp, m.tet + 4 * (size_t)t, sizeof tmp);
    memcpy(m.tet + 4 * (size_t)t, m.tet + 4 * (size_t)u, sizeof tmp);
    memcpy(m.tet + 4 * (size_t)u, tmp, sizeof tmp);
  }
  sessile_fluid *fl = NULL;
  t_must("fluid create", sessile_fluid_create(la, &m, &fl));
  size_t n4 = (size_t)m.nnodes * 4;
  double *up = t_xalloc(n4 * sizeof *up), *rhs[3], *rr = t_xalloc(n4 * sizeof *rr);
  uint64_t seed = 11;
  for (size_t k = 0; k < n4; k++) up[k] = 0.05 * (urand(&seed) - 0.5);
  sessile_fluid_params p = test_params();
  sessile_bcsr4 jac[3];
  int saved = omp_get_max_threads();
  omp_set_dynamic(0);
  for (int t = 0; t < 3; t++) {
    omp_set_num_threads(t + 1);
    rhs[t] = t_xalloc(n4 * sizeof *rhs[t]);
    t_must("fluid jacobian", sessile_fluid_jacobian(fl, NULL, &p, up, 0, &jac[t], rhs[t]));
  }
  omp_set_num_threads(saved);
  size_t nv = (size_t)jac[0].nnzb * 16;
  for (int t = 1; t < 3; t++) {
    char what[96];
    snprintf(what, sizeof what, "assembly with %d threads: the same bytes as with 1", t + 1);
    t_true(what, !memcmp(jac[t].val, jac[0].val, nv * sizeof *jac[0].val) &&
                     !memcmp(rhs[t], rhs[0], n4 * sizeof *rhs[0]));
  }
  /* a plain assembly, tet by tet in index order, without boundary rows */
  ns_assemble(fl, &p, up, 1.0, 1, rr);
  double *val = t_xalloc(nv * sizeof *val), *r = t_xalloc(n4 * sizeof *r);
  memset(val, 0, nv * sizeof *val);
  memset(r, 0, n4 * sizeof *r);
  ns_coef c = {p.rho, p.eta, p.lsic, 1.0};
  double Ke[256], Re[16];
  for (uint32_t t = 0; t < m.ntets; t++) {
    const uint32_t *v = fl->tet + 4 * (size_t)t; /* the fluid's order (a mesh not a box is sorted) */
    double X[4][3], U[16];
    for (int a = 0; a < 4; a++)
      for (int i = 0; i < 4; i++) {
        if (i < 3) X[a][i] = fl->x[3 * (size_t)v[a] + i]; /* metres */
        U[4 * a + i] = up[4 * (size_t)v[a] + i];
      }
    ns_element((const double(*)[3])X, U, NULL, &c, Re, Ke);
    for (int a = 0; a < 4; a++) {
      for (int i = 0; i < 4; i++) r[4 * (size_t)v[a] + i] += Re[4 * a + i];
      for (int b = 0; b < 4; b++)
        for (int i = 0; i < 4; i++)
          for (int j = 0; j < 4; j++)
            val[16 * (size_t)fl->pos[16 * (size_t)t + 4 * a + b] + 4 * i + j] += Ke[(4 * a + i) * 16 + 4 * b + j];
    }
  }
  double dv = 0, mv = 0, dr = 0, mr = 0;
  for (size_t k = 0; k < nv; k++) dv = fmax(dv, fabs(val[k] - fl->a.val[k])), mv = fmax(mv, fabs(val[k]));
  for (size_t k = 0; k < n4; k++) dr = fmax(dr, fabs(r[k] - rr[k])), mr = fmax(mr, fabs(r[k]));
  printf("  parallel assembly (%u tets%s, %u colours of chunks of %u) against tet by tet: Jacobian %.2e, "
         "residual %.2e of the largest entry\n", m.ntets, shuffle ? " shuffled" : "", fl->ncolours, fl->chunk,
         dv / mv, dr / mr);
  t_true("assembly: more than one colour of chunks (the test exercises the colouring)", fl->ncolours > 1);
  if (shuffle) t_true("assembly: a mesh in no spatial order is sorted (chunks of more than one tet)", fl->chunk > 1);
  /* the colouring's invariant: no node is shared by two chunks of a colour */
  uint32_t *owner = t_xalloc((size_t)m.nnodes * sizeof *owner), clash = 0, seen = 0;
  for (uint32_t col = 0; col < fl->ncolours; col++) {
    for (uint32_t i = 0; i < m.nnodes; i++) owner[i] = UINT32_MAX;
    for (uint32_t k = fl->cstart[col]; k < fl->cstart[col + 1]; k++) {
      uint32_t ch = fl->corder[k];
      for (uint64_t t = (uint64_t)ch * fl->chunk; t < (uint64_t)(ch + 1) * fl->chunk && t < m.ntets; t++, seen++)
        for (int a = 0; a < 4; a++) {
          uint32_t v = fl->tet[4 * t + a];
          if (owner[v] != UINT32_MAX && owner[v] != ch) clash++;
          owner[v] = ch;
        }
    }
  }
  free(owner);
  t_true("assembly: every tet in one chunk of the colouring", seen == m.ntets);
  t_true("assembly: no node shared by two chunks of one colour", clash == 0);
  t_check("assembly: Jacobian against tet by tet, relative to the largest entry", dv / mv, 1e-13);
  t_check("assembly: residual against tet by tet, relative to the largest entry", dr / mr, 1e-13);
  for (int t = 0; t < 3; t++) sessile_bcsr4_free(&jac[t]), free(rhs[t]);
  free(val), free(r), free(rr), free(up);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
}

/* ---- the nested start -------------------------------------------------------- */
/* A dome of radius 4 on the floor of a 20 x 20 x 16 box of 1.2 spacing
 * (7 497 nodes; the coarse box 1 089): its solid mask. */
static uint8_t *dome_scene(sessile_tetmesh *m) {
  sessile_box box;
  double o[3] = {0, 0, 0};
  make_mesh(o, 1.2, 20, 20, 16, &box, m);
  uint8_t *solid = t_xalloc(m->nnodes);
  for (uint32_t i = 0; i < m->nnodes; i++) {
    const double *x = m->xyz + 3 * i;
    double dx = x[0] - 12, dy = x[1] - 12, dz = x[2];
    solid[i] = dx * dx + dy * dy + dz * dz <= 4.0 * 4.0;
  }
  return solid;
}

/* max |u1 - u0| over the velocity components, over max |u0|. */
static double velocity_gap(double *const u[2], size_t n4) {
  double d = 0, um = 0;
  for (size_t k = 0; k < n4; k++)
    if (k % 4 != 3) d = fmax(d, fabs(u[1][k] - u[0][k])), um = fmax(um, fabs(u[0][k]));
  return d / um;
}

/* One Newton solve of the dome from rest to Newton 1e-9, linear 1e-10 (at
 * most 200 GMRES iterations a step); nested start and forcing as asked. */
static sessile_fluid_result dome_solve(const sessile_tetmesh *m, const uint8_t *solid, int nested,
                                       sessile_fluid_forcing forcing, double *u) {
  sessile_fluid *fl = NULL;
  sessile_fluid_result r;
  t_must("fluid create", sessile_fluid_create(la, m, &fl));
  sessile_fluid_params p = test_params();
  p.linear_rtol = 1e-10;
  p.linear_max = 200;
  p.newton_rtol = 1e-9;
  p.nested = nested;
  p.forcing = forcing;
  memset(u, 0, (size_t)m->nnodes * 4 * sizeof *u);
  t_must("fluid solve", sessile_fluid_solve(fl, solid, &p, u, &r));
  printf("  nested start %s, forcing %s: %s in %d fine Newton steps (%d linear iterations; aims", nested ? "on" : "off",
         forcing == SESSILE_FLUID_FORCING_EW ? "ew" : "fixed", r.converged ? "converged" : "NOT converged", r.nsteps,
         r.lin_iterations);
  for (int k = 0; k < r.nsteps; k++) printf(" %.1e (%d its)", r.step[k].lin_rtol, r.step[k].lin_iterations);
  printf("); coarse: %s, %d steps, %d iterations\n", r.coarse_tried ? "tried" : "not tried", r.coarse_steps,
         r.coarse_lin_iterations);
  sessile_fluid_destroy(fl);
  return r;
}

/* ---- the Eisenstat-Walker forcing ---------------------------------------------- */
/* The choice-2 tolerance written out again from fluid.h's description. */
static double ew_aim(const sessile_fluid_result *r, int k, double floor_rtol) {
  double eta = 0.3;
  for (int j = 1; j <= k; j++) {
    double e = pow(r->step[j].residual / r->step[j - 1].residual, (1.0 + sqrt(5.0)) / 2.0);
    double keep = pow(eta, (1.0 + sqrt(5.0)) / 2.0);
    eta = keep > 0.1 && keep > e ? keep : e;
    eta = fmax(fmin(eta, 0.9), floor_rtol);
  }
  return fmax(fmin(eta, 0.9), floor_rtol);
}

/* The nested start and the Eisenstat-Walker forcing, each against the same
 * plain solve (fixed forcing, no nested start: solved once for both). */
static void nested_and_forcing(void) {
  sessile_tetmesh m = {0};
  uint8_t *solid = dome_scene(&m);
  size_t n4 = (size_t)m.nnodes * 4;
  const double floor_rtol = 1e-10;
  double *u[3] = {t_dalloc(n4), t_dalloc(n4), t_dalloc(n4)};
  sessile_fluid_result r[3];
  r[0] = dome_solve(&m, solid, 0, SESSILE_FLUID_FORCING_FIXED, u[0]); /* plain */
  r[1] = dome_solve(&m, solid, 1, SESSILE_FLUID_FORCING_FIXED, u[1]); /* nested */
  r[2] = dome_solve(&m, solid, 0, SESSILE_FLUID_FORCING_EW, u[2]);    /* ew */

  t_true("nested start: both converge", r[0].converged && r[1].converged);
  t_true("nested start: off: no coarse solve", !r[0].coarse_tried);
  t_true("nested start: on: the coarse solution taken", r[1].coarse_tried && r[1].started_coarse);
  t_true("nested start: its start is nearer than rest", r[1].residual0 < 0.5 * r[1].residual_rest);
  t_true("nested start: fewer fine Newton steps", r[1].nsteps < r[0].nsteps);
  double *un[2] = {u[0], u[1]}, *ue[2] = {u[0], u[2]};
  t_check("nested start: the same solution (max velocity difference / max velocity)", velocity_gap(un, n4), 1e-6);

  t_true("forcing: both converge", r[0].converged && r[2].converged);
  int fixed_aims = 1, ew_aims = r[2].nsteps > 1, reached = 1;
  for (int k = 0; k < r[0].nsteps; k++) fixed_aims &= r[0].step[k].lin_rtol == floor_rtol;
  for (int k = 0; k < r[2].nsteps; k++) {
    double want = ew_aim(&r[2], k, floor_rtol);
    ew_aims &= fabs(r[2].step[k].lin_rtol - want) <= 1e-12 * want;
    reached &= r[2].step[k].lin_status == SESSILE_SOLVE_CONVERGED &&
               r[2].step[k].lin_relres <= r[2].step[k].lin_rtol * (1 + 1e-9);
  }
  t_true("forcing fixed: every step aims at linear_rtol", fixed_aims);
  t_true("forcing ew: each step aims at choice 2's tolerance from the step residuals", ew_aims);
  t_true("forcing ew: each step's true relative residual reaches its aim", reached);
  t_true("forcing ew: fewer linear iterations than fixed", r[2].lin_iterations < r[0].lin_iterations);
  t_check("forcing: the same solution (max velocity difference / max velocity)", velocity_gap(ue, n4), 1e-6);
  free(u[0]), free(u[1]), free(u[2]), free(solid);
  sessile_tetmesh_free(&m);
}

/* ---- the default scene ---------------------------------------------------------- */
static void scene(const double origin[3], double h, uint32_t cx, uint32_t cy, uint32_t cz, double R,
                  const sessile_fluid_params *p, int verbose) {
  sessile_box box;
  sessile_tetmesh m = {0};
  make_mesh(origin, h, cx, cy, cz, &box, &m);
  double mx[3];
  sessile_box_max(&box, mx);
  double ctr[2] = {0.5 * (origin[0] + mx[0]), 0.5 * (origin[1] + mx[1])};
  uint8_t *solid = t_xalloc(m.nnodes);
  for (uint32_t i = 0; i < m.nnodes; i++) {
    const double *x = m.xyz + 3 * i;
    double dx = x[0] - ctr[0], dy = x[1] - ctr[1], dz = x[2] - origin[2];
    solid[i] = dx * dx + dy * dy + dz * dz <= R * R;
  }
  double t0 = sessile_wall_seconds();
  sessile_fluid *fl = NULL;
  t_must("fluid create", sessile_fluid_create(la, &m, &fl));
  double tc = sessile_wall_seconds() - t0;
  double *up = t_xalloc((size_t)m.nnodes * 4 * sizeof *up);
  sessile_fluid_result r;
  sessile_fluid_params q = *p;
  q.monitor = verbose ? print_line : NULL;
  t_must("fluid solve", sessile_fluid_solve(fl, solid, &q, up, &r));
  printf("  scene %u x %u x %u nodes (%u tets), dome R %.1f cm: setup %.2f s; %s in %d steps, %d linear "
         "iterations, assembly %.2f s, solves %.2f s, total %.2f s, rel residual %.2e\n",
         box.n[0], box.n[1], box.n[2], m.ntets, R, tc, r.converged ? "converged" : "NOT converged",
         r.nsteps, r.lin_iterations, r.assembly_s, r.solve_s, r.seconds, r.residual / r.residual0);
  for (int s = 0; s < r.nsteps; s++)
    printf("    step %d: |R| %.3e, linear %d it relres %.2e %s, assembly %.3f s, solve %.3f s\n", s,
           r.step[s].residual, r.step[s].lin_iterations, r.step[s].lin_relres,
           sessile_solve_status_name(r.step[s].lin_status), r.step[s].assembly_s, r.step[s].solve_s);
  t_true("scene: Newton converged", r.converged);
  double umax = 0;
  for (uint32_t i = 0; i < m.nnodes; i++) umax = fmax(umax, fabs(up[4 * i]));
  t_check("scene: max |ux| / inlet below 3 (no blow-up)", umax / p->inlet[0], 3.0);
  /* warm start: a slightly larger dome */
  for (uint32_t i = 0; i < m.nnodes; i++) {
    const double *x = m.xyz + 3 * i;
    double dx = x[0] - ctr[0], dy = x[1] - ctr[1], dz = x[2] - origin[2];
    solid[i] = dx * dx + dy * dy + dz * dz <= (R + 0.5 * h) * (R + 0.5 * h);
  }
  sessile_fluid_result w;
  t_must("fluid warm solve", sessile_fluid_solve(fl, solid, &q, up, &w));
  printf("  warm re-solve (dome R + h/2): %s in %d steps, %d linear iterations, total %.2f s\n",
         w.converged ? "converged" : "NOT converged", w.nsteps, w.lin_iterations, w.seconds);
  free(up);
  free(solid);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  double tstart = sessile_wall_seconds();
  int bench = argc > 1 && strcmp(argv[1], "--bench") == 0;
  gpu = t_gpu(0);
  t_must("la", sessile_la_create(gpu, &la));
  if (bench) {
    int res = argc > 2 ? atoi(argv[2]) : 1;
    double o[3] = {0, 0, 0}, h = 1.2 / (1 << (res - 1));
    uint32_t f = 1u << (res - 1);
    sessile_fluid_params p;
    sessile_fluid_params_default(&p);
    if (argc > 3) p.ksp = atoi(argv[3]) ? SESSILE_KSP_BICGSTAB : SESSILE_KSP_GMRES;
    scene(o, h, 32 * f, 32 * f, 24 * f, 6.0, &p, 1);
    sessile_la_destroy(la);
    return t_finish(gpu);
  }

  if (argc > 1 && strcmp(argv[1], "--sphere") == 0) { /* one case, for debugging */
    double d, u;
    stokes_sphere(argc > 2 ? atoi(argv[2]) : 12, &d, &u);
    sessile_la_destroy(la);
    return t_finish(gpu);
  }
  if (argc > 1 && strcmp(argv[1], "--pois") == 0) {
    double g;
    pois_rho = argc > 3 ? atof(argv[3]) : 0.0;
    poiseuille(argc > 2 ? atoi(argv[2]) : 4, &g);
    sessile_la_destroy(la);
    return t_finish(gpu);
  }
  test_element_jacobian();
  test_element_units();
  assembly_threads(0);
  assembly_threads(1);

  double g4, g8;
  double e4 = poiseuille(4, &g4), e8 = poiseuille(8, &g8);
  t_check("Poiseuille max velocity error / U at h = H/8", e8, 2e-2);
  t_check("Poiseuille error ratio h=H/4 over H/8 >= 2.5 (shortfall)", fmax(0, 2.5 - e4 / e8), 0.0);
  t_check("Poiseuille max pressure error / (G L) at h = H/8", g8, 0.1);
  t_true("Poiseuille pressure error decreases under refinement", g8 < g4);

  double d1, d2, u1, u2;
  printf("  (%.1f s so far)\n", sessile_wall_seconds() - tstart);
  stokes_sphere(12, &d1, &u1);
  stokes_sphere(24, &d2, &u2);
  printf("  (%.1f s so far)\n", sessile_wall_seconds() - tstart);
  t_check("Stokes sphere drag relative error at h = R/4", d2, 0.25);
  t_true("Stokes sphere drag error decreases under refinement", d2 < d1);
  t_true("Stokes sphere velocity error decreases under refinement", u2 < u1);

  double eu[3], ep[3];
  int ks[3] = {4, 8, 16};
  for (int i = 0; i < 3; i++) mms(ks[i], &eu[i], &ep[i]);
  for (int i = 0; i < 2; i++) {
    double ou = log(eu[i] / eu[i + 1]) / log(2.0), op = log(ep[i] / ep[i + 1]) / log(2.0);
    printf("  MMS observed orders h=1/%d -> 1/%d: velocity %.2f, pressure %.2f\n", ks[i], ks[i + 1], ou, op);
    if (i == 1) {
      t_check("MMS velocity L2 order shortfall below 1.6", fmax(0, 1.6 - ou), 0.0);
      t_check("MMS pressure L2 order shortfall below 1.0", fmax(0, 1.0 - op), 0.0);
    }
  }

  printf("  (%.1f s so far)\n", sessile_wall_seconds() - tstart);
  newton_quadratic();
  nested_and_forcing();
  printf("  (%.1f s in all)\n", sessile_wall_seconds() - tstart);


  sessile_la_destroy(la);
  return t_finish(gpu);
}
