/* sessile — the structured tetrahedral box mesh (the paper's "cube
 * tetrahedral mesh", O'Hagan et al. §4.1).
 *
 * A box of n[0]-1 x n[1]-1 x n[2]-1 cubes of edge h; each cube is cut into 6
 * tetrahedra around its main diagonal (Kuhn / Freudenthal triangulation), so
 * the tetrahedra of neighbouring cubes match across faces.  Resolution r = 1
 * is the base grid; each step halves the cube edge (nodes 2(n-1)+1 per axis).
 *
 * Lengths are in the scene unit, centimetres (docs/model.md).  Node (i,j,k)
 * sits at origin + h (i,j,k) and has index i + n0 (j + n1 k).  x is the flow
 * direction, z = origin[2] is the substratum.
 *
 * Everything here is small and inline: the GLSL kernels (shaders/growth/)
 * mirror box_locate exactly, and host references call these. */
#ifndef SESSILE_BOX_H
#define SESSILE_BOX_H

#include <math.h>
#include <stdint.h>
#include "sessile/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_box {
  double origin[3]; /* min corner, cm */
  double h;         /* cube edge, cm */
  uint32_t n[3];    /* nodes per axis (>= 2) */
} sessile_box;

/* Boundary tags of a node or face (bits; a node on an edge has several). */
enum {
  SESSILE_TAG_INLET = 1u,      /* x = xmin */
  SESSILE_TAG_OUTLET = 2u,     /* x = xmax */
  SESSILE_TAG_SUBSTRATUM = 4u, /* z = zmin */
  SESSILE_TAG_SIDE = 8u,       /* y = ymin or y = ymax */
  SESSILE_TAG_TOP = 16u        /* z = zmax */
};

/* A box of base_cells[a] * 2^(resolution-1) cubes per axis a, cube edge
 * base_h / 2^(resolution-1), min corner origin.  Fails with SESSILE_ERR_USAGE
 * for resolution < 1, non-positive sizes, or more than 2^31 nodes. */
static inline sessile_status sessile_box_make(const double origin[3], double base_h,
                                              const uint32_t base_cells[3], int resolution,
                                              sessile_box *out) {
  SESSILE_CHECK(resolution >= 1 && resolution <= 12, SESSILE_ERR_USAGE,
                "box resolution must be between 1 and 12 (got %d)", resolution);
  SESSILE_CHECK(base_h > 0 && isfinite(base_h), SESSILE_ERR_USAGE,
                "box base cell size must be positive (got %g)", base_h);
  uint32_t f = 1u << (resolution - 1);
  double nodes = 1;
  for (int a = 0; a < 3; a++) {
    SESSILE_CHECK(base_cells[a] >= 1, SESSILE_ERR_USAGE, "box needs at least one cell per axis");
    out->origin[a] = origin[a];
    out->n[a] = base_cells[a] * f + 1;
    nodes *= out->n[a];
  }
  SESSILE_CHECK(nodes <= 2147483647.0, SESSILE_ERR_TOO_LARGE,
                "box of %u x %u x %u nodes is too large; lower the box resolution",
                out->n[0], out->n[1], out->n[2]);
  out->h = base_h / f;
  return SESSILE_OK;
}

static inline uint32_t sessile_box_nodes(const sessile_box *b) { return b->n[0] * b->n[1] * b->n[2]; }
static inline uint32_t sessile_box_cells(const sessile_box *b) {
  return (b->n[0] - 1) * (b->n[1] - 1) * (b->n[2] - 1);
}
static inline uint32_t sessile_box_index(const sessile_box *b, uint32_t i, uint32_t j, uint32_t k) {
  return i + b->n[0] * (j + b->n[1] * k);
}
static inline void sessile_box_node_pos(const sessile_box *b, uint32_t node, double p[3]) {
  uint32_t i = node % b->n[0], j = (node / b->n[0]) % b->n[1], k = node / (b->n[0] * b->n[1]);
  p[0] = b->origin[0] + b->h * i;
  p[1] = b->origin[1] + b->h * j;
  p[2] = b->origin[2] + b->h * k;
}
static inline void sessile_box_max(const sessile_box *b, double mx[3]) {
  for (int a = 0; a < 3; a++) mx[a] = b->origin[a] + b->h * (b->n[a] - 1);
}
/* Boundary tags of node (i,j,k); 0 for interior nodes. */
static inline uint32_t sessile_box_node_tags(const sessile_box *b, uint32_t i, uint32_t j, uint32_t k) {
  uint32_t t = 0;
  if (i == 0) t |= SESSILE_TAG_INLET;
  if (i == b->n[0] - 1) t |= SESSILE_TAG_OUTLET;
  if (j == 0 || j == b->n[1] - 1) t |= SESSILE_TAG_SIDE;
  if (k == 0) t |= SESSILE_TAG_SUBSTRATUM;
  if (k == b->n[2] - 1) t |= SESSILE_TAG_TOP;
  return t;
}

