/* The physics on the host (the reference of shaders/sds): scale-free edge and
 * volume springs E = k/2 ((V - R')/R')^2 (§3.2), damping, gravity, the box,
 * attraction points, contacts with an obstacle and of the surface with
 * itself (sds_hash.c).  Forces are gathered per cell over its
 * incident edges and tets in CSR order, the GPU's order. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sds/sds_internal.h"

void sessile_sds_params_default(sessile_sds_params *p) {
  memset(p, 0, sizeof *p);
  p->k_edge = 1.0;       /* prototype */
  p->k_vol = 2.0;        /* prototype */
  p->surface_mult = 1.0; /* prototype */
  p->damp_visc = 1.0;    /* prototype VISCOSITY 0.01 per step, as a rate (docs/sds.md, "Damping") */
  p->damp_vol = 0.001;   /* prototype kDamp: the tets' damping */
  p->gravity = 10.0;     /* prototype */
  p->k_wall = 1000.0;    /* ours: a 1 % radius penetration at g = 10 for r = 1 */
  p->k_attract = 1.0;
  p->self_collide = 1, p->contact_scale = 1.0; /* ours: a cell is a sphere of its radius */
  p->k_contact = 1000.0;                       /* ours: as k_wall */
  p->dt = 1e-3, p->dt_min = 1e-7, p->dt_max = 0.05, p->max_move = 0.05;
  p->stable_safety = 0.8;
}

double sds_edge_scale(const sessile_sds *o, const sessile_sds_params *p, uint32_t e) {
  if (p->uniform_stiffness) return 1.0;
  uint32_t a = o->edge[2 * (size_t)e], b = o->edge[2 * (size_t)e + 1];
  return o->edge_sm[e] * (o->r[a] + o->r[b]) * (o->m[a] + o->m[b]);
}

double sds_tet_scale(const sessile_sds *o, const sessile_sds_params *p, uint32_t t) {
  if (p->uniform_stiffness) return 1.0;
  const uint32_t *q = o->tet + 4 * (size_t)t;
  double rs = 0, ms = 0;
  for (int i = 0; i < 4; i++) rs += o->r[q[i]], ms += o->m[q[i]];
  return 0.5 * rs * 0.5 * ms;
}

void sds_external_accel(const sessile_sds_params *p, const double *x, int32_t attract, double *acc) {
  acc[0] = 0, acc[1] = 0, acc[2] = -p->gravity;
  if (p->box)
    for (int i = 0; i < 3; i++) {
      if (x[i] < p->box_lo[i]) acc[i] += p->k_wall * (p->box_lo[i] - x[i]);
      if (x[i] > p->box_hi[i]) acc[i] -= p->k_wall * (x[i] - p->box_hi[i]);
    }
  if (attract >= 0 && (uint32_t)attract < p->nattract) {
    double d[3];
    sds_sub(x, p->attract_pos + 3 * (size_t)attract, d);
    double l = sqrt(sds_dot(d, d));
    if (l > 0)
      for (int i = 0; i < 3; i++) acc[i] += p->k_attract * d[i] / l;
  }
}

double sds_external_potential(const sessile_sds_params *p, const double *x, int32_t attract) {
  double u = p->gravity * x[2];
  if (p->box)
    for (int i = 0; i < 3; i++) {
      double d = x[i] < p->box_lo[i] ? p->box_lo[i] - x[i] : (x[i] > p->box_hi[i] ? x[i] - p->box_hi[i] : 0);
      u += 0.5 * p->k_wall * d * d;
    }
  if (attract >= 0 && (uint32_t)attract < p->nattract) {
    double d[3];
    sds_sub(x, p->attract_pos + 3 * (size_t)attract, d);
    u += p->k_attract * sqrt(sds_dot(d, d));
  }
  return u;
}

/* The contacts of every cell through the host hash; NULL when out of
 * memory (the callers then ask the brute force cell by cell). */
static sessile_sds_contact *contacts_of(const sessile_sds *o, const sessile_sds_params *p) {
  sessile_sds_contact *ct = malloc((o->ncells ? o->ncells : 1) * sizeof *ct);
  if (ct && sessile_sds_contacts(o, p, ct) != SESSILE_OK) free(ct), ct = NULL;
  return ct;
}

void sessile_sds_energy_of(const sessile_sds *o, const sessile_sds_params *p, sessile_sds_energy *e) {
  memset(e, 0, sizeof *e);
  for (uint32_t k = 0; k < o->nedges; k++) {
    const uint32_t *q = o->edge + 2 * (size_t)k;
    double d[3];
    sds_sub(o->x + 3 * (size_t)q[0], o->x + 3 * (size_t)q[1], d);
    double R = o->edge_sm[k] * (o->r[q[0]] + o->r[q[1]]), s = (sqrt(sds_dot(d, d)) - R) / R;
    double kk = p->k_edge * sds_edge_mult(o, p, k) * sds_edge_scale(o, p, k);
    e->edge += 0.5 * kk * s * s;
  }
  for (uint32_t t = 0; t < o->ntets; t++) {
    double R = o->tet_sm[t] * sessile_sds_tet_rest_of(o, t), s = (sessile_sds_tet_volume(o, t) - R) / R;
    double kk = p->k_vol * (o->tet_surface[t] ? p->surface_mult : 1.0) * sds_tet_scale(o, p, t);
    e->vol += 0.5 * kk * s * s;
  }
  sessile_sds_contact *ct = contacts_of(o, p);
  for (uint32_t c = 0; c < o->ncells; c++) {
    const double *v = o->v + 3 * (size_t)c, *x = o->x + 3 * (size_t)c;
    double acc[3] = {0, 0, 0};
    sessile_sds_contact one;
    if (!ct) sessile_sds_contact_brute(o, p, c, x, &one);
    e->kinetic += 0.5 * o->m[c] * sds_dot(v, v);
    e->potential += o->m[c] * (sds_external_potential(p, x, o->attract[c]) +
                               sessile_sds_contact_accel(o, p, c, x, ct ? &ct[c] : &one, acc));
  }
  free(ct);
}

