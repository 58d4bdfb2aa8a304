/* References of the per-vertex growth kernels (probe, translocate, grow) and
 * the parameter defaults.  Each mirrors shaders/growth/<name>.comp. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/growth/growth_ref.h"

/* The defaults are the parameter table's (sessile/growth/grow_params.h), the one source:
 * this only maps the run's parameters onto the kernels'. */
void sessile_growth_params_from(const sessile_grow_params *p, sessile_growth_params *g) {
  memset(g, 0, sizeof *g);
  g->probe_offset = p->concentration_offset_distance;
  g->probe_flux = p->probe == SESSILE_PROBE_FLUX;
  g->probe_distance = p->probe_distance;
  /* The bare substratum's flux: c = 1 at H over c = 0 on the floor, dc/dz =
   * 1/H (far_field = walls: H the box top; the side walls then feed the
   * box's middle a little more than that, docs/model.md). */
  double top = p->box_base_cell * p->box_cells_z, H = sessile_params_far_field_height(p);
  g->flux_ref = 1.0 / (p->far_field != SESSILE_FAR_WALLS ? H : top); /* height, inlet: H */
  if (p->far_field != SESSILE_FAR_WALLS) g->ceiling = H;
  g->probe_samples = (uint32_t)p->probe_samples;
  g->t_give = p->t_give;
  g->translocate_passes = p->translocate_passes;
  g->translocate_sequential = p->translocate_mode == SESSILE_TRANSLOCATE_SEQUENTIAL;
  g->nutrient_threshold = p->nutrient_threshold;
  g->growth_threshold = p->growth_threshold;
  g->growth_rate = p->growth_rate;
  g->l_max = p->l_max;
  g->kinetic_order = p->kinetic_order;
  g->growth_constant = p->growth_constant;
  g->max_growth = p->max_growth;
  g->halichondrid = p->skeletal_growth == SESSILE_SKELETON_HALICHONDRID;
  g->normal_offset_radius = p->normal_offset_radius;
}

void sessile_growth_params_default(sessile_growth_params *g) {
  sessile_grow_params p;
  sessile_params_default(&p);
  sessile_growth_params_from(&p, g);
}

sessile_status sessile_growth_params_check(const sessile_growth_params *p) {
  SESSILE_CHECK(p->probe_samples >= 2 && p->probe_samples <= 1024, SESSILE_ERR_USAGE,
                "probe samples must be between 2 and 1024 (got %u)", p->probe_samples);
  SESSILE_CHECK(p->probe_offset >= 0 && isfinite(p->probe_offset), SESSILE_ERR_USAGE,
                "concentration offset distance must be >= 0 (got %g)", p->probe_offset);
  SESSILE_CHECK(p->t_give >= 0 && p->t_give <= 1, SESSILE_ERR_USAGE,
                "translocation coefficient T_give must be in [0, 1] (got %g)", p->t_give);
  SESSILE_CHECK(p->translocate_passes >= 0 && p->translocate_passes <= 1000, SESSILE_ERR_USAGE,
                "translocation passes must be between 0 and 1000 (got %d)", p->translocate_passes);
  SESSILE_CHECK(p->growth_constant > 0 && p->kinetic_order > 0, SESSILE_ERR_USAGE,
                "Chindapol constant K and kinetic order n must be > 0 (got %g, %g)",
                p->growth_constant, p->kinetic_order);
  SESSILE_CHECK(p->max_growth >= 0 && isfinite(p->max_growth), SESSILE_ERR_USAGE,
                "maxgrowth must be >= 0 (got %g)", p->max_growth);
  SESSILE_CHECK(p->normal_offset_radius >= 0 && isfinite(p->normal_offset_radius),
                SESSILE_ERR_USAGE, "normal offset radius must be >= 0 (got %g)",
                p->normal_offset_radius);
  SESSILE_CHECK(!p->probe_flux || (p->probe_distance > 0 && isfinite(p->probe_distance) &&
                                    p->flux_ref > 0 && isfinite(p->flux_ref)),
                SESSILE_ERR_USAGE, "the flux probe needs a positive probe distance and reference "
                "flux (got %g cm, %g per cm)", p->probe_distance, p->flux_ref);
  SESSILE_CHECK(isfinite(p->growth_rate) && isfinite(p->l_max), SESSILE_ERR_USAGE,
                "growth rate and Lmax must be finite");
  return SESSILE_OK;
}