/* Tetrahedron t (0..5) of the cube whose min corner is node (i,j,k): the
 * path 000 -> e_a -> e_a + e_b -> 111 for the t-th permutation (a,b,c) of
 * the axes.  Node order gives positive volume for even permutations; use
 * sessile_box_tet, which orders them so every tet has positive volume. */
static inline void sessile_box_tet(const sessile_box *b, uint32_t i, uint32_t j, uint32_t k, int t,
                                   uint32_t nodes[4]) {
  static const int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  uint32_t c[3] = {i, j, k};
  nodes[0] = sessile_box_index(b, c[0], c[1], c[2]);
  for (int s = 0; s < 3; s++) {
    c[perm[t][s]]++;
    nodes[s + 1] = sessile_box_index(b, c[0], c[1], c[2]);
  }
  if (t >= 3) { /* odd permutation: swap two nodes for positive orientation */
    uint32_t tmp = nodes[1];
    nodes[1] = nodes[2];
    nodes[2] = tmp;
  }
}

/* O(1) point location with barycentric weights: the cube holding p (clamped
 * into the box), then the Kuhn tet by sorting the local coordinates.  Writes
 * the 4 node indices and weights (summing to 1, all >= 0 for p inside the
 * box); the interpolated value of a P1 field f is sum w[q] f[nodes[q]]. */
static inline void sessile_box_locate(const sessile_box *b, const double p[3], uint32_t nodes[4],
                                      double w[4]) {
  uint32_t c[3];
  double u[3];
  for (int a = 0; a < 3; a++) {
    double x = (p[a] - b->origin[a]) / b->h;
    double cells = (double)(b->n[a] - 1);
    if (!(x > 0)) x = 0; /* also maps NaN to 0 */
    if (x > cells) x = cells;
    double f = floor(x);
    if (f > cells - 1) f = cells - 1;
    c[a] = (uint32_t)f;
    u[a] = x - f;
  }
  /* order axes by decreasing local coordinate (ties: lower axis first) */
  int o[3] = {0, 1, 2};
  for (int s = 0; s < 2; s++)
    for (int q = 0; q < 2 - s; q++)
      if (u[o[q + 1]] > u[o[q]]) {
        int tmp = o[q];
        o[q] = o[q + 1];
        o[q + 1] = tmp;
      }
  nodes[0] = sessile_box_index(b, c[0], c[1], c[2]);
  w[0] = 1.0 - u[o[0]];
  for (int s = 0; s < 3; s++) {
    c[o[s]]++;
    nodes[s + 1] = sessile_box_index(b, c[0], c[1], c[2]);
    w[s + 1] = u[o[s]] - (s < 2 ? u[o[s + 1]] : 0.0);
  }
}

/* The P1 interpolant of a nodal field at p (clamped into the box). */
static inline double sessile_box_interpolate(const sessile_box *b, const double *field, const double p[3]) {
  uint32_t nodes[4];
  double w[4];
  sessile_box_locate(b, p, nodes, w);
  return w[0] * field[nodes[0]] + w[1] * field[nodes[1]] + w[2] * field[nodes[2]] +
         w[3] * field[nodes[3]];
}

/* The trilinear (Q1) interpolant of a nodal field at p (clamped into the
 * box): isotropic where the Kuhn P1 interpolant has the cube diagonal as a
 * preferred direction; the flux probe reads the field through it
 * (docs/model.md).  Mirrored by box_trilinear in
 * shaders/growth/growth_common.glsl. */
static inline double sessile_box_trilinear(const sessile_box *b, const double *field, const double p[3]) {
  uint32_t c[3];
  double u[3];
  for (int a = 0; a < 3; a++) {
    double x = (p[a] - b->origin[a]) / b->h;
    double cells = (double)(b->n[a] - 1);
    if (!(x > 0)) x = 0;
    if (x > cells) x = cells;
    double f = floor(x);
    if (f > cells - 1) f = cells - 1;
    c[a] = (uint32_t)f;
    u[a] = x - f;
  }
  double sum = 0;
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < 2; j++)
      for (int i = 0; i < 2; i++) {
        double w = (i ? u[0] : 1 - u[0]) * (j ? u[1] : 1 - u[1]);
        w = w * (k ? u[2] : 1 - u[2]);
        sum += w * field[sessile_box_index(b, c[0] + i, c[1] + j, c[2] + k)];
      }
  return sum;
}

#ifdef __cplusplus
}
#endif
#endif
