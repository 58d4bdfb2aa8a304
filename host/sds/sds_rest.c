/* Radii (§3.2.1), volumes (eq 1), rest sizes (§3.2, Appendix A) and the
 * spring multipliers s_m = V/R (§3.2.1). */
#include <math.h>
#include "sds/sds_internal.h"

double sessile_sds_tet_volume(const sessile_sds *o, uint32_t t) {
  const uint32_t *q = o->tet + 4 * (size_t)t;
  return sds_vol4(o->x + 3 * (size_t)q[0], o->x + 3 * (size_t)q[1], o->x + 3 * (size_t)q[2],
                  o->x + 3 * (size_t)q[3]);
}

/* Appendix A, as printed: the volume of the tet of four mutually tangent
 * spheres (edge lengths r_i + r_j).  Checked against the Cayley-Menger
 * determinant in tests/sds/test_sds_complex.c. */
double sessile_sds_tet_rest(double a, double b, double c, double d) {
  double w = a * b * c;
  double x = d * sqrt(b * c * (a + b + d) * (a + c + d));
  double y = d * sqrt(a * c * (a + b + d) * (b + c + d));
  double z = d * sqrt(a * b * (a + c + d) * (b + c + d));
  double A = w + x + y - z, B = w + x - y + z, C = w - x + y + z, D = -w + x + y + z;
  return sqrt(A * B * C * D) / (3.0 * (a + d) * (b + d) * (c + d));
}

double sessile_sds_edge_rest_of(const sessile_sds *o, uint32_t e) {
  return o->r[o->edge[2 * (size_t)e]] + o->r[o->edge[2 * (size_t)e + 1]];
}

double sessile_sds_tet_rest_of(const sessile_sds *o, uint32_t t) {
  const uint32_t *q = o->tet + 4 * (size_t)t;
  return sessile_sds_tet_rest(o->r[q[0]], o->r[q[1]], o->r[q[2]], o->r[q[3]]);
}

void sessile_sds_radii_from_edges(sessile_sds *o, double density) {
  for (uint32_t c = 0; c < o->ncells; c++) {
    uint32_t b = o->cell_edge_off[c], e = o->cell_edge_off[c + 1];
    if (b < e) {
      double sum = 0;
      for (uint32_t k = b; k < e; k++) {
        const uint32_t *q = o->edge + 2 * (size_t)o->cell_edge[k];
        double d[3];
        sds_sub(o->x + 3 * (size_t)q[0], o->x + 3 * (size_t)q[1], d);
        sum += 0.5 * sqrt(sds_dot(d, d));
      }
      o->r[c] = sum / (e - b);
    }
    o->m[c] = density * 4.0 / 3.0 * SDS_PI * o->r[c] * o->r[c] * o->r[c];
  }
}

void sessile_sds_relax_multipliers(sessile_sds *o) {
  for (uint32_t e = 0; e < o->nedges; e++) {
    const uint32_t *q = o->edge + 2 * (size_t)e;
    double d[3];
    sds_sub(o->x + 3 * (size_t)q[0], o->x + 3 * (size_t)q[1], d);
    o->edge_sm[e] = sqrt(sds_dot(d, d)) / sessile_sds_edge_rest_of(o, e);
  }
  for (uint32_t t = 0; t < o->ntets; t++)
    o->tet_sm[t] = sessile_sds_tet_volume(o, t) / sessile_sds_tet_rest_of(o, t);
}

double sessile_sds_mass(double density, double r) {
  /* fma gives each product's rounding error exactly (Dekker's split on the
   * device: the same two doubles); C17 without extensions contracts nothing */
  double p = r * r, e = fma(r, r, -p);
  double q = p * r, f = fma(p, r, -q);
  double g = e * r, s = f + g;
  return density * 4.0 / 3.0 * SDS_PI * (q + s);
}