double sessile_growth_translocate_cmax(const sessile_growth_params *p) {
  return p->probe_flux ? 1e30 : 1.0;
}

/* --- probe (eq 6) ------------------------------------------------------------ */
void sessile_growth_ref_probe(const sessile_box *box, const double *pos, const double *normals,
                              uint32_t nv, const double *field, double offset, uint32_t samples,
                              double *probed) {
  for (uint32_t v = 0; v < nv; v++) {
    const double *x = pos + 3 * v, *nn = normals + 3 * v;
    double sum = 0;
    for (uint32_t k = 0; k < samples; k++) {
      double d = (double)k / (double)(samples - 1);
      double s = d * offset, p[3];
      for (int a = 0; a < 3; a++) p[a] = x[a] + s * nn[a];
      double w = 1.0 / (20.0 * d + 1.0);
      sum += w * sessile_box_interpolate(box, field, p);
    }
    probed[v] = sum / (double)samples;
  }
}

void sessile_growth_ref_probe_flux(const sessile_box *box, const double *pos, const double *normals,
                                   uint32_t nv, const double *field, double delta, double flux_ref,
                                   double *probed) {
  for (uint32_t v = 0; v < nv; v++) {
    double c[2];
    for (int k = 0; k < 2; k++) {
      double s = (k + 1) * delta, p[3];
      for (int a = 0; a < 3; a++) p[a] = pos[3 * v + a] + s * normals[3 * v + a];
      c[k] = sessile_box_trilinear(box, field, p);
    }
    double flux = (4 * c[0] - c[1]) / (2 * delta);
    flux /= flux_ref;
    probed[v] = flux > 0 ? flux : 0;
  }
}

/* --- translocation (eqs 7-8) ------------------------------------------------- */
static double clampc(double x, double cmax) { return x < 0 ? 0 : (x > cmax ? cmax : x); }

void sessile_growth_ref_translocate_pass(const uint32_t *off, const uint32_t *nbr, uint32_t nv,
                                         double t, double cmax, const double *c, double *out) {
  for (uint32_t v = 0; v < nv; v++) {
    double s = 0;
    for (uint32_t q = off[v]; q < off[v + 1]; q++) s += c[nbr[q]];
    double lose = (double)(off[v + 1] - off[v]) * t;
    double r = c[v] - lose * c[v];
    out[v] = clampc(r + t * s, cmax);
  }
}

sessile_status sessile_growth_ref_translocate_sweep(const uint32_t *off, const uint32_t *nbr,
                                                    uint32_t nv, double t, double cmax,
                                                    const double *c, double *out) {
  double *a = malloc((size_t)nv * sizeof *a + 1), *b = malloc((size_t)nv * sizeof *b + 1);
  if (!a || !b) {
    free(a), free(b);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", nv);
  }
  memcpy(a, c, (size_t)nv * sizeof *a);
  for (int p = 0; p < SESSILE_TRANSLOCATE_SWEEP; p++) {
    sessile_growth_ref_translocate_pass(off, nbr, nv, t, cmax, a, b);
    double *x = a;
    a = b, b = x;
  }
  memcpy(out, a, (size_t)nv * sizeof *a);
  free(a), free(b);
  return SESSILE_OK;
}

static void give(const uint32_t *off, const uint32_t *nbr, double t, double cmax, uint32_t y,
                 double *c) {
  double g = t * c[y];
  for (uint32_t q = off[y]; q < off[y + 1]; q++) c[nbr[q]] = clampc(c[nbr[q]] + g, cmax);
  c[y] = clampc(c[y] - (double)(off[y + 1] - off[y]) * g, cmax);
}

void sessile_growth_ref_translocate_sequential(const uint32_t *off, const uint32_t *nbr,
                                               uint32_t nv, double t, double cmax, double *c) {
  for (uint32_t v = 0; v < nv; v++) {
    give(off, nbr, t, cmax, v, c);
    for (uint32_t q = off[v]; q < off[v + 1]; q++) give(off, nbr, t, cmax, nbr[q], c);
  }
}

/* --- growth (eqs 1-2, 9-10) -------------------------------------------------- */
double sessile_growth_chindapol(const sessile_growth_params *p, double c) {
  if (!(c > 0)) return 0;
  double cn = pow(c, p->kinetic_order);
  double g = p->growth_rate * p->l_max * cn / (p->growth_constant + cn);
  return g < 0 ? 0 : (g > p->max_growth ? p->max_growth : g);
}

