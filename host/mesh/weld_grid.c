/* The welded surface's grid: parameters, sizing, memory estimate, capsule
 * constants and the brick lists (docs/weld.md).  Shared by the GPU path
 * (weld.c) and the reference (weld_ref.c), so both see the same lists. */
#include <stdlib.h>
#include <string.h>
#include "weld_internal.h"

/* The grid's frame: a fixed rotation R (from the quaternion (7, 2, 3, 5) /
 * sqrt(87)), grid = R^T world.  Along a capsule's axis the distance is
 * exactly linear, so an axis parallel to a lattice edge (the axes, the face
 * and body diagonals: vertical trunks, 45-degree branches) makes marching
 * tetrahedra emit exactly coplanar triangles with collinear edges, which a
 * conservative self-intersection test cannot tell from touching; rotated,
 * no common direction is parallel to one (docs/weld.md). */
static const double R[9] = {(49. + 4 - 9 - 25) / 87, 2 * (6. - 35) / 87,      2 * (10. + 21) / 87,
                            2 * (6. + 35) / 87,      (49. - 4 + 9 - 25) / 87, 2 * (15. - 14) / 87,
                            2 * (10. - 21) / 87,     2 * (15. + 14) / 87,     (49. - 4 - 9 + 25) / 87};

/* The grid's origin moves off the centred position by these fractions of
 * a cell: centred, a sphere at the skeleton's extreme sits at a fixed
 * offset from the nodes (half a cell for round sizes), where its distance
 * is mirror-symmetric across a node plane and again gives exactly coplanar
 * triangles (fractional parts of k phi, minus 1/2). */
static const double OFFSET[3] = {0.1180339887498949, -0.2639320225002103, 0.3541019662496845};

void weld_to_grid(const double w[3], double g[3]) {
  for (int i = 0; i < 3; i++) g[i] = R[i] * w[0] + R[3 + i] * w[1] + R[6 + i] * w[2];
}
void weld_to_world(const double g[3], double w[3]) {
  for (int i = 0; i < 3; i++) w[i] = R[3 * i] * g[0] + R[3 * i + 1] * g[1] + R[3 * i + 2] * g[2];
}

void weld_grid_free(weld_grid *g) {
  if (!g) return;
  free(g->cap), free(g->boff), free(g->blist);
  memset(g, 0, sizeof *g);
}

sessile_status weld_refuse(const weld_grid *g, double bytes, double limit, const char *what) {
  return sessile_error_set(SESSILE_ERR_NO_MEMORY,
                           "welded surface: a grid of %ux%ux%u nodes needs about %.0f MB of %s, more than the "
                           "%.0f MB allowed: a coarser grid is needed",
                           g->n[0], g->n[1], g->n[2], bytes / 1e6, what, limit / 1e6);
}

