/* The nested start ("nested iteration", full-multigrid Newton): a start far
 * from the solution (from rest, or a snapshot's warm start after ten growth
 * iterations) costs Newton 4-5 steps on the fine box; the solution of the
 * same problem on the box of twice the spacing, interpolated, is within its
 * discretisation error of the fine one, and the fine Newton needs about two.
 * The coarse solve is the same solver at an eighth of the nodes (and nests
 * again while the grid halves to at least NEST_MIN_NODES).  The fine Newton
 * still converges to its own tolerance: the result is the fine problem's,
 * only the path to it is shorter.  Measurements: docs/fluid.md, "Nested
 * start". */
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"
#include "sessile/mesh/box.h"
#include "sessile/mesh/tetmesh.h"

#define NEST_MIN_NODES 1000u /* the coarse box's nodes at least */
#define NEST_FROM 0.2        /* tried when the start's residual exceeds this of the rest state's */
#define NEST_NEWTON_FACTOR 100.0 /* the coarse Newton's tolerance over the fine one's (at most 0.1) */
#define NEST_LINEAR_RTOL 1e-2   /* the coarse linear solves' tolerance (docs/fluid.md, "Nested start") */

/* The coarse box's nodes per axis (0 when the grid does not halve). */
static uint32_t coarse_grid(const uint32_t n[3], uint32_t m[3]) {
  for (int a = 0; a < 3; a++) {
    if (n[a] < 3 || (n[a] - 1) % 2) return 0;
    m[a] = (n[a] - 1) / 2 + 1;
  }
  return m[0] * m[1] * m[2];
}

static sessile_status make_nest(sessile_fluid *fl, const uint32_t m[3]) {
  if (fl->nest) return SESSILE_OK;
  /* the fine box: x is in metres, the mesh wants centimetres */
  sessile_box b = {.origin = {100.0 * fl->x[0], 100.0 * fl->x[1], 100.0 * fl->x[2]},
                   .h = 2.0 * 100.0 * (fl->x[3] - fl->x[0])};
  memcpy(b.n, m, sizeof b.n);
  sessile_tetmesh tm = {0};
  sessile_status s = sessile_tetmesh_from_box(&b, &tm);
  if (s == SESSILE_OK) s = sessile_fluid_create(fl->la, &tm, &fl->nest);
  sessile_tetmesh_free(&tm);
  return s;
}

sessile_status ns_nested_start(sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                               const uint8_t *bc, double *up, double r_up, double *r, sessile_fluid_result *res) {
  uint32_t m[3];
  if (!fl->grid[0] || coarse_grid(fl->grid, m) < NEST_MIN_NODES) return SESSILE_OK;
  double r0 = r_up;
  if (r0 < 0) {
    ns_assemble(fl, p, up, 1.0, 0, r);
    r0 = ns_apply_bc_rows(fl, bc, 0, r);
  }
  if (!(r0 > NEST_FROM * res->residual_rest)) return SESSILE_OK; /* a good warm start */
  SESSILE_CALL(make_nest(fl, m));
  sessile_fluid *c = fl->nest;
  const uint32_t *n = fl->grid;
  size_t n4 = (size_t)fl->nnodes * 4;
  uint8_t *cs = malloc(c->nnodes);
  double *u = malloc((size_t)c->nnodes * 4 * sizeof *u), *alt = malloc(n4 * sizeof *alt);
  sessile_status s = cs && u && alt ? SESSILE_OK : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  /* coarse node I is fine node 2I: the start and the solid mask injected */
  for (uint32_t i = 0; s == SESSILE_OK && i < c->nnodes; i++) {
    uint32_t ci = i % m[0], cj = (i / m[0]) % m[1], ck = i / (m[0] * m[1]);
    size_t f = 2 * ci + (size_t)n[0] * (2 * cj + (size_t)n[1] * 2 * ck);
    cs[i] = solid ? solid[f] : 0;
    memcpy(u + 4 * (size_t)i, up + 4 * f, 4 * sizeof *u);
  }
  sessile_fluid_params q = *p;
  q.monitor = NULL; /* one line for the whole coarse solve, below */
  /* looser than the fine solve: the interpolated start is judged by the fine
   * residual, which interpolation alone leaves at about a fifth of the rest
   * state's; a coarse solution within a tenth of its own rest state's
   * (linear solves to 1e-2) starts the fine Newton as well as a tight one
   * (the same fine steps; docs/fluid.md, "Nested start: measured") */
  q.newton_rtol = NEST_NEWTON_FACTOR * p->newton_rtol;
  if (q.newton_rtol > 0.1) q.newton_rtol = 0.1;
  if (q.linear_rtol < NEST_LINEAR_RTOL) q.linear_rtol = NEST_LINEAR_RTOL;
  /* already inexact at 1e-2: Eisenstat-Walker on top loosened its steps
   * further and took 6 coarse Newton steps where 4 do (docs/fluid.md) */
  q.forcing = SESSILE_FLUID_FORCING_FIXED;
  sessile_fluid_result cr;
  if (s == SESSILE_OK) {
    res->coarse_tried = 1;
    s = sessile_fluid_solve(c, cs, &q, u, &cr);
    res->coarse_steps = cr.nsteps + cr.coarse_steps;
    res->coarse_lin_iterations = cr.lin_iterations + cr.coarse_lin_iterations;
    res->coarse_seconds = cr.seconds;
    /* a coarse problem that would not converge leaves the fine start as it was */
    if (s == SESSILE_ERR_NUMERIC) {
      ns_monitor(p, "fluid nested start: the coarse solve failed (%s); starting from the given state",
                 sessile_error_message());
      sessile_error_clear();
      s = SESSILE_OK;
      goto out;
    }
  }
  if (s != SESSILE_OK) goto out;
  /* P1 interpolation on the coarse Kuhn box: fine node 2I + d (d in {0,1}^3)
   * is coarse node I or the midpoint of the coarse edge I -> I + d (every
   * d != 0 is one of the Kuhn edge directions) */
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    uint32_t x = i % n[0], y = (i / n[0]) % n[1], z = i / (n[0] * n[1]);
    size_t I = x / 2 + (size_t)m[0] * (y / 2 + (size_t)m[1] * (z / 2));
    size_t d = (x & 1) + (size_t)m[0] * ((y & 1) + (size_t)m[1] * (z & 1));
    for (int a = 0; a < 4; a++) alt[4 * (size_t)i + a] = 0.5 * (u[4 * I + a] + u[4 * (I + d) + a]);
  }
  ns_impose_bc(fl, solid, p, bc, alt);
  ns_assemble(fl, p, alt, 1.0, 0, r);
  double r1 = ns_apply_bc_rows(fl, bc, 0, r);
  if (r1 < r0) {
    memcpy(up, alt, n4 * sizeof *up);
    res->started_coarse = 1;
  }
  ns_monitor(p, "fluid nested start: %u coarse nodes, %d Newton steps, %d linear iterations, %.2f s: "
                "|R| %.3e (rel %.2e) against the given start's %.3e: %s",
             c->nnodes, res->coarse_steps, res->coarse_lin_iterations, res->coarse_seconds, r1,
             r1 / res->residual_rest, r0, res->started_coarse ? "taken" : "not taken");
out:
  free(cs), free(u), free(alt);
  return s;
}
