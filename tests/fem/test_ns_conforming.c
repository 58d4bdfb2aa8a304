/* Stokes flow past a sphere on the conforming (TetGen) mesh: the sphere's
 * surface is a no-slip boundary (SESSILE_TAG_SPONGE), the analytic Stokes
 * solution is imposed on the box walls (pressure at the outlet), and the drag
 * -- minus the sum of the momentum reactions at the sphere's nodes -- is
 * compared with 6 pi eta R U.  Tolerance 5 % (the target).  The
 * velocity error is printed at two mesh sizes and must decrease. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/fem/fluid.h"
#include "sessile/mesh/tetgen.h"
#include "testutil.h"

#define PI 3.14159265358979323846
typedef struct { double R, U, eta; } sph_ctx;

/* Stokes' solution around a sphere of radius R at the origin, far velocity
 * (U, 0, 0); x in metres. */
static void sph_u(const double x[3], uint32_t tags, double u[3], void *vc) {
  const sph_ctx *c = vc;
  double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2], r = sqrt(r2), R = c->R;
  if (r <= R * (1 + 1e-9) || (tags & SESSILE_TAG_SPONGE)) {
    u[0] = u[1] = u[2] = 0;
    return;
  }
  double ux = c->U * x[0];
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

static void run(sessile_la *la, double size_sponge, double size_far, double *drag_err, double *u_rms) {
  /* Box [-3, 3]^3 cm, sphere of radius 1 cm (a level-4 icosphere: its
   * volume is within 1 % of the ball's). */
  sessile_box box;
  const double o[3] = {-3, -3, -3};
  const uint32_t cells[3] = {6, 6, 6};
  t_ok("box", sessile_box_make(o, 1.0, cells, 1, &box));
  sessile_surface s = {0};
  const double c0[3] = {0, 0, 0};
  t_ok("icosphere", sessile_surface_icosphere(4, 1.0, c0, &s));
  sessile_tetgen_options to;
  sessile_tetgen_options_default(&to);
  to.size_sponge = size_sponge;
  to.size_far = size_far;
  sessile_tetmesh m = {0};
  t_ok("tetgen", sessile_tetgen_conforming(&box, &s, &to, &m));
  sph_ctx c = {0.01, 1e-3, 5e-2};
  sessile_fluid_params p;
  sessile_fluid_params_default(&p);
  p.rho = 0;
  p.linear_rtol = 1e-8;
  p.linear_max = 3000;
  p.restart = 64;
  p.newton_rtol = 1e-8;
  p.newton_max = 10;
  p.velocity_tags = SESSILE_TAG_INLET | SESSILE_TAG_OUTLET | SESSILE_TAG_SIDE | SESSILE_TAG_SUBSTRATUM |
                    SESSILE_TAG_TOP | SESSILE_TAG_SPONGE;
  p.noslip_tags = SESSILE_TAG_SPONGE;
  p.pressure_tags = SESSILE_TAG_OUTLET;
  p.velocity_fn = sph_u;
  p.pressure_fn = sph_p;
  p.bc_ctx = &c;
  sessile_fluid *fl = NULL;
  double *up = calloc((size_t)m.nnodes * 4, sizeof *up), *rr = calloc((size_t)m.nnodes * 4, sizeof *rr);
  sessile_fluid_result r;
  memset(&r, 0, sizeof r);
  t_ok("fluid create", sessile_fluid_create(la, &m, &fl));
  t_ok("fluid solve", sessile_fluid_solve(fl, NULL, &p, up, &r));
  t_ok("fluid residual", sessile_fluid_residual(fl, &p, up, rr));
  double F[3] = {0, 0, 0}, se = 0;
  uint32_t nf = 0, ns = 0;
  for (uint32_t i = 0; i < m.nnodes; i++) {
    if (m.node_tags[i] & SESSILE_TAG_SPONGE) {
      for (int d = 0; d < 3; d++) F[d] -= rr[4 * i + d];
      ns++;
      continue;
    }
    double x[3] = {0.01 * m.xyz[3 * i], 0.01 * m.xyz[3 * i + 1], 0.01 * m.xyz[3 * i + 2]}, u[3];
    sph_u(x, 0, u, &c);
    for (int d = 0; d < 3; d++) se += (up[4 * i + d] - u[d]) * (up[4 * i + d] - u[d]);
    nf++;
  }
  double D = 6 * PI * c.eta * c.R * c.U;
  *drag_err = fabs(F[0] - D) / D;
  *u_rms = sqrt(se / nf) / c.U;
  printf("  conforming Stokes sphere, %u nodes (%u on the sphere), %u tets: %d linear iterations, "
         "drag %.4e N vs 6 pi eta R U = %.4e N (rel err %.4f; lateral %.1e, %.1e), RMS velocity error / U %.3e\n",
         m.nnodes, ns, m.ntets, r.lin_iterations, F[0], D, *drag_err, F[1] / D, F[2] / D, *u_rms);
  t_true("Stokes solve converged", r.converged);
  free(up);
  free(rr);
  sessile_fluid_destroy(fl);
  sessile_tetmesh_free(&m);
  sessile_surface_free(&s);
}

int main(void) {
  sessile_gpu *g = t_gpu(0);
  sessile_la *la = NULL;
  t_ok("la", sessile_la_create(g, &la));
  double d1, u1, d2, u2;
  run(la, 0.0, 0.6, &d1, &u1);
  run(la, 0.0, 0.3, &d2, &u2);
  t_check("drag relative error vs 6 pi eta R U (finer mesh)", d2, 0.05);
  t_true("velocity error decreases under refinement", u2 < u1);
  sessile_la_destroy(la);
  return t_finish(g);
}
