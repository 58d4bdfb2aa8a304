/* The integrator on the host (the reference of the GPU's integrate kernel)
 * and the inverted-tet detection (§3.1.2). */
#include <math.h>
#include <stdlib.h>
#include "sds/sds_internal.h"

/* Semi-implicit Euler, the velocity form of position Verlet (leapfrog):
 * v_{n+1} = v_n + dt F(x_n, v_n) / m, x_{n+1} = x_n + dt v_{n+1}. */
double sessile_sds_step_ref(sessile_sds *o, const sessile_sds_params *p, double dt) {
  double *f = malloc(3 * (size_t)o->ncells * sizeof *f);
  if (!f) return NAN;
  sessile_sds_forces_ref(o, p, 1, f);
  /* the friction's normals at the step's start (as the gather) */
  int fric = p->friction > 0 && p->obstacle.nf;
  sessile_sds_contact *ct = fric ? malloc((o->ncells ? o->ncells : 1) * sizeof *ct) : NULL;
  if (ct && sessile_sds_contacts(o, p, ct) != SESSILE_OK) free(ct), ct = NULL;
  /* the inertia of mass scaling (1 without it) */
  double *al = p->mass_scaling_dt > 0 ? malloc((o->ncells ? o->ncells : 1) * sizeof *al) : NULL;
  if (al && sessile_sds_inertia(o, p, al) != SESSILE_OK) free(al), al = NULL;
  if (p->mass_scaling_dt > 0 && !al) {
    free(f), free(ct);
    return NAN;
  }
  double mv = 0;
  for (uint32_t c = 0; c < o->ncells; c++) {
    double d2 = 0, n[3], mi = al ? o->m[c] * al[c] : o->m[c];
    for (int i = 0; i < 3; i++) {
      size_t k = 3 * (size_t)c + i;
      o->v[k] += dt * f[k] / mi;
    }
    sessile_sds_contact one;
    if (fric && !ct) sessile_sds_contact_brute(o, p, c, o->x + 3 * (size_t)c, &one);
    if (fric && sessile_sds_friction_normal(p, o->x + 3 * (size_t)c, ct ? &ct[c] : &one, n)) {
      /* backward Euler on -friction v_t: unconditionally stable, so the
       * bound needs no term for it */
      double *v = o->v + 3 * (size_t)c, vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
      for (int i = 0; i < 3; i++) v[i] = vn * n[i] + (v[i] - vn * n[i]) / (1 + dt * p->friction);
    }
    for (int i = 0; i < 3; i++) {
      size_t k = 3 * (size_t)c + i;
      double dx = dt * o->v[k];
      o->x[k] += dx;
      d2 += dx * dx;
    }
    double mm = sqrt(d2) / o->r[c];
    if (mm > mv || mm != mm) mv = mm;
  }
  free(f), free(ct), free(al);
  return mv;
}

sessile_status sessile_sds_inverted_ref(const sessile_sds *o, uint32_t **list, uint32_t *n) {
  uint32_t cnt = 0;
  for (uint32_t t = 0; t < o->ntets; t++)
    if (!(sessile_sds_tet_volume(o, t) > 0)) cnt++;
  *list = malloc((cnt ? cnt : 1) * sizeof **list);
  SESSILE_CHECK(*list, SESSILE_ERR_NO_MEMORY, "sds: out of memory for %u inverted tets", cnt);
  cnt = 0;
  for (uint32_t t = 0; t < o->ntets; t++)
    if (!(sessile_sds_tet_volume(o, t) > 0)) (*list)[cnt++] = t;
  *n = cnt;
  return SESSILE_OK;
}