sessile_status weld_grid_plan(const sessile_skeleton *s, const sessile_weld_params *p, weld_grid *g,
                              double *grid_bytes) {
  memset(g, 0, sizeof *g);
  *grid_bytes = 0;
  SESSILE_CHECK(p && isfinite(p->cell) && p->cell >= 0 && isfinite(p->blend) && p->blend >= 0, SESSILE_ERR_USAGE,
                "welded surface: cell and blend must be finite and >= 0");
  SESSILE_CHECK(p->cell > 0 || p->max_cells >= 8, SESSILE_ERR_USAGE,
                "welded surface: with cell = 0, max_cells must be at least 8 (got %u)", p->max_cells);
  g->blend = p->blend;
  if (s->n == 0) return SESSILE_OK;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, ext = 0;
  for (uint32_t i = 0; i < s->n; i++) {
    double a[3], b[3];
    weld_to_grid(s->a + 3 * (size_t)i, a), weld_to_grid(s->b + 3 * (size_t)i, b);
    for (int k = 0; k < 3; k++) {
      lo[k] = fmin(lo[k], fmin(a[k] - s->ra[i], b[k] - s->rb[i]));
      hi[k] = fmax(hi[k], fmax(a[k] + s->ra[i], b[k] + s->rb[i]));
    }
  }
  for (int a = 0; a < 3; a++) ext = fmax(ext, hi[a] - lo[a]);
  /* pad = 2 h + blend on each side, so the longest axis spans
   * ext + 2 pad = max_cells h */
  double h = p->cell > 0 ? p->cell : (ext + 2 * p->blend) / (double)(p->max_cells - 4);
  SESSILE_CHECK(h > 1e-30 && isfinite(h), SESSILE_ERR_USAGE, "welded surface: the cell %g is too small", h);
  double pad = 2 * h + p->blend;
  uint64_t nodes = 1;
  for (int a = 0; a < 3; a++) {
    /* one spare cell, so that the origin can move by up to h / 2 */
    double cells = ceil((hi[a] - lo[a] + 2 * pad) / h - 1e-9) + 1;
    if (cells > 4e9) cells = 4e9; /* refused below */
    g->n[a] = (uint32_t)cells + 1;
    g->lo[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * cells * h + OFFSET[a] * h;
    g->nb[a] = (g->n[a] + WELD_BRICK - 1) / WELD_BRICK;
    nodes = nodes * g->n[a] > (1ull << 62) / 4 ? (1ull << 62) / 4 : nodes * g->n[a];
  }
  g->h = h;
  g->clampv = 2 * h;
  g->nodes = nodes;
  /* field (fp64), nearest capsule, packed word and first vertex per node, 8 bytes per row;
   * lists are small beside these */
  double rows = (double)g->n[1] * g->n[2];
  *grid_bytes = 20.0 * (double)nodes + 12.0 * rows;
  if (nodes > (1ull << 31)) return weld_refuse(g, *grid_bytes, 20.0 * (1ull << 31), "memory (2^31 nodes at most)");
  return SESSILE_OK;
}

/* The capsule constants (WC_* slots): axis, length, and the slope of the
 * side; a cone whose smaller sphere lies inside the larger (L <= |ra - rb|)
 * is that larger sphere, written with L = 0, sin = 0, cos = 1. */
static void capsule_constants(const sessile_skeleton *s, uint32_t i, double rmin, double *c) {
  double a[3], b[3];
  weld_to_grid(s->a + 3 * (size_t)i, a), weld_to_grid(s->b + 3 * (size_t)i, b);
  double ra = fmax(s->ra[i], rmin), rb = fmax(s->rb[i], rmin);
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double L = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  memset(c, 0, WC_STRIDE * sizeof *c);
  if (!(L > fabs(ra - rb))) {
    const double *m = ra >= rb ? a : b;
    double r = ra >= rb ? ra : rb;
    for (int k = 0; k < 3; k++) c[WC_A + k] = c[WC_B + k] = m[k];
    c[WC_U] = 1, c[WC_RA] = c[WC_RB] = r, c[WC_L] = 0, c[WC_SIN] = 0, c[WC_COS] = 1;
    return;
  }
  for (int k = 0; k < 3; k++) c[WC_A + k] = a[k], c[WC_B + k] = b[k], c[WC_U + k] = d[k] / L;
  c[WC_L] = L, c[WC_RA] = ra, c[WC_RB] = rb;
  c[WC_SIN] = (ra - rb) / L;
  c[WC_COS] = sqrt((L - (ra - rb)) * (L + (ra - rb))) / L;
}

/* The bricks whose nodes come within `margin` of capsule i's box: node
 * ranges per axis, then bricks; *ok 0 when none. */
static void capsule_bricks(const weld_grid *g, const double *c, double margin, uint32_t b0[3], uint32_t b1[3],
                           int *ok) {
  *ok = 1;
  for (int a = 0; a < 3; a++) {
    double r = fmax(c[WC_RA], c[WC_RB]);
    double lo = fmin(c[WC_A + a], c[WC_B + a]) - r - margin, hi = fmax(c[WC_A + a], c[WC_B + a]) + r + margin;
    double i0 = ceil((lo - g->lo[a]) / g->h), i1 = floor((hi - g->lo[a]) / g->h);
    if (i0 < 0) i0 = 0;
    if (i1 > g->n[a] - 1) i1 = g->n[a] - 1;
    if (i1 < i0) {
      *ok = 0;
      return;
    }
    b0[a] = (uint32_t)i0 / WELD_BRICK, b1[a] = (uint32_t)i1 / WELD_BRICK;
  }
}

/* Can capsule c come within margin of a node of brick (x, y, z)?  The
 * distance is 1-Lipschitz: at most the half-diagonal less at any node than
 * at the centre of the brick's nodes. */
static int brick_near(const weld_grid *g, const double *c, uint32_t x, uint32_t y, uint32_t z, double margin) {
  uint32_t b[3] = {x, y, z};
  double p[3], d2 = 0;
  for (int a = 0; a < 3; a++) {
    uint32_t i0 = b[a] * WELD_BRICK, i1 = i0 + WELD_BRICK - 1;
    if (i1 > g->n[a] - 1) i1 = g->n[a] - 1;
    p[a] = g->lo[a] + g->h * 0.5 * (double)(i0 + i1);
    d2 += 0.25 * g->h * g->h * (double)(i1 - i0) * (double)(i1 - i0);
  }
  return weld_capsule_sdf(c, p[0], p[1], p[2]) - sqrt(d2) <= margin;
}

sessile_status weld_grid_lists(const sessile_skeleton *s, weld_grid *g) {
  uint32_t nb = g->nb[0] * g->nb[1] * g->nb[2];
  g->ncap = s->n;
  g->cap = malloc((size_t)s->n * WC_STRIDE * sizeof *g->cap);
  g->boff = calloc((size_t)nb + 1, sizeof *g->boff);
  SESSILE_CHECK(g->cap && g->boff, SESSILE_ERR_NO_MEMORY, "welded surface: out of host memory for %u capsules",
                s->n);
  /* A capsule farther than 3 h + 2 blend from every node of a brick cannot
   * change a node value there (values are clamped at 2 h; blend 0: exactly)
   * nor be the nearest capsule at a vertex on an edge (at most sqrt(3) h
   * long) from one of its nodes.  Tested by the capsule's box and by its
   * distance from the brick's centre less the brick's half-diagonal. */
  double margin = 3 * g->h + 2 * g->blend;
  /* A branch thinner than a cell can fall between the nodes and break into
   * pieces: radii are raised to WELD_MIN_RADIUS_CELLS cells (inside the
   * 2 h pad of the plan, so the grid still holds every capsule). */
  double rmin = WELD_MIN_RADIUS_CELLS * g->h;
  for (uint32_t i = 0; i < s->n; i++) capsule_constants(s, i, rmin, g->cap + (size_t)i * WC_STRIDE);
  uint64_t total = 0;
  for (int pass = 0; pass < 2; pass++) {
    for (uint32_t i = 0; i < s->n; i++) {
      uint32_t b0[3], b1[3];
      int ok;
      capsule_bricks(g, g->cap + (size_t)i * WC_STRIDE, margin, b0, b1, &ok);
      if (!ok) continue;
      for (uint32_t z = b0[2]; z <= b1[2]; z++)
        for (uint32_t y = b0[1]; y <= b1[1]; y++)
          for (uint32_t x = b0[0]; x <= b1[0]; x++) {
            uint32_t b = x + g->nb[0] * (y + g->nb[1] * z);
            if (!brick_near(g, g->cap + (size_t)i * WC_STRIDE, x, y, z, margin)) continue;
            if (pass == 0) g->boff[b + 1]++, total++;
            else g->blist[g->boff[b]++] = i; /* ascending i: the fold order */
          }
    }
    if (pass == 0) {
      SESSILE_CHECK(total < UINT32_MAX, SESSILE_ERR_NO_MEMORY,
                    "welded surface: %llu capsule-brick entries exceed 32-bit indices; use a larger cell",
                    (unsigned long long)total);
      for (uint32_t b = 0; b < nb; b++) g->boff[b + 1] += g->boff[b];
      g->blist = malloc((total ? total : 1) * sizeof *g->blist);
      SESSILE_CHECK(g->blist, SESSILE_ERR_NO_MEMORY, "welded surface: out of host memory for %llu list entries",
                    (unsigned long long)total);
    }
  }
  /* the fill advanced each offset to its brick's end: shift back */
  for (uint32_t b = nb; b > 0; b--) g->boff[b] = g->boff[b - 1];
  g->boff[0] = 0;
  return SESSILE_OK;
}

double weld_node_value(const weld_grid *g, uint32_t x, uint32_t y, uint32_t z, uint32_t *nearest) {
  double px = g->lo[0] + g->h * (double)x, py = g->lo[1] + g->h * (double)y, pz = g->lo[2] + g->h * (double)z;
  uint32_t b = weld_brick_of(g, x, y, z), best = UINT32_MAX;
  double f = (double)1e30f, bd = 0; /* GLSL: REAL(1e30), a float literal */
  for (uint32_t e = g->boff[b]; e < g->boff[b + 1]; e++) {
    uint32_t c = g->blist[e];
    double d = weld_capsule_sdf(g->cap + (size_t)c * WC_STRIDE, px, py, pz);
    f = g->blend > 0 ? weld_smin(f, d, g->blend) : weld_min(f, d);
    if (best == UINT32_MAX || d < bd - 0x1p-30 * g->h) best = c, bd = d; /* ties to 2^-30 h: weld_sdf.comp */
  }
  *nearest = best;
  int interior = x > 0 && y > 0 && z > 0 && x + 1 < g->n[0] && y + 1 < g->n[1] && z + 1 < g->n[2];
  return interior ? weld_min(f, g->clampv) : g->clampv;
}

sessile_status weld_output(const sessile_skeleton *s, double h, uint32_t nv, uint32_t nf, double *pos, uint32_t *tri,
                           uint32_t *nearest, sessile_surface *out, double **vertex_value) {
  SESSILE_CALL(weld_drop_pockets(pos, &nv, tri, &nf, nearest, h * h * h));
  double *val = NULL;
  if (vertex_value && nv) {
    val = malloc((size_t)nv * sizeof *val);
    SESSILE_CHECK(val, SESSILE_ERR_NO_MEMORY, "welded surface: out of host memory for %u vertex values", nv);
    for (uint32_t v = 0; v < nv; v++) val[v] = nearest[v] < s->n ? s->value[nearest[v]] : 0;
  }
  for (uint32_t v = 0; v < nv; v++) {
    double q[3] = {pos[3 * (size_t)v], pos[3 * (size_t)v + 1], pos[3 * (size_t)v + 2]};
    weld_to_world(q, pos + 3 * (size_t)v);
  }
  sessile_surface_free(out);
  out->pos = pos, out->tri = tri;
  out->nv = out->cap_v = nv, out->nf = out->cap_f = nf;
  if (vertex_value) *vertex_value = val;
  return SESSILE_OK;
}
