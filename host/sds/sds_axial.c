/* The tissue's axis, the gradient of the morphogen declared `axis=1`, and
 * what the springs take from it (docs/sds.md, "Axial stiffness", "Oriented
 * growth"): a spring takes its stiffness on the surface at birth, from its
 * direction against the axis there, a property of the spring from then on
 * (the paper: stiffness "could easily be specified per spring", §3.2), so
 * the forces stay the gradient of an energy; a growing cell's edges share
 * its growth out by their direction; and the edges of extending tissue
 * lengthen along the axis and shorten across it (convergent extension). */
#include <math.h>
#include <stdlib.h>
#include "sds/sds_internal.h"
#include "sds/sds_sim.h"

/* cos^2 of the angle between d and g; -1 where either vanishes (no axis) */
static double axial_cos2(const double *d, const double *g) {
  double dd = sds_dot(d, d), gg = sds_dot(g, g);
  if (!(dd > 0 && gg > 0)) return -1.0;
  double c = sds_dot(d, g);
  return c * c / (dd * gg);
}

double sds_axial_k(double q, const double *d, const double *g) {
  double c2 = axial_cos2(d, g);
  return c2 < 0 ? 1.0 : 1.0 + (q - 1.0) * c2; /* no axis here: isotropic */
}

void sds_axial_springs(sessile_sds *o, const sessile_morph_cells *cells, int k, double q) {
  for (uint32_t e = 0; e < o->nedges; e++) {
    if (o->edge_k[e] != 0) continue; /* born before: keeps its stiffness */
    uint32_t a = o->edge[2 * (size_t)e], b = o->edge[2 * (size_t)e + 1];
    double ga[3] = {0, 0, 0}, gb[3] = {0, 0, 0}, g[3], d[3];
    sessile_morph_gradient(cells, (int)o->nmorph, o->phi, (int)a, k, ga);
    sessile_morph_gradient(cells, (int)o->nmorph, o->phi, (int)b, k, gb);
    for (int i = 0; i < 3; i++) g[i] = ga[i] + gb[i];
    sds_sub(o->x + 3 * (size_t)a, o->x + 3 * (size_t)b, d);
    o->edge_k[e] = sds_axial_k(q, d, g);
  }
}

sessile_status sds_axial_assign(sds_sim *s) {
  if (!s->o.edge_k_defer) return SESSILE_OK;
  int k = sessile_sds_model_axis(s->model);
  SESSILE_CHECK(k >= 0, SESSILE_ERR_USAGE, "sds: axial_stiffness needs a morphogen declared axis=1");
  sessile_morph_cells cells = sds_cells_of(s);
  sds_axial_springs(&s->o, &cells, k, s->prm.axial_stiffness);
  return SESSILE_OK;
}

/* Each cell's gradient once, made when an edge first asks for it: the
 * scratch of the two edge passes below. */
typedef struct {
  double *g;
  unsigned char *have;
} grad_cache;

static sessile_status cache_make(grad_cache *gc, uint32_t ncells) {
  gc->g = malloc((3 * (size_t)ncells + 1) * sizeof *gc->g);
  gc->have = calloc((size_t)ncells + 1, 1);
  if (gc->g && gc->have) return SESSILE_OK;
  free(gc->g), free(gc->have);
  return sessile_error_set(SESSILE_ERR_NO_MEMORY, "sds: out of host memory for %u cells", ncells);
}

static void cache_free(grad_cache *gc) { free(gc->g), free(gc->have); }

/* cos^2 of the angle between edge e and the sum of morphogen k's gradients
 * at its cells; -1 where either vanishes (no axis) */
static double edge_cos2(const sessile_sds *o, const sessile_morph_cells *cells, int k, uint32_t e, grad_cache *gc) {
  uint32_t c[2] = {o->edge[2 * (size_t)e], o->edge[2 * (size_t)e + 1]};
  for (int i = 0; i < 2; i++)
    if (!gc->have[c[i]]) {
      double *g = gc->g + 3 * (size_t)c[i];
      g[0] = g[1] = g[2] = 0;
      sessile_morph_gradient(cells, (int)o->nmorph, o->phi, (int)c[i], k, g);
      gc->have[c[i]] = 1;
    }
  double ge[3], d[3];
  for (int i = 0; i < 3; i++) ge[i] = gc->g[3 * (size_t)c[0] + i] + gc->g[3 * (size_t)c[1] + i];
  sds_sub(o->x + 3 * (size_t)c[0], o->x + 3 * (size_t)c[1], d);
  return axial_cos2(d, ge);
}

