/* Internal helpers shared by host/sds/sds_*.c. */
#ifndef SESSILE_SDS_INTERNAL_H
#define SESSILE_SDS_INTERNAL_H

#include <stdint.h>
#include "sessile/sds/sds.h"

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
 * per tet k (sum r / 2) (sum m / 2), times surface_mult on surface elements;
 * 1 for both with p->uniform_stiffness (the paper's uniform springs). */
double sds_edge_scale(const sessile_sds *o, const sessile_sds_params *p, uint32_t e);
/* The stiffness multiplier of edge e's spring by where it lies: on the
 * surface surface_mult times its own edge_k (1 where there is none), else 1. */
static inline double sds_edge_mult(const sessile_sds *o, const sessile_sds_params *p, uint32_t e) {
  return o->edge_surface[e] ? p->surface_mult * (o->edge_k ? o->edge_k[e] : 1.0) : 1.0;
}
double sds_tet_scale(const sessile_sds *o, const sessile_sds_params *p, uint32_t t);

/* The stable bound's adhesion term times a cell's radius: its slope 2 A /
 * delta is this / r (0 without an obstacle's adhesion; docs/sds.md,
 * "Adhesion and friction"). */
static inline double sds_stab_adhesion(const sessile_sds_params *p) {
  return p->obstacle.nf && p->adhesion > 0 ? 2 * p->adhesion / p->contact_scale : 0;
}

/* Gravity, box penalty and attraction acceleration of a cell at x, and
 * their potential per unit mass (host reference of the GPU's; the contacts
 * are sessile_sds_contact_accel's). */
void sds_external_accel(const sessile_sds_params *p, const double *x, int32_t attract, double *acc);
double sds_external_potential(const sessile_sds_params *p, const double *x, int32_t attract);

/* A spatial hash of triangles (Teschner et al. 2003; docs/sds.md,
 * "Collisions"): each triangle one entry, in the bucket of its centroid's
 * grid cell (size h); buckets [off[b], off[b+1]) of ent, ascending. */
typedef struct sds_hash {
  uint32_t tsize, n; /* table size (a prime >= 2n + 1), triangles */
  double h, rho;     /* cell size; largest distance from a centroid to its corners */
  int32_t glo[3], ghi[3]; /* the grid cells of the centroids lie in [glo, ghi] (a query clips its box to it) */
  uint32_t *off;     /* tsize + 1 */
  uint32_t *ent;     /* n */
} sds_hash;
/* Table size: a prime >= 4n + 1 (Teschner et al.: a prime; load 1/4 keeps
 * the candidates that only share a bucket few); cell size: SDS_HASH_CELL x
 * the mean side (measured: fewest candidates per query, docs/sds.md). */
#define SDS_HASH_CELL 1.5
uint32_t sds_table_size(uint32_t n);
/* Bounding spheres of triangles: centroid and largest corner distance (4 per triangle). */
void sds_tri_spheres(const double *pos, const uint32_t *tri, uint32_t nf, double *sph);
sessile_status sds_hash_build(sds_hash *hs, const double *pos, const uint32_t *tri, uint32_t nf, double h);
void sds_hash_free(sds_hash *hs);
int32_t sds_grid_coord(double v, double h);
uint32_t sds_grid_hash(int32_t i, int32_t j, int32_t k, uint32_t T);
uint32_t sds_prime_at_least(uint32_t n);
/* Regions of the closest point on a triangle (a, b, c), and per obstacle
 * triangle its SDS_OBS_NRM reals: a pseudo-normal per region (face normal;
 * angle-weighted vertex normals; edge normals = sum of the two faces'),
 * indexed 3 region. */
enum { SDS_REGION_FACE, SDS_REGION_A, SDS_REGION_B, SDS_REGION_C, SDS_REGION_AB, SDS_REGION_AC, SDS_REGION_BC };
#define SDS_OBS_NRM 21
sessile_status sds_obstacle_normals(const sessile_sds_obstacle *ob, double **nrm);
/* Mean side length of the triangles (1 when there are none). */
double sds_mean_side(const double *pos, const uint32_t *tri, uint32_t nf);

#endif