/* lowbias32 (C. Wellons' hash-prospector): a strong 32-bit integer mix. */
static uint32_t mix32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

uint32_t sessile_growth_hash(uint64_t seed, uint32_t iteration, uint32_t vertex, uint32_t component) {
  uint32_t h = mix32(component + 0x9e3779b9u);
  h = mix32(h ^ vertex);
  h = mix32(h ^ iteration);
  h = mix32(h ^ (uint32_t)(seed >> 32));
  return mix32(h ^ (uint32_t)seed);
}

double sessile_growth_uniform(uint64_t seed, uint32_t iteration, uint32_t vertex, uint32_t component) {
  return (double)(sessile_growth_hash(seed, iteration, vertex, component) >> 8) * 5.9604644775390625e-8;
}

void sessile_growth_ref_grow(const sessile_box *box, const double *pos, const double *normals,
                             uint32_t nv, const double *c_tr, const sessile_growth_params *p,
                             uint64_t seed, uint32_t iteration, double *new_pos, double *length,
                             double *dir_out) {
  double mx[3];
  sessile_box_max(box, mx);
  if (p->ceiling > 0 && p->ceiling < mx[2]) mx[2] = p->ceiling;
  const double R = p->normal_offset_radius;
  for (uint32_t v = 0; v < nv; v++) {
    double dir[3] = {normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]};
    if (p->halichondrid) {
      double d[3];
      for (uint32_t a = 0; a < 3; a++) {
        double u = sessile_growth_uniform(seed, iteration, v, a);
        d[a] = dir[a] + R * (2.0 * u - 1.0);
      }
      double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (l > 0) dir[0] = d[0] / l, dir[1] = d[1] / l, dir[2] = d[2] / l;
    }
    double g = sessile_growth_chindapol(p, c_tr[v]);
    int grows = c_tr[v] > p->nutrient_threshold && g > p->growth_threshold;
    if (!grows) g = 0;
    for (int a = 0; a < 3; a++) {
      double x = pos[3 * v + a] + g * dir[a];
      x = x < box->origin[a] ? box->origin[a] : (x > mx[a] ? mx[a] : x);
      new_pos[3 * v + a] = x;
      if (dir_out) dir_out[3 * v + a] = dir[a];
    }
    if (length) length[v] = g;
  }
}

sessile_status sessile_growth_ref_step(const sessile_box *box, const sessile_surface *s,
                                       const double *field, const sessile_growth_params *p,
                                       uint64_t seed, uint32_t iteration, double *new_pos,
                                       double *probed, double *translocated, double *length) {
  SESSILE_CALL(sessile_growth_params_check(p));
  uint32_t nv = s->nv, *off = NULL, *nbr = NULL;
  SESSILE_CALL(sessile_surface_vertex_neighbours(s, &off, &nbr));
  double *nrm = malloc((size_t)nv * 3 * sizeof *nrm + 1);
  double *a = malloc((size_t)nv * sizeof *a + 1), *b = malloc((size_t)nv * sizeof *b + 1);
  if (!nrm || !a || !b) {
    free(off), free(nbr), free(nrm), free(a), free(b);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", nv);
  }
  sessile_surface_normals(s, nrm);
  if (p->probe_flux)
    sessile_growth_ref_probe_flux(box, s->pos, nrm, nv, field, p->probe_distance, p->flux_ref, a);
  else
    sessile_growth_ref_probe(box, s->pos, nrm, nv, field, p->probe_offset, p->probe_samples, a);
  if (probed) memcpy(probed, a, (size_t)nv * sizeof *a);
  double cmax = sessile_growth_translocate_cmax(p);
  for (int sweep = 0; sweep < p->translocate_passes; sweep++) {
    if (p->translocate_sequential) {
      sessile_growth_ref_translocate_sequential(off, nbr, nv, p->t_give, cmax, a);
      continue;
    }
    for (int q = 0; q < SESSILE_TRANSLOCATE_SWEEP; q++) {
      sessile_growth_ref_translocate_pass(off, nbr, nv, p->t_give, cmax, a, b);
      double *t = a;
      a = b, b = t;
    }
  }
  if (translocated) memcpy(translocated, a, (size_t)nv * sizeof *a);
  sessile_growth_ref_grow(box, s->pos, nrm, nv, a, p, seed, iteration, new_pos, length, NULL);
  free(off), free(nbr), free(nrm), free(a), free(b);
  return SESSILE_OK;
}
