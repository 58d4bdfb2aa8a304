/* Internal helpers shared by host/sds/sds_*.c. */
#ifndef SESSILE_SDS_INTERNAL_H
#define SESSILE_SDS_INTERNAL_H

#include <stdint.h>
#include "sessile/sds.h"

#define SDS_PI 3.14159265358979323846

/* d = b - a */
static inline void sds_sub(const double *a, const double *b, double *d) {
  d[0] = b[0] - a[0], d[1] = b[1] - a[1], d[2] = b[2] - a[2];
}
static inline void sds_cross(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
static inline double sds_dot(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/* Signed volume of the tet (p0, p1, p2, p3), eq 1. */
static inline double sds_vol4(const double *p0, const double *p1, const double *p2,
                              const double *p3) {
  double a[3], b[3], c[3], n[3];
  sds_sub(p0, p1, a), sds_sub(p0, p2, b), sds_sub(p0, p3, c);
  sds_cross(b, c, n);
  return sds_dot(a, n) / 6.0;
}

/* The stiffness scales (docs/sds.md, "Physics"): per edge k R' (m_a + m_b),
 * per tet k (sum r / 2) (sum m / 2), times surface_mult on surface elements. */
double sds_edge_scale(const sessile_sds *o, uint32_t e);
double sds_tet_scale(const sessile_sds *o, uint32_t t);

/* Penalty and attraction acceleration of cell c at x (gravity included),
 * and their potential per unit mass (host reference of the GPU's). */
void sds_external_accel(const sessile_sds_params *p, const double *x, int32_t attract, double *acc);
double sds_external_potential(const sessile_sds_params *p, const double *x, int32_t attract);

#endif