/* A bound on the stable step of semi-implicit Euler.  For one mode
 * x'' = -omega^2 x - gamma x' the scheme is stable when
 * (omega dt)^2 + 2 gamma dt < 4.  Per cell, Gershgorin's theorem on M^-1 H
 * at rest bounds omega^2: its edges give 2 K_e (K_e = d2E/dL2 = s_k / R'^2:
 * k_e (m_a + m_b) / R', or k_e / R'^2 with uniform stiffness), its tets s_t / R'^2 |grad_c V| sum_j |grad_j V|, the
 * walls k_wall (or the obstacle's adhesion slope 2 A / delta where larger;
 * its friction is implicit and needs no term); gamma likewise from the volume damping (damp_vol in place of
 * k_vol) plus the viscous c; a surface cell adds k_contact when
 * self-collision is on (the contact penalty's stiffness per unit mass).  Returns the smallest root over the cells,
 * 0 when out of memory (a bound of dt_min here made a failed allocation read
 * as springs too stiff to run).  With mass scaling (p->mass_scaling_dt H > 0)
 * a cell whose root h is below H takes the inertia alpha m, alpha =
 * (w2 H^2 + 2 gam H) / 4, whose root is H; alpha (1 elsewhere) goes to
 * alpha[c] when alpha is not NULL (stable.glsl's, operation for operation). */
static double stable_cells(const sessile_sds *o, const sessile_sds_params *p, double *alpha) {
  double *lam = calloc(o->ncells ? 2 * (size_t)o->ncells : 1, sizeof *lam); /* omega^2, gamma */
  if (!lam) return 0;
  for (uint32_t e = 0; e < o->nedges; e++) {
    const uint32_t *q = o->edge + 2 * (size_t)e;
    double R = o->edge_sm[e] * (o->r[q[0]] + o->r[q[1]]);
    double ks = p->k_edge * sds_edge_mult(o, p, e);
    double K = p->uniform_stiffness ? ks / (R * R) : ks * (o->m[q[0]] + o->m[q[1]]) / R; /* s_k / R'^2 */
    lam[2 * q[0]] += 2 * K, lam[2 * q[1]] += 2 * K;
  }
  for (uint32_t t = 0; t < o->ntets; t++) {
    const uint32_t *q = o->tet + 4 * (size_t)t;
    const double *x0 = o->x + 3 * (size_t)q[0];
    double a[3], b[3], c[3], g[4][3], gl[4], gs = 0;
    sds_sub(x0, o->x + 3 * (size_t)q[1], a), sds_sub(x0, o->x + 3 * (size_t)q[2], b);
    sds_sub(x0, o->x + 3 * (size_t)q[3], c);
    sds_cross(b, c, g[1]), sds_cross(c, a, g[2]), sds_cross(a, b, g[3]);
    for (int i = 0; i < 3; i++) g[0][i] = -(g[1][i] + g[2][i] + g[3][i]);
    for (int k = 0; k < 4; k++) gl[k] = sqrt(sds_dot(g[k], g[k])) / 6.0, gs += gl[k];
    double R = o->tet_sm[t] * sessile_sds_tet_rest_of(o, t);
    double s = sds_tet_scale(o, p, t) / (R * R);
    double ks = p->k_vol * (o->tet_surface[t] ? p->surface_mult : 1.0) * s, ds = p->damp_vol * s;
    for (int k = 0; k < 4; k++) lam[2 * q[k]] += ks * gl[k] * gs, lam[2 * q[k] + 1] += ds * gl[k] * gs;
  }
  double wall = p->box || p->obstacle.nf ? p->k_wall : 0, dt = p->dt_max;
  /* the adhesion's slope, 2 A / delta, where it exceeds the wall's */
  double adh = sds_stab_adhesion(p);
  for (uint32_t c = 0; c < o->ncells; c++) {
    double wc = adh / o->r[c] > wall ? adh / o->r[c] : wall;
    double w2 = lam[2 * c] / o->m[c] + wc + (p->self_collide && o->surface && o->surface[c] ? p->k_contact : 0),
           gam = lam[2 * c + 1] / o->m[c] + p->damp_visc;
    /* the positive root of w2 dt^2 + 2 gam dt - 4 = 0 */
    double h = w2 > 0 ? 4.0 / (gam + sqrt(gam * gam + 4 * w2)) : (gam > 0 ? 2.0 / gam : p->dt_max);
    double H = p->mass_scaling_dt, a = 1;
    if (H > 0 && h < H) a = (w2 * H * H + 2 * gam * H) / 4, h = H;
    if (alpha) alpha[c] = a;
    if (h < dt) dt = h;
  }
  free(lam);
  return dt;
}