/* The oriented growth (docs/sds.md, "Oriented growth"): the rest length
 * R' = s_m (r_a + r_b) grows by w (dr_a + dr_b) s_m instead of
 * (dr_a + dr_b) s_m, w = 1 + A (3 cos^2 - 1), whose mean over directions is
 * 1: the same growth, shared out along the axis.  A state change between
 * steps, as the radii are, so the forces stay -grad E. */
static void grow_pass(sessile_sds *o, const sessile_morph_cells *cells, int k, double A, const double *r0,
                      int *changed, grad_cache *gc) {
  for (uint32_t e = 0; e < o->nedges; e++) {
    uint32_t a = o->edge[2 * (size_t)e], b = o->edge[2 * (size_t)e + 1];
    double dr = (o->r[a] - r0[a]) + (o->r[b] - r0[b]);
    if (dr == 0) continue;
    double c2 = edge_cos2(o, cells, k, e, gc);
    if (c2 < 0) continue; /* no axis here: isotropic, s_m as it was */
    double R0 = r0[a] + r0[b], w = 1.0 + A * (3.0 * c2 - 1.0);
    o->edge_sm[e] *= (R0 + w * dr) / (R0 + dr);
    *changed = 1;
  }
}

sessile_status sds_axial_grow_edges(sessile_sds *o, const sessile_morph_cells *cells, int k, double A,
                                    const double *r0, int *changed) {
  grad_cache gc;
  SESSILE_CALL(cache_make(&gc, o->ncells));
  grow_pass(o, cells, k, A, r0, changed, &gc);
  cache_free(&gc);
  return SESSILE_OK;
}

/* Convergent extension (docs/sds.md, "Convergent extension"): each step an
 * edge between two cells whose state `extending` (index j) is set
 * multiplies its s_m by 1 + C dt (3 cos^2 - 1): longer along the axis,
 * shorter across it, 1 on average over directions.  The tissue changes its
 * shape without growing, as cells that intercalate do.  A state change
 * between steps, as the oriented growth's. */
static void extend_pass(sessile_sds *o, const sessile_morph_cells *cells, int k, double C, double dt, int j,
                        int *changed, grad_cache *gc) {
  size_t ns = o->nstate;
  for (uint32_t e = 0; e < o->nedges; e++) {
    uint32_t a = o->edge[2 * (size_t)e], b = o->edge[2 * (size_t)e + 1];
    if (o->state[a * ns + (size_t)j] == 0 || o->state[b * ns + (size_t)j] == 0) continue;
    double c2 = edge_cos2(o, cells, k, e, gc);
    if (c2 < 0) continue; /* no axis here */
    o->edge_sm[e] *= 1.0 + C * dt * (3.0 * c2 - 1.0);
    *changed = 1;
  }
}

sessile_status sds_axial_extend_edges(sessile_sds *o, const sessile_morph_cells *cells, int k, double C, double dt,
                                      int j, int *changed) {
  grad_cache gc;
  SESSILE_CALL(cache_make(&gc, o->ncells));
  extend_pass(o, cells, k, C, dt, j, changed, &gc);
  cache_free(&gc);
  return SESSILE_OK;
}

/* A step's oriented growth (r0 the radii before the rules' growth; NULL:
 * none) and convergent extension, in that order, on one gradient cache:
 * the passes change only s_m, so the gradients are the same for both. */
sessile_status sds_axial_edges_step(sds_sim *s, const double *r0, double dt) {
  int k = sessile_sds_model_axis(s->model), j = sessile_sds_model_state_index(s->model, SDS_STATE_EXTENDING);
  double C = s->prm.convergent_extension;
  SESSILE_CHECK(k >= 0, SESSILE_ERR_USAGE,
                "sds: axial_growth and convergent_extension need a morphogen declared axis=1");
  SESSILE_CHECK(C == 0 || j >= 0, SESSILE_ERR_USAGE,
                "sds: convergent_extension needs a state `" SDS_STATE_EXTENDING "`");
  if (!r0 && C == 0) return SESSILE_OK;
  sessile_morph_cells cells = sds_cells_of(s);
  grad_cache gc;
  SESSILE_CALL(cache_make(&gc, s->o.ncells));
  if (r0) grow_pass(&s->o, &cells, k, s->prm.axial_growth, r0, &s->sm_changed, &gc);
  if (C != 0) extend_pass(&s->o, &cells, k, C, dt, j, &s->sm_changed, &gc);
  cache_free(&gc);
  return SESSILE_OK;
}