double sessile_sds_energy_total(const sessile_sds_energy *e) {
  return e->edge + e->vol + e->potential + e->kinetic;
}

/* Force of edge e on its cell `which` (0: a, 1: b). */
static void edge_force(const sessile_sds *o, const sessile_sds_params *p, uint32_t e, int which,
                       double *f) {
  const uint32_t *q = o->edge + 2 * (size_t)e;
  double d[3];
  sds_sub(o->x + 3 * (size_t)q[0], o->x + 3 * (size_t)q[1], d);
  double L = sqrt(sds_dot(d, d));
  double R = o->edge_sm[e] * (o->r[q[0]] + o->r[q[1]]);
  double kk = p->k_edge * sds_edge_mult(o, p, e) * sds_edge_scale(o, p, e);
  double g = kk * (L - R) / (R * R) / L; /* dE/dx_b = g d */
  double sg = which ? -g : g;
  for (int i = 0; i < 3; i++) f[i] = sg * d[i];
}

/* Force of tet t on its vertex slot j: elastic, and with damping the
 * volume-rate damping -c scale (dV/dt)/R'^2 grad_j V (a Rayleigh
 * dissipation, so it never adds energy). */
static void tet_force(const sessile_sds *o, const sessile_sds_params *p, uint32_t t, int j, int with_damping,
                      double *f) {
  const uint32_t *q = o->tet + 4 * (size_t)t;
  const double *x0 = o->x + 3 * (size_t)q[0];
  double a[3], b[3], c[3], g[4][3];
  sds_sub(x0, o->x + 3 * (size_t)q[1], a), sds_sub(x0, o->x + 3 * (size_t)q[2], b);
  sds_sub(x0, o->x + 3 * (size_t)q[3], c);
  sds_cross(b, c, g[1]), sds_cross(c, a, g[2]), sds_cross(a, b, g[3]);
  for (int i = 0; i < 3; i++) {
    g[1][i] /= 6.0, g[2][i] /= 6.0, g[3][i] /= 6.0;
    g[0][i] = -(g[1][i] + g[2][i] + g[3][i]);
  }
  double V = sds_dot(a, g[1]);
  double R = o->tet_sm[t] * sessile_sds_tet_rest_of(o, t), sc = sds_tet_scale(o, p, t);
  double coef = p->k_vol * (o->tet_surface[t] ? p->surface_mult : 1.0) * sc * (V - R) / (R * R);
  if (with_damping && p->damp_vol > 0) {
    double vdot = 0;
    for (int k = 0; k < 4; k++) vdot += sds_dot(g[k], o->v + 3 * (size_t)q[k]);
    coef += p->damp_vol * sc * vdot / (R * R);
  }
  for (int i = 0; i < 3; i++) f[i] = -coef * g[j][i];
}

void sessile_sds_forces_ref(const sessile_sds *o, const sessile_sds_params *p, int with_damping,
                            double *f) {
  sessile_sds_contact *ct = contacts_of(o, p);
  for (uint32_t c = 0; c < o->ncells; c++) {
    double s[3] = {0, 0, 0}, fe[3];
    for (uint32_t k = o->cell_edge_off[c]; k < o->cell_edge_off[c + 1]; k++) {
      uint32_t e = o->cell_edge[k];
      edge_force(o, p, e, o->edge[2 * (size_t)e + 1] == c, fe);
      for (int i = 0; i < 3; i++) s[i] += fe[i];
    }
    for (uint32_t k = o->cell_tet_off[c]; k < o->cell_tet_off[c + 1]; k++) {
      uint32_t t = o->cell_tet[k];
      int j = 0;
      while (o->tet[4 * (size_t)t + j] != c) j++;
      tet_force(o, p, t, j, with_damping, fe);
      for (int i = 0; i < 3; i++) s[i] += fe[i];
    }
    double acc[3];
    sessile_sds_contact one;
    if (!ct) sessile_sds_contact_brute(o, p, c, o->x + 3 * (size_t)c, &one);
    sds_external_accel(p, o->x + 3 * (size_t)c, o->attract[c], acc);
    sessile_sds_contact_accel(o, p, c, o->x + 3 * (size_t)c, ct ? &ct[c] : &one, acc);
    for (int i = 0; i < 3; i++) {
      s[i] += o->m[c] * acc[i];
      if (with_damping) s[i] -= p->damp_visc * o->m[c] * o->v[3 * (size_t)c + i];
      f[3 * (size_t)c + i] = s[i];
    }
  }
  free(ct);
}
