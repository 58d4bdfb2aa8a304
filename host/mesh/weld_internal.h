/* The welded surface's shared pieces (docs/weld.md): the grid, the brick
 * lists of capsules and the per-node, per-row steps.  weld.c runs them as
 * the kernels shaders/mesh/weld_*.comp; weld_ref.c runs these C versions,
 * which mirror the kernels operation by operation (the fp64 build gives the
 * same bits). */
#ifndef SESSILE_WELD_INTERNAL_H
#define SESSILE_WELD_INTERNAL_H
#include <math.h>
#include <stdint.h>
#include "mesh_kernels.h"
#include "sessile/mesh/skeleton.h"

/* nodes per brick edge: the capsule lists are per brick of WELD_BRICK^3
 * nodes (8: weld_sdf.comp's workgroup of 64 columns of 8) */
#define WELD_BRICK 8u
/* radii below this many cells are raised to it (weld_grid.c, docs/weld.md) */
#define WELD_MIN_RADIUS_CELLS 1.0
/* the interpolation parameter is kept in [WELD_TMIN, 1 - WELD_TMIN] */
#define WELD_TMIN 1e-3

typedef struct weld_grid {
  uint32_t n[3];          /* nodes per axis */
  double lo[3], h;        /* node (i, j, k) at lo + h (i, j, k) */
  double clampv, blend;   /* node values clamped to <= clampv (2 h); smooth-union radius */
  uint32_t nb[3];         /* bricks per axis */
  uint32_t ncap;
  double *cap;            /* WC_STRIDE reals per capsule */
  uint32_t *boff, *blist; /* CSR: capsules (ascending) near each brick */
  uint64_t nodes;
} weld_grid;

/* The grid's frame: grid = R^T world, world = R grid (weld_grid.c). */
void weld_to_grid(const double w[3], double g[3]);
void weld_to_world(const double g[3], double w[3]);

/* Checks p, sizes the grid (no allocation) and estimates the bytes a run
 * needs besides the output (the grid arrays); s->n == 0 leaves nodes 0. */
sessile_status weld_grid_plan(const sessile_skeleton *s, const sessile_weld_params *p, weld_grid *g,
                              double *grid_bytes);
/* Fills the capsule constants and brick lists of a planned grid. */
sessile_status weld_grid_lists(const sessile_skeleton *s, weld_grid *g);
void weld_grid_free(weld_grid *g);
/* The message for a grid that does not fit: names the grid and the estimate. */
sessile_status weld_refuse(const weld_grid *g, double bytes, double limit, const char *what);

static inline uint32_t weld_brick_of(const weld_grid *g, uint32_t x, uint32_t y, uint32_t z) {
  return x / WELD_BRICK + g->nb[0] * (y / WELD_BRICK + g->nb[1] * (z / WELD_BRICK));
}

/* As capsule_sdf in shaders/mesh/weld_common.glsl. */
static inline double weld_capsule_sdf(const double *c, double px, double py, double pz) {
  double pa0 = px - c[0], pa1 = py - c[1], pa2 = pz - c[2];
  double u0 = c[4], u1 = c[5], u2 = c[6];
  double y = pa0 * u0 + pa1 * u1 + pa2 * u2;
  double r0 = pa0 - y * u0, r1 = pa1 - y * u1, r2 = pa2 - y * u2;
  double x = sqrt(r0 * r0 + r1 * r1 + r2 * r2);
  double sn = c[WC_SIN], cs = c[WC_COS];
  double s = y * cs - x * sn;
  if (s < 0) return sqrt(pa0 * pa0 + pa1 * pa1 + pa2 * pa2) - c[WC_RA];
  if (s > c[WC_L] * cs) {
    double pb0 = px - c[8], pb1 = py - c[9], pb2 = pz - c[10];
    return sqrt(pb0 * pb0 + pb1 * pb1 + pb2 * pb2) - c[WC_RB];
  }
  return y * sn + x * cs - c[WC_RA];
}

/* GLSL's min and max (y < x ? y : x; x < y ? y : x), zeros' signs included. */
static inline double weld_min(double x, double y) { return y < x ? y : x; }
static inline double weld_max(double x, double y) { return x < y ? y : x; }

/* As weld_smin in weld_common.glsl. */
static inline double weld_smin(double a, double b, double k) {
  double hh = weld_max(k - fabs(a - b), 0.0) / k;
  return weld_min(a, b) - hh * hh * k * 0.25;
}

/* The node value and nearest capsule (UINT32_MAX: none listed) as
 * weld_sdf.comp. */
double weld_node_value(const weld_grid *g, uint32_t x, uint32_t y, uint32_t z, uint32_t *nearest);

/* The host's passes, as weld_count/rowscan/vert/tri.comp: the packed word
 * of node i; the numbering of row r (y + ny z) from its base (first
 * vertex, triangle, active cell); vertex v; the triangles of the active
 * cell at node i from triangle t. */
uint32_t weld_count_node(const weld_grid *g, const double *field, size_t i);
void weld_rowscan_row(const weld_grid *g, const uint32_t *packed, uint32_t r, const uint32_t base[3], uint32_t *vbase,
                      uint32_t *vnode, uint32_t *clist, uint32_t *ctri);
void weld_vertex(const weld_grid *g, const double *field, const uint32_t *nnear, const uint32_t *packed,
                 const uint32_t *vbase, const uint32_t *vnode, uint32_t v, double *pos, uint32_t *nearest);
void weld_cell_tris(const weld_grid *g, const uint32_t *packed, const uint32_t *vbase, size_t i, uint32_t t,
                    uint32_t *tri);

/* Exclusive scan of the per-row (vertices, triangles, active cells) in
 * place; totals in tot.  Fails when they exceed 32-bit indices. */
sessile_status weld_scan_rows(uint32_t *rows, uint32_t nrows, uint32_t tot[3]);

/* Drops the inward-facing components (pockets of water enclosed where
 * branches fuse: buried faces) and those enclosing less than min_volume
 * (sampling specks), compacting pos, nearest and tri in order
 * (weld_clean.c). */
sessile_status weld_drop_pockets(double *pos, uint32_t *nv, uint32_t *tri, uint32_t *nf, uint32_t *nearest,
                                 double min_volume);
/* Drops pockets and specks (cells of size h), hands pos and tri (malloc'd;
 * owned by out on success) to out, replacing its contents, and maps nearest
 * capsules to s->value. */
sessile_status weld_output(const sessile_skeleton *s, double h, uint32_t nv, uint32_t nf, double *pos, uint32_t *tri,
                           uint32_t *nearest, sessile_surface *out, double **vertex_value);

/* The GPU path with its stage times (seconds, wall clock): the node values,
 * the count pass with the host scan, the emit passes, the download. */
typedef struct weld_times {
  double sdf, count, emit, download, total;
} weld_times;
sessile_status weld_gpu(sessile_gpu *gpu, const sessile_skeleton *s, const sessile_weld_params *p,
                        sessile_surface *out, double **vertex_value, weld_times *tm);

/* A random branching skeleton of nseg segments (trunk radius r0, cm), for
 * the tests and `sessile bench coral weld`; appended to s. */
sessile_status weld_random_tree(uint64_t seed, uint32_t nseg, double r0, sessile_skeleton *s);
#endif
