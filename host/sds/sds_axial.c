/* The axial stiffness (docs/sds.md, "Axial stiffness"): a spring takes its
 * stiffness on the surface at birth, from its direction against the tissue's
 * axis there, the gradient of the morphogen declared `axis=1`.  A property of
 * the spring from then on (the paper: stiffness "could easily be specified
 * per spring", §3.2), so the forces stay the gradient of an energy. */
#include <math.h>
#include "sds/sds_internal.h"
#include "sds/sds_sim.h"

double sds_axial_k(double q, const double *d, const double *g) {
  double dd = sds_dot(d, d), gg = sds_dot(g, g);
  if (!(dd > 0 && gg > 0)) return 1.0; /* no axis here: isotropic */
  double c = sds_dot(d, g);
  return 1.0 + (q - 1.0) * (c * c / (dd * gg));
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