double sessile_sds_stable_dt(const sessile_sds *o, const sessile_sds_params *p) { return stable_cells(o, p, NULL); }

sessile_status sessile_sds_inertia(const sessile_sds *o, const sessile_sds_params *p, double *alpha) {
  SESSILE_CHECK(stable_cells(o, p, alpha) > 0, SESSILE_ERR_NO_MEMORY, "sds: out of memory for the stable bound");
  return SESSILE_OK;
}

/* The critical step of semi-implicit Euler at the current state, undamped:
 * 2 / sqrt(lambda_max) of the generalised problem K u = lambda M u, K the
 * Jacobian of -F (central differences of sessile_sds_forces_ref without
 * damping, a step of 1e-7 mean radii), by power iteration on M^-1 K from a
 * fixed pseudo-random start.  The Rayleigh quotient never exceeds lambda_max,
 * so an iteration stopped early errs toward a longer step: *residual gets
 * the relative residual |K u - lambda M u|_{M^-1} / (lambda |u|_M) of the
 * last iterate, which says how far it settled.  A reference for the tests and
 * the benchmark (docs/sds.md, "Integrator"), not for the loop.  Returns 0
 * when out of memory. */
double sessile_sds_critical_dt(const sessile_sds *o, const sessile_sds_params *p, int iters, double *residual) {
  size_t n = 3 * (size_t)o->ncells;
  double *buf = malloc(5 * (n ? n : 1) * sizeof *buf);
  if (residual) *residual = INFINITY;
  if (!buf || !n) {
    free(buf);
    return 0;
  }
  double *x = buf, *u = buf + n, *fp = buf + 2 * n, *fm = buf + 3 * n, *ku = buf + 4 * n;
  sessile_sds q = *o; /* the same complex at displaced positions */
  q.x = x;
  double rmean = 0;
  for (uint32_t c = 0; c < o->ncells; c++) rmean += o->r[c] / o->ncells;
  uint64_t z = 0x9e3779b97f4a7c15ull;
  for (size_t i = 0; i < n; i++) { /* splitmix64: a start with a part along every mode */
    uint64_t w = (z += 0x9e3779b97f4a7c15ull);
    w = (w ^ (w >> 30)) * 0xbf58476d1ce4e5b9ull, w = (w ^ (w >> 27)) * 0x94d049bb133111ebull, w ^= w >> 31;
    u[i] = (double)(w >> 11) / 9007199254740992.0 - 0.5;
  }
  double lam = 0;
  for (int it = 0; it < iters; it++) {
    double umax = 0;
    for (size_t i = 0; i < n; i++) umax = fmax(umax, fabs(u[i]));
    if (!(umax > 0) || !isfinite(umax)) break;
    for (size_t i = 0; i < n; i++) u[i] /= umax; /* kept at unit size: lambda^k would overflow */
    double h = 1e-7 * rmean;
    for (size_t i = 0; i < n; i++) x[i] = o->x[i] + h * u[i];
    sessile_sds_forces_ref(&q, p, 0, fp);
    for (size_t i = 0; i < n; i++) x[i] = o->x[i] - h * u[i];
    sessile_sds_forces_ref(&q, p, 0, fm);
    double uku = 0, umu = 0;
    for (size_t i = 0; i < n; i++) {
      ku[i] = -(fp[i] - fm[i]) / (2 * h);
      uku += u[i] * ku[i], umu += u[i] * u[i] * o->m[i / 3];
    }
    lam = uku / umu;
    double r2 = 0;
    for (size_t i = 0; i < n; i++) {
      double ri = ku[i] - lam * o->m[i / 3] * u[i];
      r2 += ri * ri / o->m[i / 3];
      u[i] = ku[i] / o->m[i / 3]; /* the next iterate: M^-1 K u */
    }
    if (residual) *residual = sqrt(r2 / umu) / fabs(lam);
  }
  free(buf);
  return lam > 0 ? 2 / sqrt(lam) : INFINITY;
}
